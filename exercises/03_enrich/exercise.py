"""Exercise 03: the Heaviside enrichment and the jump it makes (see README.md).

A scalar field on one cell with n nodes; ``phi`` holds the n shape functions
φ_i at the point where the field is evaluated.  You may import numpy; not
skxfem.enrich.
"""
import numpy as np  # noqa: F401  (you will need it)


def heaviside(psi):
    """The generalised Heaviside function: H = -1 in Ω⁻ (ψ < 0), +1 in Ω⁺ (ψ > 0).

    Parameters
    ----------
    psi : float or array of floats, none of them zero.

    Returns
    -------
    ndarray
        -1.0 or +1.0 for each value, same shape as ``psi``.

    Examples
    --------
    >>> heaviside(np.array([-0.3, 2.0])).tolist()
    [-1.0, 1.0]
    """
    raise NotImplementedError("heaviside: not written yet (exercise 03, see README.md)")


def enriched_value(phi, a, b, H, H_nodes):
    """The X-FEM field in the shifted form u_h = Σ a_i φ_i + Σ b_i φ_i (H - H_i).

    Parameters
    ----------
    phi : (n,) the shape functions at the point.
    a, b : (n,) standard and enriched dofs of the nodes (b_i = 0 where a node is
        not enriched).
    H : float, H at the point (-1 or +1: the side it is evaluated on).
    H_nodes : (n,) H at the nodes, H_i = H(x_i).

    Returns
    -------
    float
        u_h at the point.

    Examples
    --------
    >>> phi = np.array([1.0, 0.0])                 # at node 0
    >>> float(enriched_value(phi, np.array([2.0, 3.0]), np.array([5.0, 7.0]), -1.0,
    ...                      np.array([-1.0, 1.0])))
    2.0
    """
    raise NotImplementedError("enriched_value: not written yet (exercise 03, see README.md)")


def jump(phi, b):
    """The jump [[u]] = u⁻ - u⁺ of the enriched field at a point of Γ.

    Parameters
    ----------
    phi : (n,) the shape functions at the point.
    b : (n,) the enriched dofs.

    Returns
    -------
    float
        [[u]] = u_h(H = -1) - u_h(H = +1) = -2 Σ φ_i b_i.

    Examples
    --------
    >>> float(jump(np.array([0.25, 0.75]), np.array([1.0, 2.0])))
    -3.5
    """
    raise NotImplementedError("jump: not written yet (exercise 03, see README.md)")
