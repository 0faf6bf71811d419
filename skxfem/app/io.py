"""Write a solver result to disk: ``result.json`` and two VTU files for ParaView.

* ``result.json``: the scene name, ``law`` and ``space``, the multiplier
  ``points`` (where Γ cuts the mesh edges), ``normals``, ``traction`` (the
  whole vector), ``pressure``, ``jump`` ([[u]] = u⁻ - u⁺), ``max_jump``,
  ``n_dofs``, ``n_multipliers``, the ``timings`` in seconds per stage (``cut``,
  ``enrich``, ``assemble``, ``solve``, and ``front`` with a crack: K along it) and
  ``linear_solve``: the solve taken (``linear``) and how it went
  (:attr:`skxfem.result.Result.linear_info`: for a tie its ``tol``, residual,
  balance, and the iterations and residuals of an iterative solve, with the
  ``backward_error`` that accepted it where rounding held the residual above ``tol``
  (null otherwise, :mod:`skxfem.linalg.iterative`); for contact
  only its ``tol``, each Newton step's Krylov iterations being in ``steps``).
  NaN or inf is never written: :func:`write_result` refuses such a result
  (:class:`NotFiniteError`) before writing.
* ``result.json`` also describes the interfaces, whatever their number (one is
  the case N = 1): ``law`` and ``space`` are lists, one per interface;
  ``interfaces`` has one entry per interface (``levelset``: the level set's
  name, ``law``, ``space``, ``friction`` μ, ``rho_n``, ``rho_t``: those given,
  or for a contact solve those used; ``n_points``); ``interface`` is the
  interface of each point and ``regions`` the sign (±1) of each level set in
  each region (one interface: ``[[-1], [1]]``, Ω⁻ then Ω⁺).
* ``front`` (only for a scene with a crack, an interface with a ``front``): one entry
  per crack, ``interface`` (its index in ``interfaces``), ``points`` (one list per front
  point), ``K_I`` and ``K_II`` (and ``K_III`` in 3D; one number per point), the stress
  intensity factors of :attr:`skxfem.result.Result.front`, and in 3D ``interior`` (a
  boolean per point: K is trusted there, its domain clear of the free surfaces the
  front ends on).
* ``displacement.vtu``: each region as its own piece of mesh with its own
  field ``displacement``, so that ParaView's *Warp By Vector* shows the
  discontinuity: piece r holds the cells with a vertex in region r, on its own
  copy of their nodes, moving with region r's field (one interface: the cells
  of Ω⁻ and the cut cells with ``u⁻``, then those of Ω⁺ and the cut cells with
  ``u⁺``).  A cut cell is thus written once per region it meets; cell data
  ``region`` (the index into ``regions``) and ``cut`` (1 on cut cells), point
  data ``levelset_0``, ``levelset_1``, ... (ψ of each interface at the nodes
  as the solve used it, 0 at the nodes on Γ: clip a region's copy at each
  ψ = 0 to see only its own part of the cut cells).
* Both also carry the support reactions: ``result.json``'s ``reactions``
  (:func:`reaction_summary`: ``applied``, each support's force, their ``total``),
  ``displacement.vtu``'s point data ``reaction`` (at the copy of each node in its own
  region) and its cell data ``strain``, ``stress`` (3 x 3, :func:`tensors9`) and
  ``von_mises``, at the centre of each cell from its piece's field.
* ``interface.vtu``: the interface facets (``line`` cells in 2D, ``triangle``
  cells in 3D) on the multiplier points, with point data ``pressure``,
  ``traction``, ``tangential_traction``, ``normal``, ``jump``, ``gap`` and
  ``interface`` (the interface of each point).  A crack is written whole, up to its
  front: its pieces (segments, triangles) with an end that is no cut point (on the
  front, at a node on the crack) come after the others, on points of their own
  (:func:`_crack_pieces`: ``jump``, ``normal``, ``gap`` evaluated there, the
  traction fields 0 on free faces, NaN on others; ``status`` -1), so that the
  cells' length (2D) or area (3D) is the crack's {ψ_h = 0, φ_h < 0}.  Its front
  points follow as ``vertex`` cells carrying the point data ``K_I``, ``K_II``
  (``K_III``), NaN at the other points; the other fields are NaN at them (``status``
  -1).

**A contact result** (content from :func:`contact_summary`) goes into the
same three files with the same fields, those of the last load step, and a
``status`` per point.  ``result.json`` adds ``status_codes`` (μ and the
ρ used are in ``interfaces``), ``newton_iterations``, the multiplier ``dofs``
(``points``, ``normals``, ``tangents``, ``weights``: where the laws are
imposed; with the winner or vital space they are not the cut edges' points;
``interface``, the interface of each dof) and a list ``steps``, one entry per
load step, at the dofs: ``load``, ``law`` (one per interface), ``pressure``,
``tangential_traction``, ``gap``, ``slip``, ``Lambda``, ``status`` (strings
``"open"``, ``"stick"``, ``"slip"``), their ``counts`` and ``newton``:
``iterations`` and ``residuals`` (one list per equation, equilibrium, contact
and friction: the relative residual at the start, then after each iteration)
and ``krylov`` (the Krylov iterations of each iterative Newton step; empty
after direct ones).  ``interface.vtu`` adds the point data ``status`` (0 open,
1 stick, 2 slip).  The VTU files hold the last step; the
series adds one of each per load step, ``displacement_0001.vtu`` ...,
``interface_0001.vtu`` ..., and their ParaView collections ``displacement.pvd`` and
``interface.pvd`` (:data:`SERIES`; the JSON has every step too).

**Array shapes.**  :class:`skxfem.result.Result` follows scikit-fem: a set of
points or vectors is ``(dim, n)`` (``mesh.p``, ``result.points``,
``result.traction``).  The files follow meshio, VTK and JSON readers, where a
point is a row: ``result.json``'s ``points``, ``normals`` and ``traction`` are
``(n, dim)`` (one list per point, ``np.array(data["points"]) ==
result.points.T``), and VTU vectors are ``(n, 3)`` (z = 0 in 2D, so ParaView
can draw them).

**One set.**  :func:`write_result` writes the three files as one set
(:func:`skxfem.fem.files.write_set`): into a new hidden folder beside ``out_dir``
that then takes its place, under a lock on the parent folder.  A failed write
(a full disk, an error in the middle, a process killed at any moment) leaves
the previous result whole, or nothing, never a mix of two runs or a truncated
file; two writers to one folder take turns; what killed writers left is
removed by the next one.  So ``out_dir`` holds the three files only
(:func:`check_output` checks it, and the rest, before a solve).
:func:`default_folder` is the folder of a scene without ``--out``.
"""
from __future__ import annotations

