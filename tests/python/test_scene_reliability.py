"""A scene's ``[reliability]`` table is the short form of ``[study] methods = ["fosm"]`` (issue 29:
one reliability table in scenes): its FOSM comes from Study.fosm's step monitors, so it does not
depend on dt_out; a fine output grid and the paper's grid formula (a second method) converge to
it; the hand-written [study] gives the same numbers; short or failed runs say why."""

from __future__ import annotations

import csv
import dataclasses
import json
import math
import re
from pathlib import Path
from typing import Any, Dict, List

import numpy as np
import pytest

from clearsim import reliability as rel
from clearsim.cli import EXIT_ERROR, main
from clearsim.errors import InputError
from clearsim.scene import Scene, load_scene_file
from walks import TOGGLE

SCENES = Path(__file__).resolve().parents[2] / "scenes"
# The dry slider-crank (5000 rpm: a turn is 12 ms), two turns, with the paper's analysis of the slider.
RELIABILITY = """
[reliability]
body = "slider"
component = "x"
bin_width = 18.0
[reliability.allowable]
displacement = [0.0, 1.0e-3]      # m
velocity = [0.0, 2.0]             # m/s
acceleration = [0.0, 5000.0]      # m/s²
"""
STUDY = """
[study]
body = "slider"
component = "x"
quantity = "QUANTITY"
limit = LIMIT
cycles = 2.0
methods = ["fosm"]
bin_width = 18.0
[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3                     # the scene's clearance: the nominal mechanism is the scene's
std = 0.05e-3
"""
FIELDS = ("bin_starts", "count", "mu_s", "sigma_s", "beta", "reliability")


def _scene(tmp_path: Path, extra: str = RELIABILITY, name: str = "scene.toml", simulation: str = "") -> Scene:
    text = (SCENES / "slider_crank.toml").read_text(encoding="utf-8")
    if simulation:
        text = text.replace("[simulation]\n", "[simulation]\n" + simulation + "\n")
    path = tmp_path / name
    path.write_text(text + extra, encoding="utf-8")
    return load_scene_file(path)


def _with(scene: Scene, **changes: Any) -> Scene:
    return dataclasses.replace(scene, simulation=dataclasses.replace(scene.simulation, **changes))


def _period(scene: Scene) -> float:
    assert scene.reliability is not None
    return 2 * math.pi / abs(scene.reliability.omega)


def _grid_fosm(run: Any, quantity: str) -> Any:
    """The paper's formula on the stored output grid (what [reliability] computed before issue 29)."""
    spec = run.scene.reliability
    error = run.errors[(spec.body, quantity)][:, 0]
    t = run.result.t[: len(error)]
    angle = np.degrees(abs(spec.omega) * (t - run.scene.simulation.t0))
    return rel.fosm(error, angle, spec.allowable[quantity], bin_width=spec.bin_width)


def _same(a: Any, b: Any) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True) for f in FIELDS) and (a.mu_S, a.sigma_S) == (b.mu_S, b.sigma_S)


def test_reliability_does_not_depend_on_dt_out(tmp_path):
    """(a) The same numbers, bit for bit, on two output grids; the grid formula (the code before)
    differs between them by more than 1e-3 in β here, so this test fails on it."""
    scene = _scene(tmp_path)
    period = _period(scene)
    coarse, fine = _with(scene, dt_out=period / 90).run(), _with(scene, dt_out=period / 720).run()
    assert set(coarse.reliability) == {"displacement", "velocity", "acceleration"}
    for q in coarse.reliability:
        assert _same(coarse.reliability[q], fine.reliability[q]), q
    grid_change = max(np.nanmax(np.abs(_grid_fosm(coarse, q).beta - _grid_fosm(fine, q).beta)) for q in coarse.reliability)
    assert grid_change > 1e-3  # the old answer moved with dt_out


