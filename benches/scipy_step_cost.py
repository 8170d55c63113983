"""Where the time of an RK45 step goes: clearsim's RK45 against SciPy's RK45 driving ``m.rhs``.

Both take about the same steps at the same tolerance (same Dormand–Prince pair, the same kind of
error norm), so the speed-up at equal tolerance is the ratio of the costs of one step attempt:

* SciPy: its own Python work per step (measured with a right-hand side that returns a
  preallocated array) plus six calls of ``m.rhs`` from Python;
* clearsim: six right-hand sides in Rust plus the stepper's arithmetic.

The script prints, per model, both costs, the speed-up they allow, and the right-hand-side cost
clearsim would need for a 100× speed-up (``scipy step / 600``). Writes
``docs/scipy_step_cost.csv``. Usage: ``python benches/scipy_step_cost.py`` (about 20 s). Times are
CPU times (``benches/scipy_speedup.py`` says why); the equal-error comparison is that bench's.
"""

from __future__ import annotations

import csv
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fixtures import CYCLE, MODELS  # noqa: E402

DOCS = Path(__file__).resolve().parent.parent / "docs"
CASES = ["slider_crank_ideal", "slider_crank_lubricated", "nine_bar_ideal", "nine_bar_dry", "nine_bar_lubricated"]
RTOL, ATOL = 1e-6, 1e-9
STAGES = 6  # right-hand sides per Dormand–Prince step attempt (FSAL)


def best_of(fn, repeat=3):
    """Smallest CPU time [s] of ``repeat`` calls of ``fn`` (and the last return value): on a
    shared machine wall time swings with the load, the process's CPU time far less."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def rhs_call_cost(m, y0, t, calls=20_000):
    """CPU time [µs] of one ``m.rhs`` call from Python."""
    def loop():
        for _ in range(calls):
            m.rhs(t, y0)
    return best_of(loop)[0] / calls * 1e6


def scipy_overhead(n, t_end, steps=10_000):
    """SciPy RK45's own work per step [µs]: a right-hand side that returns a preallocated array
    of the model's size (zero error, so the step is held at ``max_step``)."""
    z = np.zeros(n)
    h = t_end / steps
    wall, sol = best_of(lambda: solve_ivp(lambda t, y: z, (0.0, t_end), np.ones(n), method="RK45",
                                          first_step=h, max_step=h, rtol=RTOL, atol=ATOL))
    return wall / ((sol.nfev - 2) / STAGES) * 1e6


def measure(case):
    m = MODELS[case]()
    family = "nine_bar" if case.startswith("nine") else "slider_crank"
    t_end = CYCLE[family]
    y0 = m.initial_state()
    # Only the final state is recorded, as SciPy records only its steps.
    own_wall, own = best_of(lambda: m.simulate(t_end, integrator="rk45", rtol=RTOL, atol=ATOL, t_out=[t_end], progress=False))
    sp_wall, sol = best_of(lambda: solve_ivp(m.rhs, (0.0, t_end), y0, method="RK45", rtol=RTOL, atol=ATOL), repeat=2)
    own_attempts = own.stats["rhs_evaluations"] / STAGES
    sp_attempts = (sol.nfev - 2) / STAGES
    sp_step = sp_wall / sp_attempts * 1e6
    return dict(
        case=case,
        state_dim=y0.size,
        scipy_steps=sol.t.size - 1,
        clearsim_steps=own.stats["steps"],
        scipy_overhead_us=scipy_overhead(y0.size, t_end),
        rhs_call_from_python_us=rhs_call_cost(m, y0, 0.3 * t_end),
        scipy_step_us=sp_step,
        clearsim_step_us=own_wall / own_attempts * 1e6,
        clearsim_us_per_rhs=own_wall / own.stats["rhs_evaluations"] * 1e6,
        speedup_same_tol=sp_wall / own_wall,
        rhs_needed_for_100x_us=sp_step / (100 * STAGES),
    )


def main():
    rows = []
    print(f"RK45 at rtol {RTOL:g}, atol {ATOL:g}, one cycle; times per step attempt [µs]")
    print(f"{'case':26s} {'n':>3s} {'SciPy own':>9s} {'m.rhs':>6s} {'SciPy step':>10s} {'clearsim step':>13s} "
          f"{'speed-up':>8s} {'RHS for 100x':>12s}")
    for case in CASES:
        r = measure(case)
        rows.append(r)
        print(f"{case:26s} {r['state_dim']:3d} {r['scipy_overhead_us']:9.1f} {r['rhs_call_from_python_us']:6.2f} "
              f"{r['scipy_step_us']:10.1f} {r['clearsim_step_us']:13.2f} {r['speedup_same_tol']:7.1f}x "
              f"{r['rhs_needed_for_100x_us']:12.3f}", flush=True)
    DOCS.mkdir(exist_ok=True)
    with open(DOCS / "scipy_step_cost.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("wrote", DOCS / "scipy_step_cost.csv")


if __name__ == "__main__":
    main()
