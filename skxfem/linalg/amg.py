r"""Algebraic multigrid for the X-FEM stiffness: its near-null space and the hierarchy.

Smoothed aggregation (pyamg) builds its coarse spaces from a few vectors the
operator nearly annihilates.  For plain elasticity these are the rigid
motions of the body.  The X-FEM stiffness K on [a, b] has twice as many: a
rigid motion of Ω⁻ with Ω⁺ at rest, and one of Ω⁺ with Ω⁻ at rest
(:func:`rigid_modes`); their sums are the rigid motions of the body.
:func:`amg` builds the hierarchy on nodal blocks (the unknowns of a node,
standard or enriched, aggregate together) with a SuperLU coarse solve.

pyamg is an optional dependency (``pip install pyamg`` or ``skxfem[amg]``),
imported when a hierarchy is built.

>>> import scipy.sparse as sp, numpy as np
>>> A = sp.diags([-np.ones(99), 2 * np.ones(100), -np.ones(99)], [-1, 0, 1])
>>> amg(A).levels[0].A.shape
(100, 100)
"""
from __future__ import annotations

import importlib

import numpy as np
import scipy.sparse as sp

from .dependent import unit_rows
from .saddle import SingularSystemError, floating

__all__ = ["MOTIONS", "body_motions", "rigid_modes", "axis_name", "motion_name",
           "free_motion_name", "amg", "refresh", "vcycle", "SMOOTHER", "CARRIED_SMOOTHER",
           "check_held", "scaled_tie", "scaled_rows", "augmented", "check_tie_held"]


def pyamg():
    """The pyamg module, or an ImportError that says how to install it."""
    try:
        return importlib.import_module("pyamg")
    except ImportError as e:
        raise ImportError("the iterative solver needs pyamg: pip install pyamg "
                          "(or pip install skxfem[amg])") from e


MOTIONS = {2: 3, 3: 6}
"""The rigid motions of a body in 2D and 3D: translations, then rotations."""


def body_motions(x: np.ndarray) -> list[np.ndarray]:
    """The rigid motions at the points x (dim, n), each (dim, n): the translations along
    x, y (, z), then the rotations about the origin (about z in 2D; x, y, z in 3D).

    >>> [m[:, 0].tolist() for m in body_motions(np.array([[1.0], [2.0]]))]
    [[1.0, 0.0], [0.0, 1.0], [-2.0, 1.0]]
    """
    dim = x.shape[0]
    motions = [np.eye(dim)[:, [c]] * np.ones(x.shape[1]) for c in range(dim)]
    if dim == 2:
        return motions + [np.array([-x[1], x[0]])]
    z = np.zeros_like(x[0])
    return motions + [np.array([z, -x[2], x[1]]), np.array([x[2], z, -x[0]]),
                      np.array([-x[1], x[0], z])]


