r"""The enrichment of a crack's space and the radius r_e: one rule for 2D and 3D cracks.

A crack's space (:mod:`skxfem.crack.space`, :mod:`skxfem.crack.space3d`) gives the
branch functions to the nodes of the front's cells (``"topological"``, the
:data:`ENRICHMENTS`) or also to every node within r_e of the front (``"geometric"``);
:func:`enrichment_radius` checks that choice and r_e for both.  Without a radius given,
both take

.. math::

    r_e = \max\left(f\, L,\; \frac{n_d\, h}{0.75}\right)\quad
    \bigl(\text{2D: } f L \text{ at most } 3a\bigr),

L a length of the problem (the mesh's diameter D in 2D, the crack's depth a in 3D: the
largest distance from a point of the crack to its front,
:func:`skxfem.crack.space3d.crack_depth`), h the size of the front's cells and n_d h the
radius of the default interaction domain when it does not follow r_e
(:func:`skxfem.crack.sif.default_radius` in 2D, :func:`skxfem.crack.sif3d.sif_3d` in
3D): the first term is a fixed radius, as
geometric enrichment must have for its rate as h → 0; the second keeps the default
domain inside 0.75 r_e, the enriched zone, on coarse meshes (a domain that reaches
beyond r_e loses accuracy: +1.0 % in K on the Williams square at h = 1/21, +3.1 % along
a straight 3D front at h = 1/11).  The dimension enters through L and two numbers:

* ``SIZE_FRACTION`` f: 0.2 of D in 2D, 0.2 of a in 3D.  The enriched zone is an area
  ~ r_e² in 2D but a tube ~ r_e² × the front's length in 3D, twelve unknowns for each of
  its nodes.  A fraction of the body's size in 3D measured the zone on the wrong length:
  0.1 D enriched 27 % of the benchmark cube's unknowns at every n and kept the crack
  above 3 times the bonded tie, and two crack radii around a penny in a block 20 radii
  across (CG did not converge at h = 0.1 a); 0.2 D took the penny (h = 0.2 a, its block
  9.8 a across) from 6.1 s to 20 s for the same K.  The singular field's zone scales
  with the crack (the K-dominated zone is a fraction of a), hence a in 3D (the cube's
  edge crack: 0.1; a penny: 0.2 a, the study's 0.3 a within 0.2 %, below), whereas 2D
  keeps D, measured on its plates (0.2 D: K_I -0.36 %; 16/3 cells: -1.15 %), but at
  most ``DEPTH_CAP`` = 3 crack depths a (:func:`skxfem.crack.space.crack_depth`): a
  fifth of the body around a short crack is many times its length.  A centre crack of
  half-length 0.05 in the unit square under tension (29 November, one run each):
  K_I/σ√(πa) 1.0095, 1.0096, 1.0095 at n = 41, 81, 161 with 0.2 D = 0.28 (7 672,
  29 624, 116 280 unknowns; 0.8, 3.4, 21.8 s), 1.0089, 1.0096, 1.0095 with 3 a (4 568,
  18 056, 71 960; 0.17, 0.52, 2.7 s); with 2 a 1.0078, -, 1.0094 and with 1.33 a
  (the tip's room over 0.75) 1.0033, 1.0087, 1.0092.  The plates, the Williams square
  and the closed inclined crack have 3 a above 0.2 D: their r_e is as before;
* ``DOMAIN_CELLS`` n_d: the default domain in cells, 4 tip-cell sizes in 2D
  (:data:`skxfem.crack.sif.DEFAULT_CELLS`), 3 front-cell sizes across the front in 3D
  (:data:`skxfem.crack.sif3d.DEFAULT_RADIUS`), so r_e ≥ 16/3 h and 4 h.  The floor is what makes
  a coarse 3D answer trustworthy, at a price: on the cube of ``benchmarks/crack_solve.py``
  (edge crack to the middle, n × n × n tetrahedral cells) K_I at mid-front was 3.66, 3.62,
  3.63, 3.67 at n = 8, 12, 16, 20 with it, and 3.32, 3.45 at n = 8, 12 without it
  (r_e = 0.1 D alone), while the crack took 3.8 s against 0.6 s at n = 8 (one run).

The 3D trade, measured (``benchmarks/crack_radius3d.py``, whose notes give the table;
29 November): n_d = 3 and 0.75 are the least that hold a straight front's K to 1 %
(a domain of 2 or 2.5 cells: 4.6 to 5.6 % or 1.5 to 2.2 % at every n; at 0.85 r_e or
r_e: 5.5 % at n = 11).  The fixed part was 0.1 D until 29 November: above the floor from
about 23 cells across the benchmark cube, it kept 27 % of its unknowns enriched at every
n, and on a penny in a block 20 radii across it enriched two radii around the front (CG
did not converge at h = 0.1 a).  With 0.2 a (the cube's edge crack: a = 0.5, r_e = 0.1,
the floor up to n ≈ 40), one run each on the shared machine, ``benchmarks/crack_solve.py
--linear auto``: crack 14.6 -> 11.0 s at n = 32 and 29.4 -> 17.4 s at n = 40 (152 856 ->
138 006 and 291 018 -> 246 246 unknowns; ratio to the bonded tie 6.0 -> 4.6 and 5.6 ->
3.7), K_I at mid-front 3.7361 -> 3.7299 and 3.7596 -> 3.7467 (its limit about 3.81);
the straight front (the Williams slab, n = 11, 21, 31) within 0.86, 0.45, 0.68 %; the
penny with its own default r_e median 0.994 / 0.9945, worst 1.024 / 0.993 at h = 0.2 a
/ 0.1 a.

>>> from skfem import MeshTri1
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 22), np.linspace(0, 1, 22))
>>> round(default_enrichment_radius(m, 1 / 21), 4), round(default_enrichment_radius(m, 0.1), 4)
(0.2828, 0.5333)
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["ENRICHMENTS", "SIZE_FRACTION", "DEPTH_CAP", "DOMAIN_CELLS", "DOMAIN_FRACTION",
           "default_radius", "default_enrichment_radius", "enrichment_radius",
           "check_radius", "geometric_nodes"]

ENRICHMENTS = ("topological", "geometric")
"""The enrichments of a crack's space: the front cells' nodes, or also those within r_e."""

SIZE_FRACTION = {2: 0.2, 3: 0.2}
"""f: the fixed part of the default r_e, in lengths L of the problem: the mesh's diameter
in 2D, the crack's depth in 3D (module notes)."""

