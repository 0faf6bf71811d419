r"""The X-FEM displacement space: standard plus Heaviside-enriched dofs (eq. 11).

The paper's approximation is u_h = Σᵢ aᵢ φᵢ + Σⱼ bⱼ φⱼ H, with j over the
enriched nodes (the nodes of cut cells).  We use the *shifted* form

.. math:: u_h = \sum_i a_i \varphi_i + \sum_j b_j \varphi_j (H - H_j),
          \qquad H_j = H(x_j),

which spans exactly the same space (φⱼH and φⱼ are both in it), so every
result of the paper is unchanged, while aᵢ is now the displacement *at node i*:
Dirichlet conditions are imposed on aᵢ alone.  The jump is the paper's:

.. math:: [[u_h]] = u_h^- - u_h^+ = -2 \sum_j \varphi_j b_j .

Assembly uses scikit-fem throughout.  With K the standard stiffness
∫ σ(φᵢ):ε(φⱼ), K_H the signed stiffness ∫ H σ(φᵢ):ε(φⱼ) and D = diag(H_j),

.. math:: K_{ab} = K_H[:, E] - K[:, E] D, \qquad
          K_{bb} = K[E,E] + D K[E,E] D - D K_H[E,E] - K_H[E,E] D,

because H² = 1.  K_H needs the sub-cell quadrature of :mod:`skxfem.cut`; on
uncut cells H is the cell's constant side.  With K^± the stiffness of Ω^±,
K = K⁺ + K⁻ and K_H = K⁺ - K⁻ = s(2Kˢ - K) for either side s.  Only the
columns of enriched dofs of K_H enter, so K is assembled on every cell whole
(the integrand is a polynomial on a cut cell too) and Kˢ on one side, on the
cells of enriched nodes only (:func:`skxfem.fem.side_bases.parts`; on hexahedra and
prisms with a moment-fitted rule, :mod:`skxfem.fem.fitted`).  The stiffness runs
on *scalar* bases (built once by :func:`xfem_space` and shared with
:func:`far_side_fraction`), from scalar forms (:func:`skxfem.fem.material.stiffness_matrix`).

**Several interfaces** (:class:`XSpaces`): one Heaviside H^k per level set
ψ_k, each enriching the nodes of its own cut cells,

.. math:: u_h = \sum_i a_i \varphi_i + \sum_k \sum_{j \in E_k} b^k_j \varphi_j (H^k - H^k_j),

unknowns [a, b¹, b², …].  No cell is cut by two interfaces
(:func:`skxfem.cut.check_apart`), so on a cell the enrichment of Γ_k is zero
unless Γ_k cuts it (H^k is constant there and equals H^k_j at its nodes):
the Heaviside enrichments of two interfaces never meet on a cell, their blocks
in K are zero, and K is :func:`enriched_blocks` of each interface around the one
standard block A.  A crack's branch functions reach past the cells it cuts (r_e
from its front): a space that has them gives its blocks with the others
(``coupling``, :func:`couplings`).  Each interface's own space ``per_interface[k]`` numbers
[a, b^k]; :meth:`XSpaces.columns` places it among the unknowns.

>>> from skfem import MeshTri1
>>> from skxfem.levelset import plane
>>> from skxfem.cut import cut
>>> m = MeshTri1().refined(2)
>>> V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
>>> V.n_std, V.n_enr
(50, 20)
>>> W = XSpaces((V, xfem_space(m, cut(m, plane((0, 0.8), (0, 1))))))
>>> W.N, int(W.columns(1)[-1]), W.regions()[0].tolist()   # three regions
(90, 89, [[-1, -1], [1, -1], [1, 1]])
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementVector, LinearForm
from skfem.assembly import CellBasis
from skfem.helpers import dot

from .cut import Cut
from .fem.evaluate import evaluation_matrix
from .fem.loads import force_field
from .fem.material import Material, stiffness_matrix
from .fem.quadrature import cell_rule, exact_orders
from .fem.side_bases import Parts, parts, side_bases
from .scene.boundary import dirichlet, imposed

__all__ = ["XSpace", "XSpaces", "xfem_space", "stiffness", "mass",
           "enriched_blocks", "couplings", "as_spaces", "signed_bases", "far_side_fraction",
           "body_load",
           "jump_matrix", "split_fields", "from_fields", "region_fields", "constrained_dofs",
           "one_interface",
           "edge_jumps"]


@dataclass(frozen=True)
class XSpace:
    """An X-FEM vector displacement space on a cut mesh.

    Attributes
    ----------
    mesh, cut
        The mesh and its :class:`skxfem.cut.Cut`.
    basis
        The standard vector ``skfem.Basis``: it numbers the dofs and evaluates
        fields.  Its quadrature is the one-point centroid rule, so that it
        holds one value per cell; every integral over the cells uses
        :func:`side_bases` (the stiffness, at ``rule``).
    enr_dofs : (n_enr,) standard dofs of the enriched nodes, ordered node by
        node (component fastest); unknown ``n_std + k`` is the enriched dof of
        ``enr_dofs[k]``.
    H_node : (n_enr,) H(x_j) of the node of each enriched dof.
    rule : (X, W), the cell rule of the stiffness on uncut cells.
    parts : the scalar :class:`skxfem.fem.side_bases.Parts` at ``rule``, which
        :func:`stiffness` reuses (None: built when needed).
    """

    mesh: object
    cut: Cut
    basis: CellBasis
    enr_dofs: np.ndarray
    H_node: np.ndarray
    rule: tuple = field(repr=False, compare=False, default=None)
    parts: Parts | None = field(default=None, repr=False, compare=False)

    @property
    def n_std(self) -> int:
        return int(self.basis.N)

    @property
    def n_enr(self) -> int:
        return self.enr_dofs.size

    @property
    def N(self) -> int:
        return self.n_std + self.n_enr

    def regions(self) -> tuple[np.ndarray, np.ndarray]:
        """Ω⁻ and Ω⁺, ``[[-1], [1]]``, and the region of each node: :meth:`XSpaces.regions`."""
        return XSpaces((self,)).regions()

    splits = True
    """Γ splits the body in two (:meth:`XSpaces.regions` takes its signs)."""

    def signed_stiffness(self, material: Material, A=None):
        """(A, A_H): the standard stiffness ∫ σ(u):ε(v) (``A`` if given: assembled once
        for every interface) and its signed version, from :attr:`parts`
        (:func:`stiffness`)."""
        side_parts = self.parts or parts(self.mesh, self.cut, self.basis.elem.elem,
                                         self.rule)
        return side_parts.signed(lambda basis: stiffness_matrix(material, basis), A)

    def signed_mass(self, A=None):
        """(A, A_H): the standard mass ∫ u·v (``A`` if given) and its signed version,
        integrated exactly on affine cells (:func:`mass`)."""
        cell, sub = exact_orders(self.mesh, "mass")
        side_parts = parts(self.mesh, self.cut, self.basis.elem,
                           cell_rule(self.mesh, cell), sub)
        return side_parts.signed(
            lambda basis: _signed_vector_mass.assemble(basis, H=np.ones(basis.dx.shape)), A)

    def blocks(self, A: sp.csr_matrix, AH) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(A_ab, A_bb), the enriched blocks of this space from A (CSR) and its A_H
        (module notes; :func:`enriched_blocks`)."""
        E, D, AH = self.enr_dofs, sp.diags(self.H_node), AH.tocsr()
        AEE, AHEE = A[E][:, E], AH[E][:, E]
        return AH[:, E] - A[:, E] @ D, AEE + D @ AEE @ D - D @ AHEE - AHEE @ D

    def load(self, facet_loads, body_force=None, f: np.ndarray | None = None):
        """(f, f_b): the load ∫ t·φ + ∫ b·φ on the standard dofs (``f`` if given: the
        first interface's) and on this space's enriched unknowns, f_H[E] - H f[E], from
        f_H = ∫ H t·φ + ∫ H b·φ.  ``facet_loads``: ``(facets, t(x, n))`` pairs
        (:func:`skxfem.scene.load_facets`); ``body_force``: :func:`body_load`'s."""
        from .fem.loads import boundary_quadrature, surface_load
        own, f_H = np.zeros(self.n_std), np.zeros(self.n_std)
        for facets, traction in facet_loads:
            q = boundary_quadrature(self.mesh, facets, 4, psi_nodes=self.cut.psi)
            df, df_H = surface_load(self.basis, q, traction)
            own, f_H = own + df, f_H + df_H
        if body_force is not None:
            df, df_H = body_load(self, body_force)
            own, f_H = own + df, f_H + df_H
        f = own if f is None else f
        return f, f_H[self.enr_dofs] - self.H_node * f[self.enr_dofs]

    def constraints(self, scene, mesh) -> tuple[np.ndarray, np.ndarray]:
        """The constrained unknowns of [a, b] and their values (:func:`constrained_dofs`)."""
        return constrained_dofs(self, scene, mesh)


