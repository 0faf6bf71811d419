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
def test_a_cracks_counts_on_a_box_are_those_of_the_built_box(chunk, monkeypatch):
    """box_crack_counts (one slab, and many when the slabs hold 300 nodes) counts what
    mesh_crack_counts counts on the built Box (a penny on tetrahedra: the cubes hold
    the tetrahedra, so the crack and front nodes are bounds, the rest equal); in one slab
    and on the mesh ψ and φ are evaluated once at each node."""
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

    def radius(depth, h):
        return 0.5 * depth + h

    one = c.box_crack_counts(b, psi, phi, radius)
    m = box(b.n, "tet")
    calls.update(psi=0, phi=0)
    on_mesh = c.mesh_crack_counts(m, psi, phi, radius)
    assert calls == {"psi": m.nvertices, "phi": m.nvertices}
    assert (one.nodes, one.cells, one.points, one.depth) == \
        (on_mesh.nodes, on_mesh.cells, on_mesh.points, on_mesh.depth)
    assert np.isclose(one.front_size, on_mesh.front_size) and one.branch == on_mesh.branch
    assert one.crack_nodes >= on_mesh.crack_nodes and one.front_nodes >= on_mesh.front_nodes
    assert 0 < one.branch < one.nodes and one.depth > 0 and one.points > 0
    calls.update(psi=0, phi=0)
    c.box_crack_counts(b, psi, phi, radius)
    if chunk == 10**6:
        assert calls == {"psi": m.nvertices, "phi": m.nvertices}


@pytest.mark.parametrize("n, z0, front", [(6, 0.5, "edge"), (7, 0.5, "edge"),
                                          (6, 0.52, "penny"), (8, 0.5, "penny")])
def test_a_cracks_counts_are_its_space_and_points(n, z0, front):
    """On a cube of tetrahedra, the crack and the node plane or not: the branch and
    Heaviside nodes and r_e are those of skxfem.crack.space3d (r_e to 0.2 %: the space
    snaps its nodal values and takes its front cells to round-off) (the zone as
    skxfem.crack.radius builds it, found from the nodes), the points those the crack
    carries (its own cut points behind the front; before, every edge the whole plane
    ψ = 0 touched: 2342 for 55 at n = 10)."""
    import numpy as np

    from skxfem.crack.geometry3d import crack_geometry_3d
    from skxfem.crack.radius import default_radius
    from skxfem.crack.space3d import crack_space_3d
    from skxfem.levelset import LevelSet, plane
    from skxfem.studies.counts import box_crack_counts

    psi = plane((0.5, 0.5, z0), (0, 0, 1))
    phi = plane((0.5, 0.5, 0.5), (1, 0, 0)) if front == "edge" else \
        LevelSet(lambda x: np.hypot(x[0] - 0.5, x[1] - 0.5) - 0.3, 3, "penny")
    counts = box_crack_counts(Box(n, "tet"), psi, phi,
                              lambda depth, h: default_radius(3, depth, h))
    m = box(n, "tet")
    g = crack_geometry_3d(m, psi, phi)
    V = crack_space_3d(m, g)
    assert np.isclose(counts.radius, V.radius, rtol=2e-3)      # its snapped nodal values
    assert V.branch.size <= counts.branch <= 1.1 * V.branch.size
    assert counts.heaviside >= V.heaviside.size
    assert g.points.shape[1] <= counts.points <= 2 * g.points.shape[1]
