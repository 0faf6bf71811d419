"""A size guard: the unknowns and memory of a scene, estimated before it is assembled.

A triangle box with ``n = 10000`` asks for 10⁸ nodes; building it, let alone
solving it, takes many gigabytes.  :func:`estimate` counts, without building
the mesh, what a solve will meet, and :func:`check` refuses a scene whose
estimate exceeds a limit, naming the estimate and how to raise the limit; a
Box that needs more than the limit even without its interface is refused
from its cell counts alone, before ψ is evaluated.

The counts are upper bounds:

* nodes and cells: exact (from a :class:`~skxfem.scene.Box`'s cell counts, or
  from the mesh itself when the scene carries one or names a file, which is
  then read);
* enriched nodes: the corners of the cells on which ψ takes both signs (for a
  Box, of the grid's hypercubes, which contain its cells), so
  ``n_dofs ≤ dim × (nodes + enriched nodes)``;
* multipliers: ``ncomp`` per cut edge (``dim`` for a bonded tie, 1 for a
  bilateral one); for a Box every grid segment of the cell type's edge
  directions on which ψ changes sign counts (both diagonals of a face
  where the mesh has one).

With several interfaces (``Scene(interfaces=...)``) each is counted so, its
enriched nodes and its multipliers (with its own law) added to the others'.

A crack (an interface with a ``front``) is counted as its solve builds it
(:class:`~skxfem.studies.counts.CrackCounts`): its multipliers on its own cut points
behind the front (``ncomp`` each, none for the law ``free``), not on every edge the
whole surface ψ = 0 touches; 4 × dim branch unknowns on each node of the front's cells
or within r_e of the front, r_e as :mod:`skxfem.crack.radius` takes it (the interface's
``enrichment_radius``, or the default rule from the crack's depth and the front cells'
size, found from ψ and φ at the nodes as the space finds them; none beyond the front
cells for topological enrichment), dim Heaviside unknowns on the other nodes of the cells
it cuts; the dense interface terms only on the columns B reads (the jumping unknowns of
the cells it cuts, dim per node) and only where multipliers live.  On the cubes and
squares of the sweep below the unknowns are bounds within 7 % (most exact).  The LU fill
grows with the unknowns per node that a crack's zone adds (:data:`LU_FILL` times the
ratio of the unknowns per node to dim, to the power 2 - p; 1 for a tie); a crack adds
:data:`CRACK_NODE_BYTES` per branch node, and :data:`CRACK_LU` and :data:`COULOMB_LU`
where multipliers live on its faces.  ``auto`` resolves as the solve does: direct wherever
multipliers live on a crack's faces and for any crack in 2D; where a 3D crack's zone holds
more than :data:`~skxfem.linalg.choice.AUTO_ZONE` of the nodes the solve tries CG and
falls back to the direct solve, so the estimate is the larger of the two.

Measured (``scripts/calibrate_budget.py``, whose notes give the whole table; 29 November
2026; 96 cases), estimate over peak: contact and bonded cracks on tetrahedral cubes
n = 6-16 1.32-2.48 (the 10³ and 11³ cubes of ``skxfem run``'s frictionless edge crack:
2.02 GB for a 1.35 GB peak and 0.70 GB for 0.43 GB; before: 11.2 and 12.7 GB, refused at
the default limit); 2D cracks n = 21-82 (triangles, quadrilaterals; free, frictionless,
Coulomb, bonded) 1.32-2.76; free 3D cracks n = 6-20 1.35-2.85 where the solve took the
path priced, 4-7 where auto's CG try converged (the estimate prices the direct
fall-back: 1.56 and 1.79 times the direct solve's peak at n = 10 and 8).  Before:
0.37-0.85 for free 3D cracks (no bound) and 3-46 for the others.  Ties and fully cutting
interfaces are estimated as before.

ψ is evaluated at the nodes in slabs of about 10⁶ points, so the guard itself
stays small.  The memory depends on the linear solver that will run
(:func:`skxfem.linalg.choice.choose_linear`, for ties and contact alike).
*Direct*: the cells (mesh, basis values, the assembly of K), the sparse LU
of the saddle matrix (fill measured, :data:`LU_FILL`) and the dense interface
blocks of :mod:`skxfem.linalg.saddle` (``3 m ncols + 2 m² + 2 ncols²`` doubles).
*Iterative*: :data:`ITERATIVE_BYTES` (contact: :data:`CONTACT_ITERATIVE_BYTES`)
per unknown, displacement and multiplier, everything included. The constants
were calibrated against the peak resident memory of solves on this machine
(``scripts/calibrate_budget.py``); :data:`SAFETY` is the factor on top. The
estimate over the peak memory a direct solve added (one process per case, the
peak reset before the solve; before the lighter assembly of 24 November 2026,
which made it looser: prisms n = 8, 2.5 times):

``strip`` on triangles, n = 32-512 (9.6 MB ... 5.7 GB), 1.6-1.9 times; on
quadrilaterals, n = 64, 256, 1.4 times; ``paper_plate`` on prisms, n = 8-24
(78 MB ... 4.4 GB), 1.7-1.9 times; hexahedra 1.2-1.6 times; tetrahedra, n = 5,
9, 3.1 and 3.2 times; so the estimate is an upper bound within a factor 4 (the cut
edges of tetrahedra are over-counted most); ``tests/test_budget.py`` checks cases.

>>> from skxfem import scenes
>>> e = estimate(scenes.strip(8, cell="tri"))
>>> e.n_nodes, e.n_cells
(90, 144)
>>> check(scenes.strip(2000, cell="tri"), 2**30)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
skxfem.studies.budget.TooLargeError: the scene 'strip...' needs at least ... GB ...
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from ..contact.laws import CONTACT_LAWS
from ..crack.radius import DEPTH_CAP, default_radius
from ..fem.meshes import CELLS, cell_name
from ..fem.quadrature import cell_rule
from ..linalg.choice import choose_linear
from ..linalg.scalars import is_integer
from ..scene.model import Box, Resolved, Scene, check_scene, resolve
from .counts import (
    NVERTS,
    box_counts,
    box_crack_counts,
    box_size,
    mesh_counts,
    mesh_crack_counts,
)

__all__ = ["DEFAULT_MAX_BYTES", "Estimate", "TooLargeError", "check", "estimate",
           "parse_bytes", "format_bytes", "format_count"]

DEFAULT_MAX_BYTES = 4 * 2**30
"""The limit :func:`check` applies unless told otherwise: 4 GiB."""


LU_FILL = {2: (15.5, 1.27), 3: (5.3, 1.6)}
"""Non-zeros of L + U of the saddle matrix of size N: ``c N^p`` per dimension
(SuperLU with COLAMD, as :mod:`skxfem.linalg.saddle` calls it; fitted above the measured
fill of 2D strips with N = 2 440 to 530 440 and 3D plates with N = 862 to 52 852;
the measured exponent falls with N, from 1.67 to 1.52 between the 3D sizes)."""
LU_BYTES = 24
"""Peak bytes of SuperLU per non-zero of L + U (values, indices, growth)."""
PER_CELL = 2.0
"""Bytes per cell and per (quadrature point × basis function × derivative)."""
SAFETY = 1.2  # the factor on the sum of the terms
ITERATIVE_BYTES = {2: 2200, 3: 8200}
"""Peak bytes per unknown (N + m) of an iterative tie, assembly included, the largest
measured on 25 November 2026: strip (tri n = 128-512, quad 256) 1881-2160, paper
plate (hex, prism, n = 12-32) 6871-8161; at the minimal exact quadrature."""
KRYLOV_BYTES = 2 * 41 * 8
"""Coulomb's iterative step adds the basis of its projected GMRES
(:func:`skxfem.linalg.pcg.projected_gmres`: 41 + 40 vectors of the unknowns'
length, by the algorithm, not measured)."""
CONTACT_ITERATIVE_BYTES = {2: 3100, 3: 10900}
"""The same for contact (its interface operators and the hierarchy carried over
to each Newton step besides): ``press`` in ``scripts/calibrate_budget.py``, tri
128, quad 256: 2915-3054; hex 12, 24: 9552-10841.  With :data:`KRYLOV_BYTES`
and :data:`SAFETY`, the slipping block (Coulomb, hex n = 42, 259 290 unknowns)
is estimated at 3.7 GB for a measured peak of 2.95 GB (27 November 2026)."""


CRACK_NODE_BYTES = {2: 100 * 2**10, 3: 250 * 2**10}
"""Peak bytes per branch node of a crack besides the linear solve (its enriched cells'
sub-cell rules, branch values and COO assembly, 4 dim unknowns per node): above the
largest measured in ``scripts/calibrate_budget.py``'s crack sweep (module notes), 2D
23-105 KB, 3D 48-241 KB, the contact laws the most."""
CRACK_LU = {2: 2.5, 3: 1.3}
"""The factor on :data:`LU_FILL` where multipliers live on a crack's faces: in 2D the
contact step's LU filled 1.5-2.3 times the model (the two tips' zones: the inclined and
centre cracks), in 3D up to 1.39 times (n = 12-16; 1.0 at n = 6); Coulomb's in 2D once
more (:data:`COULOMB_LU`)."""
COULOMB_LU = {2: 2.0, 3: 1.0}
"""Coulomb on a 2D crack's faces held about two factorisations at its peak (the
inclined crack, n = 21-81: the peak less one LU was 1.0-1.25 LU)."""


@dataclass(frozen=True)
class Estimate:
    """Upper bounds of what solving a scene meets.

    ``n_nodes``, ``n_cells``: the mesh; ``n_dofs``: unknowns (standard and
    enriched); ``n_multipliers``: interface unknowns; ``bytes``: peak memory
    of the ``linear`` solve (``"direct"`` or ``"iterative"``).
    """

    n_nodes: int
    n_cells: int
    n_dofs: int
    n_multipliers: int
    bytes: int
    linear: str = "direct"

    def __str__(self) -> str:
        return (f"{format_count(self.n_nodes)} nodes, {format_count(self.n_cells)} cells, "
                f"up to {format_count(self.n_dofs)} unknowns and "
                f"{format_count(self.n_multipliers)} multipliers, {self.linear} solve")


class TooLargeError(ValueError):
    """A scene whose estimated memory exceeds the limit given to :func:`check`."""


def format_bytes(n: float) -> str:
    """``n`` bytes in GB, MB or KB (powers of 1024), for messages.

    >>> format_bytes(3 * 2**30), format_bytes(5.5 * 2**20), format_bytes(1000)
    ('3 GB', '5.5 MB', '0.977 KB')
    >>> format_bytes(2**40 * 10**40)
    '1e+40 TB'
    """
    for unit, size in (("TB", 2**40), ("GB", 2**30), ("MB", 2**20), ("KB", 2**10)):
        if n >= size or unit == "KB":
            v = float(min(n, 10**300)) / size
            return f"{v:.0f} {unit}" if 100 <= v < 1e6 else f"{v:.3g} {unit}"


def format_count(k: int) -> str:
    """An exact count, written with an exponent above 10¹²: the absurd sizes a user may
    give (``n = 9223372036854775807``) stay readable.

    >>> format_count(123456), format_count(2**64), format_count(10**400)
    ('123456', '1.84e+19', '1.00e+400')
    """
    if k < 10**12:
        return str(k)
    digits = str(k)
    return f"{digits[0]}.{digits[1:3]}e+{len(digits) - 1}"


def parse_bytes(text: str) -> int:
    """A size such as ``"4G"``, ``"500M"``, ``"2.5GB"`` or ``"1000000"`` in bytes.

    >>> parse_bytes("4G"), parse_bytes("500MB"), parse_bytes("1024")
    (4294967296, 524288000, 1024)

    A size below one byte (``"0.5"``) is refused: a number without a unit is in bytes.
    """
    s = str(text).strip().upper().removesuffix("B")
    scale = {"K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40}.get(s[-1:], 1)
    try:
        value = float(s[:-1] if scale > 1 else s)
    except ValueError:
        value = float("nan")
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"a memory size must be a positive number with an optional unit "
                         f"K, M, G or T (e.g. 8G), got {text!r}")
    if value * scale < 1:
        raise ValueError(f"a memory size must be at least one byte, got {text!r} (a number "
                         f"without a unit is in bytes; e.g. 8G is 8 gigabytes)")
    return int(value * scale)


def _memory(dim: int, cell: str, order, n_nodes, n_cells, n_dofs, ncols, m,
            lu_factor: float = 1.0, per_node: float = 1.0) -> float:
    """Bytes of the terms named in the module notes (before :data:`SAFETY`);
    ``per_node``: the unknowns per node over dim, where a crack's zone raises them."""
    nq = cell_rule(CELLS[cell], order)[1].size
    nbf = dim * NVERTS[cell]
    cells = n_cells * (PER_CELL * 8 * nq * nbf * (1 + dim + dim * dim)  # basis values
                       + 3 * 8 * nbf * nbf                                 # COO assembly
                       + 8 * NVERTS[cell])                                # t
    nodes = n_nodes * 8 * dim * 4
    c, p = LU_FILL[dim]
    lu = LU_BYTES * c * (n_dofs + m) ** p * per_node ** (2 - p) * lu_factor
    dense = 8 * (3 * m * ncols + 2 * m * m + 2 * ncols * ncols)
    return cells + nodes + lu + dense


