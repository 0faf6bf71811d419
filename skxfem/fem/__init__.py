"""Finite-element kernels on scikit-fem: meshes and their cells, simplex
clipping, quadrature (cut cells' sub-simplices, moment-fitted rules), the
bases of each side of Γ, the material, loads, evaluation, VTU pieces, checked
file reads and the exact solutions."""
