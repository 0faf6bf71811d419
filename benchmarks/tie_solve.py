"""Benchmark: the tied X-FEM solve against a plain scikit-fem elasticity solve.

For the paper's plate (hex and prism, vital space) and the 2D strip (tri,
vital), each size prints the unknowns, the X-FEM tie solve by the direct
path (:func:`skxfem.linalg.saddle.solve`) and by the iterative one
(:func:`skxfem.linalg.iterative.solve`), the plain scikit-fem elasticity solve of
the same mesh without interface (minimal exact quadrature, the same
stiffness kernel :func:`skxfem.fem.material.stiffness_matrix`, pyamg smoothed
aggregation with the rigid-body modes, SuperLU coarse solve, CG to 1e-10),
their ratios, the iterations, the peak memory and the assembly stages
(``Problem.timings``).  Each case runs in its own process, so that its peak
resident memory (``ru_maxrss``) is its own.

Targets (issue 11): solve ratio ≤ 2, total ratio ≤ 1.5, memory ratio ≤ 2,
time growing no faster than about dofs^1.2.  The machine is shared: compare
ratios measured in one run.

The AMG's smoother (:data:`skxfem.linalg.amg.SMOOTHER`): a Chebyshev polynomial of
degree 2 instead of pyamg's symmetric block Gauss-Seidel, whose sweeps cost several
products with K_r each.  Measured on ``skxfem.solve(scene, linear="iterative")``, one
run each, solve stage Gauss-Seidel -> Chebyshev (CG iterations): the plate hex n = 24
2.26 s (22) -> 1.37 s (29), n = 32 5.65 (26) -> 2.43 (40); prism n = 24 2.72 (35) -> 1.34
(39), n = 32 5.68 (37) -> 2.73 (46); tet n = 24 1.98 (38) -> 1.02 (45); the strip tri
n = 256 2.41 (61) -> 1.26 (59), quad n = 400 4.55 (28) -> 1.73 (33); U within 1e-11 of
each other and of the direct solve (the bilateral law, two interfaces, slivers and a
stiffer Ω⁺ in the notes of :data:`~skxfem.linalg.amg.SMOOTHER`).  The plain solve here
keeps pyamg's defaults.

    python benchmarks/tie_solve.py                 # plate n = 16, 24, 32; strip n = 256, 512
    python benchmarks/tie_solve.py --quick         # plate n = 8, 12; strip n = 64, 128
    python benchmarks/tie_solve.py --sizes 16 20 --strip-sizes 256
    python benchmarks/tie_solve.py --repeat 3      # the least of 3 runs per case
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

from skxfem.studies.progress import Progress


def _scene(kind: str, cell: str, n: int):
    from skxfem.scene.benchmarks import paper_plate, strip
    return (paper_plate(n, cell, space="vital") if kind == "plate"
            else strip(n, cell, space="vital"))


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def rigid_body_modes(basis) -> np.ndarray:
    """The rigid motions of a plain vector P1/Q1 basis, (N, 3) in 2D, (N, 6) in 3D."""
    x = basis.mesh.p
    zero, one = np.zeros(x.shape[1]), np.ones(x.shape[1])
    if x.shape[0] == 2:
        motions = [(one, zero), (zero, one), (-x[1], x[0])]
    else:
        motions = [(one, zero, zero), (zero, one, zero), (zero, zero, one),
                   (zero, -x[2], x[1]), (x[2], zero, -x[0]), (-x[1], x[0], zero)]
    Z = np.zeros((basis.N, len(motions)))
    for k, m in enumerate(motions):
        Z[basis.nodal_dofs.ravel(), k] = np.concatenate(m)
    return Z


def plain(kind: str, cell: str, n: int) -> dict:
    """Plain scikit-fem elasticity on the scene's mesh, no interface: AMG-CG."""
    return plain_solve(_scene(kind, cell, n))


