"""Tests for skxfem/fem/exact.py: the Airy solution of the plate is an elasticity solution.

What is checked, at random points, for the 2D strip (plane strain and plane
stress) and the 3D plate, with several E, ν and P:

1. Compatibility: ``strain`` is the symmetric gradient of ``displacement``
   (central finite differences).
2. Constitutive consistency: σ = C ε(u) is the documented Airy stress
   σ_tt = -4P s(1-s), σ_ss = -4P t², σ_st = 0 (s across, t up), with
   σ_xx = ν(σ_yy + σ_zz) and u_x = 0 in 3D (plane strain, rollers).
3. Equilibrium: div σ = 0 (finite differences of the quadratic σ).
4. Interface: on every horizontal plane, in particular Γ (t = 0.5), the
   traction σ·n is -p n with p = ``pressure`` = 4P s(1-s): no tangential part.
5. The boundary values the scenes ``exact_strip``/``exact_plate`` impose are
   those of this solution: their pressures equal -σ·n·n on the loaded faces
   (with zero shear there), the unloaded roller faces x = 0, 1 carry no
   shear, and the imposed bottom displacement is ``displacement``.
"""
import numpy as np
import pytest
from skfem import Basis, ElementVector

from skxfem.fem.exact import ExactPlate
from skxfem.fem.material import Material
from skxfem.scene import dirichlet, load_facets, resolve_mesh, traction
from skxfem.scene.benchmarks import P_MAX, exact_plate, exact_strip

CASES = [
    (2, Material(1.0, 0.3, "strain"), 1.0),
    (2, Material(2.5, 0.2, "stress"), 1.7),
    (2, Material(3.0, 0.45, "strain"), 0.4),
    (3, Material(1.0, 0.3), 1.0),
    (3, Material(2.5, 0.2), 1.7),
]
IDS = ["2d-strain", "2d-stress", "2d-strain-nu045", "3d", "3d-other"]


def random_points(dim, rng, k=20):
    return rng.uniform(0.0, 1.0, (dim, k))


def across_up(sol, x):
    """The in-plane coordinates (s across, t up) and their axes."""
    return (x[0], x[1], 0, 1) if sol.dim == 2 else (x[1], x[2], 1, 2)


def stress(sol, x):
    return sol.material.stress(sol.strain(x), sol.dim)


def fd_gradient(f, x, h):
    """∂f_i/∂x_j by central differences, shape (out..., dim, npoints)."""
    cols = []
    for j in range(x.shape[0]):
        e = np.zeros((x.shape[0], 1))
        e[j] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.stack(cols, axis=-2)


@pytest.mark.parametrize("dim, material, P", CASES, ids=IDS)
def test_strain_is_the_symmetric_gradient_of_the_displacement(dim, material, P):
    sol = ExactPlate(material, dim, P)
    x = random_points(dim, np.random.default_rng(0))
    grad = fd_gradient(sol.displacement, x, 1e-5)  # (dim, dim, k)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2))
    err = np.abs(eps - sol.strain(x)).max()
    assert err < 1e-8 * P / material.E, \
        f"ε = sym ∇u fails by {err:.2e}: strain() and displacement() disagree"


@pytest.mark.parametrize("dim, material, P", CASES, ids=IDS)
def test_stress_is_the_airy_stress(dim, material, P):
    sol = ExactPlate(material, dim, P)
    x = random_points(dim, np.random.default_rng(1))
    sig = stress(sol, x)
    s, t, i, j = across_up(sol, x)
    tol = 1e-12 * P
    assert np.abs(sig[j, j] + 4 * P * s * (1 - s)).max() < tol, "σ_tt should be -4P s(1-s)"
    assert np.abs(sig[i, i] + 4 * P * t ** 2).max() < tol, "σ_ss should be -4P t²"
    assert np.abs(sig[i, j]).max() < tol, "σ_st should vanish"
    if dim == 3:
        nu = material.nu
        assert np.abs(sig[0, 0] - nu * (sig[1, 1] + sig[2, 2])).max() < tol, \
            "plane strain along x: σ_xx = ν(σ_yy + σ_zz)"
        assert np.abs(sig[0, 1]).max() < tol and np.abs(sig[0, 2]).max() < tol
        assert np.all(sol.displacement(x)[0] == 0), "rollers on x = 0, 1: u_x = 0"
        y = x.copy()
        y[0] = 0.5  # nothing depends on x
        assert np.abs(sol.displacement(x) - sol.displacement(y)).max() == 0


