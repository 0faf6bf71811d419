"""Measurements: convergence, the 3D validation, the conforming FEM
reference, the speed-accuracy frontier, the table of extremes, the size
guard and progress lines."""
