"""The clearsim command line (clearsim.cli), run in-process on the shipped scenes."""

from __future__ import annotations

import json
import subprocess
import sys
import types
from pathlib import Path

import pytest

import clearsim
from clearsim.cli import main

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
