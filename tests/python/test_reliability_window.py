"""The analysed window's start-up check (issue 41.8): a study whose peaks sit at the window's
start (the start-up jolt of a run from rest, ``skip_cycles = 0``) warns, naming skip_cycles."""

import warnings

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.errors import ReliabilityWarning
from clearsim.reliability import Normal, Output, Study
from clearsim.reliability.window import at_window_start

CLEARANCES = {"clearance": np.array([0.3e-3, 0.5e-3, 0.7e-3])}


def _study(skip: float) -> Study:
    return Study(lambda clearance: models.slider_crank("lubricated", clearance=clearance), {"clearance": Normal(0.5e-3, 0.05e-3)},
                 Output(body="slider", component="x", quantity="acceleration"), 1e9, skip_cycles=skip, progress=False)  # fmt: skip


def test_peaks_at_the_start_up_jolt_warn_and_name_skip_cycles():
    """skip_cycles = 0 on the lubricated slider-crank: every sample's peak is the jolt at t = 0
    (19 419 m/s², the same whatever the clearance: 0.3, 0.5 and 0.7 mm), and the study says so;
    one turn later the peaks follow the clearance (2 696, 2 885 and 4 924 m/s²) and it is silent."""
    with pytest.warns(ReliabilityWarning, match=r"window's start.*100% of 3.*skip_cycles") as seen:
        early, _ = _study(0.0).run_samples(CLEARANCES)
    assert len([w for w in seen if issubclass(w.category, ReliabilityWarning)]) == 1
    np.testing.assert_allclose(early.peaks, early.peaks[0], rtol=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ReliabilityWarning)
        settled, _ = _study(1.0).run_samples(CLEARANCES)
    assert np.all(np.diff(settled.peaks) > 100.0) and np.all(settled.peaks < 0.3 * early.peaks[0])


def test_a_study_warns_once_and_clearsim_monte_carlo_too():
    """The warning comes once a study (FORM's and Monte Carlo's batches run the same loop), and
    from ``clearsim.monte_carlo``, whose samples run through a study."""
    study = _study(0.0)
    with pytest.warns(ReliabilityWarning, match="skip_cycles"):
        study.monte_carlo(3, seed=1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ReliabilityWarning)
        study.monte_carlo(3, seed=2)
    with pytest.warns(ReliabilityWarning, match="skip_cycles"):
        clearsim.monte_carlo(lambda clearance: models.slider_crank("lubricated", clearance=clearance), {"clearance": Normal(0.5e-3, 0.05e-3)}, 3,
                             body="slider", component="x", allowable={"acceleration": (0.0, 1e9)}, progress=False)  # fmt: skip


def test_a_jolt_is_a_peak_at_the_start_that_stands_out():
    """Within 1 % of the window's length of its start, and twice every later time bin's extreme;
    an error that merely falls through the window (or a window of one bin) is not one."""
    jolt, falling = ([5.0, 2.0, 1.0], [-1.0, -1.0, 0.0]), ([5.0, 4.0, 3.0], [0.0, 0.0, 0.0])
    assert at_window_start(1.0, 1.0, 0.1, *jolt) and at_window_start(1.001, 1.0, 0.1, *jolt)
    assert not at_window_start(1.0011, 1.0, 0.1, *jolt) and not at_window_start(1.05, 1.0, 0.1, *jolt)
    assert not at_window_start(1.0, 1.0, 0.1, *falling) and not at_window_start(1.0, 1.0, 0.1, [5.0], [0.0])
