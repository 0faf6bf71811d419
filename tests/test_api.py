"""The public API (``import skxfem``) and the floors of the package."""
import tomllib
from pathlib import Path

import numpy as np
import pytest

import skxfem

ROOT = Path(__file__).resolve().parents[1]


def test_a_notebook_needs_one_import():
    """The cell of issue 8: solve a built-in scene, then plot the pressure."""
    from matplotlib.figure import Figure

    r = skxfem.solve(skxfem.scenes.strip(16, cell="tri"))
    ax = Figure().add_subplot()
    ax.plot(r.points[0], r.pressure, "o")
    assert r.points.shape == (2, r.pressure.size) and np.all(np.isfinite(r.pressure))
    # the total force on Γ is the applied load, ∫ 4x(1 - x) dx = 2/3
    order = np.argsort(r.points[0])
    assert np.trapezoid(r.pressure[order], r.points[0][order]) == pytest.approx(2 / 3, rel=1e-3)


def test_exported_names_exist_and_steps_are_there():
    for name in skxfem.__all__:
        assert hasattr(skxfem, name), f"skxfem.__all__ lists {name!r} but it is missing"
    for step in ("levelset", "cut", "enrich", "multipliers", "lbb", "stabilised", "contact"):
        assert getattr(skxfem, step).__name__ == f"skxfem.{step}"
    assert skxfem.__version__.count(".") >= 2


def test_solve_hands_a_contact_scene_to_the_contact_solver():
    from dataclasses import replace

    s = skxfem.scenes.strip(3)
    s = replace(s, law="frictionless",
                displacements=s.displacements + (skxfem.Displacement("ymax", {"x": 0.0}),))
    result = skxfem.solve(s)
    assert isinstance(result, skxfem.Result) and result.is_contact
    assert type(result) is type(skxfem.solve(replace(s, law="bilateral")))
    assert result.steps[-1].pressure.min() > 0


def test_every_module_and_package_stands_on_a_layer():
    """The import-linter layers contract lists every top-level module and subpackage, so
    that a new one cannot escape the layers by being forgotten; and the top level shows
    the method, not every helper (issue 19: about 15 entries; issue 28 added
    skxfem.gamma, the interface object, and issue 29 a subpackage for cracks)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
    layers = next(c for c in config["contracts"] if c["type"] == "layers")["layers"]
    listed = {m.strip() for line in layers for m in line.split("|")}
    top = ROOT / "skxfem"
    modules = {f"skxfem.{p.stem}" for p in top.glob("*.py")
               if p.stem not in ("__init__", "__main__")}
    packages = {f"skxfem.{p.name}" for p in top.iterdir() if (p / "__init__.py").is_file()}
    assert (modules | packages) - listed == set(), "add these to a layer in pyproject.toml"
    assert listed - (modules | packages) == set(), "these layers name nothing that exists"
    assert len(modules | packages) <= 18, sorted(modules | packages)
    assert not [p for p in top.glob("*/*/__init__.py")], "one level of subpackages"


def test_importing_skxfem_does_not_import_matplotlib():
    """`import skxfem` imported matplotlib (through skxfem.viz.plotting), so every solve and
    every `skxfem run` paid for it and printed its config warnings; skxfem.viz.plotting and
    skxfem.viz.figures are imported when first used."""
    import subprocess
    import sys
    code = ("import sys, skxfem; before = 'matplotlib' in sys.modules; "
            "p = skxfem.plotting; from skxfem import figures; "
            "print(before, p.__name__, figures.__name__, 'matplotlib' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, check=True)
    assert done.stdout.split() == ["False", "skxfem.viz.plotting", "skxfem.viz.figures", "True"]
    with pytest.raises(AttributeError, match="no attribute 'plots'"):
        skxfem.plots
