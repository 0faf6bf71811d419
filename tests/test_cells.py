"""skxfem.fem.cells: reference topology of the five cell types."""
import math

import numpy as np
import pytest
from skfem import MeshHex1, MeshQuad1, MeshTet1, MeshTri1, MeshWedge1

from skxfem.fem.cells import cell_edges, on_common_face, reference_simplices

MESHES = {"tri": MeshTri1, "quad": MeshQuad1, "tet": MeshTet1, "hex": MeshHex1,
          "prism": MeshWedge1}
VOLUME = {"tri": 0.5, "quad": 1.0, "tet": 1 / 6, "hex": 1.0, "prism": 0.5}
EDGES = {"tri": 3, "quad": 4, "tet": 6, "hex": 12, "prism": 9}


@pytest.mark.parametrize("cell", MESHES)
def test_reference_simplices_tile_the_reference_cell(cell):
    """The simplices use the cell's own vertices and their volumes add up exactly."""
    mesh = MESHES[cell]()
    ref = mesh.elem().doflocs
    S = ref[reference_simplices(mesh)]                    # (ns, dim + 1, dim)
    vol = np.abs(np.linalg.det(S[:, 1:] - S[:, :1])) / math.factorial(mesh.dim())
    assert np.all(vol > 0), "a degenerate simplex"
    assert vol.sum() == pytest.approx(VOLUME[cell], abs=1e-15)


@pytest.mark.parametrize("cell", MESHES)
def test_cell_edges_and_shared_faces(cell):
    mesh = MESHES[cell]()
    local, t2e, edges = cell_edges(mesh)
    assert local.shape == (EDGES[cell], 2) and t2e.shape[0] == EDGES[cell]
    # every local edge maps to a global edge with the same two vertices
    glob = np.sort(edges[:, t2e[:, 0]], axis=0)
    assert np.array_equal(glob, np.sort(mesh.t[local.T, 0], axis=0))
    share = on_common_face(mesh, local)
    assert np.array_equal(share, share.T) and share.diagonal().all()
    if mesh.dim() == 2:      # in 2D a facet is an edge: only itself
        assert np.array_equal(share, np.eye(len(local), dtype=bool))