@dataclass(frozen=True)
class XSpaces:
    """The X-FEM space of a scene's interfaces: one Heaviside enrichment each.

    ``per_interface``: the :class:`XSpace` of each interface, on its own unknowns
    [a, b^k]; the unknowns of the whole are [a, b¹, b², …] (module notes).  A space
    of one interface reads its ``cut``, ``rule`` and ``parts`` on itself.
    """

    per_interface: tuple[XSpace, ...]

    def __getattr__(self, name):  # a space of one interface: its own (a convenience)
        return one_interface(self, "per_interface", ("cut", "rule", "parts"), name)

    @property
    def enr_dofs(self) -> np.ndarray:
        """(n_enr,) the standard dof of each enriched unknown, interface after interface."""
        return np.concatenate([V.enr_dofs for V in self.per_interface])

    @property
    def H_node(self) -> np.ndarray:
        """(n_enr,) H^k(x_j) of each enriched unknown's node, for its own interface k."""
        return np.concatenate([V.H_node for V in self.per_interface])

    @property
    def mesh(self):
        return self.per_interface[0].mesh

    @property
    def basis(self) -> CellBasis:
        return self.per_interface[0].basis

    @property
    def n_std(self) -> int:
        return self.per_interface[0].n_std

    @property
    def n_enr(self) -> int:
        return sum(V.n_enr for V in self.per_interface)

    @property
    def N(self) -> int:
        return self.n_std + self.n_enr

    @property
    def offsets(self) -> tuple[int, ...]:
        """The unknown of the first enriched dof of each interface."""
        sizes = np.cumsum([0] + [V.n_enr for V in self.per_interface])
        return tuple(int(self.n_std + o) for o in sizes[:-1])

    def columns(self, k: int) -> np.ndarray:
        """(n_std + n_enr_k,) the unknowns of interface k's space [a, b^k] among [a, b¹, …]."""
        own = self.offsets[k] + np.arange(self.per_interface[k].n_enr)
        return np.r_[np.arange(self.n_std), own]

    def lift(self, k: int, A) -> sp.csr_matrix:
        """An operator A_k on interface k's unknowns [a, b^k] as one on the whole's
        (A_k composed with the restriction U ↦ [a, b^k]): its columns renumbered by
        :meth:`columns`, its entries unchanged and in their order."""
        A = sp.csr_matrix(A)
        return sp.csr_matrix((A.data, self.columns(k)[A.indices], A.indptr),
                             shape=(A.shape[0], self.N))

    def regions(self) -> tuple[np.ndarray, np.ndarray]:
        """The regions the interfaces split the body into: their signs (R, n_interfaces),
        ±1 per level set, in lexicographic order, and the region of each node (nverts,).

        A region is a sign pattern taken by a node (its side of each level set,
        ``cut.node_side``: a node on Γ takes a side too): no cell is cut twice, so
        every region that meets a cut cell holds one of its nodes.  A Γ that ends inside the body
        (a crack: its space's ``splits`` False) splits no region and has no sign.
        """
        signs = np.array([V.cut.node_side for V in self.per_interface
                          if V.splits]).reshape(-1, self.mesh.p.shape[1])
        patterns, node_region = np.unique(signs.T, axis=0, return_inverse=True)
        return patterns, node_region.ravel()


