"""Monte Carlo reliability runner: parallel batches in Rust, and through a Dask executor."""

import math

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Output, Study, Uniform

OMEGA = 5000 * 2 * math.pi / 60  # [rad/s] the slider-crank model's crank


def _dry(clearance: float) -> clearsim.Mechanism:
    return models.slider_crank("dry", clearance=clearance)


def build(clearance, omega):
    return models.slider_crank("dry", clearance=clearance, rpm=omega * 60 / (2 * math.pi), journal_radius=10e-3 - clearance)


DISTS = {"clearance": Uniform(0.2e-3, 0.5e-3), "omega": Normal(5000 * 2 * math.pi / 60, 10.0)}
ALLOW = {"displacement": (0.0, 2e-4), "velocity": (0.0, 0.5), "acceleration": (0.0, 5000.0)}


def test_monte_carlo_runs_and_reports_intervals():
    mc = clearsim.monte_carlo(build, DISTS, 8, omega="omega", body="slider", component="x", allowable=ALLOW, progress=False, seed=1, keep_errors=True)
    assert mc.ok.all() and not mc.failures
    assert mc.errors["acceleration"].shape == (8, 361)
    for q in ("displacement", "velocity", "acceleration"):
        fp = mc.first_passage[q]
        assert 0.0 <= fp.lo <= fp.p <= fp.hi <= 1.0
        b = mc.bins[q]
        assert np.all((b.lo <= b.reliability) & (b.reliability <= b.hi))
    # Larger clearance → larger peak displacement error, sample by sample (a physical trend).
    peak = np.max(np.abs(mc.errors["displacement"]), axis=1)
    c = mc.inputs["clearance"][mc.ok]
    assert np.corrcoef(c, peak)[0, 1] > 0.5
    assert mc.table("acceleration")


def test_monte_carlo_with_dask_executor_matches_local_batch():
    distributed = pytest.importorskip("dask.distributed")
    local = clearsim.monte_carlo(build, DISTS, 4, omega="omega", body="slider", component="x", allowable=ALLOW, progress=False, seed=3, keep_errors=True)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = clearsim.monte_carlo(
                build, DISTS, 4, omega="omega", body="slider", component="x", allowable=ALLOW, progress=False, seed=3,
                executor=client.get_executor(), chunk_size=2, keep_errors=True,
            )
    for q in local.errors:
        np.testing.assert_array_equal(local.errors[q], remote.errors[q])


def test_bad_omega_name_is_an_input_error():
    with pytest.raises(clearsim.InputError, match="omega"):
        clearsim.monte_carlo(build, {"clearance": 0.3e-3}, 2, omega="speed", body="slider", component="x", allowable=ALLOW, progress=False)


@pytest.mark.parametrize(
    "kwargs, field, message",
    [
        ({"component": "x", "allowable": ALLOW}, "body", "missing body"),
        ({"body": "slider", "allowable": ALLOW}, "component", "no default"),
        ({"body": "slider", "component": "x"}, "allowable", "missing allowable"),
        ({"body": "slider", "component": "theta", "allowable": {"velocity": (0, 1.0)}, "quantities": ["displacement"]}, "allowable.displacement", r"\[rad\]"),
        ({"body": "slider", "component": "x", "allowable": ALLOW, "on_failure": "ignore"}, "on_failure", "fail, exclude, raise"),
        ({"body": "slider", "component": "x", "allowable": {"displacement": (2e-4, 0.0)}}, "allowable.displacement", r"lower < upper \[m\]"),
        ({"body": "slider", "component": "x", "allowable": {"displacement": 2e-4}}, "allowable.displacement", "give \\(lower, upper\\)"),
        ({"body": "slider", "component": "x", "allowable": {"displacement": (0.0, 1e-4, 2e-4)}}, "allowable.displacement", "lower < upper"),
    ],
)
def test_limits_and_output_are_explicit(kwargs, field, message):
    """No default body, axis or limit: a missing one is an InputError naming it (a theta
    output asks for its limit in rad)."""
    with pytest.raises(clearsim.InputError, match=message) as info:
        clearsim.monte_carlo(build, {"clearance": 0.3e-3, "omega": 500.0}, 2, omega="omega", progress=False, **kwargs)
    assert info.value.field == field


