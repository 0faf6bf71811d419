"""The command line: scene file -> solve -> result.json and VTU files; clean errors."""
import json
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

from skxfem.cli import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(tmp_path, name):
    assert main(["run", str(EXAMPLES / f"{name}.toml"), "--out", str(tmp_path / name)]) == 0
    return json.loads((tmp_path / name / "result.json").read_text())


def test_01_plate_example_runs_end_to_end(tmp_path, capsys):
    data = run(tmp_path, "plate")
    out = capsys.readouterr().out
    assert out.count("\n") == 1 and out.startswith("plate: ") and "multipliers" in out
    assert data["scene"] == "plate" and data["n_dofs"] > 0 and data["n_multipliers"] > 0
    points = np.array(data["points"])
    assert points.shape[1] == 3 and np.allclose(points[:, 2], 0.5), "points lie on Γ"
    assert data["max_jump"] < 1e-10, "the bonded interface does not open"
    assert min(data["pressure"]) > 0, "the plate is compressed everywhere on Γ"
    assert set(data["timings"]) >= {"cut", "enrich", "assemble", "solve"}
    m = meshio.read(tmp_path / "plate" / "displacement.vtu")
    assert m.cells[0].type == "hexahedron" and len(m.cells[0]) == 4 * 4 * 5
    assert meshio.read(tmp_path / "plate" / "interface.vtu").points.shape == points.shape


def test_02_plate_with_rollers_is_the_plane_strain_strip(tmp_path):
    """plate.toml at any x equals strip.toml (its (y, z) are the strip's (x, y))."""
    plate, strip = run(tmp_path, "plate"), run(tmp_path, "strip")
    s = np.array(strip["points"])
    for point, p in zip(plate["points"], plate["pressure"], strict=True):
        [k] = np.flatnonzero(np.isclose(s[:, 0], point[1]))
        assert p == pytest.approx(strip["pressure"][k], rel=1e-6)


def test_03_interface_force_balances_the_load(tmp_path):
    """∫_Γ p dx = ∫ 4x(1 - x) dx = 2/3 (vertical equilibrium of Ω⁺), p piecewise linear."""
    strip = run(tmp_path, "strip")
    order = np.argsort(np.array(strip["points"])[:, 0])
    x = np.array(strip["points"])[order, 0]
    p = np.array(strip["pressure"])[order]
    assert np.trapezoid(p, x) == pytest.approx(2 / 3, rel=1e-8)


@pytest.mark.parametrize("text, words", [
    ("[mesh]\nbox = {n = 'four', cell = 'quad'}\n[levelset]\nexpr = 'y - 0.5'",
     ["[mesh] box.n"]),
    ("[mesh]\nbox = {n = 3, cell = 'quad'}\n[levelset]\nexpr = 'sin(y)'",
     ["[levelset] expr", "function call"]),
    ("[mesh]\nbox = {n = 2, cell = 'quad'}\n[levelset]\nexpr = 'y - 5.25'",
     ["cuts no cell"]),                       # refused by the solver's cut step
    ("[mesh]\nbox = {n = [2, 3], cell = 'quad'}\n[levelset]\nexpr = 'y - 0.5'\n"
     "[[load]]\nboundary = 'ymax'\npressure = 1.0",
     ["singular", "displacements"]),          # no support: the body floats
])
def test_04_bad_scenes_exit_2_with_one_line(tmp_path, capsys, text, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("skxfem: error: ") and "Traceback" not in err
    assert all(w in err for w in words), err
    assert not (tmp_path / "out").exists()


def test_05_missing_file_exits_2_and_debug_shows_the_error(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.toml")]) == 2
    assert "nope.toml" in capsys.readouterr().err
    with pytest.raises(FileNotFoundError):
        main(["run", str(tmp_path / "nope.toml"), "--debug"])


def test_06_python_m_skxfem_and_default_out_folder(tmp_path):
    done = subprocess.run([sys.executable, "-m", "skxfem", "run", str(EXAMPLES / "strip.toml")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "strip" / "result.json").is_file()       # --out defaults to ./<name>
    bad = subprocess.run([sys.executable, "-m", "skxfem", "run", "missing.toml"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