def test_a_fine_output_grid_converges_to_the_monitored_fosm(tmp_path):
    """(b) A second method: the paper's formula on the stored grid, per bin, approaches the
    monitors' time averages as the grid is refined: within 1 % of the largest bin mean and 0.02
    in β at 36 000 points a turn, closer than at 360 (measured figures: docs/physics.md §6; the
    rest is the monitor's quadrature over rk45's long free-flight steps: h_max = T/720 shrinks
    it to ≤ 0.35 %, |Δβ| ≤ 0.002)."""
    scene = _scene(tmp_path)
    period = _period(scene)
    runs = {n: _with(scene, dt_out=period / n).run() for n in (360, 36000)}
    for q, monitored in runs[36000].reliability.items():
        scale = float(np.max(monitored.mu_s))
        gap = {}
        for n, run in runs.items():
            grid = _grid_fosm(run, q)
            assert np.array_equal(grid.bin_starts, monitored.bin_starts)
            gap[n] = max(np.max(np.abs(grid.mu_s - monitored.mu_s)), np.max(np.abs(grid.sigma_s - monitored.sigma_s))) / scale
            if n == 36000:
                assert gap[n] < 1e-2, (q, gap[n])
                assert np.max(np.abs(grid.beta - monitored.beta)) < 0.02, q
                assert grid.min_angle == monitored.min_angle and grid.min_reliability == pytest.approx(monitored.min_reliability, abs=1e-3)
        assert gap[36000] < gap[360], (q, gap)


def test_reliability_is_the_hand_written_study(tmp_path):
    """(c) [reliability] and the [study] with methods = ["fosm"] it stands for give identical
    numbers (one output per quantity, limit = the allowable's upper end); the alias's settings
    are that study's."""
    from clearsim.scene.alias import alias_study

    scene = _scene(tmp_path)
    run = scene.run()
    settings = alias_study(scene.reliability, scene.simulation)
    assert settings.methods == ["fosm"] and settings.inputs == {} and settings.cycles == pytest.approx(2.0) and settings.skip_cycles == 0.0
    assert [o.quantity for o in settings.outputs] == list(run.reliability) and [lim.value for lim in settings.limits] == [1e-3, 2.0, 5000.0]
    for q, limit in (("displacement", "1.0e-3"), ("acceleration", "5000.0")):
        written = _scene(tmp_path, STUDY.replace("QUANTITY", q).replace("LIMIT", limit), name=f"{q}.toml")
        assert written.reliability is None and written.study is not None
        assert _same(written.study_model(progress=False).fosm(), run.reliability[q]), q


def test_fosm_takes_an_allowable_range(tmp_path):
    """Study.fosm against [Δv, Δu]: μ_S = (Δu + Δv)/2, σ_S = (Δu − Δv)/6 (P31–P32) and
    β = (μ_S − μ_s)/√(σ_S² + σ_s²) (P30) per bin, from the same monitored μ_s, σ_s."""
    scene = _scene(tmp_path, RELIABILITY.replace("displacement = [0.0, 1.0e-3]", "displacement = [2.0e-4, 1.0e-3]"))
    run = scene.run()
    ranged = run.reliability["displacement"]
    assert (ranged.mu_S, ranged.sigma_S) == pytest.approx((6e-4, 8e-4 / 6), rel=1e-15)
    beta = (ranged.mu_S - ranged.mu_s) / np.sqrt(ranged.sigma_S**2 + ranged.sigma_s**2)
    np.testing.assert_allclose(ranged.beta, beta, rtol=1e-14)
    study = _scene(tmp_path, STUDY.replace("QUANTITY", "displacement").replace("LIMIT", "1.0e-3"), name="s.toml").study_model(progress=False)
    zero_based = study.fosm()
    np.testing.assert_array_equal(zero_based.mu_s, ranged.mu_s)  # the range moves S, not s
    assert (zero_based.mu_S, zero_based.sigma_S) == pytest.approx((5e-4, 1e-3 / 6), rel=1e-15)  # the default [0, limit]
    with pytest.raises(InputError, match="allowable"):
        study.fosm(allowable=(1e-3, 1e-4))


