r"""The linear solve of one contact Newton step: direct, or iterative where the step is a tie.

:func:`direct` solves the whole Newton matrix of :mod:`skxfem.contact_newton`
by SuperLU.  :func:`iterative` uses that the step of a frictionless or
adhesive law *is* a tied problem.  In the Newton matrix, the row of a closed
dof j (χ_j = 1) is the linearised d_j = 0 and that of an open dof fixes its
multiplier:

.. math:: \frac{\rho_n}{w_j} B_{n,j} \Delta U = -R_{n,j} \quad (\chi_j = 1),
          \qquad \Delta\lambda_j = -R_{n,j} \quad (\chi_j = 0),

and ``adhesive`` adds, per tangent a, ρ_τ/w_j B_{τa,j} ΔU = R_{τa,j} at
closed dofs and ΔT_{aj} = -R_{τa,j} at open ones.  The open unknowns are
known; moved to the right-hand side of equilibrium they leave

.. math:: K \Delta U + B^T y = f, \qquad B \Delta U = c, \qquad
          (\Delta\lambda, \Delta T)_{closed} = -y,

with B the closed rows of B_n (and of the B_τa), f = -R_u + the open rows'
forces: the tie of :func:`skxfem.iterative.solve` with a right-hand side c.
A Coulomb step is not a tie (at a slipping dof Δλ moves the tangential
force μλΛ): it stays direct (:func:`skxfem.linear.choose_linear`).

>>> import numpy as np, scipy.sparse as sp
>>> x, rows, lu = direct(sp.csr_matrix([[4.0, 1.0], [1.0, 0.0]]), np.array([-1.0, 0.0]), 1)
>>> x.round(12).tolist()
[0.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .contact_laws import normal_update
from .iterative import solve as tie_solve

__all__ = ["scales", "direct", "iterative"]


def scales(A, nu):
    """Row and column scales (r, c) of the Newton matrix ``A``: Jacobi on the
    first ``nu`` (displacement) unknowns, the others to unit max."""
    A = sp.csr_matrix(A)
    n = A.shape[0]
    diag = np.abs(A.diagonal()[:nu])
    c = np.ones(n)
    c[:nu] = 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0))
    r = c.copy()
    A1 = sp.diags(r) @ A @ sp.diags(c)
    c[nu:] /= np.maximum(abs(A1[:, nu:]).max(axis=0).toarray().ravel(), 1e-300)
    A1 = A @ sp.diags(c)
    r[nu:] = 1.0 / np.maximum(abs(A1[nu:]).max(axis=1).toarray().ravel(), 1e-300)
    return r, c


def direct(A, R, nu, reuse=None):
    """Solve A x = -R by SuperLU on the scaled matrix: x, the row scales, and
    the factorisation, which ``reuse`` passes back to the next call: if A has
    not changed (a Newton step whose active set and, for Coulomb, iterate
    leave the matrix as it was), it is not factorised again."""
    A = sp.csr_matrix(A)
    if reuse is not None and reuse[0].shape == A.shape and (reuse[0] != A).nnz == 0:
        _, r, c, lu = reuse
        return c * lu.solve(-r * R), r, reuse
    r, c = scales(A, nu)
    As = sp.diags(r) @ A @ sp.diags(c)
    try:
        lu = spla.splu(As.tocsc(), permc_spec="COLAMD")
        pivots = np.abs(lu.U.diagonal())
        if pivots.min() < 1e-11 * pivots.max():
            raise RuntimeError(f"smallest LU pivot {pivots.min() / pivots.max():.1e} "
                               f"of the largest")
    except RuntimeError as e:  # SuperLU: "Factor is exactly singular"
        raise ValueError(
            f"the contact Newton matrix is singular ({e}): either a part of the body can "
            f"move freely (a frictionless or open interface leaves a rigid motion of one "
            f"side: add supports on each side), or some multipliers depend on the others "
            f"(the naive space on tetrahedra, or a support acting on a face that Γ cuts: "
            f"use space='vital' or move the support)") from e
    return c * lu.solve(-r * R), r, (A, r, c, lu)


def iterative(ops, law, K, free, g_n, R, modes=None, blocksize=1, tol=1e-12, reuse=None):
    """Solve the Newton step of a frictionless or adhesive ``law`` as a tie.

    ``R`` = (R_u, R_n, R_t) as :func:`skxfem.contact_newton.residual`, ``g_n``
    the augmented normal gap (χ), ``modes`` and ``blocksize`` as
    :func:`skxfem.iterative.solve`.  Returns the step x = (ΔU_free, Δλ, ΔT) of
    the Newton matrix, solved to the relative residual ``tol``, and the tie's
    :class:`skxfem.iterative.Setup`, which ``reuse`` passes back to the next
    call: the same closed dofs, the same tie, no second AMG set-up.

    Raises
    ------
    ValueError
        A Coulomb law, or dependent multipliers (the direct path refuses them
        too: the law must hold at every dof, so its multiplier must be unique).
    skxfem.iterative.ConvergenceError, skxfem.saddle.SingularSystemError
        As :func:`skxfem.iterative.solve` (a part of the body free to move).
    """
    if law.name not in ("frictionless", "adhesive"):
        raise ValueError(f"the iterative contact step solves frictionless and adhesive "
                         f"laws, not {law.name!r}: use linear='direct'")
    R_u, R_n, R_t = R
    N, m = K.shape[0], ops.w.size
    k = R_t.size // m if m else 0
    closed = normal_update(g_n)[1] > 0
    # the open dofs' unknowns, and their forces on equilibrium
    d_lam = np.where(closed, 0.0, -R_n)
    d_T = np.where(closed, 0.0, -R_t.reshape(k, m))
    rows = [(ops.Bn, -(ops.w / law.rho_n) * R_n, d_lam)]
    rows += [(ops.Bt[a], (ops.w / law.rho_t) * R_t.reshape(k, m)[a], d_T[a])
             for a in range(k)]
    f = np.zeros(N)
    f[free] = -R_u
    f += sum(Bx.T @ known for Bx, _, known in rows)
    B = sp.vstack([Bx[closed] for Bx, _, _ in rows], format="csr")
    c = np.concatenate([rhs[closed] for _, rhs, _ in rows])
    fixed = np.setdiff1d(np.arange(N), free)
    dU, mu, info = tie_solve(K, B, f, fixed, np.zeros(fixed.size), modes=modes,
                             blocksize=blocksize, c=c, tol=tol, reuse=reuse)
    if info.removed:  # as the direct path: a pressure at every dof must be unique
        raise ValueError(
            f"{info.removed} contact multipliers depend on the others (the naive space on "
            f"tetrahedra, or a support acting on a face that Γ cuts): use space='vital' "
            f"or move the support")
    parts = mu.reshape(k + 1, -1)  # the closed dofs' λ, then those of each T_a
    d_lam[closed], d_T[:, closed] = parts[0], parts[1:]
    return np.concatenate([dU[free], d_lam, d_T.ravel()]), info.setup
