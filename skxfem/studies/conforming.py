r"""Classical FEM on a mesh that follows Γ: the reference curve of the paper's Figure 9.

"With FEM, the mesh follows the interface" (paper §5): Γ is a plane of mesh
faces, and a bonded interface is then no interface at all, the displacement
is one continuous field.  :func:`solve_conforming` solves a scene that way
(its loads and displacements, no enrichment, no multiplier) and refuses a
mesh that Γ cuts; :func:`energy_error` measures W(u_h) as
:func:`skxfem.studies.convergence.energy_error` does for X-FEM, with its own rule of
order 4 on every cell; :func:`study_conforming` is the paper's curve: the
exact plate on hexahedra with an even number of cells in z, so that Γ
(z = 0.5) is a layer of faces.

>>> rows = study_conforming([2, 4])
>>> [r.n for r in rows], bool(rows[1].energy < rows[0].energy)
([2, 4], True)
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np
from skfem import Basis, ElementVector, condense
from skfem import solve as skfem_solve
from skfem.helpers import ddot, sym_grad

from ..fem.exact import ExactPlate
from ..fem.loads import boundary_quadrature, surface_load
from ..fem.material import stiffness_matrix
from ..fem.quadrature import cell_rule
from ..scene.benchmarks import P_MAX, exact_plate
from ..scene.laws import in_words
from ..scene.model import Box, Scene, dirichlet, load_facets, resolve
from .convergence import StudyRow

__all__ = ["ConformingResult", "solve_conforming", "energy_error", "study_conforming"]


@dataclass(frozen=True)
class ConformingResult:
    """The displacement ``u`` (dofs of ``basis``, a vector basis on ``mesh``)."""

    scene: Scene
    mesh: object
    basis: Basis
    u: np.ndarray


def solve_conforming(scene: Scene) -> ConformingResult:
    """Solve ``scene`` by classical FEM on its mesh, which must follow Γ.

    Raises
    ------
    ValueError
        A law other than ``bonded`` (a conforming contact element is not
        part of skxfem), or a mesh with a cell that Γ cuts (nodes on both
        sides of Γ): then the mesh does not follow Γ.
    """
    scene, mesh = resolve(scene)
    laws = [i.law for i in scene.interfaces]
    if any(law != "bonded" for law in laws):
        raise ValueError(f"solve_conforming needs law='bonded' (Γ is then no interface "
                         f"at all), got {in_words(laws)}; for other "
                         f"laws use skxfem.solve")
    psi = np.array([i.levelset(mesh.p) for i in scene.interfaces])   # (n, nverts)
    tol = 1e-12 * float(np.ptp(mesh.p, axis=1).max())
    v = psi[:, mesh.t]           # a cell is cut if one of the Γ has nodes on both sides
    cut = np.flatnonzero(((v < -tol).any(axis=1) & (v > tol).any(axis=1)).any(axis=0))
    if cut.size:
        raise ValueError(f"the mesh does not follow Γ: Γ cuts {cut.size} cells (first "
                         f"{cut[:3].tolist()}); classical FEM needs Γ on mesh faces, "
                         f"e.g. an even number of cells across it")
    scalar = Basis(mesh, mesh.elem(), quadrature=cell_rule(mesh))
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh))
    K = stiffness_matrix(scene.material, scalar)
    f = np.zeros(basis.N)
    for facets, traction in load_facets(scene, mesh):
        f += surface_load(basis, boundary_quadrature(mesh, facets, 4), traction)[0]
    D, g = dirichlet(scene, mesh, basis)
    x = np.zeros(basis.N)
    x[D] = g
    u = skfem_solve(*condense(K, f, x=x, D=D))
    return ConformingResult(scene, mesh, basis, u)


def energy_error(result: ConformingResult, exact_strain, order: int = 4) -> float:
    """Relative energy norm of u_h - u, exact strain ``exact_strain(x)``.

    A uniform compression (plane strain, rollers on x = 0 and y = 0, p = 1 on
    y = 1) is exact to round-off:

    >>> from skxfem.scene import SurfaceLoad, rollers
    >>> from skxfem.levelset import plane
    >>> scene = Scene(Box(2, "quad"), plane((0, 0.5), (0, 1)), displacements=(
    ...     rollers("xmin"), rollers("ymin")), loads=(SurfaceLoad("ymax", pressure=1.0),))
    >>> nu = scene.material.nu                                 # E = 1
    >>> eps = lambda x: np.multiply.outer(np.diag([nu * (1 + nu), nu ** 2 - 1]),
    ...                                   np.ones(x.shape[1:]))
    >>> energy_error(solve_conforming(scene), eps) < 1e-13
    True
    """
    mesh, material = result.mesh, result.scene.material
    dim = mesh.dim()
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, order))
    eps_h = sym_grad(basis.interpolate(result.u))
    eps = exact_strain(basis.mapping.F(basis.X))
    e = eps_h - eps
    num = np.sum(ddot(material.stress(e, dim), e) * basis.dx)
    den = np.sum(ddot(material.stress(eps, dim), eps) * basis.dx)
    return float(np.sqrt(num / den))


def study_conforming(ns, cell: str = "hex") -> list[StudyRow]:
    """The paper's FEM curve: :func:`~skxfem.scenes.exact_plate` on a mesh that
    follows Γ (n cells in y, n in z, n even; one layer along x), its energy error.

    The pressure entries of the rows are NaN (no multiplier), ``space`` is ``"fem"``.
    """
    rows = []
    for n in ns:
        if not (isinstance(n, int) and n >= 2 and n % 2 == 0):
            raise ValueError(f"study_conforming needs even n (Γ at z = 0.5 on mesh faces), "
                             f"got {n!r}")
        base = exact_plate(n, cell, nx=1)
        scene = replace(base, mesh=Box((1, n, n), cell, (1.0, 1.0, 1.0)),
                        name=f"conforming_{base.name}")
        t0 = time.perf_counter()
        result = solve_conforming(scene)
        e = energy_error(result, ExactPlate(scene.material, 3, P_MAX).strain)
        rows.append(StudyRow(n, 1.0 / n, "fem", float("nan"), -1, float("nan"),
                             float("nan"), e, int(result.basis.N), 0, time.perf_counter() - t0))
    return rows
