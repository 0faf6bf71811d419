r"""The inf-sup (LBB) condition, measured: the numerical test of Chapelle & Bathe (1993).

A multiplier space is stable when the discrete inf-sup constant

.. math:: \beta_h = \inf_{\mu} \sup_{v} \frac{\int_\Gamma \lambda_h(\mu) [[v]]}
          {\|\mu\|_{\Lambda} \, \|v\|_{A}}

stays bounded away from zero as h → 0 (paper §5, Bathe 2001).  With A the
matrix of the displacement norm, B_r = Pᵀ B the coupling reduced to the space
and M the matrix of the multiplier norm, β_h² is the smallest non-zero
eigenvalue of the generalised problem

.. math:: B_r A^{-1} B_r^T \, x = \beta^2 M x .

The right multiplier norm is H^{-1/2}(Γ).  On a mesh of size h its discrete
stand-in is √h ‖λ‖_{L²(Γ)} — M = h × (interface mass) — which is what
:func:`inf_sup` uses by default.  With the plain L² mass (``scaling="l2"``)
every space, stable or not, gives β_h → 0 like √h (for the oscillating
multipliers that set the infimum, ‖λ‖_{-1/2} ≈ √h ‖λ‖_0), so that variant
cannot separate stable from unstable spaces; it is reported for comparison.

Zero eigenvalues are spurious multiplier modes (multipliers that B_r does not
see at all); their number is the rank deficiency of B_r, reported separately.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .contact.interface import operators, sticking_rows
from .cut import point_lengths
from .enrich import mass
from .problem import assemble
from .scene.laws import CONTACT_LAWS
from .scene.model import resolve

__all__ = ["InfSup", "inf_sup_constant", "inf_sup"]


@dataclass(frozen=True)
class InfSup:
    """Result of the inf-sup test.

    ``beta`` the smallest non-zero singular value (β_h); ``eigenvalues`` all
    β² sorted; ``n_zero`` the number of (numerically) zero ones; ``rank`` and
    ``size`` of B_r; ``h`` the mesh size used in M.
    """

    beta: float
    eigenvalues: np.ndarray
    n_zero: int
    rank: int
    size: int
    h: float


def inf_sup_constant(A, B, M, tol: float = 1e-6, rank_tol: float = 1e-10,
                     h: float = 1.0, block: int = 128) -> InfSup:
    """β_h from matrices: A (N, N) SPD, B (m, N), M (m, m) SPD.

    An eigenvalue counts as zero when its β is below ``tol`` times the
    largest β: round-off leaves the zero modes near √ε ≈ 1e-8 of it, since
    the eigenvalues are β².  The rank of B counts its singular values above
    ``rank_tol`` times the largest (round-off: ε).  The two counts are
    independent measurements of one thing, the multipliers B cannot see.

    Only B's non-zero columns enter: the jump reaches the enriched unknowns
    of the cut cells alone, so B_c = B[:, cols] is (m, c) with c ≤ dim·n_enr,
    an interface-sized block like S itself, never the N columns of B.  The
    rank is that of B_c, from its singular values (dense SVD of B_c; no
    sparse rank-revealing QR in scipy), and S = B_c (A⁻¹ B_cᵀ)[cols] is
    formed from sparse LU solves in blocks of ``block`` right-hand sides,
    so no dense (N, m) array is held.

    >>> import numpy as np, scipy.sparse as sp
    >>> r = inf_sup_constant(sp.identity(3), sp.csr_matrix([[1., 0, 0], [0, 2., 0]]), np.eye(2))
    >>> round(r.beta, 12), r.n_zero
    (1.0, 0)
    """
    A = sp.csc_matrix(A)
    B = sp.csr_matrix(B)
    M = M.toarray() if sp.issparse(M) else np.asarray(M, float)
    cols = np.unique(B.indices)                        # the unknowns B reaches
    Bc = B[:, cols].toarray()                          # (m, c): the interface block
    lu = spla.splu(A)
    S = np.zeros((B.shape[0],) * 2)
    for k in range(0, B.shape[0], block):
        rhs = np.zeros((A.shape[0], min(block, B.shape[0] - k)))
        rhs[cols] = Bc[k:k + block].T
        S[:, k:k + block] = Bc @ lu.solve(rhs)[cols]
    S = 0.5 * (S + S.T)
    ev = np.sort(np.abs(sla.eigh(S, M, eigvals_only=True)))
    zero = ev <= tol ** 2 * ev.max()
    nz = ev[~zero]
    sv = sla.svdvals(Bc) if Bc.size else np.zeros(0)
    rank = np.count_nonzero(sv > rank_tol * sv.max()) if sv.size else 0
    return InfSup(float(np.sqrt(nz.min())) if nz.size else 0.0, ev, int(zero.sum()),
                  int(rank), B.shape[0], h)


def inf_sup(scene, scaling: str = "h", law: str | None = None) -> InfSup:
    """β_h of the scene's multiplier space, for the law the scene solves
    (or ``law``): the normal (``bilateral``) or vector (``bonded``) tie.

    Everything comes from :func:`skxfem.problem.assemble`, the problem the
    solver solves: B is its reduced coupling, with the support-aware spaces
    of the law's components.  A is its stiffness plus E/L² times the X-FEM
    mass (so bodies that float without the tie are still normed),
    restricted to the free unknowns; M is h·(interface mass)
    (``scaling="h"``, the discrete H^{-1/2} norm) or the plain interface
    mass (``"l2"``).  Both masses are integrated exactly (the volume one
    with its own orders, :func:`skxfem.enrich.mass`; the interface rule of
    order 4 is exact for P1 × P1 on the flat facets).

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene`; its mesh, level set, material,
        displacements, ``space`` and ``law`` are used (its loads are not).
    scaling
        ``"h"`` or ``"l2"``, the norm of the multipliers (see the module notes).
    law
        ``None`` (the scene's), ``"bilateral"`` (one multiplier per point),
        ``"bonded"`` (dim of them) or ``"stick"``: a contact where every dof
        sticks, the normal multipliers and those of each tangent that no
        support holds (:func:`skxfem.contact.interface.operators`), normed by
        their own interface masses.

    Returns
    -------
    InfSup
        β_h, all β², the zero modes, the rank of B_r and the h used in M
        (the mean length of the cut edges).
    """
    if scaling not in ("h", "l2"):
        raise ValueError(f"scaling must be 'h' or 'l2', got {scaling!r}")
    resolved = resolve(scene)
    laws = [i.law for i in resolved.scene.interfaces] if law is None else [law]
    contact = [name for name in laws if name in CONTACT_LAWS]
    if contact or all(name == "free" for name in laws):
        what = (f"law {contact[0]!r} is a contact law, whose multipliers change "
                f"with the contact state" if contact else "law 'free' has no "
                "multipliers (free faces), so no inf-sup constant")
        raise ValueError(f"inf_sup: {what}; give law='bilateral' (the normal "
                         f"multipliers), 'stick' or 'bonded'")
    p = assemble(resolved, "bilateral" if law == "stick" else law)
    mesh, V = p.mesh, p.V
    L = np.ptp(mesh.p, axis=1).max()
    A = p.K + (p.scene.material.E / L ** 2) * mass(V)
    # the L² norm of λ_h on each interface, its components apart
    M = sp.block_diag([sp.kron(sp.identity(q.ncomp), q.M_edges) for q in p.interfaces],
                      format="csr")
    free = np.setdiff1d(np.arange(V.N), p.D)   # the solver's, enriched ones included
    # mesh size across Γ: the mean length of the cut edges (anisotropic
    # meshes, such as one layer of prisms along x, are measured where it matters;
    # at a vertex on Γ the mean of its edges: skxfem.cut.point_lengths)
    h = float(np.mean(np.concatenate([point_lengths(mesh, q.cut)
                                      for q in p.interfaces])))
    B, Ps = p.B, [p.P]
    if law == "stick":
        ops = operators(p)
        B, kept = sticking_rows(p.B, ops.Bt, ops.tangent_held)
        Ps += [Pt[:, d] for Pt, d in zip(ops.Pt, kept)]
    Mr = sp.block_diag([P.T @ M @ P for P in Ps], format="csr")
    Mr = Mr * (h if scaling == "h" else 1.0)
    return inf_sup_constant(A[free][:, free], B[:, free], Mr, h=h)
