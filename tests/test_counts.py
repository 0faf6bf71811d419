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


@pytest.mark.parametrize("chunk", [10**6, 300])
def test_a_cracks_counts_in_one_sweep_are_those_of_three(chunk, monkeypatch):
    """box_crack_counts is box_counts, box_crack_depth and box_front_nodes (a penny in a
    Box of tetrahedra; one slab, and many when the slabs hold 300 nodes) and
    mesh_crack_counts the mesh's three on the built Box (the same depth and front nodes:
    they are the nodes'); in one slab and on the mesh ψ and φ are evaluated once at
    each node."""
    import numpy as np

    import skxfem.studies.counts as c
    from skxfem.levelset import LevelSet

    monkeypatch.setattr(c, "_CHUNK", chunk)
    calls = {"psi": 0, "phi": 0}

    def counted(name, f):
        def g(x):
            calls[name] += x.shape[1]
            return f(x)
        return LevelSet(g, 3, name)

    psi = counted("psi", lambda x: x[2] - 0.52)
    phi = counted("phi", lambda x: np.hypot(x[0] - 0.5, x[1] - 0.4) - 0.3)
    b = Box((9, 8, 7), "tet")

    def radius(depth):
        return 0.5 * depth + 0.1

    one = c.box_crack_counts(b, psi, phi, 0.2, radius)
    depth = c.box_crack_depth(b, psi, phi, 0.2)
    assert one == (c.box_counts(b, psi), depth, c.box_front_nodes(b, psi, phi, radius(depth)))
    assert 0 < one[2] < box_size(b)[0] and depth > 0
    m = box(b.n, "tet")
    calls.update(psi=0, phi=0)
    on_mesh = c.mesh_crack_counts(m, psi, phi, 0.2, radius)
    assert calls == {"psi": m.nvertices, "phi": m.nvertices}
    mesh_depth = c.mesh_crack_depth(m, psi, phi, 0.2)
    assert on_mesh == (c.mesh_counts(m, psi), mesh_depth,
                       c.mesh_front_nodes(m, psi, phi, radius(mesh_depth)))
    assert on_mesh[1:] == one[1:]
    calls.update(psi=0, phi=0)
    c.box_crack_counts(b, psi, phi, 0.2, radius)
    if chunk == 10**6:
        assert calls == {"psi": m.nvertices, "phi": m.nvertices}