def rigid_modes(V, sides: bool = True, centre=None, length: float = 1.0) -> np.ndarray:
    """The rigid motions of Ω⁻ and of Ω⁺, each with the other side at rest, on [a, b].

    With the shifted enrichment u = Σ aᵢφᵢ + Σ bⱼφⱼ(H - Hⱼ) and R a rigid
    motion, "R on the side s, 0 on the other" has aᵢ = R(xᵢ) at the nodes of
    side s (Hᵢ = s), aᵢ = 0 elsewhere, and bⱼ = s R(xⱼ)/2 at every enriched
    node (its far side gets R or -R from the jump 2bⱼ).  The two sum to R on
    the whole body, with b = 0.

    Parameters
    ----------
    V
        An :class:`skxfem.enrich.XSpaces` on [a, b¹, b², …] (an
        :class:`~skxfem.enrich.XSpace`: the space of one interface).
    sides
        ``False``: only the k rigid motions of the whole body (their sums).
    centre, length
        The rotations turn about ``centre`` (default the origin) and move a
        point at distance ``length`` from it by 1 (default 1): the same span,
        columns of comparable size wherever the mesh lies.

    Returns
    -------
    (N, R k) array, column R i + r the i-th motion of region r with the others at
    rest (R regions, :meth:`~skxfem.enrich.XSpaces.regions`; one interface: R = 2,
    columns 2i and 2i+1 the i-th motion of Ω⁻ and of Ω⁺), ``sides=False``: (N, k),
    their sums; k = 3 in 2D (two translations, one rotation), 6 in 3D.

    With several interfaces, at a node j of region σ enriched by Γ_k, whose far
    side is the region σ' (σ with its k-th sign flipped), u = a + b^k(H^k - H^k_j)
    must be R·[σ = r] on its side and R·[σ' = r] on the far one: aⱼ = R(xⱼ)[σ = r],
    b^k_j = H^k_j R(xⱼ)([σ = r] - [σ' = r])/2 (with one interface the formula above).

    >>> from skxfem.scene.benchmarks import strip
    >>> from skxfem.problem import assemble
    >>> p = assemble(strip(3, "tri"))
    >>> Z = rigid_modes(p.V)
    >>> Z.shape, float(abs(p.K @ Z).max()) < 1e-12
    ((48, 6), True)
    """
    dim = V.mesh.p.shape[0]
    x = V.mesh.p - (np.zeros((dim, 1)) if centre is None
                    else np.asarray(centre, float).reshape(dim, 1))
    x = x / length
    nd = V.basis.nodal_dofs  # (dim, nverts)
    motions = body_motions(x)
    node_of = np.zeros(V.n_std, dtype=np.int64)
    node_of[nd.ravel()] = np.tile(np.arange(x.shape[1]), dim)
    Z, R = _region_modes(V, motions, node_of, nd)
    return Z if sides else sum(Z[:, r::R] for r in range(R))


def _region_modes(V, motions, node_of, nd) -> tuple[np.ndarray, int]:
    """The motions of each region of ``V`` (:func:`rigid_modes`) and the number of
    regions R (:meth:`skxfem.enrich.XSpaces.regions`; an XSpace is the space of one
    interface, whose regions are Ω⁻ and Ω⁺); ``nd`` the standard dofs of each node
    (``V.basis.nodal_dofs``, which a crack's space builds anew at each call)."""
    spaces = getattr(V, "per_interface", (V,))
    patterns, node_region = V.regions()
    R = patterns.shape[0]
    # a region's signs as the bits of one number, one bit per interface that splits
    codes = ((patterns > 0).astype(np.int64) << np.arange(patterns.shape[1])).sum(axis=1)
    bit = np.cumsum([Vk.splits for Vk in spaces]) - 1   # the bit of each splitting one
    order = np.argsort(codes)
    region_of = node_region[node_of]  # the region of each standard dof's node
    starts = np.cumsum([V.n_std] + [Vk.n_enr for Vk in spaces])
    far = []   # the region on the far side of interface k of each of its enriched dofs
    for k, Vk in enumerate(spaces):
        if not Vk.splits:   # a crack: the body is one around its front, its unknowns 0
            far.append(region_of[Vk.enr_dofs])
            continue
        want = codes[region_of[Vk.enr_dofs]] ^ (1 << int(bit[k]))
        at = np.minimum(np.searchsorted(codes[order], want), R - 1)
        far.append(np.where(codes[order][at] == want, order[at], -1))
    Z = np.zeros((V.N, R * len(motions)))
    for i, motion in enumerate(motions):
        a = np.zeros(V.n_std)
        a[nd.ravel()] = motion.ravel()
        for r in range(R):
            col = R * i + r
            Z[:V.n_std, col] = np.where(region_of == r, a, 0.0)
            for k, Vk in enumerate(spaces):
                on = (region_of[Vk.enr_dofs] == r).astype(float) - (far[k] == r)
                Z[starts[k]:starts[k + 1], col] = 0.5 * Vk.H_node * a[Vk.enr_dofs] * on
    return Z, R


