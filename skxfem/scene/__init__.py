"""A problem as data: the interface laws and spaces (one table), the scene and
its parts, boundaries, formulas, the built-in benchmark scenes and scene files.

The modules: :mod:`~skxfem.scene.laws` (the laws and spaces a scene may choose),
:mod:`~skxfem.scene.parts` (:class:`Box`, :class:`Displacement`,
:class:`SurfaceLoad`, :class:`Interface`), :mod:`~skxfem.scene.expr` (formulas),
:mod:`~skxfem.scene.boundary` (named and selected boundaries),
:mod:`~skxfem.scene.model` (:class:`Scene`, which this package exports with its
parts), :mod:`~skxfem.scene.benchmarks` (the paper's plate, the strip, the exact
and the known-answer scenes: ``skxfem.scenes``), :mod:`~skxfem.scene.settings`
(:class:`Solver`, how a scene is solved), :mod:`~skxfem.scene.file` and
:mod:`~skxfem.scene.tomlcheck` (scene files).
"""
from .model import (
    CELLS,
    CONTACT_LAWS,
    LAWS,
    MAX_QUADRATURE_ORDER,
    MAX_STEPS,
    SPACES,
    Box,
    Displacement,
    Interface,
    Resolved,
    Scene,
    Solver,
    SurfaceLoad,
    check_scene,
    clamped,
    dirichlet,
    load_facets,
    resolve,
    resolve_mesh,
    rollers,
    traction,
)

__all__ = ["Box", "Displacement", "SurfaceLoad", "Interface", "Scene", "clamped", "rollers",
           "resolve_mesh", "dirichlet", "load_facets", "traction", "LAWS", "CONTACT_LAWS",
           "SPACES", "CELLS", "check_scene", "MAX_QUADRATURE_ORDER", "Solver", "MAX_STEPS",
           "Resolved", "resolve"]