def one_interface(owner, field: str, names: tuple, name: str):
    """``getattr(items[0], name)`` for ``name`` in ``names``, ``items`` the tuple
    ``owner.field`` of one interface's parts: the one-interface conveniences of
    :class:`XSpaces` and :class:`skxfem.problem.Problem`, as ``__getattr__``; an
    AttributeError for another name, or with more interfaces than one."""
    kind = type(owner).__name__
    if name not in names:
        raise AttributeError(f"'{kind}' object has no attribute {name!r}")
    items = owner.__dict__.get(field, ())
    if len(items) != 1:
        raise AttributeError(f"{kind}.{name} is that of one interface; this one has "
                             f"{len(items)}: read {field}[k].{name}")
    return getattr(items[0], name)


def constrained_dofs(V: XSpace, scene, mesh) -> tuple[np.ndarray, np.ndarray]:
    """Constrained unknowns of the X-FEM space and their values.

    The shifted enrichment φⱼ(H - Hⱼ) vanishes on a boundary facet that Γ
    does not cut, so there imposing aᵢ imposes u, except at a node on Γ of the
    other side (Hⱼ ≠ H there: a facet of Ω⁻ touching Γ at a node of Ω⁺).  On a
    facet that Γ cuts, u = a + b(H - Hⱼ) takes both signs of H.  So where a
    displacement acts on the whole facet (it selects all the facet's vertices)
    the enriched dofs of its components at those nodes (all the nodes of a cut
    facet) are set to zero as well.  Each
    displacement is taken on its own: two supports whose nodes together
    cover a facet do not constrain it.

    Parameters
    ----------
    V
        The X-FEM space (:func:`skxfem.enrich.xfem_space`).
    scene, mesh
        The scene and its resolved mesh.

    Returns
    -------
    dofs, values
        Indices into the unknowns [a, b] (``V.N`` of them) and imposed values.
    """
    dofs, values = dirichlet(scene, mesh, V.basis)
    psi, node_side = V.cut.psi, V.cut.node_side
    bf = mesh.facets[:, mesh.boundary_facets()]
    neg, plus = (psi[bf] < 0).any(axis=0), (psi[bf] > 0).any(axis=0)
    # the nodes where H - Hⱼ does not vanish on the facet: all of a cut facet's; on
    # an uncut one (side s) its nodes on Γ of the other side, Hⱼ = -s
    differs = (neg & plus) | (node_side[bf] != np.where(neg, -1, 1))
    pos = np.full(V.n_std, -1)
    pos[V.enr_dofs] = np.arange(V.n_enr)
    enr = [np.zeros(0, dtype=np.int64)]
    for support_nodes, components in imposed(scene, mesh):
        selected = np.zeros(mesh.p.shape[1], dtype=bool)
        selected[support_nodes] = True
        whole = selected[bf].all(axis=0)
        nodes = np.unique(bf[:, whole][differs[:, whole]])
        for comp in components:
            b = pos[V.basis.nodal_dofs[comp, nodes]]
            enr.append(V.n_std + b[b >= 0])
    enr = np.unique(np.concatenate(enr))
    return (np.concatenate([dofs, enr]),
            np.concatenate([values, np.zeros(enr.size)]))


