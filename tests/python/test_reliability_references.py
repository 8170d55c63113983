"""Every Study sample is measured against its own reference, however many distinct references a
batch holds (issue 36, item 1: a Monte Carlo run with more distinct ideal mechanisms than the
Python cache's 256 measured its first samples against none, their "error" being the slider's
position itself). The core's batch now makes the references (rust/batch.rs: each distinct one
run on first use, dropped after its last sample); a monitor without its reference cannot be built."""

from __future__ import annotations

import numpy as np
import pytest

import clearsim
from clearsim import reliability as rel
from clearsim.schema import ATOL, RTOL


def _slider_crank(rpm: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="dry", rpm=rpm)


def _study(cycles: float = 1.0) -> rel.Study:
    # A random crank speed gives every sample its own ideal mechanism.
    return rel.Study(_slider_crank, {"rpm": rel.Normal(5000.0, 50.0)}, rel.Output(body="slider", component="x", quantity="displacement"),
                     rel.Limit(1e-3), cycles=cycles, progress=False)  # fmt: skip


@pytest.mark.parametrize("threads", [1, 2])
def test_more_distinct_references_than_the_cache_agree_with_the_samples_run_one_by_one(threads):
    # One core batch of 20 samples with 20 distinct references, on one thread and on two.
    study = _study(cycles=0.5)
    study.threads = threads
    points = {"rpm": np.linspace(4900.0, 5100.0, 20)}
    together, _ = study.evaluate(points)
    alone = np.array([_study(cycles=0.5).evaluate({"rpm": [v]})[0].peaks[0] for v in points["rpm"]])
    np.testing.assert_allclose(together.peaks, alone, rtol=1e-12)
    # The error against the ideal slider stays within the joint's play (0.5 mm) and some dynamics:
    # the slider's position itself (≈ 0.17 m) would be far above.
    assert np.all(together.peaks < 2e-3)


def test_a_thousand_distinct_references_through_monte_carlo():
    # The shipped cache (256) with 1 000 distinct ideal mechanisms, as the user met it, against
    # the same samples run one by one (a tenth of them, spread over the whole chunk).
    study = _study(cycles=0.25)
    mc = study.monte_carlo(1000, seed=1)
    assert mc.failures == []
    assert np.all(mc.peaks < 2e-3), f"samples measured against no reference: {np.flatnonzero(mc.peaks >= 2e-3)[:10]}"
    picks = np.arange(0, 1000, 97)
    alone = np.array([_study(cycles=0.25).evaluate({"rpm": [mc.inputs["rpm"][k]]})[0].peaks[0] for k in picks])
    np.testing.assert_allclose(mc.peaks[picks], alone, rtol=1e-12)
    assert mc.pf == 0.0


def test_traces_past_the_cache_carry_their_own_ideal():
    study = _study(cycles=0.25)
    ev, traces = study.run_samples({"rpm": [4950.0, 5000.0, 5050.0, 5100.0]}, keep_traces=4, raw_traces=True)
    assert all(isinstance(tr["ideal"], dict) for tr in traces)
    for tr, rpm in zip(traces, [4950.0, 5000.0, 5050.0, 5100.0]):
        # The ideal slider at the end of the window is the closed form of that sample's speed.
        ideal = tr["ideal"]
        theta = rpm * 2 * np.pi / 60.0 * ideal["t"][-1]
        r, l = 0.05, 0.12
        x = r * np.cos(theta) + np.sqrt(l**2 - (r * np.sin(theta)) ** 2)
        col = tr["columns"][0]
        assert ideal["q"][-1, col] == pytest.approx(x, abs=1e-6)
        # A second method: the ideal twin run on its own, at the reference's tolerances (a tenth
        # of the study's) with the trace's output times: the reference at those times is that run.
        twin = _slider_crank(rpm).idealized().simulate(float(ideal["t"][-1]), t_out=ideal["t"], rtol=RTOL / 10, atol=ATOL / 10, progress=False)
        np.testing.assert_allclose(ideal["q"], twin._raw["q"], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(ideal["qd"], twin._raw["qd"], rtol=1e-12, atol=1e-12)
