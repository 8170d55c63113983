"""A study on a Dask cluster whose workers are killed, resumed from its checkpoint (issue 41.3).

    python benches/cluster_resume.py [n]

The dry slider-crank study of ``benches/study_overhead.py`` (clearance N(0.5 mm, 0.02 mm), one
crank cycle), ``n`` samples (default 1 024) on a Dask ``LocalCluster`` (2 workers × 1 thread, a
worker that dies kills its tasks: ``allowed-failures`` 0) with ``checkpoint=``: once a third of
the samples has finished, both workers are killed (SIGKILL; their nannies restart them). The run
ends in a ``ClusterError`` naming the chunks lost; the same call then resumes, running only
those. Prints the times, the samples lost and rerun, and whether the resumed answer equals the
uninterrupted local one bit for bit.
"""

from __future__ import annotations

import os
import signal
import sys
import tempfile
import threading
import time
from typing import Any

import numpy as np

import clearsim
from clearsim import reliability as rel


def build(clearance: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="dry", clearance=clearance)


def study(**options: Any) -> rel.Study:
    return rel.Study(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, rel.Output(body="slider", component="x"), rel.Limit(1e-3), progress=False, **options)


class Counting:
    """The executor, counting the samples it is sent."""

    def __init__(self, inner: Any) -> None:
        self.inner, self.samples = inner, 0

    def submit(self, fn: Any, *args: Any) -> Any:
        self.samples += len(args[0])
        return self.inner.submit(fn, *args)


def main() -> None:
    import dask
    from dask.distributed import Client, LocalCluster

    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1024
    t = time.perf_counter()
    local = study().monte_carlo(n, seed=1)
    print(f"local: {time.perf_counter() - t:.1f} s", flush=True)
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
            executor = client.get_executor()
            study().monte_carlo(4, seed=0, executor=executor)  # warm the workers up
            with tempfile.TemporaryDirectory() as where:
                pids = list(client.run(os.getpid).values())

                def kill_when_a_third_is_done() -> None:
                    while len([f for f in os.listdir(where) if f.startswith("chunk_")]) * 32 < n // 3:
                        time.sleep(0.05)
                    for pid in pids:
                        os.kill(pid, signal.SIGKILL)

                threading.Thread(target=kill_when_a_third_is_done, daemon=True).start()
                t = time.perf_counter()
                try:
                    study().monte_carlo(n, seed=1, executor=executor, checkpoint=where)
                    print("no chunk was lost (the workers were killed too late)")
                except clearsim.ClusterError as err:
                    lost = sum(b - a for a, b, _ in err.lost)
                    print(f"killed run: {time.perf_counter() - t:.1f} s, ClusterError: {len(err.lost)} chunks ({lost} samples) lost, {err.finished} finished and saved", flush=True)
                    print(f"  {str(err)[:300]}", flush=True)
                try:
                    client.wait_for_workers(2, timeout=60)
                except Exception:  # noqa: BLE001 — a nanny that did not bring its worker back: resume on the others
                    print(f"resuming on {len(client.scheduler_info()['workers'])} worker(s)", flush=True)
                again = Counting(executor)
                t = time.perf_counter()
                resumed = study().monte_carlo(n, seed=1, executor=again, checkpoint=where)
                same = np.array_equal(local.peaks, resumed.peaks, equal_nan=True) and local.pf == resumed.pf
                print(f"resumed: {time.perf_counter() - t:.1f} s, {again.samples} samples run again; equal to the local run bit for bit: {same}")


if __name__ == "__main__":
    main()
