"""skxfem.fem.material: Hooke's law on scikit-fem's elasticity model."""
import numpy as np
import pytest
from skfem import Basis, ElementTriP1, ElementVector, MeshTri1

from skxfem.fem.material import Material, stiffness_form, stiffness_matrix
from skxfem.fem.meshes import box
from skxfem.fem.quadrature import cell_rule, subcell_rule


def test_lame_constants_plane_strain_and_stress():
    m = Material(E=2.0, nu=0.25)
    lam, mu = m.lame(3)
    assert (lam, mu) == pytest.approx((2 * 0.25 / (1.25 * 0.5), 2 / 2.5))
    assert m.lame(2) == m.lame(3)                      # plane strain: the 3D constants
    lam_s, mu_s = Material(E=2.0, nu=0.25, plane="stress").lame(2)
    assert mu_s == pytest.approx(mu) and lam_s == pytest.approx(2 * mu * lam / (lam + 2 * mu))


def test_stress_of_a_uniaxial_strain():
    """ε = e₁⊗e₁: σ₁₁ = λ + 2μ, σ₂₂ = λ, σ₁₂ = 0."""
    m = Material(E=1.0, nu=0.3)
    lam, mu = m.lame(2)
    eps = np.zeros((2, 2, 1))
    eps[0, 0] = 1.0
    sig = m.stress(eps, 2)[:, :, 0]
    assert sig == pytest.approx(np.array([[lam + 2 * mu, 0], [0, lam]]))


def test_stiffness_form_is_symmetric_and_blind_to_translations():
    basis = Basis(MeshTri1().refined(2), ElementVector(ElementTriP1()))
    K = stiffness_form(Material(E=3.0, nu=0.2), 2).assemble(basis)
    assert abs(K - K.T).max() < 1e-14 and np.allclose(K @ np.tile([1.0, 0.0], basis.N // 2), 0)


@pytest.mark.parametrize("plane", ["strain", "stress"])
def test_scalar_assembly_is_scikit_fems_elasticity(cell, plane):
    """stiffness_matrix on the scalar basis gives scikit-fem's linear_elasticity
    on the vector basis, entry by entry, on every cell type (distorted cells, so
    that no entry vanishes by symmetry) and in both 2D models."""
    mesh = box(3, cell)
    mesh = mesh.__class__(mesh.p + 0.1 * np.sin(7 * mesh.p[::-1]), mesh.t)
    m = Material(E=3.0, nu=0.35, plane=plane)
    rule = cell_rule(mesh, 2)
    K = stiffness_form(m, mesh.dim()).assemble(
        Basis(mesh, ElementVector(mesh.elem()), quadrature=rule))
    K_fast = stiffness_matrix(m, Basis(mesh, mesh.elem(), quadrature=rule))
    assert K_fast.shape == K.shape
    assert abs(K_fast - K).max() < 1e-13 * abs(K).max()


def test_scalar_assembly_with_a_rule_per_element():
    """On sub-simplices (a rule of its own for each element, as the X-FEM's cut
    cells use) the two assemblies agree too."""
    mesh = box(2, "hex")
    rule = subcell_rule(np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                                  [[1, 1, 1], [0, 1, 1], [1, 0, 1], [1, 1, 0]]], float),
                        np.arange(2), 4)
    cells = np.array([3, 5])
    m = Material(E=1.0, nu=0.3)
    K = stiffness_form(m, 3).assemble(Basis(mesh, ElementVector(mesh.elem()), elements=cells,
                                            quadrature=(rule.X, rule.W)))
    K_fast = stiffness_matrix(m, Basis(mesh, mesh.elem(), elements=cells,
                                       quadrature=(rule.X, rule.W)))
    assert abs(K).max() > 0 and abs(K_fast - K).max() < 1e-13 * abs(K).max()


@pytest.mark.parametrize("kwargs, error, match", [
    ({"E": 0.0}, ValueError, "E must be a positive"), ({"nu": 0.5}, ValueError, "nu must"),
    ({"plane": "shell"}, ValueError, "plane must be"),
    ({"E": float("inf")}, ValueError, r"E must be .* in \[1e-100, 1e\+100\]"),
    ({"E": float("nan")}, ValueError, "E must be a positive"),
    ({"E": 1e308}, ValueError, "another unit of stress"),
    ({"E": 1e-320}, ValueError, "another unit of stress"),
    ({"nu": float("nan")}, ValueError, "nu must satisfy"),
    ({"E": True}, TypeError, "E must be a real number"),
    ({"nu": "0.3"}, TypeError, "nu must be a real number"),
])
def test_bad_material(kwargs, error, match):
    with pytest.raises(error, match=match):
        Material(**kwargs)


def test_numpy_numbers_are_numbers():
    """A modulus read from an array is a number like any other."""
    assert Material(E=np.float32(2.0), nu=np.float64(0.25)).lame(3) == \
        pytest.approx(Material(E=2.0, nu=0.25).lame(3))
    assert Material(E=np.int64(2)).E == 2


@pytest.mark.parametrize("E", [1e-100, 1e100])
def test_the_ends_of_the_accepted_moduli_solve(E):
    """E at either end of E_RANGE, the load scaled alike: the pressure of E = 1 times E."""
    from skxfem import solve
    from skxfem.levelset import plane
    from skxfem.scene import Box, Scene, SurfaceLoad, clamped
    s = Scene(Box((2, 3), "quad"), plane((0, 0.5), (0, 1)), Material(E=E),
              (clamped("ymin"),), (SurfaceLoad("ymax", pressure=E),))
    ref = solve(Scene(Box((2, 3), "quad"), plane((0, 0.5), (0, 1)), Material(),
                      (clamped("ymin"),), (SurfaceLoad("ymax", pressure=1.0),)))
    assert np.allclose(solve(s).pressure / E, ref.pressure, rtol=1e-10)


@pytest.mark.parametrize("nu", [0.49999999999, 0.4999999, 0.5 - 1e-12])
def test_a_nearly_incompressible_material_is_refused_saying_why(nu):
    """Issue 18: ν = 0.49999999999 was refused on every cell as "a part of the
    body can move freely"; it is refused when the material is made, as nearly
    incompressible, with the limit NU_MAX and λ/μ."""
    with pytest.raises(ValueError, match=r"nearly incompressible .*λ/μ = .*up to 0\.499999"):
        Material(E=1.0, nu=nu)


def test_the_largest_accepted_poisson_ratio_solves_the_patch_test(cell):
    """At NU_MAX (λ/μ = 5e5) every cell still passes the patch test."""
    from skxfem.fem.material import NU_MAX
    from skxfem.levelset import plane
    from skxfem.scene import Box
    from skxfem.studies.extremes import patch_error, patch_scene

    dim = 2 if cell in ("tri", "quad") else 3
    psi = plane((0.5,) * (dim - 1) + (0.53,), (0.0,) * (dim - 1) + (1.0,))
    error, _ = patch_error(patch_scene(Box(4, cell), psi, material=Material(1.0, NU_MAX)))
    assert error <= 1e-8


def test_numpy_scalars_and_0d_arrays_are_numbers():
    """E and ν computed with numpy (np.float32, a 0-d array) are the same material."""
    for E, nu in ((np.float32(2.0), np.array(0.25)), (np.array(2), np.float64(0.25))):
        m = Material(E=E, nu=nu)
        assert (type(m.E), type(m.nu)) == (float, float) and m == Material(2.0, 0.25)
    with pytest.raises(TypeError, match="material E must be a real number"):
        Material(E=np.array([2.0]))
