r"""The rigid slide of a part that only Γ holds, where every Coulomb point of it slides.

A part of the body that no support touches is held along Γ by friction alone.
Where every closed point of it slides, the Newton matrix of
:mod:`skxfem.contact.newton` is singular: in the slip branch the friction force
R ŝ does not change with the slip (2D), so nothing fixes how far the part slides
as a rigid body.  Unloaded from a large load to a small one, this is the usual
state: the elastic shear relaxes, the points slide backwards on one side and
forwards on the other, and the answer has a point sticking between them in a
band |r_τ − ρ_τ s| ≤ μp that is μp/ρ_τ thin (ρ_τ ≈ E/h is set for the loaded
state, the pressure fell 100-fold).  The merit ‖R‖ is flat along that slide
until a point enters its band, so no line search finds it, and the
all-closed-and-sticking Jacobian of the fallback moves the part by a few
per cent of the way per iteration (``tests/test_contact_holding.py``: the
friction residual stalled at 1e-4 for 60 iterations, then 64 step cuts).

**Which parts.**  Parts joined by a closed point that sticks move together: with
two interfaces, a middle slab that Γ₂ holds in part to the top slides with it on
Γ₁ (:func:`clusters`); a cluster stuck to a part a support holds is held.

**The slide.**  The part's rigid slides are the translations Z t (t ∈ ℝ^q) that
keep every closed point closed (Bₙ Z t = 0 there: q = dim − 1 on a plane Γ).
Tested with Z, equilibrium says that the friction forces balance the resultant
f = Zᵀ F + (Bₙ Z)ᵀ λ of the part's loads; with every point sliding, r_τj =
−R_j ŝ_j (R_j = μ p_j the radius of its ball, s_j its slip increment), this is
the stationarity of the convex

.. math:: \Phi(t) = \sum_j w_j R_j \,|s_j + D_j t| - f\cdot t, \qquad
          D_j = \frac{B_\tau Z|_j}{w_j},

the friction's dissipation (w_j the weights of the dofs): its minimiser is the
slide at which friction holds the part, a point j sticking where s_j + D_j t = 0.
:func:`slide` moves the part there (the pressure and the displacement of the
rest as they are), sets each sliding point's traction on its ball, −R ŝ, and
leaves Newton to correct the elastic part from a state whose matrix is regular
(one point sticks).  Φ is minimised exactly in 1D (q = 1: a weighted median of
the points' breakpoints) and by iteratively reweighted least squares
(Weiszfeld) otherwise, then snapped onto the nearest point that sticks.

>>> d, s, c = np.array([[1.0], [1.0], [1.0]]), np.array([-1.0, 0.5, 2.0]), np.ones(3)
>>> float(minimise(s[:, None], d[:, :, None], c, np.zeros(1))[0])   # the median point sticks
-0.5
"""
from __future__ import annotations

import numpy as np

from .laws import SLIP

__all__ = ["translations", "slides", "minimise", "bounded", "clusters", "slide", "slips"]

SNAP = 1e-10
"""A point whose slip |s + D t| is below this fraction of the largest slip of the
part, at the minimiser found, is taken to stick (:func:`slide`)."""


def translations(modes: np.ndarray, D: np.ndarray, dim: int) -> list[np.ndarray]:
    """The translations (N, dim) of each part that no support touches: columns of the
    rigid ``modes`` (:func:`skxfem.linalg.amg.rigid_modes`, column R i + r the i-th
    motion of part r) that move no imposed unknown ``D``.

    >>> modes = np.eye(6)    # 2D, two parts: columns 0, 2 part 0's translations
    >>> [T.shape for T in translations(modes, np.array([0]), 2)]   # unknown 0 held
    [(6, 2)]
    """
    parts = modes.shape[1] // (3 if dim == 2 else 6)
    out = []
    for r in range(parts):
        T = modes[:, [parts * i + r for i in range(dim)]]
        if not np.any(T[D] != 0):
            out.append(T)
    return out


