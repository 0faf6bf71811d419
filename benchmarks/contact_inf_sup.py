"""Measurement: the inf-sup constant of a *sticking* contact against the bonded tie.

A contact solve in which every dof sticks imposes [[u]]·n = 0 at the normal
dofs (rows ``Bn`` of :func:`skxfem.contact.interface.operators`) and
[[u]]·t_a = 0 at the tangential dofs that no support holds (rows ``Bt[a]``).
This script measures β_h of that constraint set, and its zero modes (the
multipliers it cannot see), in the norms :func:`skxfem.lbb.inf_sup` uses, next
to β_h of the bonded tie on the same scene: the paper's plate with the
rollers on x = 0 and 1, two layers of cells along x.

Where the tangent spaces are the tie's (hexahedra, prisms) the two must agree
to round-off.  On tetrahedra the tie rebuilds the stars around the rollers'
nodes for u_x, a space the contact cannot share with the pressure at the
same dofs (module notes of :mod:`skxfem.contact.interface`), and the
numbers say what that costs.

    python benchmarks/contact_inf_sup.py                    # prism and tet, n = 3 5 7 9
    python benchmarks/contact_inf_sup.py --cells hex --n 3 5
"""
from __future__ import annotations

import argparse

import numpy as np
import scipy.sparse as sp

from skxfem.contact.interface import operators
from skxfem.enrich import mass
from skxfem.lbb import inf_sup, inf_sup_constant
from skxfem.problem import assemble
from skxfem.scene.benchmarks import paper_plate


def sticking_inf_sup(scene):
    """β_h of the constraints of a contact where every dof sticks
    (:class:`skxfem.lbb.InfSup`), scaled as :func:`skxfem.lbb.inf_sup` scales it."""
    p = assemble(scene, law="bilateral")
    ops = operators(p)
    length = np.ptp(p.mesh.p, axis=1).max()
    A = p.K + (scene.material.E / length ** 2) * mass(p.V)
    free = np.setdiff1d(np.arange(p.V.N), p.D)
    a, b = p.cut.edges
    h = float(np.mean(np.linalg.norm(p.mesh.p[:, a] - p.mesh.p[:, b], axis=0)))
    rows, masses = [ops.Bn], [p.P.T @ p.M_edges @ p.P]
    for k, Bt in enumerate(ops.Bt):
        dofs = np.flatnonzero(~ops.tangent_held[:, k])
        rows.append(Bt[dofs])
        Pk = ops.Pt[k][:, dofs]
        masses.append(Pk.T @ p.M_edges @ Pk)
    B = sp.vstack(rows, format="csr")
    return inf_sup_constant(A[free][:, free], B[:, free], sp.block_diag(masses) * h, h=h)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", nargs="+", default=["prism", "tet"],
                        choices=["hex", "prism", "tet"])
    parser.add_argument("--n", nargs="+", type=int, default=[3, 5, 7, 9])
    parser.add_argument("--space", default="vital", choices=["vital", "winner"])
    args = parser.parse_args(argv)
    print(f"{'cell':6} {'n':>3} {'contact β_h':>12} {'zero':>5} {'tie β_h':>9} {'zero':>5}")
    for cell in args.cells:
        for n in args.n:
            scene = paper_plate(n, cell, space=args.space, nx=2)
            stick, tie = sticking_inf_sup(scene), inf_sup(scene, law="bonded")
            print(f"{cell:6} {n:3d} {stick.beta:12.4f} {stick.n_zero:5d} "
                  f"{tie.beta:9.4f} {tie.n_zero:5d}")


if __name__ == "__main__":
    main()