def axis_name(v) -> str:
    """The name of the direction of ``v`` (either way along it): an axis, else
    its rounded unit components, the first non-zero one positive.

    >>> axis_name([0.0, -2.0]), axis_name([-1.0, 1.0])
    ('y', '(0.707, -0.707)')
    """
    v = np.asarray(v, float)
    v = v / np.linalg.norm(v)
    v = v * np.sign(v[np.flatnonzero(np.abs(v) > 1e-9)[0]])
    axis = int(np.argmax(np.abs(v)))
    if abs(abs(v[axis]) - 1.0) < 1e-9:
        return "xyz"[axis]
    return "(" + ", ".join(f"{x:.3g}" for x in v) + ")"


def motion_name(c, dim: int, centre=None, length: float = 1.0, verb: bool = True) -> str:
    """A rigid motion in words, from its coefficients ``c`` on the k motions of
    :func:`rigid_modes` (translations along x, y (, z), then the rotations)
    with the same ``centre`` and ``length``.

    >>> motion_name([0.0, 1.0, 0.0], 2)
    'translate along y'
    >>> motion_name([0.5, -0.5, 1.0], 2)        # turning about the origin, then shifted
    'rotate about z (about the point (0.5, 0.5))'
    """
    c = np.asarray(c, float)
    centre = np.zeros(dim) if centre is None else np.asarray(centre, float)
    t, w = c[:dim], c[dim:]
    if dim == 2:
        if abs(w[0]) > 1e-6 * max(np.abs(c).max(), 1e-300):
            x0 = centre + length * np.array([-t[1], t[0]]) / w[0]
            point = ", ".join(f"{x:.3g}" for x in x0)
            return f"{'rotate' if verb else 'rotates'} about z (about the point ({point}))"
    elif np.linalg.norm(w) > 1e-6 * max(np.abs(c).max(), 1e-300):
        x0 = centre + length * np.cross(w, t) / (w @ w)
        point = ", ".join(f"{x:.3g}" for x in x0)
        return (f"{'rotate' if verb else 'rotates'} about an axis along {axis_name(w)} "
                f"through ({point})")
    return f"{'translate' if verb else 'translates'} along {axis_name(t)}"


SMOOTHER = ("chebyshev", {"degree": 2})
"""The smoother of a hierarchy :func:`amg` builds for the operator it solves: every tie's
K_r, a crack's block-scaled K (:func:`skxfem.linalg.iterative.solve`).  A Chebyshev
polynomial of degree 2 in the level's matrix, before and after the coarse correction
(symmetric: the V-cycle stays a preconditioner for CG).  A step needs only products with
the matrix, which pyamg's symmetric block Gauss-Seidel sweeps several times slower: CG
takes more iterations, each far cheaper.

Measured, one run each, the solve stage of ``skxfem.solve(scene, linear="iterative")``,
block Gauss-Seidel -> this (-> degree 3), CG iterations in brackets; U within 1e-11 and
the tractions within 5e-11 of each other, and of the direct solve where it was run (3D
n ≤ 16, the strip n = 256), as close as with Gauss-Seidel:

* the paper's plate, bonded (``paper_plate``): hex n = 24 2.26 s (22) -> 1.37 s (29)
  (1.67 s (23)), n = 32 5.65 (26) -> 2.43 (40) (3.07 (31)); prism n = 24 2.72 (35) ->
  1.34 (39) (1.19 (34)), n = 32 5.68 (37) -> 2.73 (46) (3.57 (39)); tet n = 24 1.98 (38)
  -> 1.02 (45) (1.28 (38)); ``benchmarks/crack_solve.py``'s tie (tet, n = 24) 1.37 (40)
  -> 0.74 (46);
* bilateral (hex n = 24, rollers on y = 0): 2.68 (26) -> 1.58 (33); two interfaces, a
  tilted bonded one and a bilateral one (hex n = 24, 56 925 unknowns): 6.54 (36) -> 5.03
  (46) (4.50 (38));
* slivers, Γ 1e-3 of a cell above a plane of nodes: hex n = 24 1.39 (22) -> 1.12 (27);
  prism n = 16 (1e-4) 0.45 (29) -> 0.33 (38); tet n = 12 0.19 (25) -> 0.23 (42) (0.16 (35));
* Ω⁺ 100 times stiffer (``material_plus``): hex n = 12 0.40 (54) -> 0.23 (80), n = 16
  0.77 (52) -> 0.90 (111) (another run: 1.39 -> 1.18); 200 times, n = 12: 0.51 (76) ->
  0.29 (115).  300 or 1000 times at n = 12, 100 times at n = 24: neither smoother
  reaches the default 1e-12 in 500 iterations (both stall at 1e-12 to 5e-12, the floor of
  such a system; the solve now takes such an answer by its backward error,
  :mod:`skxfem.linalg.iterative`);
* 2D, the strip (``strip``): tri n = 256, 133 640 unknowns, 2.41 (61) -> 1.26 (59) (1.81
  (56)); quad n = 400, 324 008 unknowns, 4.55 (28) -> 1.73 (33) (1.85 (29)); tri n = 512
  (529 416 unknowns): none reaches 1e-12 in 500 iterations (1.6e-12 to 1.7e-12; taken
  now by its backward error);
* a crack (``benchmarks/crack_solve.py``'s, n = 24): 4.77 (57) -> 2.19 (64), Chebyshev
  on the finest level and Gauss-Seidel below 2.48 (63); on its scaled system alone,
  n = 16 1.71 (49) -> 0.79 (56), degree 1 94 iterations.

Degree 3 is as fast within the noise of the shared machine up to n = 24, slower at 32."""


