"""Wrong: the piece at the lone vertex is always counted in Ω⁻."""
import math

import numpy as np

from skxfem.fem.simplex import split

EXPECT = "Ω⁻ and Ω⁺ are swapped"


def subcell_volumes(X, psi):
    X, psi = np.asarray(X, float), np.asarray(psi, float)
    d = X.shape[1]
    total = abs(np.linalg.det(X[1:] - X[0])) / math.factorial(d)
    neg = psi < 0
    lone = np.flatnonzero(neg) if neg.sum() == 1 else np.flatnonzero(~neg)
    if lone.size != 1:                      # two against two: right
        sub, _, side = split(X[None], psi[None])
        vol = np.abs(np.linalg.det(sub[:, 1:] - sub[:, :1])) / math.factorial(d)
        return float(vol[side < 0].sum()), float(vol[side > 0].sum())
    a = lone[0]
    small = total * np.prod([psi[a] / (psi[a] - psi[j]) for j in range(d + 1) if j != a])
    return float(small), float(total - small)
