r"""The tip frame of a crack and the polar coordinates (r, θ) around its front.

A crack is described by two level sets (see :mod:`skxfem.levelset` for ψ):

* ψ, whose zero set carries the crack: Ω⁻ = {ψ < 0}, Ω⁺ = {ψ > 0}, n = ∇ψ/|∇ψ|;
* φ, which cuts it: the crack is the part of {ψ = 0} where φ < 0, the front
  is {ψ = 0, φ = 0}, and φ > 0 lies ahead of the crack.

The frame and its signs, stated once
------------------------------------
At a point of the front,

.. math:: e_1 = \frac{\nabla\varphi}{|\nabla\varphi|}\ \text{(ahead of the crack)},\qquad
          e_2 = \frac{\nabla\psi}{|\nabla\psi|} = n\ \text{(into } \Omega^+),\qquad
          e_3 = e_1 \times e_2\ \text{(3D: along the front)}.

In 3D the frame is right-handed by construction.  In 2D there is no e₃ and
(e₁, e₂) may be either handed; elasticity is isotropic, so the near-tip fields
written in (e₁, e₂) hold in both.  If ∇φ is not exactly normal to ∇ψ (level
sets that are not re-orthogonalised), :func:`tip_frame` keeps e₂ = n, the one
normal of the package, and takes e₁ from the part of ∇φ normal to it:
e₁ = (∇φ - (∇φ·n) n)/|∇φ - (∇φ·n) n|, which is ∇φ/|∇φ| when ∇φ ⟂ ∇ψ.

Polar coordinates
-----------------
With local coordinates x₁ = φ and x₂ = ψ, both **signed distances** (|∇φ| =
|∇ψ| = 1) and **orthogonal** (∇φ·∇ψ = 0), which is exact for a straight front
and holds to first order in the distance for a curved one,

.. math:: r = \sqrt{\psi^2 + \varphi^2} \ \text{(distance to the front)},\qquad
          \theta = \operatorname{atan2}(\psi, \varphi) \in [-\pi, \pi].

θ = 0 ahead of the crack, θ > 0 on the Ω⁺ side, θ = ±π on the crack faces
only: +π on the face of Ω⁺ and -π on the face of Ω⁻ (:func:`polar` takes the
side of points lying exactly on the faces), so that off the faces θ ∈ (-π, π).
Their gradients, used by every chain rule of the package (:func:`polar_gradients`),
are

.. math:: \nabla r = \cos\theta\, e_1 + \sin\theta\, e_2, \qquad
          \nabla\theta = \frac{-\sin\theta\, e_1 + \cos\theta\, e_2}{r}.

Arrays follow scikit-fem's layout: a vector field is ``(dim, ...)``, the
first index the component.

>>> import numpy as np
>>> f = tip_frame(np.array([1.0, 0.0]), np.array([0.0, 2.0]))
>>> f.e1.tolist(), f.e2.tolist(), f.e3
([1.0, 0.0], [0.0, 1.0], None)
>>> r, theta = polar(np.array([-1.0, 0.0]), np.array([0.0, 1.0]), side=1)
>>> r.tolist(), (theta / np.pi).tolist()     # on the Ω⁺ face, then straight above
([1.0, 1.0], [1.0, 0.5])
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["TipFrame", "tip_frame", "straight_frame", "local_coordinates", "polar",
           "polar_gradients", "face_tolerance", "ON_FACE"]

ON_FACE = 1e-10
"""With a ``side``, :func:`polar` puts a point on a crack face when |ψ| ≤ ON_FACE r (and
φ < 0), or within :func:`face_tolerance` of it: the round-off of a point computed on the
face in global coordinates, far below the distance of any quadrature point off the face."""


def as_real(name: str, value: ArrayLike, shape: tuple | None = None,
            finite: bool = True) -> np.ndarray:
    """``value`` as a float array, else a ValueError naming the argument ``name``.

    ``shape`` (optional) is the shape it must have; ``finite`` refuses NaN and inf.

    >>> as_real("r", [1, 2]).dtype
    dtype('float64')
    """
    try:
        a = np.asarray(value)
    except ValueError:              # a ragged list
        a = np.asarray(None)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{name} must be an array of real numbers, got dtype {a.dtype}: "
                         f"{repr(value)[:60]}")
    a = a.astype(float, copy=False)
    if shape is not None and a.shape != tuple(shape):
        raise ValueError(f"{name} must have shape {tuple(shape)}, got {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        bad = int(np.size(a) - np.isfinite(a).sum())
        raise ValueError(f"{name} holds {bad} NaN or infinite value(s); it must be finite")
    return a


def _field(name: str, value: ArrayLike) -> np.ndarray:
    a = as_real(name, value)
    if a.ndim == 0 or a.shape[0] not in (2, 3):
        raise ValueError(f"{name} must be a vector field of shape (dim, ...) with dim 2 or 3, "
                         f"got shape {a.shape}")
    return a


def _unit(name: str, v: np.ndarray) -> np.ndarray:
    size = np.sqrt((v ** 2).sum(axis=0))
    if np.any(size == 0):
        raise ValueError(f"{name} is zero at {int((size == 0).sum())} point(s): no direction")
    return v / size


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


@dataclass(frozen=True)
class TipFrame:
    """The tip frame: unit vectors e₁ (ahead), e₂ = n (into Ω⁺), e₃ = e₁ × e₂ (3D).

    Attributes
    ----------
    e1, e2 : (dim, ...) arrays, one frame per point (``(dim,)`` for one frame).
    e3 : (3, ...) in 3D, None in 2D.
    """

    e1: np.ndarray
    e2: np.ndarray
    e3: np.ndarray | None = None

    @property
    def dim(self) -> int:
        return int(self.e1.shape[0])

    @property
    def R(self) -> np.ndarray:
        """The rotation (dim, dim, ...): its rows are e₁, e₂ (, e₃), so x_local = R x."""
        rows = [self.e1, self.e2] + ([self.e3] if self.e3 is not None else [])
        return np.stack(rows)

    def to_local(self, v: ArrayLike) -> np.ndarray:
        """Components (v·e₁, v·e₂, ...) of a vector field ``v`` of shape (dim, ...)."""
        return np.einsum("ab...,b...->a...", self.R, _field("v", v))

    def to_global(self, v: ArrayLike) -> np.ndarray:
        """The vector Σ_a v_a e_a of local components ``v`` (dim, ...)."""
        return np.einsum("ab...,a...->b...", self.R, _field("v", v))

    def tensor_to_local(self, T: ArrayLike) -> np.ndarray:
        """R T Rᵀ: a tensor field (dim, dim, ...) in the frame's components."""
        return np.einsum("ai...,ij...,bj...->ab...", self.R, as_real("T", T), self.R)

    def tensor_to_global(self, T: ArrayLike) -> np.ndarray:
        """Rᵀ T R: a tensor field given in the frame's components, back to global ones."""
        return np.einsum("ai...,ab...,bj...->ij...", self.R, as_real("T", T), self.R)


