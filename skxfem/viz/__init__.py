"""Drawing (matplotlib, pyvista): plots, the paper's figures, the schematics,
3D renders."""
