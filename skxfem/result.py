r"""What a solve returns, for every law: the fields of both sides and of Γ at the cut edges.

:func:`skxfem.solve` returns a :class:`Result` whatever the law: a tie
(``bonded``, ``bilateral``, :mod:`skxfem.solver`) or contact (``frictionless``,
``coulomb``, ``adhesive``, :mod:`skxfem.contact`).  Its interface fields live
at the ``points`` where Γ cuts the mesh edges (the paper's multiplier points,
§4.2), joined by the interface ``facets``, for every law and multiplier space:

* ``traction`` (dim, n): r = σ⁻·n, the whole traction vector; its parts by
  name: :attr:`Result.normal_traction` λ = r·n (≤ 0 in contact),
  :attr:`Result.pressure` p = -λ, :attr:`Result.tangential_traction` r_τ;
* ``jump`` (dim, n): [[u]] = u⁻ - u⁺ at the points; :attr:`Result.gap`
  d_n = [[u]]·n (≤ 0 admissible in contact).

A multiplier space keeps fewer multipliers μ than cut edges, λ = P μ on the
edges (§5): the fields are those of λ_h at the points, for a contact law
too, whose laws are imposed at the multiplier dofs (:mod:`skxfem.contact`).
A contact result adds the load ``steps`` (the values at the dofs, each step's
Newton iterations), the ``status`` of each point (open, stick, slip: that of
the dof that carries most of its multiplier) and the total ``iterations``.

>>> import skxfem
>>> from dataclasses import replace
>>> s = skxfem.scenes.strip(3, sides="rollers")
>>> tie, glued = skxfem.solve(s), skxfem.solve(replace(s, law="adhesive"))
>>> type(tie) is type(glued), glued.status.tolist()   # pressed and held: every point sticks
(True, [1, 1, 1, 1])
>>> bool(abs(tie.pressure - glued.pressure).max() < 1e-12)
True

**Interfaces and regions.** The interface fields of all interfaces are
concatenated, interface after interface (one interface: its own), with
``interface`` (n,) the index of each point's interface and ``facets`` indexing
the concatenated points.  The interfaces split the body into regions, so a result
has the displacement of each region: ``regions`` (R, n_interfaces), the side (±1)
of each level set in each region, and ``u_regions`` (R, dim, nverts), each
region's field at the nodes (:func:`skxfem.enrich.region_fields`).  With one
interface they are Ω⁻ and Ω⁺ (``[[-1], [1]]``), which :attr:`Result.u_minus` and
:attr:`Result.u_plus` read (conveniences, None with several).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .enrich import region_fields

__all__ = ["Result", "result"]


@dataclass(frozen=True)
class Result:
    """What :func:`skxfem.solve` returns; the names match ``result.json``.

    ``points``, ``normals``, ``traction``, ``jump`` are (dim, n) at the cut
    edges' points, ``facets`` (dim, nf) index them; ``max_jump`` is the
    largest jump the law forbids at the interface quadrature points
    (|[[u]]| bonded, |[[u]]·n| bilateral, the largest penetration max(d_n, 0)
    in contact); ``removed`` counts the dependent multipliers removed;
    ``linear`` says which linear solve ran (``"direct"`` or ``"iterative"``)
    and ``linear_info`` how it went: the relative ``residual`` of the saddle
    system reached, the ``balance`` of the multipliers, its ``tol`` and, for
    the iterative solve, its CG ``iterations`` and ``residuals`` and the
    ``backward_error`` that accepted a residual rounding held above ``tol``
    (None otherwise; :mod:`skxfem.linalg.iterative`).
    Contact adds ``steps`` (:class:`skxfem.contact.Step`), ``status`` (n,)
    (0 open, 1 stick, 2 slip), the interface operators ``ops`` and the
    ``law`` (a tuple of :class:`skxfem.contact.newton.Law`, one per interface);
    for a tie they are empty.
    ``interface`` (n,) is the interface of each point, ``regions`` and
    ``u_regions`` the regions and their nodal fields (module notes).  ``U`` holds
    the unknowns [a, b¹, …] of the X-FEM space ``V`` (:class:`skxfem.enrich.XSpaces`,
    as :attr:`skxfem.problem.Problem.V`) and ``problem`` the assembled problem.
    ``front``: one dict per interface with a front (a crack, :class:`skxfem.gamma.Crack`),
    in the scene's order: ``points`` (m, dim) the front's points, ``K_I``, ``K_II``
    and, in 3D, ``K_III`` (m,) the stress intensity factors there
    (:func:`skxfem.crack.sif.sif`, :func:`skxfem.crack.sif3d.sif_3d`), in 3D
    ``interior`` (m,) whether K is trusted there (the point's domain clear of the free
    surfaces the front ends on, :func:`skxfem.crack.kind3d.front_reach`), and
    ``interface`` the index of the crack in the scene's interfaces; empty without a
    crack.  ``timings``: seconds per stage, ``cut``, ``enrich``, ``assemble``,
    ``solve`` and, with a crack, ``front`` (K along its fronts).
    """

    scene: object
    mesh: object
    points: np.ndarray
    normals: np.ndarray
    traction: np.ndarray
    jump: np.ndarray
    facets: np.ndarray
    max_jump: float
    n_dofs: int
    n_multipliers: int
    removed: int = 0
    timings: dict = field(default_factory=dict)
    U: np.ndarray | None = field(default=None, repr=False)
    V: object = field(default=None, repr=False)
    linear: str = "direct"
    linear_info: dict = field(default_factory=dict)
    problem: object = field(default=None, repr=False)
    steps: tuple = ()
    status: np.ndarray | None = None
    ops: object = field(default=None, repr=False)
    law: object = None
    interface: np.ndarray | None = None
    regions: np.ndarray | None = None
    u_regions: np.ndarray | None = field(default=None, repr=False)
    front: tuple = ()

    @property
    def u_minus(self) -> np.ndarray | None:
        """Ω⁻'s nodal field (dim, nverts) of a result of one interface: ``u_regions[0]``
        (a convenience; None with several level sets, read ``u_regions``)."""
        return self.u_regions[0] if np.shape(self.regions)[1] == 1 else None

    @property
    def u_plus(self) -> np.ndarray | None:
        """Ω⁺'s nodal field (dim, nverts) of a result of one interface: ``u_regions[1]``
        (a convenience, as :attr:`u_minus`)."""
        return self.u_regions[1] if np.shape(self.regions)[1] == 1 else None

    @property
    def normal_traction(self) -> np.ndarray:
        """λ = r·n (n,), ≤ 0 in contact."""
        return (self.traction * self.normals).sum(0)

    @property
    def pressure(self) -> np.ndarray:
        """p = -r·n (n,)."""
        return -self.normal_traction

    @property
    def tangential_traction(self) -> np.ndarray:
        """r_τ = r - (r·n) n (dim, n)."""
        return self.traction - self.normal_traction * self.normals

    @property
    def gap(self) -> np.ndarray:
        """d_n = [[u]]·n (n,), ≤ 0 admissible in contact."""
        return (self.jump * self.normals).sum(0)

    @property
    def is_contact(self) -> bool:
        """True for the result of a contact solve: it has load ``steps``."""
        return len(self.steps) > 0

    @property
    def iterations(self) -> int:
        """The Newton iterations of every load step (0 for a tie)."""
        return sum(int(st.newton.iterations) for st in self.steps)

    @property
    def reactions(self) -> np.ndarray:
        """(dim, nverts) the force each support exerts on each node: K U - F at the imposed
        displacement components (0 elsewhere), F the loads (of the last step); their
        sum balances the loads, :attr:`applied` (module notes)."""
        pb = self.problem
        F = self.steps[-1].F if self.steps and self.steps[-1].F is not None else pb.F
        r = np.zeros(pb.V.N)
        r[pb.D] = (pb.K @ self.U - F)[pb.D]
        return r[:pb.V.n_std][pb.V.basis.nodal_dofs]

    @property
    def applied(self) -> np.ndarray:
        """(dim,) the resultant of the loads (surface loads and body force, of the last
        step): the sum of F over the standard unknowns of each component."""
        pb = self.problem
        F = self.steps[-1].F if self.steps and self.steps[-1].F is not None else pb.F
        return np.asarray(F)[:pb.V.n_std][pb.V.basis.nodal_dofs].sum(axis=1)

    def support_forces(self) -> np.ndarray:
        """(n_displacements, dim) the resultant reaction of each imposed displacement of
        the scene, in its order; a node and component imposed by several goes to the
        last (as :func:`skxfem.scene.boundary.dirichlet` imposes it)."""
        from .scene.boundary import imposed  # the scene layer, below this one
        R = self.reactions
        owner = np.full(R.shape, -1)
        for k, (nodes, components) in enumerate(imposed(self.scene, self.mesh)):
            for c in components:
                owner[c, nodes] = k
        return np.array([[R[c][owner[c] == k].sum() for c in range(R.shape[0])]
                         for k in range(len(self.scene.displacements))]).reshape(-1, R.shape[0])

    def fields(self) -> list[tuple[np.ndarray, object]]:
        """The displacement field of each region and its material: one (field,
        material) per region, in the order of ``regions`` (one interface: (u⁻, Ω⁻'s),
        (u⁺, Ω⁺'s); a material per side is for one interface only)."""
        minus, plus = self.scene.materials()
        return [(u, minus if (signs[:1] < 0).any() else plus)  # no sign: no Γ splits it
                for u, signs in zip(self.u_regions, np.asarray(self.regions))]

    def strains(self) -> list[np.ndarray]:
        """(dim, dim, ncells) the strain ε = sym ∇u of each field of :meth:`fields` at the
        centre of every cell (the fields extend over the whole mesh: a cell of one side
        reads its own side's)."""
        basis = self.problem.V.basis          # one quadrature point per cell: its centre
        out = []
        for u, _ in self.fields():
            x = np.zeros(basis.N)
            x[basis.nodal_dofs] = u
            g = basis.interpolate(x).grad[..., 0]          # (dim, dim, ncells)
            out.append(0.5 * (g + np.swapaxes(g, 0, 1)))
        return out

    def stresses(self) -> list[np.ndarray]:
        """(dim, dim, ncells) σ(ε) of each field of :meth:`fields`, with its material."""
        dim = self.mesh.dim()
        return [m.stress(eps, dim) for eps, (_, m) in zip(self.strains(), self.fields())]


def result(pb, U: np.ndarray, traction: np.ndarray, max_jump: float, n_multipliers: int,
           seconds: float, linear: str, linear_info: dict, **contact) -> Result:
    """The :class:`Result` of the assembled problem ``pb`` solved as U in ``seconds``, with
    the ``traction`` (dim, n) at the cut edges' points (of every interface in turn);
    ``contact``: the keywords ``steps``, ``status``, ``ops``, ``law``, ``removed``.  Its
    ``timings``: the stages of ``pb.timings`` (cut, enrich, assemble), the solve and,
    with a crack, ``front``: K along its fronts (:func:`_fronts`)."""
    t = pb.timings
    timings = {"cut": t["cut"] + t["space"], "enrich": t["enrich"],
               "assemble": sum(t[k] for k in ("stiffness", "load", "constraints", "interface",
                                              "prolongation")), "solve": seconds}
    regions, fields = region_fields(pb.V, U)
    common = dict(scene=pb.scene, mesh=pb.mesh, traction=traction, max_jump=float(max_jump),
                  n_dofs=pb.V.N, n_multipliers=int(n_multipliers), timings=timings, U=U,
                  V=pb.V, linear=linear, linear_info=linear_info, problem=pb,
                  regions=regions, u_regions=fields, **contact)
    start = time.perf_counter()
    front = _fronts(pb, U, traction, contact.get("steps", ()))
    if front:
        timings["front"] = time.perf_counter() - start
    qs = pb.interfaces
    sizes = [q.cut.edge_ids.size for q in qs]
    offsets = np.cumsum([0] + sizes[:-1])
    return Result(
        points=np.hstack([q.cut.points for q in qs]),
        normals=np.hstack([q.normals() for q in qs]),
        jump=np.hstack([q.gamma.point_jumps(q.V, U[q.columns]) for q in qs]),
        facets=np.hstack([_joined(q.cut.facets) + o for q, o in zip(qs, offsets)]),
        interface=np.repeat(np.arange(len(qs)), sizes),
        front=front, **common)


def _joined(facets: np.ndarray) -> np.ndarray:
    """The interface facets whose ends are all cut points (a crack's facet that ends at
    the front, end -1, joins no two points)."""
    return facets[:, (facets >= 0).all(axis=0)]


def _fronts(pb, U: np.ndarray, traction: np.ndarray, steps=()) -> tuple:
    """The stress intensity factors of each interface with a front (its kind's
    :meth:`skxfem.gamma.Gamma.front`, given the interface's ``traction`` at its cut
    points, which loaded faces carry, the body force of the solved state, whose
    term the interaction integral holds, and the scene's other interfaces with their
    unknowns, whose fields reach into a front's domain; None for one that has none),
    each with the index of its ``interface`` in the scene."""
    ends = np.cumsum([0] + [q.cut.edge_ids.size for q in pb.interfaces])
    force = _body_force(pb, steps)
    qs = pb.interfaces
    fronts = (q.gamma.front(q.V, U[q.columns], pb.scene.material, traction[:, a:b],
                            body_force=force,
                            others=tuple((o.gamma, o.V, U[o.columns]) for o in qs if o is not q))
              for q, a, b in zip(qs, ends[:-1], ends[1:]))
    return tuple(dict(f, interface=k) for k, f in enumerate(fronts) if f is not None)


def _body_force(pb, steps) -> object:
    """The body force of the state U solves: the last step's (its load factor times the
    scene's, or its load state's, :class:`skxfem.contact.history.Step`), the scene's
    without steps; None: none."""
    return steps[-1].body_force if steps else pb.scene.body_force


def on_edges(P: sp.spmatrix, values: np.ndarray) -> np.ndarray:
    """Values at the multiplier dofs (m, ...) carried to the cut edges by λ = P μ."""
    return np.asarray(sp.csr_matrix(P) @ values)