def plain_solve(scene) -> dict:
    """Plain scikit-fem elasticity on ``scene``'s mesh, its loads and supports, no
    interface: AMG-CG (also used by ``benchmarks/contact_solve.py``)."""
    import pyamg
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from skfem import Basis, ElementVector

    from skxfem.fem.loads import boundary_quadrature, surface_load
    from skxfem.fem.material import stiffness_matrix
    from skxfem.fem.quadrature import cell_rule, exact_orders
    from skxfem.scene import resolve_mesh
    from skxfem.scene.boundary import dirichlet, load_facets

    t = {}
    t0 = time.perf_counter()
    mesh = resolve_mesh(scene)
    rule = cell_rule(mesh, exact_orders(mesh)[0])  # the X-FEM's rule on uncut cells
    # dofs, loads and supports: a vector basis holding one point per cell, as the X-FEM's
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, 0))
    t["mesh"] = time.perf_counter() - t0
    # the X-FEM's own kernel (scalar forms; scikit-fem's linear_elasticity on
    # the vector basis gives the same matrix 6-8 times slower in 3D)
    K = stiffness_matrix(scene.material, Basis(mesh, mesh.elem(), quadrature=rule))
    t["stiffness"] = time.perf_counter() - t0 - sum(t.values())
    f = np.zeros(basis.N)
    for facets, traction in load_facets(scene, mesh):
        f += surface_load(basis, boundary_quadrature(mesh, facets, 4), traction)[0]
    D, g = dirichlet(scene, mesh, basis)
    t["load"] = time.perf_counter() - t0 - sum(t.values())
    # imposed unknowns as identity rows (symmetric): the nodal blocks stay whole
    fixed = np.zeros(basis.N, dtype=bool)
    fixed[D] = True
    u0 = np.zeros(basis.N)
    u0[D] = g
    keep = sp.diags((~fixed).astype(float))
    A = (keep @ K @ keep + sp.diags(fixed.astype(float))).tocsr()
    b = np.where(fixed, u0, f - K @ u0)
    dim = mesh.dim()
    ml = pyamg.smoothed_aggregation_solver(sp.bsr_matrix(A, blocksize=(dim, dim)),
                                           B=rigid_body_modes(basis), coarse_solver="splu")
    its = []
    u, info = spla.cg(A, b, rtol=1e-10, M=ml.aspreconditioner(),
                      callback=lambda _: its.append(1))
    t["solve"] = time.perf_counter() - t0 - sum(t.values())
    assert info == 0, f"plain CG did not converge ({info})"
    return {"dofs": int(basis.N), "solve": t["solve"], "total": sum(t.values()),
            "iterations": len(its), "stages": t}


def xfem(kind: str, cell: str, n: int, solver: str, save: str) -> dict:
    """The tied X-FEM problem: assembly (Problem.timings) and the saddle solve;
    U and the edge tractions λ = Pμ are saved to ``save`` (.npz)."""
    from skxfem.linalg import iterative, saddle
    from skxfem.linalg.amg import rigid_modes
    from skxfem.problem import assemble
    from skxfem.solver import _differences

    p = assemble(_scene(kind, cell, n))
    assembled_mb = _rss_mb()
    t0 = time.perf_counter()
    G = _differences(p.cut, p.ncomp) @ p.P
    if solver == "direct":
        U, mu, info = saddle.solve(p.K, p.B, p.F, p.D, p.g, G=G)
        its = 0
    else:
        U, mu, info = iterative.solve(p.K, p.B, p.F, p.D, p.g, G=G, modes=rigid_modes(p.V),
                                      blocksize=p.mesh.dim(), bonded=p.law == "bonded")
        its = info.iterations
    solve = time.perf_counter() - t0
    np.savez(save, U=U, lam=p.P @ mu)
    return {"dofs": int(p.K.shape[0]), "multipliers": int(p.B.shape[0]), "solve": solve,
            "total": sum(p.timings.values()) + solve, "iterations": its,
            "stages": dict(p.timings), "assembled_mb": assembled_mb}


def worker(args) -> None:
    kind, cell, n, what, save = args.worker
    base = _rss_mb()
    out = plain(kind, cell, int(n)) if what == "plain" else xfem(kind, cell, int(n), what, save)
    out.update(peak_mb=_rss_mb(), base_mb=base)
    print(json.dumps(out))


def best(kind, cell, n, what, tmp, repeat: int) -> dict | None:
    """The run of least total time among ``repeat`` (the machine is shared)."""
    runs = [run(kind, cell, n, what, tmp) for _ in range(repeat)]
    runs = [r for r in runs if r is not None]
    return min(runs, key=lambda r: r["total"]) if runs else None