def as_spaces(V: XSpace | XSpaces) -> XSpaces:
    """``V`` as an :class:`XSpaces`: an :class:`XSpace` is the space of one interface,
    ``XSpaces((V,))``, with the same unknowns [a, b].

    >>> from skfem import MeshTri1
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut
    >>> m = MeshTri1().refined(1)
    >>> V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    >>> as_spaces(V).N == V.N, as_spaces(as_spaces(V)) == as_spaces(V)
    (True, True)
    """
    return V if isinstance(V, XSpaces) else XSpaces((V,))


@LinearForm
def _signed_mass(v, w):
    return w["H"] * v


def far_side_fraction(mesh, cut: Cut, scalar_parts: Parts | None = None) -> np.ndarray:
    """For each node j: ∫ φⱼ over the side of Γ opposite to the node, / ∫ φⱼ.

    The shifted enrichment φⱼ(H - Hⱼ) lives on that far side only; where it is
    a sliver the enriched dof carries no information but spoils the
    conditioning (see :func:`xfem_space`).  A node of no cut cell has no far
    side: 0.  ``scalar_parts``: :func:`skxfem.fem.side_bases.parts` of the scalar
    element at a rule exact for φⱼ (default: the stiffness' rule).
    """
    side_parts = scalar_parts or parts(mesh, cut, mesh.elem())
    total, signed = side_parts.signed(
        lambda basis: _signed_mass.assemble(basis, H=np.ones(basis.dx.shape)))
    j = cut.enriched  # signed is exact there only
    frac = np.zeros(mesh.p.shape[1])
    frac[j] = 0.5 * (total[j] - cut.node_side[j] * signed[j]) / total[j]
    return np.clip(frac, 0.0, 1.0)


