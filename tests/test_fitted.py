"""skxfem.fem.fitted: the fitted rules integrate their polynomial space exactly.

1. On every cut cell of a slanted plane (hexahedra, prisms), the fitted rule of
   each side integrates every monomial of its space as the sub-simplex rule of
   high order does, to round-off; the two sides add up to the whole cell.
2. Off its space it is not exact (x³ on hexahedra): the test can fail.
3. Cells without a fitted rule (tri, quad, tet) get None.
"""
import numpy as np
import pytest

from skxfem.cut import cut
from skxfem.fem.fitted import FITTED, _monomials, fitted_rule
from skxfem.fem.meshes import box
from skxfem.fem.quadrature import subcell_rule
from skxfem.levelset import plane


def _cut(cell):
    mesh = box(3, cell)
    return mesh, cut(mesh, plane((0.41, 0.47, 0.52), (0.3, 0.2, 1.0)))


@pytest.mark.parametrize("cell", ["hex", "prism"])
def test_exact_on_its_space_and_the_sides_add_up(cell):
    mesh, c = _cut(cell)
    exps, _, order = FITTED[mesh.elem().refdom]
    whole = 0
    for s in (-1, 1):
        rule = fitted_rule(c, s, mesh.elem().refdom)
        sub = c.sub_side == s
        ref = subcell_rule(c.sub_ref[sub], c.sub_cell[sub], order + 2)
        assert np.array_equal(rule.cells, ref.cells)
        fitted = np.einsum("kcq,cq->ck", _monomials(exps, rule.X), rule.W)
        exact = np.einsum("kcq,cq->ck", _monomials(exps, ref.X), ref.W)
        assert np.abs(fitted - exact).max() < 1e-13
        whole = whole + rule.W.sum(axis=1)
    assert np.allclose(whole, 1.0 if cell == "hex" else 0.5, atol=1e-13)


def test_not_exact_off_its_space():
    mesh, c = _cut("hex")
    rule = fitted_rule(c, 1, mesh.elem().refdom)
    sub = c.sub_side == 1
    ref = subcell_rule(c.sub_ref[sub], c.sub_cell[sub], 8)
    cube = np.array([[3, 0, 0]])
    fitted = np.einsum("kcq,cq->ck", _monomials(cube, rule.X), rule.W)
    exact = np.einsum("kcq,cq->ck", _monomials(cube, ref.X), ref.W)
    assert np.abs(fitted - exact).max() > 1e-6


@pytest.mark.parametrize("cell", ["tri", "quad", "tet"])
def test_no_fitted_rule(cell):
    mesh = box(3, cell)
    c = cut(mesh, plane((0.41,) * mesh.dim(), (0.3,) + (1.0,) * (mesh.dim() - 1)))
    assert fitted_rule(c, 1, mesh.elem().refdom) is None