def test_pooled_fosm_is_the_time_average_of_a_dense_grid():
    """The monitor's FOSM moments (∫|e|dt/∫dt per bin) against sample moments of the errors on
    a dense stored grid (a second method): they agree to the grid's quadrature error."""
    dists = {"clearance": Uniform(0.3e-3, 0.5e-3), "omega": 5000 * 2 * math.pi / 60}
    mc = clearsim.monte_carlo(build, dists, 4, omega="omega", body="slider", component="x", allowable={"displacement": (0.0, 2e-4)},
                              progress=False, seed=3, bin_width=36.0, points_per_cycle=7200, keep_errors=True)  # fmt: skip
    e = np.abs(mc.errors["displacement"])[:, :-1]  # drop the window's end point (it opens no segment)
    per_bin = e.reshape(e.shape[0], 10, -1)
    np.testing.assert_allclose(mc.bins["displacement"].fosm.mu_s, per_bin.mean(axis=(0, 2)), rtol=2e-3)
    np.testing.assert_allclose(mc.bins["displacement"].fosm.sigma_s, per_bin.std(axis=(0, 2)), rtol=2e-2)


def _locking(clearance, omega):
    """Samples with clearance above 0.4 mm get a rod shorter than the crank: the mechanism locks
    up within the first turn, so those runs fail; the others are the usual slider-crank."""
    rod = 0.03 if clearance > 0.4e-3 else 0.12
    return models.slider_crank("dry", clearance=clearance, rpm=omega * 60 / (2 * math.pi), journal_radius=10e-3 - clearance, rod_length=rod)


def test_failed_samples_are_counted_with_their_reason():
    """Failed samples are kept with their reason; with on_failure='fail' each counts as an
    exceedance, with 'exclude' the estimate is over the completed ones and bounded both ways,
    with 'raise' the first failure is raised naming the sample."""
    # A completed sample takes < 1 000 steps; a locked one would run on with its journal many
    # clearances deep: the step budget stops it.
    common = dict(omega="omega", body="slider", component="x", allowable={"displacement": (0.0, 1.0)}, progress=False, seed=2, max_steps=20_000)
    n = 12
    mc = clearsim.monte_carlo(_locking, DISTS, n, **common)
    locked = mc.inputs["clearance"] > 0.4e-3
    assert 0 < locked.sum() < n
    np.testing.assert_array_equal(~mc.ok, locked)
    assert mc.n_failed == int(locked.sum()) and sorted(k for k, _ in mc.failures) == list(np.flatnonzero(locked))
    assert all(reason for _, reason in mc.failures) and sum(mc.failure_reasons().values()) == mc.n_failed
    # A 1 m limit is never reached by a completed sample: every exceedance is a failed sample.
    fp = mc.first_passage["displacement"]
    assert fp.p == pytest.approx(mc.n_failed / n)
    assert np.nanmax(mc.bins["displacement"].reliability) == pytest.approx(1 - mc.n_failed / n)
    excluded = clearsim.monte_carlo(_locking, DISTS, n, on_failure="exclude", **common)
    assert excluded.first_passage["displacement"].p == 0.0
    assert excluded.pf_bounds["displacement"] == pytest.approx((0.0, mc.n_failed / n))
    with pytest.raises(clearsim.SimulationError, match=r"Monte Carlo sample \d+ \(clearance="):
        clearsim.monte_carlo(_locking, DISTS, n, on_failure="raise", **common)


def test_a_step_budget_fails_samples_with_that_reason():
    common = dict(omega="omega", body="slider", component="x", allowable={"displacement": (0.0, 1.0)}, progress=False, seed=2)
    with pytest.raises(clearsim.SimulationError, match=r"no Monte Carlo sample completed \(4 failed\).*maximum number of steps \(40\)"):
        clearsim.monte_carlo(build, DISTS, 4, max_steps=40, **common)


