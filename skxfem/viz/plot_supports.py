r"""Which cut edges lose which multiplier component where Γ meets a support (issue 7).

One figure: the faces of a 3D mesh normal to one axis (the plate's roller
faces x = 0 and x = 1), one row per face and one column per multiplier
component, with the cut edges lying in the face drawn by what the
component's prolongation P gives them (:attr:`skxfem.problem.Problem.P`,
one block per component): no multiplier of its own (a support holds that
jump at both ends: :attr:`skxfem.problem.Problem.held_edges`; it takes the λ of a
neighbour on Γ, or none where the supports hold the whole jump), a μ of its
own or of its group (one weight), or interpolated between two μ.

>>> from skxfem.problem import assemble
>>> from skxfem.scene.benchmarks import paper_plate
>>> p = assemble(paper_plate(3, "prism", space="vital", nx=2))
>>> Ps = [s.P for s in p.component_spaces]
>>> fig = plot_held_edges(p.mesh, p.cut, Ps, held_edges=p.held_edges)
>>> len(fig.axes), fig.axes[0].get_title()
(6, 'λ_x on x = 0')
"""
from __future__ import annotations

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from .plotting import COLORS, legend_size

__all__ = ["plot_held_edges", "KINDS"]

#: How a cut edge is drawn: held, else by the number of entries of its row of P.
KINDS = {0: ("no λ of its own (jump held)", COLORS["gamma"], (0, (3, 2)), 2.2),
         1: ("its own / its group's μ", COLORS["vital"], "-", 2.6),
         2: ("interpolated between two μ", COLORS["winner"], ":", 2.2)}


def plot_held_edges(mesh, cut, prolongations, axis: int = 0, values=None,
                    labels=None, held_edges=None) -> Figure:
    """The cut edges of the faces ``x_axis = value`` of a 3D mesh, per component.

    Parameters
    ----------
    mesh
        A 3D scikit-fem mesh.
    cut
        Its :class:`skxfem.cut.Cut`.
    prolongations
        One (n_edges, m_k) sparse P per multiplier component
        (``[s.P for s in problem.component_spaces]``).
    axis
        The coordinate normal to the faces (0: x).
    values
        The faces' coordinates; default the smallest and largest.
    labels
        The components' names; default x, y, z (three blocks) or n (one).
    held_edges
        (components, n_edges) bool, the edges whose jump in each component a
        support holds (``problem.held_edges``); default: those with an empty row of P.

    Returns
    -------
    Figure
        One row per face, one column per component.
    """
    if mesh.dim() != 3:
        raise ValueError(f"mesh must be 3D (faces of a box), got a {mesh.dim()}D mesh")
    ne = cut.edge_ids.size
    kinds = [np.diff(P.tocsr().indptr) for P in prolongations]
    if any(k.size != ne for k in kinds):
        raise ValueError(f"prolongations must have one row per cut edge ({ne})")
    if held_edges is not None:
        held_edges = np.asarray(held_edges, dtype=bool)
        if held_edges.shape != (len(kinds), ne):
            raise ValueError(f"held_edges must be one row of {ne} bools per component, got "
                             f"shape {held_edges.shape}")
        kinds = [np.where(h, 0, np.maximum(k, 1)) for k, h in zip(kinds, held_edges)]
    labels = labels or ("xyz" if len(kinds) == 3 else ("n",) * len(kinds))
    values = values if values is not None else (mesh.p[axis].min(), mesh.p[axis].max())
    u, v = [a for a in range(3) if a != axis]
    tol = 1e-9 * np.ptp(mesh.p[axis])
    ends = mesh.p[v][cut.edges]                              # the band of cells Γ cuts
    lo, hi = ends.min(), ends.max()
    lo, hi = max(lo - 0.5 * (hi - lo), mesh.p[v].min()), min(hi + 0.5 * (hi - lo),
                                                               mesh.p[v].max())
    width = np.ptp(mesh.p[u])
    fig = Figure(figsize=(3.4 * len(kinds), (0.8 + 2.9 * (hi - lo) / width) * len(values) + 0.4),
                 layout="constrained")
    axes = np.atleast_2d(fig.subplots(len(values), len(kinds), squeeze=False))
    for row, value in zip(axes, values):
        on = np.abs(mesh.p[axis] - value) <= tol
        face_edges = mesh.edges[:, on[mesh.edges].all(axis=0)]
        in_face = on[cut.edges].all(axis=0)
        for ax, kind, label in zip(row, kinds, labels):
            ax.add_collection(LineCollection(
                np.transpose(mesh.p[[u, v]][:, face_edges], (2, 1, 0)),
                colors="#d9d9d9", linewidths=0.7))
            for count, (_, color, style, width) in KINDS.items():
                edges = cut.edges[:, in_face & (np.minimum(kind, 2) == count)]
                ax.add_collection(LineCollection(
                    np.transpose(mesh.p[[u, v]][:, edges], (2, 1, 0)), colors=color,
                    linestyles=style, linewidths=width))
            ax.plot(*cut.points[[u, v]][:, in_face], "o", ms=3, color="k")
            ax.set_xlim(mesh.p[u].min() - 0.02 * width, mesh.p[u].max() + 0.02 * width)
            ax.set_ylim(lo, hi)
            ax.set_aspect("equal")
            ax.set_title(f"λ_{label} on {'xyz'[axis]} = {value:g}", fontsize="medium")
            ax.set_xlabel("xyz"[u])
            ax.set_ylabel("xyz"[v])
    handles = [Line2D([], [], color=c, ls=s, lw=w, label=t) for t, c, s, w in KINDS.values()]
    handles.append(Line2D([], [], color="k", marker="o", ls="", ms=3,
                          label="multiplier points"))
    fig.legend(handles=handles, loc="outside lower center", ncol=4, frameon=False,
               fontsize=legend_size(fig))
    return fig
