"""Monte Carlo throughput: samples per second of the nine-bar (one crank cycle, clearance
N(0.5 mm, 0.02 mm), slider y displacement, velocity and acceleration errors against the paper's
limits), dry and lubricated, on all local cores. Usage: ``python benches/mc_throughput.py [n]``.
"""

from __future__ import annotations

import math
import os
import sys
import time

import clearsim
from clearsim import models
from clearsim.reliability import PAPER_ALLOWABLE, Normal


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 16
    cores = os.cpu_count() or 1
    for kind in ("dry", "lubricated"):

        def build(clearance: float, kind: str = kind) -> clearsim.Mechanism:
            return models.nine_bar(kind, clearance=clearance, omega=-5 * math.pi)

        start = time.perf_counter()
        mc = clearsim.monte_carlo(
            build, {"clearance": Normal(0.5e-3, 0.02e-3)}, n, omega=-5 * math.pi, body="slider9", component="y",
            allowable=dict(PAPER_ALLOWABLE), progress=False, seed=0,
        )  # fmt: skip
        wall = time.perf_counter() - start
        print(f"{kind:>10}: {n / wall:6.1f} samples/s on {cores} cores ({n / wall / cores:.1f} per core), {n} samples in {wall:.2f} s, {mc.n_failed} failed")


if __name__ == "__main__":
    main()
