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
    "compressor.toml": 0.01,
    "roller_chain.toml": 0.0005,
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


def _gas_work_closed_form(r: float, l: float, e: float, table: dict) -> float:
    """∮ F_x dx_p over one crank turn [J] of the gas-force table against the ideal offset
    slider-crank's piston position x_p(θ) = r cos θ + √(l² − (e − r sin θ)²), by quadrature."""
    theta = np.linspace(0.0, 2 * np.pi, 200_001)
    x = r * np.cos(theta) + np.sqrt(l**2 - (e - r * np.sin(theta)) ** 2)
    f = np.interp(theta % table["period"], table["angle"], table["fx"])
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))


def test_compressor_takes_the_gas_work_of_its_table_each_turn():
    """The gas-force table follows the crank angle: the work the piston does against it over
    the second turn matches the table integrated along the ideal piston stroke (the clearances
    move the piston by tens of µm: 1 %), and it is negative (a compressor absorbs work)."""
    scene = load_scene_file(SCENES / "compressor.toml")
    gas = next(f for f in scene.mechanism.description()["forces"] if f["name"] == "gas")
    table = {"angle": gas["fx"]["table"]["x"], "fx": gas["fx"]["table"]["y"], "period": gas["fx"]["table"]["period"]}
    period = 2 * np.pi / 157.07963267948966
    res = scene.mechanism.simulate(2 * period, dt_out=period / 2000, outputs=["states", "energy", "joints"], progress=False)
    load = res.energy()["load"]
    turn = np.searchsorted(res.t, period)
    expected = _gas_work_closed_form(0.04, 0.14, 0.01, table)
    assert expected < -20.0
    assert load[-1] - load[turn] == pytest.approx(expected, rel=0.01)
    # the crank pin's film carries the load off the wall; the dry wrist pin runs on it
    eps = {j: np.linalg.norm(res.eccentricity(j), axis=1) / c for j, c in (("crank-pin", 30e-6), ("wrist-pin", 20e-6))}
    assert eps["crank-pin"].max() < 1.0 and eps["wrist-pin"][turn:].max() > 1.0


def test_compressor_reliability_study_from_the_cli(tmp_path, capsys):
    """The scene's [study]: FORM on the two pins' clearance tolerances."""
    scene = SCENES / "compressor.toml"
    assert "skip_cycles = 1.0" in scene.read_text()  # the start-up turn is skipped (a start after t = 0)
    out = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(out), "-q", "--no-plots"]) == 0
    rows = (out / "reliability.csv").read_text().splitlines()
    method, pf = rows[1].split(",")[:2]
    assert method == "form" and 1e-3 < float(pf) < 0.2


def test_roller_chain_takes_up_the_load_through_its_tight_span():
    """The roller-chain drive's start-up (3 of its 5 ms): the work of the drive is all accounted
    for (kinetic energy, the load's work, the films' and contacts' dissipation: the balance closes
    to 1e-6 of the drive's work), the upper span is pulled tight — its 20 pins against their
    walls along the span, ε > 0.9, while the pins seated on the sprockets stay near the centre —
    and the driven sprocket lags the driver by exactly the slack those 20 pins took up:
    R (sin θ₁ − sin θ₂) = Σ e_x (the tops of the two pitch circles of radius R, 254 mm apart,
    joined by 20 rigid links and 20 pin offsets)."""
    import math

    scene = load_scene_file(SCENES / "roller_chain.toml")
    res = scene.mechanism.simulate(0.003, dt_out=1e-4, outputs=["states", "joints", "energy"], progress=False)
    assert res.completed and res.stats["integrator"] == "radau"
    e = res.energy()
    assert e["driver"][-1] > 0.1 and abs(e["balance"][-1] - e["balance"][0]) < 1e-6 * e["driver"][-1]
    c = 25e-6
    ecc = {k: res.eccentricity(f"pin{k:02d}")[-1] for k in range(60)}
    tight = [ecc[k] for k in range(1, 21)]
    assert all(np.linalg.norm(v) > 0.9 * c and v[0] > 0.99 * np.linalg.norm(v) for v in tight)
    seated_driven = [ecc[k] for k in range(21, 30, 2)]
    assert all(np.linalg.norm(v) < 0.2 * c for v in seated_driven)
    radius = 12.7e-3 / (2 * math.sin(math.pi / 20))
    th1, th2 = res.position("sprocket-driver")[-1, 2], res.position("sprocket-driven")[-1, 2]
    lag = radius * (math.sin(th1) - math.sin(th2))
    assert lag > 10 * c and sum(v[0] for v in tight) == pytest.approx(lag, rel=1e-3)
