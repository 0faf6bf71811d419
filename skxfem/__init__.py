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
  :class:`Interface` (one of several interfaces of a scene), :class:`Solver`
  (how it is solved: ``Scene.solver``, a scene file's ``[solver]``),
  :func:`load_scene` (a TOML scene file) and the built-in scenes
  ``skxfem.scenes`` (``paper_plate``, ``strip``, ``exact_plate`` ...);
* the level sets :func:`plane`, :func:`circle`, :func:`sphere` and their
  combinations;
* :func:`assemble`, the one assembled interface problem every solver shares;
* the step modules, one per chapter of the book: ``levelset``, ``cut``,
  ``enrich``, ``multipliers``, ``lbb``, ``stabilised``, ``contact``; and
  ``plotting`` (imported when first used: a solve does not import matplotlib) and
  ``evaluate`` (``pressure_along``) to look at a result.
  The paper's figures are ``skxfem.viz.figures`` (imported on demand).

The stable multiplier space (vital edges, the paper's algo2) is what a scene
gets unless it asks for another.

**The tree.** The top level holds the steps of the method in the order of the
book — ``levelset``, ``cut``, ``enrich``, ``multipliers``, ``lbb``,
``stabilised`` — then ``gamma`` (one interface's geometry, the contract of a kind
of Γ), ``problem`` (the one assembled interface problem),
``result`` (what every solve returns) and ``solver``; the rest is grouped in
subpackages, one layer each.  A module imports only from the layers below its
own (import-linter checks it in ``make test``; the contract is in
``pyproject.toml``), lowest first:

1. ``linalg``: the linear solves (``saddle``, ``iterative``, ``amg``, ``pcg``,
   ``dependent``: the dependent multipliers and the smoothest choice among
   them), which one a problem gets (``choice``), BLAS ``threads``, and the
   rigid motions left free (``rigid``);
2. ``fem``: ``simplex``, ``cells`` (the cell types, one table), ``meshes``,
   ``quadrature``, ``fitted`` (moment-fitted rules), ``side_bases`` (the bases
   of each side of Γ), ``material``, ``loads``,
   ``evaluate``, ``vtu``, ``files``, ``cutgraph``, the exact solutions;
3. ``levelset`` (the sign convention);
4. ``scene``: ``laws`` (the laws and spaces, one table), ``parts``, ``expr``,
   ``boundary``, ``settings`` (:class:`Solver`), ``model`` (the :class:`Scene`),
   ``benchmarks`` (``skxfem.scenes``), ``file`` and ``tomlcheck`` (scene files);
5. ``cut``;  6. ``enrich``;  7. ``multipliers``;  8. ``stabilised``;
9. ``crack``: the mathematics of a Γ with a front (2D and 3D: its geometry, rules,
   space, multipliers on its faces, stress intensity factors, the 3D kind);
10. ``gamma``;  11. ``problem``;  12. ``result``;
13. ``contact``: ``laws``, ``interface``, ``step`` (the linear solve of a
    Newton step), ``newton``, ``fixed_point``, ``history`` (``solve``);
14. ``lbb``, ``solver``;
15. ``studies``: ``convergence``, ``conforming``, ``validation3d``, the
    ``extremes`` tables, ``frontier``, ``budget`` and ``counts`` (the size
    guard), ``progress``, ``cracks`` and ``cracks3d``;
16. ``viz``: every module that draws (matplotlib, pyvista; a second contract);
17. ``app``: ``cli``, ``reproduce``, ``grade`` and ``graded``, ``io`` (the
    result files).
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
    lbb,
    levelset,
    multipliers,
    stabilised,
)
from .fem import evaluate  # noqa: E402
from .fem.material import Material  # noqa: E402
from .levelset import circle, complement, intersection, plane, sphere, union  # noqa: E402
from .problem import assemble  # noqa: E402
from .result import Result  # noqa: E402
from .scene import benchmarks as scenes  # noqa: E402
from .scene.file import load_scene  # noqa: E402
from .scene.model import (  # noqa: E402
    Box,
    Displacement,
    Interface,
    Scene,
    Solver,
    SurfaceLoad,
    clamped,
    rollers,
)
from .solver import solve  # noqa: E402


def __getattr__(name: str):
    """``skxfem.plotting`` and ``skxfem.figures`` (:mod:`skxfem.viz.plotting`,
    :mod:`skxfem.viz.figures`), imported when first used: they import matplotlib,
    which a solve (and ``skxfem run``) does without."""
    if name in ("plotting", "figures"):
        import importlib
        return importlib.import_module(f"{__name__}.viz.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "__version__", "solve", "Result", "assemble", "Scene", "Solver", "Interface", "Box",
    "Displacement", "SurfaceLoad", "clamped", "rollers", "Material", "load_scene", "plane",
    "circle", "sphere", "union", "intersection", "complement", "scenes", "levelset", "cut",
    "enrich", "multipliers", "lbb", "stabilised", "contact", "plotting", "evaluate",
]