import json
import os
import re
from pathlib import Path

import meshio
import numpy as np
import scipy.sparse as sp

from ..contact.interface import tangent_frames
from ..contact.laws import STATUS_NAMES
from ..fem.files import check_folder, quiet, write_set
from ..fem.vtu import (
    interface_levelsets,
    node_regions,
    pad3,
    region_levelsets,
    region_pieces,
    vectors3,
    vtk_cells,
)
from ..multipliers import InterfaceRule

__all__ = ["write_result", "result_summary", "NotFiniteError", "reaction_summary", "tensors9",
           "von_mises", "vtk_cells", "check_output", "region_pieces", "default_folder",
           "contact_summary", "EQUATIONS"]

_STAGES = ("cut", "enrich", "assemble", "solve")
_FILES = {"json": "result.json", "displacement": "displacement.vtu",
          "interface": "interface.vtu"}


class NotFiniteError(RuntimeError):
    """A result holding NaN or inf: never written (a bug of the solve, not of the input)."""


def _plain(a, key: str = "a value") -> list | float | None:
    """A number or an array as plain Python floats (nested lists); ``None`` (a value not
    given, such as the ρ of a tie) stays None.  NaN or inf is refused
    (:class:`NotFiniteError`, naming ``key``): a result file never holds them."""
    if a is None:
        return None
    a = np.asarray(a, dtype=float)
    if not np.all(np.isfinite(a)):
        raise NotFiniteError(f"the result's {key} holds NaN or inf "
                             f"({int(np.size(a) - np.isfinite(a).sum())} of {np.size(a)} "
                             f"values); nothing was written: please report this scene")
    return a.tolist()


