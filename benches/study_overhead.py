"""What a Study sample costs beyond its run, and what a study sends to an executor.

    python benches/study_overhead.py overhead [n]      # Study.monte_carlo against the same runs bare
    python benches/study_overhead.py dask [n ...]      # a Dask LocalCluster (2 workers × 1 thread) against the local run
    python benches/study_overhead.py bytes [n]         # pickled bytes per task and per sample
    python benches/study_overhead.py instructions [n]  # the overhead by instruction counts (cachegrind)

``overhead``: the dry slider-crank (clearance N(0.5 mm, 0.02 mm), one crank cycle, slider x
displacement error), ``n`` samples (default 256) through ``Study.monte_carlo``, against the same
descriptions and output grid run bare through ``_core.run_batch`` (no monitors, no reference):
the ratio of CPU time (all threads; steadier than wall time on a shared machine) and of wall
time. ``dask``: wall time (and CPU time, all processes: the figure a loaded machine does not
distort) of ``Study.monte_carlo`` locally and through ``client.get_executor()``, results
compared bit for bit. ``bytes``: the pickled arguments of the tasks an executor gets
(what crosses to a worker), per task and per sample. ``instructions``: the same comparison as
``overhead`` on one thread by instructions executed (``valgrind --tool=cachegrind
--cache-sim=no``, six processes: the common start, the start with the descriptions built, the
bare batch, the study's own jobs built, those jobs run, the study), the repeatable figure on a
shared machine, with the difference split into building the samples, the monitors with their
reference runs, and the study's Python around the batch.
"""

from __future__ import annotations

import pickle
import sys
import time
from typing import Any, List

import numpy as np

import clearsim
from clearsim import _core
from clearsim import reliability as rel


def build(clearance: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="dry", clearance=clearance)


def study(**options: Any) -> rel.Study:
    return rel.Study(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, rel.Output(body="slider", component="x"), rel.Limit(1e-3), progress=False, **options)


def clocks() -> tuple:
    return time.perf_counter(), time.process_time()


def overhead(n: int) -> None:
    st = study()
    st.monte_carlo(8, seed=99)  # warm up (imports, first compile)
    u = np.random.default_rng(1).standard_normal((n, 1))
    values = st.values(u)["clearance"]
    descs = [build(float(c)).description() for c in values]
    t0, t1, _ = st._window({"clearance": 0.5e-3})
    settings = build(0.5e-3).run_settings(t1, t_out=[t0, t1], outputs=["states"], **st.run_options)
    rounds = []
    for _ in range(3):
        w, c = clocks()
        _core.run_batch(descs, [settings] * n, 0)
        bare = (time.perf_counter() - w, time.process_time() - c)
        w, c = clocks()
        st.monte_carlo(n, seed=1)
        full = (time.perf_counter() - w, time.process_time() - c)
        rounds.append((bare, full))
    best_bare = min(r[0][1] for r in rounds)
    best_full = min(r[1][1] for r in rounds)
    wall_bare = min(r[0][0] for r in rounds)
    wall_full = min(r[1][0] for r in rounds)
    print(f"dry slider-crank, n = {n}: bare run_batch {1e3 * best_bare / n:.2f} ms CPU/sample ({1e3 * wall_bare / n:.2f} ms wall), "
          f"Study.monte_carlo {1e3 * best_full / n:.2f} ms CPU/sample ({1e3 * wall_full / n:.2f} ms wall): "
          f"{best_full / best_bare:.3f}× CPU, {wall_full / wall_bare:.3f}× wall (best of 3)")


def part(which: str, n: int) -> None:
    """One of the processes ``instructions`` counts: the start, the start with the descriptions
    and settings built (``built``), the bare batch (``bare``), the study's own jobs built (its
    mechanisms, descriptions and run settings with monitors: ``jobs``) and run through the same
    batch (``monitored``), or the study (``study``), one thread."""
    st = study(threads=1)
    st.monte_carlo(8, seed=99)
    if which == "study":
        st.monte_carlo(n, seed=1)
        return
    if which == "start":
        return
    if which in ("jobs", "monitored"):
        jobs = st._chunk_jobs(st.values(np.random.default_rng(1).standard_normal((n, 1))), 0, n, 0, 360, None, True)
        descs = [j.mechanism._description() for j in jobs]
        if which == "monitored":
            _core.run_batch(descs, [j.settings for j in jobs], 1)
        return
    values = st.values(np.random.default_rng(1).standard_normal((n, 1)))["clearance"]
    descs = [build(float(c)).description() for c in values]
    t0, t1, _ = st._window({"clearance": 0.5e-3})
    settings = build(0.5e-3).run_settings(t1, t_out=[t0, t1], outputs=["states"], **st.run_options)
    if which == "bare":
        _core.run_batch(descs, [settings] * n, 1)


