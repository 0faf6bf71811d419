r"""Reproduce the paper's figures and numbers: ``python -m skxfem.app.reproduce``.

``make figures`` runs ``python -m skxfem.app.reproduce --quick --out out/``.  It
writes into ``--out``

* ``fig1.png`` ... ``fig4.png``: schematics of the paper's Figures 1-4
  (:mod:`skxfem.viz.schematics`);
* ``fig5.png`` ... ``fig10.png``: the paper's Figures 5-10 (see
  :mod:`skxfem.viz.figures`), ``fig7_2d.png`` and ``fig8_2d.png``: Figures 7
  and 8 on the 2D strip of triangles, and ``inf_sup.png``: β_h vs h (our
  addition);
* ``summary.json``: the measured numbers — per cell and space, for every n:
  the inf-sup constant β_h of the bilateral tie (``beta_h``, ``beta_l2``:
  both norms of :func:`skxfem.lbb.inf_sup`, ``n_zero`` its zero modes) and
  of the bonded tie the scenes solve (``beta_h_bonded``, ``n_zero_bonded``),
  the relative L² error of the contact pressure and the relative energy
  error with their observed rates, sizes and timings; ``fem_conforming``:
  the energy error of classical FEM on hexahedra that follow Γ (the
  paper's FEM curve of Figure 9, :mod:`skxfem.studies.conforming`); ``block3d``: the
  genuinely 3D validation (:mod:`skxfem.studies.validation3d`);
* ``block3d.png`` (its errors against h) and ``block3d_pressure.png`` (its
  pressures against the exact ones), ``vital_3d.png`` (the multiplier
  spaces on a sphere through tetrahedra, :func:`skxfem.viz.figures.fig_vital_3d`);
* ``frontier_energy.png``, ``frontier_pressure.png``, ``frontier.json``: the
  speed-accuracy frontier (:mod:`skxfem.studies.frontier`): error against wall time
  for every method a user can choose, with the Pareto front; its per-method
  summary is also under ``frontier`` in ``summary.json``;
* ``crack_convergence.png``, ``crack_condition.png``, ``crack_K.png``,
  ``crack_branch.png``, ``crack_friction.png``: a crack with a tip
  (:mod:`skxfem.studies.cracks`, :mod:`skxfem.viz.crack_plots`): the energy error of
  the Williams square against h (geometric ≈ h¹, topological ≈ h^½), the condition
  numbers (raw, Jacobi, block scaling), the K errors, the four branch functions, the
  closed inclined crack's K_II against the friction and the inf-sup constant of the
  contact spaces up to the front; their numbers under ``crack`` in ``summary.json`` (K
  per mesh, enrichment and mode, the fitted energy rates, the condition numbers, the
  edge-cracked plate against Tada's factor, ``friction`` and ``inf_sup`` rows);

and prints the tables of :func:`report`: sorted, their columns explained, every
mesh without a result below them (and, on a terminal, one progress line per part).
Errors are measured against the exact solution of :mod:`skxfem.fem.exact`
(scenes :func:`~skxfem.scenes.exact_strip` and
:func:`~skxfem.scenes.exact_plate` with one layer of cells along x), under
which the paper's reference p(y) = 4y(1 - y) is the exact contact pressure.
3D uses prisms (all three spaces) and hexahedra (the naive space: on this
structured mesh cut by a plane every space is the naive one), 2D triangles and
quadrilaterals (all three spaces).  The plate does not depend on x, so its
prisms give the triangles' numbers; the block of
:func:`~skxfem.scenes.exact_block` (Γ slanted against all three axes, an
exact solution varying in x, y and z) is solved on hexahedra, prisms and
tetrahedra with all three spaces.

``--quick`` took 116 s and 0.9 GB (measured once, 27 November 2026, 2 shared
cores; 2D up to 1/h = 64, 3D up to 32, the block up to 16 cells per side), and the
crack part added since 13 s (the Williams square up to 1/h = 41, measured once); the
default goes one mesh further in each and sweeps a larger frontier (8 minutes and
2.4 GB, measured once on 23 November 2026).  ``--sizes``
replaces every list of meshes (for tests; the block, n³ cells, takes the
smallest size and its half).

>>> parser().parse_args(["--quick", "--sizes", "8", "16"]).sizes
[8, 16]
"""
from __future__ import annotations

