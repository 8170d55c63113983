"""The clearsim command line with mixed joint kinds and with failures after some files are
written (issue 28 item 3): what finished is written and summarised, the cause is one line on
stderr (the traceback only with --debug), the exit code is not zero."""

from __future__ import annotations

import json
import sys
import types
import warnings
from pathlib import Path

import pytest

from clearsim import plots
from clearsim.cli import main

EXIT_FAILURE = 1  # clearsim.cli.EXIT_FAILURE

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def test_run_with_a_lubricated_and_a_dry_joint_in_the_outputs(tmp_path, capsys):
    # scenes/compressor.toml lists its lubricated crank pin and its dry wrist pin in [outputs];
    # on the old code the orbit figure raised KeyError: 'wrist-pin (dry)' after the CSVs.
    out = tmp_path / "out"
    assert main(["run", str(SCENES / "compressor.toml"), "-o", str(out), "--t-end", "0.01", "-q"]) == 0
    assert capsys.readouterr().err == ""
    assert (out / "orbits.png").stat().st_size > 10_000
    summary = json.loads((out / "summary.json").read_text())
    assert "orbits.png" in summary["files"] and "not_written" not in summary
    header = (out / "joints.csv").read_text().splitlines()[0]
    assert "crank-pin.eps [1]" in header and "wrist-pin.eps [1]" in header


def _broken(*args, **kwargs):
    raise ValueError("a figure that cannot be drawn")


def test_a_failed_figure_leaves_the_other_outputs_and_the_summary(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(plots, "plot_journal_orbits", _broken)
    out = tmp_path / "out"
    code = main(["run", str(SCENES / "slider_crank.toml"), "-o", str(out), "--t-end", "0.004", "-q"])
    assert code == EXIT_FAILURE
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "Traceback" not in err
    assert "orbits.png" in err and "ValueError: a figure that cannot be drawn" in err and str(out) in err
    for name in ("bodies.csv", "joints.csv", "slider_x.png", "slider_x_error.png", "summary.json"):
        assert (out / name).is_file(), name
    assert not (out / "orbits.png").exists()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["not_written"] == {"orbits.png": "ValueError: a figure that cannot be drawn"}
    assert "orbits.png" not in summary["files"] and summary["run"]["t_reached"] == pytest.approx(0.004)
    assert "Not written" in (out / "summary.md").read_text() and "a figure that cannot be drawn" in (out / "summary.md").read_text()


def test_debug_prints_the_traceback(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(plots, "plot_journal_orbits", _broken)
    out = tmp_path / "out"
    assert main(["run", str(SCENES / "slider_crank.toml"), "-o", str(out), "--t-end", "0.002", "-q", "--debug"]) == EXIT_FAILURE
    err = capsys.readouterr().err
    assert "Traceback" in err and "_broken" in err and (out / "summary.md").is_file()


def test_a_failed_animation_leaves_the_figures_and_the_summary(tmp_path, capsys, monkeypatch):
    from clearsim.result import Result

    monkeypatch.setattr(Result, "animate", _broken)
    out = tmp_path / "out"
    code = main(["run", str(SCENES / "slider_crank.toml"), "-o", str(out), "--t-end", "0.002", "-q", "--animate", str(out / "run.gif")])
    assert code == EXIT_FAILURE
    assert "run.gif" in capsys.readouterr().err
    summary = json.loads((out / "summary.json").read_text())
    assert "run.gif" in summary["not_written"] and "orbits.png" in summary["files"]


def _fake_module(monkeypatch, name: str, **functions) -> None:
    module = types.ModuleType(name)
    for key, fn in functions.items():
        setattr(module, key, fn)
    monkeypatch.setitem(sys.modules, name, module)


def test_reliability_failure_after_some_files(tmp_path, capsys, monkeypatch):
    def run_study(scene, out_dir, **kwargs):
        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "reliability.csv").write_text("method,pf\nform,0.01\n")
        raise RuntimeError("the importance sampling broke")

    _fake_module(monkeypatch, "clearsim.reliability.report", run_study=run_study)
    out = tmp_path / "rel"
    code = main(["reliability", str(SCENES / "nine_bar_reliability.toml"), "-o", str(out), "-q"])
    assert code == EXIT_FAILURE
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "Traceback" not in err and "RuntimeError: the importance sampling broke" in err
    report = (out / "report.md").read_text()
    assert "stopped early" in report and "the importance sampling broke" in report and "`reliability.csv`" in report


def test_paper_failure_after_some_files(tmp_path, capsys, monkeypatch):
    def run_paper_study(out_dir, **kwargs):
        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "fig08_errors_clearance.png").write_bytes(b"png")
        raise KeyError("lub-c0.3-5pi")

    _fake_module(monkeypatch, "clearsim.paper", run_paper_study=run_paper_study)
    out = tmp_path / "paper"
    assert main(["paper", "-o", str(out), "-q"]) == EXIT_FAILURE
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "KeyError: 'lub-c0.3-5pi'" in err
    report = (out / "report.md").read_text()
    assert "clearsim paper stopped early" in report and "`fig08_errors_clearance.png`" in report


def test_a_clearsim_error_keeps_exit_code_2_and_one_line(tmp_path, capsys, monkeypatch):
    from clearsim.errors import SimulationError

    def run_study(scene, out_dir, **kwargs):
        raise SimulationError("step size underflow at t = 0.01 s")

    _fake_module(monkeypatch, "clearsim.reliability.report", run_study=run_study)
    out = tmp_path / "rel"
    out.mkdir()
    assert main(["reliability", str(SCENES / "nine_bar_reliability.toml"), "-o", str(out), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "clearsim: error: step size underflow at t = 0.01 s"
    assert "step size underflow" in (out / "report.md").read_text()


def test_a_scene_error_comes_after_the_unit_slip_that_caused_it(tmp_path, capsys):
    """The compressor's crank pin given as ``journal_radius = 10`` (mm as m): the finite film's
    L/D = 0.0006 stops the scene, and the warning that names the real cause (a journal radius of
    the order of the mechanism: mm?) is printed before that error. Before: the warning, caught
    while the file was read, was dropped with the error, which advises another film model."""
    from pathlib import Path

    from clearsim.cli import main

    text = (Path(__file__).resolve().parents[2] / "scenes" / "compressor.toml").read_text(encoding="utf-8")
    assert text.count("journal_radius = 10e-3 ") == 1
    path = tmp_path / "mm.toml"
    path.write_text(text.replace("journal_radius = 10e-3 ", "journal_radius = 10 "), encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # conftest makes a PlausibilityWarning an error
        assert main(["run", str(path), "-o", str(tmp_path / "out"), "-q", "--no-plots"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    mm = next(k for k, line in enumerate(lines) if "journal_radius = 10 m" in line and "did you give mm?" in line)
    assert lines[mm].startswith(f"clearsim: warning: {path}:") and lines[-1].startswith("clearsim: error: ") and mm < len(lines) - 1
    assert "L/D" in lines[-1]
