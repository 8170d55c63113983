"""Smaller defects the walking-beam pump's user-path walk found (tests/data/scenes/beam_pump.toml):
each test says what it printed before."""

from __future__ import annotations

from pathlib import Path

import pytest

import clearsim

PUMP = Path(__file__).resolve().parents[1] / "data" / "scenes" / "beam_pump.toml"


def test_a_dry_joint_is_not_a_bearing_with_a_film():
    """The pump (lubricated crank pin A, dry saddle O4) run with ``extremes=True, bearings=True``: the bearing
    summary, the summary and the repr list A only, whose film is positive; O4's gap minimum (its
    penetration, negative) stays in ``extremes``. Before: ``bearings`` listed O4 with
    ``min_film_thickness`` −9.0 µm and the repr printed "O4: h_min -9.01 µm"."""
    m = clearsim.load_scene(PUMP)
    res = m.simulate(0.05, dt_out=1e-3, extremes=True, bearings=True, progress=False)
    assert list(res.bearing_summary()) == ["A"] and list(res.summary()["bearings"]) == ["A"]
    assert res.bearing_summary()["A"]["min_film_thickness"] > 0.0
    assert "O4: h_min" not in repr(res) and "A: h_min" in repr(res)
    assert res.extremes("O4", "film_thickness").min < 0.0  # the penetration, under its own name


def test_the_reliability_report_says_fosm_skipped_the_film_output(tmp_path, capsys):
    """``clearsim reliability`` on the pump's series [study] (the plunger's error and the crank
    pin's film thickness, a lower limit) with ``--methods fosm``: FOSM analyses the error and
    says, on stdout and in report.md, that it skipped ``A.film_thickness`` and why. Before: the
    film output vanished from the FOSM results without a word."""
    from clearsim.cli import main

    text = PUMP.read_text(encoding="utf-8")
    scene = tmp_path / "pump.toml"
    scene.write_text(text[: text.index("\n[study.life]")], encoding="utf-8")
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "--methods", "fosm", "--no-plots"]) == 0
    said = capsys.readouterr().out
    assert "fosm                 skips A.film_thickness (film thickness of joint A ≥ 5e-06 m): FOSM compares an error" in said
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "FOSM skipped `A.film_thickness` (film thickness of joint A ≥ 5e-06 m): FOSM compares an error with an allowable range [0, limit]" in report
    assert "FOSM `plunger.y.displacement` (nominal mechanism, 18° bins" in report


def test_plot_mechanism_outside_the_run_echoes_the_time_given():
    """``res.plot_mechanism(t)`` at a t outside the run (or NaN) is an InputError that names the
    t given and the run's span. Before: ``invalid t: the run covers [0, 0.05] s`` (which t?), and
    NaN drew a figure of NaN positions."""
    res = clearsim.load_scene(PUMP).simulate(0.05, dt_out=1e-3, progress=False)
    with pytest.raises(clearsim.InputError, match=r"invalid t = 0\.7 s: outside the run, which covers \[0, 0\.05\] s") as info:
        res.plot_mechanism(0.7)
    assert info.value.value == 0.7
    with pytest.raises(clearsim.InputError, match=r"invalid t = -0\.01 s: outside the run"):
        res.plot_mechanism(-0.01)
    with pytest.raises(clearsim.InputError, match=r"invalid t = nan: must be a finite time"):
        res.plot_mechanism(float("nan"))