import argparse
import json
import sys
import textwrap
import time
from pathlib import Path

import numpy as np

from ..fem.cells import CELL_TYPES
from ..lbb import inf_sup
from ..multipliers import SPACES
from ..scene.benchmarks import exact_scene
from ..stabilised import vital_edges, winner_nodes
from ..studies import cracks
from ..studies.conforming import study_conforming
from ..studies.convergence import study, summary_columns, summary_rates
from ..studies.progress import Progress
from ..studies.validation3d import study_block
from ..studies.validation3d import summary as block_summary
from ..viz import crack_plots, figures, schematics
from ..viz.frontier_plots import reproduce_frontier
from ..viz.validation3d_plots import fig_block, fig_block_pressure

__all__ = ["main", "parser", "plan", "report", "LEGEND"]

SETS = {
    "quick": {"d2": (8, 16, 32, 64), "d3": (8, 16, 32), "fig5": 8, "fig7": (4, 8, 16, 32),
              "fig8": (8, 16), "block": (4, 8, 16), "crack": (11, 21, 41), "tada": (41,)},
    "full": {"d2": (8, 16, 32, 64, 128), "d3": (8, 16, 32, 64), "fig5": 16,
             "fig7": (4, 8, 16, 32, 64), "fig8": (16, 32), "block": (4, 8, 16, 32),
             "crack": (11, 21, 41, 81), "tada": (41, 81)},
}
PARTS = ("fig5", "fig6", "fig7", "fig8", "fig7_2d", "fig8_2d", "study_tri", "study_quad",
         "study_prism", "study_hex", "fem_conforming", "study_block", "block_pressure",
         "vital_3d", "frontier", "crack")
"""The timed parts of a run, in order (one progress line each, on a terminal)."""
CELLS = {"tri": ("naive", "winner", "vital"), "quad": ("naive", "winner", "vital"),
         "prism": ("naive", "winner", "vital"), "hex": ("naive",)}


class _Parser(argparse.ArgumentParser):
    """argparse, with a usage error in one line (exit 2), as ``skxfem`` reports errors."""

    def error(self, message):
        self.exit(2, f"skxfem: error: reproduce: {message} (see {self.prog} --help)\n")


def parser() -> argparse.ArgumentParser:
    """The command line of ``python -m skxfem.app.reproduce``."""
    p = _Parser(prog="python -m skxfem.app.reproduce",
                                description="Reproduce Figures 5-10 of Géniaut, Massin & "
                                            "Moës (2007) and write summary.json.")
    p.add_argument("--out", type=Path, default=Path("out"), help="output folder (created)")
    p.add_argument("--quick", action="store_true",
                   help="coarser meshes: 116 s, measured once on 27 November 2026 on 2 "
                        "shared cores (make figures)")
    p.add_argument("--sizes", type=int, nargs="+", metavar="N",
                   help="1/h of every study and of Figures 5, 7, 8 (e.g. 8 16, for tests)")
    return p