def _clip(count: int) -> float:
    """A count as a float, at most 10¹⁰⁰ (beyond any memory): the counts are exact
    integers, and the memory terms stay finite floats for the absurd ones."""
    return float(min(count, 10**100))


def estimate(scene: Scene, linear: str | None = None) -> Estimate:
    """Upper bounds of the nodes, cells, unknowns, multipliers and memory of a solve.

    A Box is never built: ψ is evaluated on its grid in slabs.  A mesh file
    is read (as the solve would).

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene`.
    linear
        The linear solver of ``skxfem.solve(scene, linear=...)``: ``"auto"``
        resolves as the solve does (every law alike);
        ``None``: the scene's, ``scene.solver.linear``.

    Returns
    -------
    Estimate
    """
    mesh = None
    if isinstance(scene, Resolved):   # its mesh built or read already
        scene, mesh = scene
    items = check_scene(scene).interfaces
    linear = scene.solver.linear if linear is None else linear
    if mesh is None and isinstance(scene.mesh, Box):
        box = scene.mesh
        size = box.size or (1.0,) * box.dim
        D = np.linalg.norm(size)
        dim, cell = box.dim, box.cell
        count, crack = partial(box_counts, box), partial(box_crack_counts, box)
    else:
        mesh = resolve(scene).mesh if mesh is None else mesh
        D = np.linalg.norm(np.ptp(mesh.p, axis=1))
        dim, cell = mesh.dim(), cell_name(mesh)
        count, crack = partial(mesh_counts, mesh), partial(mesh_crack_counts, mesh)
    counts, cracks = [], []
    for i in items:                      # a crack: ψ and φ evaluated once
        if i.front is None:
            counts.append(count(i.levelset))
            cracks.append(None)
        else:
            cracks.append(crack(i.levelset, i.front, partial(_branch_radius, i, dim, D)))
            counts.append((cracks[-1].nodes, cracks[-1].cells))
    return _estimate(scene, linear, *counts[0][:2],
                     [0 if k is not None else c[2] for c, k in zip(counts, cracks)],
                     [0 if k is not None else c[3] for c, k in zip(counts, cracks)], cell,
                     cracks)


