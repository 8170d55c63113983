"""``clearsim reliability``'s report (clearsim.reliability.report): every row of reliability.csv
carries its runs, wall time and β, and a study whose every sample failed is reported and drawn
with its reasons instead of crashing on a log axis of nothing."""

from __future__ import annotations

import csv
import warnings
from pathlib import Path
from types import SimpleNamespace

import pytest
from scipy import stats

from clearsim.reliability.report import Run
from clearsim.reliability.study import ModeEstimate

COMPRESSOR = Path(__file__).resolve().parents[2] / "scenes" / "compressor.toml"


def test_mode_rows_share_the_system_runs_and_every_row_has_a_beta() -> None:
    study = SimpleNamespace(outputs=["x", "h"], mode_names=["x", "h"])
    r = Run(study, settings=None, n=40, echo=lambda *a, **k: None)
    mc = SimpleNamespace(pf=0.25, interval=(0.13, 0.41), cov=0.27, n_runs=40, wall_time=2.5)
    r.row("monte_carlo", mc)
    r.row("monte_carlo", ModeEstimate("x", 0.1, (0.04, 0.23), 4), mode="x", of=mc)
    r.row("monte_carlo", ModeEstimate("h", 0.0, (0.0, 0.09), 0), mode="h", of=mc)
    system, x, h = r.rows
    assert system["beta"] == pytest.approx(-stats.norm.ppf(0.25), rel=1e-12) and x["beta"] == pytest.approx(-stats.norm.ppf(0.1), rel=1e-12)
    assert h["beta"] == float("inf")
    assert [row["runs"] for row in r.rows] == [40, 40, 40] and [row["wall_time_s"] for row in r.rows] == [2.5, 2.5, 2.5]
    form = SimpleNamespace(pf=0.01, beta=2.3, interval=(0.01, 0.01), n_runs=12, wall_time=1.0)
    r.row("form", form)
    assert r.rows[-1]["beta"] == 2.3  # FORM's own index, not −Φ⁻¹(p_f) = 2.326


def test_every_sample_failed_is_reported_and_drawn_with_its_reasons(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The compressor with a 20-step budget per run: every Monte Carlo run fails. The old code
    stopped with matplotlib's "Data cannot be log-scaled" and wrote no report."""
    from clearsim import plots
    from clearsim.cli import main

    text = COMPRESSOR.read_text(encoding="utf-8").replace("dt_out = 1e-4 ", "max_steps = 20\ndt_out = 1e-4 ", 1)
    assert "max_steps = 20" in text
    scene = tmp_path / "compressor.toml"
    scene.write_text(text, encoding="utf-8")
    drawn = []
    save = plots.save

    def recording_save(fig, path):  # type: ignore[no-untyped-def]
        drawn.extend(t.get_text() for ax in fig.axes for t in ax.texts)
        return save(fig, path)

    monkeypatch.setattr(plots, "save", recording_save)
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no matplotlib warning either
        assert main(["reliability", str(scene), "-o", str(out), "--methods", "monte_carlo", "--samples", "3", "-q"]) == 0
    assert any("no sample succeeded (3 of 3 failed)" in t and "3 × maximum number of steps (20) reached" in t for t in drawn)
    assert (out / "reliability.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "Monte Carlo: 3 of 3 runs failed (counted as exceedances): 3 × maximum number of steps (20) reached" in report
    (row,) = csv.DictReader((out / "reliability.csv").open(encoding="utf-8"))
    assert float(row["pf"]) == 1.0 and float(row["beta"]) == float("-inf") and int(row["runs"]) == 3


def _overlapping_tick_labels(fig) -> list:  # type: ignore[no-untyped-def]
    """Pairs of visible tick labels on one axis of ``fig`` whose drawn boxes overlap."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    found = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            labels = [t for t in axis.get_ticklabels(which="both") if t.get_visible() and t.get_text()]
            boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in labels]
            found += [(a, b) for i, (a, ba) in enumerate(boxes) for b, bb in boxes[i + 1 :] if ba.overlaps(bb)]
    return found


def test_the_study_figure_has_no_overlapping_tick_labels(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The plunger pump's study (walk 6): four inputs named by path (``big-end.clearance``, ...)
    under the FORM and Sobol bars, and p_f estimates within one decade on a log axis. Before, the
    input names ran into each other and matplotlib labelled the minor ticks of the log axis
    (2×10⁻², 3×10⁻², ...) on top of each other."""
    from clearsim import plots
    from clearsim.reliability.report import plot_study

    names = ["big-end.clearance", "wrist-pin.clearance", "big-end.viscosity", "rod"]
    study = SimpleNamespace(output=SimpleNamespace(unit="m"), limit=75e-6, outputs=["plunger.x"])
    est = {"form": SimpleNamespace(pf=0.12, beta=1.18, n_runs=69, importance=dict(zip(names, [0.02, 0.01, 0.0, 0.97]))),
           "importance_sampling": SimpleNamespace(pf=0.114, interval=(0.075, 0.153), n_runs=64),
           "subset": SimpleNamespace(pf=0.135, interval=(0.114, 0.156), n_runs=1000),
           "ak_mcs": SimpleNamespace(pf=0.143, interval=(0.133, 0.154), n_runs=49),
           "ak_is": SimpleNamespace(pf=0.0897, interval=(0.0228, 0.649), n_runs=80),
           "sobol": SimpleNamespace(first=dict(zip(names, [0.05, 0.04, 0.01, 1.0])), total=dict(zip(names, [0.07, 0.03, 0.0, 1.0])), n_runs=600)}  # fmt: skip
    drawn = []
    monkeypatch.setattr(plots, "save", lambda fig, path: drawn.append(fig) or path)
    plot_study(study, est, tmp_path / "reliability.png")
    (fig,) = drawn
    assert _overlapping_tick_labels(fig) == []


def test_a_scenes_samples_size_subset_levels() -> None:
    """``samples`` in a scene's ``[study]`` is subset simulation's runs per level too (the walk's
    pump ran 1 000 a level whatever ``samples`` said, with no key to change it)."""
    from types import SimpleNamespace

    from clearsim.reliability.report import METHOD_RUNNERS, Run

    asked = {}

    def subset(**kw: float) -> SimpleNamespace:
        asked.update(kw)
        return SimpleNamespace(pf=0.1, interval=(0.05, 0.15), cov=0.2, n_runs=3 * kw["n_per_level"], wall_time=1.0)

    study = SimpleNamespace(subset=subset, outputs=["slider.x"], mode_names=["slider.x"])
    run = Run(study=study, settings=SimpleNamespace(seed=0), n=200, echo=lambda *a: None)
    METHOD_RUNNERS["subset"](run)
    assert asked["n_per_level"] == 200 and run.rows[0]["runs"] == 600