def plan(quick: bool, sizes=None) -> dict:
    """The meshes of each part: ``d2``/``d3`` study sizes, ``fig5`` n, ``fig7``/``fig8`` ns,
    ``block`` the cells per side of the 3D block, ``crack`` those of the Williams square
    (odd: the crack runs mid-cell; the condition numbers on its first three), ``tada``
    the cells across the edge-cracked plate.

    >>> plan(True, [8, 16])["block"], plan(True, [8, 16])["crack"], plan(True)["crack"]
    ((4, 8), (9, 17), (11, 21, 41))
    """
    if not sizes:
        return dict(SETS["quick" if quick else "full"])
    sizes = tuple(sorted(set(sizes)))
    return {"d2": sizes, "d3": sizes, "fig5": min(8, sizes[-1]), "fig7": sizes,
            "fig8": sizes[-2:], "block": tuple(sorted({max(2, sizes[0] // 2), sizes[0]})),
            "crack": tuple(sorted({n + 1 - n % 2 for n in sizes})),
            "tada": (2 * sizes[-1] + 1,)}


def _measure(cell, ns):
    """Study rows and inf-sup results (both norms) of ``cell`` for its spaces."""
    rows = study(lambda n, s: exact_scene(n, cell, s), ns, CELLS[cell], with_inf_sup=False)
    betas = {(scaling, space): [inf_sup(exact_scene(n, cell, space), scaling, "bilateral")
                                for n in ns]
             for scaling in ("h", "l2") for space in CELLS[cell]}
    betas.update({("bonded", space): [inf_sup(exact_scene(n, cell, space), "h", "bonded")
                                      for n in ns] for space in CELLS[cell]})
    return rows, betas


def _table(cell, rows, betas) -> dict:
    out = {}
    for space in CELLS[cell]:
        out[space] = {
            **summary_columns([r for r in rows if r.space == space]),
            "beta_h": [r.beta for r in betas["h", space]],
            "beta_l2": [r.beta for r in betas["l2", space]],
            "h_cut_edges": [r.h for r in betas["h", space]],
            "n_zero": [r.n_zero for r in betas["h", space]],
            "beta_h_bonded": [r.beta for r in betas["bonded", space]],
            "n_zero_bonded": [r.n_zero for r in betas["bonded", space]],
        }
    return out


LEGEND = """\
Rows sorted by dimension (2D, then 3D), cell type, space (naive, winner, vital), 1/h.
  1/h      cells per unit length along Γ (the block: cells per side)
  beta_h   inf-sup constant β_h of the bilateral tie, M = h × interface mass
           (skxfem.lbb.inf_sup): bounded away from 0 for a stable space
  bonded   the same constant for the bonded tie, the law the scenes solve
  L2(p)    relative L²(Γ) error of the contact pressure p = -λ
  W(u)     relative energy error of the displacement
  max(p)   largest error of p at the multiplier points, relative to max |p|
  rate     observed order of the error on its left against the row above:
           log(e_above / e) / log(h_above / h), blank on a space's first mesh"""
"""What the columns of the printed tables mean (:func:`report` prints it after them)."""


def _order(cell: str, space: str, n: int) -> tuple:
    """The sort key of a printed row: dimension, cell type, space, 1/h."""
    return (CELL_TYPES[cell].dim, cell, SPACES.index(space), n)


def _rows(studies: dict, columns) -> list[tuple]:
    """``(key, values)`` per mesh of ``{cell: {space: table}}``, the rate of each
    listed error column next to it (None on a space's first mesh)."""
    rows = []
    for cell, spaces in studies.items():
        for space, t in spaces.items():
            for k, n in enumerate(t["n"]):
                values = [t[c][k] if c not in RATES else
                          (t[RATES[c]][k - 1] if k else None) for c in columns]
                rows.append((_order(cell, space, n), (cell, space, n, *values)))
    return [r for _, r in sorted(rows, key=lambda r: r[0])]


RATES = {"pressure_l2_rate": "pressure_l2_rates", "energy_rate": "energy_rates"}


def _rate(r) -> str:
    return "     " if r is None else f"{r:5.2f}"


def report(summary: dict) -> str:
    """The text ``make figures`` prints: the convergence table of the plate and the
    strip, the table of the 3D block, both sorted (:func:`_order`), what their columns
    mean (:data:`LEGEND`), then every mesh that has no result, with the solver's
    whole message.

    >>> t = {"n": [8], "beta_h": [0.5], "beta_h_bonded": [0.4], "pressure_l2": [0.1],
    ...      "pressure_l2_rates": [], "energy": [0.2], "energy_rates": []}
    >>> block = {"studies": {}, "failures": [{"cell": "tet", "space": "naive", "n": 4,
    ...                                      "reason": "refused: too dependent"}]}
    >>> text = report({"studies": {"tri": {"vital": t}}, "block3d": block})
    >>> print(text.splitlines()[2])
    tri    vital      8   0.5000   0.4000  1.00e-01        2.00e-01
    >>> print(text.split("Failures")[1])
     (1 mesh with no result):
    tet naive 1/h = 4: refused: too dependent
    """
    lines = ["The plate (3D) and the strip (2D): summary.json, studies",
             f"{'cell':6} {'space':7} {'1/h':>4} {'beta_h':>8} {'bonded':>8} {'L2(p)':>9} "
             f"{'rate':>5} {'W(u)':>9} {'rate':>5}"]
    columns = ("beta_h", "beta_h_bonded", "pressure_l2", "pressure_l2_rate", "energy",
               "energy_rate")
    for cell, space, n, beta, bonded, p, pr, e, er in _rows(summary["studies"], columns):
        lines.append(f"{cell:6} {space:7} {n:4d} {beta:8.4f} {bonded:8.4f} {p:9.2e} "
                     f"{_rate(pr)} {e:9.2e} {_rate(er)}".rstrip())
    block = summary["block3d"]
    lines += ["", "The 3D block, Γ slanted against all three axes: summary.json, block3d",
              f"{'cell':6} {'space':7} {'1/h':>4} {'W(u)':>9} {'rate':>5} {'L2(p)':>9} "
              f"{'rate':>5} {'max(p)':>9}"]
    columns = ("energy", "energy_rate", "pressure_l2", "pressure_l2_rate", "pressure_max")
    for cell, space, n, e, er, p, pr, pmax in _rows(block["studies"], columns):
        lines.append(f"{cell:6} {space:7} {n:4d} {e:9.2e} {_rate(er)} {p:9.2e} {_rate(pr)} "
                     f"{pmax:9.2e}")
    lines += ["", LEGEND, ""]
    failures = sorted(block["failures"], key=lambda f: _order(f["cell"], f["space"], f["n"]))
    if not failures:
        lines.append("Failures: none (every mesh has a result)")
    else:
        count = f"{len(failures)} mesh{'es' if len(failures) > 1 else ''}"
        lines.append(f"Failures ({count} with no result):")
        for f in failures:
            lines.append(textwrap.fill(f"{f['cell']} {f['space']} 1/h = {f['n']}: "
                                       f"{f['reason']}", 88, subsequent_indent="    ",
                                       break_long_words=False, break_on_hyphens=False))
    return "\n".join(lines)


FRICTIONS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8)
"""The frictions μ of the closed inclined crack in ``crack_friction.png`` (β = 20°, 30°
on 1/h = 21: the faces stick from μ = tan β)."""


def _crack(out, save, ns, nxs) -> dict:
    """The crack studies and figures (:mod:`skxfem.studies.cracks`); their summary."""
    williams = cracks.williams_study(ns)
    conditioning = cracks.conditioning_study(ns[:3])
    plates = cracks.tada_study(nxs)
    save(crack_plots.fig_crack_convergence(williams), "crack_convergence")
    save(crack_plots.fig_crack_conditioning(conditioning), "crack_condition")
    save(crack_plots.fig_crack_K(williams), "crack_K")
    save(crack_plots.fig_branch_functions(), "crack_branch")
    friction = cracks.friction_study((21,), (20.0, 30.0), FRICTIONS)
    inf_sup = cracks.crack_inf_sup(ns)
    save(crack_plots.fig_crack_friction(friction, inf_sup), "crack_friction")
    return cracks.summary(williams, conditioning, plates, friction, inf_sup)


def main(argv=None) -> int:
    """Compute, draw and write everything; returns the exit code 0."""
    args = parser().parse_args(argv)
    sizes = plan(args.quick, args.sizes)
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    timings = {}
    start = time.perf_counter()

    def save(fig, name):
        fig.savefig(out / f"{name}.png", dpi=120, bbox_inches="tight")

    progress = Progress(len(PARTS), "reproduce")

    def timed(name, make):
        t0 = time.perf_counter()
        value = make()
        timings[name] = round(time.perf_counter() - t0, 2)
        progress.step(name)
        return value

    for name in ("fig1", "fig2", "fig3", "fig4"):     # the schematics of Figures 1-4
        save(getattr(schematics, name)(), name)
    save(timed("fig5", lambda: figures.fig5(sizes["fig5"])), "fig5")
    save(timed("fig6", figures.fig6), "fig6")
    graph = figures.figure6_graph()
    algo1, algo2 = winner_nodes(*graph), vital_edges(*graph)
    save(timed("fig7", lambda: figures.fig7(sizes["fig7"])), "fig7")
    save(timed("fig8", lambda: figures.fig8(sizes["fig8"])), "fig8")
    save(timed("fig7_2d", lambda: figures.fig7(sizes["fig7"], cell="tri")), "fig7_2d")
    save(timed("fig8_2d", lambda: figures.fig8(sizes["fig8"], cell="tri")), "fig8_2d")

    measured = {}
    for cell in ("tri", "quad", "prism", "hex"):
        ns = sizes["d2"] if cell in ("tri", "quad") else sizes["d3"]
        measured[cell] = timed(f"study_{cell}", lambda c=cell, ns=ns: _measure(c, ns))
    studies = {cell: _table(cell, *m) for cell, m in measured.items()}
    rows = {cell: m[0] for cell, m in measured.items()}
    shown = {"tri": ("naive", "winner", "vital"), "prism": ("naive", "winner", "vital"),
             "quad": ("naive",), "hex": ("naive",)}
    fem = timed("fem_conforming", lambda: study_conforming(
        sorted({2 * max(1, n // 2) for n in sizes["d3"]})))
    save(figures.fig9({c: [r for r in rows[c] if r.space in shown[c]] for c in rows},
                      fem={"hex": fem}), "fig9")
    save(figures.fig10({c: [r for r in rows[c] if r.space in shown[c]] for c in rows}), "fig10")
    inf_sup = [{(c, s): measured[c][1][scaling, s] for c in ("tri", "quad", "prism")
                for s in shown[c]} for scaling in ("h", "l2", "bonded")]
    save(figures.fig_inf_sup(*inf_sup), "inf_sup")

    block = timed("study_block", lambda: study_block(sizes["block"]))
    save(fig_block(block), "block3d")
    save(timed("block_pressure", lambda: fig_block_pressure(min(8, sizes["block"][-1]))),
         "block3d_pressure")
    save(timed("vital_3d", figures.fig_vital_3d), "vital_3d")

    frontier = timed("frontier", lambda: reproduce_frontier(out, args.quick, args.sizes))
    crack = timed("crack", lambda: _crack(out, save, sizes["crack"], sizes["tada"]))

    quad = studies["quad"]
    summary = {
        "paper": "Géniaut, Massin & Moës (2007), §5, Figures 5-10",
        "quick": bool(args.quick), "sizes": sizes,
        "reference": "exact: skxfem.fem.exact.ExactPlate, contact pressure p = 4 s (1 - s) on Γ",
        "scenes": {"tri": "exact_strip(n, 'tri')", "quad": "exact_strip(n, 'quad')",
                   "prism": "exact_plate(n, 'prism', nx=1)", "hex": "exact_plate(n, 'hex', nx=1)"},
        "figure6": {"winner": {"multipliers": algo1.size, "winner_nodes": algo1.winners.tolist()},
                    "vital": {"multipliers": algo2.size,
                              "vital_edges": [list(figures.FIG6_EDGES[e]) for e in
                                              np.flatnonzero(algo2.vital)]}},
        "quad_spaces_coincide": float(max(
            np.ptp([quad[s][k][i] for s in quad]) for k in ("beta_h", "pressure_l2")
            for i in range(len(quad["naive"]["n"])))),
        "studies": studies,
        "fem_conforming": {"hex": {
            "scene": "exact_plate(n, 'hex', nx=1) on 1 x n x n cells: Γ on mesh faces",
            "n": [r.n for r in fem], "h": [r.h for r in fem],
            "energy": [r.energy for r in fem],
            "energy_rates": summary_rates([r.h for r in fem], [r.energy for r in fem]),
            "n_dofs": [r.n_dofs for r in fem]}},
        "block3d": block_summary(block),
        "frontier": frontier,
        "crack": crack,
        "timings": timings,
    }
    timings["total"] = round(time.perf_counter() - start, 2)
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(report(summary))
    print(f"wrote {len(list(out.glob('*.png')))} figures and summary.json to {out}/ "
          f"in {timings['total']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
