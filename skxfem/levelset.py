r"""Level sets: the interface Γ as the zero set of a function ψ.

The one sign convention of skxfem
---------------------------------
Every module, chapter and test uses the convention stated here and nowhere else.

* Ω⁻ = {ψ < 0} is the paper's body Ω¹ ("below" the interface) and
  Ω⁺ = {ψ > 0} is Ω² ("above").  Γ = {ψ = 0}.
* The unit normal of Γ is n = ∇ψ/|∇ψ|: it points from Ω⁻ into Ω⁺ and is the
  paper's n = n¹, the outward normal of Γ¹ = ∂Ω⁻ ∩ Γ.  It is the one normal:
  tractions are reported on it at every multiplier point (:func:`point_normals`,
  from :func:`gradient`: analytic for planes, circles, spheres and their
  combinations, a central difference otherwise); only for ψ given as nodal
  values do the facets' normals stand in.
* The generalised Heaviside function is H = -1 in Ω⁻ and H = +1 in Ω⁺
  (paper §4.1), so the X-FEM field is u = Σ aᵢφᵢ + Σ bⱼφⱼH (eq. 11).
* The jump is [[u]] = u(p¹) - u(p²) = u⁻ - u⁺ (eq. 3), hence
  [[u]] = -2 Σⱼ φⱼ bⱼ on Γ, and the normal gap is d_n = [[u]]·n ≤ 0 (eq. 3):
  a negative d_n opens the interface, a positive one would mean interpenetration.
* The interface traction is r = σ(u⁻)·n = λn + r_τ (eq. 4); λ ≤ 0 in contact
  (eq. 5).  Results report the contact *pressure* p = -λ, positive in compression.

A level set is any callable ``psi(x)`` taking coordinates ``x`` of shape ``(dim, ...)``
(scikit-fem's layout: ``x[0]`` is the first coordinate) and returning real numbers
of shape ``(...)``.  The helpers below build signed-distance functions, with their
gradients, and combine them; :func:`nodal_values` evaluates one on a mesh, checked.

>>> import numpy as np
>>> psi = plane(point=(0.0, 0.5), normal=(0.0, 1.0))
>>> psi(np.array([[0.2, 0.2], [0.0, 1.0]]))
array([-0.5,  0.5])
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike

from .linalg.scalars import is_integer

__all__ = ["LevelSet", "plane", "circle", "sphere", "union", "intersection",
           "complement", "nodal_values", "gradient", "point_normals", "unit"]


@dataclass(frozen=True)
class LevelSet:
    """A named level set function ψ with its spatial dimension.

    Parameters
    ----------
    fun
        ``fun(x) -> ψ(x)``: for ``x`` of shape ``(dim, ...)``, reals of shape ``(...)``.
    dim
        Number of coordinates ``fun`` reads (the int 2 or 3).
    name
        Human-readable description, used in error messages and plots.
    grad
        Optional ``grad(x) -> ∇ψ(x)``, finite and of the shape of ``x``; without
        it :meth:`gradient` takes central differences of ``fun``.

    Bad arguments raise TypeError/ValueError, a ``fun`` or ``grad`` breaking this ValueError.
    """

    fun: Callable[[np.ndarray], np.ndarray]
    dim: int
    name: str = "psi"
    grad: Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self):
        if not callable(self.fun):
            raise TypeError(f"LevelSet fun must be a callable psi(x), got {self.fun!r}")
        ok = is_integer(self.dim)
        if not ok or self.dim not in (2, 3):
            raise (ValueError if ok else TypeError)(
                f"LevelSet dim must be the int 2 or 3 (coordinates fun reads), got {self.dim!r}")
        object.__setattr__(self, "dim", int(self.dim))
        if not (self.grad is None or callable(self.grad)):
            raise TypeError(f"LevelSet grad must be None or callable, got {self.grad!r}")

    def _points(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        if x.shape[0] != self.dim:
            raise ValueError(f"level set {self.name!r} is {self.dim}D but got points with "
                             f"{x.shape[0]} coordinates; use a {x.shape[0]}D level set")
        return x

    def __call__(self, x: ArrayLike) -> np.ndarray:
        x = self._points(x)
        return _real(self.fun(x), x.shape[1:], f"level set {self.name!r}", "one value per point")

    def gradient(self, x: ArrayLike) -> np.ndarray:
        """∇ψ at ``x`` (dim, ...): ``grad`` if given, else :func:`gradient`'s differences."""
        x = self._points(x)
        if self.grad is None:
            return gradient(self, x)
        who = f"grad of level set {self.name!r}"
        g = _real(self.grad(x), x.shape, who, "∇ψ shaped like the points x")
        if not np.all(np.isfinite(g)):
            raise ValueError(f"{who} returned NaN or inf; ∇ψ must be finite")
        return g


