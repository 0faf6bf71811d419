"""Which linear solve a problem gets: direct (SuperLU) or iterative (AMG + projected CG).

The direct solve factorises the whole saddle matrix: simple, exact, and the
faster one on small systems, but its fill grows like dofs² in 3D.  The
iterative one (:mod:`skxfem.linalg.iterative`) grows like a plain elasticity solve;
it needs pyamg.  It solves the ties and each contact Newton step as one tie
(:mod:`skxfem.contact.step`), every law alike.

>>> choose_linear("auto", 2, 1000), choose_linear("direct", 3, 10**6)
('direct', 'direct')
"""
from __future__ import annotations

import importlib.util

from .scalars import is_number

__all__ = ["LINEAR", "AUTO_ITERATIVE", "AUTO_ZONE", "LINEAR_TOL", "choose_linear",
           "check_linear_tol"]

LINEAR = ("auto", "direct", "iterative")
"""The linear solves: SuperLU on the saddle system (:func:`skxfem.linalg.saddle.solve`),
AMG-preconditioned projected CG (:func:`skxfem.linalg.iterative.solve`, needs pyamg),
or ``auto``."""

AUTO_ITERATIVE = {2: 100_000, 3: 5_000}
"""``auto`` takes the iterative path from this many unknowns (per dimension),
when pyamg is installed: measured break-even on 2 cores, 3D near 3k unknowns
(5.5x faster at 17k), 2D near 100k (1.6x faster at 529k),
``benchmarks/tie_solve.py``."""

AUTO_ZONE = 0.7
"""``auto`` solves a 3D crack directly when its branch-enriched nodes are more than this
fraction of the mesh's nodes (``crack_zone``): the zone is then no tube but most of the
body, and projected CG stalls on the near dependence of the branch functions
(:func:`skxfem.crack.assembly.dependent_dofs`; exact when every node is enriched).
Measured on the unit cube of n³ × 6 tetrahedra with an edge crack to its middle and the
default r_e, on rollers with two nodes held (one run each): n = 7, 91 % enriched, 7 104
unknowns: CG stopped at 6.7e-6 after 500 iterations; n = 6, 82 %: 1.2e-12 after 500;
n = 9, 65 %: 1e-12 in 74; n = 8, 52 %: 48; n = 12, 25 %: 58.  A body clamped below (its
supports hold the branch unknowns too) converges even fully enriched (144 iterations),
and the direct solve costs it time there (``tests/test_linalg_blocks.py``'s cube at
n = 8, 78 %: 3.7 s against CG's 1.6 s): a zone that large means a coarse mesh, a small
system.  So :func:`skxfem.solver.solve_problem` gives CG a few iterations first there
(:data:`skxfem.solver.ZONE_ITERATIONS`) and solves directly only if it stalls."""

LINEAR_TOL = 1e-12
"""The relative residual the iterative solve reaches by default (``linear_tol``).
Measured (one run): a bonded block in uniform compression, 5 × 20 × 20
hexahedra, λ exact to 3.7e-10 at 1e-10 (36 CG iterations, 4.1 s), 1.8e-12 at
1e-12 (43, 4.6 s), 2.9e-13 at 1e-13 (46, 5.0 s); the direct solve 3.5e-14."""

def choose_linear(method: str, dim: int, n_unknowns: int, crack_multipliers: bool = False,
                  crack: bool = False, crack_zone: float = 0.0) -> str:
    """The linear solve ``method`` resolves to for ``n_unknowns`` in ``dim`` D:
    ``auto`` is ``iterative`` from :data:`AUTO_ITERATIVE` unknowns if pyamg is
    there, and ``direct`` whatever the size where multipliers (contact, a tie) live on
    a crack's faces (``crack_multipliers``): projected CG stalls there even with the
    crack's block scaling (:mod:`skxfem.linalg.blocks`; at 5e-3 on the inclined crack
    of :mod:`skxfem.studies.cracks3d`, 8 592 unknowns, and 5.5e-7 on
    ``pressed_slab(21, 3, "bonded")``).  ``direct`` too for a crack in 2D (``crack``):
    its branch zone (0.2 diameters, :mod:`skxfem.crack.radius`) is thousands of cells
    across at the sizes where ``auto`` would iterate, and CG stalls above the default
    tolerance (the edge crack of ``tests/test_linalg_blocks.py`` on 200 × 200 cells,
    161 274 unknowns: 6.9e-12 after 3000 iterations, one run; its LU 17 s), whereas a 3D
    crack's zone stays a tube a few cells across and CG reaches 1e-12 in about 60
    iterations (``benchmarks/crack_solve.py``) — unless the mesh is so coarse that the
    zone holds more than :data:`AUTO_ZONE` of its nodes (``crack_zone``, the largest
    fraction of a crack): then ``direct``.

    >>> choose_linear("auto", 2, 10**6, crack=True), choose_linear("iterative", 2, 10, crack=True)
    ('direct', 'iterative')
    >>> [choose_linear("auto", 3, 10**4, crack=True, crack_zone=z) for z in (0.3, 0.9)]
    ['iterative', 'direct']

    Raises
    ------
    ValueError
        An unknown ``method``.
    """
    if method not in LINEAR:
        raise ValueError(f"linear must be one of {LINEAR}, got {method!r}")
    if method != "auto":
        return method
    big = n_unknowns >= AUTO_ITERATIVE[dim] and not crack_multipliers \
        and not (crack and (dim == 2 or crack_zone > AUTO_ZONE))
    return "iterative" if big and importlib.util.find_spec("pyamg") else "direct"


def check_linear_tol(tol) -> float:
    """``tol`` as a float if it is a number in (0, 1), else a ValueError.

    >>> import numpy as np
    >>> check_linear_tol(1e-8), check_linear_tol(np.array(1e-8))   # numpy's numbers too
    (1e-08, 1e-08)
    """
    if not is_number(tol) or not 0 < tol < 1:
        raise ValueError(f"linear_tol must be a number in (0, 1), the relative residual of "
                         f"the iterative linear solve (default {LINEAR_TOL:g}), got {tol!r}")
    return float(tol)
