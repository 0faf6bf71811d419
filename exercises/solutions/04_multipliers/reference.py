"""Reference for exercise 04 (skxfem.multipliers.interface_mass takes a quadrature rule)."""
import numpy as np

# the library's interface mass computes M too (with a quadrature rule): the book shows
# its contract only (skxfem.app.graded reads this list)
LIBRARY_ANSWERS = ("skxfem.multipliers.interface_mass",)


def interpolate(lam, segments, k, s):
    a, b = np.asarray(segments)[:, k]
    return float((1.0 - s) * lam[a] + s * lam[b])


def interface_mass(points, segments):
    points, segments = np.asarray(points, float), np.asarray(segments)
    L = np.linalg.norm(points[:, segments[1]] - points[:, segments[0]], axis=0)
    M = np.zeros((points.shape[1],) * 2)
    for i in range(2):
        for j in range(2):
            np.add.at(M, (segments[i], segments[j]), L * (2.0 if i == j else 1.0) / 6.0)
    return M