def run(kind, cell, n, what, tmp) -> dict | None:
    save = f"{tmp}/{kind}_{cell}_{n}_{what}.npz"
    proc = subprocess.run([sys.executable, __file__, "--worker", kind, cell, str(n), what, save],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        print(f"  {kind} {cell} n={n} {what} failed:\n{proc.stderr[-2000:]}", file=sys.stderr)
        return None
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    if what != "plain":
        out.update(np.load(save))
    return out


def difference(a, b) -> str:
    """Relative differences of U and of λ between two X-FEM solves."""
    if a is None or b is None:
        return "-"
    dU = np.linalg.norm(a["U"] - b["U"]) / np.linalg.norm(b["U"])
    dl = np.linalg.norm(a["lam"] - b["lam"]) / np.linalg.norm(b["lam"])
    return f"{dU:.0e} / {dl:.0e}"


def slope(dofs, times) -> float:
    """Exponent a of time ~ dofs^a, least squares over the sizes of one series."""
    if len(dofs) < 2:
        return float("nan")
    return float(np.polyfit(np.log(dofs), np.log(times), 1)[0])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="plate n = 8, 12; strip n = 64, 128")
    ap.add_argument("--sizes", type=int, nargs="+", help="plate sizes n (hex and prism)")
    ap.add_argument("--strip-sizes", type=int, nargs="+", help="strip sizes n (tri)")
    ap.add_argument("--direct-max-dofs", type=int, default=60000,
                    help="skip the 3D direct solve above this many unknowns (its time and "
                         "memory grow like dofs^2); default 60000")
    ap.add_argument("--direct-max-dofs-2d", type=int, default=10 ** 6,
                    help="the same in 2D (fill grows far more slowly); default 1e6")
    ap.add_argument("--repeat", type=int, default=1,
                    help="runs per case and solver; the least total time is kept (default 1)")
    ap.add_argument("--worker", nargs=5, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        return worker(args)
    sizes = args.sizes or ([8, 12] if args.quick else [16, 24, 32])
    strip_sizes = args.strip_sizes or ([64, 128] if args.quick else [256, 512])
    cases = [("plate", "hex", n) for n in sizes] + [("plate", "prism", n) for n in sizes] \
        + [("strip", "tri", n) for n in strip_sizes]
    rows, series = [], {}
    progress = Progress(len(cases), "tie_solve")  # on stderr, only on a terminal
    tmp = tempfile.mkdtemp(prefix="tie_solve_")
    for kind, cell, n in cases:
        pl = best(kind, cell, n, "plain", tmp, args.repeat)
        it = best(kind, cell, n, "iterative", tmp, args.repeat)
        if pl is None or it is None:
            progress.step(f"{kind} {cell} n={n} failed")
            continue
        cap = args.direct_max_dofs if kind == "plate" else args.direct_max_dofs_2d
        di = run(kind, cell, n, "direct", tmp) if it["dofs"] <= cap else None  # once: slow
        rows.append((kind, cell, n, pl, it, di))
        progress.step(f"{kind} {cell} n={n}")
        series.setdefault(cell, []).append((it["dofs"], it["solve"], it["total"],
                                            pl["solve"], pl["total"]))
    cpu = platform.processor() or platform.machine()
    print(f"\n{time.strftime('%Y-%m-%d %H:%M')} on {platform.node()} ({cpu}, {os.cpu_count()} "
          f"cores, Python {platform.python_version()}); one process per solve, the least "
          f"total of {args.repeat} run(s) per case (direct: one)")
    print("\n| case | dofs | mult. | direct solve | iter. solve (its) | plain solve (its) | "
          "solve ratio | X-FEM total | plain total | total ratio | direct/iter. | "
          "peak MB iter./plain (ratio) | over import: iter./plain (ratio) | "
          "iter. vs direct: dU / dλ |")
    print("|---" * 14 + "|")
    for kind, cell, n, pl, it, di in rows:
        d = f"{di['solve']:.2f} s" if di else "skipped"
        dr = f"{di['solve'] / it['solve']:.1f}" if di else "-"
        inc_it, inc_pl = it["peak_mb"] - it["base_mb"], pl["peak_mb"] - pl["base_mb"]
        print(f"| {cell} n={n} | {it['dofs']} | {it['multipliers']} | {d} | "
              f"{it['solve']:.2f} s ({it['iterations']}) | {pl['solve']:.2f} s "
              f"({pl['iterations']}) | {it['solve'] / pl['solve']:.2f} | {it['total']:.2f} s | "
              f"{pl['total']:.2f} s | {it['total'] / pl['total']:.2f} | {dr} | "
              f"{it['peak_mb']:.0f}/{pl['peak_mb']:.0f} ({it['peak_mb'] / pl['peak_mb']:.2f}) | "
              f"{inc_it:.0f}/{inc_pl:.0f} ({inc_it / max(inc_pl, 1):.2f}) | "
              f"{difference(it, di)} |")
    print("\nAssembly stages of the X-FEM problem (s), and the set-up share "
          "(cut + space + enrich) of the X-FEM total:")
    names = list(rows[0][4]["stages"]) if rows else []
    print("| case | " + " | ".join(names) + " | set-up share |")
    print("|---" * (len(names) + 2) + "|")
    for kind, cell, n, pl, it, di in rows:
        st = it["stages"]
        share = sum(st[k] for k in ("cut", "space", "enrich")) / it["total"]
        print(f"| {cell} n={n} | " + " | ".join(f"{st[k]:.2f}" for k in names)
              + f" | {100 * share:.0f} % |")
    print("\nPeak memory (MB) of the X-FEM process after assembly, before the solve:")
    print("  " + ", ".join(f"{cell} n={n}: {it['assembled_mb']:.0f}"
                           for kind, cell, n, pl, it, di in rows))
    print("\nPlain scikit-fem stages (s):")
    for kind, cell, n, pl, it, di in rows:
        print(f"  {cell} n={n}: " + ", ".join(f"{k} {v:.2f}" for k, v in pl["stages"].items()))
    print("\nGrowth exponents a in time ~ dofs^a (least squares over the sizes):")
    for cell, pts in series.items():
        dofs, its, itt, pls, plt = map(np.array, zip(*pts))
        if len(dofs) < 2:
            print(f"  {cell}: one size only, no exponent")
            continue
        print(f"  {cell}: X-FEM iterative solve {slope(dofs, its):.2f}, X-FEM total "
              f"{slope(dofs, itt):.2f}, plain solve {slope(dofs, pls):.2f}, plain total "
              f"{slope(dofs, plt):.2f}")


if __name__ == "__main__":
    main()