def test_a_run_shorter_than_a_turn_says_so(tmp_path, capsys):
    """No NaN bins and no traceback: the run is made and kept, the FOSM is not, and the run says why."""
    scene = _scene(tmp_path).with_overrides(t_end=0.5 * _period(_scene(tmp_path)))
    run = scene.run()
    assert run.failure is None and run.result.completed and run.reliability == {}
    assert run.reliability_failure is not None and "whole crank turn" in run.reliability_failure and "t_end" in run.reliability_failure
    out = tmp_path / "out"
    assert main(["run", str(tmp_path / "scene.toml"), "-o", str(out), "--t-end", "0.006", "--no-plots"]) == 0
    printed = capsys.readouterr().out
    assert "[reliability]: FOSM not computed" in printed and "whole crank turn" in printed
    summary: Dict[str, Any] = json.loads((out / "summary.json").read_text())
    assert "reliability" not in summary and "whole crank turn" in summary["reliability_failure"]
    assert "whole crank turn" in (out / "summary.md").read_text() and not list(out.glob("reliability_*.csv"))


def test_a_failed_run_gives_no_fosm_and_says_why(tmp_path):
    scene = _scene(tmp_path, simulation="max_steps = 200")
    run = scene.run()
    assert run.failure is not None and run.reliability == {}
    assert run.reliability_failure is not None and run.reliability_failure.startswith("FOSM not computed: the run failed")


def test_a_scene_may_hold_both_tables(tmp_path):
    """[reliability] (clearsim run) and [study] (clearsim reliability) are read independently:
    neither changes the other's numbers."""
    both = _scene(tmp_path, RELIABILITY + STUDY.replace("QUANTITY", "velocity").replace("LIMIT", "2.0"))
    alone = _scene(tmp_path, name="alone.toml")
    assert both.reliability == alone.reliability and both.study is not None and both.study.outputs[0].quantity == "velocity"
    a, b = both.run().reliability, alone.run().reliability
    assert all(_same(a[q], b[q]) for q in a)
    assert _same(both.study_model(progress=False).fosm(), a["velocity"])


@pytest.mark.parametrize("integrator", ["rk45", "radau"])
def test_one_monitored_run_gives_every_quantity_bit_for_bit(tmp_path, monkeypatch, integrator):
    """[reliability] makes one monitored run for all its quantities (it made one each), and each
    quantity's numbers are, bit for bit, those of Study.fosm run for that quantity alone (the
    monitors do not steer the step: explicit rk45 and implicit radau, whose acceleration monitor
    shares the KKT workspace with the integrator)."""
    from clearsim.reliability.study import Study
    from clearsim.scene.alias import alias_study
    from clearsim.scene.study import study_of

    scene = _scene(tmp_path).with_overrides(integrator=integrator)
    calls: List[int] = []
    original = Study.run_samples

    def counted(self: Any, points: Any, **kwargs: Any) -> Any:
        calls.append(len(self.outputs))
        return original(self, points, **kwargs)

    monkeypatch.setattr(Study, "run_samples", counted)
    run = scene.run()
    assert calls == [3]  # one run, monitoring three quantities
    monkeypatch.setattr(Study, "run_samples", original)
    settings = alias_study(scene.reliability, scene.simulation)
    study = study_of(settings, scene.mechanism, scene.simulation, progress=False)
    assert settings.allowable is not None
    for i, output in enumerate(settings.outputs):
        alone = study.fosm(output=i, allowable=settings.allowable[i])
        assert _same(alone, run.reliability[output.quantity]), (integrator, output.quantity)
    two = study.fosm_all(outputs=[2, 0], allowable=[None, settings.allowable[0]])
    assert _same(two[1], run.reliability["displacement"]) and two[0].mu_S == 2500.0  # its own range: (0, limit)
    with pytest.raises(InputError, match="ranges"):
        study.fosm_all(outputs=[0, 1], allowable=[None])


def _fosm_rows(path: Path) -> Dict[str, np.ndarray]:
    rows = list(csv.reader(path.open(encoding="utf-8")))
    assert rows[0] == ["output", "error_unit", "bin_start [deg]", "mu_s_error_unit", "sigma_s_error_unit", "beta", "reliability"]
    names = sorted({r[0] for r in rows[1:]}, key=[r[0] for r in rows[1:]].index)
    return {name: np.array([[float(x) for x in r[2:]] for r in rows[1:] if r[0] == name]) for name in names}


