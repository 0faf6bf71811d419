"""Write a solver result to disk: ``result.json`` and two VTU files for ParaView.

* ``result.json``: the scene name, the multiplier ``points`` (one coordinate
  list per point), ``normals``, ``traction``, ``pressure``, ``max_jump``,
  ``n_dofs``, ``n_multipliers`` and the ``timings`` in seconds per stage.
  NaN or inf become ``null``.
* ``displacement.vtu``: the mesh with point data ``u_minus`` and ``u_plus``
  (the nodal fields of Ω⁻ and Ω⁺) and cell data ``side``: -1 in Ω⁻, +1 in Ω⁺,
  0 in the cells the interface cuts.
* ``interface.vtu``: the interface facets (``line`` cells in 2D, ``triangle``
  cells in 3D) on the multiplier points, with point data ``pressure``,
  ``traction`` and ``normal``.

Vectors are written with 3 components (z = 0 in 2D) so ParaView can draw them.
"""
from __future__ import annotations

import json
from pathlib import Path

import meshio
import numpy as np
from skfem.io.meshio import to_meshio

from .levelset import nodal_values

__all__ = ["write_result", "result_summary", "cell_sides", "vtk_cells"]

_STAGES = ("cut", "enrich", "assemble", "solve")
# VTK wants cells positively oriented: the simplex of these corners has det > 0
# (a wedge's face (0, 1, 2) has its right-hand normal pointing *away* from (3, 4, 5));
# scikit-fem allows either orientation, so mirrored cells get their nodes flipped.
_CORNERS = {"triangle": [0, 1, 2], "quad": [0, 1, 3], "tetra": [0, 1, 2, 3],
            "hexahedron": [0, 1, 3, 4], "wedge": [0, 2, 1, 3]}
_FLIP = {"triangle": [0, 2, 1], "quad": [0, 3, 2, 1], "tetra": [0, 2, 1, 3],
         "hexahedron": [0, 3, 2, 1, 4, 7, 6, 5], "wedge": [0, 2, 1, 3, 5, 4]}

def _plain(a) -> list | float | None:
    """A number or an array as plain Python floats (nested lists), NaN/inf as None."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, None).tolist()


def _vectors3(a: np.ndarray) -> np.ndarray:
    """(dim, n) → (n, 3), padding 2D vectors with a zero z component."""
    a = np.asarray(a, dtype=float)
    return np.vstack([a, np.zeros((3 - a.shape[0], a.shape[1]))]).T


def cell_sides(mesh, psi_nodes: np.ndarray) -> np.ndarray:
    """-1 for cells in Ω⁻, +1 in Ω⁺, 0 for cells with vertices on both sides.

    >>> from skfem import MeshTri1                # cells (0, 1, 2) and (1, 3, 2)
    >>> cell_sides(MeshTri1(), np.array([-1.5, -0.5, -0.5, 0.5])).tolist()
    [-1, 0]
    """
    psi = psi_nodes[mesh.t]
    cut = (psi.min(axis=0) < 0) & (psi.max(axis=0) > 0)
    return np.where(cut, 0, np.sign(psi.mean(axis=0))).astype(np.int64)


def vtk_cells(mesh) -> tuple[str, np.ndarray]:
    """The meshio cell type and the (ncells, nverts) cells, positively oriented for VTK.

    The node order is scikit-fem's ``to_meshio`` (which renumbers hexahedra).

    >>> from skfem import MeshTri1
    >>> kind, cells = vtk_cells(MeshTri1())
    >>> kind, cells.tolist()
    ('triangle', [[0, 1, 2], [1, 3, 2]])
    """
    block = to_meshio(mesh, encode_cell_data=False).cells[0]
    t = block.data.copy()
    corners = mesh.p[:, t[:, _CORNERS[block.type]]]            # (dim, ncells, dim + 1)
    edges = corners[:, :, 1:] - corners[:, :, :1]
    flip = np.linalg.det(np.moveaxis(edges, 0, 1)) < 0          # det of (ncells, dim, dim)
    t[flip] = t[flip][:, _FLIP[block.type]]
    return block.type, t


def result_summary(result) -> dict:
    """The content of ``result.json`` as a dict of plain Python values."""
    timings = {k: float(v) for k, v in dict(result.timings).items()}
    missing = [s for s in _STAGES if s not in timings]
    if missing:
        raise ValueError(f"result.timings lacks the stages {missing}; expected {_STAGES}")
    return {
        "scene": result.scene.name,
        "law": result.scene.law,
        "space": result.scene.space,
        "points": _plain(np.asarray(result.points).T),
        "normals": _plain(np.asarray(result.normals).T),
        "traction": _plain(np.asarray(result.traction).T),
        "pressure": _plain(result.pressure),
        "max_jump": _plain(result.max_jump),
        "n_dofs": int(result.n_dofs),
        "n_multipliers": int(result.n_multipliers),
        "timings": timings,
    }


def write_result(result, out_dir: str | Path) -> dict[str, Path]:
    """Write ``result.json``, ``displacement.vtu`` and ``interface.vtu`` into ``out_dir``.

    Parameters
    ----------
    result
        A :class:`skxfem.solver.Result` (or any object with the same attributes).
    out_dir
        Folder to write into; created if missing.

    Returns
    -------
    dict
        ``{"json": ..., "displacement": ..., "interface": ...}`` paths.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = {"json": out / "result.json", "displacement": out / "displacement.vtu",
             "interface": out / "interface.vtu"}
    paths["json"].write_text(json.dumps(result_summary(result), indent=1, allow_nan=False))

    mesh = result.mesh
    cell_type, cells = vtk_cells(mesh)
    cell_data = {}
    levelset = getattr(result.scene, "levelset", None)
    if levelset is not None:
        cell_data["side"] = [cell_sides(mesh, nodal_values(levelset, mesh))]
    meshio.write(paths["displacement"], meshio.Mesh(
        _vectors3(mesh.p), [(cell_type, cells)],
        point_data={"u_minus": _vectors3(result.u_minus), "u_plus": _vectors3(result.u_plus)},
        cell_data=cell_data))

    points = np.asarray(result.points, dtype=float)
    facets = np.asarray(result.facets, dtype=np.int64)
    kind = {2: "line", 3: "triangle"}[points.shape[0]]
    meshio.write(paths["interface"], meshio.Mesh(
        _vectors3(points), [(kind, facets.T.reshape(-1, points.shape[0]))],
        point_data={"pressure": np.asarray(result.pressure, dtype=float),
                    "traction": _vectors3(result.traction),
                    "normal": _vectors3(result.normals)}))
    return paths