def _real(v, shape: tuple, who: str, what: str) -> np.ndarray:
    """``v`` as floats of ``shape``, else a ValueError saying what ``who`` returned."""
    try:
        a = np.asarray(v)
    except ValueError:  # a ragged list: refused below as an object
        a = np.asarray(None)
    if a.dtype.kind not in "iuf" or a.shape != shape:
        raise ValueError(f"{who} must return real numbers, {what}: expected shape {shape}, "
                         f"got dtype {a.dtype}, shape {a.shape}: {repr(v)[:40]}")
    return a.astype(float, copy=False)


def gradient(psi: Callable, x: ArrayLike) -> np.ndarray:
    """∇ψ at points ``x`` of shape (dim, ...), for any level set callable.

    A :class:`LevelSet` with an analytic gradient (plane, circle, sphere and their
    combinations) returns it.  Otherwise a central difference with the step
    h = ε^(1/3) max|x| (ε the machine epsilon), balancing truncation h²|ψ‴|/6 and
    round-off ε|ψ|/h: an error near ε^(2/3) ≈ 4e-11 for ψ smooth on the scale of x.
    Within h of a kink it is meaningless: use :func:`union` or :func:`intersection`.

    >>> gradient(circle((0, 0), 1.0), np.array([[3.0], [4.0]])).ravel().tolist()
    [0.6, 0.8]
    >>> g = gradient(lambda x: x[0] ** 2 + x[1], np.array([[0.5], [2.0]]))
    >>> bool(np.allclose(g.ravel(), [1.0, 1.0], atol=1e-9))
    True
    """
    if isinstance(psi, LevelSet) and psi.grad is not None:
        return psi.gradient(x)
    f = psi if isinstance(psi, LevelSet) else (
        lambda y: _real(psi(y), y.shape[1:], "psi", "one value per point"))
    x = np.asarray(x, dtype=float)
    h = np.finfo(float).eps ** (1 / 3) * max(float(np.abs(x).max(initial=0.0)), 1e-300)
    g = np.empty(x.shape)
    for i in range(x.shape[0]):  # dim evaluations each way, vectorised over the points
        xp, xm = x.copy(), x.copy()
        xp[i] += h
        xm[i] -= h
        g[i] = (f(xp) - f(xm)) / (xp[i] - xm[i])
    return g


