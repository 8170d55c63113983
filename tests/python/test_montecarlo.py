"""Monte Carlo reliability runner: parallel batches in Rust, and through a Dask executor."""

import math

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Uniform


def build(clearance, omega):
    return models.slider_crank("dry", clearance=clearance, rpm=omega * 60 / (2 * math.pi), journal_radius=10e-3 - clearance)


DISTS = {"clearance": Uniform(0.2e-3, 0.5e-3), "omega": Normal(5000 * 2 * math.pi / 60, 10.0)}
ALLOW = {"displacement": (0.0, 2e-4), "velocity": (0.0, 0.5), "acceleration": (0.0, 5000.0)}


def test_monte_carlo_runs_and_reports_intervals():
    mc = clearsim.monte_carlo(build, DISTS, 8, omega="omega", body="slider", axis="x", allowable=ALLOW, progress=False, seed=1)
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
    local = clearsim.monte_carlo(build, DISTS, 4, omega="omega", body="slider", axis="x", allowable=ALLOW, progress=False, seed=3)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = clearsim.monte_carlo(
                build, DISTS, 4, omega="omega", body="slider", axis="x", allowable=ALLOW, progress=False, seed=3,
                executor=client.get_executor(), chunk_size=2,
            )
    for q in local.errors:
        np.testing.assert_array_equal(local.errors[q], remote.errors[q])


def test_bad_omega_name_is_an_input_error():
    with pytest.raises(clearsim.InputError, match="omega"):
        clearsim.monte_carlo(build, {"clearance": 0.3e-3}, 2, omega="speed", progress=False)