DEPTH_CAP = 3.0
"""In 2D, the fixed part of the default r_e is at most this many crack depths (module
notes): a fifth of the mesh's diameter is the plates' radius, not a short crack's."""

DOMAIN_CELLS = {2: 4.0, 3: 3.0}
"""n_d: the default interaction domain's radius in front-cell sizes (module notes)."""

DOMAIN_FRACTION = 0.75
"""With geometric enrichment, the default interaction domain (2D: r_d,
:func:`skxfem.crack.sif.default_radius`) is this fraction of r_e: it lies inside the
enriched zone, where u_h holds the branch functions.  Measured on the Williams square at
h = 1/21 (triangles, mode I): r_e = 0.141 with a 4-cell domain (r_d = 0.19 > r_e) gave K
+1.0 %; r_e = 0.283, r_d = 0.75 r_e +0.24 %."""


def default_radius(dim: int, length: float, h: float, cap: float = np.inf) -> float:
    """The default r_e = max(min(f L, ``cap``), n_d h / 0.75) in ``dim`` D (module notes),
    L the problem's ``length`` (the mesh's diameter in 2D, the crack's depth in 3D), ``h``
    the size of the front's cells and ``cap`` a bound of the fixed part (2D:
    :data:`DEPTH_CAP` crack depths).

    >>> round(default_radius(3, 0.5, 1 / 16), 4), round(default_radius(3, 0.5, 1 / 48), 4)
    (0.25, 0.1)
    >>> round(default_radius(2, 2 ** 0.5, 1 / 161), 4)      # a short crack: f D ...
    0.2828
    >>> round(default_radius(2, 2 ** 0.5, 1 / 161, cap=3 * 0.05), 4)   # ... or 3 depths
    0.15
    """
    if dim not in SIZE_FRACTION:
        raise ValueError(f"mesh must be 2D or 3D, got {dim}D")
    if not (np.isfinite(h) and h > 0):
        raise ValueError(f"h must be a positive cell size, got {h!r}")
    return max(min(SIZE_FRACTION[dim] * length, cap),
               DOMAIN_CELLS[dim] * float(h) / DOMAIN_FRACTION)


def default_enrichment_radius(mesh, h: float, depth: float | None = None) -> float:
    """:func:`default_radius` on ``mesh``, ``h`` the size of the front's cells: in 2D the
    largest extent of a tip cell, in 3D their mean size across the front
    (:func:`skxfem.crack.sif3d.front_sizes`); ``depth`` the crack's depth
    (:func:`skxfem.crack.space3d.crack_depth`, :func:`skxfem.crack.space.crack_depth`):
    L in 3D, in 2D the cap :data:`DEPTH_CAP` depths (None: no cap)."""
    ok = depth is not None and np.isfinite(depth) and depth > 0
    if mesh.dim() == 3:
        if not ok:
            raise ValueError(f"depth must be the 3D crack's depth (> 0), got {depth!r}")
        return default_radius(3, float(depth), h)
    return default_radius(mesh.dim(), float(np.linalg.norm(np.ptp(mesh.p, axis=1))), h,
                          DEPTH_CAP * float(depth) if ok else np.inf)


