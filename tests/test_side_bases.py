"""skxfem.fem.side_bases: the two ways of covering the sides of Γ give one X-FEM matrix.

1. parts: A_H = s(2Aˢ - A) equals A⁺ - A⁻ of side_bases in every column of an
   enriched node, and A (every cell whole) equals A⁺ + A⁻, on all five cells
   and for a slanted plane (cut cells of many shapes).
2. The side integrated on its own is the one with fewer sub-simplices, and its
   bases cover only cells that hold an enriched node.
"""
import numpy as np
from skfem import BilinearForm

from skxfem.cut import cut
from skxfem.fem.meshes import box
from skxfem.fem.side_bases import parts, side_bases
from skxfem.levelset import plane


@BilinearForm
def _grad_grad(u, v, w):
    return sum(u.grad[i] * v.grad[i] for i in range(u.grad.shape[0]))


def _slanted(cell):
    mesh = box(4, cell)
    dim = mesh.dim()
    normal = (0.3, 1.0) if dim == 2 else (0.3, 0.2, 1.0)
    return mesh, cut(mesh, plane((0.43,) * dim, normal))


def test_parts_give_the_side_sums_on_the_columns_of_enriched_nodes(cell):
    mesh, c = _slanted(cell)
    A = AH = 0
    for b, s in side_bases(mesh, c, mesh.elem()):
        part = _grad_grad.assemble(b)
        A, AH = A + part, AH + s * part
    A2, AH2 = parts(mesh, c, mesh.elem()).signed(_grad_grad.assemble)
    scale = abs(A).max()
    assert abs(A2 - A).max() < 1e-13 * scale
    E = c.enriched
    assert abs(AH[:, E]).max() > 0.1 * scale
    assert abs((AH2 - AH).tocsc()[:, E]).max() < 1e-13 * scale


def test_one_side_near_the_enriched_nodes(cell):
    mesh, c = _slanted(cell)
    p = parts(mesh, c, mesh.elem())
    counts = {s: int(np.sum(c.sub_side == s)) for s in (-1, 1)}
    assert counts[p.side] <= counts[-p.side]
    assert p.whole.nelems == mesh.t.shape[1]
    holds = np.zeros(mesh.p.shape[1], dtype=bool)
    holds[c.enriched] = True
    for b in p.near:
        assert holds[mesh.t[:, b.tind]].any(axis=0).all()
