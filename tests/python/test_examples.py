"""The example scenes (scenes/*.toml) run briefly from the CLI, and what each shows is there."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from clearsim.cli import main
from clearsim.scene import load_scene, load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"
EXAMPLES = {
    "press_workpiece.toml": 0.05,
    "engine.toml": 0.02,
    "slider_crank_guide_clearance.toml": 0.01,
    "four_bar_spring.toml": 0.1,
}


@pytest.mark.parametrize("name, t_end", sorted(EXAMPLES.items()))
def test_example_scene_runs_from_the_cli(tmp_path, capsys, name, t_end):
    out = tmp_path / "out"
    assert main(["run", str(SCENES / name), "-o", str(out), "--t-end", str(t_end), "-q"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary  # written
    assert any(p.suffix == ".png" for p in out.iterdir())


def test_every_shipped_scene_is_exercised():
    shipped = {p.name for p in SCENES.glob("*.toml")}
    assert set(EXAMPLES) <= shipped
    # tested in test_scene / test_cli / test_reliability_cli
    assert shipped - set(EXAMPLES) == {"nine_bar.toml", "nine_bar_lubricated.toml", "slider_crank.toml", "nine_bar_reliability.toml"}


def test_engine_crank_speed_fluctuates_under_the_gas_force():
    m = load_scene(SCENES / "engine.toml")
    res = m.simulate(0.08, dt_out=1e-4, progress=False)
    w = res.velocity("crank")[:, 2]
    assert res.completed and w.min() > 100.0 and np.ptp(w[res.t > 0.02]) > 20.0


def test_press_workpiece_load_acts_near_bottom_dead_centre():
    scene = load_scene_file(SCENES / "press_workpiece.toml")
    loaded = scene.mechanism.simulate(0.4, dt_out=1e-3, outputs=["states", "energy"], progress=False)
    e = loaded.energy()
    assert e["load"][-1] < -1.0  # the workpiece takes work out of the press each stroke
