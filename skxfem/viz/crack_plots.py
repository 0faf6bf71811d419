r"""Figures of a crack with a front (:mod:`skxfem.studies.cracks`, :mod:`skxfem.crack`).

* :func:`fig_crack_convergence`: the classic figure, the relative energy error of the
  Williams square against h, geometric enrichment ≈ h¹ against topological ≈ h^½,
  with the fitted slopes in the legend and slope triangles 1 and ½ drawn;
* :func:`fig_crack_conditioning`: condition numbers against h, topological and
  geometric, raw, Jacobi- and block-scaled;
* :func:`fig_crack_K`: the error of K against h, per enrichment and mode;
* :func:`fig_branch_functions`: the four branch functions around the tip, one panel
  each, the crack drawn where they jump;
* :func:`fig_crack_friction`: contact on the crack faces, the closed inclined crack's
  K_II against the friction μ with Dolbow et al.'s line (0 where the faces stick), and
  the inf-sup constant of the naive, winner and vital spaces up to the front against h.

Each takes data (rows of the studies) and returns a :class:`matplotlib.figure.Figure`
built without pyplot, in the style of :mod:`skxfem.viz.figstyle`: log axes, grid,
legends of :func:`~skxfem.viz.plotting.legend_size`.  Colours: one per enrichment
(:data:`ENRICHMENT_COLORS`), the crack in Γ's colour.
"""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..crack.branch import branch
from ..studies.cracks import energy_rates
from .figstyle import finish, log_axes
from .plotting import COLORS, CURVE_COLORS

__all__ = ["ENRICHMENT_COLORS", "SCALING_STYLE", "fig_crack_convergence",
           "fig_crack_conditioning", "fig_crack_K", "fig_branch_functions",
           "fig_crack_friction"]

ENRICHMENT_COLORS = {"topological": CURVE_COLORS[1], "geometric": CURVE_COLORS[0]}
"""One colour per enrichment, in every crack figure."""
SCALING_STYLE = {"raw": (":", "x"), "jacobi": ("--", "s"), "block": ("-", "o")}
"""Line style and marker of each scaling of :func:`fig_crack_conditioning`."""
_MODE_STYLE = {"I": ("-", "o"), "II": ("--", "s")}


def _select(rows, **keys):
    sel = [r for r in rows if all(getattr(r, k) == v for k, v in keys.items())]
    return sorted(sel, key=lambda r: -r.h)


def _h_ticks(ax, rows):
    """Ticks at the meshes' h, labelled 1/n."""
    ns = sorted({r.n for r in rows})
    ax.set_xticks([1 / n for n in ns], [f"1/{n}" for n in ns])


def _slope_triangle(ax, x0, y0, slope, width, label, below=True):
    """A right triangle of the given log-log slope from (x0, y0), ``width`` decades wide
    (a factor 10**width in x), its slope written at the vertical side."""
    x1 = x0 * 10 ** width
    y1 = y0 * 10 ** (slope * width)
    corner = (x1, y0) if below else (x0, y1)
    ax.plot([x0, x1, corner[0], x0], [y0, y1, corner[1], y0], color="0.3", lw=0.9)
    if below:
        ax.annotate(label, (x1, np.sqrt(y0 * y1)), xytext=(3, 0), textcoords="offset points",
                    va="center", ha="left", fontsize="small")
    else:
        ax.annotate(label, (x0, np.sqrt(y0 * y1)), xytext=(-3, 0), textcoords="offset points",
                    va="center", ha="right", fontsize="small")


def fig_crack_convergence(rows, mode: str = "I") -> Figure:
    """The relative energy error against h of each enrichment (one curve each, the
    least-squares slope in the legend) and slope triangles 1 and ½ under and over them.

    Parameters
    ----------
    rows
        :class:`skxfem.studies.cracks.WilliamsRow` s; those of ``mode`` are drawn.

    >>> from skxfem.studies.cracks import WilliamsRow
    >>> rows = [WilliamsRow(n, 1 / n, k, "I", (1, 0), 0.01, n ** -p, 0)
    ...         for k, p in (("topological", 0.5), ("geometric", 1.0)) for n in (4, 8)]
    >>> [ln.get_label() for ln in fig_crack_convergence(rows).axes[0].lines[:2]]
    ['topological, slope 0.50', 'geometric, slope 1.00']
    """
    fig = Figure(figsize=(6.2, 4.6), layout="constrained")
    ax = fig.add_subplot()
    rates = energy_rates(rows, mode)
    kinds = list(dict.fromkeys(r.enrichment for r in rows if r.mode == mode))
    for kind in kinds:
        sel = _select(rows, mode=mode, enrichment=kind)
        rate = f", slope {rates[kind]:.2f}" if kind in rates else ""
        ax.plot([r.h for r in sel], [r.energy for r in sel], "-o", ms=5, lw=1.5,
                color=ENRICHMENT_COLORS.get(kind, COLORS["mesh"]), label=f"{kind}{rate}")
    log_axes(ax)
    _h_ticks(ax, [r for r in rows if r.mode == mode])
    h = np.array([r.h for r in rows if r.mode == mode])
    e = np.array([r.energy for r in rows if r.mode == mode])
    if h.size > 1:
        width = 0.35 * np.log10(h.max() / h.min())
        x0 = h.min() * 10 ** (0.15 * np.log10(h.max() / h.min()))
        low = min(r.energy for r in _select(rows, mode=mode) if np.isclose(r.h, h.min()))
        _slope_triangle(ax, x0, 0.55 * low, 1.0, width, "1", below=True)
        high = max(e)
        _slope_triangle(ax, x0, 1.5 * high * (x0 / h.max()) ** 0.5, 0.5, width, "½",
                        below=False)
    finish(ax, "h (cell size)", f"Energy error, Williams square, mode {mode}",
           ylabel="relative energy error ‖u - u_h‖_E / ‖u‖_E")
    return fig