def _vector(name: str, v: ArrayLike) -> np.ndarray:
    try:
        a = np.asarray(v)
    except ValueError:  # a ragged list: refused below as an object
        a = np.asarray(None)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be a sequence of 2 or 3 real numbers, got {v!r}")
    if a.ndim != 1 or a.size not in (2, 3):
        raise ValueError(f"{name} must be a 2- or 3-vector, got {v!r}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return a.astype(float)


def plane(point: ArrayLike, normal: ArrayLike) -> LevelSet:
    """Signed distance to the plane (a line in 2D) through ``point``.

    ψ(x) = (x - point)·n̂ with n̂ = normal/|normal|, so ``normal`` points into Ω⁺.
    Only the direction of ``normal`` counts: it is scaled by its largest
    component before |normal| is taken, so that no size overflows (1e200)
    or underflows (1e-320) to a zero n̂; a zero normal is refused.

    >>> psi = plane((0, 0, 0.5), (0, 0, 2))
    >>> float(psi(np.array([0.1, 0.2, 1.0])))
    0.5
    >>> plane((0, 0), (1e200, 1e200)).name
    'plane(point=[0.0, 0.0], normal=[0.7071067811865475, 0.7071067811865475])'
    """
    x0, n = _vector("point", point), _vector("normal", normal)
    if x0.size != n.size:
        raise ValueError("point and normal must have the same dimension")
    if (top := np.abs(n).max()) == 0.0:
        raise ValueError(f"normal must be non-zero (it gives the direction of ∇ψ, into Ω⁺), "
                         f"got {normal!r}")
    n = n / top
    n, d = n / np.linalg.norm(n), n.size
    return LevelSet(lambda x: sum(n[i] * (x[i] - x0[i]) for i in range(d)), d,
                    f"plane(point={x0.tolist()}, normal={n.tolist()})",
                    lambda x: np.broadcast_to(n.reshape((d,) + (1,) * (x.ndim - 1)), x.shape))


def _ball(center: ArrayLike, radius: float, dim: int, kind: str) -> LevelSet:
    x0 = _vector("center", center)
    if x0.size != dim:
        raise ValueError(f"{kind} center must have {dim} coordinates, got {center!r}")
    if isinstance(radius, bool) or not isinstance(radius, numbers.Real):
        raise TypeError(f"{kind} radius must be a real number, got {radius!r}; pass e.g. 0.3")
    if not (np.isfinite(radius := float(radius)) and radius > 0):
        raise ValueError(f"{kind} radius must be a positive number, got {radius!r}")

    def grad(x):  # (x - x0)/|x - x0|; 0 at the centre, where ψ has no gradient
        d = x - x0.reshape((dim,) + (1,) * (x.ndim - 1))
        r = np.sqrt((d ** 2).sum(axis=0))
        return d / np.where(r > 0, r, 1.0)

    return LevelSet(lambda x: np.sqrt(sum((x[i] - x0[i]) ** 2 for i in range(dim))) - radius,
                    dim, f"{kind}(center={x0.tolist()}, radius={radius})", grad)


def circle(center: ArrayLike, radius: float) -> LevelSet:
    """Signed distance to a circle: Ω⁻ is the disc inside.

    >>> float(circle((0, 0), 1.0)(np.array([2.0, 0.0])))
    1.0
    """
    return _ball(center, radius, 2, "circle")


def sphere(center: ArrayLike, radius: float) -> LevelSet:
    """Signed distance to a sphere: Ω⁻ is the ball inside.

    >>> float(sphere((0, 0, 0), 1.0)(np.array([0.0, 0.0, 0.5])))
    -0.5
    """
    return _ball(center, radius, 3, "sphere")


def _same_dim(op: str, a: LevelSet, b: LevelSet) -> int:
    for k, v in (("a", a), ("b", b)):
        if not isinstance(v, LevelSet):
            raise TypeError(f"{op}: {k} must be a LevelSet (plane, circle, ...; wrap a callable "
                            f"as LevelSet(fun, dim)), got {type(v).__name__} {v!r}")
    if a.dim != b.dim:
        raise ValueError(f"cannot combine a {a.dim}D and a {b.dim}D level set")
    return a.dim


def _active(a: LevelSet, b: LevelSet, pick_a: Callable) -> Callable:
    """∇ of min or max: the gradient of the branch ``pick_a(ψ_a, ψ_b)`` selects."""
    return lambda x: np.where(pick_a(a(x), b(x)), a.gradient(x), b.gradient(x))


def union(a: LevelSet, b: LevelSet) -> LevelSet:
    """Ω⁻ = Ω⁻(a) ∪ Ω⁻(b), via ψ = min(ψ_a, ψ_b); ∇ψ is that of the smaller."""
    return LevelSet(lambda x: np.minimum(a(x), b(x)), _same_dim("union", a, b),
                    f"union({a.name}, {b.name})", _active(a, b, np.less_equal))


def intersection(a: LevelSet, b: LevelSet) -> LevelSet:
    """Ω⁻ = Ω⁻(a) ∩ Ω⁻(b), via ψ = max(ψ_a, ψ_b); ∇ψ is that of the larger."""
    return LevelSet(lambda x: np.maximum(a(x), b(x)), _same_dim("intersection", a, b),
                    f"intersection({a.name}, {b.name})", _active(a, b, np.greater_equal))


def complement(a: LevelSet) -> LevelSet:
    """Swap the sides: ψ → -ψ (so ∇ψ and n flip too)."""
    return LevelSet(lambda x: -a(x), _same_dim("complement", a, a), f"complement({a.name})",
                    lambda x: -a.gradient(x))


def nodal_values(psi: Callable, mesh) -> np.ndarray:
    """ψ at the vertices of a scikit-fem ``mesh``, shape ``(nverts,)``, checked.

    ``psi`` is a :class:`LevelSet` or any callable on ``(dim, nverts)`` arrays.
    A ValueError if the dimensions differ or ψ returns anything but finite real
    numbers, one per vertex.

    >>> from skfem import MeshTri1
    >>> nodal_values(plane((0.5, 0), (1, 0)), MeshTri1()).tolist()
    [-0.5, 0.5, -0.5, 0.5]
    """
    dim = getattr(psi, "dim", None)
    if dim is not None and dim != mesh.dim():
        raise ValueError(f"psi is a {dim}D level set but the mesh is {mesh.dim()}D; "
                         f"build the level set with {mesh.dim()} coordinates")
    who = f"level set {psi.name!r}" if isinstance(psi, LevelSet) else "psi"
    values = _real(psi(mesh.p), mesh.p.shape[1:], who, "one value per point")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{who} returned NaN or inf at some mesh vertices; "
                         "check the level set and the mesh coordinates")
    return values