def test_a_stalled_sample_is_stopped_by_its_wall_time_budget():
    m = models.slider_crank("dry", clearance=0.5e-3)
    with pytest.raises(clearsim.SimulationError, match="wall-time budget") as info:
        m.simulate(10.0, rtol=1e-12, atol=1e-15, dt_out=1e-3, max_seconds=0.2, progress=False)
    partial = info.value.result
    assert 0.0 < partial.t[-1] < 10.0  # what was computed is kept



def test_answers_do_not_depend_on_the_output_density():
    """The first-passage probability and per-bin reliability come from the integrator's every
    step: the same with 36 or 3 600 stored points per cycle, while the stored grid alone misses
    peaks between its samples (issue: 0.81 vs 1.00)."""
    dists = {"clearance": Uniform(0.3e-3, 0.5e-3), "omega": 5000 * 2 * math.pi / 60}
    allow = {"acceleration": (0.0, 2.8e5)}  # m/s²: within the range of the impact peaks
    common = dict(omega="omega", body="slider", component="x", allowable=allow, progress=False, seed=4, bin_width=36.0, keep_errors=True)
    coarse = clearsim.monte_carlo(build, dists, 8, points_per_cycle=36, **common)
    fine = clearsim.monte_carlo(build, dists, 8, points_per_cycle=3600, **common)
    np.testing.assert_allclose(coarse.peaks["acceleration"], fine.peaks["acceleration"], rtol=1e-6)
    assert coarse.first_passage["acceleration"] == fine.first_passage["acceleration"]
    np.testing.assert_array_equal(coarse.bins["acceleration"].reliability, fine.bins["acceleration"].reliability)
    # FOSM from time-averaged moments: the same to round-off, not within "1 %".
    np.testing.assert_allclose(coarse.bins["acceleration"].fosm.mu_s, fine.bins["acceleration"].fosm.mu_s, rtol=1e-9)
    np.testing.assert_allclose(coarse.bins["acceleration"].fosm.reliability, fine.bins["acceleration"].fosm.reliability, rtol=1e-9)
    # The monitor sees at least what any stored grid sees (up to the reference's interpolation).
    grid_peak = np.abs(fine.errors["acceleration"]).max(axis=1)
    assert np.all(fine.peaks["acceleration"] >= grid_peak * (1 - 1e-4))
    coarse_grid_peak = np.abs(coarse.errors["acceleration"]).max(axis=1)
    assert np.all(coarse_grid_peak < 0.9 * coarse.peaks["acceleration"]), "36 points a cycle miss the impact peaks"
    # The limit lies inside the range of peaks: the probability is informative, and the one the
    # coarse grid alone would give is wrong.
    p = coarse.first_passage["acceleration"].p
    assert 0 < p < 1
    assert (coarse_grid_peak > 2.8e5).mean() < p


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


def test_monte_carlo_without_omega_takes_the_driver_speed_as_study_does():
    """``clearsim.monte_carlo`` without ``omega`` (and no input named omega) takes the nominal
    mechanism's constant-speed driver's, as ``Study`` does: the same bins as ``omega=OMEGA``.
    Before: ``invalid omega = 'omega': not a sampled input`` for an omega never given."""
    kwargs = dict(body="slider", component="x", allowable={"displacement": (0.0, 1e-3)}, cycles=0.25, progress=False)
    mc = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, **kwargs)
    given = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, omega=OMEGA, **kwargs)
    np.testing.assert_array_equal(mc.bins["displacement"].reliability, given.bins["displacement"].reliability)
    for q in mc.peaks:
        np.testing.assert_array_equal(mc.peaks[q], given.peaks[q])