def _branch_radius(interface, dim: int, diameter: float, depth: float, h: float
                   ) -> float | None:
    """r_e of a crack as its space takes it (:mod:`skxfem.crack.radius`): None when
    topological, else the interface's ``enrichment_radius`` or
    :func:`skxfem.crack.radius.default_radius` of the mesh's ``diameter`` (2D, at most
    :data:`~skxfem.crack.radius.DEPTH_CAP` depths) or the crack's ``depth`` (3D) and the
    front cells' size ``h`` (in 2D ``depth`` + ``h`` bounds the crack's depth, which its
    pieces' ends measure, between the nodes: so r_e bounds the space's)."""
    if interface.enrichment == "topological":
        return None
    r = interface.enrichment_radius
    if r is not None:
        return r
    if dim == 2:
        return default_radius(2, float(diameter), float(h),
                              DEPTH_CAP * (float(depth) + float(h)))
    return default_radius(3, float(depth), float(h))


def _estimate(scene, linear, n_nodes, n_cells, n_enr_nodes, n_edges, cell,
              cracks=None) -> Estimate:
    """The :class:`Estimate` of ``scene`` from its counts, one per interface: enriched
    nodes and cut edges, or for a crack its
    :class:`~skxfem.studies.counts.CrackCounts` (``cracks``, None for the others)."""
    dim = scene.dim
    items = scene.interfaces
    cracks = [None] * len(items) if cracks is None else cracks
    enr, sites, cols = [], [], []            # per interface: unknowns, points, B's columns
    for e, k, c in zip(n_enr_nodes, n_edges, cracks, strict=True):
        if c is None:
            enr.append(dim * e)
            sites.append(k)
            cols.append(dim * e)
        else:
            enr.append(dim * c.heaviside + 4 * dim * c.branch)
            sites.append(c.points)
            cols.append(dim * c.crack_nodes)
    n_enr = sum(enr)
    n_dofs = dim * n_nodes + n_enr
    ncomp = [0 if i.law == "free" else 1 if i.law == "bilateral" else dim for i in items]
    m = sum(k * p for k, p in zip(ncomp, sites))          # contact: λ_n and friction
    ncols = sum(c for k, c in zip(ncomp, cols) if k)      # B's columns: where it has rows
    laws = ["frictionless" if i.law == "coulomb" and i.friction == 0 else i.law
            for i in items]
    law = ("coulomb" if "coulomb" in laws else
           next((x for x in laws if x in CONTACT_LAWS), laws[0]))
    on_crack = any(i.front is not None and i.law != "free" for i in items)
    crack = any(i.front is not None for i in items)
    zone = max((c.branch / c.nodes for c in cracks if c is not None), default=0.0)
    chosen = choose_linear(linear, dim, n_dofs, on_crack, crack, zone)
    # a zone over AUTO_ZONE: auto tries CG first, then the direct solve (solve_problem)
    tried = chosen == "direct" and choose_linear(linear, dim, n_dofs, on_crack,
                                                 crack) == "iterative"
    branch = CRACK_NODE_BYTES[dim] * sum(c.branch for c in cracks if c is not None)
    bytes_ = 0.0
    if chosen == "iterative" or tried:
        per = (CONTACT_ITERATIVE_BYTES if law in CONTACT_LAWS else ITERATIVE_BYTES)[dim]
        per += KRYLOV_BYTES if law == "coulomb" else 0
        bytes_ = SAFETY * (per * _clip(n_dofs + m) + branch)
    if chosen == "direct":
        factor = (CRACK_LU[dim] * (COULOMB_LU[dim] if law == "coulomb" else 1.0)
                  if on_crack else 1.0)
        zoned = sum(e for e, c in zip(enr, cracks) if c is not None)
        bytes_ = max(bytes_, SAFETY * (_memory(
            dim, cell, scene.quadrature_order,
            *map(_clip, (n_nodes, n_cells, n_dofs, ncols, m)), factor,
            1.0 + zoned / (dim * n_nodes)) + branch))
    return Estimate(n_nodes, n_cells, n_dofs, m, int(bytes_), chosen)


