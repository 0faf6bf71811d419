r"""A 2D crack as the steps below a scene see a space: the crack kind's X-FEM space.

:class:`CrackXSpace` wraps a :class:`~skxfem.crack.space.CrackSpace` (the unknowns
[a, b, c]: standard, Heaviside, branch) with the methods that
:func:`skxfem.enrich.stiffness`, :func:`skxfem.problem.assemble`'s load and
constraints, and :meth:`skxfem.enrich.XSpaces.regions` ask every space of a scene
(the contract of :mod:`skxfem.gamma`):

* ``signed_stiffness(material, A)`` and ``blocks(A, K)``: the crack's own stiffness
  (:func:`skxfem.crack.assembly.stiffness`, its tip cells on the almost-polar rule),
  given as its standard block and its enriched blocks;
* ``load(facet_loads, body_force, f)``: the scene's surface loads on [a, b, c]
  (:func:`skxfem.crack.assembly.traction_load`);
* ``constraints(scene, mesh)``: the scene's displacements on [a, b, c]
  (:func:`skxfem.crack.assembly.supported_dofs`: a mouth is never clamped shut);
* ``splits = False``: a crack ends inside the body and splits no region.

Its enriched unknowns are ``enr_dofs``-ordered as the crack space's [b, c]; each one's
standard dof is ``enr_dofs`` and its ``H_node`` is that of its Heaviside node (0 for a
branch unknown), so that the nodal fields of the regions hold a + Σ b(σ - H) with the
crack's unknowns left out (the shifted enrichment vanishes at the nodes).

>>> import numpy as np
>>> from skfem import MeshTri1
>>> from skxfem.crack.geometry import crack_geometry
>>> from skxfem.crack.space import crack_space
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
>>> V = CrackXSpace(crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)))
>>> V.N == V.space.N, V.enr_dofs.size == V.n_enr, V.splits
(True, True, False)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..fem.material import Material
from .assembly import FACET_POINTS, Load, Support, stiffness, supported_dofs, traction_load
from .assembly import _facets as check_facets
from .space import CrackSpace

__all__ = ["CrackXSpace"]


@dataclass(frozen=True)
class CrackXSpace:
    """The X-FEM space of a crack kind of Γ (module notes): ``space`` its
    :class:`~skxfem.crack.space.CrackSpace`."""

    space: CrackSpace
    splits = False

    @property
    def mesh(self):
        return self.space.mesh

    @property
    def cut(self):
        """The crack's geometry (the fields of a :class:`skxfem.cut.Cut`)."""
        return self.space.geometry

    @property
    def basis(self):
        return self.space.basis

    @property
    def n_std(self) -> int:
        return self.space.n_std

    @property
    def n_enr(self) -> int:
        return self.space.N - self.space.n_std

    @property
    def N(self) -> int:
        return self.space.N

    @property
    def enr_dofs(self) -> np.ndarray:
        """(n_enr,) the standard dof of each enriched unknown [b, c] (its node and
        component)."""
        V, nd = self.space, self.space.basis.nodal_dofs
        heav = nd[:, V.heaviside].T                        # (nh, 2)
        branch = np.repeat(nd[:, V.branch].T[:, None, :], 4, axis=1)   # (nb, 4, 2)
        return np.concatenate([heav.ravel(), branch.ravel()]).astype(np.int64)

    @property
    def H_node(self) -> np.ndarray:
        """(n_enr,) H(x_j) of each Heaviside unknown's node, 0 for a branch unknown."""
        V = self.space
        return np.concatenate([np.repeat(V.H_node, 2), np.zeros(V.n_branch)])

    def signed_stiffness(self, material: Material, A=None):
        """(A, K): the standard block of the crack's stiffness K (``A`` if given) and K
        itself, whose enriched blocks :meth:`blocks` reads."""
        K = stiffness(self.space, material).tocsr()
        n = self.n_std
        return (K[:n, :n] if A is None else A), K

    def blocks(self, A, K) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(K_ab, K_bb): the crack stiffness' blocks of its enriched unknowns."""
        n = self.n_std
        return K[:n, n:].tocsr(), K[n:, n:].tocsr()

    def load(self, facet_loads, body_force=None, f: np.ndarray | None = None):
        """(f, f_b): the surface loads on the standard dofs (``f`` if given) and on the
        enriched unknowns [b, c] (:func:`skxfem.crack.assembly.traction_load`, each
        facet's outward normal given to the traction ``t(x, n)``)."""
        if body_force is not None:
            raise ValueError("a body force on a scene with a crack is not supported yet")
        mesh = self.mesh
        loads = []
        for facets, traction in facet_loads:
            fac = check_facets(mesh, facets, "a load's facets")
            n = _outward_normals(mesh, fac)
            n_pts = np.repeat(n, 2 * FACET_POINTS, axis=1)  # facet_pieces' order

            def t(x, traction=traction, n_pts=n_pts):
                return np.asarray(traction(x, n_pts), float)

            loads.append(Load(fac, t))
        F = traction_load(self.space, loads)
        return (F[:self.n_std] if f is None else f), F[self.n_std:]

    def constraints(self, scene, mesh) -> tuple[np.ndarray, np.ndarray]:
        """The scene's displacements as the crack's supports on [a, b, c]
        (:func:`skxfem.crack.assembly.supported_dofs`)."""
        from ..scene.boundary import _values, imposed
        supports = []
        for nodes, components in imposed(scene, mesh):
            for c, (value, what) in components.items():
                def u(x, c=c, value=value, what=what):
                    out = np.zeros_like(x, dtype=float)
                    out[c] = _values(value, x, what)
                    return out

                supports.append(Support(_facets_of(mesh, nodes), np.asarray(nodes), u, (c,)))
        return supported_dofs(self.space, supports)


def _outward_normals(mesh, facets: np.ndarray) -> np.ndarray:
    """(2, nf) the outward unit normals of boundary facets of a 2D mesh."""
    a, b = mesh.p[:, mesh.facets[0, facets]], mesh.p[:, mesh.facets[1, facets]]
    d = b - a
    n = np.array([d[1], -d[0]]) / np.linalg.norm(d, axis=0)
    centre = mesh.p[:, mesh.t[:, mesh.f2t[0, facets]]].mean(axis=1)
    flip = ((centre - a) * n).sum(axis=0) > 0
    return np.where(flip, -n, n)


def _facets_of(mesh, nodes: np.ndarray) -> np.ndarray:
    """The boundary facets whose nodes are all among ``nodes`` (a support's facets: where
    :func:`skxfem.crack.assembly.supported_dofs` decides what a mouth keeps free)."""
    mark = np.zeros(mesh.p.shape[1], dtype=bool)
    mark[nodes] = True
    bf = mesh.boundary_facets()
    return bf[mark[mesh.facets[:, bf]].all(axis=0)]
