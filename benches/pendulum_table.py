"""Baker & Gollub's driven pendulum table, clearsim against an independent integration.

    python benches/pendulum_table.py [--cycles N] [--transient N]

For each drive g of Baker & Gollub (*Chaotic Dynamics*, 1996: q = 2, ω_D = 2/3, from θ = 0.2 at
rest; period 1 at 0.9 and 1.35, period 2 at 1.07 and 1.45, period 4 at 1.47, chaotic at 1.15 and
1.5): clearsim's :func:`clearsim.dynamics.bifurcation` of ``clearsim.models.driven_pendulum``
with the largest Lyapunov exponent for every value (``lyapunov=True``), against SciPy's DOP853
on the plain ODE (tests/python/dynamics_reference.py: the period its sections repeat with, the
exponent of its variational equation), over the same periods. Prints a Markdown table (the one
in docs/examples.md) and the wall times.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))

from dynamics_reference import pendulum_exponent, pendulum_sections, repeat_period  # noqa: E402

from clearsim import dynamics, models  # noqa: E402

BAKER_GOLLUB = {0.9: "period 1", 1.07: "period 2", 1.15: "chaotic", 1.35: "period 1", 1.45: "period 2", 1.47: "period 4", 1.5: "chaotic"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cycles", type=int, default=100, help="analysed drive periods (default 100)")
    ap.add_argument("--transient", type=int, default=150, help="drive periods before (default 150)")
    args = ap.parse_args()
    gs = list(BAKER_GOLLUB)
    t = time.perf_counter()
    b = dynamics.bifurcation(models.driven_pendulum, gs, "g", transient_cycles=args.transient, cycles=args.cycles,
                             output=("bob", "velocity", "theta"), lyapunov=True, integrator="dop853", rtol=1e-9, atol=1e-11, progress=False)  # fmt: skip
    t_clearsim = time.perf_counter() - t
    t = time.perf_counter()
    rows = []
    for g, kind, lam, (lo, hi) in zip(gs, b.kind, b.exponent, b.exponent_interval):
        k = repeat_period(pendulum_sections(g, args.transient, args.cycles + 1, rtol=1e-10))
        ref, half = pendulum_exponent(g, args.transient, args.cycles, rtol=1e-10)
        ref_kind = f"period-{k}" if k else ("chaotic" if ref - half > 0 else "not periodic")
        rows.append(f"| {g} | {BAKER_GOLLUB[g]} | {kind} | {ref_kind} | {lam:+.4f} [{lo:+.3f}, {hi:+.3f}] | {ref:+.4f} ± {half:.3f} |")
    t_ref = time.perf_counter() - t
    print("| g | Baker & Gollub | clearsim | SciPy (ODE) | λ clearsim [1/s] (95 %) | λ SciPy, variational [1/s] (95 %) |")
    print("|---|---|---|---|---|---|")
    print("\n".join(rows))
    print(f"\n{args.transient} + {args.cycles} drive periods (T = {2 * math.pi / (2 / 3):.4f} s) a value; clearsim {t_clearsim:.1f} s for the "
          f"{len(gs)} values with their exponents (batch on all cores), SciPy {t_ref:.1f} s (one core).")  # fmt: skip
    assert np.all(np.isfinite(b.exponent))


if __name__ == "__main__":
    main()
