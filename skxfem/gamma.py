r"""One interface Γ as the steps below the scene see it: the contract of a kind of Γ.

A scene's :class:`~skxfem.scene.Interface` says *what* Γ is (its level set ψ, its
law, its multiplier space).  Every step that needs Γ's *geometry* — the cut
(:mod:`skxfem.cut`), the enrichment (:mod:`skxfem.enrich`), the multiplier space
(:mod:`skxfem.stabilised`), the normals at the multiplier points, the level set
written to the files — asks one object for it, the :class:`Gamma` of the
interface (:func:`gamma`).  :func:`skxfem.problem.assemble` builds one per
interface and keeps it in the interface's :class:`~skxfem.problem.Part`
(``part.gamma``); the solver, the contact Newton, the results and the writers
read the part's fields and never the level set or the kind.

**The contract of a kind.**  A new kind of Γ (a crack: a Γ = {ψ = 0, φ < 0}
that ends inside the body at a front {ψ = φ = 0}) is one more class with the
methods of :class:`Gamma`, returned by :func:`gamma` for its interfaces; nothing
else changes.  Each method must meet:

1. ``cut(mesh, label) -> Cut``: the :class:`skxfem.cut.Cut` of Γ_h on ``mesh``:
   the cut edges and their points (where the multipliers live), the interface
   facets joining them, the cut cells' sub-cells with their sides, the nodal ψ
   as used (``cut.psi``: its sign gives each node its side), and the nodes to
   enrich (``cut.enriched``).  Refuse, with a ValueError naming ``label``, a Γ
   that does not cross the body.  A Γ that ends inside a cell cuts that cell
   partially: its facets stop at the front, and the edges it does not cross are
   not cut edges.
2. ``space(mesh, cut, order) -> XSpace``: the X-FEM space of this Γ on its own
   unknowns [a, b] (:class:`skxfem.enrich.XSpace`): ``enr_dofs``, ``H_node``
   and a ``parts`` that :func:`skxfem.enrich.stiffness` can integrate, so that
   the jump across Γ is -2 Σⱼ φⱼ bⱼ (:func:`skxfem.enrich.jump_matrix`).  A crack
   adds its tip functions as more unknowns of the same space.
3. ``multipliers(mesh, cut, fixed=None, per_edge=None) -> Space``: the
   multiplier space of its interface on the cut edges (:mod:`skxfem.stabilised`).
4. ``normals(cut) -> (dim, n)``: unit normals n = ∇ψ/|∇ψ| at the cut points,
   pointing into Ω⁺ (the sign convention of :mod:`skxfem.levelset`);
   ``normals_at(points)`` the same at any points on Γ (the interface rule's).
5. ``nodal(cut) -> (nverts,)``: the level set at the nodes, as the files write
   it (``levelset_k``): the ψ the solve used.

**What a crack kind will add** (issue 29; the 2D pieces are in :mod:`skxfem.crack`:
``crack_geometry`` carries the fields of a Cut, ``crack_space`` the unknowns [a, b, c],
``crack.assembly.stiffness`` its blocks, ``crack.sif`` the stress intensity factors).
Three places below the kinds read more than the contract above and must then ask
the kind instead: :func:`skxfem.enrich.stiffness` integrates a Heaviside space by
its ``parts`` (a crack's branch functions bring their own blocks, Bᵀ W C B on the
tip cells' almost-polar rules); the regions of :meth:`skxfem.enrich.XSpaces.regions`
(rigid modes, held checks, the pieces of the files) take every Γ as splitting the
body in two, which a Γ that ends inside it does not; and a law without multipliers
(``free``) gives a part with no column in P.

>>> from skfem import MeshTri1
>>> from skxfem.levelset import plane
>>> from skxfem.scene import Interface
>>> g = gamma(Interface(plane((0, 0.3), (0, 1))))
>>> m = MeshTri1().refined(2)
>>> c = g.cut(m, "")
>>> g.space(m, c).n_enr, g.normals(c)[:, 0].tolist()
(20, [0.0, 1.0])
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .cut import Cut
from .cut import cut as cut_mesh
from .enrich import XSpace, xfem_space
from .levelset import point_normals, unit
from .multipliers import Space
from .scene.parts import Interface
from .stabilised import multiplier_space

__all__ = ["Gamma", "gamma"]


@dataclass(frozen=True)
class Gamma:
    """An interface that cuts the body through: Γ = {ψ = 0} (the paper's kind).

    ``interface`` the scene's :class:`~skxfem.scene.Interface`.  The methods are
    the contract of the module notes."""

    interface: Interface

    def cut(self, mesh, label: str = "") -> Cut:
        """The :class:`~skxfem.cut.Cut` of Γ on ``mesh`` (``label`` names it in messages)."""
        return cut_mesh(mesh, self.interface.levelset, label)

    def space(self, mesh, cut: Cut, order: int | None = None) -> XSpace:
        """The Heaviside-enriched space of Γ (:func:`skxfem.enrich.xfem_space`)."""
        return xfem_space(mesh, cut, order)

    def multipliers(self, mesh, cut: Cut, fixed=None, per_edge=None) -> Space:
        """The interface's multiplier space (:func:`skxfem.stabilised.multiplier_space`)."""
        return multiplier_space(self.interface.space, mesh, cut, fixed=fixed,
                                per_edge=per_edge)

    def normals(self, cut: Cut) -> np.ndarray:
        """Unit normals ∇ψ/|∇ψ| (dim, n) at the cut points
        (:func:`skxfem.levelset.point_normals`)."""
        return point_normals(cut, self.interface.levelset)

    def normals_at(self, points: np.ndarray) -> np.ndarray:
        """∇ψ/|∇ψ| (dim, n) at ``points`` on Γ; NaN where ∇ψ is not finite or vanishes."""
        n = np.asarray(self.interface.levelset.gradient(points), float)
        with np.errstate(all="ignore"):   # scaled first: the square of 1e300 overflows
            top = np.abs(n).max(axis=0)
            ok = np.isfinite(top) & (top > 0)
            n, _ = unit(n / np.where(ok, top, 1.0))
        return np.where(ok, n, np.nan)

    def nodal(self, cut: Cut) -> np.ndarray:
        """ψ at the nodes as the solve used it (snapped off the nodes: ``cut.psi``)."""
        return cut.psi


def gamma(interface: Interface) -> Gamma:
    """The :class:`Gamma` of a scene's interface: its kind (module notes; today every
    interface cuts the body through)."""
    if not isinstance(interface, Interface):
        raise TypeError(f"interface must be a skxfem.scene.Interface, got "
                        f"{type(interface).__name__}")
    return Gamma(interface)
