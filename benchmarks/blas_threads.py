"""Benchmark: skxfem's solves with a threaded BLAS against one BLAS thread.

skxfem limits the BLAS libraries to one thread during its solves
(:mod:`skxfem.linalg.threads`, ``SKXFEM_THREADS``).  For each case this prints the
wall time of the solve with BLAS threaded over every core (what a notebook
or a shell without ``OPENBLAS_NUM_THREADS=1`` gets: ``SKXFEM_THREADS=off``)
and limited (the default), the least and the median of ``--repeat`` runs,
the two settings alternating so that both see the same load of a shared
machine, and their ratio.

    python benchmarks/blas_threads.py              # plate hex n = 8, prism n = 6, 3D contact
    python benchmarks/blas_threads.py --repeat 5
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

from threadpoolctl import threadpool_info, threadpool_limits

import skxfem
from skxfem import scenes
from skxfem.linalg.threads import using

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def cases() -> dict:
    return {
        "plate hex n=8, tie (direct)": lambda: skxfem.solve(scenes.paper_plate(8, "hex"),
                                                            linear="direct"),
        "plate prism n=6, tie (direct)": lambda: skxfem.solve(scenes.paper_plate(6, "prism"),
                                                              linear="direct"),
        "block.toml: 3D Coulomb contact": lambda: skxfem.solve(
            skxfem.load_scene(EXAMPLES / "block.toml")),
    }


def timed(run, threaded: bool, cores: int) -> float:
    """Wall time of ``run()``: BLAS on ``cores`` threads left alone, or skxfem's limit."""
    with threadpool_limits(limits=cores, user_api="blas"):   # the caller's setting
        with using(None) if threaded else using(1):
            t0 = time.perf_counter()
            run()
            return time.perf_counter() - t0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per setting (default 3)")
    args = parser.parse_args(argv)
    cores = os.cpu_count() or 1
    libraries = sorted({f"{d['internal_api']} {d['version']}" for d in threadpool_info()
                        if d["user_api"] == "blas"})
    print(f"{cores} cores, BLAS: {', '.join(libraries)}; load average "
          f"{os.getloadavg()[0]:.1f}; python {sys.version.split()[0]}")
    print(f"{'case':32} {'threaded (s)':>16} {'one thread (s)':>16} {'ratio':>6}")
    print(f"{'':32} {'least  median':>16} {'least  median':>16}")
    for name, run in cases().items():
        run()                                                  # warm up: imports, caches
        times = {True: [], False: []}
        for _ in range(args.repeat):
            for threaded in (True, False):
                times[threaded].append(timed(run, threaded, cores))
        least = {k: min(v) for k, v in times.items()}
        median = {k: statistics.median(v) for k, v in times.items()}
        print(f"{name:32} {least[True]:7.2f} {median[True]:7.2f}  "
              f"{least[False]:7.2f} {median[False]:7.2f}  {median[True] / median[False]:5.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