def _jsonable(value, key: str = "result"):
    """Arrays and numpy numbers inside dicts and lists as plain Python values (NaN and
    inf refused, naming the key)."""
    if isinstance(value, dict):
        return {k: _jsonable(v, f"{key}.{k}") for k, v in value.items()}
    if isinstance(value, list):
        return [_jsonable(v, f"{key}[{i}]") for i, v in enumerate(value)]
    return _plain(value, key) if isinstance(value, (np.ndarray, float, np.floating)) \
        else value


def result_summary(result) -> dict:
    """The content of ``result.json`` as a dict of plain Python values.

    A contact result gives :func:`contact_summary`.
    """
    timings = {k: float(v) for k, v in dict(result.timings).items()}
    missing = [s for s in _STAGES if s not in timings]
    if missing:
        raise ValueError(f"result.timings lacks the stages {missing}; expected {_STAGES}")
    items = result.scene.interfaces
    data = {
        "scene": result.scene.name,
        "law": [i.law for i in items],
        "space": [i.space for i in items],
        "points": _plain(np.asarray(result.points).T, "points"),
        "normals": _plain(np.asarray(result.normals).T, "normals"),
        "traction": _plain(np.asarray(result.traction).T, "traction"),
        "pressure": _plain(result.pressure, "pressure"),
        "jump": _plain(np.asarray(result.jump).T, "jump"),
        "max_jump": _plain(result.max_jump, "max_jump"),
        "n_dofs": int(result.n_dofs),
        "n_multipliers": int(result.n_multipliers),
        "timings": timings,
        "linear_solve": _jsonable({"linear": result.linear, **dict(result.linear_info)},
                                  "linear_solve"),
    }
    if _solved(result):
        data["reactions"] = _jsonable(reaction_summary(result), "reactions")
    if result.is_contact:
        data.update(_jsonable(contact_summary(result), "steps"))
    data.update(_interfaces(result, items))
    fronts = getattr(result, "front", ())   # a result-like object may have none
    if fronts:  # a crack's stress intensity factors (none: the key is absent)
        data["front"] = [{"interface": int(f["interface"]),
                          "points": _plain(np.asarray(f["points"]), "front points"),
                          **{k: _plain(np.asarray(f[k]), k)
                             for k in ("K_I", "K_II", "K_III") if k in f},
                          **({"interior": np.asarray(f["interior"], bool).tolist()}
                             if "interior" in f else {})}
                         for f in fronts]
    return data


def reaction_summary(result) -> dict:
    """The ``reactions`` of ``result.json``: the resultant of the loads (``applied``:
    surface loads and body force, of the last step), that of each imposed displacement
    in the scene's order (``supports``: its ``boundary`` and ``force``) and their sum
    (``total``), which balances ``applied``: total + applied = 0 to round-off."""
    forces = result.support_forces()
    def name(d):
        text = d.boundary if isinstance(d.boundary, str) else \
            getattr(d.boundary, "text", None) or "selection"
        where = getattr(d, "where", None)
        return text if where is None else \
            f"{text} where {getattr(where, 'text', None) or 'selection'}"

    names = [name(d) for d in result.scene.displacements]
    return {"applied": np.asarray(result.applied, dtype=float),
            "total": np.asarray(result.reactions.sum(axis=1), dtype=float),
            "supports": [{"boundary": name, "force": np.asarray(f, dtype=float)}
                         for name, f in zip(names, forces, strict=True)]}


def _interfaces(result, items) -> dict:
    """The ``interfaces``, ``interface`` and ``regions`` of ``result.json`` (module
    notes): of the scene's interfaces ``items``, the μ and ρ given, or for contact
    those of ``result.law`` (one :class:`~skxfem.contact.newton.Law` per interface)."""
    counts = np.bincount(result.interface, minlength=len(items))
    laws = result.law if result.is_contact else [None] * len(items)
    entries = []
    for i, law, n in zip(items, laws, counts):
        entries.append({"levelset": i.levelset.name, "law": i.law, "space": i.space,
                        "friction": _plain(i.friction) if law is None else float(law.mu),
                        "rho_n": _plain(i.rho_n if law is None else law.rho_n),
                        "rho_t": _plain(i.rho_t if law is None else law.rho_t),
                        "n_points": int(n)})
    return {"interfaces": entries, "interface": np.asarray(result.interface).tolist(),
            "regions": np.asarray(result.regions).tolist()}


