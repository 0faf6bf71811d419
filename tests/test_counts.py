"""skxfem.studies.counts: the sizes of a Box in exact integers, equal to the built mesh's."""
import math

import pytest

from skxfem.fem.meshes import box
from skxfem.scene import Box
from skxfem.studies.counts import box_size


@pytest.mark.parametrize("n", [1, 3, (2, 5), (2, 3, 4)])
def test_box_size_is_that_of_the_built_box(cell, n):
    dim = Box(1, cell).dim
    if isinstance(n, tuple) and len(n) != dim:
        n = (n * 2)[:dim]
    mesh = box(n, cell)
    assert box_size(Box(n, cell)) == (mesh.nvertices, mesh.nelements)


@pytest.mark.parametrize("n", [2**63 - 1, 3037000500, (4294967297, 4294967295), 10**200])
def test_box_size_is_exact_where_numpy_wraps(n):
    """np.prod gave 1, a negative number and -1 for the first three."""
    b = Box(n, "quad")
    nodes, cells = box_size(b)
    assert cells == math.prod(b.n) > 2**63 and nodes == math.prod(k + 1 for k in b.n)
    assert box_size(Box(n if isinstance(n, int) else n[0], "tet"))[1] % 6 == 0
