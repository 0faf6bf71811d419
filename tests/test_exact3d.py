"""Tests for skxfem/fem/exact3d.py: Love's solution on the block is an elasticity solution
that varies in all three directions, and exact_block imposes exactly its values.

What is checked, at random points, for several E, ν and P:

1. Compatibility: ``gradient`` is ∇``displacement`` and ``strain`` its
   symmetric part (central finite differences).
2. Equilibrium without body force: div σ = 0 (finite differences).
3. The documented dome: σ_zz = -P(1 - ξ² - η² - ½ξη) on the horizontal plane
   through the centre, σ·n and p = -n·σ·n as documented.
4. Genuinely 3D: u changes along x, y and z, and the pressure along Γ has a
   gradient with a part along every axis.
5. The scene exact_block: its loads are σ·n on the five loaded faces, its
   bottom displacement is u, Γ is slanted against all three axes, keeps off
   every node of the meshes n = 2 ... 64 as documented and stays within
   0.3 < z < 0.81.
"""
import numpy as np
import pytest
from skfem import Basis, ElementVector

from skxfem.fem.exact3d import CENTRE, GAMMA_NORMAL, GAMMA_POINT, ExactBlock
from skxfem.fem.material import Material
from skxfem.scene import dirichlet, resolve_mesh, traction
from skxfem.scene.benchmarks import P_MAX, exact_block

CASES = [(Material(1.0, 0.3), 1.0), (Material(2.5, 0.2), 1.7), (Material(3.0, 0.45), 0.4),
         (Material(1e3, -0.5), 2.0)]
IDS = ["nu03", "nu02", "nu045", "auxetic"]


def points(seed, k=25):
    return np.random.default_rng(seed).uniform(0.0, 1.0, (3, k))


def fd(f, x, h):
    """∂f/∂x_j by central differences, stacked on axis -2: shape (out..., 3, k)."""
    cols = []
    for j in range(3):
        e = np.zeros((3, 1))
        e[j] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.stack(cols, axis=-2)


def unit(n):
    n = np.asarray(n, float)
    return n / np.linalg.norm(n)


@pytest.mark.parametrize("material, P", CASES, ids=IDS)
def test_gradient_and_strain_are_those_of_the_displacement(material, P):
    sol = ExactBlock(material, P)
    x = points(0)
    G = fd(sol.displacement, x, 1e-5)
    scale = np.abs(G).max()
    assert scale > 0.1 * P / material.E, "the field is not trivially zero"
    assert np.abs(G - sol.gradient(x)).max() < 1e-8 * scale, "gradient() is not ∇u"
    eps = 0.5 * (G + G.transpose(1, 0, 2))
    assert np.abs(eps - sol.strain(x)).max() < 1e-8 * scale, "strain() is not sym ∇u"


@pytest.mark.parametrize("material, P", CASES, ids=IDS)
def test_equilibrium_without_body_force(material, P):
    sol = ExactBlock(material, P)
    x = points(1)
    div = np.einsum("ijjk->ik", fd(sol.stress, x, 1e-3))
    assert np.abs(div).max() < 1e-9 * P, f"div σ = {np.abs(div).max():.2e}, should be 0"
    assert np.abs(sol.stress(x)).max() > 0.3 * P


@pytest.mark.parametrize("material, P", CASES, ids=IDS)
def test_the_documented_dome_and_tractions(material, P):
    sol = ExactBlock(material, P)
    x = points(2)
    x[2] = CENTRE[2]
    xi, eta = x[0] - 0.5, x[1] - 0.5
    dome = -P * (1 - xi ** 2 - eta ** 2 - 0.5 * xi * eta)
    assert np.abs(sol.stress(x)[2, 2] - dome).max() < 1e-13 * P
    n = unit([0.3, -0.4, 0.8])[:, None] + 0 * x
    assert np.allclose(sol.traction(x, n), np.einsum("ijk,jk->ik", sol.stress(x), n))
    m = unit(GAMMA_NORMAL)
    assert np.allclose(sol.pressure(x), -np.einsum("i,ijk,j->k", m, sol.stress(x), m))


