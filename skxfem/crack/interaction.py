r"""Stress intensity factors by the domain interaction integral, with the crack-face term.

The J-integral and its domain form
----------------------------------
In the tip frame (:mod:`skxfem.crack.frame`), J = lim_{Γ→0} ∫_Γ (W δ₁ⱼ - σᵢⱼ uᵢ,₁) mⱼ ds
on a small contour Γ around the tip, m its normal pointing away from the tip,
W = σ:ε/2.  Take a function q equal to 1 at the tip and 0 on an outer contour
C₀, and the ring A between them, bounded by Γ, C₀ and the two crack faces C⁺
(on Ω⁺) and C⁻ (on Ω⁻).  On ∂A let m* be the normal pointing out of A, which is
-m on Γ and the outward normal of the body on the faces.  As q = 0 on C₀,

.. math:: J = -\oint_{\partial A} (W\delta_{1j} - \sigma_{ij}u_{i,1})\, q\, m^*_j\,ds
              + \int_{C^+ \cup C^-} (W\delta_{1j} - \sigma_{ij}u_{i,1})\, q\, m^*_j\, ds .

On the faces m*₁ = 0 (they are parallel to e₁), so the last integral is
-∫ tᵢ uᵢ,₁ q ds with t = σ·m*, the traction the faces carry (from a contact or
a pressure).  The divergence theorem turns the closed integral into one over A;
with equilibrium σᵢⱼ,ⱼ = 0 (no body force) its part (W,₁ - (σᵢⱼ uᵢ,₁),ⱼ) q vanishes
because σᵢⱼ uᵢ,₁ⱼ = σᵢⱼ εᵢⱼ,₁ = W,₁.  What remains is

.. math:: J = \int_A (\sigma_{ij} u_{i,1} - W\delta_{1j})\, q_{,j}\, dA
              - \int_{C^+\cup C^-} t_i\, u_{i,1}\, q\, ds .

**With a body force** b (σᵢⱼ,ⱼ + bᵢ = 0) the part of the divergence multiplying q no
longer vanishes: (W δ₁ⱼ - σᵢⱼ uᵢ,₁),ⱼ = W,₁ - σᵢⱼ,ⱼ uᵢ,₁ - σᵢⱼ uᵢ,₁ⱼ = bᵢ uᵢ,₁, and

.. math:: J = \int_A (\sigma_{ij} u_{i,1} - W\delta_{1j})\, q_{,j}\, dA
              - \int_A b_i\, u_{i,1}\, q\, dA
              - \int_{C^+\cup C^-} t_i\, u_{i,1}\, q\, ds ,

an integral over the whole of A where q ≠ 0 (the tip included: u,₁ ∼ r^{-1/2} is
integrable), not only over the ring where ∇q ≠ 0.

The interaction integral
------------------------
For the sum of the solution (σ, u) and an auxiliary field (σᵃ, uᵃ) the J of
the sum is J + Jᵃ + I, with the interaction integral

.. math:: I = \int_A \bigl[\sigma_{ij}\, u^a_{i,1} + \sigma^a_{ij}\, u_{i,1}
              - \sigma_{ik}\, \varepsilon^a_{ik}\, \delta_{1j}\bigr]\, q_{,j}\, dA
              \;-\; \int_{C^+\cup C^-} t_i\, u^a_{i,1}\, q\, ds,

where σᵃ:ε = σ:εᵃ, and the auxiliary field, a Williams field
(:mod:`skxfem.crack.williams`), has traction-free faces (tᵃ = 0) so that only
the solution's face traction t appears.  It is in equilibrium without a body force
(σᵃᵢⱼ,ⱼ = 0), so the sum carries the solution's b only, and a body force adds

.. math:: -\int_A b_i\, u^a_{i,1}\, q\, dA

to I: the divergence of the interaction integrand is σᵢⱼ,ⱼ uᵃᵢ,₁ + σᵢⱼ εᵃᵢⱼ,₁ +
σᵃᵢⱼ εᵢⱼ,₁ - (σᵢₖ εᵃᵢₖ),₁ = -bᵢ uᵃᵢ,₁ (σᵃ:ε,₁ = σ,₁:εᵃ by the symmetry of Hooke's
law, a homogeneous material).  It holds the x₁-derivative of the auxiliary field, not
of the solution's (b·u,₁ q belongs to J, not to I).  Without it a loaded body (gravity, a
spinning disc) gives a K that changes with the domain (tests/test_crack_body_force.py:
a Williams field plus a smooth field of body force b).  Without the face term the domain
integral depends on A as soon as the faces are loaded (a closed crack in
contact, a pressurised crack).  With J = (K_I² + K_II²)/E′ + K_III²/(2μ),

.. math:: I = \frac{2}{E'} (K_I K_I^a + K_{II} K_{II}^a) + \frac{1}{\mu} K_{III} K_{III}^a,

so the auxiliary fields of unit K_I, K_II, K_III give K_I = E′ I_I/2,
K_II = E′ I_II/2, K_III = μ I_III (:func:`sif_from_interaction`), with E′ = E
in plane stress, E/(1 - ν²) in plane strain and in 3D.

**Signs of t.**  t = σ·m* with m* the outward normal of the body: on the face of
Ω⁺, m* = -n (n = ∇ψ/|∇ψ| = e₂), on the face of Ω⁻, m* = +n.  With the
package's interface traction r = σ(u⁻)·n (:mod:`skxfem.levelset`), a closed crack
carries t⁻ = r on the face of Ω⁻ and t⁺ = -r on the face of Ω⁺; a pressure p
in an open crack gives t = -p m*, the same tractions as a closed crack in
compression with contact pressure p.

**In 3D** the same integrand over a volume, with q of the distance to the
front times a function of the position along it, gives ∫_front I(s) q(s) ds:
divide by ∫ q ds along the front for the local I.  This module takes one frame
(a straight front, or the frame of one front point).

Everything here is arrays at quadrature points: the points, their weights, the
solution's ∇u and σ there, ∇q, and the faces' rules.  Nothing depends on a mesh,
so sub-cell rules of the X-FEM feed it as they are, without a loop over points.

>>> import numpy as np
>>> r = np.array([0.1, 0.5, 2.0])
>>> q, gq = q_function(r, np.stack([np.ones(3), np.zeros(3)]), 1.0)   # ∇r = e₁
>>> q.tolist(), gq[0].tolist()                     # the cone 1 - r/r_d
([0.9, 0.5, 0.0], [-1.0, -1.0, 0.0])
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..fem.material import Material
from .frame import TipFrame, as_real
from .williams import near_tip, shear_modulus

__all__ = ["CrackFace", "q_function", "interaction_integrals", "sif_from_interaction",
           "stress_intensity", "effective_modulus"]


@dataclass(frozen=True)
class CrackFace:
    """A quadrature rule on one crack face, with the solution's traction there.

    Attributes
    ----------
    x : (dim, n) points on the face (ψ = 0, φ < 0).
    w : (n,) weights (the length or area element included).
    traction : (dim, n) the traction the face carries, σ·m* with m* the outward
        normal of the body: -n on the face of Ω⁺, +n on that of Ω⁻.
    q : (n,) the weight function q at the points.
    side : +1 for the face of Ω⁺ (θ = +π), -1 for that of Ω⁻ (θ = -π).
    """

    x: np.ndarray
    w: np.ndarray
    traction: np.ndarray
    q: np.ndarray
    side: int

    def __post_init__(self):
        x = as_real("face x", self.x)
        if x.ndim != 2 or x.shape[0] not in (2, 3):
            raise ValueError(f"face x must have shape (dim, n), got {x.shape}")
        n = x.shape[1]
        for name, shape in (("w", (n,)), ("traction", x.shape), ("q", (n,))):
            object.__setattr__(self, name, as_real(f"face {name}", getattr(self, name), shape))
        object.__setattr__(self, "x", x)
        if self.side not in (1, -1):
            raise ValueError(f"face side must be +1 (Ω⁺) or -1 (Ω⁻), got {self.side!r}")


def q_function(r: ArrayLike, grad_r: ArrayLike, r_d: float, plateau: float = 0.0,
               boundary: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """The weight q of the domain: 1 near the front, 0 beyond the radius, and ∇q.

    q = 1 for r ≤ ρ r_d, q = (R - r)/(R - ρR) between, 0 for r ≥ R, where the
    radius R = min(r_d, boundary) is clipped by the distance from the front to the
    boundary (and to other fronts) so that the domain stays in the body; ρ is the
    ``plateau`` (0: a cone).  ∇q = -∇r/(R - ρR) on the ring, 0 elsewhere.

    Parameters
    ----------
    r : (...) distances to the front.
    grad_r : (dim, ...) ∇r (:func:`skxfem.crack.frame.polar_gradients`).
    r_d : the radius asked for, > 0.
    plateau : ρ in [0, 1).
    boundary : the distance from the front to the boundary, > 0.

    Examples
    --------
    >>> q, gq = q_function(np.array([0.3, 0.75]), np.array([[1.0, 0.0], [0.0, 1.0]]),
    ...                    2.0, plateau=0.5, boundary=1.0)
    >>> q.tolist(), gq.tolist()
    ([1.0, 0.5], [[0.0, 0.0], [0.0, -2.0]])
    """
    r = as_real("r", r)
    grad_r = as_real("grad_r", grad_r)
    if grad_r.shape[1:] != r.shape or grad_r.shape[:1] not in ((2,), (3,)):
        raise ValueError(f"grad_r must have shape (dim,) + r.shape = (dim,) + {r.shape}, got "
                         f"{grad_r.shape}")
    for name, v in (("r_d", r_d), ("boundary", boundary)):
        if not (isinstance(v, (int, float, np.floating)) and v > 0):
            raise ValueError(f"{name} must be a positive number, got {v!r}")
    if not 0 <= plateau < 1:
        raise ValueError(f"plateau must be in [0, 1), got {plateau!r}")
    R = min(float(r_d), float(boundary))
    inner = plateau * R
    q = np.clip((R - r) / (R - inner), 0.0, 1.0)
    ring = (r > inner) & (r < R)
    return q, np.where(ring, -grad_r / (R - inner), 0.0) + 0.0   # no -0.0


def _check(w, grad_u, sigma, grad_q, x):
    x = as_real("x", x)
    if x.ndim < 1 or x.shape[0] not in (2, 3):
        raise ValueError(f"x must have shape (dim, ...), got {x.shape}")
    dim, pts = x.shape[0], x.shape[1:]
    return (x, as_real("w", w, pts), as_real("grad_u", grad_u, (dim, dim) + pts),
            as_real("sigma", sigma, (dim, dim) + pts), as_real("grad_q", grad_q, (dim,) + pts))


def _body(body_force, q, x):
    """(b, q) checked against the points x (None, None without a body force)."""
    if body_force is None:
        if q is not None:
            raise ValueError("q is only used with a body_force; give both or neither")
        return None, None
    if q is None:
        raise ValueError("a body_force needs q at the points (the weight of its term "
                         "-∫ b·u^a_{,1} q dA)")
    return as_real("body_force", body_force, x.shape), as_real("q", q, x.shape[1:])


def interaction_integrals(x: ArrayLike, w: ArrayLike, grad_u: ArrayLike,
                          sigma: ArrayLike, grad_q: ArrayLike, origin: ArrayLike,
                          frame: TipFrame, material: Material, faces=(),
                          body_force: ArrayLike | None = None,
                          q: ArrayLike | None = None) -> np.ndarray:
    """I for the auxiliary Williams fields of unit K_I, K_II (and K_III in 3D).

    Parameters
    ----------
    x : (dim, ...) quadrature points of the domain A, off the crack faces.
    w : (...) their weights.
    grad_u : (dim, dim, ...) the solution's ∂uᵢ/∂xⱼ at the points.
    sigma : (dim, dim, ...) the solution's stress at the points.
    grad_q : (dim, ...) ∇q at the points (:func:`q_function`).
    origin, frame : the tip and its frame (one frame, vectors of shape (dim,)).
    material : the :class:`skxfem.fem.material.Material` of the auxiliary fields.
    faces : :class:`CrackFace` rules of the loaded crack faces (none: free faces).
    body_force : (dim, ...) the body force b at the points (None: none); the points
        must then cover all of A where q ≠ 0, the tip's cells included (module notes).
    q : (...) q at the points; required with ``body_force``.

    Returns
    -------
    ndarray
        (I_I, I_II) in 2D, (I_I, I_II, I_III) in 3D.

    Examples
    --------
    >>> from skxfem.crack.frame import straight_frame
    >>> f, mat = straight_frame([1.0, 0.0], [0.0, 1.0]), Material(1.0, 0.3)
    >>> x = np.array([[0.5], [0.0]])                  # one point, ∇q = 0: nothing
    >>> z = np.zeros((2, 2, 1))
    >>> interaction_integrals(x, [1.0], z, z, np.zeros((2, 1)), [0, 0], f, mat).tolist()
    [0.0, 0.0]
    """
    x, w, grad_u, sigma, grad_q = _check(w, grad_u, sigma, grad_q, x)
    dim = x.shape[0]
    b, q = _body(body_force, q, x)
    e1 = frame.e1.reshape((dim,) + (1,) * (x.ndim - 1))
    du1 = np.einsum("ij...,j...->i...", grad_u, e1)           # ∂u/∂x₁ along e₁
    q1 = (grad_q * e1).sum(axis=0)                             # q,₁
    result = []
    for mode in range(dim):                                    # 2 or 3 auxiliary fields
        K = np.eye(3)[mode]
        aux = near_tip(x, origin, frame, material, K)
        dua1 = np.einsum("ij...,j...->i...", aux.grad_u, e1)
        integrand = (np.einsum("i...,ij...,j...->...", dua1, sigma, grad_q)
                     + np.einsum("i...,ij...,j...->...", du1, aux.sigma, grad_q)
                     - np.einsum("ik...,ik...->...", sigma, aux.strain) * q1)
        if b is not None:
            integrand = integrand - q * (b * dua1).sum(axis=0)
        total = (w * integrand).sum()
        for face in faces:
            af = near_tip(face.x, origin, frame, material, K, side=face.side)
            dfa1 = np.einsum("ij...,j->i...", af.grad_u, frame.e1)
            total -= (face.w * face.q * (face.traction * dfa1).sum(axis=0)).sum()
        result.append(total)
    return np.array(result)


def effective_modulus(material: Material, dim: int = 2) -> float:
    """E′: E in plane stress, E/(1 - ν²) in plane strain and 3D.

    >>> effective_modulus(Material(1.0, 0.2, plane="stress"))
    1.0
    >>> effective_modulus(Material(0.96, 0.2))
    1.0
    """
    if dim == 2 and material.plane == "stress":
        return material.E
    return material.E / (1 - material.nu ** 2)


def sif_from_interaction(I: ArrayLike, material: Material, dim: int = 2) -> np.ndarray:
    """K from the interaction integrals of unit auxiliary fields: E′I/2 (I, II), μI (III).

    >>> sif_from_interaction([2.0, -1.0], Material(1.0, 0.0, plane="stress")).tolist()
    [1.0, -0.5]
    """
    I = as_real("I", I)
    if I.shape != (dim,):
        raise ValueError(f"I must hold {dim} values (modes I, II{', III' if dim == 3 else ''})"
                         f", got shape {I.shape}")
    scale = np.array([effective_modulus(material, dim) / 2] * 2
                     + ([shear_modulus(material)] if dim == 3 else []))
    return scale * I


def stress_intensity(x: ArrayLike, w: ArrayLike, grad_u: ArrayLike, sigma: ArrayLike,
                     grad_q: ArrayLike, origin: ArrayLike, frame: TipFrame,
                     material: Material, faces=(), body_force: ArrayLike | None = None,
                     q: ArrayLike | None = None) -> np.ndarray:
    """(K_I, K_II) in 2D, (K_I, K_II, K_III) in 3D: :func:`interaction_integrals` turned
    into K by :func:`sif_from_interaction`; same arguments."""
    x = as_real("x", x)
    I = interaction_integrals(x, w, grad_u, sigma, grad_q, origin, frame, material, faces,
                              body_force, q)
    return sif_from_interaction(I, material, x.shape[0])