def tip_frame(grad_phi: ArrayLike, grad_psi: ArrayLike) -> TipFrame:
    """The tip frame from the gradients of the two level sets.

    Parameters
    ----------
    grad_phi : (dim, ...) ∇φ, φ > 0 ahead of the crack.
    grad_psi : (dim, ...) ∇ψ, ψ > 0 in Ω⁺; same shape.

    Returns
    -------
    TipFrame
        e₂ = ∇ψ/|∇ψ|, e₁ the unit part of ∇φ normal to e₂, e₃ = e₁ × e₂ in 3D.

    Raises
    ------
    ValueError
        On NaN, shapes that differ or are not (dim, ...), a zero gradient, or ∇φ
        parallel to ∇ψ (no front there).

    Examples
    --------
    >>> f = tip_frame([0.0, 0.0, 3.0], [0.0, 1.0, 0.0])
    >>> f.e1.tolist(), f.e2.tolist(), f.e3.tolist()
    ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
    """
    gphi, gpsi = _field("grad_phi", grad_phi), _field("grad_psi", grad_psi)
    if gphi.shape != gpsi.shape:
        raise ValueError(f"grad_phi and grad_psi must have the same shape, got {gphi.shape} "
                         f"and {gpsi.shape}")
    e2 = _unit("grad_psi", gpsi)
    tangent = gphi - (gphi * e2).sum(axis=0) * e2
    size, scale = np.sqrt((tangent ** 2).sum(axis=0)), np.sqrt((gphi ** 2).sum(axis=0))
    if np.any(size <= 1e-12 * scale) or np.any(scale == 0):
        raise ValueError("grad_phi is zero or parallel to grad_psi at "
                         f"{int(np.sum((size <= 1e-12 * scale) | (scale == 0)))} point(s): "
                         "the level sets do not cross there, so there is no front")
    e1 = tangent / size
    return TipFrame(e1, e2, _cross(e1, e2) if gphi.shape[0] == 3 else None)


def straight_frame(e1: ArrayLike, e2: ArrayLike) -> TipFrame:
    """One frame from the two directions (a straight front): :func:`tip_frame` of them.

    >>> straight_frame([0.0, 1.0], [-1.0, 0.0]).R.tolist()
    [[0.0, 1.0], [-1.0, 0.0]]
    """
    return tip_frame(e1, e2)


def local_coordinates(x: ArrayLike, origin: ArrayLike, frame: TipFrame) -> np.ndarray:
    """Coordinates x_a = e_a·(x - origin) of points ``x`` (dim, ...) in a frame.

    ``origin`` is a point of the front (dim,) and ``frame`` one frame (vectors of
    shape (dim,)).  For a straight front x₁ = φ, x₂ = ψ are the two signed distances.

    >>> f = straight_frame([0.0, 1.0], [-1.0, 0.0])
    >>> local_coordinates(np.array([[1.0], [3.0]]), [1.0, 1.0], f).ravel().tolist()
    [2.0, 0.0]
    """
    x = _field("x", x)
    o = as_real("origin", origin, (x.shape[0],))
    if frame.e1.shape != (x.shape[0],):
        raise ValueError(f"frame must be one frame of {x.shape[0]}D vectors (shape "
                         f"({x.shape[0]},)), got e1 of shape {frame.e1.shape}")
    d = x - o.reshape((-1,) + (1,) * (x.ndim - 1))
    return np.tensordot(frame.R, d, axes=(1, 0))