CARRIED_SMOOTHER = ("block_gauss_seidel", {"sweep": "symmetric"})
"""The smoother of the hierarchy a contact solve builds once for K_s and carries over to
every Newton step's tie (:func:`skxfem.linalg.iterative.stiffness_setup`,
:func:`refresh`): pyamg's symmetric block Gauss-Seidel, which solves each node's block of
the step's K_r exactly, wherever the step's rows and interface stiffness stiffen it.

Chebyshev was measured and left out.  On every level it needed 2 to 5 times the Krylov
iterations and was slower on the larger scenes; on the finest level only (block
Gauss-Seidel below) it was faster everywhere measured, but a Newton solve at the kink of
the slip limit, where the sliding stiffness is nearly singular, then took 29 iterations
instead of 9 (``tests/test_contact_linear.py``, the 3D block at μ = 5, ρ_τ = 1e-3 E/h;
degree 3: 12).  One run each, the solve stage of ``skxfem.solve(scene,
linear="iterative")``, this -> Chebyshev degree 2 on the finest level (-> on every
level), the Krylov iterations of all Newton steps in brackets, the solutions within
4e-11 of each other: the slipping block (``slipping_block``, Coulomb) hex n = 14 1.56 s
(42) -> 1.44 s (74) (1.75 s (88)), n = 24 6.63 (69) -> 5.80 (117) (7.10 (179)); prism
n = 14 1.34 (64) -> 1.03 (67); tet n = 12 0.79 (63) -> 0.74 (94); frictionless, hex
n = 14 1.15 (58) -> 0.86 (90); adhesive, hex n = 14 0.66 (30) -> 0.53 (47); the adhesive
plate hex n = 24 2.45 (25) -> 1.81 (35) (2.10 (64)); 2D, the adhesive quad strip n = 200
(82 008 unknowns) 1.79 (43) -> 1.11 (41) (2.05 (156)), n = 400 (324 008) 7.95 (50) ->
5.60 (52) (10.49 (261))."""


AMG_SEED = 0
"""The seed of the random start vectors pyamg draws (``np.random``) to estimate the
spectral radius of each level's smoother: fixed, so that an iterative solve gives
the same numbers, to the last bit, every time it runs."""