def fig_crack_conditioning(rows) -> Figure:
    """Condition numbers against h: colour = enrichment, line style = scaling
    (:data:`SCALING_STYLE`).

    Parameters
    ----------
    rows
        :class:`skxfem.studies.cracks.ConditionRow` s.

    >>> from skxfem.studies.cracks import ConditionRow
    >>> rows = [ConditionRow(n, 1 / n, "geometric", s, c * n ** 2)
    ...         for s, c in (("raw", 1e5), ("block", 1.0)) for n in (4, 8)]
    >>> [ln.get_label() for ln in fig_crack_conditioning(rows).axes[0].lines]
    ['geometric, raw', 'geometric, block-scaled']
    """
    fig = Figure(figsize=(6.2, 4.6), layout="constrained")
    ax = fig.add_subplot()
    names = {"raw": "raw", "jacobi": "Jacobi-scaled", "block": "block-scaled"}
    for kind in dict.fromkeys(r.enrichment for r in rows):
        for scaling in SCALING_STYLE:
            sel = _select(rows, enrichment=kind, scaling=scaling)
            if sel:
                ls, marker = SCALING_STYLE[scaling]
                ax.plot([r.h for r in sel], [r.condition for r in sel], ls=ls, marker=marker,
                        ms=5, lw=1.5, color=ENRICHMENT_COLORS.get(kind, COLORS["mesh"]),
                        label=f"{kind}, {names[scaling]}")
    log_axes(ax)
    _h_ticks(ax, rows)
    finish(ax, "h (cell size)", "Condition number of the supported stiffness",
           ylabel="condition number κ₂", below=True)
    return fig


def fig_crack_K(rows) -> Figure:
    """The K error max |K - K_exact| against h: colour = enrichment, line style = mode.

    Parameters
    ----------
    rows
        :class:`skxfem.studies.cracks.WilliamsRow` s.

    >>> from skxfem.studies.cracks import WilliamsRow
    >>> rows = [WilliamsRow(n, 1 / n, "geometric", m, (1, 0), 0.1 / n, 0.1, 0)
    ...         for m in ("I", "II") for n in (4, 8)]
    >>> [ln.get_label() for ln in fig_crack_K(rows).axes[0].lines]
    ['geometric, mode I', 'geometric, mode II']
    """
    fig = Figure(figsize=(6.2, 4.6), layout="constrained")
    ax = fig.add_subplot()
    for kind in dict.fromkeys(r.enrichment for r in rows):
        for mode, (ls, marker) in _MODE_STYLE.items():
            sel = _select(rows, enrichment=kind, mode=mode)
            if sel:
                ax.plot([r.h for r in sel], [r.K_error for r in sel], ls=ls, marker=marker,
                        ms=5, lw=1.5, color=ENRICHMENT_COLORS.get(kind, COLORS["mesh"]),
                        label=f"{kind}, mode {mode}")
    log_axes(ax)
    _h_ticks(ax, rows)
    finish(ax, "h (cell size)", "Stress intensity factors, Williams square",
           ylabel="K error max |K - K_exact| (K_exact = 1)")
    return fig


