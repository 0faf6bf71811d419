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

``crack:cell:n:shape:pos:law`` is a crack on the unit square or cube of n cells a side:
ψ = y - y0 (3D: z - z0) on the node plane y0 = (n // 2) / n (``node``) or mid-cell
(``mid``), the front φ = x - 0.5 (``edge``, to the middle) or a centre crack |x - 0.5| <
0.3 (2D) / a penny of radius 0.3 (3D) (``centre``, ``penny``), the bottom clamped, the top
pulled (``free``, ``bonded``) or pressed (``frictionless``, ``coulomb`` with μ = 0.3);
``inclined:cell:n:mu`` is :func:`skxfem.studies.cracks.inclined_scene` (30°, two tips).

Later on 29 November the 3D default r_e took the front cells' cross-section
(:func:`skxfem.crack.space3d.cross_section`, h√2 for these cubes) instead of the nodes'
distance to the front (0.71 h with the plane through the middle of the cells): the
``mid`` zones are about twice as wide, the ``node`` ones 11 % wider.  Measured then
(case: N, peak / estimate MB, ratio): tet:11:edge:mid:frictionless 19 008, 1944 / 3444,
1.77; tet:9:penny:mid:coulomb 15 000, 1171 / 2109, 1.80; tet:13:edge:mid:bonded 24 444,
2808 / 4618, 1.64; tet:10:edge:node:frictionless 17 325, 1575 / 2471, 1.57;
tet:7:edge:mid:frictionless 7680, 416 / 802, 1.93; tet:9:edge:mid:free (CG) 13 560,
226 / 1559, 6.89.  The table below is from before.

The crack sweep of 29 November 2026 (one process per case, one at a time, ``--linear
auto`` as ``skxfem run``; the peak is the solve's, ``before`` the estimate of main at
68a947a, ``now`` this one; N and m the solve's and the estimate's; solve the linear solve
auto took, est the one priced (i iterative, d direct: with a CG try first where auto may
fall back to it); peak and estimates in MB; fricl: frictionless), measured by
``python scripts/calibrate_budget.py CASE ...`` with the cases below::

    case                            N solve/est  m s/est lin  peak  before (x)    now (x)
    tet:6:edge:node:free         5145/5145     0/0    i/d    88     52 ( 0.6)   350 (3.96)
    tet:6:edge:node:fricl        5145/5145    21/63   d/d   210   1113 ( 5.3)   430 (2.05)
    tet:6:edge:node:coulomb      5145/5145    21/63   d/d   206   1113 ( 5.4)   430 (2.09)
    tet:6:edge:node:bonded       5145/5145    63/63   d/d   173   1113 ( 6.4)   430 (2.48)
    tet:6:edge:mid:free          4977/4977     0/0    d/d   116     51 ( 0.4)   330 (2.85)
    tet:6:edge:mid:fricl         4977/4977    21/234  d/d   221    702 ( 3.2)   423 (1.91)
    tet:6:edge:mid:coulomb       4977/4977    21/234  d/d   210    702 ( 3.4)   423 (2.02)
    tet:6:edge:mid:bonded        4977/4977    63/234  d/d   196    702 ( 3.6)   423 (2.15)
    tet:6:penny:node:free        5145/5145     0/0    i/d    74     52 ( 0.7)   350 (4.72)
    tet:6:penny:node:fricl       5145/5145     9/27   d/d   254   1113 ( 4.4)   426 (1.68)
    tet:6:penny:node:coulomb     5145/5145     9/27   d/d   250   1113 ( 4.5)   426 (1.70)
    tet:6:penny:node:bonded      5145/5145    27/27   d/d   224   1113 ( 5.0)   426 (1.90)
    tet:6:penny:mid:free         4461/4749     0/0    d/d   139     51 ( 0.4)   304 (2.20)
    tet:6:penny:mid:fricl        4461/4749    13/111  d/d   270    702 ( 2.6)   377 (1.40)
    tet:6:penny:mid:coulomb      4461/4749    13/111  d/d   221    702 ( 3.2)   377 (1.70)
    tet:6:penny:mid:bonded       4461/4749    39/111  d/d   202    702 ( 3.5)   377 (1.86)
    tet:8:edge:node:free        10503/10503    0/0    i/d   148    110 ( 0.7)   965 (6.50)
    tet:8:edge:node:fricl       10503/10503   36/108  d/d   702   4030 ( 5.7)  1209 (1.72)
    tet:8:edge:node:coulomb     10503/10503   36/108  d/d   681   4030 ( 5.9)  1209 (1.78)
    tet:8:edge:node:bonded      10503/10503  108/108  d/d   621   4030 ( 6.5)  1209 (1.95)
    tet:8:edge:mid:free          8667/8775     0/0    i/d   144    107 ( 0.7)   699 (4.84)
    tet:8:edge:mid:fricl         8667/8775    36/408  d/d   558   2699 ( 4.8)   914 (1.64)
    tet:8:edge:mid:coulomb       8667/8775    36/408  d/d   558   2699 ( 4.8)   914 (1.64)
    tet:8:edge:mid:bonded        8667/8775   108/408  d/d   507   2699 ( 5.3)   914 (1.80)
    tet:8:penny:node:free       10839/10839    0/0    i/d   154    110 ( 0.7)  1021 (6.65)
    tet:8:penny:node:fricl      10839/10839   21/63   d/d   670   4030 ( 6.0)  1272 (1.90)
    tet:8:penny:node:coulomb    10839/10839   21/63   d/d   668   4030 ( 6.0)  1272 (1.90)
    tet:8:penny:node:bonded     10839/10839   63/63   d/d   607   4030 ( 6.6)  1272 (2.09)
    tet:8:penny:mid:free         8979/9267     0/0    i/d   182    107 ( 0.6)   771 (4.23)
    tet:8:penny:mid:fricl        8979/9267    22/207  d/d   595   2699 ( 4.5)   974 (1.64)
    tet:8:penny:mid:coulomb      8979/9267    22/207  d/d   589   2699 ( 4.6)   974 (1.65)
    tet:8:penny:mid:bonded       8979/9267    66/207  d/d   532   2699 ( 5.1)   974 (1.83)
    tri:21:edge:mid:free         1884/1884     0/0    d/d    18     97 ( 5.4)    25 (1.38)
    tri:22:edge:node:free        2036/2056     0/0    d/d    19     97 ( 5.2)    27 (1.46)
    tri:21:centre:mid:fricl      2664/2728    13/50   d/d    33    201 ( 6.1)    81 (2.45)
    inclined:tri:21:0.0          2664/2744    10/38   d/d    37    205 ( 5.6)    82 (2.23)
    inclined:tri:21:0.3          2664/2744    10/38   d/d    60    205 ( 3.4)   136 (2.26)
    quad:21:edge:mid:free        1884/1884     0/0    d/d    20     98 ( 5.0)    26 (1.32)
    quad:22:edge:node:free       2036/2056     0/0    d/d    19     98 ( 5.2)    28 (1.49)
    quad:21:centre:mid:fricl     2664/2728    12/24   d/d    47    195 ( 4.1)    82 (1.72)
    inclined:quad:21:0.0         2664/2744    10/32   d/d    43    210 ( 4.9)    83 (1.93)
    inclined:quad:21:0.3         2664/2744    10/32   d/d    68    210 ( 3.1)   136 (2.01)
    tri:41:edge:mid:free         6956/7020     0/0    d/d    70    414 ( 5.9)   111 (1.59)
    tri:42:edge:node:free        7214/7254     0/0    d/d    70    449 ( 6.4)   113 (1.61)
    tri:41:centre:mid:fricl      9808/9872    25/98   d/d   168   1203 ( 7.2)   370 (2.21)
    inclined:tri:41:0.0         10104/10280   18/70   d/d   198   1314 ( 6.7)   397 (2.01)
    inclined:tri:41:0.3         10104/10280   18/70   d/d   362   1314 ( 3.6)   689 (1.91)
    quad:41:edge:mid:free        6956/7020     0/0    d/d    74    418 ( 5.7)   115 (1.55)
    quad:42:edge:node:free       7214/7254     0/0    d/d    72    453 ( 6.3)   117 (1.62)
    quad:41:centre:mid:fricl     9808/9872    24/48   d/d   250   1170 ( 4.7)   372 (1.49)
    inclined:quad:41:0.0        10104/10280   18/56   d/d   262   1340 ( 5.1)   401 (1.53)
    inclined:quad:41:0.3        10104/10280   18/56   d/d   459   1340 ( 2.9)   692 (1.51)
    tri:81:edge:mid:free        26768/26832    0/0    d/d   304   4418 (14.5)   516 (1.70)
    tri:82:edge:node:free       27294/27494    0/0    d/d   334   4743 (14.2)   530 (1.59)
    tri:81:centre:mid:fricl     37776/37936   49/194  d/d   971  14126 (14.6)  1878 (1.93)
    inclined:tri:81:0.0         39112/39400   36/142  d/d  1098  15614 (14.2)  2013 (1.83)
    inclined:tri:81:0.3         39112/39400   36/142  d/d  2012  15614 ( 7.8)  3620 (1.80)
    quad:81:edge:mid:free       26768/26832    0/0    d/d   323   4433 (13.7)   531 (1.64)
    quad:82:edge:node:free      27294/27494    0/0    d/d   362   4759 (13.2)   546 (1.51)
    quad:81:centre:mid:fricl    37776/37936   48/96   d/d  1257  13894 (11.1)  1887 (1.50)
    inclined:quad:81:0.0        39112/39400   36/112  d/d  1485  15769 (10.6)  2027 (1.37)
    inclined:quad:81:0.3        39112/39400   36/112  d/d  2708  15769 ( 5.8)  3633 (1.34)
    tet:10:edge:node:free       15741/15741    0/0    i/d   233    198 ( 0.8)  1636 (7.02)
    tet:10:edge:node:fricl      15741/15741   55/165  d/d  1386  11475 ( 8.3)  2070 (1.49)
    tet:10:edge:node:coulomb    15741/15741   55/165  d/d  1394  11475 ( 8.2)  2070 (1.48)
    tet:10:edge:node:bonded     15741/15741  165/165  d/d  1352  11475 ( 8.5)  2070 (1.53)
    tet:10:edge:mid:free        11979/12243    0/0    i/i   178    194 ( 1.1)   315 (1.77)
    tet:10:edge:mid:fricl       11979/12243   55/630  d/d   923   8063 ( 8.7)  1375 (1.49)
    tet:11:edge:mid:fricl        8856/8856    72/759  d/d   440  13025 (29.6)   718 (1.63)
    tet:10:penny:node:fricl     17061/17541   25/75   d/d  1582  11475 ( 7.2)  2504 (1.58)
    tet:10:penny:mid:free       13857/14145    0/0    i/i   282    194 ( 0.7)   381 (1.35)
    tet:12:edge:mid:free        16107/16419    0/0    i/i   213    316 ( 1.5)   390 (1.83)
    tet:12:edge:mid:fricl       16107/16419   78/900  d/d  1316  19912 (15.1)  1994 (1.51)
    tet:12:penny:mid:fricl      17655/17847   48/477  d/d  1518  20298 (13.4)  2225 (1.47)
    tet:14:edge:mid:free        21195/21555    0/0    i/i   253    457 ( 1.8)   475 (1.88)
    tet:13:edge:mid:fricl       12600/12600   98/1053 d/d   645  29656 (46.0)  1164 (1.81)
    tet:16:edge:mid:free        27387/27795    0/0    i/i   292    597 ( 2.0)   570 (1.95)
    tet:20:edge:mid:free        43659/44163    0/0    i/i   395    839 ( 2.1)   796 (2.01)
    tet:14:edge:mid:coulomb     21195/21555  105/1218 d/d  1982  39332 (19.9)  2852 (1.44)
    tet:12:edge:node:bonded     20514/20592  234/234  d/d  2144  27798 (13.0)  2858 (1.33)
    tet:16:edge:mid:fricl       27387/27795  136/1584 d/d  2502  62872 (25.1)  4023 (1.61)
    tet:14:penny:mid:bonded     26259/26547  192/663  d/d  2622  44688 (17.0)  4006 (1.53)
    press:hex:12                 7605/7605   169/507  i/i    63    101 ( 1.6)   101 (1.60)
    press:tet:8                  2916/2916   225/1875 d/d    50    230 ( 4.6)   230 (4.63)
    plate:tet:9                  3600/3600   280/2352 d/d    62    336 ( 5.4)   336 (5.41)
    tri:41:edge:mid:fricl        6956/7020    21/82   d/d    90    447 ( 5.0)   194 (2.15)
    quad:41:edge:mid:coulomb     6956/7020    21/42   d/d   121    428 ( 3.5)   333 (2.76)
    tri:81:edge:node:fricl      26620/26852   41/82   d/d   536   5042 ( 9.4)   967 (1.80)
    quad:61:edge:mid:bonded     15232/15296   62/62   d/d   321   1630 ( 5.1)   498 (1.55)
    tri:61:centre:mid:free      21488/21616    0/0    d/d   267   4830 (18.1)   507 (1.90)
    inclined:tri:61:0.3         22280/22488   26/106  d/d   940   5483 ( 5.8)  1808 (1.92)
    tet:12:edge:node:coulomb    20514/20592   78/234  d/d  2163  27798 (12.8)  2858 (1.32)
    tet:12:penny:node:fricl     23547/24435   37/111  d/d  2737  27798 (10.2)  3894 (1.42)
    tet:12:penny:mid:coulomb    17655/17847   48/477  d/d  1515  20298 (13.4)  2225 (1.47)
    tet:9:edge:mid:bonded        6000/6000   150/513  d/d   257   4785 (18.6)   428 (1.66)
    tet:7:penny:node:coulomb     7680/7680    12/36   d/d   427   2198 ( 5.2)   764 (1.79)

The free 3D cracks whose zone holds most of the coarse cube (n = 6-10: i/d) are priced
for the direct solve auto falls back to when its CG stalls (skxfem.solver), hence 4-7
times the peak of the CG that converged; forced direct (``--linear direct``), their
peaks were 540 MB at n = 8 (edge, node plane) and 1049 MB at n = 10, estimated 965 and
1636 MB (1.79, 1.56).  Every other crack is 1.32-2.85 times its peak.  The rows
press:hex:12, press:tet:8 and plate:tet:9 (contact and a tie across the whole body)
keep the estimates of before.
Tetrahedral cubes only: 3D cracks take tetrahedra.
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
