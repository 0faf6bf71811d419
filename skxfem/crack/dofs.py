r"""The numbering of a crack space's unknowns U = [a, b, c], alike in 2D and 3D.

A crack's space (:class:`skxfem.crack.space.CrackSpace` in 2D,
:class:`skxfem.crack.space3d.CrackSpace3D` in 3D) numbers its unknowns the same way in
any dimension d: first the n_std standard unknowns a, then d Heaviside unknowns b per
Heaviside node, then 4 d branch unknowns c per branch node (function l, then component).
:class:`EnrichedUnknowns` gives both spaces that numbering from their ``mesh``,
``heaviside`` and ``branch`` nodes and their own ``n_std``, and :func:`virtual_map` the
map T from [a, b, c] to the coefficients of their virtual functions φᵢ g.

>>> from dataclasses import dataclass
>>> from skfem import MeshTri1
>>> @dataclass
... class Space(EnrichedUnknowns):
...     mesh: object
...     heaviside: np.ndarray
...     branch: np.ndarray
...     n_std: int = 8
>>> V = Space(MeshTri1(), np.array([0, 1]), np.array([2]))
>>> V.N, V.heaviside_dofs().tolist(), V.branch_dofs().shape
(20, [[8, 9], [10, 11]], (1, 4, 2))
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["EnrichedUnknowns", "virtual_map"]


class EnrichedUnknowns:
    """The numbering of [a, b, c] (module notes), for a space with the attributes
    ``mesh``, ``heaviside`` (nh,) and ``branch`` (nb,) nodes and ``n_std`` (and
    ``nodal_dofs``, the standard unknowns (d, nverts), for :meth:`branch_blocks`)."""

    @property
    def n_heav(self) -> int:
        """The number of Heaviside unknowns b: d per Heaviside node."""
        return self.mesh.dim() * self.heaviside.size

    @property
    def n_branch(self) -> int:
        """The number of branch unknowns c: 4 d per branch node."""
        return 4 * self.mesh.dim() * self.branch.size

    @property
    def N(self) -> int:
        """The number of unknowns [a, b, c]."""
        return self.n_std + self.n_heav + self.n_branch

    def heaviside_dofs(self) -> np.ndarray:
        """(nh, d) the unknowns b of each Heaviside node."""
        return self.n_std + np.arange(self.n_heav).reshape(-1, self.mesh.dim())

    def branch_dofs(self) -> np.ndarray:
        """(nb, 4, d) the unknowns c of each branch node, function l, component."""
        return (self.n_std + self.n_heav
                + np.arange(self.n_branch).reshape(-1, 4, self.mesh.dim()))

    def branch_blocks(self) -> np.ndarray:
        """(nb, 5 d) the unknowns [a_k, c_k] of each branch node (the space's
        ``nodal_dofs`` (d, nverts), then its :meth:`branch_dofs`)."""
        a = self.nodal_dofs[:, self.branch].T              # (nb, d)
        return np.hstack([a, self.branch_dofs().reshape(-1, 4 * self.mesh.dim())])

    def enriched_nodes(self) -> np.ndarray:
        """The nodes with enriched unknowns (Heaviside or branch), sorted."""
        return np.union1d(self.heaviside, self.branch)

    def support_cells(self, nodes: np.ndarray) -> np.ndarray:
        """The cells holding one of ``nodes``: the union of their supports."""
        mark = np.zeros(self.mesh.p.shape[1], dtype=bool)
        mark[nodes] = True
        return np.flatnonzero(mark[self.mesh.t].any(axis=0))


def virtual_map(nodal_dofs: np.ndarray, heav: np.ndarray, H_node: np.ndarray,
                branch_nodes: np.ndarray, F_node: np.ndarray) -> sp.csr_matrix:
    """T: (6 n_std, N), the coefficients ũ_{g, dof} of the virtual functions φᵢ g of the
    six kinds g = 1, H, F₁ … F₄ from the unknowns [a, b, c] (the shifted enrichment:
    ũ_1 = a - Σ H(x_j) b - Σ F_l(x_k) c_l, ũ_H = b, ũ_{F_l} = c_l).

    ``nodal_dofs`` (d, nverts) the standard unknowns of each node and component,
    ``heav`` (nh,) the Heaviside nodes and ``H_node`` their H(x_j), ``branch_nodes``
    (nb,) and ``F_node`` (4, nb) their F_l(x_k), numbered as :class:`EnrichedUnknowns`.

    >>> T = virtual_map(np.array([[0, 2], [1, 3]]), np.array([1]), np.array([1.0]),
    ...                 np.array([], int), np.zeros((4, 0)))
    >>> T.shape, T.toarray()[:4, 4:].tolist()      # a at node 1 less b
    ((24, 6), [[0.0, 0.0], [0.0, 0.0], [-1.0, 0.0], [0.0, -1.0]])
    """
    d, n = nodal_dofs.shape[0], nodal_dofs.size
    hd, bd = nodal_dofs[:, heav].T.ravel(), nodal_dofs[:, branch_nodes].T   # (d nh,), (nb, d)
    nh, nb = hd.size, bd.shape[0]
    rows = [np.arange(n), n + hd, hd]
    cols = [np.arange(n), n + np.arange(nh), n + np.arange(nh)]
    vals = [np.ones(n), np.ones(nh), -np.repeat(H_node, d)]
    c0 = n + nh
    for l in range(4):                                    # the four branch functions
        dofs = bd.ravel()
        c = c0 + (4 * d * np.arange(nb)[:, None] + d * l + np.arange(d)).ravel()
        rows += [(2 + l) * n + dofs, dofs]
        cols += [c, c]
        vals += [np.ones(dofs.size), -np.repeat(F_node[l], d)]
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(6 * n, c0 + 4 * d * nb))
