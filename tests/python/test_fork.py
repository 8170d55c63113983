"""A fork-based process pool after an in-core batch must not hang (issue: rayon's global pool
has no threads in a forked child; every batch now builds and drops its own pool)."""

from __future__ import annotations

import multiprocessing as mp
import sys
from concurrent.futures import ProcessPoolExecutor

import pytest

import clearsim

pytestmark = pytest.mark.skipif(sys.platform == "win32" or "fork" not in mp.get_all_start_methods(), reason="needs fork")


def _peak_error(clearance: float) -> float:
    m = clearsim.models.slider_crank("dry", clearance=clearance)
    res, ideal = m.simulate_with_ideal(0.002, dt_out=1e-4)  # an in-core batch of 2
    return float(abs(res.error(ideal, "slider", "displacement")[:, 0]).max())


def test_fork_pool_after_an_in_core_batch_finishes():
    here = _peak_error(0.5e-3)  # the parent runs a parallel batch first
    pool = ProcessPoolExecutor(max_workers=2, mp_context=mp.get_context("fork"))
    try:
        futures = [pool.submit(_peak_error, c) for c in (0.5e-3, 0.3e-3)]
        # On the old code the children waited forever on the parent's rayon pool: fail, not hang.
        results = [f.result(timeout=60) for f in futures]
    finally:
        for proc in list(getattr(pool, "_processes", {}).values()):
            proc.kill()
        pool.shutdown(wait=False, cancel_futures=True)
    assert results[0] == pytest.approx(here, rel=1e-12)
    assert all(r > 0 for r in results)