def slides(T: np.ndarray, Bn, closed: np.ndarray) -> np.ndarray:
    """The slides (N, q) of a part with translations ``T`` (N, dim): those that keep
    the normal jump of the ``closed`` dofs, an orthonormal basis of the null space
    of Bₙ T there (q = 0 where the closed dofs hold every translation)."""
    a = Bn[closed] @ T
    if a.shape[0] == 0:
        return T
    _, sigma, Vt = np.linalg.svd(a)
    rank = int(np.sum(sigma > 1e-8 * max(float(np.abs(a).max()), 1e-300)))
    return T @ Vt[rank:].T


def minimise(s: np.ndarray, D: np.ndarray, c: np.ndarray, f: np.ndarray,
             iterations: int = 200) -> np.ndarray:
    """The minimiser t (q,) of Φ(t) = Σ c_j |s_j + D_j t| - f·t (module notes).

    ``s`` (n, k) slips, ``D`` (n, k, q) their change per unit t, ``c`` (n,) ≥ 0 the
    weights w_j R_j.  q = 1: the exact weighted median of the breakpoints; else
    Weiszfeld's iteration, snapped onto the point whose slip it nearly cancels."""
    n, k, q = D.shape
    if q == 1 and k == 1:
        d, c0 = D[:, 0, 0], c * (D[:, 0, 0] != 0)
        ok = c0 > 0
        if ok.any():
            t_j = -s[ok, 0] / d[ok]                 # where each point's slip vanishes
            weight = c0[ok] * np.abs(d[ok])
            order = np.argsort(t_j)
            # Φ' just past the i-th breakpoint: 2 Σ_{≤i} weight - Σ weight - f
            slope = 2 * np.cumsum(weight[order]) - weight.sum() - f[0]
            i = int(np.searchsorted(slope, 0.0))
            return np.array([t_j[order][min(i, t_j.size - 1)]])
    # Weiszfeld: t = argmin Σ c_j |s_j + D_j t|² / (2|s_j + D_j t|) - f·t, reweighted
    t = np.zeros(q)
    best, value = t, _phi(s, D, c, f, t)
    for _ in range(iterations):
        g = s + np.einsum("nkq,q->nk", D, t)
        norm = np.maximum(np.linalg.norm(g, axis=1), 1e-14 * max(np.abs(s).max(), 1e-300))
        a = c / norm
        A = np.einsum("n,nkq,nkp->qp", a, D, D)
        b = f - np.einsum("n,nkq,nk->q", a, D, s)
        try:
            t = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            break
        v = _phi(s, D, c, f, t)
        if v < value:
            best, value = t, v
    # snap onto the point nearest to sticking, where it lowers Φ
    for j in np.argsort(np.linalg.norm(s + np.einsum("nkq,q->nk", D, best), axis=1))[:3]:
        if c[j] > 0 and np.linalg.matrix_rank(D[j]) == q and k == q:
            snapped = np.linalg.solve(D[j], -s[j])
            if _phi(s, D, c, f, snapped) <= value:
                best, value = snapped, _phi(s, D, c, f, snapped)
    return best


def bounded(D: np.ndarray, c: np.ndarray, f: np.ndarray, directions: int = 720) -> bool:
    """Whether Φ (:func:`minimise`) has a minimiser: the friction the points can give
    along every slide e, Σ c_j |D_j e|, exceeds the load along it, f·e (q = 1 exactly;
    q = 2 on ``directions`` unit vectors; q > 2 on the axes and their opposites)."""
    q = D.shape[2]
    if q == 1:
        E = np.array([[1.0], [-1.0]])
    elif q == 2:
        a = np.linspace(0.0, 2 * np.pi, directions, endpoint=False)
        E = np.c_[np.cos(a), np.sin(a)]
    else:
        E = np.vstack([np.eye(q), -np.eye(q)])
    reach = np.linalg.norm(np.einsum("nkq,eq->enk", D, E), axis=2) @ c
    return bool(np.all(reach > E @ f * (1 + 1e-9)))


def _phi(s, D, c, f, t) -> float:
    return float(c @ np.linalg.norm(s + np.einsum("nkq,q->nk", D, t), axis=1) - f @ t)


def slips(ops, U, U_prev) -> np.ndarray:
    """s (m, k): the weighted tangential jump increments over the step, Bt_a (U - U_prev)
    / w (the s of :func:`skxfem.contact.newton.jumps`)."""
    return np.stack([B @ (U - U_prev) for B in ops.Bt], axis=1) / ops.w[:, None]