def test_clearsim_reliability_runs_the_alias(tmp_path, capsys):
    """An alias behaves as what it aliases: ``clearsim reliability`` on a scene with only
    [reliability] runs its study (FOSM per quantity of the nominal mechanism) and prints and
    writes the numbers ``clearsim run`` gives; methods that need random inputs say so."""
    _scene(tmp_path)
    path = str(tmp_path / "scene.toml")
    assert main(["run", path, "-o", str(tmp_path / "run"), "--no-plots"]) == 0
    printed_run = capsys.readouterr().out
    out = tmp_path / "rel"
    assert main(["reliability", path, "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())["reliability"]["minimum"]
    written = _fosm_rows(out / "fosm.csv")
    assert list(written) == ["slider.x.displacement", "slider.x.velocity", "slider.x.acceleration"]
    for q in ("displacement", "velocity", "acceleration"):
        shown = re.search(rf"FOSM {q}: min R = ([0-9.]+) \(β = ([-0-9.]+)\) at ([0-9.]+)°", printed_run)
        assert shown is not None
        assert f"slider.x.{q}: min R = {shown[1]} (β = {shown[2]}) at {shown[3]}°" in printed, q
        rows = list(csv.reader((tmp_path / "run" / f"reliability_{q}.csv").open(encoding="utf-8")))
        by_run = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0])}
        table = written[f"slider.x.{q}"]  # bin_start, mu_s, sigma_s, beta, reliability: full precision
        unit = {"displacement": "m", "velocity": "m/s", "acceleration": "m/s^2"}[q]
        for k, name in enumerate(("bin_start [deg]", f"mu_s [{unit}]", f"sigma_s [{unit}]", "beta", "reliability")):
            np.testing.assert_array_equal(table[:, k], by_run[name], err_msg=f"{q} {name}")
        assert table[:, 4].min() == summary[q]["reliability"]
    report = (out / "report.md").read_text()
    assert "no [study]" not in printed and "none: `[reliability]`" in report and (out / "reliability.png").stat().st_size > 0
    assert main(["reliability", path, "-o", str(tmp_path / "mc"), "--methods", "monte_carlo"]) == EXIT_ERROR
    assert "[[study.input]]" in capsys.readouterr().err


def test_bins_are_crank_angles_when_the_window_starts_mid_turn(tmp_path):
    """t_start half a turn in (7 bins and a bit: moved up to the 8th bin edge, 144°): the bins
    still hold crank angles |ω| (t − t0), as the paper's formula on a fine grid from that edge
    finds them (Study.fosm folded them from the window's start before, 144° off)."""
    scene = _scene(tmp_path, RELIABILITY.replace('bin_width = 18.0', 'bin_width = 18.0\nt_start = 0.0047'))
    period = _period(scene)
    run = _with(scene, dt_out=period / 36000).run()
    start = 8 * period / 20
    assert _alias_start(scene) == pytest.approx(start, rel=1e-12)
    for q, monitored in run.reliability.items():
        error = run.errors[("slider", q)][:, 0]
        t = run.result.t[: len(error)]
        keep = t >= start - 1e-12
        grid = rel.fosm(error[keep], np.degrees(abs(scene.reliability.omega) * t[keep]), scene.reliability.allowable[q], bin_width=18.0)
        assert np.max(np.abs(grid.mu_s - monitored.mu_s)) < 1e-2 * np.max(monitored.mu_s), q


def _alias_start(scene: Scene) -> float:
    from clearsim.scene.alias import alias_study

    settings = alias_study(scene.reliability, scene.simulation)
    return settings.skip_cycles * _period(scene)


def test_a_series_study_states_that_every_output_must_hold():
    """The repr of a study of several outputs (a series system: it fails when any passes its
    limit) states what holds when it is safe: each output within its limit, joined by "and".
    Before: "film thickness of joint A ≥ 5e-07 m or y displacement error ≤ 0.0005 m"."""
    from clearsim.scene.study import scene_study
    from clearsim.scene import load_scene_file

    text = repr(scene_study(load_scene_file(TOGGLE), progress=False))
    assert "film thickness of joint A ≥ 5e-07 m and y displacement error of ram ≤ 0.0005 m" in text and " or " not in text