def _floor(scene, linear) -> Estimate | None:
    """For a Box, the estimate without interface (no enrichment, no multiplier): a
    lower bound of :func:`estimate` known without evaluating ψ (the least over the
    solvers ``"auto"`` may pick); ``None`` for a mesh."""
    box = scene.mesh
    if not isinstance(box, Box):
        return None
    none = [0] * len(scene.interfaces)
    counts = (*box_size(box), none, none, box.cell)
    floors = []
    for pick in ("direct", "iterative") if linear == "auto" else (linear,):
        try:
            floors.append(_estimate(scene, pick, *counts))
        except (ValueError, ImportError):  # a solver this law (or this install) has not
            if linear != "auto":
                raise
    return min(floors, key=lambda e: e.bytes)


def check(scene: Scene, max_bytes: int = DEFAULT_MAX_BYTES,
          option: str | None = None, linear: str | None = None) -> Estimate:
    """:func:`estimate`, refusing a scene above ``max_bytes``.

    Parameters
    ----------
    scene
        The scene.
    max_bytes
        The limit in bytes.
    option
        The command-line option that raises the limit, named in the message
        (``skxfem run`` passes ``"--max-memory"``); by default the message
        names ``max_bytes=``.
    linear
        As for :func:`estimate`.

    Returns
    -------
    Estimate
        The estimate of an accepted scene.

    Raises
    ------
    TooLargeError
        (a ValueError) If the estimate exceeds ``max_bytes``.
    """
    if not (is_integer(max_bytes) and max_bytes > 0):
        raise ValueError(f"max_bytes must be a positive integer, got {max_bytes!r}")
    given = scene   # a Resolved scene's estimate reads its mesh
    scene = given.scene if isinstance(given, Resolved) else check_scene(given)
    linear = scene.solver.linear if linear is None else linear
    floor = _floor(scene, linear)
    if floor is not None and floor.bytes > max_bytes:  # refused before ψ is evaluated
        raise _too_large(scene, floor, max_bytes, option, "at least", linear)
    e = estimate(given, linear)
    if e.bytes > max_bytes:
        raise _too_large(scene, e, max_bytes, option, "about", linear)
    return e


def _too_large(scene, e: Estimate, max_bytes: int, option, how: str, linear: str
               ) -> TooLargeError:
    """The refusal of ``scene``, whose (lower bound, ``how``) estimate ``e`` is too large."""
    more = 2 * e.bytes
    hint = (f"max_bytes={more}" if option is None
            else f"{option} {format_bytes(more).replace(' ', '')}")
    solve = "either solve" if linear == "auto" else f"{e.linear} solve"
    what = str(e) if how == "about" else (
        f"{format_count(e.n_nodes)} nodes, {format_count(e.n_cells)} cells, "
        f"{format_count(e.n_dofs)} unknowns before any enrichment, {solve}")
    return TooLargeError(
        f"the scene {scene.name!r} needs {how} {format_bytes(e.bytes)} ({what}); the limit "
        f"is {format_bytes(max_bytes)}: use a coarser mesh, or raise the limit (e.g. {hint})")
