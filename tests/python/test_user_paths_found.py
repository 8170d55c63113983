"""Defects found by walking a user's paths (issue 28 item 2 and the walk of a mechanism of our
own, docs/examples.md): each is a focused test here, and its cell in the user-path matrix
(test_user_paths.py) covers its class."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Output, Study

OMEGA = 5000 * 2 * math.pi / 60  # [rad/s] the slider-crank model's crank


def _dry(clearance: float) -> clearsim.Mechanism:
    return models.slider_crank("dry", clearance=clearance)


@pytest.mark.parametrize("cycles", [0.1, 0.5])
def test_a_window_shorter_than_a_turn_leaves_its_unseen_bins_empty(cycles):
    """clearsim.monte_carlo and Study.fosm over less than a turn: the crank-angle bins the window
    never reaches hold no sample (NaN, as fosm() leaves empty bins), the others are analysed.
    Before: ``InputError: invalid mu_s = nan: must be a number`` (the unseen bins' 0/0 mean
    reached the reliability index), and the per-bin Monte Carlo reliability said R = 1 there."""
    mc = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, omega=OMEGA, cycles=cycles, body="slider",
                              component="x", allowable={"displacement": (0.0, 1e-3)}, progress=False)  # fmt: skip
    bins = mc.bins["displacement"]
    n_seen = int(round(cycles * 360 / 18))
    assert np.all(np.isfinite(bins.reliability[:n_seen])) and np.all(np.isnan(bins.reliability[n_seen:]))
    assert np.all(bins.n_samples[n_seen:] == 0) and np.all(bins.n_samples[:n_seen] == 2)
    assert np.all(np.isfinite(bins.fosm.beta[:n_seen])) and np.all(np.isnan(bins.fosm.beta[n_seen:]))
    assert bins.fosm.min_angle < cycles * 360
    study = Study(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3,
                  omega=OMEGA, cycles=cycles, progress=False)  # fmt: skip
    fosm = study.fosm()
    assert np.all(np.isfinite(fosm.reliability[:n_seen])) and np.all(np.isnan(fosm.reliability[n_seen:]))


def test_simulate_with_ideal_takes_the_options_of_simulate():
    """``progress=False``, which every ``simulate`` call in a script carries, is accepted by
    ``simulate_with_ideal`` too. Before: ``TypeError: Running.run_settings() got an unexpected
    keyword argument 'progress'``."""
    m = _dry(0.5e-3)
    res, ideal = m.simulate_with_ideal(0.002, progress=False, dt_out=1e-4)
    assert res.completed and ideal.completed and len(res.t) == len(ideal.t) == 21
