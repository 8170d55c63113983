"""Wall and CPU time of ``clearsim paper`` in a first process (empty finite-bearing disk cache,
as on a fresh machine) and in a second one (issue 28 item 9: ≤ 10 s on 2 cores).

    python benches/paper_first_run.py            # the cores this process may use
    taskset -c 0 python benches/paper_first_run.py

Each process runs with its own empty ``CLEARSIM_CACHE_DIR`` for the first run, kept for the
second. The CPU time (user + system, all threads) is printed next to the wall time together with
the load average: on a machine shared with other work the wall time grows with the load, while
CPU / cores is a lower bound of the wall time alone. The tables of the paper's bearing ship with
the library, so both processes should solve none ("tables solved" stays 0).
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(cache: Path, out: Path) -> tuple:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()[0]
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "clearsim", "paper", "-q", "-o", str(out)], check=True, env=dict(os.environ, CLEARSIM_CACHE_DIR=str(cache)))
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, load, len(list(cache.glob("*.bin"))) if cache.exists() else 0


def main() -> None:
    cores = len(os.sched_getaffinity(0))
    with tempfile.TemporaryDirectory() as tmp:
        cache, out = Path(tmp) / "cache", Path(tmp) / "paper"
        for which in ("first process (empty cache)", "second process"):
            wall, cpu, load, solved = run(cache, out)
            print(f"{which}: {wall:.2f} s wall, {cpu:.2f} s CPU (≥ {cpu / cores:.2f} s on {cores} core(s)), load {load:.1f}, tables solved {solved}")


if __name__ == "__main__":
    main()
