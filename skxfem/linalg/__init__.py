"""The linear algebra of the solves: the direct saddle solve, the iterative
path (AMG, projected CG, the dependencies of B), which solve a problem
gets, BLAS threads, the rigid motions a problem leaves free, and what every
argument takes for a number (:mod:`~skxfem.linalg.scalars`)."""
