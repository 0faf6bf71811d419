"""Measurement: the inf-sup constant of a *sticking* contact against the bonded tie.

A contact solve in which every dof sticks imposes [[u]]·n = 0 at the normal
dofs and [[u]]·t_a = 0 at the tangential dofs that no support holds.  This
script prints β_h of that constraint set and its zero modes (the multipliers
it cannot see), ``skxfem.lbb.inf_sup(scene, law="stick")``, next to β_h of
the bonded tie on the same scene: the paper's plate with the rollers on
x = 0 and 1, two layers of cells along x.

Each tangent has the tie's space of that component (on tetrahedra, where the
tie rebuilds the stars around the rollers' nodes for u_x, its multipliers are
placed at the normal dofs they overlap most: module notes of
:mod:`skxfem.contact.interface`), so the two agree to round-off on every
cell.  With ``--tilt`` Γ is tilted about e_y: the rollers then hold [[u]]·e_x,
a mix of the normal and t₁ jumps, and the tangent t₁ is held where the normal
is; the constraints differ from the tie's, and β_h shows whether they are as
stable.

    python benchmarks/contact_inf_sup.py                    # prism and tet, n = 3 5 7 9
    python benchmarks/contact_inf_sup.py --cells hex --n 3 5
    python benchmarks/contact_inf_sup.py --tilt 11.3   # Γ tilted about e_y: the rollers
                                                       # hold neither n nor a tangent
"""
from __future__ import annotations

import argparse
from dataclasses import replace

import numpy as np

from skxfem.lbb import inf_sup
from skxfem.levelset import plane
from skxfem.scene.benchmarks import paper_plate


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", nargs="+", default=["prism", "tet"],
                        choices=["hex", "prism", "tet"])
    parser.add_argument("--n", nargs="+", type=int, default=[3, 5, 7, 9])
    parser.add_argument("--space", default="vital", choices=["vital", "winner"])
    parser.add_argument("--tilt", type=float, default=0.0,
                        help="tilt Γ by this angle (degrees) about e_y")
    args = parser.parse_args(argv)
    print(f"{'cell':6} {'n':>3} {'contact β_h':>12} {'zero':>5} {'tie β_h':>9} {'zero':>5}")
    for cell in args.cells:
        for n in args.n:
            scene = paper_plate(n, cell, space=args.space, nx=2)
            if args.tilt:
                t = np.deg2rad(args.tilt)
                scene = replace(scene, levelset=plane((0.5, 0.5, 0.5),
                                                      (np.sin(t), 0.0, np.cos(t))))
            stick, tie = inf_sup(scene, law="stick"), inf_sup(scene, law="bonded")
            print(f"{cell:6} {n:3d} {stick.beta:12.4f} {stick.n_zero:5d} "
                  f"{tie.beta:9.4f} {tie.n_zero:5d}")


if __name__ == "__main__":
    main()
