"""The linear algebra of the solves: the direct saddle solve, the iterative
path (AMG, projected CG, the dependencies of B), which solve a problem
gets, BLAS threads, and the rigid motions a problem leaves free."""