def amg(A: sp.spmatrix, modes: np.ndarray | None = None, blocksize: int = 1,
        smoother=SMOOTHER):
    """pyamg smoothed aggregation for the SPD ``A`` with near-null space ``modes``.

    Nodal blocks of ``blocksize`` unknowns are aggregated together (the
    unknowns of a node must be interleaved); the coarsest level is solved by
    SuperLU, or by a pseudo-inverse if it is singular (an aggregate whose
    nodes lie on a line, where a rotation vanishes).  The modes are used as
    they are (pyamg's smoothing of candidates is off: rigid modes are exact).
    ``smoother``: pyamg's (name, options) of the pre- and post-smoother, the
    same on every level (:data:`SMOOTHER`, :data:`CARRIED_SMOOTHER`); a Chebyshev
    smoother only multiplies by each level's matrix, and the finest level then keeps
    ``A`` in CSR (a V-cycle of a 3D crack's, 6.7 M nonzeros, 14.6 ms against 15.8 ms
    with its 3 × 3 blocks, one run).
    Returns the pyamg ``MultilevelSolver``, the same for the same ``A`` at every
    run (:data:`AMG_SEED`); the global ``np.random`` state is left unchanged.
    """
    amg_module = pyamg()
    given = sp.csr_matrix(A)
    A = sp.bsr_matrix(given, blocksize=(blocksize, blocksize)) if blocksize > 1 else given
    state = np.random.get_state()  # pyamg estimates spectral radii from np.random:
    try:
        for coarse in ("splu", "pinv"):
            np.random.seed(AMG_SEED)  # a fixed start makes every solve reproducible
            try:
                ml = amg_module.smoothed_aggregation_solver(
                    A, B=modes, coarse_solver=coarse, improve_candidates=None,
                    presmoother=smoother, postsmoother=smoother)
            except RuntimeError:  # a singular coarsest matrix: an aggregate on which
                if coarse == "pinv":  # the modes are dependent (nodes on a line)
                    raise
                continue
            ml.skxfem_coarse, ml.skxfem_smoother = coarse, smoother
            if smoother[0] == "chebyshev":
                ml.levels[0].A = given
            return ml
    finally:
        np.random.set_state(state)  # the caller's random numbers are left as they were


def refresh(ml, A: sp.spmatrix, change: sp.spmatrix | None = None):
    """The hierarchy ``ml`` (of :func:`amg`, for A₀) carried over to A = A₀ + ΔA.

    Aggregates and prolongators P are kept; every coarse operator is updated by
    the Galerkin product of the change, A_{l+1} += R_l ΔA_l P_l, which costs
    little where ΔA lives on a few rows (the interface rows of a contact
    Newton step); the smoothers and the coarsest factorisation are set up
    again.  ``change``: ΔA, if the caller has it (else A - A₀, its zeros
    dropped).  A new ``MultilevelSolver``: ``ml`` is left as it was.  The
    hierarchy is then the Galerkin hierarchy of A on A₀'s coarse spaces: a
    preconditioner for A as good as those spaces are for it.

    >>> import scipy.sparse as sp, numpy as np
    >>> A0 = sp.diags([-np.ones(99), 2.0 * np.ones(100), -np.ones(99)], [-1, 0, 1]).tocsr()
    >>> ml = amg(A0); A = (A0 + sp.diags(np.r_[1.0, np.zeros(99)])).tocsr()
    >>> new = refresh(ml, A); P, R = new.levels[0].P, new.levels[0].R
    >>> bool(abs(new.levels[1].A - R @ A @ P).max() < 1e-12), new is not ml
    (True, True)
    """
    amg_module = pyamg()
    old = ml.levels
    A = _like(A, old[0].A)
    change = sp.csr_matrix(A - old[0].A if change is None else change)
    change.eliminate_zeros()
    levels = []
    for i, level in enumerate(old):
        new = amg_module.multilevel.MultilevelSolver.Level()
        for key, value in vars(level).items():
            setattr(new, key, value)
        if i == 0:
            new.A = A
        else:
            change = sp.csr_matrix(old[i - 1].R @ change @ old[i - 1].P)
            new.A = level.A + _like(change, level.A)
        levels.append(new)
    coarse = levels[-1].A
    for name in dict.fromkeys((ml.skxfem_coarse, "pinv")):
        out = amg_module.multilevel.MultilevelSolver(levels, coarse_solver=name)
        try:  # factorise the coarsest matrix now: a singular one takes the pseudo-inverse
            out.coarse_solver(coarse, np.zeros(coarse.shape[0]))
            break
        except RuntimeError:
            continue
    smoother = ml.skxfem_smoother               # set by amg(): the hierarchy's own
    out.skxfem_coarse, out.skxfem_smoother = name, smoother
    state = np.random.get_state()
    np.random.seed(AMG_SEED)
    try:
        amg_module.relaxation.smoothing.change_smoothers(out, smoother, smoother)
    finally:
        np.random.set_state(state)
    return out


