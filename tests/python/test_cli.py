"""The clearsim command line (clearsim.cli), run in-process on the shipped scenes."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim.cli import main

from walks import SHAPER, TOGGLE, WIPER, pump_scene as _pump_scene, read_csv as _csv

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _header(path: Path) -> list:
    return path.read_text(encoding="utf-8").splitlines()[0].split(",")


def test_run_nine_bar(tmp_path, capsys):
    out = tmp_path / "nb"
    assert main(["run", str(SCENES / "nine_bar.toml"), "-o", str(out), "--t-end", "0.4", "-q"]) == 0  # [reliability]: a crank turn
    for name in ("bodies.csv", "bodies_ideal.csv", "errors.csv", "joints.csv", "reliability_velocity.csv", "summary.json", "summary.md"):
        assert (out / name).is_file(), name
    for name in ("slider9_y.png", "slider9_y_error.png", "orbits.png", "reliability.png"):
        assert (out / name).stat().st_size > 10_000, name
    assert _header(out / "bodies.csv") == ["t [s]", "slider9.position.y [m]", "slider9.velocity.y [m/s]", "slider9.acceleration.y [m/s^2]"]
    assert _header(out / "errors.csv")[1:] == [
        "slider9.displacement_error.y [m]",
        "slider9.velocity_error.y [m/s]",
        "slider9.acceleration_error.y [m/s^2]",
    ]
    assert _header(out / "joints.csv")[:6] == ["t [s]", "A.ex [m]", "A.ey [m]", "A.eps [1]", "A.fx [N]", "A.fy [N]"]
    assert len((out / "bodies.csv").read_text().splitlines()) == 1 + 2001  # header + 0.4 s / 2e-4 s + 1
    summary = json.loads((out / "summary.json").read_text())
    assert summary["run"]["t_reached"] == pytest.approx(0.4) and summary["run"]["failure"] is None
    assert set(summary["run"]["impacts"]) == {"A", "B"}
    assert summary["run"]["max_constraint_violation"] < 1e-6
    minimum = summary["reliability"]["minimum"]
    assert set(minimum) == {"displacement", "velocity", "acceleration"}
    assert all(0.0 < m["reliability"] <= 1.0 for m in minimum.values())
    assert "FOSM" in (out / "summary.md").read_text()
    assert capsys.readouterr().out == ""  # -q


def test_run_slider_crank_without_plots(tmp_path, capsys):
    out = tmp_path / "sc"
    assert main(["run", str(SCENES / "slider_crank.toml"), "-o", str(out), "--t-end", "0.002", "--no-plots", "--integrator", "dop853"]) == 0
    assert not list(out.glob("*.png"))
    assert _header(out / "joints.csv") == [
        "t [s]", "rod-slider.ex [m]", "rod-slider.ey [m]", "rod-slider.eps [1]", "rod-slider.fx [N]", "rod-slider.fy [N]",
        "rod-slider.normal [N]", "rod-slider.tangential [N]",
    ]  # fmt: skip
    summary = json.loads((out / "summary.json").read_text())
    assert summary["integrator"] == "dop853" and "reliability" not in summary
    assert "wrote" in capsys.readouterr().out


def test_bad_scene_exit_code_and_message(tmp_path, capsys):
    text = (SCENES / "slider_crank.toml").read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("journal_radius = 9.5e-3", "journal_radius_ = 9.5e-3"))
    line = bad.read_text().splitlines().index("journal_radius_ = 9.5e-3               # m") + 1
    assert main(["run", str(bad), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "Traceback" not in err
    assert f"{bad}:{line}:" in err and "journal_radius_" in err


def test_simulation_failure_writes_partial_results(tmp_path, capsys):
    text = (SCENES / "slider_crank.toml").read_text().replace('integrator = "auto"', 'integrator = "rk45"\nmax_steps = 300  #')
    scene = tmp_path / "short.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out), "--no-plots", "-q"]) == 2
    err = capsys.readouterr().err
    assert "simulation failed" in err and "maximum number of steps" in err and "partial results" in err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["run"]["failure"] and 0 < summary["run"]["t_reached"] < 0.024
    assert (out / "bodies.csv").is_file() and (out / "errors.csv").is_file()


def test_info_and_version(capsys):
    assert main(["info"]) == 0
    out = capsys.readouterr().out
    assert clearsim.__version__ in out and "nine_bar" in out and "slider_crank" in out and "rk45" in out
    assert "``" not in out and ":class:" not in out, "reST markup leaks into the terminal"
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0 and clearsim.__version__ in capsys.readouterr().out


def test_no_command_is_a_usage_error(capsys):
    assert main([]) == 2
    assert "usage" in capsys.readouterr().err


def test_paper_calls_the_study(tmp_path, monkeypatch, capsys):
    calls = []

    def run_paper_study(out_dir, cycles=3, quick=False, progress=True, film="long", compare_films=True):
        calls.append((out_dir, cycles, quick, progress, film, compare_films))
        return out_dir

    fake = types.ModuleType("clearsim.paper")
    fake.run_paper_study = run_paper_study  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "clearsim.paper", fake)
    assert main(["paper", "-o", str(tmp_path), "--quick", "--cycles", "2", "-q"]) == 0
    assert calls == [(tmp_path, 2, True, False, "long", True)]
    assert main(["paper", "-q", "--film", "finite", "--no-film-comparison"]) == 0
    assert calls[-1] == (Path("clearsim-paper"), 3, False, False, "finite", False)


def test_python_dash_m():
    done = subprocess.run([sys.executable, "-m", "clearsim", "--version"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == f"clearsim {clearsim.__version__}"


@pytest.mark.parametrize("scene, t_end, joint, clearance", [(TOGGLE, 0.1, "A", 40e-6), (SHAPER, 0.0667, "A", 30e-6)])
def test_walked_scenes_run_and_study_from_the_cli(tmp_path, scene, t_end, joint, clearance):
    """The walks' own mechanisms (a toggle press, a shaper's quick return; each a lubricated and a
    dry pin) through ``clearsim run`` (a short --t-end, figures on) and ``clearsim reliability``
    (2 Monte Carlo samples of their [study], skip_cycles = 1). The joints CSV's film thickness is
    c − |e| at every sample, and its power loss is at least the Couette shear's |T| ω_rel."""
    import json

    from clearsim.cli import main

    out = tmp_path / "run"
    assert main(["run", str(scene), "-o", str(out), "-q", "--t-end", str(t_end)]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["run"]["t_reached"] == pytest.approx(t_end) and summary["run"]["failure"] is None
    assert 0 < summary["run"]["bearings"][joint]["min_film_thickness"] < clearance
    head, data = _csv(out / "joints.csv")
    col = {h: k for k, h in enumerate(head)}
    if f"{joint}.film_thickness [m]" in col:
        e = np.hypot(data[:, col[f"{joint}.ex [m]"]], data[:, col[f"{joint}.ey [m]"]])
        assert np.allclose(data[:, col[f"{joint}.film_thickness [m]"]], clearance - e, rtol=0.0, atol=1e-15)
        assert np.all(data[:, col[f"{joint}.power_loss [W]"]] >= 0.0)
    assert (out / "orbits.png").stat().st_size > 0 and (out / "summary.md").read_text(encoding="utf-8").count("| A |") == 1
    rel = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(rel), "-q", "--methods", "monte_carlo", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(np.isfinite(samples[:, head.index("A.film_thickness [m]")]))
    assert "| monte_carlo | system |" in (rel / "report.md").read_text(encoding="utf-8")


def test_the_pump_runs_studies_and_animates_from_the_cli(tmp_path, capsys):
    """The walking-beam pump (a Watt-type six-bar with a plunger; a lubricated short-bearing crank
    pin and a dry, worn saddle bearing) through ``clearsim run`` over its first turn and a bit
    with ``--animate`` (a turn is 24 frames: the 50-frame floor) and ``clearsim reliability``
    (2 Monte Carlo samples and FOSM of its [study], skip_cycles = 1). The film thickness in
    joints.csv is c − |e|; [reliability]'s FOSM printed by ``run`` does not change with dt_out."""
    import json
    import re

    from PIL import Image

    from clearsim.cli import main

    scene = _pump_scene(tmp_path, '["monte_carlo", "fosm"]')
    printed = {}
    for dt_out in ("1e-3", "4e-3"):
        path = tmp_path / f"pump_{dt_out}.toml"
        path.write_text(scene.read_text(encoding="utf-8").replace("dt_out = 1e-3 ", f"dt_out = {dt_out} "), encoding="utf-8")
        out = tmp_path / f"run_{dt_out}"
        args = ["run", str(path), "-o", str(out), "--no-plots"] + (["--animate", str(out / "run.gif")] if dt_out == "1e-3" else [])
        assert main(args) == 0
        printed[dt_out] = re.findall(r"FOSM \w+: min R = .*", capsys.readouterr().out)
    assert len(printed["1e-3"]) == 3 and printed["1e-3"] == printed["4e-3"]
    out = tmp_path / "run_1e-3"
    with Image.open(out / "run.gif") as gif:
        assert gif.n_frames == 50
    head, _ = _csv(out / "reliability_acceleration.csv")  # name [unit], as every clearsim CSV file (was angle_deg, mu_s, ...)
    assert head == ["cycle", "bin_start [deg]", "bin_centre [deg]", "samples", "mu_s [m/s^2]", "sigma_s [m/s^2]", "mu_S [m/s^2]", "sigma_S [m/s^2]", "beta", "reliability"]
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["run"]["failure"] is None and 0 < summary["run"]["bearings"]["A"]["min_film_thickness"] < 30e-6
    head, data = _csv(out / "joints.csv")
    col = {h: k for k, h in enumerate(head)}
    e = np.hypot(data[:, col["A.ex [m]"]], data[:, col["A.ey [m]"]])
    assert np.allclose(data[:, col["A.film_thickness [m]"]], 30e-6 - e, rtol=0.0, atol=1e-15)
    rel = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(rel), "-q", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(np.isfinite(samples[:, head.index("A.film_thickness [m]")]))
    report = (rel / "report.md").read_text(encoding="utf-8")
    assert "| monte_carlo | system |" in report and "FOSM `plunger.y.displacement`" in report


def test_the_wiper_runs_and_studies_from_the_cli(tmp_path, capsys):
    """The windscreen-wiper four-bar (walk 4: a crank-rocker with a lubricated crank pin A and a
    dry rocker pin B) through ``clearsim run`` and ``clearsim reliability``. The "auto" integrator
    resolves to radau (a lubricated joint), named beside its setting in summary.json; [reliability]'s
    FOSM printed by ``run`` is the same whatever dt_out and t0 (its crank angle is |ω| t from
    t = 0); the rocker's angle error is bounded by the play: the pin B can sit c_A + c_B off the
    ideal, which turns the 50 mm rocker by at most (c_A + c_B)/(r sin μ) (μ ≥ 30°, the
    transmission angle), and by more than nothing."""
    import json

    from clearsim.cli import main

    text = WIPER.read_text(encoding="utf-8")
    printed = {}
    for label, edit in (("base", text), ("dt_out", text.replace("dt_out = 2e-3 ", "dt_out = 5e-4 ")),
                        ("t0", text.replace("cycles = 2 ", "t0 = 0.25\ncycles = 2 "))):  # fmt: skip
        assert edit != text or label == "base"
        path = tmp_path / f"wiper_{label}.toml"
        path.write_text(edit, encoding="utf-8")
        out = tmp_path / f"run_{label}"
        assert main(["run", str(path), "-o", str(out), "--no-plots"]) == 0
        printed[label] = re.findall(r"FOSM \w+: min R = [0-9.]+ \(β = [-0-9.]+\) at (\d+)°", capsys.readouterr().out)
    assert len(printed["base"]) == 3 and printed["base"] == printed["dt_out"] == printed["t0"]
    summary = json.loads((tmp_path / "run_base" / "summary.json").read_text(encoding="utf-8"))
    assert summary["integrator"] == "radau" and summary["integrator_setting"] == "auto"
    assert summary["run"]["failure"] is None and 0 < summary["run"]["bearings"]["A"]["min_film_thickness"] < 20e-6
    head, data = _csv(tmp_path / "run_base" / "errors.csv")
    peak = np.max(np.abs(data[:, head.index("rocker.displacement_error.theta [rad]")]))
    assert 0.0 < peak < (20e-6 + 0.1e-3) / (0.05 * math.sin(math.radians(30)))
    rel = tmp_path / "rel"
    assert main(["reliability", str(WIPER), "-o", str(rel), "-q", "--methods", "monte_carlo,fosm", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(samples[:, head.index("peak [rad]")] < 5e-3)
    report = (rel / "report.md").read_text(encoding="utf-8")
    assert "monte_carlo" in report and "FOSM" in report