def test_error_traces_are_kept_only_when_asked():
    """``clearsim.monte_carlo`` kept every sample's full run (~213 KB a sample on the nine-bar:
    709 MB at n = 2 048); now it keeps the error rows of the samples ``keep_errors`` asks for
    (none by default) and every estimate is the same whatever it keeps (from the monitors)."""
    common = dict(omega="omega", body="slider", component="x", allowable=ALLOW, progress=False, seed=5)
    none = clearsim.monte_carlo(build, DISTS, 6, **common)
    some = clearsim.monte_carlo(build, DISTS, 6, keep_errors=2, **common)
    every = clearsim.monte_carlo(build, DISTS, 6, keep_errors=True, **common)
    assert none.errors["velocity"].shape == (0, 361) and none.crank_angle.shape == (0, 361) and none.error_samples.size == 0
    assert some.errors["velocity"].shape == (2, 361) and list(some.error_samples) == [0, 1]
    assert every.errors["velocity"].shape == (6, 361) and list(every.error_samples) == list(range(6))
    np.testing.assert_array_equal(some.errors["acceleration"], every.errors["acceleration"][:2])
    # The stored rows are the run minus its ideal twin on the same grid (a second computation).
    m = build(float(every.inputs["clearance"][3]), float(every.inputs["omega"][3]))
    t = every.crank_angle[3] / math.degrees(abs(float(every.inputs["omega"][3])))
    res, ideal = m.simulate_with_ideal(float(t[-1]), t_out=t)
    np.testing.assert_allclose(every.errors["displacement"][3], res.error(ideal, "slider", "displacement")[:, 0], atol=2e-7)  # 0.1 % of the 0.2 mm limit: step control
    for q in ALLOW:
        np.testing.assert_allclose(none.peaks[q], every.peaks[q], rtol=1e-9)
        assert none.first_passage[q] == every.first_passage[q]
        np.testing.assert_array_equal(none.bins[q].reliability, every.bins[q].reliability)
        np.testing.assert_allclose(none.bins[q].fosm.mu_s, every.bins[q].fosm.mu_s, rtol=1e-9)
    with pytest.raises(clearsim.InputError, match="keep_errors"):
        clearsim.monte_carlo(build, DISTS, 2, keep_errors=-1, **common)


def test_monte_carlo_of_a_point_on_a_body():
    """``point=`` names the output as ``Output(body=, point=, component=)`` does. At the rod's
    centroid (0, 0) the point's numbers are the rod's own coordinate's (a point monitor against a
    coordinate monitor); at the rod's crank end (−l/2, 0) they vanish: that point is the crank pin,
    whose motion the ideal crank joint and the constant-speed driver fix exactly in both runs
    (rigid-body kinematics), while the rod's centroid moves off its ideal path."""
    allow = {"displacement": (0.0, 1e-4)}
    kw = dict(omega="omega", allowable=allow, progress=False, seed=2, keep_errors=True)
    body = clearsim.monte_carlo(build, DISTS, 3, body="rod", component="x", **kw)
    centre = clearsim.monte_carlo(build, DISTS, 3, body="rod", component="x", point=(0.0, 0.0), **kw)
    np.testing.assert_array_equal(centre.peaks["displacement"], body.peaks["displacement"])
    np.testing.assert_array_equal(centre.bins["displacement"].reliability, body.bins["displacement"].reliability)
    np.testing.assert_allclose(centre.errors["displacement"], body.errors["displacement"], rtol=0, atol=1e-15)
    pin = clearsim.monte_carlo(build, DISTS, 3, body="rod", component="magnitude", point=(-0.06, 0.0), **kw)
    assert np.max(body.peaks["displacement"]) > 1e-5
    # zero to the constraints' drift (~4e-9 m at the default tolerances), 1e-4 of the centroid's error
    assert np.max(pin.peaks["displacement"]) < 1e-8 and np.max(np.abs(pin.errors["displacement"])) < 1e-8
    with pytest.raises(clearsim.InputError, match="component.*magnitude"):
        clearsim.monte_carlo(build, DISTS, 2, body="rod", component="theta", point=(0.0, 0.0), **kw)
