r"""skxfem: X-FEM with contact on an interface that cuts the mesh, on scikit-fem.

A notebook needs one import, as with scikit-fem:

>>> import skxfem
>>> r = skxfem.solve(skxfem.scenes.strip(8, cell="tri"))
>>> r.points.shape[0], r.pressure.shape == r.points.shape[1:]   # (dim, n) and (n,)
(2, True)

What ``import skxfem`` gives:

* ``skxfem.solve(scene)`` — the tied interface (laws ``bonded``, ``bilateral``)
  or, for the contact laws (``frictionless``, ``coulomb``, ``adhesive``), the
  contact solve of :mod:`skxfem.contact`;
* the scene and its parts: :class:`Scene`, :class:`Box`, :class:`Displacement`,
  :class:`SurfaceLoad`, :func:`clamped`, :func:`rollers`, :class:`Material`,
  :class:`Interface` (one of several interfaces of a scene),
  :func:`load_scene` (a TOML scene file) and the built-in scenes
  ``skxfem.scenes`` (``paper_plate``, ``strip``, ``exact_plate`` ...);
* the level sets :func:`plane`, :func:`circle`, :func:`sphere` and their
  combinations;
* :func:`assemble`, the one assembled interface problem every solver shares;
* the step modules, one per chapter of the book: ``levelset``, ``cut``,
  ``enrich``, ``multipliers``, ``lbb``, ``stabilised``, ``contact``; and
  ``plotting`` (imported when first used: a solve does not import matplotlib) and
  ``evaluate`` (``pressure_along``) to look at a result.
  The paper's figures are ``skxfem.figures`` (imported on demand).

The stable multiplier space (vital edges, the paper's algo2) is what a scene
gets unless it asks for another.

The package is flat; its modules stand on floors, lowest first.  A module
imports only from lower floors (import-linter checks it in ``make test``; the
contract is in ``pyproject.toml``):

1. ``laws`` (the interface laws, one table); the kernels: ``simplex``, ``expr``,
   ``saddle``, ``vtu``, ``progress``, ``grade``,
   ``graded`` (the course's tooling), ``linear`` (which solve), ``threads`` (the BLAS
   threads of a solve), ``files`` (checked reads, a set of files written as one); then
   ``amg``, ``smoothest``, ``pcg``, then ``iterative`` (the scalable linear solve);
2. ``levelset`` (the sign convention), ``meshes``, ``cells``, ``material``,
   ``quadrature``, ``evaluate``, ``contact_laws``;
3. ``cut``, ``exact``, ``exact3d``;  4. ``enrich``, ``loads``;
5. ``multipliers``, ``cutgraph``;  6. ``stabilised``;
7. the scene: ``scene_parts``, ``tomlcheck``, ``boundary``, ``scene``, then
   ``scenes``, ``scenefile``;
8. ``rigid`` (the rigid motions left free), then ``problem``, then ``result`` (what
   every solve returns);  9. ``contact_linear``, then ``contact_interface``,
   ``contact_newton``, ``contact_fixed_point``;  10. ``lbb``, ``contact``, then ``solver``;
11. ``io`` (on ``io_contact``), ``budget`` (on ``counts``), ``convergence``;
12. the studies: ``extremes``, ``frontier``, ``conforming``, ``validation3d``,
    then ``extremes_scales``, ``extremes_shapes``, then ``extremes_table``;
13. drawing: ``plotting``, then ``figstyle``, ``plot_space``, ``render3d``,
    ``schematics``, then ``figures``, ``contact_plots``, ``plot_supports``, ``frontier_plots``,
    ``validation3d_plots``;
14. ``reproduce``, ``cli``.
"""
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("skxfem")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.1.0"

from . import (  # noqa: E402  (the steps, in the order of the book)
    contact,
    cut,
    enrich,
    evaluate,
    lbb,
    levelset,
    multipliers,
    scenes,
    stabilised,
)
from .levelset import circle, complement, intersection, plane, sphere, union  # noqa: E402
from .material import Material  # noqa: E402
from .problem import assemble  # noqa: E402
from .result import Result  # noqa: E402
from .scene import (  # noqa: E402
    Box,
    Displacement,
    Interface,
    Scene,
    SurfaceLoad,
    clamped,
    rollers,
)
from .scenefile import load_scene  # noqa: E402
from .solver import solve  # noqa: E402


def __getattr__(name: str):
    """``skxfem.plotting`` and ``skxfem.figures``, imported when first used: they import
    matplotlib, which a solve (and ``skxfem run``) does without."""
    if name in ("plotting", "figures"):
        import importlib
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "__version__", "solve", "Result", "assemble", "Scene", "Interface", "Box", "Displacement",
    "SurfaceLoad", "clamped", "rollers", "Material", "load_scene", "plane", "circle",
    "sphere", "union", "intersection", "complement", "scenes", "levelset", "cut", "enrich",
    "multipliers", "lbb", "stabilised", "contact", "plotting", "evaluate",
]