def vcycle(ml):
    """One V-cycle of the hierarchy ``ml`` from zero, as a ``LinearOperator``: the
    preconditioner of CG.

    The same numbers, bit for bit, as pyamg's ``ml.aspreconditioner(cycle="V")``,
    without its two residual norms on the finest level (one before the cycle, one after:
    two products with the finest matrix of each application, which the preconditioner
    never uses).

    >>> import scipy.sparse as sp, numpy as np
    >>> A = sp.diags([-np.ones(99), 2 * np.ones(100), -np.ones(99)], [-1, 0, 1]).tocsr()
    >>> ml = amg(A); b = np.arange(100.0)
    >>> bool(np.array_equal(vcycle(ml) @ b, ml.aspreconditioner(cycle="V") @ b))
    True
    """
    from scipy.sparse.linalg import LinearOperator

    levels = ml.levels

    def cycle(i, b):
        level = levels[i]
        x = np.zeros_like(b)
        level.presmoother(level.A, x, b)
        coarse_b = level.R @ (b - level.A @ x)
        if i == len(levels) - 2:
            coarse_x = ml.coarse_solver(levels[-1].A, coarse_b)
        else:
            coarse_x = cycle(i + 1, coarse_b)
        x += level.P @ coarse_x
        level.postsmoother(level.A, x, b)
        return x

    def apply(b):
        b = np.ravel(np.asarray(b, dtype=np.result_type(b, levels[0].A.dtype)))
        if len(levels) == 1:
            return ml.coarse_solver(levels[0].A, b)
        return cycle(0, b)

    A = levels[0].A
    return LinearOperator(A.shape, apply, dtype=A.dtype)


def _like(A, template):
    """A in the format of ``template``: BSR with its blocks, or CSR."""
    if template.format == "bsr":
        return A if A.format == "bsr" and A.blocksize == template.blocksize else \
            sp.bsr_matrix(A, blocksize=template.blocksize)
    return sp.csr_matrix(A)


def check_held(Kr, Z, rigid_tol: float = 1e-11, dim: int | None = None):
    """Refuse a rigid motion of a side that ``Kr`` leaves free.

    The smallest Rayleigh quotient of ``Kr`` (scaled to unit diagonal) over
    the span of the modes ``Z`` (orthonormalised) must reach ``rigid_tol``;
    otherwise a :class:`skxfem.linalg.saddle.SingularSystemError` naming the motion
    (:func:`free_motion_name` in ``dim`` D; ``Z`` as :func:`rigid_modes` orders them).
    """
    Q, R = np.linalg.qr(Z)
    d = np.abs(np.diag(R))
    Q = Q[:, d > 1e-12 * d.max()] if d.size and d.max() > 0 else Q[:, :0]
    if Q.shape[1] == 0:
        return
    energies, vectors = np.linalg.eigh(Q.T @ (Kr @ Q))
    if energies[0] < rigid_tol:
        c = np.linalg.lstsq(Z, Q @ vectors[:, 0], rcond=None)[0]
        raise floating(f"{free_motion_name(c, dim)}: a rigid motion of energy "
                       f"{energies[0]:.1e}",
                       "the system")


