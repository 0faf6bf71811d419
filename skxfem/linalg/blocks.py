r"""The block scaling of enriched nodes, for the iterative solve of a crack.

At a node with enriched unknowns, its standard unknowns a and its enriched ones
(b, and the branch unknowns c of a crack) are nearly dependent: near a front the
branch functions F_l φ_k are close to combinations of φ_k and of each other, and the
diagonal (Jacobi) scaling of :func:`skxfem.linalg.amg.scaled_tie` leaves the node's
block badly conditioned, so that AMG-preconditioned CG stalls.  As the direct crack
solve does (Béchet et al. 2005, :func:`skxfem.crack.space3d.nodal_scaling`), each such
node's block [a, b, c] (its ``dim`` standard unknowns and every enriched unknown of the
node) is scaled by the inverse transpose of the Cholesky factor of its diagonal block,
K_bb = L Lᵀ, S_b = L⁻ᵀ: the scaled block Sᵀ K S is the identity.  The change of unknowns
U = S U_s is symmetric (K_s = Sᵀ K S, F_s = Sᵀ F, B_s = B S) and the near-null space
becomes S⁻¹ Z (S⁻¹ = Lᵀ on a block).  A block holding an imposed unknown is left to the
Jacobi scaling (so that U_s = U there).

>>> import scipy.sparse as sp
>>> K = sp.csr_matrix(np.array([[4.0, 2, 0], [2, 2, 0], [0, 0, 9]]))
>>> S, Sinv = enriched_scaling(K, np.array([0]), 1, 1)
>>> (S.T @ K @ S).toarray().round(12).tolist()
[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 9.0]]
>>> bool(abs((S @ Sinv).toarray() - np.eye(3)).max() < 1e-12)
True
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["node_blocks", "enriched_scaling", "block_scaling", "congruence"]


def node_blocks(enr_dofs: np.ndarray, n_std: int, dim: int) -> list[np.ndarray]:
    """The blocks of the enriched nodes: for each node with enriched unknowns, its ``dim``
    standard unknowns then its enriched ones (``n_std + i`` for the enriched unknown i
    whose standard dof is ``enr_dofs[i]``), as arrays (nb, k) of the nodes with k
    unknowns each.

    >>> [b.tolist() for b in node_blocks(np.array([2, 3, 2, 3]), 4, 2)]
    [[[2, 3, 4, 5, 6, 7]]]
    """
    enr_dofs = np.asarray(enr_dofs, dtype=np.int64)
    if enr_dofs.ndim != 1 or (enr_dofs.size and (enr_dofs.min() < 0
                                                 or enr_dofs.max() >= n_std)):
        raise ValueError(f"enr_dofs must be standard dofs in [0, {n_std}), one per enriched "
                         f"unknown")
    if dim < 1 or n_std % dim:
        raise ValueError(f"dim must divide n_std = {n_std}, got {dim!r}")
    node = enr_dofs // dim
    order = np.argsort(node, kind="stable")
    nodes, first, counts = np.unique(node[order], return_index=True, return_counts=True)
    out = []
    for k in np.unique(counts):                           # nodes with k enriched unknowns
        pick = np.flatnonzero(counts == k)
        enr = n_std + order[first[pick, None] + np.arange(k)]           # (nb, k)
        std = dim * nodes[pick, None] + np.arange(dim)                  # (nb, dim)
        out.append(np.hstack([std, enr]))
    return out


def enriched_scaling(K: sp.spmatrix, enr_dofs: np.ndarray, n_std: int, dim: int,
                     fixed: np.ndarray | None = None) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(S, S⁻¹): the block scaling of the module notes (identity off the enriched
    nodes' blocks and on the blocks holding an unknown of ``fixed``, indices)."""
    blocks = node_blocks(enr_dofs, n_std, dim)
    if fixed is not None and len(fixed):
        blocks = [B[~np.isin(B, fixed).any(axis=1)] for B in blocks]
    return block_scaling(K, blocks, np.ones(K.shape[0]))


def block_scaling(K: sp.spmatrix, blocks, diagonal: np.ndarray
                  ) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(S, S⁻¹): S = L⁻ᵀ on each block of unknowns (rows of the arrays ``blocks``, each
    (nb, k)), L the Cholesky factor of K's diagonal block there (Sᵀ K S = I on it), and
    ``diagonal`` (N,) on the unknowns in no block.

    >>> S, Sinv = block_scaling(sp.diags([4.0, 9.0, 16.0]), [np.array([[0, 1]])],
    ...                         np.full(3, 0.25))
    >>> S.diagonal().round(4).tolist(), bool(np.allclose((S @ Sinv).toarray(), np.eye(3)))
    ([0.5, 0.3333, 0.25], True)
    """
    K = sp.csr_matrix(K)
    N = K.shape[0]
    rows, cols, vals, inv = [], [], [], []
    done = np.zeros(N, dtype=bool)
    for B in blocks:
        if not B.shape[0]:
            continue
        k = B.shape[1]
        r = np.repeat(B, k, axis=1).ravel()
        c = np.tile(B, (1, k)).ravel()
        try:
            L = np.linalg.cholesky(np.asarray(K[r, c]).reshape(-1, k, k))
        except np.linalg.LinAlgError:
            raise ValueError("an enriched node's block of the stiffness is not positive "
                             "definite: an enriched function vanishes on its support, or "
                             "two of a node's functions coincide") from None
        rows.append(r)
        cols.append(c)
        vals.append(np.transpose(np.linalg.inv(L), (0, 2, 1)).ravel())    # L⁻ᵀ
        inv.append(np.transpose(L, (0, 2, 1)).ravel())                    # Lᵀ
        done[B.ravel()] = True
    rest = np.flatnonzero(~done)
    r = np.concatenate([rest, *rows])
    c = np.concatenate([rest, *cols])
    S = sp.csr_matrix((np.concatenate([diagonal[rest], *vals]), (r, c)), shape=(N, N))
    Sinv = sp.csr_matrix((np.concatenate([1 / diagonal[rest], *inv]), (r, c)), shape=(N, N))
    return S, Sinv


def congruence(K: sp.spmatrix, S: sp.spmatrix, blocksize: int = 1) -> sp.csr_matrix:
    """Sᵀ K S in canonical CSR (exact zeros dropped, rows sorted: pyamg's aggregates follow
    the order of a row), by products of ``blocksize`` × ``blocksize`` blocks (the unknowns
    of a node, interleaved): on a 3D crack's K (6.7 M nonzeros, ``benchmarks/crack_solve.py``
    at n = 24) the products of 3 × 3 blocks take 0.29 s against 0.68 s entry by entry (one
    run), the same matrix to the last bit there.

    >>> K = sp.csr_matrix(np.array([[4.0, 2, 0, 0], [2, 2, 0, 0], [0, 0, 9, 1], [0, 0, 1, 1]]))
    >>> S, _ = enriched_scaling(K, np.array([0, 1]), 2, 2)
    >>> congruence(K, S, 2).toarray().round(12)[:2].tolist()
    [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]]
    """
    N = K.shape[0]
    if blocksize < 1 or N % blocksize:
        raise ValueError(f"blocksize must divide the {N} unknowns, got {blocksize!r}")
    if blocksize == 1:
        out = (S.T @ K @ S).tocsr()
    else:
        b = (blocksize, blocksize)
        out = (sp.csr_matrix(S.T).tobsr(blocksize=b) @ sp.csr_matrix(K).tobsr(blocksize=b)
               @ sp.csr_matrix(S).tobsr(blocksize=b)).tocsr()
    out.eliminate_zeros()
    out.sort_indices()
    return out
