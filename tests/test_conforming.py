"""Tests for skxfem/studies/conforming.py: classical FEM on a mesh that follows Γ.

1. A patch test on every cell type: a uniform compression is exact to round-off.
2. It refuses what it cannot do: a mesh that Γ cuts, a law other than bonded,
   an odd number of cells across Γ in the study.
3. The paper's claim of Figure 9: the energy error of conforming FEM on
   hexahedra falls like h, at the same rate as X-FEM on hexahedra.
"""
from dataclasses import replace

import numpy as np
import pytest

from skxfem.levelset import plane
from skxfem.scene import Box, Scene, SurfaceLoad, rollers
from skxfem.scene.benchmarks import exact_scene
from skxfem.studies.conforming import energy_error, solve_conforming, study_conforming
from skxfem.studies.convergence import observed_rates, study


def compression(cell, n=2):
    """Rollers on the three (two) min faces, pressure 1 on the top: uniform stress."""
    dim = 2 if cell in ("tri", "quad") else 3
    axes = "xyz"[:dim]
    gamma = plane((0.0,) * (dim - 1) + (0.5,), (0.0,) * (dim - 1) + (1.0,))
    return Scene(Box(n, cell), gamma, displacements=tuple(rollers(f"{a}min") for a in axes),
                 loads=(SurfaceLoad(f"{axes[-1]}max", pressure=1.0),))


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
def test_uniform_compression_is_exact(cell):
    scene = compression(cell)
    dim, nu = scene.dim, scene.material.nu
    lam, mu = scene.material.lame(dim)
    # σ = -e_top ⊗ e_top; plane strain in 2D (ε_zz = 0), free lateral faces in 3D
    if dim == 2:
        diag = [nu * (1 + nu), nu ** 2 - 1]
    else:
        diag = [nu, nu, -1.0]                    # E = 1
    eps = lambda x: np.multiply.outer(np.diag(diag), np.ones(x.shape[1:]))  # noqa: E731
    result = solve_conforming(scene)
    assert energy_error(result, eps) < 1e-12, f"{cell}: not exact"
    top = np.isclose(result.mesh.p[-1], 1.0)
    u = result.u[result.basis.nodal_dofs]
    assert np.allclose(u[-1, top], diag[-1]), "the top moves by ε_top"


def test_a_mesh_that_gamma_cuts_is_refused():
    scene = compression("quad", 3)       # 3 cells: Γ at 0.5 cuts the middle row
    with pytest.raises(ValueError, match="does not follow Γ"):
        solve_conforming(scene)


def test_only_the_bonded_law():
    with pytest.raises(ValueError, match="law='bonded'"):
        solve_conforming(replace(compression("quad"), law="bilateral"))


@pytest.mark.parametrize("n", [3, 0, 2.0])
def test_study_needs_even_n(n):
    with pytest.raises(ValueError, match="even n"):
        study_conforming([n])


def test_fem_and_xfem_on_hexahedra_converge_at_the_same_rate():
    ns = (4, 8, 16)
    fem = study_conforming(ns)
    xfem = study(lambda n, s: exact_scene(n, "hex", s), ns, ["vital"], with_inf_sup=False)
    h = [1 / n for n in ns]
    rate_fem = observed_rates(h, [r.energy for r in fem])
    rate_xfem = observed_rates(h, [r.energy for r in xfem])
    assert np.all(rate_fem > 0.9), f"FEM energy rate {rate_fem}, expected 1"
    assert abs(rate_fem[-1] - rate_xfem[-1]) < 0.1, (rate_fem, rate_xfem)
    assert all(r.space == "fem" and np.isnan(r.pressure_l2) for r in fem)
    assert [r.n_dofs for r in fem] == [3 * 2 * (n + 1) ** 2 for n in ns]
