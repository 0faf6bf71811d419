"""skxfem: X-FEM with contact on an interface that cuts the mesh, on scikit-fem."""
__version__ = "0.1.0"