def clusters(parts, ops, status, laws) -> list[np.ndarray]:
    """The translations (N, dim) of the clusters of ``parts`` (translations of the parts
    that only Γ holds) that move as one: parts joined by a closed dof that sticks (or
    whose law has no slip) move together; a cluster that such a dof joins to a part a
    support holds is held, and left out."""
    stuck = (status == 1) | ((status != 0) & (laws.tangential == "stick"))
    touch = [(abs(ops.Bn @ T).sum(axis=1) + sum(abs(B @ T).sum(axis=1) for B in ops.Bt)) > 0
             for T in parts]
    label = list(range(len(parts)))

    def root(i):
        while label[i] != i:
            i = label[i]
        return i
    for a in range(len(parts)):
        for b in range(a + 1, len(parts)):
            if np.any(touch[a] & touch[b] & stuck):
                label[root(a)] = root(b)
    anchored = set()
    for a in range(len(parts)):
        others = np.any([touch[b] for b in range(len(parts)) if b != a], axis=0) \
            if len(parts) > 1 else np.zeros(touch[a].size, bool)
        if np.any(touch[a] & stuck & ~others):
            anchored.add(root(a))          # stuck to a supported part
    groups = {}
    for a in range(len(parts)):
        groups.setdefault(root(a), []).append(a)
    return [sum(parts[a] for a in members) for key, members in groups.items()
            if key not in anchored]


def slide(step, it, res, F):
    """(U, r_τ) of the iterate ``it`` with every part that only Γ holds slid to where
    friction holds it (module notes), or None where no part slides to a point that
    sticks (``step.slides``: the translations of those parts, :func:`translations`;
    ``F`` the step's loads).  A part is slid only where all its Coulomb dofs that are
    closed and pressed (radius > 0) slide, no dof holds it by its law (a no-slip law),
    and those dofs can hold its loads (:func:`bounded`); a 3D part held with every
    point sliding, the slip directions apart, is left as it is.  The sliding dofs get
    the traction on their ball against their slip, -R ŝ, the dofs that stick the least
    (minimum-norm) tractions that balance the part's loads, each kept in its ball."""
    laws, ops = step.laws, step.ops
    closed = res.status != 0
    coulomb = (laws.tangential == "coulomb") & closed & (res.radius > 0)
    free = ~laws.tangent_held
    U, r = it.U.copy(), it.r.copy()
    moved = False
    for T in clusters(step.slides, ops, res.status, laws):
        Z = slides(T, ops.Bn, closed)
        if Z.shape[1] == 0:
            continue
        G = np.stack([B @ Z for B in ops.Bt], axis=1) * free[:, :, None]  # (m, k, q)
        D = G / ops.w[:, None, None]
        touches = np.abs(D).max(axis=(1, 2)) > 0
        on = coulomb & touches
        if not on.any() or np.any(res.status[on] != SLIP) or np.any(
                (laws.tangential == "stick") & closed & touches):
            continue
        f = Z.T @ F + (ops.Bn @ Z).T @ it.lam
        c = ops.w[on] * res.radius[on]
        if not bounded(D[on], c, f):
            continue                  # these dofs cannot hold the part: Newton's to find
        t = minimise((slips(ops, U, step.U_prev) * free)[on], D[on], c, f)
        s = slips(ops, U + Z @ t, step.U_prev) * free
        norm = np.linalg.norm(s, axis=1)
        sliding = on & (norm > SNAP * norm[on].max())
        stuck = on & ~sliding
        if not stuck.any():
            continue                  # held with every point sliding (3D)
        U = U + Z @ t
        r[sliding] = -(res.radius[sliding] / norm[sliding])[:, None] * s[sliding]
        # the stuck tractions balance the part: Σ_j G_jᵀ r_j = -f
        known = np.einsum("nkq,nk->q", G[~stuck], r[~stuck])
        A = G[stuck].transpose(2, 0, 1).reshape(G.shape[2], -1)      # (q, n_stuck k)
        x = np.linalg.lstsq(A, -f - known, rcond=None)[0].reshape(-1, G.shape[1])
        size = np.linalg.norm(x, axis=1)
        R = res.radius[stuck]
        r[stuck] = x * np.minimum(1.0, R / np.where(size > 0, size, 1.0))[:, None]
        moved = True
    return (U, r * free) if moved else None
