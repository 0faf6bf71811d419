"""Figures of the crack chapter (skxfem.viz.crack_plots): what is drawn (curves, their
data, colours, labels, slopes), not pixels."""
import numpy as np
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure

from skxfem.crack.branch import branch
from skxfem.studies.cracks import (
    ConditionRow,
    FrictionRow,
    InfSupRow,
    WilliamsRow,
    conditioning_study,
    williams_study,
)
from skxfem.viz.crack_plots import (
    ENRICHMENT_COLORS,
    fig_branch_functions,
    fig_crack_conditioning,
    fig_crack_convergence,
    fig_crack_friction,
    fig_crack_K,
)
from skxfem.viz.plotting import COLORS


def same_colour(a, b):
    return np.allclose(to_rgba(a), to_rgba(b))


def rows(rate=None):
    """Williams rows of exact power laws: energy ~ h^p, K error ~ h^(2p)."""
    rate = rate or {"topological": 0.5, "geometric": 1.0}
    return [WilliamsRow(n, 1 / n, kind, mode, (1.0, 0.0), 0.1 * n ** (-2 * p), n ** -p, 0)
            for mode in ("I", "II") for kind, p in rate.items() for n in (10, 20, 40)]


def test_convergence_figure_has_one_curve_per_enrichment_and_slope_triangles():
    fig = fig_crack_convergence(rows())
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    curves = [ln for ln in ax.lines if ln.get_label()[0] != "_"]
    assert [c.get_label() for c in curves] == ["topological, slope 0.50",
                                               "geometric, slope 1.00"]
    for c, kind in zip(curves, ("topological", "geometric")):
        assert same_colour(c.get_color(), ENRICHMENT_COLORS[kind])
        assert np.allclose(c.get_xdata(), [0.1, 0.05, 0.025])
    # the two slope triangles: closed polygons of 4 points, slopes 1 and ½ in log-log
    triangles = [ln for ln in ax.lines if ln.get_label()[0] == "_"]
    slopes = sorted(np.log(ln.get_ydata()[1] / ln.get_ydata()[0])
                    / np.log(ln.get_xdata()[1] / ln.get_xdata()[0]) for ln in triangles)
    assert np.allclose(slopes, [0.5, 1.0])
    assert sorted(t.get_text() for t in ax.texts) == ["1", "½"]
    assert ax.get_xscale() == ax.get_yscale() == "log"
    assert [t.get_text() for t in ax.get_xticklabels()] == ["1/10", "1/20", "1/40"]


def test_convergence_figure_draws_the_mode_asked():
    data = rows()
    fig = fig_crack_convergence(data, mode="II")
    assert "mode II" in fig.axes[0].get_title()


def test_conditioning_figure_from_a_measured_study():
    study = conditioning_study((5, 7), ("topological", "geometric"), (None, "block"))
    fig = fig_crack_conditioning(study)
    lines = {ln.get_label(): ln for ln in fig.axes[0].lines}
    assert list(lines) == ["topological, raw", "topological, block-scaled",
                           "geometric, raw", "geometric, block-scaled"]
    raw = lines["geometric, raw"]
    assert raw.get_linestyle() == ":" and same_colour(raw.get_color(),
                                                      ENRICHMENT_COLORS["geometric"])
    measured = [r.condition for r in study if (r.enrichment, r.scaling) == ("geometric", "raw")]
    assert np.allclose(raw.get_ydata(), measured)
    assert raw.get_ydata().min() > 10 * lines["geometric, block-scaled"].get_ydata().max()


def test_conditioning_figure_skips_missing_scalings():
    fig = fig_crack_conditioning([ConditionRow(4, 0.25, "geometric", "jacobi", 10.0)])
    assert [ln.get_label() for ln in fig.axes[0].lines] == ["geometric, Jacobi-scaled"]


def test_K_figure_one_curve_per_enrichment_and_mode():
    data = williams_study((5, 7), enrichments=("geometric",), modes=("I", "II"))
    fig = fig_crack_K(data)
    lines = fig.axes[0].lines
    assert [ln.get_label() for ln in lines] == ["geometric, mode I", "geometric, mode II"]
    assert lines[0].get_linestyle() == "-" and lines[1].get_linestyle() == "--"
    assert np.allclose(lines[1].get_ydata(), [r.K_error for r in data if r.mode == "II"])


def test_branch_figure_shows_the_four_functions_and_their_jump():
    fig = fig_branch_functions(radius=4.0, n_r=6, n_theta=13)
    panels = fig.axes[:4]
    assert [ax.get_title()[:2] for ax in panels] == ["F₁", "F₂", "F₃", "F₄"]
    for l, ax in enumerate(panels):
        mesh = ax.collections[0]
        values = np.asarray(mesh.get_array()).reshape(6, 13)
        r = np.linspace(0, 4.0, 6)[:, None]
        theta = np.linspace(-np.pi, np.pi, 13)[None, :]
        assert np.allclose(values, branch(r + 0 * theta, theta + 0 * r)[l])
        crack = ax.lines[0]
        assert same_colour(crack.get_color(), COLORS["gamma"])
        assert np.allclose(crack.get_xdata(), [-4.0, 0.0])
    # F₁ jumps by 2√r across the faces (θ = ±π), the others are continuous there
    F = branch(np.full(2, 4.0), np.array([np.pi, -np.pi]))
    assert np.allclose(F[:, 0] - F[:, 1], [4.0, 0, 0, 0])


def test_friction_figure_draws_the_exact_line_the_solves_and_the_inf_sup():
    """Top: per β the line sin β cos β - μ cos² β clipped at 0 (it reaches 0 at tan β),
    the |K_II| of both tips as markers; below: β_h per space in the space's colour."""
    k = np.sin(np.radians(30)) * np.cos(np.radians(30))
    rows_ = [FrictionRow("tri", 21, 30.0, mu, mu < 0.577, (0, 0), (v, -v), (v, -v), 0,
                         0.0, 1, 0) for mu, v in ((0.0, k), (0.8, 0.0))]
    inf = [InfSupRow(s, "tri", n, 1 / n, b / n ** 0.1, n, 0)
           for s, b in (("naive", 0.1), ("winner", 0.5), ("vital", 0.6)) for n in (11, 21)]
    top, below = fig_crack_friction(rows_, inf).axes
    line, marks = top.lines[0], top.lines[1]
    mu, exact = line.get_data()
    assert np.isclose(exact[0], k) and exact[mu > np.tan(np.radians(30))].max() == 0
    assert np.allclose(marks.get_ydata(), [k, k, 0, 0]), "both tips, |K_II|"
    assert [ln.get_label() for ln in below.lines] == ["naive", "winner", "vital"]
    for ln in below.lines:
        assert same_colour(ln.get_color(), COLORS[ln.get_label()])
    assert len(fig_crack_friction(rows_).axes) == 1
