"""skxfem.viz.schematics: the paper's Figures 1-4 drawn from the library's objects."""
import re

import numpy as np
import pytest
from matplotlib.figure import Figure

from skxfem.viz.plotting import COLORS
from skxfem.viz.schematics import fig1, fig2, fig3, fig4


def texts(fig):
    """Every text of the figure: axes texts, titles and legend labels."""
    found = [fig.texts]
    for ax in fig.axes:
        found += [ax.texts, [ax.title]]
        if ax.get_legend():
            found.append(ax.get_legend().get_texts())
    found += [legend.get_texts() for legend in fig.legends]
    return " | ".join(t.get_text() for group in found for t in group)


def test_figure1_names_the_notation():
    fig = fig1()
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    shown = texts(fig)
    for name in ("Ω¹ = Ω⁻", "Ω² = Ω⁺", "(ψ < 0)", "(ψ > 0)", "n = ∇ψ/|∇ψ|", "Γ_u", "Γ_t",
                 "Γ_c = Γ = {ψ = 0}", "n_ext", "n¹ = n", "n² = -n", "r¹ = r", "r² = -r",
                 "p¹", "p²", "Γ¹", "Γ²"):
        assert name in shown, name


def test_figure2_gap_is_negative_when_open():
    shown = texts(fig2())
    d_n = float(re.search(r"d_n = \[\[x\]\]·n = (-?[\d.]+) < 0: open", shown).group(1))
    assert d_n < 0
    for name in ("r = λn + r_τ", "λn", "r_τ", "p = -λ ≥ 0", "λ ≤ 0", "|r_τ| ≤ μ|λ|"):
        assert name in shown, name


@pytest.mark.parametrize("mu", [0.2, 0.5, 1.0, 2.5])
def test_figure2_cone_has_half_angle_arctan_mu(mu):
    right = fig2(mu).axes[1]
    dashed = [line.get_xydata() for line in right.lines if line.get_linestyle() == "--"]
    assert len(dashed) == 2
    a, b = (d[1] - d[0] for d in dashed)           # both leave the contact point
    assert np.allclose(dashed[0][0], dashed[1][0])
    angle = np.arccos(a @ b / np.linalg.norm(a) / np.linalg.norm(b))
    assert abs(angle - 2 * np.arctan(mu)) < 1e-9
    assert f"μ = {mu:g}" in texts(right.figure)


@pytest.mark.parametrize("mu", [0.0, -1.0, float("nan"), "0.5", 10.0])
def test_figure2_refuses_a_bad_friction_coefficient(mu):
    with pytest.raises(ValueError, match="mu must be a number"):
        fig2(mu)


def test_figure3_polygons_are_fans_of_sub_triangles():
    """A k-gon is cut into k - 2 triangles: a hexagon into 4, a quadrilateral into 2;
    each cut edge has an intersection point and a middle node."""
    fig = fig3()
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    fig.draw_without_rendering()                    # 3D polygons are projected when drawn
    for ax, (edges, triangles) in zip(fig.axes, [(6, 4), (4, 2)]):
        assert len(ax.collections[1].get_paths()) == triangles
        assert f"{edges} cut edges, {triangles} sub-triangles" in ax.get_title()
        points = [c for c in ax.collections
                  if c.get_facecolor().size and np.allclose(
                      c.get_facecolor()[0][:3], _rgb(COLORS["gamma"]))]
        assert len(points[-1].get_offsets()) == edges
    shown = texts(fig)
    assert "intersection points (skxfem)" in shown and "middle nodes" in shown


def _rgb(color):
    from matplotlib.colors import to_rgb
    return np.array(to_rgb(color))


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_figure4_meshes_have_the_papers_counts(n):
    """hex: n·n·nz cells, (n+1)² cut edges; prisms: twice the cells and (n+1)(2n+1) cut
    edges, the diagonals included; the points in view are on the faces x = 1 and y = 0."""
    nz = n if n % 2 else n + 1
    fig = fig4(n)
    assert isinstance(fig, Figure) and len(fig.axes) == 4
    geometry, key, hexes, prisms = fig.axes                  # key: the legend's panel
    assert f"hex: {n * n * nz} cells, {(n + 1) ** 2} cut edges" in hexes.get_title()
    assert f"prism: {2 * n * n * nz} cells, {(n + 1) * (2 * n + 1)} cut edges" \
        in prisms.get_title()
    for ax, in_view in ((hexes, 2 * n + 1), (prisms, 3 * n + 1)):
        assert len(ax.collections[-1].get_offsets()) == in_view
    assert "assumed: rollers u_x = 0 on x = 0, 1" in texts(fig)
    assert "unit cube assumed" in geometry.get_title()


@pytest.mark.parametrize("n, nz", [(0, None), (2.5, None), (True, None), (13, None),
                                   (4, 4), (4, 0), (4, 1.0)])
def test_figure4_refuses_bad_meshes(n, nz):
    with pytest.raises(ValueError, match="must be"):
        fig4(n, nz)