def face_tolerance(x: ArrayLike, origin: ArrayLike) -> np.ndarray:
    """How far from ψ = 0 the local coordinates of points ``x`` computed on a face may
    land: :data:`ON_FACE` (|x - origin| + |origin|), the round-off of
    e₂·(x - origin) for points given in global coordinates.

    >>> face_tolerance(np.array([[3.0], [4.0]]), [0.0, 0.0]).tolist()
    [5e-10]
    """
    x = _field("x", x)
    o = as_real("origin", origin, (x.shape[0],)).reshape((-1,) + (1,) * (x.ndim - 1))
    return ON_FACE * (np.sqrt(((x - o) ** 2).sum(axis=0)) + np.sqrt((o ** 2).sum()))


def polar(phi: ArrayLike, psi: ArrayLike, side: ArrayLike | None = None,
          tol: ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Polar coordinates (r, θ) around the front from the level-set values.

    r = √(ψ² + φ²), θ = atan2(ψ, φ) ∈ [-π, π]; this assumes φ and ψ signed
    distances, orthogonal (see the module notes).  On the crack faces (ψ = 0,
    φ < 0) the side decides: θ = +π on the face of Ω⁺, -π on the face of Ω⁻.
    Points computed on a face in global coordinates carry ψ of round-off, not
    zero: with ``side``, points with φ < 0 and |ψ| ≤ ``tol`` count as on the face.

    Parameters
    ----------
    phi, psi : arrays of the same shape: φ (> 0 ahead) and ψ (> 0 in Ω⁺).
    side : optional +1 or -1 (array broadcasting with ``phi``): which face the
        points with |ψ| ≤ tol, φ < 0 belong to.  Without it the sign of the zero
        ψ decides, as in ``atan2`` (+0.0: Ω⁺, -0.0: Ω⁻).
    tol : with ``side``, how far from ψ = 0 a point of a face may be (array
        broadcasting with ``phi``); default :data:`ON_FACE` r.  The round-off of
        local coordinates is relative to the global ones: :func:`face_tolerance`.

    Returns
    -------
    r, theta : arrays of the shape of ``phi``.

    Examples
    --------
    >>> r, t = polar(np.array([3.0, 0.0]), np.array([4.0, -2.0]))
    >>> r.tolist(), (t / np.pi).tolist()
    ([5.0, 2.0], [0.2951672353008665, -0.5])
    >>> float(polar(-1.0, 0.0, side=-1)[1] / np.pi)
    -1.0
    """
    phi, psi = as_real("phi", phi), as_real("psi", psi)
    if phi.shape != psi.shape:
        raise ValueError(f"phi and psi must have the same shape, got {phi.shape} and "
                         f"{psi.shape}")
    r, theta = np.hypot(phi, psi), np.arctan2(psi, phi)
    if side is not None:
        s = as_real("side", side)
        if not np.all(np.abs(s) == 1):
            raise ValueError("side must be +1 (the face of Ω⁺) or -1 (the face of Ω⁻)")
        try:
            s = np.broadcast_to(s, phi.shape)
        except ValueError:
            raise ValueError(f"side of shape {s.shape} does not broadcast to the shape of "
                             f"phi, {phi.shape}") from None
        tol = ON_FACE * r if tol is None else as_real("tol", tol)
        theta = np.where((np.abs(psi) <= tol) & (phi < 0), s * np.pi, theta)
    return r, theta


def polar_gradients(r: ArrayLike, theta: ArrayLike, frame: TipFrame
                    ) -> tuple[np.ndarray, np.ndarray]:
    """∇r and ∇θ (each (dim, ...)) at points of polar coordinates (r, θ) in ``frame``.

    ∇r = cos θ e₁ + sin θ e₂ and ∇θ = (-sin θ e₁ + cos θ e₂)/r: the derivatives
    of r = √(x₁² + x₂²), θ = atan2(x₂, x₁) for x_a = e_a·(x - origin).
    ``frame`` is one frame (vectors (dim,)) or one per point (dim, ...).

    >>> f = straight_frame([1.0, 0.0], [0.0, 1.0])
    >>> gr, gt = polar_gradients(2.0, np.pi / 2, f)
    >>> np.round(gr, 12).tolist(), np.round(gt, 12).tolist()
    ([0.0, 1.0], [-0.5, 0.0])
    """
    r, theta = as_real("r", r), as_real("theta", theta)
    if r.shape != theta.shape:
        raise ValueError(f"r and theta must have the same shape, got {r.shape} and "
                         f"{theta.shape}")
    if np.any(r <= 0):
        raise ValueError("r must be positive: ∇θ is singular on the front (r = 0)")
    c, s = np.cos(theta), np.sin(theta)
    e1, e2 = (e.reshape(e.shape + (1,) * (r.ndim - e.ndim + 1)) for e in (frame.e1, frame.e2))
    return c * e1 + s * e2, (-s * e1 + c * e2) / r
