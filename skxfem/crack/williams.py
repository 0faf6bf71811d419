r"""The exact near-tip fields of Williams: modes I, II (in-plane) and III (antiplane).

In the tip frame (:mod:`skxfem.crack.frame`: x₁ = r cos θ ahead of the tip,
x₂ = r sin θ into Ω⁺, x₃ along the front), a crack with traction-free faces
loaded in mode I, II or III has near its front the displacement and stress
below (e.g. Anderson, *Fracture Mechanics*, tables 2.1 and 2.2), with μ the
shear modulus E/(2(1 + ν)) and κ the Kolosov constant (:func:`kolosov`):
κ = 3 - 4ν in plane strain (and in 3D), κ = (3 - ν)/(1 + ν) in plane stress.

Displacements, with C = 1/(2μ √(2π)) and the half-angle identities
2 sin²(θ/2) = 1 - cos θ, 2 cos²(θ/2) = 1 + cos θ::

    mode I  (K_I):   u₁ = K_I  C √r (κ - cos θ) cos(θ/2)
                     u₂ = K_I  C √r (κ - cos θ) sin(θ/2)
    mode II (K_II):  u₁ = K_II C √r (κ + 2 + cos θ) sin(θ/2)
                     u₂ = -K_II C √r (κ - 2 + cos θ) cos(θ/2)
    mode III (K_III): u₃ = K_III (2/μ) √(r/(2π)) sin(θ/2)

Stresses, with S = 1/√(2π r)::

    mode I:   σ₁₁ = K_I S cos(θ/2) (1 - sin(θ/2) sin(3θ/2))
              σ₂₂ = K_I S cos(θ/2) (1 + sin(θ/2) sin(3θ/2))
              σ₁₂ = K_I S cos(θ/2) sin(θ/2) cos(3θ/2)
    mode II:  σ₁₁ = -K_II S sin(θ/2) (2 + cos(θ/2) cos(3θ/2))
              σ₂₂ = K_II S sin(θ/2) cos(θ/2) cos(3θ/2)
              σ₁₂ = K_II S cos(θ/2) (1 - sin(θ/2) sin(3θ/2))
    mode III: σ₁₃ = -K_III S sin(θ/2),   σ₂₃ = K_III S cos(θ/2)

and, in 3D (plane strain in the (e₁, e₂) plane), σ₃₃ = ν (σ₁₁ + σ₂₂).

**Signs.**  On the faces θ = ±π, so the face of Ω⁺ (θ = +π) moves by
u₂ = +K_I C √r (κ + 1) and the face of Ω⁻ by the opposite: K_I > 0 opens the
crack.  u₁ = ±K_II C √r (κ + 1): K_II > 0 when the face of Ω⁺ slides along +e₁
relative to the face of Ω⁻; u₃ = ±K_III (2/μ)√(r/2π): K_III > 0 when it slides
along +e₃.  In the package's jump [[u]] = u⁻ - u⁺ these are negative.

**Gradient.**  Each displacement is √r g(θ), so ∂_r u = u/(2r) and
∂_θ u = √r g′(θ); the chain rule of :mod:`skxfem.crack.branch` gives
∂u/∂x₁ = (cos θ g/2 - sin θ g′)/√r and ∂u/∂x₂ = (sin θ g/2 + cos θ g′)/√r.

The fields are written in the frame and turned to global components by the
frame's rotation R (rows e_a): u = Rᵀ u_loc, σ = Rᵀ σ_loc R, ∇u = Rᵀ ∇u_loc R.

>>> import numpy as np
>>> from skxfem.fem.material import Material
>>> f = near_tip_local(np.array([1e-2]), np.array([0.0]), Material(1.0, 0.3), K=(1.0, 0.0))
>>> bool(np.isclose(f.sigma[1, 1, 0], 1 / np.sqrt(2 * np.pi * 1e-2)))   # K_I/√(2πr) ahead
True
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..fem.material import Material
from .frame import TipFrame, as_real, face_tolerance, local_coordinates, polar

__all__ = ["NearTip", "kolosov", "shear_modulus", "near_tip_local", "near_tip_modes", "near_tip"]


@dataclass(frozen=True)
class NearTip:
    """A near-tip field at points: displacement, its gradient and the stress.

    Attributes
    ----------
    u : (dim, ...) the displacement.
    grad_u : (dim, dim, ...) ∂u_i/∂x_j (i the component, j the derivative).
    sigma : (dim, dim, ...) the stress.
    """

    u: np.ndarray
    grad_u: np.ndarray
    sigma: np.ndarray

    @property
    def strain(self) -> np.ndarray:
        """ε = (∇u + ∇uᵀ)/2, shape (dim, dim, ...)."""
        return (self.grad_u + np.swapaxes(self.grad_u, 0, 1)) / 2


def _material(material) -> Material:
    if not isinstance(material, Material):
        raise TypeError(f"material must be a skxfem Material(E, nu, plane), got "
                        f"{type(material).__name__}")
    return material


def kolosov(material: Material, dim: int = 2) -> float:
    """The Kolosov constant κ: 3 - 4ν in plane strain and 3D, (3 - ν)/(1 + ν) in plane stress.

    ``material.plane`` decides in 2D; in 3D the near-front field is plane strain.

    >>> kolosov(Material(1.0, 0.25)), kolosov(Material(1.0, 0.25, plane="stress"))
    (2.0, 2.2)
    """
    nu = _material(material).nu
    if dim == 2 and material.plane == "stress":
        return (3 - nu) / (1 + nu)
    return 3 - 4 * nu


def shear_modulus(material: Material) -> float:
    """μ = E/(2(1 + ν)).

    >>> shear_modulus(Material(2.6, 0.3))
    1.0
    """
    return _material(material).E / (2 * (1 + material.nu))


def _angular(theta: np.ndarray, kappa: float):
    """g(θ) and g′(θ) of each displacement component, per unit K and C (module notes)."""
    s, c, st, ct = np.sin(theta / 2), np.cos(theta / 2), np.sin(theta), np.cos(theta)
    g = {"I": ((kappa - ct) * c, (kappa - ct) * s),
         "II": ((kappa + 2 + ct) * s, -(kappa - 2 + ct) * c),
         "III": (s,)}
    dg = {"I": (st * c - (kappa - ct) * s / 2, st * s + (kappa - ct) * c / 2),
          "II": ((kappa + 2 + ct) * c / 2 - st * s, (kappa - 2 + ct) * s / 2 + st * c),
          "III": (c / 2,)}
    return g, dg


def _stress(theta: np.ndarray):
    """The in-plane σ₁₁, σ₂₂, σ₁₂ of modes I and II and σ₁₃, σ₂₃ of mode III, per unit K S."""
    s, c = np.sin(theta / 2), np.cos(theta / 2)
    s3, c3 = np.sin(3 * theta / 2), np.cos(3 * theta / 2)
    return {"I": (c * (1 - s * s3), c * (1 + s * s3), c * s * c3),
            "II": (-s * (2 + c * c3), s * c * c3, c * (1 - s * s3)),
            "III": (-s, c)}


def near_tip_local(r: ArrayLike, theta: ArrayLike, material: Material,
                   K: ArrayLike = (1.0, 0.0, 0.0), dim: int = 2) -> NearTip:
    """The Williams field of the modes ``K`` in the tip frame's components.

    Parameters
    ----------
    r, theta : arrays of one shape, r > 0, θ ∈ [-π, π] (±π on the faces).
    material : :class:`skxfem.fem.material.Material`; in 2D its ``plane`` decides κ.
    K : (K_I, K_II) or (K_I, K_II, K_III); K_III only in 3D (in 2D, modes I and II).
    dim : 2 or 3.

    Returns
    -------
    NearTip
        u (dim, ...), ∇u and σ (dim, dim, ...), all in the frame's components.

    Examples
    --------
    >>> f = near_tip_local(1.0, np.pi, Material(2.6, 0.3), K=(0.0, 1.0))   # Ω⁺ face
    >>> u1 = (3 - 4 * 0.3 + 1) / (2 * np.sqrt(2 * np.pi))   # slides along +e₁
    >>> bool(np.isclose(f.u[0], u1)), bool(np.allclose(f.sigma[:, 1], 0))   # traction-free
    (True, True)
    """
    material = _material(material)
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    k = as_real("K", K)
    if k.shape not in ((2,), (3,)):
        raise ValueError(f"K must be (K_I, K_II) or (K_I, K_II, K_III), got shape {k.shape}")
    if dim == 2 and k.size == 3 and k[2] != 0:
        raise ValueError("K_III needs dim = 3: mode III is antiplane (along e₃)")
    k = np.append(k, 0.0) if k.size == 2 else k
    return _fields(*_polar_arguments(r, theta), material, (k,), dim)[0]


def near_tip_modes(r: ArrayLike, theta: ArrayLike, material: Material,
                   dim: int = 3) -> tuple[NearTip, ...]:
    """The Williams fields of the unit modes, I and II (and III in 3D): each the numbers
    of :func:`near_tip_local` with K = (1, 0, 0), (0, 1, 0), (0, 0, 1), the angular
    functions computed once for all.

    >>> m = Material(2.6, 0.3)
    >>> r, theta = np.array([0.5, 1.0]), np.array([1.0, -np.pi])
    >>> III = near_tip_modes(r, theta, m)[2]
    >>> bool(np.array_equal(III.grad_u, near_tip_local(r, theta, m, (0, 0, 1), 3).grad_u))
    True
    """
    material = _material(material)
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    return _fields(*_polar_arguments(r, theta), material, tuple(np.eye(3)[:dim]), dim)


def _polar_arguments(r: ArrayLike, theta: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """r and θ as arrays of one shape, r > 0 and |θ| ≤ π, or a ValueError."""
    r, theta = as_real("r", r), as_real("theta", theta)
    if r.shape != theta.shape:
        raise ValueError(f"r and theta must have the same shape, got {r.shape} and "
                         f"{theta.shape}")
    if np.any(r <= 0):
        raise ValueError("r must be positive: the stress is singular on the front (r = 0)")
    if np.any(np.abs(theta) > np.pi):
        raise ValueError("theta must lie in [-pi, pi] (±pi on the crack faces)")
    return r, theta


def _fields(r: np.ndarray, theta: np.ndarray, material: Material, Ks, dim: int
            ) -> list[NearTip]:
    """The fields of each mode mix K (3,) of ``Ks`` at (r, θ), the angular functions
    computed once; the modes of a zero K are left out (they add nothing)."""
    mu, kappa, nu = shear_modulus(material), kolosov(material, dim), material.nu
    sr, ct, st = np.sqrt(r), np.cos(theta), np.sin(theta)
    g, dg = _angular(theta, kappa)
    sig = _stress(theta)
    C, S = 1 / (2 * mu * np.sqrt(2 * np.pi)), 1 / np.sqrt(2 * np.pi * r)
    out = []
    for k in Ks:
        u, gu, sigma = (np.zeros(shape + r.shape) for shape in ((dim,), (dim, dim), (dim, dim)))
        modes = (("I", k[0], C), ("II", k[1], C)) + ((("III", k[2], 4 * C),) if dim == 3
                                                     else ())
        for mode, Km, Cm in modes:                      # two or three modes, not points
            if Km == 0:
                continue
            comps = (0, 1) if mode != "III" else (2,)
            for a, ga, dga in zip(comps, g[mode], dg[mode]):
                u[a] += Km * Cm * sr * ga
                gu[a, 0] += Km * Cm * (ct * ga / 2 - st * dga) / sr
                gu[a, 1] += Km * Cm * (st * ga / 2 + ct * dga) / sr
            if mode == "III":
                s13, s23 = sig[mode]
                sigma[0, 2] += Km * S * s13
                sigma[1, 2] += Km * S * s23
            else:
                s11, s22, s12 = sig[mode]
                sigma[0, 0] += Km * S * s11
                sigma[1, 1] += Km * S * s22
                sigma[0, 1] += Km * S * s12
        sigma[1, 0] = sigma[0, 1]
        if dim == 3:
            sigma[2, 0], sigma[2, 1] = sigma[0, 2], sigma[1, 2]
            sigma[2, 2] = nu * (sigma[0, 0] + sigma[1, 1])
        out.append(NearTip(u, gu, sigma))
    return out


def near_tip(x: ArrayLike, origin: ArrayLike, frame: TipFrame, material: Material,
             K: ArrayLike = (1.0, 0.0, 0.0), side: ArrayLike | None = None) -> NearTip:
    """The Williams field at points ``x`` (dim, ...), in global components.

    Parameters
    ----------
    x : (dim, ...) points.
    origin : (dim,) the tip (a point of the front).
    frame : one :class:`skxfem.crack.frame.TipFrame` (vectors of shape (dim,)).
    material, K : as :func:`near_tip_local`.
    side : +1 or -1 for points on the crack faces (:func:`skxfem.crack.frame.polar`,
        within :func:`skxfem.crack.frame.face_tolerance` of them).

    Examples
    --------
    >>> from skxfem.crack.frame import straight_frame
    >>> f = straight_frame([0.0, 1.0], [-1.0, 0.0])       # crack along -y, Ω⁺ at x < 0
    >>> t = near_tip(np.array([[0.0], [0.5]]), [0.0, 0.0], f, Material(1.0, 0.3))
    >>> bool(np.isclose(t.sigma[0, 0, 0], 1 / np.sqrt(np.pi)))      # σ along e₂ = -x
    True
    """
    xl = local_coordinates(x, origin, frame)
    tol = None if side is None else face_tolerance(x, origin)
    r, theta = polar(xl[0], xl[1], side, tol)
    loc = near_tip_local(r, theta, material, K, frame.dim)
    return NearTip(frame.to_global(loc.u), frame.tensor_to_global(loc.grad_u),
                   frame.tensor_to_global(loc.sigma))
