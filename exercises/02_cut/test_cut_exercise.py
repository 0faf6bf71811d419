"""Exercise 02, cutting: make these pass in order (``pytest exercises/02_cut``)."""
import math

import numpy as np
from skfem import MeshTri1

ASKED = ("cut_edges", "intersection_points", "subcell_volumes")
LIBRARY = ("skxfem.cut", "skxfem.fem.simplex")   # they hold the answers: write your own

#  3 ---- 2       two triangles of the unit square, ψ at the vertices
#  | \    |       0: -0.5, 1: 0.5, 2: 1.5, 3: 0.5  (ψ = x + y - 0.5)
#  |   \  |
#  0 ---- 1       edges: (0,1) (1,2) (2,3) (3,0) (1,3)
SQUARE = np.array([[0.0, 1.0, 1.0, 0.0], [0.0, 0.0, 1.0, 1.0]])
EDGES = np.array([[0, 1, 2, 3, 1], [1, 2, 3, 0, 3]])
PSI = SQUARE.sum(axis=0) - 0.5


def pair(edges, e):
    return f"({edges[0, e]}, {edges[1, e]})"


def check_cut_edges(impl, edges, psi):
    got = np.asarray(impl.cut_edges(edges, psi)).ravel()
    want = np.flatnonzero(psi[edges[0]] * psi[edges[1]] < 0)
    for e in got:
        assert 0 <= e < edges.shape[1], (
            f"cut_edges returned index {e}, but there are only {edges.shape[1]} edges "
            f"(0..{edges.shape[1] - 1}): are your indices off by one?")
        assert e in want, (
            f"cut_edges returned edge {e} = {pair(edges, e)}, whose vertices have ψ = "
            f"{psi[edges[:, e]].tolist()}: it is not cut"
            + (" (it only touches Γ at a vertex: S_e needs ψ_a ψ_b < 0, strictly)"
               if 0.0 in psi[edges[:, e]] else " (ψ has the same sign at both ends)"))
    for e in want:
        assert e in got, (f"edge {e} = {pair(edges, e)} has ψ = {psi[edges[:, e]].tolist()} of "
                          f"opposite signs: it is cut, but cut_edges did not return it")
    assert np.array_equal(got, want), f"return the indices in increasing order: {want.tolist()}"


def test_01_cut_edges_of_two_triangles(impl):
    check_cut_edges(impl, EDGES, PSI)


def test_02_an_edge_touching_gamma_is_not_cut(impl):
    psi = np.array([-1.0, 0.0, 1.0, 2.0])            # Γ passes through vertex 1
    check_cut_edges(impl, EDGES, psi)


def test_03_cut_edges_of_a_mesh(impl):
    mesh = MeshTri1().refined(2)
    psi = 0.6 * mesh.p[0] + 0.8 * mesh.p[1] - 0.53
    check_cut_edges(impl, mesh.facets, psi)


def check_points(impl, nodes, edges, psi, exact=None):
    got = np.asarray(impl.intersection_points(nodes, edges, psi), dtype=float)
    assert got.shape == (nodes.shape[0], edges.shape[1]), (
        f"intersection_points must return shape (dim, ne) = "
        f"{(nodes.shape[0], edges.shape[1])}, got {got.shape}")
    for e in range(edges.shape[1]):
        a, b = edges[:, e]
        x = got[:, e]
        ab = nodes[:, b] - nodes[:, a]
        s = np.dot(x - nodes[:, a], ab) / np.dot(ab, ab)
        assert np.allclose(nodes[:, a] + s * (nodes[:, b] - nodes[:, a]), x, atol=1e-12) \
            and -1e-12 <= s <= 1 + 1e-12, (
            f"the intersection point of edge {pair(edges, e)} is at {np.round(x, 4).tolist()}, "
            f"which is not on the segment from {nodes[:, a].tolist()} to {nodes[:, b].tolist()}")
        psi_h = psi[a] + s * (psi[b] - psi[a])       # the linear interpolant of ψ there
        assert abs(psi_h) < 1e-12, (
            f"the intersection point of edge {pair(edges, e)} is at {np.round(x, 4).tolist()}, "
            f"but ψ_h there is {psi_h:.3g}; it should be 0 (t = ψ_a / (ψ_a - ψ_b) from "
            f"vertex a = {a})")
        if exact is not None:
            assert abs(exact(x)) < 1e-12, (
                f"the intersection point of edge {pair(edges, e)} is at "
                f"{np.round(x, 4).tolist()}, but ψ there is {exact(x):.3g}; it should be 0")