def test_the_answer_varies_in_all_three_directions():
    sol = ExactBlock(Material(1.0, 0.3))
    x = points(3)
    G = sol.gradient(x)                                            # (i, j, point)
    along = np.sqrt(np.mean(G ** 2, axis=(0, 2)))                  # |∂u/∂x_j|, rms
    assert np.all(along > 0.1 * along.max()), f"u hardly changes along an axis: {along}"
    # the pressure along Γ: its tangential gradient has a part along every axis
    m = unit(GAMMA_NORMAL)
    on = x - np.outer(m, m @ (x - np.array(GAMMA_POINT)[:, None]))   # projected on Γ
    grad = fd(sol.pressure, on, 1e-5)
    tangential = grad - np.outer(m, m @ grad)
    assert np.all(np.abs(tangential).max(axis=1) > 0.05), \
        f"p on Γ is constant along an axis: {np.abs(tangential).max(axis=1)}"


# the scene -------------------------------------------------------------------
FACES = {"xmin": (0, 0.0, -1.0), "xmax": (0, 1.0, 1.0), "ymin": (1, 0.0, -1.0),
         "ymax": (1, 1.0, 1.0), "zmax": (2, 1.0, 1.0)}


@pytest.mark.parametrize("cell", ["hex", "prism", "tet"])
def test_exact_block_loads_are_the_exact_tractions(cell):
    scene = exact_block(2, cell)
    sol = ExactBlock(scene.material, P_MAX)
    assert {load.boundary for load in scene.loads} == set(FACES)
    rng = np.random.default_rng(4)
    for load in scene.loads:
        axis, value, sign = FACES[load.boundary]
        x = rng.uniform(0, 1, (3, 15))
        x[axis] = value
        n = np.zeros_like(x)
        n[axis] = sign
        got = traction(load, x, n)
        assert np.abs(got - sol.traction(x, n)).max() < 1e-14, load.boundary
        assert np.abs(got).max() > 0.05, f"{load.boundary}: a load worth checking"


@pytest.mark.parametrize("cell", ["hex", "prism", "tet"])
def test_exact_block_bottom_is_the_exact_displacement(cell):
    scene = exact_block(3, cell)
    mesh = resolve_mesh(scene)
    basis = Basis(mesh, ElementVector(mesh.elem()))
    dofs, values = dirichlet(scene, mesh, basis)
    bottom = np.flatnonzero(mesh.p[2] == 0.0)
    assert set(dofs) == set(basis.nodal_dofs[:, bottom].ravel()), "only the bottom, all of it"
    exact = ExactBlock(scene.material, P_MAX).displacement(mesh.p)
    expected = np.zeros(basis.N)
    expected[basis.nodal_dofs] = exact
    assert np.abs(values - expected[dofs]).max() < 1e-15
    assert np.abs(exact[:, bottom]).min(axis=1).max() > 1e-3, "the bottom moves"


def test_gamma_is_slanted_and_keeps_off_the_nodes_and_the_held_bottom():
    m = unit(GAMMA_NORMAL)
    assert np.all(np.abs(m) > 0.15), "slanted against all three axes"
    for n in range(2, 65):
        g = np.arange(n + 1) / n
        psi = (m[0] * (g[:, None, None] - GAMMA_POINT[0]) + m[1] * (g[None, :, None]
               - GAMMA_POINT[1]) + m[2] * (g[None, None, :] - GAMMA_POINT[2]))
        assert np.abs(psi).min() * n >= 0.0028, f"Γ within 0.0028 h of a node for n = {n}"
    corners = np.array([[x, y] for x in (0, 1) for y in (0, 1)]).T
    z = GAMMA_POINT[2] - (m[0] * (corners[0] - GAMMA_POINT[0])
                          + m[1] * (corners[1] - GAMMA_POINT[1])) / m[2]
    assert z.min() > 0.3 and z.max() < 0.81, z


@pytest.mark.parametrize("bad, match", [({"cell": "quad"}, "cell"), ({"n": 0}, "n must"),
                                        ({"n": 2.0}, "n must")])
def test_exact_block_refuses_bad_input(bad, match):
    with pytest.raises(ValueError, match=match):
        exact_block(**{"n": 2, "cell": "hex", **bad})