def xfem_space(mesh, cut: Cut, order: int | None = None, sliver: float = 1e-8) -> XSpace:
    """Build the X-FEM space of ``mesh`` cut by ``cut``.

    Nodes of cut cells are enriched, except those whose far-side fraction
    (:func:`far_side_fraction`) is below ``sliver``: Γ only grazes a corner of
    their support (a plane a tiny distance from a node), the enriched
    function is numerically zero and the other nodes' enrichment carries the
    jump there.
    """
    if not sliver >= 0:
        raise ValueError(f"sliver must be a non-negative fraction, got {sliver!r}")
    rule = cell_rule(mesh, order or exact_orders(mesh)[0])
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, 0))
    scalar = parts(mesh, cut, mesh.elem(), rule)
    nodes = cut.enriched[far_side_fraction(mesh, cut, scalar)[cut.enriched] >= sliver]
    enr = basis.nodal_dofs[:, nodes].T  # (nenr_nodes, dim)
    H_node = np.repeat(cut.node_side[nodes], mesh.dim()).astype(float)
    return XSpace(mesh, cut, basis, enr.ravel(), H_node, rule, scalar)


def signed_bases(V: XSpace, orders: tuple[int, int] | None = None):
    """The pairs (basis, H) covering the mesh, H = ±1 the constant value of
    the Heaviside function on that basis: see :func:`skxfem.fem.side_bases.side_bases`.

    ``orders`` (cell, sub-simplex): the quadrature orders; default those of
    ``V`` (its stiffness rule and the stiffness' sub-simplex order)."""
    if orders is None:
        return side_bases(V.mesh, V.cut, V.basis.elem, V.rule)
    return side_bases(V.mesh, V.cut, V.basis.elem, cell_rule(V.mesh, orders[0]), orders[1])


def enriched_blocks(V: XSpace | XSpaces, A, AH, cross=None) -> sp.csr_matrix:
    """The X-FEM matrix on [a, b¹, b², …] from A = ∫ g(φᵢ, φⱼ) on the standard dofs
    and, for each interface k, A_H = ∫ H^k g(φᵢ, φⱼ) (``AH``, one per interface): A,
    the blocks of each enrichment with A (module notes, H² = 1), and between two
    enrichments ``cross[(j, k)]`` (j's rows, k's columns; :func:`couplings`), else zero.
    Only the columns of the enriched dofs of each A_H are read."""
    V = as_spaces(V)
    A = A.tocsr()
    cross = cross or {}
    parts = [Vk.blocks(A, AHk) for Vk, AHk in zip(V.per_interface, AH, strict=True)]
    rows = [[A] + [Aab for Aab, _ in parts]]

    def between(k, j):
        return cross[(k, j)] if (k, j) in cross else (
            cross[(j, k)].T if (j, k) in cross else None)

    for k, (Aab, Abb) in enumerate(parts):
        rows.append([Aab.T] + [Abb if j == k else between(k, j)
                               for j in range(len(parts))])
    return sp.bmat(rows, format="csr")


def couplings(V: XSpace | XSpaces, material: Material) -> dict:
    """The stiffness blocks between the enrichments of two interfaces, ``(j, k) ->``
    j's rows and k's columns, from a space's ``coupling(other, material)`` (a crack's:
    its branch functions reach past the cells it cuts, into another crack's enriched
    supports); none from two Heaviside spaces (a shifted Heaviside enrichment vanishes
    outside its interface's cut cells, and no cell is cut by two)."""
    spaces, out = as_spaces(V).per_interface, {}
    for k in range(len(spaces)):
        for j in range(k):
            for a, b, key in ((spaces[j], spaces[k], (j, k)), (spaces[k], spaces[j], (k, j))):
                if hasattr(a, "coupling"):
                    block = a.coupling(b, material)
                    if block is not None and block.nnz:
                        out[key] = block
                    break
    return out


