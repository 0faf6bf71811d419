"""Benchmark: 3D contact with friction against the bonded tie of the same scene.

Two scenes, each at the sizes n asked for:

* the slipping block (:func:`skxfem.scenes.slipping_block`): n × n × (n + 1)
  hexahedra, Coulomb μ = 0.3 on a joint of slope 0.4, every point slides, load
  steps 0.5 and 1;
* the paper's plate with the adhesive law (``paper_plate(n, "hex", law="adhesive")``):
  every point sticks.

For each: the unknowns and multipliers; the contact solve (``skxfem.solve``:
assembly included) with its Newton iterations per load step and the Krylov
iterations of each Newton step; the bonded tie of the same scene (law
``bonded``); the plain scikit-fem elasticity solve of the same mesh, loads and
supports without interface (``benchmarks/tie_solve.py``'s); their ratios, the
peak resident memory of each (each case runs in its own process) and the
growth exponents a in time ~ unknowns^a.

Targets (issue 27 of the tracker): slipping block ≤ 4× the tie, adhesive plate
≤ 1.5× the tie, memory ≤ 1.5× the tie, growth no faster than unknowns^1.2.
The machine is shared: compare ratios measured in one run.

    python benchmarks/contact_solve.py                      # n = 8, 14, 24, 32
    python benchmarks/contact_solve.py --sizes 8 14         # a quick look
    python benchmarks/contact_solve.py --scenes block --sizes 42   # one large block
    python benchmarks/contact_solve.py --linear direct --sizes 8 10  # SuperLU steps
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time
from dataclasses import replace

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tie_solve import plain_solve, slope  # noqa: E402  (a sibling script)

from skxfem.studies.progress import Progress  # noqa: E402


def _scene(kind: str, n: int, law: str | None = None):
    from skxfem.scene.benchmarks import paper_plate, slipping_block
    if kind == "block":
        s = slipping_block(n)
    else:
        s = paper_plate(n, "hex", law="adhesive")
    return s if law is None else replace(s, law=law, friction=None)


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def worker(kind: str, n: int, what: str, linear: str) -> dict:
    """One case in this process: ``contact``, ``tie`` (law bonded) or ``plain``."""
    import skxfem

    base = _rss_mb()
    if what == "plain":
        out = plain_solve(_scene(kind, n))
        return {"dofs": out["dofs"], "total": out["total"], "iterations": out["iterations"],
                "peak_mb": _rss_mb(), "base_mb": base}
    scene = _scene(kind, n, "bonded" if what == "tie" else None)
    t0 = time.perf_counter()
    r = skxfem.solve(scene, linear=linear)
    total = time.perf_counter() - t0
    out = {"dofs": int(r.n_dofs), "multipliers": int(r.n_multipliers), "total": total,
           "linear": r.linear, "peak_mb": _rss_mb(), "base_mb": base,
           "timings": {k: float(v) for k, v in r.timings.items()}}
    if what == "tie":
        out["iterations"] = r.linear_info.get("iterations", 0)
    else:
        out["newton"] = [int(st.newton.iterations) for st in r.steps]
        out["inner"] = [list(map(int, st.newton.inner)) for st in r.steps]
        out["status"] = np.bincount(r.steps[-1].status, minlength=3).tolist()
    return out


def run(kind: str, n: int, what: str, linear: str) -> dict | None:
    proc = subprocess.run([sys.executable, __file__, "--worker", kind, str(n), what, linear],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        print(f"  {kind} n={n} {what} failed:\n{proc.stderr[-2000:]}", file=sys.stderr)
        return None
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[8, 14, 24, 32])
    ap.add_argument("--scenes", nargs="+", choices=("block", "plate"),
                    default=["block", "plate"])
    ap.add_argument("--linear", choices=("auto", "direct", "iterative"), default="auto",
                    help="the linear solve of the contact steps and of the tie (default auto)")
    ap.add_argument("--no-plain", action="store_true", help="skip the plain elasticity solve")
    ap.add_argument("--worker", nargs=4, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        kind, n, what, linear = args.worker
        print(json.dumps(worker(kind, int(n), what, linear)))
        return
    cases = [(kind, n) for kind in args.scenes for n in args.sizes]
    progress = Progress(len(cases), "contact_solve")
    rows = []
    for kind, n in cases:
        contact = run(kind, n, "contact", args.linear)
        tie = run(kind, n, "tie", args.linear)
        plain = None if args.no_plain else run(kind, n, "plain", args.linear)
        progress.step(f"{kind} n={n}")
        if contact is not None and tie is not None:
            rows.append((kind, n, contact, tie, plain))
    cpu = platform.processor() or platform.machine()
    print(f"\n{time.strftime('%Y-%m-%d %H:%M')} on {platform.node()} ({cpu}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}); one process per "
          f"solve, linear={args.linear}; times include assembly")
    print("\n| scene | n | unknowns | mult. | Newton its per step | Krylov its per Newton step"
          " | contact | tie (its) | plain (its) | contact/tie | contact/plain | peak MB "
          "contact/tie/plain | memory contact/tie |")
    print("|---" * 13 + "|")
    for kind, n, c, t, p in rows:
        inner = " / ".join(",".join(map(str, s)) or "-" for s in c["inner"])
        pl = f"{p['total']:.2f} s ({p['iterations']})" if p else "-"
        cp = f"{c['total'] / p['total']:.1f}" if p else "-"
        pmb = f"{p['peak_mb']:.0f}" if p else "-"
        print(f"| {kind} | {n} | {c['dofs']} | {c['multipliers']} | "
              f"{', '.join(map(str, c['newton']))} | {inner} | {c['total']:.2f} s "
              f"({c['linear']}) | {t['total']:.2f} s ({t['iterations']}) | {pl} | "
              f"{c['total'] / t['total']:.2f} | {cp} | {c['peak_mb']:.0f}/{t['peak_mb']:.0f}/"
              f"{pmb} | {c['peak_mb'] / t['peak_mb']:.2f} |")
    print("\nGrowth exponents a in time ~ unknowns^a (least squares over the sizes):")
    for kind in args.scenes:
        pts = [(c["dofs"], c["total"], t["total"]) for k, n, c, t, p in rows if k == kind]
        if len(pts) < 2:
            continue
        dofs, ct, tt = map(np.array, zip(*pts))
        print(f"  {kind}: contact {slope(dofs, ct):.2f}, tie {slope(dofs, tt):.2f}")


if __name__ == "__main__":
    main()