def fig_branch_functions(radius: float = 1.0, n_r: int = 40, n_theta: int = 181) -> Figure:
    """The four branch functions F_l(r, θ) on the disc r < ``radius`` around the tip,
    in the tip frame (x₁ ahead of the crack, x₂ into Ω⁺), on a polar grid, so that the
    jump across the crack (θ = ±π, drawn in Γ's colour) stays sharp.

    >>> fig = fig_branch_functions(n_r=5, n_theta=9)
    >>> len(fig.axes), fig.axes[0].get_title()
    (5, 'F₁ = √r sin(θ/2)')
    """
    r = np.linspace(0.0, radius, n_r)
    theta = np.linspace(-np.pi, np.pi, n_theta)
    R, T = np.meshgrid(r, theta, indexing="ij")
    F = branch(R, T)
    x1, x2 = R * np.cos(T), R * np.sin(T)
    titles = ("F₁ = √r sin(θ/2)", "F₂ = √r cos(θ/2)", "F₃ = √r sin(θ/2) sin θ",
              "F₄ = √r cos(θ/2) sin θ")
    fig = Figure(figsize=(6.2, 5.6), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True, sharey=True)
    lim = float(np.sqrt(radius))
    for ax, f, title in zip(axes.ravel(), F, titles):
        mesh = ax.pcolormesh(x1, x2, f, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="gouraud")
        ax.contour(x1, x2, f, levels=np.linspace(-lim, lim, 11)[1:-1], colors="k",
                   linewidths=0.4)
        ax.plot([-radius, 0], [0, 0], color=COLORS["gamma"], lw=2.5)
        ax.plot([0], [0], "o", color=COLORS["gamma"], ms=4)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize="medium")
    for ax in axes[1]:
        ax.set_xlabel("x₁ (ahead: e₁)")
    for ax in axes[:, 0]:
        ax.set_ylabel("x₂ (into Ω⁺: e₂)")
    fig.colorbar(mesh, ax=axes, shrink=0.8, label="F_l (r in units of the radius)")
    return fig


def fig_crack_friction(friction_rows, inf_sup_rows=()) -> Figure:
    """Top: |K_II| / σ√(πa) of the closed inclined crack against μ, one colour per β
    (markers: the solves at both tips; line: sin β cos β - μ cos² β, 0 once μ ≥ tan β).
    Below (with ``inf_sup_rows``): β_h of each multiplier space against h, log axes.

    Parameters
    ----------
    friction_rows
        :class:`skxfem.studies.cracks.FrictionRow` s (one mesh).
    inf_sup_rows
        :class:`skxfem.studies.cracks.InfSupRow` s.

    >>> from skxfem.studies.cracks import FrictionRow, InfSupRow
    >>> rows = [FrictionRow("tri", 21, 30.0, mu, True, (0, 0), (k, -k), (k, -k), 0, 0, 1, 0)
    ...         for mu, k in ((0.0, 0.43), (0.3, 0.21))]
    >>> inf = [InfSupRow(s, "tri", n, 1 / n, b, n, 0) for s, b in (("naive", 0.1),
    ...        ("vital", 0.6)) for n in (11, 21)]
    >>> fig = fig_crack_friction(rows, inf)
    >>> [ln.get_label() for ln in fig.axes[1].lines]
    ['naive', 'vital']
    """
    fig = Figure(figsize=(6.2, 8.8 if inf_sup_rows else 4.6), layout="constrained")
    ax = fig.add_subplot(2 if inf_sup_rows else 1, 1, 1)
    mus = np.linspace(0.0, max(1.0, max(r.friction for r in friction_rows)), 201)
    for k, beta in enumerate(dict.fromkeys(r.beta for r in friction_rows)):
        color = CURVE_COLORS[k % len(CURVE_COLORS)]
        b = np.radians(beta)
        exact = np.maximum(np.sin(b) * np.cos(b) - mus * np.cos(b) ** 2, 0.0)
        ax.plot(mus, exact, color=color, lw=1.2, label=f"β = {beta:g}°: exact")
        sel = [r for r in friction_rows if r.beta == beta]
        ax.plot([r.friction for r in sel for _ in r.K_II],
                [abs(k) for r in sel for k in r.K_II], ls="none", marker="o", ms=5,
                mfc="none", color=color, label=f"β = {beta:g}°: X-FEM, both tips")
        ax.axvline(np.tan(b), color=color, ls=":", lw=1.0)
    finish(ax, "friction μ (dotted: tan β, the faces stick beyond)",
           "Closed inclined crack under compression", ylabel="|K_II| / σ√(πa)")
    if inf_sup_rows:
        ax = fig.add_subplot(2, 1, 2)
        for name in dict.fromkeys(r.space for r in inf_sup_rows):
            sel = _select(inf_sup_rows, space=name)
            ax.plot([r.h for r in sel], [r.beta for r in sel], marker="o", ms=5, lw=1.5,
                    color=COLORS.get(name, COLORS["mesh"]), label=name)
        log_axes(ax)
        finish(ax, "h (mean crossed-edge length)", "Inf-sup constant up to the crack front",
               ylabel="β_h")
    return fig
