r"""Quadrature of cracked tetrahedra: collapsed Gauss rules and almost-polar rules at the front.

The 3D twin of :mod:`skxfem.crack.quadrature`.  Every rule here maps a product
Gauss–Legendre rule on the unit cube onto tetrahedra (m, 4, 3) given by their
vertices, and returns physical points (m, nq, 3) and weights (m, nq).

* :func:`collapsed`: the conical product (Duffy) rule
  x = V₀ + u(V₁ - V₀) + us(V₂ - V₁) + ust(V₃ - V₂), dx = 6|T| u² s du ds dt, with n
  points in each direction: exact for polynomials of degree 2n - 3 (the weight u² s is
  taken into the integrand), any order asked.
* :func:`edge_polar`: a sub-tetrahedron whose edge V₀V₁ lies on the front (the
  sub-tetrahedra of :mod:`skxfem.crack.geometry3d` put those vertices first).  Every
  point is x = (1 - u) p + u q with p = (1 - s)V₀ + sV₁ on the edge and
  q = (1 - t)V₂ + tV₃ on the opposite one,

  .. math:: dx = 6|T|\, u (1 - u)\, du\, ds\, dt,

  and the distance to the front is r = u d(q), d(q) > 0 the distance of q to the
  front's line; θ depends on t only.  The factor u cancels the 1/r of the stiffness
  integrand, and with u = σ² every r^{k/2}, k ≥ -2, is a polynomial in σ: the 3D form
  of the almost-polar rule of Béchet et al. (2005), Gauss in σ (along the rays), in s
  (along the front) and in t (across the rays).  ∫ 1/r over the right-angled tetrahedron
  below with n_θ = 4, 6, 8, 10: errors 2.5e-4, 6e-6, 1.6e-7, 4e-9 (measured).
* :func:`vertex_polar`: a sub-tetrahedron with one vertex V₀ on the front (it meets the
  front there only): the conical product rule with u = σ² (r ∝ u along each ray).

>>> import numpy as np
>>> T = np.array([[[0.0, 0, 0], [0, 0, 1], [1, 0, 0], [0, 1, 0]]])    # edge V₀V₁ on z
>>> x, w = edge_polar(T)
>>> r = np.hypot(x[0, :, 0], x[0, :, 1])
>>> exact = np.log(1 + np.sqrt(2)) / np.sqrt(2)        # ∫ 1/r over this tetrahedron
>>> bool(abs(w[0] @ (1 / r) - exact) < 1e-6), round(float(w.sum()), 14)
(True, 0.16666666666667)
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

__all__ = ["POLAR_POINTS", "NEAR_POINTS", "NEAR_GRADING", "VERTEX_POINTS", "collapsed",
           "edge_polar", "vertex_polar", "order_points"]

POLAR_POINTS = (5, 3, 8)
"""(n_r, n_s, n_θ): Gauss points along the rays (in σ = √u), along the front and across
the rays of :func:`edge_polar`."""

NEAR_POINTS = 5
"""Points per direction of :func:`collapsed` on the cells around the front cells (in the
support of a front cell's node) and on the front cells' sub-tetrahedra off the front."""

NEAR_GRADING = ((0.3, 8), (0.1, 12), (0.03, 16), (0.01, 20))
"""(ratio, n): the points per direction of :func:`collapsed` on a tetrahedron near the
front that does not meet it, where the front passes within ratio times its longest edge
(:func:`skxfem.crack.space3d.near_points`); :data:`NEAR_POINTS` beyond.  The exact state
of the penny pressed shut (:func:`skxfem.studies.cracks3d.pressed_penny`: σ = -p e_z ⊗ e_z,
the faces carrying p) should give K U₀ = Jᵀ(w p) on every row (the divergence theorem
between the cells' rules and the faces'): on the branch rows the 5³ rule left 3.4e-3,
5.5e-3, 1.0e-2 h^2.5 p at h = 0.2, 0.125, 0.1 (10³ everywhere: 4.4e-4, 9.3e-4, 1.6e-3,
slow: the front passes at 1e-2 of a piece's size), this grading 9.8e-4, 1.4e-3, 1.0e-3.
Solved, the pressure at the crossings was then within 0.27 %, 0.35 %, 0.14 % of p
(1.6 %, 0.8 %, 1.0 % before), and |K_I| that of the exact state (the interaction
integral's own error; sif_3d grades its own near rule only for faces that carry a
traction, :data:`skxfem.crack.sif3d.FACE_RULES`).  The two closest steps (0.03, 0.01)
are for a front that passes a piece at a hundredth of its size (a front cell's piece
off the front, the neighbour across a face the front nearly touches): the through
crack pressed shut (:func:`skxfem.studies.cracks3d.pressed_slab`, n = 13, front at
x = 0.575) gave |K| = 1.02e-3 p√(πa) with the pressure 0.37 % off with two steps, 8.0e-4
and 0.23 % with them (its exact state 4.5e-4); n = 11 at x = 0.5875 4.6e-4 -> 2.2e-4.
They cost the stiffness of that slab 201 000 -> 352 000 points, of the pressed penny at
n = 16 1.54 M -> 1.71 M, of the cube of ``benchmarks/crack_solve.py`` none (n = 16, 24).

Closer still, the steps do not resolve the branch functions' 1/r stiffness along a line
on a piece's face: the front of that cube (n = 12) 1e-9 behind the node plane x = 0.5
gave K_I 3.60356 at mid-front, 1e-9 past it 3.60041, on it 3.59996 (there the cells on
both sides touch the front and take the almost-polar rules).  A step (1e-3, 32) added:
3.60271 behind; (1e-5, 48) too: 3.60219 and 3.60009, slowly towards the value on the
plane.  Left as
is (K within 1e-3 across a node plane, tests/test_crack_3d.py); a rule that resolves it
would give such a piece the almost-polar rule about the front's trace on its face."""

VERTEX_POINTS = (4, 5)
"""(n_r, n_θ) of :func:`vertex_polar` (its integrand is regular: r⁻¹ u² ∝ u, but turns
fast across the rays near the front's line).  On the front cells' vertex pieces of
benchmarks/crack_solve.py the stiffness's energy, relative to (12, 12): (4, 4) 2.3e-5
(n = 16) and 1.2e-5 (n = 24), (4, 5) -4.4e-6 and -2.1e-6, (4, 6) 9e-7 and 4e-7; (5, 4)
as (4, 4)."""


def _gauss01(n: int) -> tuple[np.ndarray, np.ndarray]:
    s, w = leggauss(n)
    return (s + 1) / 2, w / 2


def _grid(*ns):
    pts = [_gauss01(n) for n in ns]
    mesh = np.meshgrid(*[p for p, _ in pts], indexing="ij")
    wts = np.meshgrid(*[w for _, w in pts], indexing="ij")
    return [m.ravel() for m in mesh], np.prod([w.ravel() for w in wts], axis=0)


def _six_volumes(T: np.ndarray) -> np.ndarray:
    return np.abs(np.linalg.det(T[:, 1:] - T[:, :1]))


def order_points(order: int) -> int:
    """The points per direction of :func:`collapsed` exact to degree ``order``.

    >>> order_points(8)
    6
    """
    return max(1, int(np.ceil((order + 3) / 2)))


def _conical(T, u, s, t, w):
    V0, V1, V2, V3 = (T[:, i, None] for i in range(4))
    x = (V0 + u[None, :, None] * (V1 - V0) + (u * s)[None, :, None] * (V2 - V1)
         + (u * s * t)[None, :, None] * (V3 - V2))
    return x, _six_volumes(T)[:, None] * w[None]


def collapsed(T: np.ndarray, n: int = NEAR_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """The conical product Gauss rule of n³ points on tetrahedra T (m, 4, 3).

    >>> T = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]])
    >>> x, w = collapsed(T, 3)
    >>> round(float(w[0] @ x[0, :, 0] ** 3), 14)          # ∫ x³ = 3!·3!/6! = 1/120
    0.00833333333333
    """
    T = np.asarray(T, float)
    (u, s, t), w = _grid(n, n, n)
    return _conical(T, u, s, t, w * u ** 2 * s)


def vertex_polar(T: np.ndarray, n_r: int = VERTEX_POINTS[0],
                 n_t: int = VERTEX_POINTS[1]) -> tuple[np.ndarray, np.ndarray]:
    """The almost-polar rule of tetrahedra T (m, 4, 3) with vertex V₀ on the front.

    >>> T = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]])
    >>> x, w = vertex_polar(T)
    >>> round(float(w.sum()), 14)
    0.16666666666667
    """
    T = np.asarray(T, float)
    (sig, s, t), w = _grid(n_r, n_t, n_t)
    u = sig ** 2
    return _conical(T, u, s, t, w * 2 * sig * u ** 2 * s)


def edge_polar(T: np.ndarray, n_r: int = POLAR_POINTS[0], n_s: int = POLAR_POINTS[1],
               n_t: int = POLAR_POINTS[2]) -> tuple[np.ndarray, np.ndarray]:
    """The almost-polar rule of tetrahedra T (m, 4, 3) whose edge V₀V₁ lies on the front
    (module notes).

    >>> T = np.array([[[0.0, 0, 0], [0, 0, 2], [1, 0, 0], [0, 1, 0]]])
    >>> x, w = edge_polar(T)
    >>> r = np.hypot(x[0, :, 0], x[0, :, 1])
    >>> round(float(w[0] @ (1 / r)), 6)        # ∫ 1/r: its width 2 times the previous
    1.24645
    """
    T = np.asarray(T, float)
    (sig, s, t), w = _grid(n_r, n_s, n_t)
    u = sig ** 2
    V0, V1, V2, V3 = (T[:, i, None] for i in range(4))
    p = V0 + s[None, :, None] * (V1 - V0)
    q = V2 + t[None, :, None] * (V3 - V2)
    x = p + u[None, :, None] * (q - p)
    return x, _six_volumes(T)[:, None] * (w * 2 * sig * u * (1 - u))[None]
