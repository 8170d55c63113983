"""clearsim.batch, the one batch runner: runs started on threads (clearsim.batch.start) give the
results of Mechanism.simulate bit for bit (a second route into the same core), in the order
given; a run that stops is kept with its partial result and the reason (counted, not dropped)."""

from __future__ import annotations

import numpy as np
import pytest

from clearsim import batch, models
from clearsim.errors import InputError, SimulationError


def _mechanisms():
    return [models.slider_crank("dry", rpm=3000.0), models.slider_crank("lubricated", rpm=3000.0), models.slider_crank("ideal", rpm=3000.0)]


def test_started_runs_equal_simulate_bit_for_bit_in_order():
    mechs = _mechanisms()
    settings = [m.run_settings(0.02, dt_out=1e-4) for m in mechs]
    with batch.start([m.description() for m in mechs], settings, threads=2) as started:
        raws = started.results(False, "test", ["dry", "lubricated", "ideal"])
    for mech, s, raw in zip(mechs, settings, raws):
        res, failure = batch.finish(mech, raw, s)
        assert failure is None
        ref = mech.simulate(0.02, dt_out=1e-4, progress=False)
        assert res.stats["integrator"] == ref.stats["integrator"]
        arrays = [k for k, v in ref._raw.items() if isinstance(v, np.ndarray)]
        assert {"t", "q", "qd", "qdd"} <= set(arrays)
        for name in arrays:  # every stored channel, bit for bit
            assert np.array_equal(res._raw[name], ref._raw[name], equal_nan=True), name
        assert res.stats["steps"] == ref.stats["steps"] and res.stats["rejected_steps"] == ref.stats["rejected_steps"]


def test_a_stopped_run_is_kept_with_its_reason():
    mechs = _mechanisms()
    settings = [m.run_settings(0.02, dt_out=1e-4, max_steps=20 if k == 0 else 50_000_000) for k, m in enumerate(mechs)]
    raws = batch.start([m.description() for m in mechs], settings).results(False, "test")
    assert len(raws) == 3 and batch.failed(raws[0]) and not batch.failed(raws[1])
    res, failure = batch.finish(mechs[0], raws[0], settings[0])
    assert isinstance(failure, SimulationError) and "maximum number of steps" in str(failure)
    assert failure.result is res and 0 < len(res.t) < 201  # what it computed (of the 201 outputs asked for), kept
    assert float(res.stats["t_reached"]) < 0.02


def test_settings_must_match_descriptions():
    m = models.slider_crank("ideal")
    with pytest.raises(InputError) as info:
        batch.start([m.description()], [])
    assert info.value.field == "settings"