def instructions(n: int) -> None:
    import re
    import subprocess

    counts = {}
    for which in ("start", "built", "bare", "jobs", "monitored", "study"):
        out = subprocess.run(
            ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null", sys.executable, __file__, "part", which, str(n)],
            capture_output=True, text=True, check=True,
        ).stderr  # fmt: skip
        counts[which] = int(re.search(r"I\s+refs:\s+([\d,]+)", out).group(1).replace(",", ""))
    bare = (counts["bare"] - counts["built"]) / n
    full = (counts["study"] - counts["start"]) / n
    print(f"dry slider-crank, n = {n}, one thread: bare run_batch {bare / 1e6:.2f} M instructions a sample, Study.monte_carlo {full / 1e6:.2f} M: {full / bare:.3f}×")
    # Where the difference goes: building the sample (the user's build(**inputs), its description
    # and the study's run settings), the monitors with their reference runs in the core, and the
    # study's own Python around the batch (reading results back, the estimate).
    building = (counts["jobs"] - counts["start"]) / n
    monitoring = (counts["monitored"] - counts["jobs"]) / n - bare
    rest = (counts["study"] - counts["monitored"]) / n
    print(f"  of a bare run: building the sample {building / bare:+.3f}, monitors and reference runs {monitoring / bare:+.3f}, the study's Python around the batch {rest / bare:+.3f}")


def tasks(n: int) -> List[tuple]:
    """The argument tuples the executor's map gets for a Study.monte_carlo of n samples."""
    calls: List[tuple] = []

    class Recorder:
        def map(self, fn: Any, *iterables: Any) -> Any:
            for args in zip(*iterables):
                calls.append(args)
                yield fn(*args)

    study().monte_carlo(n, seed=1, executor=Recorder())
    return calls


def traffic(n: int) -> None:
    calls = tasks(n)
    sizes = [len(pickle.dumps(args)) for args in calls]
    samples = sum(len(args[0]) for args in calls)
    print(f"n = {n}: {len(calls)} tasks, {np.mean(sizes) / 1e3:.1f} kB a task, {sum(sizes) / samples / 1e3:.2f} kB a sample "
          f"({sum(sizes) / 1e6:.2f} MB in all)")


def dask(ns: List[int]) -> None:
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
        executor = client.get_executor()
        study().monte_carlo(4, seed=0, executor=executor)  # warm the workers up
        def cpu() -> float:
            import resource

            r = resource.getrusage(resource.RUSAGE_SELF)
            return r.ru_utime + r.ru_stime

        for n in ns:
            t, c = time.perf_counter(), cpu()
            local = study().monte_carlo(n, seed=1)
            t_local, c_local = time.perf_counter() - t, cpu() - c
            w0, c0 = sum(client.run(cpu).values()), cpu()
            t = time.perf_counter()
            remote = study().monte_carlo(n, seed=1, executor=executor)
            t_remote = time.perf_counter() - t
            c_remote = sum(client.run(cpu).values()) - w0 + cpu() - c0
            same = np.array_equal(local.peaks, remote.peaks, equal_nan=True)
            print(f"n = {n}: local {t_local:.2f} s ({c_local:.1f} s CPU), Dask 2 × 1 thread {t_remote:.2f} s ({c_remote:.1f} s CPU of the workers and "
                  f"this process) ({t_remote / t_local:.2f}×); peaks identical: {same}")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "overhead"
    args = [int(a) for a in sys.argv[2:]] if what != "part" else []
    if what == "overhead":
        overhead(args[0] if args else 256)
    elif what == "part":
        part(sys.argv[2], int(sys.argv[3]))
    elif what == "instructions":
        instructions(args[0] if args else 64)
    elif what == "bytes":
        traffic(args[0] if args else 1024)
    elif what == "dask":
        dask(args or [1024, 4096])
    else:
        raise SystemExit(__doc__)