def check_output(out_dir: str | Path) -> Path:
    """Check, without creating anything, that results can be written into ``out_dir``.

    The folder may be missing (it is created by :func:`write_result`, with its
    parents) or hold an earlier result only (which is replaced).

    Raises
    ------
    ValueError
        If ``out_dir`` or one of its parents is an existing file, it holds
        other files or is the current folder (:func:`skxfem.fem.files.check_folder`),
        or the folder that would receive it is not writable.

    >>> check_output("results/plate").name
    'plate'
    """
    out = Path(out_dir)
    if str(out_dir) == "":
        raise ValueError("the output folder is empty; give a folder name such as "
                         "results/plate")
    check_folder(out, [*_FILES.values(), *SERIES])
    existing = Path(os.path.realpath(out)).parent
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise ValueError(f"output folder {str(out)!r} is below the file {str(existing)!r}; "
                         f"give another output folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise ValueError(f"output folder {str(out)!r} cannot be written: "
                         f"{str(existing)!r} is not writable; give another output folder")
    return out


def default_folder(name: str) -> Path:
    """The output folder of a scene named ``name`` when none is given: one folder
    below the current one, whatever the name holds.

    Every run of characters other than letters, digits, ``-``, ``_`` and ``.``
    (path separators, spaces, control characters) becomes ``_``; leading and
    trailing dots and ``_`` go, so that neither ``..`` nor a hidden folder can
    result; at most 100 bytes in UTF-8 (33 CJK characters: file systems count bytes);
    ``result`` if nothing is left.

    >>> [str(default_folder(s)) for s in ("../../escaped", "/etc/plate 2", "..", "été")]
    ['escaped', 'etc_plate_2', 'result', 'été']
    >>> len(str(default_folder("結" * 100)))
    33
    """
    safe = re.sub(r"[^\w.-]+", "_", str(name)).strip("._")
    safe = os.fsencode(safe)[:100].decode("utf-8", "ignore").strip("._")  # 100 bytes
    return Path(safe or "result")


def _write_json(result, path: Path):
    path.write_text(json.dumps(result_summary(result), indent=1, allow_nan=False))


def tensors9(t: np.ndarray, out_of_plane: np.ndarray | None = None) -> np.ndarray:
    """(n, 9) rows of 3 x 3 tensors from (dim, dim, n), as VTK reads a tensor; in 2D the
    zz entry is ``out_of_plane`` (n,) (0 if None).

    >>> tensors9(np.array([[[1.0], [2.0]], [[2.0], [3.0]]]), np.array([4.0])).tolist()
    [[1.0, 2.0, 0.0, 2.0, 3.0, 0.0, 0.0, 0.0, 4.0]]
    """
    dim, n = t.shape[0], t.shape[-1]
    full = np.zeros((3, 3, n))
    full[:dim, :dim] = t
    if dim == 2 and out_of_plane is not None:
        full[2, 2] = out_of_plane
    return np.moveaxis(full, 2, 0).reshape(n, 9)


def _zz(eps, sig, material, dim):
    """The out-of-plane strain and stress of a 2D field: plane strain ε_zz = 0 and
    σ_zz = ν(σ_xx + σ_yy); plane stress σ_zz = 0 and ε_zz = -ν/(1 - ν)(ε_xx + ε_yy)."""
    if dim == 3:
        return None, None
    nu = material.nu
    if material.plane == "stress":
        return -nu / (1 - nu) * (eps[0, 0] + eps[1, 1]), np.zeros(eps.shape[-1])
    return np.zeros(eps.shape[-1]), nu * (sig[0, 0] + sig[1, 1])