def stiffness(V: XSpace | XSpaces, material: Material,
              material_plus: Material | None = None) -> sp.csr_matrix:
    """The X-FEM stiffness on the unknowns [a, b¹, …]: ∫ σ(u):ε(v), each part
    assembled from scalar forms (:func:`skxfem.fem.material.stiffness_matrix`), A
    once and A_H per interface.

    ``material_plus``: the material of Ω⁺ (``material`` that of Ω⁻), for a space of
    one interface: A = K⁻ + K⁺ and A_H = K⁺ - K⁻, each side assembled on its own
    cells and sub-cells (:func:`skxfem.fem.side_bases.side_bases`)."""
    V = as_spaces(V)
    if material_plus is not None and material_plus != material:
        if len(V.per_interface) != 1:
            raise ValueError("stiffness: a material per side of Γ (material_plus) is "
                             "for a space of one interface; give one material")
        Vk = V.per_interface[0]
        A = AH = 0
        for basis, side in side_bases(Vk.mesh, Vk.cut, Vk.mesh.elem(), Vk.rule):
            Ks = stiffness_matrix(material_plus if side > 0 else material, basis)
            A, AH = A + Ks, AH + side * Ks
        return enriched_blocks(V, A, [AH])

    A, AH = None, []
    for Vk in V.per_interface:  # each space signs its own (a crack: its own blocks)
        A, AHk = Vk.signed_stiffness(material, A)
        AH.append(AHk)
    return enriched_blocks(V, A, AH, couplings(V, material))


@BilinearForm
def _signed_vector_mass(u, v, w):
    return w["H"] * dot(u, v)


def mass(V: XSpace | XSpaces) -> sp.csr_matrix:
    """The X-FEM mass matrix on the unknowns [a, b¹, …]: ∫ u·v, integrated
    exactly on affine cells (its own orders, :data:`skxfem.fem.quadrature.EXACT_ORDERS`, not the
    stiffness' of ``V``'s basis)."""
    V = as_spaces(V)
    A, AH = None, []
    for Vk in V.per_interface:  # each space signs its own (a crack: its own blocks)
        A, AHk = Vk.signed_mass(A)
        AH.append(AHk)
    return enriched_blocks(V, A, AH)


def body_load(V: XSpace, force) -> tuple[np.ndarray, np.ndarray]:
    """(f, f_H) of a body force b (a volume force, F/L³, such as gravity ρg) on the
    standard dofs: f = ∫ b·φ and f_H = ∫ H b·φ (exact on the enriched dofs only), for
    :meth:`XSpace.load`.  ``force``: :func:`skxfem.fem.loads.force_field`'s (dim values,
    each a number or a callable ``x -> array`` such as a formula), integrated on the
    sides of Γ by the rule of the mass
    (:data:`skxfem.fem.quadrature.EXACT_ORDERS`: exact for a constant or linear b on
    affine cells).

    >>> from skfem import MeshQuad1
    >>> from skxfem.cut import cut
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(1)
    >>> V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    >>> f, f_H = body_load(V, (0.0, -2.0))
    >>> float(f[V.basis.nodal_dofs[1]].sum()), float(f[V.basis.nodal_dofs[0]].sum())
    (-2.0, 0.0)
    """
    values = force_field(force, V.mesh.dim())

    @LinearForm
    def form(v, w):
        return w["H"] * sum(b * v[i] for i, b in enumerate(values(w.x)))

    cell, sub = exact_orders(V.mesh, "mass")
    side_parts = parts(V.mesh, V.cut, V.basis.elem, cell_rule(V.mesh, cell), sub)
    return side_parts.signed(lambda basis: form.assemble(basis, H=np.ones(basis.dx.shape)))


def jump_matrix(V: XSpace, cells: np.ndarray, ref: np.ndarray) -> sp.csr_matrix:
    """The operator U ↦ [[u_h]] = -2 Σⱼ φⱼ bⱼ at points on Γ (component-major rows)."""
    Phi = evaluation_matrix(V.basis, cells, ref)
    return sp.hstack([sp.csr_matrix((Phi.shape[0], V.n_std)),
                      -2.0 * Phi[:, V.enr_dofs]], format="csr")