def enrichment_radius(mesh, enrichment: str, radius: float | None,
                      front_size: Callable[[], float],
                      depth: Callable[[], float] | None = None) -> float | None:
    """r_e of a crack's space on ``mesh``: ``None`` for ``"topological"`` enrichment,
    ``radius`` (checked: a positive number) or, if ``None``,
    :func:`default_enrichment_radius` of ``front_size()`` and ``depth()`` for
    ``"geometric"``.

    ``front_size`` and ``depth`` are called only for that default: the front cells' size h
    and the crack's depth.  The nodes within r_e: :func:`geometric_nodes`.

    >>> from skfem import MeshTri1
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 22), np.linspace(0, 1, 22))
    >>> enrichment_radius(m, "topological", 0.3, lambda: 1 / 21) is None
    True
    >>> enrichment_radius(m, "geometric", 0.3, lambda: 1 / 21)
    0.3
    >>> round(enrichment_radius(m, "geometric", None, lambda: 0.1), 4)
    0.5333
    """
    if enrichment not in ENRICHMENTS:
        raise ValueError(f"enrichment must be one of {ENRICHMENTS}, got {enrichment!r}")
    if enrichment == "topological":
        return None
    if radius is None:
        radius = default_enrichment_radius(mesh, front_size(),
                                           None if depth is None else depth())
    if not (isinstance(radius, (int, float, np.floating)) and np.isfinite(radius)
            and radius > 0):
        raise ValueError(f"radius must be a positive number, got {radius!r}")
    return radius


def geometric_nodes(front_nodes: np.ndarray, distance: np.ndarray, radius: float | None,
                    given: bool = False) -> np.ndarray:
    """The nodes that get the branch functions: ``front_nodes`` (those of the front's
    cells, every enrichment's) and, with a ``radius`` r_e (geometric), every node within r_e
    of the front, ``distance`` (N,) each node's distance to it.

    A radius the user ``given`` that reaches no node beyond the front cells' is refused:
    it gave topological enrichment (rate h^½) under the name geometric, silently.  The
    message names enrichment_radius, the nearest such node's distance (about a cell) and
    the cure.

    >>> geometric_nodes(np.array([0, 1]), np.array([0.1, 0.1, 0.2, 0.5]), 0.3).tolist()
    [0, 1, 2]
    >>> geometric_nodes(np.array([0, 1]), np.array([0.1, 0.1, 0.2, 0.5]), 0.15, given=True)
    Traceback (most recent call last):
    ...
    ValueError: enrichment_radius 0.15 reaches no node beyond the front cells' (the nearest ...
    """
    if radius is None:
        return np.unique(front_nodes)
    near = np.flatnonzero(distance <= radius)
    beyond = np.setdiff1d(near, front_nodes)
    if given and beyond.size == 0:
        others = np.setdiff1d(np.arange(distance.size), front_nodes)
        nearest = float(distance[others].min()) if others.size else np.inf
        raise ValueError(
            f"enrichment_radius {radius:.3g} reaches no node beyond the front cells' (the "
            f"nearest is {nearest:.3g} from the front, about a cell): geometric enrichment "
            f"within it is topological enrichment; take enrichment_radius above "
            f"{nearest:.3g} (None: the default, several cells), or ask for "
            f"enrichment='topological'")
    return np.union1d(front_nodes, near)


def check_radius(radius: float, h: float, name: str = "radius", dim: int = 3) -> None:
    """Refuse an interaction domain ``radius`` under the size ``h`` of the front's cells
    (2D: the tip cell's extent; 3D: the front cells' size across the front,
    :func:`skxfem.crack.sif3d.front_sizes`): the domain would hold no cell (K came out
    NaN in 3D, numpy's 'need at least one array to concatenate' in 2D).

    >>> check_radius(0.3, 0.1)
    >>> check_radius(0.01, 0.1)
    Traceback (most recent call last):
    ...
    ValueError: radius 0.01 is under the front cells' size 0.1: the interaction domain ...
    """
    if radius < h * (1 - 1e-9):                          # h to round-off: accepted
        raise ValueError(f"{name} {radius:.3g} is under the front cells' size {h:.3g}: the "
                         f"interaction domain would hold no cell; take it at least "
                         f"{h:.3g} (the default: {DOMAIN_CELLS[dim]:g} cells)")
