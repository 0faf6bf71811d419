r"""Built-in benchmark scenes.

* :func:`paper_plate`: the 3D plate of Géniaut, Massin & Moës (2007), §5;
* :func:`strip`: its 2D plane-strain analogue;
* :func:`exact_plate`, :func:`exact_strip`: the same with the loads of
  :mod:`skxfem.fem.exact`, under which the paper's reference p(y) is exact;
* :func:`exact_block`: not in the paper, a genuinely 3D check: a cube cut
  by a slanted plane under the loads of :mod:`skxfem.fem.exact3d`.
* :func:`slipping_block`: a cube whose upper part, pressed and held at its top,
  slides on a slanted Coulomb joint: the size benchmark of the contact solver
  (``benchmarks/contact_solve.py``);
* :func:`sliding`, :func:`uniaxial` and :func:`uniform_block`: blocks in a
  uniform contact state (:class:`skxfem.fem.exact.UniformContact`) — sliding at
  the slip limit in any direction, on a horizontal or slanted Γ, or pressed —
  the known answers of the contact solver.

Both are plain :class:`~skxfem.scene.Scene` objects: change a field with
``dataclasses.replace(scene, space=...)``.  ``examples/plate.toml`` and
``examples/strip.toml`` describe the same set-ups as scene files.

>>> scene = paper_plate(n=2)
>>> scene.mesh
Box(n=(2, 2, 3), cell='hex', size=(1.0, 1.0, 1.0))
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..fem.exact import ExactPlate, UniformContact
from ..fem.exact3d import GAMMA_NORMAL, GAMMA_POINT, ExactBlock
from ..fem.material import Material
from ..levelset import plane
from .expr import Expression
from .laws import FRICTION_LAWS
from .model import Box, Displacement, Scene, SurfaceLoad, clamped, rollers

__all__ = ["paper_plate", "slipping_block", "strip", "exact_plate", "exact_strip",
           "exact_scene", "exact_block", "P_MAX", "sliding", "uniaxial", "uniform_block", "DRIVES"]

P_MAX = 1.0
"""Peak of the parabolic pressure, P_max = 1 Pa as in the paper."""


def _odd_cells(n: int, nz: int | None, key: str) -> int:
    if not (isinstance(n, int) and not isinstance(n, bool) and n >= 1):
        raise ValueError(f"n must be a positive integer, got {n!r}")
    if nz is None:
        return n if n % 2 == 1 else n + 1
    if not (isinstance(nz, int) and not isinstance(nz, bool) and nz >= 1 and nz % 2 == 1):
        raise ValueError(f"{key} must be an odd positive integer so that the interface "
                         f"at 0.5 cuts a layer of cells, got {nz!r}")
    return nz


def paper_plate(n: int = 4, cell: str = "hex", nz: int | None = None,
                law: str = "bonded", space: str = "vital", nx: int | None = None) -> Scene:
    """The plate under non-uniform compression of the paper, §5 (Figures 4, 5, 7-10).

    From the paper: a 3D elastic plate whose bottom face is clamped, a parabolic
    pressure p(y) on the top face with P_max = 1 Pa, an interface Γ crossing the
    whole plate at z = 0.5 m, regular meshes of hexahedra or of prisms
    ("pentahedrons") with an *odd* number of cells in z so that Γ cuts cells,
    and 1/h cells in y and z; frictional contact with a Coulomb coefficient
    "high enough to have adherence", i.e. the interface sticks: ``law="bonded"``.

    Assumed here, because the paper does not state it:

    * Ω = [0, 1]³ (Γ at z = 0.5 m suggests a unit height; the pressure
      reference curve 4 P_max y (1 - y) needs y ∈ [0, 1]);
    * p(y) = 4 P_max y (1 - y), the parabola vanishing at y = 0 and y = 1;
    * E = 1 Pa, ν = 0.3 (the contact pressure of this test does not depend on E);
    * rollers u_x = 0 on the faces x = 0 and x = 1, so that the solution does
      not depend on x and is the plane-strain solution of :func:`strip`;
    * the paper's reference contact pressure is p(y) itself ("the analytical
      solution ... equal to the prescribed pressure p(y)").  For an elastic
      block this is an approximation: only the resultant, ∫ σ_zz dy = ∫ p dy on
      every plane z = const, is exact;
    * n cells in x as in y (the paper does not give the count along x).

    Parameters
    ----------
    n
        Cells in x and y (for prisms: n squares in y, each cut into 2 triangles).
    cell
        ``"hex"`` or ``"prism"`` (prisms: triangles in the (y, z) plane extruded
        along x, as in the paper's Figure 4); ``"tet"`` (not in the paper:
        each box cell cut into tetrahedra, see :class:`skxfem.scene.Box`).
    nz
        Cells in z, odd; default ``n`` if odd else ``n + 1``.
    law, space
        Interface law and multiplier space (see :data:`skxfem.scene.LAWS`).
    nx
        Cells in x, default ``n`` (the solution does not depend on x).
    """
    if cell not in ("hex", "prism", "tet"):
        raise ValueError(f"cell must be 'hex', 'prism' or 'tet' for the paper plate, "
                         f"got {cell!r}")
    nz = _odd_cells(n, nz, "nz")
    nx = n if nx is None else nx
    if not (isinstance(nx, int) and not isinstance(nx, bool) and nx >= 1):
        raise ValueError(f"nx must be a positive integer, got {nx!r}")
    return Scene(
        mesh=Box((nx, n, nz), cell, (1.0, 1.0, 1.0)),
        levelset=plane(point=(0.0, 0.0, 0.5), normal=(0.0, 0.0, 1.0)),
        material=Material(E=1.0, nu=0.3, plane="strain"),
        displacements=(clamped("zmin"), rollers("xmin"), rollers("xmax")),
        loads=(SurfaceLoad("zmax", pressure=Expression(f"4*{P_MAX}*y*(1 - y)", 3)),),
        law=law, space=space, name=f"paper_plate_{cell}_{nx}x{n}x{nz}")


def slipping_block(n: int = 8, cell: str = "hex", law: str = "coulomb", mu: float = 0.3,
                   steps: tuple = (0.5, 1.0), space: str = "vital") -> Scene:
    """A cube of n × n × (n + 1) cells whose upper part slides on a slanted joint.

    The unit cube, E = 1000, ν = 0.3, clamped at z = 0; its top z = 1 is held in
    x and y and pressed by p = 10; Γ is the plane through (0.5, 0.5, 0.52) with
    normal (0, 0.4, 1) (a slope of 0.4, steeper than μ = 0.3: with Coulomb
    friction every point of Γ slides).  ``law`` any law (``coulomb`` takes
    ``mu``), applied in the load ``steps``.  The size benchmark of the contact
    solver (issue 27 of the tracker; ``benchmarks/contact_solve.py``).

    >>> s = slipping_block(4)
    >>> s.mesh.n, s.law, s.friction
    ((4, 4, 5), 'coulomb', 0.3)
    """
    return Scene(Box((n, n, n + 1), cell), plane((0.5, 0.5, 0.52), (0.0, 0.4, 1.0)),
                 Material(E=1000.0, nu=0.3),
                 displacements=(clamped("zmin"), Displacement("zmax", {"x": 0.0, "y": 0.0})),
                 loads=(SurfaceLoad("zmax", pressure=10.0),), law=law,
                 friction=mu if law in FRICTION_LAWS else None, steps=tuple(steps),
                 space=space, name=f"slipping_block_{cell}_{n}")


def strip(n: int = 4, cell: str = "quad", ny: int | None = None,
          law: str = "bonded", space: str = "vital", sides: str = "free") -> Scene:
    """The 2D plane-strain analogue of :func:`paper_plate` on [0, 1]².

    The plate's coordinates (y, z) become (x, y): the bottom y = 0 is clamped,
    the pressure p(x) = 4 P_max x (1 - x) acts on the top y = 1, Γ is the line
    y = 0.5 (Ω⁻ below) and the sides x = 0, x = 1 are free (``sides="free"``)
    or on rollers, u_x = 0 (``sides="rollers"``, as the plate's faces x = 0
    and x = 1: then Γ meets a support).  Same material assumptions as
    :func:`paper_plate` (E = 1, ν = 0.3, plane strain).

    Parameters
    ----------
    n
        Cells in x.
    cell
        ``"quad"`` or ``"tri"``.
    ny
        Cells in y, odd; default ``n`` if odd else ``n + 1``.
    law, space
        Interface law and multiplier space.
    sides
        ``"free"`` or ``"rollers"``: the supports of the sides x = 0 and x = 1.

    >>> strip(n=2, cell="tri").mesh
    Box(n=(2, 3), cell='tri', size=(1.0, 1.0))
    >>> strip(n=2, sides="rollers").name
    'strip_quad_2x3_rollers'
    """
    if cell not in ("quad", "tri"):
        raise ValueError(f"cell must be 'quad' or 'tri' for the strip, got {cell!r}")
    if sides not in ("free", "rollers"):
        raise ValueError(f"sides must be 'free' or 'rollers', got {sides!r}")
    ny = _odd_cells(n, ny, "ny")
    supports = (rollers("xmin"), rollers("xmax")) if sides == "rollers" else ()
    return Scene(
        mesh=Box((n, ny), cell, (1.0, 1.0)),
        levelset=plane(point=(0.0, 0.5), normal=(0.0, 1.0)),
        material=Material(E=1.0, nu=0.3, plane="strain"),
        displacements=(clamped("ymin"),) + supports,
        loads=(SurfaceLoad("ymax", pressure=Expression(f"4*{P_MAX}*x*(1 - x)", 2)),),
        law=law, space=space,
        name=f"strip_{cell}_{n}x{ny}" + ("_rollers" if sides == "rollers" else ""))


def _exact_bcs(sol, faces, bottom):
    """Loads and bottom displacement under which :mod:`skxfem.fem.exact` is exact."""
    comps = "xyz"[:sol.dim]
    bottom_u = Displacement(bottom, {c: (lambda x, i=i: sol.displacement(x)[i])
                                     for i, c in enumerate(comps)})
    sides = tuple(SurfaceLoad(f, pressure=sol.side_pressure) for f in faces)
    top = SurfaceLoad("ymax" if sol.dim == 2 else "zmax", pressure=sol.pressure)
    return bottom_u, (top,) + sides


def exact_strip(n: int = 4, cell: str = "quad", ny: int | None = None,
                law: str = "bonded", space: str = "vital") -> Scene:
    """:func:`strip` with the loads of :mod:`skxfem.fem.exact`: the pressure on Γ is p(x).

    Same mesh, material and top pressure as :func:`strip`; in addition a
    pressure 4P y² on the sides x = 0 and x = 1, and the bottom y = 0 held at
    the exact displacement instead of clamped.  Then the exact contact
    pressure on Γ is the paper's reference p(x) = 4P x(1 - x), with zero
    tangential traction, for any E, ν.

    >>> exact_strip(3).name
    'exact_strip_quad_3x3'
    """
    base = strip(n, cell, ny, law, space)
    sol = ExactPlate(base.material, 2, P_MAX)
    bottom_u, loads = _exact_bcs(sol, ("xmin", "xmax"), "ymin")
    return replace(base, displacements=(bottom_u,), loads=loads,
                   name="exact_" + base.name)


def exact_plate(n: int = 4, cell: str = "hex", nz: int | None = None, nx: int | None = None,
                law: str = "bonded", space: str = "vital") -> Scene:
    """:func:`paper_plate` with the loads of :mod:`skxfem.fem.exact` (see :func:`exact_strip`).

    ``nx`` cells along x (default ``n``): with rollers on x = 0 and x = 1 the
    solution does not depend on x, so ``nx = 1`` gives the same answer at a
    fraction of the cost.
    """
    base = paper_plate(n, cell, nz, law, space, nx)
    sol = ExactPlate(base.material, 3, P_MAX)
    bottom_u, loads = _exact_bcs(sol, ("ymin", "ymax"), "zmin")
    return replace(base, displacements=(bottom_u, rollers("xmin"), rollers("xmax")),
                   loads=loads, name="exact_" + base.name)


def exact_scene(n: int, cell: str, space: str = "vital") -> Scene:
    """The exact benchmark of a cell type, cheapest form: :func:`exact_strip`
    for ``"tri"``/``"quad"``, :func:`exact_plate` with one layer of cells
    along x for ``"tet"``/``"hex"``/``"prism"``.  Its interface coordinate
    (the paper's y) is x in 2D and y in 3D.

    >>> exact_scene(8, "tri").dim, exact_scene(8, "prism").mesh.n
    (2, (1, 8, 9))
    """
    if cell in ("tri", "quad"):
        return exact_strip(n, cell, space=space)
    return exact_plate(n, cell, nx=1, space=space)


def exact_block(n: int = 4, cell: str = "hex", law: str = "bonded",
                space: str = "vital") -> Scene:
    """A genuinely 3D benchmark: the unit cube under the loads of :mod:`skxfem.fem.exact3d`.

    n × n × n cells (hexahedra, prisms or tetrahedra of :class:`~skxfem.scene.Box`),
    Γ the plane through :data:`~skxfem.fem.exact3d.GAMMA_POINT` with normal
    :data:`~skxfem.fem.exact3d.GAMMA_NORMAL` (slanted against all three axes,
    it cuts the four side faces), E = 1, ν = 0.3; the bottom z = 0 held at
    the exact displacement, the five other faces loaded by the exact
    traction σ·n.  The exact contact pressure on Γ varies along x, y and z
    (:meth:`~skxfem.fem.exact3d.ExactBlock.pressure`); the field is continuous,
    so the tie law is ``bonded``, or ``bilateral`` for its normal part only
    when the tangential traction is not needed (it is not zero here: use
    ``bonded`` to compare with the exact solution).

    >>> scene = exact_block(3, "tet")
    >>> scene.mesh, len(scene.loads)
    (Box(n=(3, 3, 3), cell='tet', size=(1.0, 1.0, 1.0)), 5)
    """
    if cell not in ("hex", "prism", "tet"):
        raise ValueError(f"cell must be 'hex', 'prism' or 'tet' for the block, got {cell!r}")
    if not (isinstance(n, int) and not isinstance(n, bool) and n >= 1):
        raise ValueError(f"n must be a positive integer, got {n!r}")
    material = Material(E=1.0, nu=0.3)
    sol = ExactBlock(material, P_MAX)
    bottom = Displacement("zmin", {c: (lambda x, i=i: sol.displacement(x)[i])
                                   for i, c in enumerate("xyz")})
    loads = []
    for face in ("xmin", "xmax", "ymin", "ymax", "zmax"):
        axis, sign = "xyz".index(face[0]), (1.0 if face.endswith("max") else -1.0)
        normal = sign * np.eye(3)[:, axis]
        loads.append(SurfaceLoad(face, traction=tuple(
            (lambda x, i=i, m=normal: sol.traction(x, m.reshape((3,) + (1,) * (x.ndim - 1))
                                                   + 0 * x)[i])
            for i in range(3))))
    return Scene(mesh=Box((n, n, n), cell, (1.0, 1.0, 1.0)),
                 levelset=plane(point=GAMMA_POINT, normal=GAMMA_NORMAL),
                 material=material, displacements=(bottom,), loads=tuple(loads),
                 law=law, space=space, name=f"exact_block_{cell}_{n}")


DRIVES = ("displacement", "mixed", "free")
"""How :func:`uniform_block` loads the block: ``displacement``, both ends imposed;
``mixed``, the top's tangential components imposed and its normal stress a
pressure; ``free``, the bottom on rollers (two corners pinned), the top pressed,
the sides free.  The other faces carry the traction of the uniform stress."""


def _frame(dim: int, tilt: float, angle: float):
    """Unit normal n (into the upper body) tilted by ``tilt`` from the vertical
    in the first coordinate plane, and the tangent at ``angle`` from the
    tangent t₁ in that plane (3D: towards t₂ = n × t₁)."""
    c, s = np.cos(tilt), np.sin(tilt)
    n = np.zeros(dim)
    n[0], n[-1] = -s, c
    t1 = np.zeros(dim)
    t1[0], t1[-1] = c, s
    if dim == 2:
        return n, t1 * (1.0 if np.cos(angle) >= 0 else -1.0)
    t2 = np.cross(n, t1)
    return n, np.cos(angle) * t1 + np.sin(angle) * t2


def sliding(dim: int = 2, mu: float = 0.5, slip: float = 0.1, angle: float = 0.0,
            tilt: float = 0.0, p: float = 1.0, ratio: float = 1.0,
            material: Material = Material(1.0, 0.3)) -> UniformContact:
    """A pressed block sliding on Γ: σ = -p n⊗n + r_τ⊗n + n⊗r_τ, r_τ = ratio·μp t.

    ``tilt`` the angle of Γ from the horizontal, ``angle`` the slip direction
    in Γ (3D), ``slip`` how far the upper body has moved along t ([[u]] =
    -slip·t).  ``ratio`` = 1 and ``slip`` > 0: sliding at the limit |r_τ| = μp;
    ``ratio`` = 1 and ``slip`` = 0: exactly at the slip limit, at rest;
    ``ratio`` < 1 and ``slip`` = 0: sticking.

    >>> sol = sliding(2, mu=0.5, slip=0.1)
    >>> sol.pressure, sol.shear.round(12).tolist(), sol.jump.tolist()
    (1.0, [0.5, 0.0], [-0.1, 0.0])
    """
    n, t = _frame(dim, tilt, angle)
    tau = ratio * mu * p * t
    sigma = -p * np.outer(n, n) + np.outer(tau, n) + np.outer(n, tau)
    return UniformContact(material, sigma, n, 0.0 - slip * t)


def uniaxial(dim: int = 2, tilt: float = 0.0, p: float = 1.0,
             material: Material = Material(1.0, 0.3)) -> UniformContact:
    """A block under a vertical pressure p across Γ tilted by ``tilt``: on Γ the
    pressure p cos²(tilt) and the shear p sin(tilt)cos(tilt); it sticks where
    tan(tilt) ≤ μ.

    >>> round(uniaxial(2, tilt=np.pi / 4).pressure, 12)
    0.5
    """
    n, _ = _frame(dim, tilt, 0.0)
    sigma = np.zeros((dim, dim))
    sigma[-1, -1] = -p
    return UniformContact(material, sigma, n)


def uniform_block(sol: UniformContact, cell: str | None = None, n: int = 3,
                  law: str = "coulomb", mu: float = 0.5, drive: str = "displacement",
                  **interface) -> Scene:
    """The unit box [0, 1]^dim cut by Γ through its centre, loaded so that
    ``sol`` is its exact solution (``drive``: :data:`DRIVES`).

    ``cell`` (default ``quad``/``hex``) and ``n`` cells per direction (odd, so
    that Γ cuts cells); ``law``, ``mu`` (its ``friction``, a law with friction
    only) and the keywords ``rho_n``, ``rho_t``,
    ``space`` of the :class:`~skxfem.scene.Scene`.

    >>> s = uniform_block(sliding(2), n=3)
    >>> s.law, [d.boundary for d in s.displacements]
    ('coulomb', ['ymin', 'ymax'])
    """
    dim = sol.dim
    if drive not in DRIVES:
        raise ValueError(f"drive must be one of {DRIVES}, got {drive!r}")
    cell = cell or ("quad" if dim == 2 else "hex")
    axes = "xyz"[:dim]
    v = axes[-1]

    def u(side, i):
        return lambda x: sol.displacement(x, side)[i]

    def face_load(face):
        axis, end = axes.index(face[0]), 1.0 if face.endswith("max") else -1.0
        outward = np.zeros(dim)
        outward[axis] = end
        return SurfaceLoad(face, traction=tuple(float(f) for f in sol.face_traction(outward)))

    sides = [f"{a}{e}" for a in axes[:-1] for e in ("min", "max")]
    top_pressure = float(-sol.sigma[-1, -1])
    if drive == "displacement":
        disp = (Displacement(f"{v}min", {c: u(-1, i) for i, c in enumerate(axes)}),
                Displacement(f"{v}max", {c: u(1, i) for i, c in enumerate(axes)}))
        loads = tuple(face_load(f) for f in sides)
    elif drive == "mixed":
        disp = (Displacement(f"{v}min", {c: u(-1, i) for i, c in enumerate(axes)}),
                Displacement(f"{v}max", {c: u(1, i) for i, c in enumerate(axes[:-1])}))
        loads = tuple(face_load(f) for f in sides) + (
            SurfaceLoad(f"{v}max", pressure=top_pressure),)
    else:
        side_t = [sol.face_traction(np.eye(dim)[i]) for i in range(dim - 1)]
        if any(np.abs(t).max() > 1e-12 * np.abs(sol.sigma).max() for t in side_t):
            raise ValueError("drive='free' needs a stress with traction-free sides")
        corner = lambda x: np.all(np.abs(x) < 1e-12, axis=0)  # noqa: E731
        disp = (Displacement(f"{v}min", {v: u(-1, dim - 1)}),
                Displacement(corner, {c: u(-1, i) for i, c in enumerate(axes[:-1])}))
        if dim == 3:
            other = lambda x: (np.abs(x[0] - 1) < 1e-12) & (np.abs(x[1]) < 1e-12) & (  # noqa
                np.abs(x[2]) < 1e-12)
            disp += (Displacement(other, {"y": u(-1, 1)}),)
        loads = (SurfaceLoad(f"{v}max", pressure=top_pressure),)
    n_cells = (n,) * (dim - 1) + (n if n % 2 else n + 1,)
    return Scene(Box(n_cells, cell), plane((0.5,) * dim, tuple(sol.normal)), sol.material,
                 displacements=disp, loads=loads, law=law,
                 friction=mu if law in FRICTION_LAWS else None,
                 name=f"uniform_{drive}_{cell}_{n}", **interface)
