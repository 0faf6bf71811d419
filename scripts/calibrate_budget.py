"""Measure the peak memory of solves, to calibrate and check skxfem.budget.

    python scripts/calibrate_budget.py strip:tri:64 plate:prism:8 ...

Each case runs in its own subprocess; printed per case (one JSON line): the
sizes the solve met (nodes, cells, unknowns, enriched dofs, multipliers, the
non-zeros of L + U), the peak resident memory the solve added (the peak VmHWM, reset
just before the solve, minus the resident memory before it) and skxfem.budget's
estimate.  Not a test: it takes seconds to minutes and depends on the machine.
"""
import subprocess
import sys

CHILD = r"""
import dataclasses, json, sys
import numpy as np
import scipy.sparse.linalg as spla
from skxfem import budget, saddle, scenes
from skxfem.scene import Box
from skxfem.solver import solve

kind, cell, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
if cell == "tet":  # the paper's plate on tetrahedra
    hexes = scenes.paper_plate(n, cell="hex")
    scene = dataclasses.replace(hexes, mesh=Box(hexes.mesh.n, "tet"))
else:
    scene = {"strip": scenes.strip, "plate": scenes.paper_plate}[kind](n, cell=cell)
est = budget.estimate(scene)
seen = {}
splu = spla.splu
def spy(A, **kw):
    lu = splu(A, **kw)
    seen["lu_nnz"] = int(lu.L.nnz + lu.U.nnz)
    seen["A_n"] = int(A.shape[0])
    return lu
saddle.spla.splu = spy
def status(key):
    with open("/proc/self/status") as f:
        return 1024 * int(next(l for l in f if l.startswith(key)).split()[1])
solve(scenes.strip(2, cell="quad"))
before = status("VmRSS:")
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")   # reset the peak VmHWM
r = solve(scene)
peak = status("VmHWM:")
print(json.dumps({"case": f"{kind}:{cell}:{n}", "nodes": int(r.mesh.nvertices),
                  "cells": int(r.mesh.nelements), "N": int(r.n_dofs),
                  "n_enr": int(r.space.n_enr), "m": int(r.n_multipliers + r.removed),
                  **seen, "measured_MB": round((peak - before) / 2**20, 1),
                  "estimate_MB": round(est.bytes / 2**20, 1),
                  "est_nodes": est.n_nodes, "est_dofs": est.n_dofs,
                  "est_multipliers": est.n_multipliers}))
"""

if __name__ == "__main__":
    for case in sys.argv[1:]:
        done = subprocess.run([sys.executable, "-c", CHILD, *case.split(":")],
                              capture_output=True, text=True, check=False)
        print(done.stdout.strip() or done.stderr.strip().splitlines()[-1], flush=True)