def von_mises(sigma9: np.ndarray) -> np.ndarray:
    """(n,) the von Mises stress of (n, 9) stress tensors: sqrt(3/2 s:s), s the deviator.

    >>> float(von_mises(np.array([[2.0, 0, 0, 0, 0, 0, 0, 0, 0]]))[0])   # uniaxial 2
    2.0
    """
    s = sigma9.reshape(-1, 3, 3)
    dev = s - np.trace(s, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3
    return np.sqrt(1.5 * (dev * dev).sum(axis=(1, 2)))


def _solved(result) -> bool:
    """True for a result that can give its stresses and reactions (a
    :class:`skxfem.result.Result` with its problem; a stand-in may lack them)."""
    return getattr(result, "problem", None) is not None and hasattr(result, "strains")


def _cell_fields(result, pieces: list[np.ndarray]) -> dict:
    """The cell data ``strain``, ``stress`` (3 x 3, 9 components) and ``von_mises`` of
    the written cells: piece k holds the cells ``pieces[k]`` with field k of
    :meth:`skxfem.result.Result.fields` ({} for a result without them)."""
    if not _solved(result):
        return {}
    dim = result.mesh.dim()
    eps9, sig9 = [], []
    for eps, sig, (_, material), cells in zip(result.strains(), result.stresses(),
                                              result.fields(), pieces, strict=True):
        e, s = eps[:, :, cells], sig[:, :, cells]
        ezz, szz = _zz(e, s, material, dim)
        eps9.append(tensors9(e, ezz))
        sig9.append(tensors9(s, szz))
    sig = np.vstack(sig9)
    return {"strain": [np.vstack(eps9)], "stress": [sig], "von_mises": [von_mises(sig)]}


def _reactions(result, nodes: list[np.ndarray], owners: list[np.ndarray]) -> dict:
    """``{"reaction": (n, 3)}``, the support reaction at each written point: at a
    node's copy in its own piece (``owners[k]``: the points of piece k whose node lies
    in it), 0 at the other copies, so that the reactions of the file sum to those of
    the result ({} for a result without them)."""
    if not _solved(result):
        return {}
    R = result.reactions
    out = [np.where(own[:, None], R[:, n].T, 0.0) for n, own in zip(nodes, owners)]
    return {"reaction": pad3(np.vstack(out))}


def _write_displacement(result, path: Path):
    """``displacement.vtu``: a piece per region, each with its own field (module notes)."""
    mesh = result.mesh
    cell_type, _ = vtk_cells(mesh)
    psi = interface_levelsets(result)
    node_region = node_regions(result.regions, region_levelsets(result))
    points, cells, region, cut, disp, nodes = region_pieces(mesh, node_region,
                                                            result.u_regions)
    levelsets = {f"levelset_{k}": psi_k[nodes] for k, psi_k in enumerate(psi)}
    regions_of = node_region[mesh.t]
    pieces = [np.flatnonzero((regions_of == r).any(axis=0))
              for r in range(len(result.u_regions))]
    per = [np.unique(mesh.t[:, c]) for c in pieces]
    reaction = _reactions(result, per, [node_region[n] == r for r, n in enumerate(per)])
    with quiet():  # meshio's own messages are not ours to print
        meshio.write(path, meshio.Mesh(
            pad3(points), [(cell_type, cells)],
            point_data={"displacement": pad3(disp), **levelsets, **reaction},
            cell_data={"region": [region], "cut": [cut], **_cell_fields(result, pieces)}),
            file_format="vtu")


def _write_interface(result, path: Path):
    points = np.asarray(result.points, dtype=float)
    facets = np.asarray(result.facets, dtype=np.int64)
    kind = {2: "line", 3: "triangle"}[points.shape[0]]
    n, r, jump = (np.asarray(a, dtype=float) for a in (result.normals, result.traction,
                                                        result.jump))
    data = {"pressure": np.asarray(result.pressure, dtype=float),
            "traction": vectors3(r),
            "tangential_traction": vectors3(r - (r * n).sum(0) * n),
            "normal": vectors3(n),
            "jump": vectors3(jump),
            "gap": (jump * n).sum(0)}
    data["interface"] = np.asarray(result.interface, dtype=np.int64)
    if result.is_contact:
        data["status"] = np.asarray(result.status, dtype=np.int64)
    cells = facets.T.reshape(-1, points.shape[0])
    points = vectors3(points)
    pieces = _crack_pieces(result)
    if pieces is not None:                 # a crack's pieces up to its front
        more, x, at = pieces
        cells, points = np.vstack([cells, more]), np.vstack([points, x])
        data = {name: np.concatenate([a, at.get(name, np.full((len(x),) + a.shape[1:], -1))])
                for name, a in data.items()}
    cells = [(kind, cells)]
    fronts = getattr(result, "front", ())   # a result-like object may have none
    if fronts:
        points, cells, data = _with_fronts(fronts, points, cells, data)
        cells = [c for c in cells if len(c[1])]   # a crack along mesh faces: no cut point
    with quiet():
        meshio.write(path, meshio.Mesh(points, cells, point_data=data), file_format="vtu")


def _crack_pieces(result) -> tuple[np.ndarray, np.ndarray, dict] | None:
    """The pieces of each crack that ``result.facets`` leaves out, those with an end that
    is no cut point (-1 in its cut's ``facets``: on the front, at a node on the crack,
    inside a cell's face), so that interface.vtu shows the crack up to its front.

    Returns (cells (np, dim), points (k, 3), point data) or None (no such piece, or a
    result without its problem): ``cells`` index the cut points, then the k new points,
    the pieces' ends that are no cut point (one per place); at those ``jump`` is
    u⁻ - u⁺ evaluated there (the kind's ``jump``; 0 at the front), ``normal`` ∇ψ/|∇ψ|,
    ``gap``, ``interface``, and the traction fields 0 on free faces (law ``free``: no
    multiplier), NaN on others (their multipliers live at the cut points); ``status``
    is -1 (left to the caller)."""
    pb, U = getattr(result, "problem", None), getattr(result, "U", None)
    if pb is None or U is None:
        return None
    cells, points, fields = [], [], []
    offset = 0
    new = np.shape(result.points)[1]
    for k, q in enumerate(pb.interfaces):
        f = np.asarray(q.cut.facets)
        stop = (f < 0).any(axis=0)
        if stop.any():
            idx, x, at = _stopped_pieces(q, U, stop, offset, new, k)
            cells.append(idx.T)
            points.append(x)
            fields.append(at)
            new += x.shape[1]
        offset += q.cut.edge_ids.size
    if not cells:
        return None
    data = {name: np.concatenate([d[name] for d in fields]) for name in fields[0]}
    return np.vstack(cells), vectors3(np.hstack(points)), data


def _stopped_pieces(q, U: np.ndarray, stop: np.ndarray, offset: int, first: int, k: int):
    """(cells (dim, np), points (dim, m), point data) of the pieces ``stop`` of the
    interface part ``q`` (:func:`_crack_pieces`): a -1 end becomes one of the m new
    points, numbered from ``first``, its vertices at one place merged (a piece along a
    mesh edge is listed once by the crack's geometry, in the cell on its Ω⁻ side)."""
    mesh, cut = q.mesh, q.cut
    f = np.asarray(cut.facets)[:, stop]
    idx = f + offset
    miss = f < 0
    ends = np.transpose(cut.pieces[stop], (1, 0, 2))[miss]          # (m', dim)
    owner = np.broadcast_to(cut.facet_cell[stop], miss.shape)[miss]
    scale = 1e-9 * np.ptp(mesh.p, axis=1).max()
    _, one, inv = np.unique(np.round(ends / scale), axis=0, return_index=True,
                            return_inverse=True)
    idx[miss] = first + inv.ravel()
    x, cells = ends[one].T, owner[one]
    m, dim = x.shape[1], x.shape[0]
    normals = q.gamma.normals_at(x)
    ref = mesh.mapping().invF(x[:, :, None], tind=cells)[:, :, 0]
    rule = InterfaceRule(points=x, normals=normals, weights=np.zeros(m), cells=cells,
                         ref=ref, N=sp.csr_matrix((m, 0)))
    jump = np.asarray(q.gamma.jump(q.V, rule) @ U[q.columns]).reshape(dim, m)
    r = np.full((dim, m), 0.0 if q.multiplier_space is None else np.nan)
    return idx, x, {"pressure": r[0], "traction": vectors3(r),
                    "tangential_traction": vectors3(r), "normal": vectors3(normals),
                    "jump": vectors3(jump), "gap": (jump * normals).sum(0),
                    "interface": np.full(m, k, dtype=np.int64)}


def _with_fronts(fronts, points: np.ndarray, cells: list, data: dict):
    """interface.vtu's points, cells and point data with each crack's front points
    appended as ``vertex`` cells: point data ``K_I``, ``K_II`` (``K_III``) there and NaN
    at the cut points; at the front points the cut points' fields are NaN (``status``
    -1) and ``interface`` is the crack's."""
    front = np.vstack([vectors3(np.asarray(f["points"], dtype=float).T) for f in fronts])
    n, m = len(points), len(front)
    owner = np.concatenate([np.full(len(f["points"]), f["interface"]) for f in fronts])
    data = {name: np.concatenate([a, owner if name == "interface" else
                                  np.full((m,) + a.shape[1:], -1 if a.dtype.kind == "i"
                                          else np.nan)])
            for name, a in data.items()}
    for key in ("K_I", "K_II", "K_III"):
        if any(key in f for f in fronts):
            at_front = np.concatenate([np.asarray(f.get(key, np.full(len(f["points"]),
                                                                     np.nan)), dtype=float)
                                       for f in fronts])
            data[key] = np.concatenate([np.full(n, np.nan), at_front])
    return (np.vstack([points, front]),
            cells + [("vertex", np.arange(n, n + m, dtype=np.int64)[:, None])], data)


_WRITERS = {"json": _write_json, "displacement": _write_displacement,
            "interface": _write_interface}


SERIES = ("displacement.pvd", "interface.pvd", "displacement_*.vtu", "interface_*.vtu")
"""The files of the series of a contact result: a ParaView collection (``.pvd``) of
each VTU file, with one file per load step (``displacement_0001.vtu`` ...)."""


def _pvd(files: list[str]) -> str:
    """A ParaView collection of ``files``, their timesteps 1, 2, ... (the load steps).

    >>> print(_pvd(["a_0001.vtu"]))
    <?xml version="1.0"?>
    <VTKFile type="Collection" version="0.1">
      <Collection>
        <DataSet timestep="1" part="0" file="a_0001.vtu"/>
      </Collection>
    </VTKFile>
    <BLANKLINE>
    """
    rows = "".join(f'    <DataSet timestep="{k + 1}" part="0" file="{f}"/>\n'
                   for k, f in enumerate(files))
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
            f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")


def _series(result) -> dict:
    """The writers of the series of a contact result (:data:`SERIES`): each load step's
    displacement.vtu and interface.vtu, and their collections."""
    if not getattr(result, "is_contact", False) or not _solved(result):
        return {}
    from ..contact.history import step_results  # the contact layer, below this one
    steps = step_results(result)
    writers = {}
    for kind, write in (("displacement", _write_displacement),
                        ("interface", _write_interface)):
        files = [f"{kind}_{k + 1:04d}.vtu" for k in range(len(steps))]
        for name, step in zip(files, steps):
            writers[name] = lambda path, step=step, write=write: write(step, path)
        writers[f"{kind}.pvd"] = lambda path, files=files: path.write_text(_pvd(files))
    return writers


def write_result(result, out_dir: str | Path) -> dict[str, Path]:
    """Write ``result.json``, ``displacement.vtu`` and ``interface.vtu`` into ``out_dir``.

    All or nothing, as one set (see the module notes): ``out_dir`` is replaced
    by a folder holding the three new files once all are complete.

    Parameters
    ----------
    result
        A :class:`skxfem.result.Result` (or any object with the same
        attributes), of a tie or of contact.
    out_dir
        Folder to write into; created if missing (and removed again if the
        writing fails); it may hold an earlier result only.

    Returns
    -------
    dict
        ``{"json": ..., "displacement": ..., "interface": ...}`` paths; a contact
        result adds ``"displacement_series"`` and ``"interface_series"``, the
        ``.pvd`` collections of one file per load step (:data:`SERIES`).

    Raises
    ------
    ValueError
        From :func:`check_output` or :func:`result_summary`.
    NotFiniteError
        A result holding NaN or inf (a RuntimeError: never written).
    OSError
        If a file cannot be written (e.g. the disk is full); nothing is left.
    """
    out = check_output(out_dir)
    result_summary(result)                      # refuse a bad result before touching disk
    if not np.all(np.isfinite(np.asarray(result.u_regions, dtype=float))):
        raise NotFiniteError("the result's u_regions (the fields of displacement.vtu) "
                             "holds NaN or inf; nothing was written: please report this scene")
    writers = {name: (lambda path, key=key: _WRITERS[key](result, path))
               for key, name in _FILES.items()}
    series = _series(result)
    written = write_set(out, {**writers, **series}, SERIES)
    paths = {key: written[name] for key, name in _FILES.items()}
    if series:
        paths.update({f"{kind}_series": written[f"{kind}.pvd"]
                      for kind in ("displacement", "interface")})
    return paths


# -----------------------------------------------------------------------------
# What ``result.json`` adds for a contact result: the law, and every load step at the dofs.
# -----------------------------------------------------------------------------


EQUATIONS = ("equilibrium", "contact", "friction")
"""The equations whose relative residuals :class:`~skxfem.contact.newton.NewtonInfo` holds."""


def _tangents(result) -> np.ndarray:
    """(m, k, dim): the tangent frame of each multiplier dof's normal.

    On a plane Γ it is the frame of ``ops.Bt``; on a curved Γ the components
    are ψ_j-weighted means over frames that turn with n, close to this one.
    """
    return np.moveaxis(tangent_frames(result.ops.normals), 2, 0)


def _step(step) -> dict:
    """One load step's entry of ``result.json``."""
    residuals = np.asarray(step.newton.residuals, dtype=float).reshape(-1, len(EQUATIONS))
    status = [STATUS_NAMES[k] for k in np.asarray(step.status)]
    return {
        "load": step.load if isinstance(step.load, str) else float(step.load),
        "law": list(step.law),
        "increments": int(step.increments),
        "pressure": np.asarray(step.pressure, dtype=float),
        "tangential_traction": np.asarray(step.traction, dtype=float),
        "gap": np.asarray(step.gap, dtype=float),
        "slip": np.asarray(step.slip, dtype=float),
        "Lambda": np.asarray(step.Lambda, dtype=float),
        "status": status,
        "counts": {name: status.count(name) for name in STATUS_NAMES},
        "newton": {"iterations": int(step.newton.iterations),
                   "residuals": dict(zip(EQUATIONS, residuals.T, strict=True)),
                   "krylov": [int(k) for k in step.newton.inner]},
    }


def contact_summary(result) -> dict:
    """What a contact ``result.json`` adds to a tie's: the ``status`` of each point,
    the multiplier ``dofs`` (with the interface of each: where the laws are imposed,
    :mod:`skxfem.contact.interface`) and one entry per load step at the dofs
    (``pressure`` p = -λ ≥ 0, ``gap`` the weighted normal jump d ≤ 0, ``slip`` and
    ``tangential_traction`` on the dof's ``tangents``, ``status``); μ and the ρ
    used are in ``interfaces`` (:func:`result_summary`).

    Arrays are numpy arrays here (:func:`skxfem.app.io.result_summary` turns
    them into lists, NaN into ``null``); a set of points or vectors is one
    row per point, as in the tie's file.

    Raises
    ------
    ValueError
        If the result has no load step.

    >>> from dataclasses import replace
    >>> from skxfem import contact
    >>> from skxfem.scene import Displacement
    >>> from skxfem.scene.benchmarks import strip
    >>> s = strip(n=3)
    >>> s = replace(s, law="frictionless",
    ...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
    >>> data = contact_summary(contact.solve(s))
    >>> data["steps"][-1]["status"], data["status_codes"]["slip"]
    (['slip', 'slip', 'slip', 'slip'], 2)
    >>> data["status"] == data["steps"][-1]["status"]   # quads: one dof per cut edge
    True
    """
    if len(result.steps) == 0:
        raise ValueError("the contact result has no load step; give a non-empty history")
    ops = result.ops
    dofs = {"points": np.asarray(ops.points, dtype=float).T,
            "normals": np.asarray(ops.normals, dtype=float).T,
            "tangents": _tangents(result),
            "weights": np.asarray(ops.w, dtype=float),
            "interface": np.asarray(ops.interface).tolist()}
    return {
        "status_codes": {name: code for code, name in enumerate(STATUS_NAMES)},
        "status": [STATUS_NAMES[k] for k in np.asarray(result.status)],
        "dofs": dofs,
        "n_steps": len(result.steps),
        "newton_iterations": result.iterations,
        "steps": [_step(st) for st in result.steps],
    }