def point_normals(cut, psi=None) -> np.ndarray:
    """The unit normals n = ∇ψ/|∇ψ| (dim, n_points) at the multiplier points of a cut.

    ``cut`` is a :class:`skxfem.cut.Cut`, ``psi`` the level set callable the mesh
    was cut by (see :func:`gradient`): exact for planes, circles, spheres.  With
    ``None`` or nodal values ψ is known only at the nodes, and each point gets the
    area-weighted mean normal of its facets.  A ValueError if ∇ψ vanishes (or is not finite).

    >>> from skfem import MeshTri1
    >>> from skxfem.cut import cut as cut_mesh
    >>> cut = cut_mesh(MeshTri1().refined(3), circle((0.5, 0.5), 0.3))
    >>> n = point_normals(cut, circle((0.5, 0.5), 0.3))
    >>> r = cut.points - 0.5
    >>> bool(np.allclose(n, r / np.linalg.norm(r, axis=0), atol=1e-14))
    True
    """
    if psi is None or not callable(psi):  # facet normals weighted by their measures
        n = np.zeros_like(cut.points)
        np.add.at(n.T, cut.facets.ravel(),
                  np.tile((cut.normals * cut.measures).T, (cut.facets.shape[0], 1)))
    else:
        n = gradient(psi, cut.points)
    n, size = unit(n)
    if not np.all(ok := np.isfinite(size) & (size > 0)):
        what = "is NaN or inf" if not np.isfinite(size[~ok]).all() else "vanishes"
        raise ValueError(f"∇ψ {what} at interface points {cut.points[:, ~ok].T[:3].tolist()}"
                         f": Γ has no normal there; use a level set finite, with ∇ψ ≠ 0, on Γ")
    return n


def unit(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The columns of ``v`` (dim, n) as unit vectors, and the largest |component| of
    each, with no overflow or underflow in between (each column is divided by that
    first): ∇ψ of ``1e300*(y - 0.5)`` has a norm whose square overflows.  A column
    that is 0 or not finite stays as it is (its largest component 0, or inf or NaN).

    >>> n, top = unit(np.array([[3e300, 0.0], [-4e300, 0.0]]))
    >>> n.tolist(), top.tolist()
    ([[0.6, 0.0], [-0.8, 0.0]], [4e+300, 0.0])
    """
    v = np.asarray(v, dtype=float)
    with np.errstate(all="ignore"):
        top = np.abs(v).max(axis=0)
        ok = np.isfinite(top) & (top > 0)
        scaled = v / np.where(ok, top, 1.0)
        return np.where(ok, scaled / np.linalg.norm(np.where(ok, scaled, 1.0), axis=0), v), top
