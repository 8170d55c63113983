"""Studies beyond one machine (issue 41 items 3 and 5): finished chunks are saved to a checkpoint
directory and the same call resumes from it, bit for bit the uninterrupted answer; runs lost to
the machinery (a worker that dies, a cluster that finishes nothing) are a ClusterError naming the
chunks lost, apart from samples whose own run fails; the progress bar moves per finished chunk."""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import Future, ProcessPoolExecutor
from typing import Any, List

import numpy as np
import pytest

import clearsim
from clearsim import progress
from clearsim import reliability as rel
from clearsim.errors import ClusterError


def _build(clearance: float, rod: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="dry", clearance=clearance, rod_length=rod)


def _study(**options: Any) -> rel.Study:
    inputs = {"clearance": rel.Normal(0.5e-3, 0.02e-3), "rod": rel.Normal(0.12, 0.5e-3)}
    return rel.Study(_build, inputs, rel.Output(body="slider", component="x"), rel.Limit(1e-3), cycles=0.25, progress=False, **options)


def _worker_dies(*args: Any) -> None:
    os._exit(3)  # the worker process dies mid-task, as a killed or out-of-memory worker does


class Inline:
    """An executor that runs each task here, counting the samples it ran."""

    def __init__(self) -> None:
        self.samples = 0

    def submit(self, fn: Any, *args: Any) -> "Future[Any]":
        self.samples += len(args[0])
        fut: "Future[Any]" = Future()
        fut.set_result(fn(*args))
        return fut


class Dying(ProcessPoolExecutor):
    """A process pool whose third task kills its worker."""

    def __init__(self) -> None:
        super().__init__(max_workers=2, mp_context=multiprocessing.get_context("fork"))
        self.tasks = 0

    def submit(self, fn: Any, *args: Any, **kwargs: Any) -> "Future[Any]":  # type: ignore[override]
        self.tasks += 1
        return super().submit(_worker_dies if self.tasks == 3 else fn, *args, **kwargs)


class Stalled(Inline):
    """A cluster that finishes the first task and then nothing (a worker hung, no nanny)."""

    def submit(self, fn: Any, *args: Any) -> "Future[Any]":
        return super().submit(fn, *args) if self.samples == 0 else Future()


def _same(a: Any, b: Any) -> None:
    np.testing.assert_array_equal(a.peaks, b.peaks)
    np.testing.assert_array_equal(a.first_passage_times, b.first_passage_times)
    assert (a.pf, a.interval, a.failures) == (b.pf, b.interval, b.failures)


def test_a_run_resumed_after_a_dead_worker_equals_an_uninterrupted_one(tmp_path):
    whole = _study().monte_carlo(12, seed=3)
    with Dying() as pool, pytest.raises(ClusterError) as caught:
        _study(chunk_size=2).monte_carlo(12, seed=3, executor=pool, checkpoint=tmp_path)
    err = caught.value
    n_lost = sum(b - a for a, b, _ in err.lost)
    assert err.lost and "BrokenProcessPool" in err.lost[0][2] and err.checkpoint == str(tmp_path)
    assert err.finished + n_lost == 12 and "the same call resumes" in str(err)
    assert len(list(tmp_path.glob("chunk_*.pkl"))) == err.finished // 2 and not list(tmp_path.glob(".chunk_*"))
    again = Inline()
    resumed = _study(chunk_size=2).monte_carlo(12, seed=3, executor=again, checkpoint=tmp_path)
    assert again.samples == n_lost  # only the lost samples ran again
    _same(resumed, whole)
    other = Inline()
    _study(chunk_size=2).monte_carlo(12, seed=4, executor=other, checkpoint=tmp_path)
    assert other.samples == 12  # other samples: nothing stored is theirs


def test_without_a_checkpoint_the_error_says_how_to_keep_finished_samples():
    with Dying() as pool, pytest.raises(ClusterError, match=r"lost to the executor, not to the mechanism.*checkpoint="):
        _study(chunk_size=2).monte_carlo(8, seed=1, executor=pool)


def test_a_cluster_that_finishes_nothing_times_out_saying_what_finished(tmp_path):
    with pytest.raises(ClusterError, match=r"TimeoutError: no chunk finished in 0.3 s.*2 of the 8 samples so far finished.*resumes") as caught:
        _study(chunk_size=2).monte_carlo(8, seed=1, executor=Stalled(), checkpoint=tmp_path, timeout=0.3)
    assert [(a, b) for a, b, _ in caught.value.lost] == [(2, 4), (4, 6), (6, 8)]
    _same(_study().monte_carlo(8, seed=1, checkpoint=tmp_path), _study().monte_carlo(8, seed=1))


def test_clearsim_monte_carlo_resumes_from_its_checkpoint(tmp_path):
    kwargs = dict(body="slider", component="x", allowable={"displacement": (0.0, 2e-4)}, cycles=0.25, progress=False, seed=2, chunk_size=2)
    build = lambda clearance: _build(clearance, 0.12)  # noqa: E731
    first = clearsim.monte_carlo(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, 6, executor=Inline(), checkpoint=tmp_path, **kwargs)
    again = Inline()
    second = clearsim.monte_carlo(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, 6, executor=again, checkpoint=tmp_path, **kwargs)
    assert again.samples == 0
    np.testing.assert_array_equal(first.peaks["displacement"], second.peaks["displacement"])
    np.testing.assert_array_equal(first.bins["displacement"].reliability, second.bins["displacement"].reliability)


class Updates:
    """A progress bar that records its updates."""

    made: List[List[float]] = []

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self.steps: List[float] = []
        Updates.made.append(self.steps)

    def update(self, n: float = 1) -> None:
        self.steps.append(n)

    def close(self) -> None:
        pass


@pytest.mark.parametrize("executor", [None, "inline"])
def test_the_bar_moves_as_chunks_finish(monkeypatch, executor):
    """Over an executor the bar moved once per 1 024 samples (below that: straight to the end);
    now per finished chunk, locally too."""
    monkeypatch.setattr(progress, "bar", Updates)
    Updates.made = []
    st = _study()
    st.progress = True
    st.monte_carlo(300, seed=0, executor=Inline() if executor else None)
    steps = [s for s in Updates.made if sum(s) == 300]
    assert steps and len(steps[0]) >= 3 and max(steps[0]) < 300, steps


def test_a_dask_cluster_runs_and_resumes_from_a_checkpoint(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    whole = _study().monte_carlo(8, seed=5)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = _study(chunk_size=2).monte_carlo(8, seed=5, executor=client.get_executor(), checkpoint=tmp_path)
    _same(remote, whole)
    assert len(list(tmp_path.glob("chunk_*.pkl"))) == 4
    again = Inline()
    _same(_study().monte_carlo(8, seed=5, executor=again, checkpoint=tmp_path), whole)
    assert again.samples == 0
