"""The scene files of examples/: each runs with `skxfem run`, opens with what it models,
and the 3D contact example (block.toml) shows what its comment says."""
import json
from pathlib import Path

import numpy as np
import pytest

from skxfem.app.cli import main
from skxfem.scene.file import load_scene

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.toml"))


def test_the_examples_cover_2d_3d_ties_and_contact():
    scenes = [load_scene(p) for p in EXAMPLES]
    kinds = {(s.dim, all(i.law in ("bonded", "bilateral") for i in s.interfaces))
             for s in scenes}
    assert kinds == {(2, True), (3, True), (2, False), (3, False)}, kinds
    assert any(len(s.interfaces) > 1 for s in scenes), "an example with several interfaces"


def test_the_column_of_three_blocks(tmp_path, capsys):
    """column.toml: the glued and the frictionless interface each carry the whole load,
    ∫ p = 1.5 over the width, the frictionless one no tangential traction."""
    path = next(p for p in EXAMPLES if p.stem == "column")
    assert main(["run", str(path), "--out", str(tmp_path)]) == 0
    assert "bonded+frictionless" in capsys.readouterr().out
    data = json.loads((tmp_path / "result.json").read_text())
    assert [i["law"] for i in data["interfaces"]] == ["bonded", "frictionless"]
    points, which = np.array(data["points"]), np.array(data["interface"])
    traction = np.array(data["traction"])
    for k in (0, 1):
        x, ty = points[which == k, 0], traction[which == k, 1]
        order = np.argsort(x)
        # the vertical traction along Γ, integrated over its width (trapezoid on the
        # multiplier points, the ends extended flat): the load 1.5
        xs = np.r_[0.0, x[order], 1.0]
        ts = np.r_[ty[order][0], ty[order], ty[order][-1]]
        assert abs(np.trapezoid(ts, xs) + 1.5) < 0.05, k
    n = np.array(data["normals"])[which == 1]
    t = traction[which == 1]
    assert np.abs(t - (t * n).sum(1)[:, None] * n).max() < 1e-10


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_each_example_runs(tmp_path, capsys, path):
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert out.count("\n") == 1 and out.startswith(f"{load_scene(path).name}: "), out
    assert (tmp_path / "out" / "result.json").exists()


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_each_example_opens_with_what_it_models(path):
    """A comment for a reader of the file, not a pointer into the project's own history."""
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("# ") and len(first) > 30, first
    for internal in ("issue", "tests/", "test_", "TODO"):
        assert internal not in first, first


def test_the_3d_block_opens_slides_and_sticks_by_coulomb(tmp_path, capsys):
    """block.toml: open near the corner x = y = 0 (p = 0), sliding points carry a
    tangential traction μp against their slip, sticking ones at most μp."""
    path = next(p for p in EXAMPLES if p.stem == "block")
    assert main(["run", str(path), "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    data = json.loads((tmp_path / "result.json").read_text())
    last, codes, mu = data["steps"][-1], data["status_codes"], data["interfaces"][0]["friction"]
    points = np.array(data["points"])
    status, p = np.array(last["status"]), np.array(last["pressure"])
    t = np.linalg.norm(np.array(last["tangential_traction"]), axis=1)
    assert points.shape[1] == 3 and mu == 0.5
    assert np.ptp(points[:, 2]) > 0.05, "Γ is slanted"
    count = {name: int((status == name).sum()) for name in codes}
    assert min(count.values()) >= 1, count
    opened = status == "open"
    assert np.all(points[opened, :2].sum(1) < 0.5) and np.all(np.abs(p[opened]) < 1e-10)
    slip, stick = status == "slip", status == "stick"
    np.testing.assert_allclose(t[slip], mu * p[slip], rtol=1e-6)
    v = np.array(last["slip"])[slip]
    cosine = (np.array(last["tangential_traction"])[slip] * v).sum(1) / t[slip] \
        / np.linalg.norm(v, axis=1)
    np.testing.assert_allclose(cosine, -1.0, atol=1e-6)
    assert np.all(t[stick] <= mu * p[stick] * (1 + 1e-8))
    assert points[stick, :2].sum(1).mean() > points[slip, :2].sum(1).mean()
