r"""What the 2D and 3D crack kinds' X-FEM spaces share: the methods every space is asked.

:class:`skxfem.gamma.CrackXSpace` (2D) and :class:`skxfem.crack.kind3d.CrackXSpace3D`
(3D) wrap a crack's space ``space`` (:class:`~skxfem.crack.space.CrackSpace`,
:class:`~skxfem.crack.space3d.CrackSpace3D`) with the methods that
:func:`skxfem.enrich.stiffness`, :func:`skxfem.problem.assemble` and
:meth:`skxfem.enrich.XSpaces.regions` ask every space (the contract in
:mod:`skxfem.gamma`).  :class:`CrackXSpaceBase` holds those that read only the
numbering of [a, b, c] (:mod:`skxfem.crack.dofs`) and the crack's own stiffness, mass
and supports, given by each kind as class attributes:

* ``_stiffness(space, material)`` and ``_mass(space)``: the crack's stiffness and mass
  on [a, b, c];
* ``_support`` and ``_supported_dofs``: a support of the crack's harness and the
  function that turns a list of them into the constrained unknowns and their values
  (a mouth is never clamped shut).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..fem.material import Material
from ..scene.boundary import imposed, imposed_values

__all__ = ["CrackXSpaceBase", "facets_of"]


class CrackXSpaceBase:
    """The methods of a crack's X-FEM space shared in 2D and 3D (module notes), on its
    ``space``."""

    splits = False
    """A crack ends inside the body: it splits no region."""

    @property
    def mesh(self):
        return self.space.mesh

    @property
    def cut(self):
        """The crack's geometry (the fields of a :class:`skxfem.cut.Cut`)."""
        return self.space.geometry

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
        V, nd = self.space, self.space.nodal_dofs
        heav = nd[:, V.heaviside].T                        # (nh, d)
        branch = np.repeat(nd[:, V.branch].T[:, None, :], 4, axis=1)   # (nb, 4, d)
        return np.concatenate([heav.ravel(), branch.ravel()]).astype(np.int64)

    @property
    def H_node(self) -> np.ndarray:
        """(n_enr,) H(x_j) of each Heaviside unknown's node, 0 for a branch unknown."""
        V = self.space
        return np.concatenate([np.repeat(V.H_node, V.mesh.dim()), np.zeros(V.n_branch)])

    def signed_stiffness(self, material: Material, A=None):
        """(A, K): the standard block of the crack's stiffness K (``A`` if given) and K
        itself, whose enriched blocks :meth:`blocks` reads."""
        K = self._stiffness(self.space, material).tocsr()
        n = self.n_std
        return (K[:n, :n] if A is None else A), K

    def signed_mass(self, A=None):
        """(A, M): the standard block of the crack's mass M (``A`` if given) and M itself
        (:mod:`skxfem.lbb`), whose enriched blocks :meth:`blocks` reads."""
        M = self._mass(self.space)
        n = self.n_std
        return (M[:n, :n] if A is None else A), M

    def coupling(self, other, material: Material) -> sp.csr_matrix | None:
        """The stiffness block between this crack's enrichment (rows) and that of
        ``other``, another interface's space of the scene (columns), for
        :func:`skxfem.enrich.couplings`: None where their enrichments share no cell (a
        crack's branch functions reach r_e from its front; a cut interface's shifted
        Heaviside enrichment lives on its cut cells only).  The 2D kind assembles it
        with another crack or a cut interface (:func:`skxfem.crack.assembly.coupling`,
        :func:`~skxfem.crack.assembly.cut_coupling`); where it is not assembled (a 3D
        crack's zone meeting another interface's enrichment) the scene is refused,
        naming the cure, rather than solved without it."""
        crack = isinstance(other, CrackXSpaceBase)
        mine = self.space.support_cells(self.space.enriched_nodes() if crack else
                                        self.space.branch)   # shifted H: own cut cells
        theirs = (other.space.support_cells(other.space.enriched_nodes()) if crack else
                  other.cut.cells)
        shared = np.intersect1d(mine, theirs)
        if not shared.size:
            return None
        block = self._coupling(other, material)
        if block is not None:
            return block
        x = ", ".join(f"{v:.4g}" for v in self.mesh.p[:, self.mesh.t[:, shared[0]]].mean(axis=1))
        raise ValueError(
            f"a crack's enriched zone (its branch functions, within enrichment_radius of its "
            f"front) and another interface's enrichment share {shared.size} cell(s) (e.g. "
            f"around ({x})): their interaction is not assembled in {self.mesh.dim()}D; "
            f"give the crack a smaller enrichment_radius (or enrichment = 'topological'), "
            f"or move them apart")

    def _coupling(self, other, material: Material) -> sp.csr_matrix | None:
        """The block of :meth:`coupling` where the enrichments share cells; None: the
        kind does not assemble it (the 2D kind does)."""
        return None

    def blocks(self, A, K) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(K_ab, K_bb): the crack stiffness' blocks of its enriched unknowns."""
        n = self.n_std
        return K[:n, n:].tocsr(), K[n:, n:].tocsr()

    def constraints(self, scene, mesh) -> tuple[np.ndarray, np.ndarray]:
        """The scene's displacements as the crack's supports on [a, b, c] (the kind's
        ``_supported_dofs``: a mouth is never clamped shut)."""
        supports = []
        for nodes, components in imposed(scene, mesh):
            for c, (value, what) in components.items():
                def u(x, c=c, value=value, what=what):
                    out = np.zeros_like(x, dtype=float)
                    out[c] = imposed_values(value, x, what)
                    return out

                supports.append(self._support(facets_of(mesh, nodes),
                                              np.asarray(nodes), u, (c,)))
        return self._supported_dofs(self.space, supports)


def facets_of(mesh, nodes: np.ndarray) -> np.ndarray:
    """The boundary facets whose nodes are all among ``nodes`` (a support's facets: where
    the crack's supported dofs decide what a mouth keeps free)."""
    mark = np.zeros(mesh.p.shape[1], dtype=bool)
    mark[nodes] = True
    bf = mesh.boundary_facets()
    return bf[mark[mesh.facets[:, bf]].all(axis=0)]
