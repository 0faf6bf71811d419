r"""The numbering of a crack space's unknowns U = [a, b, c], alike in 2D and 3D.

A crack's space (:class:`skxfem.crack.space.CrackSpace` in 2D,
:class:`skxfem.crack.space3d.CrackSpace3D` in 3D) numbers its unknowns the same way in
any dimension d: first the n_std standard unknowns a, then d Heaviside unknowns b per
Heaviside node, then 4 d branch unknowns c per branch node (function l, then component).
:class:`EnrichedUnknowns` gives both spaces that numbering from their ``mesh``,
``heaviside`` and ``branch`` nodes and their own ``n_std``.

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

__all__ = ["EnrichedUnknowns"]


class EnrichedUnknowns:
    """The numbering of [a, b, c] (module notes), for a space with the attributes
    ``mesh``, ``heaviside`` (nh,) and ``branch`` (nb,) nodes and ``n_std``."""

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

    def enriched_nodes(self) -> np.ndarray:
        """The nodes with enriched unknowns (Heaviside or branch), sorted."""
        return np.union1d(self.heaviside, self.branch)

    def support_cells(self, nodes: np.ndarray) -> np.ndarray:
        """The cells holding one of ``nodes``: the union of their supports."""
        mark = np.zeros(self.mesh.p.shape[1], dtype=bool)
        mark[nodes] = True
        return np.flatnonzero(mark[self.mesh.t].any(axis=0))