def free_motion_name(c, dim: int | None = None) -> str:
    """Who moves how, for coefficients ``c`` on the 2k columns of :func:`rigid_modes`
    (the whole body, Ω⁻ or Ω⁺ alone, or the two apart), or on the k motions of the whole
    body (``sides=False``; told apart by ``dim``: without it 6 columns are read as 2D's
    two sides).

    >>> free_motion_name([0.0, 1.0, 0.0, 0.0, 0.0, 0.0])   # Ω⁺ along x
    'Ω⁺ can translate along x'
    >>> free_motion_name([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], dim=3)   # the body, along y
    'the whole body can translate along y'
    """
    c = np.asarray(c, float)
    k = MOTIONS.get(dim)
    if k is not None and c.size == k:                        # the motions of the body
        return f"the whole body can {motion_name(c, dim)}"
    if c.size not in (6, 12) or (k is not None and c.size != 2 * k):
        return "a combination of the modes"                  # not the layout of rigid_modes
    minus, plus = c[0::2], c[1::2]
    dim = 2 if minus.size == 3 else 3
    size = max(np.abs(c).max(), 1e-300)
    if np.abs(plus).max() < 1e-6 * size:
        return f"Ω⁻ can {motion_name(minus, dim)}"
    if np.abs(minus).max() < 1e-6 * size:
        return f"Ω⁺ can {motion_name(plus, dim)}"
    if np.abs(minus - plus).max() < 1e-6 * size:
        return f"the whole body can {motion_name(minus, dim)}"
    return f"Ω⁻ can {motion_name(minus, dim)} as Ω⁺ {motion_name(plus, dim, verb=False)}"


def scaled_tie(K, B, fixed):
    """Jacobi-scaled K (imposed unknowns as identity rows, so nodal blocks stay
    whole) and B with unit rows: s, K_s = S K S, B_n = R B S, the row scales R."""
    diag = np.abs(K.diagonal())
    if np.any(diag[~fixed] == 0):
        raise SingularSystemError(
            f"{int(np.sum(diag[~fixed] == 0))} unknown(s) have no stiffness at all (a node "
            f"that no cell uses, or an enriched function with an empty support): remove "
            f"unused nodes from the mesh or impose those unknowns")
    s = np.where(fixed, 1.0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)))
    keep = sp.diags(np.where(fixed, 0.0, s))
    Ks = (keep @ K @ keep + sp.diags(fixed.astype(float))).tocsr()
    return (s, Ks, *scaled_rows(B, s, fixed))


def scaled_rows(B, s, fixed):
    """The rows of B in the scaling s of :func:`scaled_tie` (imposed columns dropped),
    each to unit length: B_n = R B S and the row scales R."""
    return unit_rows(B @ sp.diags(np.where(fixed, 0.0, s)))


def augmented(K, B, fixed, r: float):
    """:func:`scaled_tie` and the augmented K_r = K_s + r B_nᵀB_n: s, B_n, the row scales, K_r
    (K_s itself without rows, a crack with free faces: no copy of it)."""
    s, Ks, Bn, rows = scaled_tie(K, B, fixed)
    return s, Bn, rows, Ks if Bn.shape[0] == 0 else (Ks + r * (Bn.T @ Bn)).tocsr()


def check_tie_held(K, B, fixed, modes, r: float = 3.0, rigid_tol: float = 1e-11,
                   scaled=None):
    """Refuse a rigid motion of a side (of ``modes``) that neither the imposed
    unknowns (boolean ``fixed``) nor the rows of ``B`` hold: :func:`check_held`
    on the K_r of :func:`augmented`.  ``scaled``: (s, K_s) of :func:`scaled_tie`
    for this K and ``fixed``, if the caller has them (several checks of one K).

    >>> import scipy.sparse as sp, numpy as np
    >>> K = sp.csr_matrix([[1.0, -1.0], [-1.0, 1.0]]); Z = np.ones((2, 1))
    >>> check_tie_held(K, sp.csr_matrix([[1.0, 0.0]]), np.zeros(2, bool), Z)
    >>> check_tie_held(K, sp.csr_matrix((0, 2)), np.zeros(2, bool), Z)
    Traceback (most recent call last):
    ...
    skxfem.linalg.saddle.SingularSystemError: the system is singular (a combination of the ...
    """
    if scaled is None:
        s, _, _, Kr = augmented(K, B, fixed, r)
    else:
        s, Ks = scaled
        Bn = scaled_rows(B, s, fixed)[0]
        Kr = Ks + r * (Bn.T @ Bn)
    check_held(Kr, modes / s[:, None], rigid_tol)
