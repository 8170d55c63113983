"""``clearsim run``'s summaries and joints CSV carry every bearing reading: λ = h_min/σ beside
the minimum film in summary.md (as summary.json has it), and a heat model's oil temperature in
summary.json, summary.md, the stdout summary and joints.csv, checked against closed forms on a
centred, unloaded journal (Petroff's loss, heated as T_amb + P/hA (1 − e^(−t hA/C)))."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest

from clearsim import cli
from heat_reference import C, L, OMEGA, R, T_AMB, rotor_scene
from walks import WIPER, read_csv as _csv

MU, SIGMA = 0.03, 1e-6
CAP, HA, T_END = 0.05, 0.2, 0.05
SCENE = rotor_scene(f"{MU}", CAP, HA, T_END, simulation='dt_out = 0.01\n[outputs]\njoint_quantities = ["film_thickness"]', film=f"roughness = {SIGMA}")


def test_the_summaries_and_csv_carry_lambda_and_the_oil_temperature(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = tmp_path / "rotor.toml"
    scene.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "out"
    assert cli.main(["run", str(scene), "-o", str(out), "--no-plots"]) == 0
    petroff = 2 * math.pi * MU * R**3 * L * OMEGA**2 / C  # W, a centred journal's loss
    t_end = T_AMB + petroff / HA * (1 - math.exp(-T_END * HA / CAP))
    b = json.loads((out / "summary.json").read_text(encoding="utf-8"))["run"]["bearings"]["pin"]
    assert b["lambda"] == pytest.approx(C / SIGMA, rel=1e-9)  # unloaded: h_min = c
    assert b["temperature_start"] == T_AMB and b["temperature_end"] == pytest.approx(t_end, abs=1e-3 * (t_end - T_AMB))
    md = (out / "summary.md").read_text(encoding="utf-8")
    header = next(line for line in md.splitlines() if line.startswith("| lubricated joint"))
    row = next(line for line in md.splitlines() if line.startswith("| pin |"))
    cells = dict(zip([h.strip() for h in header.split("|")[1:-1]], [c.strip() for c in row.split("|")[1:-1]]))
    assert float(cells["λ = h_min/σ"]) == pytest.approx(C / SIGMA, rel=1e-3)
    assert float(cells["oil T start [K]"]) == pytest.approx(T_AMB) and float(cells["oil T end [K]"]) == pytest.approx(t_end, rel=1e-5)
    rows = list(csv.reader((out / "joints.csv").open(encoding="utf-8")))
    k = rows[0].index("pin.temperature [K]")
    assert float(rows[1][k]) == pytest.approx(T_AMB) and float(rows[-1][k]) == pytest.approx(b["temperature_end"], rel=1e-9)
    assert "pin.film_thickness [m]" in rows[0]
    stdout = capsys.readouterr().out
    assert "bearing pin: min film 40 µm, λ = 40, oil 313.15 → " in stdout


def test_the_summary_names_the_integrator_that_ran(tmp_path: Path) -> None:
    """A scene asking for integrator = "auto" gets the name the core resolved (radau for a
    lubricated joint), in summary.json and summary.md, with the setting beside it."""
    import json

    from clearsim.cli import main

    scene = Path(__file__).resolve().parents[2] / "scenes" / "nine_bar_lubricated.toml"
    assert main(["run", str(scene), "-o", str(tmp_path), "--t-end", "0.005", "--no-plots", "-q"]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))
    assert (summary["integrator"], summary["integrator_setting"]) == ("radau", "auto")
    assert "integrator radau (auto)" in (tmp_path / "summary.md").read_text(encoding="utf-8")


def test_a_scene_run_from_a_later_t0_says_where_it_started(tmp_path):
    """``clearsim run`` of a scene with ``t0 = 0.25`` (``cycles = 2``: t_end = t0 + 2 s): summary.json
    and summary.md give the window the run covered, t0 as well as t_end, and the first output
    time is t0. Before: both said only ``t_end = 2.25 s``, so a reader took it for a 2.25 s run."""
    import json

    from clearsim.cli import main

    path = tmp_path / "wiper_t0.toml"
    path.write_text(WIPER.read_text(encoding="utf-8").replace("cycles = 2 ", "t0 = 0.25\ncycles = 2 "), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out), "-q", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["t0"] == 0.25 and summary["t_end"] == pytest.approx(2.25, abs=1e-12)
    head, data = _csv(out / "bodies.csv")
    assert data[0, 0] == summary["t0"]
    assert "t0 = 0.25 s, t_end = 2.25 s" in (out / "summary.md").read_text(encoding="utf-8")