@pytest.mark.parametrize("dim, material, P", CASES, ids=IDS)
def test_equilibrium(dim, material, P):
    sol = ExactPlate(material, dim, P)
    x = random_points(dim, np.random.default_rng(2))
    grad = fd_gradient(lambda y: stress(sol, y), x, 1e-3)  # (dim, dim, dim, k)
    div = np.einsum("ijjk->ik", grad)
    assert np.abs(div).max() < 1e-9 * P, f"div σ = {np.abs(div).max():.2e}, should be 0"
    # the stress is not trivially zero: the check above has something to check
    assert np.abs(stress(sol, x)).max() > 0.1 * P


@pytest.mark.parametrize("dim, material, P", CASES, ids=IDS)
def test_traction_on_every_horizontal_plane_is_the_paper_pressure(dim, material, P):
    sol = ExactPlate(material, dim, P)
    rng = np.random.default_rng(3)
    x = random_points(dim, rng)
    s, _, _, j = across_up(sol, x)
    t = x[j].copy()
    side = sol.side_pressure(x)
    assert np.abs(side - 4 * P * t ** 2).max() < 1e-14 * P, "side pressure 4P t²"
    for height in (0.5, 0.0, 0.8, 1.0):  # Γ first, then any horizontal plane
        x[j] = height
        n = np.zeros(dim)
        n[j] = 1.0
        r = np.einsum("ijk,j->ik", stress(sol, x), n)
        p = sol.pressure(x)
        assert np.abs(p - 4 * P * s * (1 - s)).max() < 1e-14 * P, "p = 4P s(1-s)"
        assert np.abs(r + p * n[:, None]).max() < 1e-12 * P, (
            f"on the plane at height {height} the traction σ·n should be -p n, "
            f"a pure pressure p = 4P s(1-s)")


# the boundary values of the scenes ------------------------------------------

SCENES = {
    "strip-quad": lambda: exact_strip(3, "quad"),
    "strip-tri": lambda: exact_strip(2, "tri"),
    "plate-hex": lambda: exact_plate(2, "hex"),
    "plate-prism": lambda: exact_plate(2, "prism", nx=1),
}
FACES = {"xmin": (0, 0.0, -1.0), "xmax": (0, 1.0, 1.0), "ymin": (1, 0.0, -1.0),
         "ymax": (1, 1.0, 1.0), "zmin": (2, 0.0, -1.0), "zmax": (2, 1.0, 1.0)}


def points_on(face, dim, rng):
    axis, value, sign = FACES[face]
    x = random_points(dim, rng)
    x[axis] = value
    n = np.zeros((dim, x.shape[1]))
    n[axis] = sign
    return x, n


@pytest.mark.parametrize("name", SCENES)
def test_scene_loads_are_the_exact_tractions(name):
    scene = SCENES[name]()
    dim = scene.dim
    sol = ExactPlate(scene.material, dim, P_MAX)
    rng = np.random.default_rng(4)
    loaded = set()
    for load in scene.loads:
        loaded.add(load.boundary)
        x, n = points_on(load.boundary, dim, rng)
        exact = np.einsum("ijk,jk->ik", stress(sol, x), n)
        got = traction(load, x, n)
        assert np.abs(got - exact).max() < 1e-12, (
            f"{name}: the load on {load.boundary} is not σ_exact·n of the exact solution")
    up = "ymax" if dim == 2 else "zmax"
    sides = {"xmin", "xmax"} if dim == 2 else {"ymin", "ymax"}
    assert loaded == {up} | sides, f"{name}: loaded faces {loaded}"
    if dim == 3:  # the roller faces: no shear, the exact u_x = 0 there
        for face in ("xmin", "xmax"):
            x, n = points_on(face, dim, rng)
            r = np.einsum("ijk,jk->ik", stress(sol, x), n)
            assert np.abs(r[1:]).max() < 1e-12, f"rollers on {face} need σ_xy = σ_xz = 0"


@pytest.mark.parametrize("name", SCENES)
def test_scene_bottom_displacement_is_the_exact_one(name):
    scene = SCENES[name]()
    mesh = resolve_mesh(scene)
    sol = ExactPlate(scene.material, scene.dim, P_MAX)
    basis = Basis(mesh, ElementVector(mesh.elem()))
    dofs, values = dirichlet(scene, mesh, basis)
    exact = np.zeros(basis.N)
    exact[basis.nodal_dofs] = sol.displacement(mesh.p)
    bottom = np.flatnonzero(mesh.p[-1] == 0.0)
    assert set(basis.nodal_dofs[:, bottom].ravel()) <= set(dofs), \
        "every component of every bottom node must be imposed"
    assert np.abs(values - exact[dofs]).max() < 1e-15, \
        "the imposed displacements must be the exact ones (component by component)"
    assert np.abs(exact[basis.nodal_dofs[:, bottom]]).max() > 1e-3, \
        "the exact bottom displacement is not zero: the check above is not empty"
    assert len(load_facets(scene, mesh)) == len(scene.loads)
