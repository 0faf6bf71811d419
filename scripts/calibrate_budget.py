"""Measure the peak memory of solves, to calibrate and check skxfem.studies.budget.

    python scripts/calibrate_budget.py strip:tri:64 plate:prism:8 ...
    python scripts/calibrate_budget.py --linear iterative plate:hex:16 strip:tri:256 ...
    python scripts/calibrate_budget.py --linear iterative press:hex:24 press:quad:256

``press`` is frictionless contact: a box of n cells a side (3D: n x n x n), Γ
across the middle (n even), the bottom clamped, the top pressed and held tangentially.

Each case runs in its own subprocess; printed per case (one JSON line): the
sizes the solve met (nodes, cells, unknowns, enriched dofs, multipliers, the
non-zeros of L + U), the peak resident memory the solve added (the peak VmHWM, reset
just before the solve, minus the resident memory before it) and skxfem.studies.budget's
estimate, for the linear solver ``--linear`` (default ``auto``, as ``skxfem.solve``;
``bytes_per_unknown`` is the measured peak over N + m, what
``budget.ITERATIVE_BYTES`` bounds).  Not a test: it takes seconds to minutes and
depends on the machine.
"""
import subprocess
import sys

CHILD = r"""
import dataclasses, json, sys
import numpy as np
import scipy.sparse.linalg as spla
from skxfem import scenes
from skxfem.studies import budget
from skxfem.linalg import saddle
from skxfem.levelset import plane
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, clamped
from skxfem.solver import solve

args, linear = sys.argv[1:-1], sys.argv[-1]
kind, cell, n = args[0], args[1], int(args[2])
dim = 2 if cell in ("tri", "quad") else 3
if kind == "crack":  # crack:cell:n:shape:pos:law
    from skxfem.fem.material import Material
    from skxfem.levelset import LevelSet
    from skxfem.scene import Interface
    shape, pos, law = args[3:6]
    e = np.eye(dim)
    z0 = (n // 2 + (0.0 if pos == "node" else 0.5)) / n
    if shape == "edge":
        phi = plane((0.5,) * dim, e[0])
    elif dim == 3:
        phi = LevelSet(lambda x: np.hypot(x[0] - 0.5, x[1] - 0.5) - 0.3, 3, "penny")
    else:
        phi = LevelSet(lambda x: np.abs(x[0] - 0.5) - 0.3, 2, "centre")
    crack = Interface(plane((0.5,) * (dim - 1) + (z0,), e[-1]), law=law, front=phi,
                      **({"friction": 0.3} if law == "coulomb" else {}))
    top, bottom = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    load = (SurfaceLoad(top, traction=tuple(e[-1])) if law in ("free", "bonded")
            else SurfaceLoad(top, pressure=1.0))
    scene = Scene(Box((n,) * dim, cell), interfaces=(crack,), material=Material(1.0, 0.3),
                  displacements=(clamped(bottom),), loads=(load,))
elif kind == "inclined":  # inclined:cell:n:friction
    from skxfem.studies.cracks import inclined_scene
    scene = inclined_scene(n, 30.0, float(args[3]), cell=cell)[1]
elif cell == "tet":  # the paper's plate on tetrahedra
    hexes = scenes.paper_plate(n, cell="hex")
    scene = dataclasses.replace(hexes, mesh=Box(hexes.mesh.n, "tet"))
elif kind == "press":  # frictionless contact, pressed everywhere
    top, bottom = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    mid = (0.5,) * (dim - 1) + (0.5 + 0.5 / n,)  # mid-cell for an even n
    scene = Scene(Box((n,) * dim, cell), plane(mid, np.eye(dim)[-1]),
                  displacements=(clamped(bottom), Displacement(top, {"x": 0.0, "y": 0.0}
                                                               if dim == 3 else {"x": 0.0})),
                  loads=(SurfaceLoad(top, pressure=1.0),), law="frictionless")
else:
    scene = {"strip": scenes.strip, "plate": scenes.paper_plate}[kind](n, cell=cell)
est = budget.estimate(scene, linear)
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
r = solve(scene, linear=linear)
peak = status("VmHWM:")
if r.is_contact:  # a ContactResult: the sizes of its bilateral problem
    p = r.problem
    solved = r.linear
    r = dataclasses.make_dataclass("R", [])()
    r.mesh, r.n_dofs, r.V, r.n_multipliers = p.mesh, p.V.N, p.V, p.B.shape[0]
    r.removed, r.linear = 0, solved
print(json.dumps({"case": ":".join(args), "nodes": int(r.mesh.nvertices),
                  "cells": int(r.mesh.nelements), "N": int(r.n_dofs),
                  "n_enr": int(r.V.n_enr), "m": int(r.n_multipliers + r.removed),
                  **seen, "measured_MB": round((peak - before) / 2**20, 1),
                  "estimate_MB": round(est.bytes / 2**20, 1),
                  "ratio": round(est.bytes / (peak - before), 2), "linear": est.linear,
                  "solved": r.linear,
                  "bytes_per_unknown": round((peak - before)
                                             / (r.n_dofs + r.n_multipliers + r.removed)),
                  "est_nodes": est.n_nodes, "est_dofs": est.n_dofs,
                  "est_multipliers": est.n_multipliers}))
"""

if __name__ == "__main__":
    args = sys.argv[1:]
    linear = "auto"
    if args[:1] == ["--linear"]:
        linear, args = args[1], args[2:]
    for case in args:
        done = subprocess.run([sys.executable, "-c", CHILD, *case.split(":"), linear],
                              capture_output=True, text=True, check=False)
        print(done.stdout.strip() or done.stderr.strip().splitlines()[-1], flush=True)
