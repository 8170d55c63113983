"""A study through an executor ships descriptions and settings, never a reference (issue 41
items 1–2): each worker's batch runs the reference itself (rust/batch.rs), one core thread a
task unless told otherwise, and the answers are those of the in-process run bit for bit."""

from __future__ import annotations

import pickle
from typing import Any, List

import numpy as np
import pytest

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError


def _build(clearance: float, rod: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="dry", clearance=clearance, rod_length=rod)


def _study(**options: Any) -> rel.Study:
    inputs = {"clearance": rel.Normal(0.5e-3, 0.02e-3), "rod": rel.Normal(0.12, 0.5e-3)}
    return rel.Study(_build, inputs, rel.Output(body="slider", component="x"), rel.Limit(1e-3), cycles=0.25, progress=False, **options)


class Recorder:
    """An executor that runs each task here and keeps its arguments."""

    def __init__(self) -> None:
        self.calls: List[tuple] = []

    def map(self, fn: Any, *iterables: Any) -> Any:
        for args in zip(*iterables):
            self.calls.append(args)
            yield fn(*args)


@pytest.mark.parametrize("reference", ["own_ideal", "nominal"])
def test_a_task_carries_descriptions_and_settings_only(reference):
    rec = Recorder()
    local = _study(reference=reference).monte_carlo(24, seed=2)
    shipped = _study(reference=reference).monte_carlo(24, seed=2, executor=rec)
    np.testing.assert_array_equal(local.peaks, shipped.peaks)
    samples = sum(len(args[0]) for args in rec.calls)
    per_sample = sum(len(pickle.dumps(args)) for args in rec.calls) / samples
    # A description and its settings: about 1 kB (a shipped reference was ~113 kB a sample).
    assert per_sample < 4e3, per_sample
    for descriptions, settings, threads, nominal in rec.calls:
        assert threads == 1  # one core thread a task under an executor
        assert all(isinstance(v, (int, float, str, bool, list, dict, type(None), np.ndarray)) for s in settings for v in s.values())
        assert all(np.asarray(s["t_out"]).size == 2 for s in settings)  # no reference grid shipped as times
        assert (nominal is None) == (reference == "own_ideal")


def test_threads_per_task_are_the_users_to_give():
    rec = Recorder()
    _study(threads=2).monte_carlo(4, seed=0, executor=rec)
    assert {args[2] for args in rec.calls} == {2}
    for bad in (-1, 1.5, True):
        with pytest.raises(InputError, match="threads"):
            _study(threads=bad)


def test_a_dask_cluster_of_processes_gives_the_local_answers():
    distributed = pytest.importorskip("dask.distributed")
    local = _study(reference="nominal").monte_carlo(8, seed=4)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = _study(reference="nominal", chunk_size=2).monte_carlo(8, seed=4, executor=client.get_executor())
    np.testing.assert_array_equal(local.peaks, remote.peaks)
    assert remote.failures == []