def edge_jumps(V: XSpace, U: np.ndarray) -> np.ndarray:
    """[[u]] (dim, ne) at the cut edges' points: -2((1 - t) b_a + t b_b).

    Along an edge (a, b) the shape functions of its two ends are the only ones
    left, and linear, so the jump -2 Σ_j φ_j b_j at the point t of the edge
    (ψ's zero, t = ψ_a/(ψ_a - ψ_b)) needs the enriched dofs of a and b only; at a
    vertex v on Γ (the point (v, v)), [[u]] = -2 b_v.

    >>> from skfem import MeshQuad1
    >>> from skxfem.cut import cut
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(1)
    >>> V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    >>> U = np.zeros(V.N); U[V.n_std:] = -0.5          # b = -1/2: [[u]] = 1
    >>> edge_jumps(V, U).round(12).tolist()[0]
    [1.0, 1.0, 1.0]
    """
    cut = V.cut
    a, b = cut.edges
    with np.errstate(invalid="ignore"):   # a vertex on Γ, (v, v): its own b
        t = np.where(a == b, 0.0, cut.psi[a] / (cut.psi[a] - cut.psi[b]))
    bvals = np.zeros(V.n_std)
    bvals[V.enr_dofs] = U[V.n_std:]
    nodal = bvals[V.basis.nodal_dofs]  # (dim, nverts)
    return -2.0 * ((1 - t) * nodal[:, a] + t * nodal[:, b])


def split_fields(V: XSpace, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodal values (dim, nverts) of the Ω⁻ and Ω⁺ fields of a space of one interface,
    u± = a + b(±1 - H_j): its two regions' (:func:`region_fields`)."""
    minus, plus = region_fields(V, U)[1]
    return minus, plus


def from_fields(V: XSpace, minus: np.ndarray, plus: np.ndarray) -> np.ndarray:
    """The unknowns U = [a, b] of nodal fields (dim, nverts) u⁻ on Ω⁻ and u⁺ on Ω⁺:
    aᵢ the field of node i's own side, b_j = (u⁺ - u⁻)/2 at the enriched nodes
    (u± = a + b(±1 - H_j)).  The inverse of :func:`split_fields` on each node's own
    side and at the enriched nodes.

    >>> import numpy as np
    >>> from skfem import MeshQuad1
    >>> from skxfem.cut import cut
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(1)
    >>> V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    >>> minus, plus = np.zeros((2, 9)), np.ones((2, 9))   # [[u]] = -1
    >>> U = from_fields(V, minus, plus)
    >>> [np.array_equal(f[:, V.cut.enriched], g[:, V.cut.enriched])
    ...  for f, g in zip(split_fields(V, U), (minus, plus))]
    [True, True]
    """
    nd = V.basis.nodal_dofs
    a, b = np.zeros(V.n_std), np.zeros(V.n_std)
    a[nd] = np.where(V.cut.node_side < 0, minus, plus)
    b[nd] = 0.5 * (np.asarray(plus, float) - minus)
    return np.concatenate([a, b[V.enr_dofs]])


def region_fields(V: XSpace | XSpaces, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The regions and the nodal values (R, dim, nverts) of each region's field.

    In region σ (its sign σ_k = ±1 for each level set), u = a + Σ_k b^k (σ_k - H^k_j)
    at the nodes: the field of that region continued over the cells it meets.  A Γ
    that splits no region (a crack: ``splits`` False) adds nothing at the nodes (its
    shifted enrichment vanishes there).
    The regions are :meth:`XSpaces.regions`; for one interface [[-1], [1]], Ω⁻ and Ω⁺,
    whose fields are those of :func:`split_fields`.

    >>> from skfem import MeshQuad1
    >>> from skxfem.cut import cut
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(2)
    >>> W = XSpaces(tuple(xfem_space(m, cut(m, plane((0, y), (0, 1)))) for y in (0.3, 0.8)))
    >>> U = np.zeros(W.N); U[W.offsets[1]:] = -0.5    # b² = -1/2: [[u]] = 1 across Γ₂
    >>> signs, fields = region_fields(W, U)
    >>> jumps = fields[:-1] - fields[1:]                 # across Γ₁, then Γ₂
    >>> signs.tolist(), [float(abs(j).max()) for j in jumps]
    ([[-1, -1], [1, -1], [1, 1]], [0.0, 1.0])
    """
    V = as_spaces(V)
    patterns, _ = V.regions()
    a = U[:V.n_std]
    fields = []
    splitting = [(Vk, start) for Vk, start in zip(V.per_interface, V.offsets) if Vk.splits]
    for sigma in patterns:
        u = a.copy()
        for k, (Vk, start) in enumerate(splitting):
            u[Vk.enr_dofs] += U[start:start + Vk.n_enr] * (sigma[k] - Vk.H_node)
        fields.append(u[V.basis.nodal_dofs])
    return patterns, np.array(fields)
