"""Reference for exercise 02, built on the library: skxfem.cut.strictly_cut_edges
(S_e and the intersection points) and skxfem.fem.simplex.split (the sub-cells)."""
import math

import numpy as np

from skxfem.cut import strictly_cut_edges
from skxfem.fem.simplex import split


def cut_edges(edges, psi):
    edges, psi = np.asarray(edges), np.asarray(psi, float)
    return strictly_cut_edges(edges, psi, np.zeros((1, psi.size)))[0]   # no coordinates needed


def intersection_points(nodes, edges, psi):
    nodes, edges, psi = np.asarray(nodes, float), np.asarray(edges), np.asarray(psi, float)
    return strictly_cut_edges(edges, psi, nodes)[1]        # every edge given is strictly cut


def subcell_volumes(X, psi):
    X, psi = np.asarray(X, float), np.asarray(psi, float)
    d = X.shape[1]
    sub, _, side = split(X[None], psi[None])
    vol = np.abs(np.linalg.det(sub[:, 1:] - sub[:, :1])) / math.factorial(d)
    return float(vol[side < 0].sum()), float(vol[side > 0].sum())
