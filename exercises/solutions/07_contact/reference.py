"""Reference for exercise 07 (eq. 6-9).  skxfem's contact module, when it lands, is to
implement this same contract; until then this file is the reference."""
import numpy as np


def augmented_multiplier(lam, d_n, rho_n):
    if not rho_n > 0:
        raise ValueError(f"rho_n must be positive, got {rho_n!r}")
    return np.asarray(lam, float) - rho_n * np.asarray(d_n, float)


def contact_derivative(g_n):
    return np.where(np.asarray(g_n, float) < 0, 1.0, 0.0)


def contact_update(g_n):
    return contact_derivative(g_n) * np.asarray(g_n, float)


def project_unit_ball(g):
    g = np.asarray(g, float)
    norm = np.linalg.norm(g, axis=0)
    return g / np.maximum(norm, 1.0)


def project_unit_ball_derivative(g):
    g = np.asarray(g, float)
    k = g.shape[0]
    norm = np.linalg.norm(g, axis=0)
    eye = np.eye(k).reshape((k, k) + (1,) * (g.ndim - 1))
    outside = norm >= 1.0
    safe = np.where(outside, norm, 1.0)
    ghat = g / safe
    radial = (eye - ghat[:, None] * ghat[None, :]) / safe
    return np.where(outside, radial, eye * np.ones_like(norm))
