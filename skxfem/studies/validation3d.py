r"""The genuinely 3D validation: the block of :mod:`skxfem.fem.exact3d`, errors against h.

The paper's plate, with rollers on x = 0, 1 and a load that does not depend
on x, is a plane-strain problem: its prisms give the triangles' numbers and
its hexahedra the quadrilaterals'.  Here the answer varies in x, y and z:
:func:`skxfem.scenes.exact_block`, the unit cube cut by a plane Γ slanted
against all three axes, under the loads of Love's exact solution
(:class:`skxfem.fem.exact3d.ExactBlock`).  :func:`study_block` solves it on
hexahedra, prisms and tetrahedra with every multiplier space and measures,
per mesh, with :mod:`skxfem.studies.convergence`:

* W(u_h), the relative energy error (expected rate 1);
* L(λ_h), the relative L²(Γ) error of the contact pressure (expected rate 1
  for the stable spaces, as in the paper's Figure 10);
* the largest pressure error at the multiplier points, relative to max |p|:
  where the naive space oscillates.

A mesh the solver refuses is kept as a :class:`Failure` with the solver's
message, not dropped: the naive space on tetrahedra has hundreds of dependent
multipliers, and where Γ passes close to a node the remaining ones are nearly
dependent (:class:`skxfem.linalg.saddle.NearlyDependentError`).  Its removal of the
dependent multipliers (a rank-revealing step) took more than 15 minutes at
n = 16 on 2 cores, so the naive space on tetrahedra is run up to
:data:`NAIVE_TET_MAX_N` only.

>>> block = study_block([3], cells=("hex",), spaces=("vital",))
>>> row = block.rows["hex"][0]
>>> row.n, row.space, row.energy < 0.25, block.failures
(3, 'vital', True, ())
"""
from __future__ import annotations

from dataclasses import dataclass

from ..fem.exact3d import GAMMA_NORMAL, GAMMA_POINT, ExactBlock
from ..linalg.saddle import NearlyDependentError
from ..multipliers import SPACES
from ..scene.benchmarks import P_MAX, exact_block
from .convergence import observed_rates, study, summary_columns
from .progress import Progress

__all__ = ["CELLS", "EXPECTED_RATES", "NAIVE_TET_MAX_N", "Failure", "BlockStudy",
           "study_block", "summary", "last_rates"]

CELLS = ("hex", "prism", "tet")
"""The 3D cells of the study."""

EXPECTED_RATES = {"energy": 1.0, "pressure_l2": 1.0}
"""The rates a stable space should reach: W(u_h) ~ h for linear elements, and
L(λ_h) ~ h (measured between 1 and 1.5 in 2D, as the paper's Figure 10)."""

NAIVE_TET_MAX_N = 8
"""The finest mesh the naive space on tetrahedra is solved on (see above)."""


@dataclass(frozen=True)
class Failure:
    """A mesh of the study with no result: ``reason``, the solver's message."""

    cell: str
    space: str
    n: int
    reason: str


@dataclass(frozen=True)
class BlockStudy:
    """What :func:`study_block` returns.

    ``rows`` per cell, the :class:`~skxfem.studies.convergence.StudyRow` of each solved
    (space, n), in the order solved; ``failures`` the meshes with no result.
    """

    rows: dict
    failures: tuple


def study_block(ns, cells=CELLS, spaces=SPACES, progress: Progress | None = None
                ) -> BlockStudy:
    """Solve :func:`~skxfem.scenes.exact_block` for every cell, space and n.

    Parameters
    ----------
    ns
        Cells per side of the cube (h = 1/n).
    cells, spaces
        Subsets of :data:`CELLS` and :data:`skxfem.multipliers.SPACES`.
    progress
        One line per mesh (default: a :class:`~skxfem.studies.progress.Progress`, on
        in a terminal only).
    """
    ns = [int(n) for n in ns]
    unknown = [c for c in cells if c not in CELLS] + [s for s in spaces if s not in SPACES]
    if unknown:
        raise ValueError(f"study_block: unknown cells or spaces {unknown}; cells are {CELLS}, "
                         f"spaces {SPACES}")
    exact = ExactBlock(exact_block(1).material, P_MAX)
    progress = progress or Progress(len(cells) * len(spaces) * len(ns), "block")
    quiet = Progress(0, "block", enabled=False)
    rows, failures = {cell: [] for cell in cells}, []
    for cell in cells:
        for space in spaces:
            for n in ns:
                if cell == "tet" and space == "naive" and n > NAIVE_TET_MAX_N:
                    failures.append(Failure(cell, space, n, f"not run: the removal of the "
                                            f"naive space's dependent multipliers on "
                                            f"tetrahedra is too slow beyond n = "
                                            f"{NAIVE_TET_MAX_N}"))
                    continue
                try:
                    rows[cell] += study(lambda k, s, c=cell: exact_block(k, c, space=s), [n],
                                        [space], exact=exact, with_inf_sup=False,
                                        progress=quiet)
                except NearlyDependentError as e:
                    failures.append(Failure(cell, space, n, str(e)))
                progress.step(f"block {cell} {space} n={n}")
    return BlockStudy(rows, tuple(failures))


def summary(block: BlockStudy) -> dict:
    """The numbers of a :class:`BlockStudy`, as ``summary.json`` stores them.

    Per cell and space: ``n``, ``h``, ``energy``, ``pressure_l2`` (with their
    observed rates between successive solved meshes), ``pressure_max``,
    ``n_dofs``, ``n_multipliers``, ``seconds_solve``; then ``failures``.

    >>> s = summary(study_block([3, 4], cells=("prism",), spaces=("vital",)))
    >>> len(s["studies"]["prism"]["vital"]["energy_rates"])
    1
    """
    studies = {}
    for cell, rows in block.rows.items():
        studies[cell] = {}
        for space in [s for s in SPACES if any(r.space == s for r in rows)]:
            studies[cell][space] = summary_columns([r for r in rows if r.space == space])
    return {
        "scene": "exact_block(n, cell): unit cube, n cells per side",
        "reference": "exact: skxfem.fem.exact3d.ExactBlock (Love's solution), pressure "
                     "p = -n·σ·n on Γ",
        "gamma": {"point": list(GAMMA_POINT), "normal": list(GAMMA_NORMAL)},
        "expected_rates": dict(EXPECTED_RATES),
        "studies": studies,
        "failures": [{"cell": f.cell, "space": f.space, "n": f.n, "reason": f.reason}
                     for f in block.failures],
    }


def last_rates(block: BlockStudy) -> dict:
    """``{(cell, space): (energy rate, pressure rate)}`` of the two finest solved meshes.

    >>> rates = last_rates(study_block([2, 4], cells=("hex",), spaces=("vital",)))
    >>> [bool(r > 0.8) for r in rates["hex", "vital"]]     # energy, pressure: about h
    [True, True]
    """
    out = {}
    for cell, rows in block.rows.items():
        for space in SPACES:
            mine = [r for r in rows if r.space == space]
            if len(mine) > 1:
                h = [r.h for r in mine[-2:]]
                out[cell, space] = tuple(float(observed_rates(h, [getattr(r, k) for r in
                                                                  mine[-2:]])[0])
                                         for k in ("energy", "pressure_l2"))
    return out

