"""Crank-angle bins do not depend on the start time (docs/physics.md §6): every per-bin
reliability answer bins the crank angle |ω| t modulo 360° with t from t = 0 (the given pose's
time), whatever the run's start t0 or the turns a study skips, and a window opens on a bin edge
of that angle. Before: bins counted |ω| (t − t0) (a scene's ``[simulation] t0 = T/4`` moved the
pump's min R from 252° to 162°), ``clearsim.monte_carlo`` folded its time bins from the window's
start, and a window opening inside a bin (skip_cycles = 0.26) mixed two bins."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Output, Study
from clearsim.scene import load_scene_file
from clearsim.scene.alias import scene_fosm

OMEGA = 5000 * 2 * math.pi / 60  # [rad/s] the slider-crank model's crank
TURN = 2 * math.pi / OMEGA  # [s]
PUMP = Path(__file__).resolve().parents[1] / "data" / "scenes" / "beam_pump.toml"


def _force_study(skip_cycles: float, t0: float = 0.0) -> Study:
    """FOSM of the lubricated slider-crank's pin force (near a pure function of crank angle once
    the film has settled), a run from ``t0``."""
    study = Study(lambda c: models.slider_crank("lubricated", clearance=c), {"c": 0.5e-3}, Output(joint="rod-slider", quantity="force"), 1e4,
                  cycles=1.0, skip_cycles=skip_cycles, progress=False)  # fmt: skip
    if t0:
        study.run_options["t0"] = t0  # as a scene's [simulation] t0 sets it
    return study


def test_the_pump_scene_reports_the_same_bins_from_any_t0(tmp_path):
    """The walking-beam pump's ``[reliability]`` over the window [0.5, 1.0] s, once run from
    t0 = 0 and once from t0 = T/4 = 0.125 s: the same crank-angle bins (min R of the plunger's
    displacement error at 252° both times; per-bin R of every quantity within 2e-3, the
    difference the start-up transients leave). Before: 252° and 162°, the bins rolled by 90°."""
    text = PUMP.read_text(encoding="utf-8")
    text = text[: text.index("\n[study]")]
    results = []
    for t0 in (0.0, 0.125):
        path = tmp_path / f"pump_{t0}.toml"
        path.write_text(text.replace("cycles = 2                            # × 0.5 s", f"t0 = {t0}\nt_end = 1.0"), encoding="utf-8")
        scene = load_scene_file(path)
        results.append(scene_fosm(scene.reliability, scene.mechanism, scene.simulation))
    from_0, from_quarter = results
    assert from_0["displacement"].min_angle == from_quarter["displacement"].min_angle == 252.0
    for q in from_0:
        np.testing.assert_array_equal(from_0[q].bin_starts, from_quarter[q].bin_starts)
        np.testing.assert_allclose(from_quarter[q].reliability, from_0[q].reliability, rtol=0.0, atol=2e-3, err_msg=q)


def test_a_study_run_from_t0_bins_the_angle_from_t_0():
    """The lubricated slider-crank's pin force over its second turn [T, 2T], run from t0 = 0 and
    from t0 = T/4 (and the window [1.25 T, 2.25 T] from T/4): per-bin μ_s within 1 % (the
    film's start-up differs) and the same min-R bin. Before: the run from T/4 put each value 90°
    (5 bins) later."""
    base = _force_study(1.0).fosm()
    for skip in (1.0, 1.25):
        late = _force_study(skip, t0=TURN / 4).fosm()
        np.testing.assert_array_equal(late.bin_starts, base.bin_starts)
        np.testing.assert_allclose(late.mu_s, base.mu_s, rtol=1e-2, err_msg=f"skip_cycles = {skip}")
        assert late.min_angle == base.min_angle


@pytest.mark.parametrize("skip", [0.25, 0.26])
def test_skipped_turns_do_not_move_the_bins(skip):
    """A Study with skip_cycles = 0.25 or 0.26 (a window that would open inside the 90° bin)
    against skip_cycles = 0: the bins 108°…342° the two windows share in the same first turn
    (the same run up to the step the output grid cuts) agree within 1e-3 of μ_s. Before, with
    0.26, every monitor time bin straddled two crank-angle bins (1 % off)."""
    base = _force_study(0.0).fosm()
    late = _force_study(skip).fosm()
    shared = slice(6, None)
    np.testing.assert_allclose(late.mu_s[shared], base.mu_s[shared], rtol=1e-3)
    np.testing.assert_allclose(late.sigma_s[shared], base.sigma_s[shared], rtol=1e-2, atol=1e-3 * float(np.max(base.mu_s)))


def test_monte_carlo_bins_count_the_angle_from_t_0():
    """``clearsim.monte_carlo`` (MonteCarloBins, its per-bin FOSM from the monitors) over [T, 2T]
    and over [1.25 T, 2.25 T]: the bins 90°…342° both windows take from the same turn agree within
    5e-3 of μ_s (2e-3 at 90°, where the later window's grid cuts a step), and the stored crank angles start at |ω| t = 360° and 450°. Before: both folded
    their first time bin onto 0° and the crank angles started at 0."""
    kwargs = dict(body="slider", component="x", allowable={"displacement": (0.0, 1e-3)}, cycles=1.0, progress=False, omega=OMEGA, keep_errors=True)
    build = lambda clearance: models.slider_crank("lubricated", clearance=clearance)  # noqa: E731
    runs = {skip: clearsim.monte_carlo(build, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, skip_cycles=skip, **kwargs) for skip in (1.0, 1.25)}
    assert runs[1.0].crank_angle[0, 0] == pytest.approx(360.0) and runs[1.25].crank_angle[0, 0] == pytest.approx(450.0)
    a, b = runs[1.0].bins["displacement"], runs[1.25].bins["displacement"]
    np.testing.assert_array_equal(a.bin_starts, b.bin_starts)
    shared = slice(5, None)
    np.testing.assert_allclose(b.fosm.mu_s[shared], a.fosm.mu_s[shared], rtol=5e-3)


def test_bin_fold_follows_the_absolute_crank_angle():
    """A window of 18° bins after 0.26 turns opens at 0.3 turns (0.25: at 0.25). Monitor time bins from a window opening at 0.25 turns with 18° bins are crank-angle bins
    5, 6, …, 19, 0, 1 (edges of |ω| t); with 25° bins (not dividing 360°, 15 bins, the last
    10° wide) the bin each time bin starts in: 0°, 25°, …, 350°, then 15° (bin 0), 40° (bin 1)."""
    from clearsim.reliability.fosm import bin_fold, window_start_turns

    assert window_start_turns(0.26, 18.0) == pytest.approx(0.3) and window_start_turns(0.25, 18.0) == 0.25
    np.testing.assert_array_equal(bin_fold(0.25, 18.0, 17), np.r_[np.arange(5, 20), 0, 1])
    np.testing.assert_array_equal(bin_fold(0.0, 25.0, 17), np.r_[np.arange(15), 0, 1])