def test_04_points_of_two_triangles(impl):
    cut = np.flatnonzero(PSI[EDGES[0]] * PSI[EDGES[1]] < 0)
    check_points(impl, SQUARE, EDGES[:, cut], PSI)


def test_05_points_lie_on_a_plane_interface(impl):
    mesh = MeshTri1().refined(3)
    psi = 0.6 * mesh.p[0] + 0.8 * mesh.p[1] - 0.53     # a plane: ψ_h = ψ exactly
    edges = mesh.facets[:, psi[mesh.facets[0]] * psi[mesh.facets[1]] < 0]
    check_points(impl, mesh.p, edges, psi, exact=lambda x: 0.6 * x[0] + 0.8 * x[1] - 0.53)


def volumes(impl, X, psi):
    got = impl.subcell_volumes(np.asarray(X, float), np.asarray(psi, float))
    assert len(got) == 2, "subcell_volumes returns two numbers, (v_minus, v_plus)"
    return float(got[0]), float(got[1])


def check_volumes(impl, X, psi, want_minus, want_plus, what):
    vm, vp = volumes(impl, X, psi)
    if abs(vm - want_plus) < 1e-12 and abs(vp - want_minus) < 1e-12 and want_minus != want_plus:
        raise AssertionError(
            f"{what} with ψ = {list(psi)}: Ω⁻ and Ω⁺ are swapped, got v_minus = {vm:.6g} and "
            f"v_plus = {vp:.6g}; Ω⁻ is where ψ < 0")
    assert abs(vm - want_minus) < 1e-12 and abs(vp - want_plus) < 1e-12, (
        f"{what} with ψ = {list(psi)}: the part in Ω⁻ measures {want_minus:.6g} and the part "
        f"in Ω⁺ {want_plus:.6g}; got {vm:.6g} and {vp:.6g}")


TRI = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
TET = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]


def test_06_volumes_add_up_to_the_simplex(impl):
    rng = np.random.default_rng(2)
    for d in (2, 3):
        for _ in range(20):
            X = rng.random((d + 1, d))
            psi = rng.normal(size=d + 1)
            total = abs(np.linalg.det(X[1:] - X[0])) / math.factorial(d)
            vm, vp = volumes(impl, X, psi)
            assert vm >= -1e-14 and vp >= -1e-14, f"a measure cannot be negative: {vm}, {vp}"
            assert abs(vm + vp - total) < 1e-12, (
                f"the two parts of a {'triangle' if d == 2 else 'tetrahedron'} of measure "
                f"{total:.6g} must add up to it; got {vm:.6g} + {vp:.6g} (ψ = "
                f"{np.round(psi, 3).tolist()})")


def test_07_cut_triangle(impl):
    # the lone vertex 0 keeps a triangle with legs t = 1/2 and 1/4: area 1/16
    check_volumes(impl, TRI, [-1.0, 1.0, 3.0], 1 / 16, 7 / 16, "the triangle (0,0) (1,0) (0,1)")
    check_volumes(impl, TRI, [1.0, -1.0, -3.0], 7 / 16, 1 / 16, "the triangle (0,0) (1,0) (0,1)")


def test_08_cut_tetrahedron_one_vertex_alone(impl):
    # the lone vertex keeps a tetrahedron with legs 1/2, 1/4, 1/4: volume 1/6 · 1/32
    check_volumes(impl, TET, [-1.0, 1.0, 3.0, 3.0], 1 / 192, 31 / 192, "the unit tetrahedron")
    check_volumes(impl, TET, [1.0, -1.0, -3.0, -3.0], 31 / 192, 1 / 192, "the unit tetrahedron")


def test_09_cut_tetrahedron_two_against_two(impl):
    # ψ_h = -1 + 4y + 4z: Ω⁻ = {y + z < 1/4}, of volume ∫_0^1/4 (1 - s) s ds = 5/192
    check_volumes(impl, TET, [-1.0, -1.0, 3.0, 3.0], 5 / 192, 27 / 192, "the unit tetrahedron")
