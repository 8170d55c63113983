"""clearsim's default method against SciPy at equal error: the README's SciPy figures.

On one cycle of the lubricated nine-bar and slider-crank (the fixtures of ``benches/fixtures.py``),
the slider's displacement on 1 001 output times is compared with a tight reference (clearsim's
DOP853 at rtol 1e-12, atol 1e-15). Each method runs at a ladder of tolerances (atol = rtol/1000):

* clearsim's default method (``integrator="auto"``: RADAU5 on these models), and RK45 for
  comparison, storing the states only (what SciPy returns);
* SciPy's ``solve_ivp`` driving ``m.rhs`` with RK45, and with Radau, BDF and LSODA, each given
  ``jac=m.jacobian`` (the Newton matrix clearsim's RADAU5 uses), on the same output times
  (``t_eval``).

The CPU time of a method at the error of a clearsim run is read off the method's work-precision
front (its runs that no other of its runs beats in both time and error), interpolated in
log–log between the two runs that bracket the error; the ratio is that time over clearsim's.
"best SciPy" is the fastest of Radau, BDF and LSODA at that error. A ratio printed as ">x" means
that no SciPy run of that method was as accurate (x: its most accurate run's time over
clearsim's); "<x" that SciPy's loosest run was already more accurate (x: that run's time).

A second table compares clearsim's RK45 with SciPy's RK45 the same way. The third, per step at
the error of clearsim's default run: steps, right-hand sides and Newton matrices
(``jacobians``) of each run, and its time per step and per right-hand side: where SciPy's time
goes (its time per right-hand side is mostly Python's) against clearsim's.

Usage: ``python benches/scipy_speedup.py [--quick] [--cases nine_bar_lubricated,...]``
(about 5 minutes on 2 cores; ``--quick`` about 1). Times are the process's CPU time, the best of
several runs (SciPy's linear algebra held to one thread, as clearsim's run is): on a shared machine
wall times swing with the load — a 3 ms run took 3 to 30 ms while the machine was busy — while
CPU time stays within a few percent.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
import warnings

# One thread for the linear algebra of both sides, so that CPU time is the work done.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
from scipy import integrate
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fixtures import CYCLE, MODELS  # noqa: E402

#: case -> (fixture, slider body, axis of its motion)
CASES = {
    "nine_bar_lubricated": ("nine_bar_lubricated", "slider9", 1),
    "slider_crank_lubricated": ("slider_crank_lubricated", "slider", 0),
}
#: rtol ladders (atol = rtol · 1e-3, the default ratio); clearsim's default rtol 1e-6 is the headline.
OWN_TOLS = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
SCIPY_TOLS = {
    "RK45": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
    "Radau": [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
    "BDF": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10],
    "LSODA": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10],
}
IMPLICIT = ("Radau", "BDF", "LSODA")
DEFAULT_RTOL = 1e-6
OUTPUTS = 1001


class Budget(Exception):
    """A SciPy run went over its CPU-time budget."""


def counting(base: Any) -> Any:
    """SciPy's solver class ``base``, counting its accepted steps in ``steps`` (a class
    attribute, reset before each run; ``_step_impl`` returns once per accepted step)."""

    class Counting(base):  # type: ignore[misc, valid-type]
        steps = 0

        def _step_impl(self) -> Any:
            Counting.steps += 1
            return super()._step_impl()

    Counting.__name__ = base.__name__
    return Counting


def best_time(fn: Callable[[], Any], repeat: int, budget: float = math.inf) -> Tuple[float, Any]:
    """Smallest CPU time [s] of up to ``repeat`` calls of ``fn`` (fewer once they add up to
    ``budget``), and the last return value."""
    best, out, spent = math.inf, None, 0.0
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        wall = time.process_time() - t0
        best, spent = min(best, wall), spent + wall
        if spent > budget:
            break
    return best, out


def run_case(case: str, quick: bool, budget: float) -> List[Dict[str, Any]]:
    fixture, slider, axis = CASES[case]
    m = MODELS[fixture]()
    t_end = CYCLE["nine_bar" if case.startswith("nine") else "slider_crank"]
    grid = np.linspace(0.0, t_end, OUTPUTS)
    ref = m.simulate(t_end, integrator="dop853", rtol=1e-12, atol=1e-15, t_out=grid, outputs=["states"], progress=False)
    ref_x = ref.position(slider)[:, axis]
    index = m.state_index(slider, "xy"[axis])
    y0 = m.initial_state()
    rows: List[Dict[str, Any]] = []
    print(f"\n== {case}: one cycle ({t_end:g} s), reference DOP853 rtol 1e-12 in {ref.stats['steps']} steps", flush=True)

    def record(method: str, rtol: float, wall: float, x: Optional[np.ndarray], steps: Any, rhs: Any, jac: Any, note: str = "") -> None:
        err = float(np.max(np.abs(x - ref_x))) if x is not None else math.nan
        rows.append(dict(case=case, method=method, rtol=rtol, wall=wall, error=err, steps=steps, rhs=rhs, jac=jac, note=note))
        print(f"  {method:16s} rtol {rtol:7.0e}  {wall * 1e3:10.2f} ms  error {err:9.2e} m  steps {steps!s:>6}  rhs {rhs!s:>7}  jac {jac!s:>5} {note}", flush=True)

    own_tols = OWN_TOLS[1:4] if quick else OWN_TOLS
    for integrator in ("auto", "rk45"):
        for rtol in own_tols:
            kw = dict(integrator=integrator, rtol=rtol, atol=rtol * 1e-3, t_out=grid, outputs=["states"], progress=False)
            wall, res = best_time(lambda: m.simulate(t_end, **kw), repeat=3 if quick else 7, budget=5.0)
            name = f"clearsim {res.stats['integrator']}" + (" (auto)" if integrator == "auto" else "")
            record(name, rtol, wall, res.position(slider)[:, axis], res.stats["steps"], res.stats["rhs_evaluations"], res.stats["jacobians"])

    for method, tols in SCIPY_TOLS.items():
        for rtol in tols[1:-1:2] if quick else tols:
            calls = [0]
            start = [0.0]

            def f(t: float, y: np.ndarray) -> np.ndarray:
                calls[0] += 1
                if calls[0] % 512 == 0 and time.process_time() - start[0] > budget:
                    raise Budget()
                return m.rhs(t, y)

            solver = counting(getattr(integrate, method))

            def solve() -> Any:
                calls[0] = 0
                solver.steps = 0
                start[0] = time.process_time()
                jac = {"jac": m.jacobian} if method in IMPLICIT else {}
                return solve_ivp(f, (0.0, t_end), y0, method=solver, rtol=rtol, atol=rtol * 1e-3, t_eval=grid, **jac)

            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    wall, sol = best_time(solve, repeat=1 if quick else 2, budget=budget)
                if not sol.success:
                    record(f"scipy {method}", rtol, wall, None, "", sol.nfev, sol.njev, note=f"failed: {sol.message}"[:60])
                    continue
                record(f"scipy {method}", rtol, wall, sol.y[index], solver.steps, sol.nfev, sol.njev)
            except Budget:
                record(f"scipy {method}", rtol, budget, None, "", calls[0], "", note=f"stopped after {budget:g} s")
                break
    return rows


def front(runs: List[Dict[str, Any]]) -> List[Tuple[float, float]]:
    """(error, wall) of the runs that no run at least as accurate beats in time, by increasing
    error: the corners of the time a method needs for a given error."""
    pts = sorted((r["error"], r["wall"]) for r in runs if math.isfinite(r["error"]) and r["error"] > 0)
    out: List[Tuple[float, float]] = []
    for e, w in pts:
        if not out or w < out[-1][1]:
            out.append((e, w))
    return out


def time_at(runs: List[Dict[str, Any]], error: float) -> Tuple[Optional[float], str]:
    """A method's wall time at ``error`` from its front (log–log interpolation), and "" / ">" /
    "<" as in the module doc."""
    pts = front(runs)
    if not pts:
        return None, ""
    if error < pts[0][0]:
        return pts[0][1], ">"
    if error >= pts[-1][0]:
        return pts[-1][1], "<" if error > pts[-1][0] else ""
    for (e0, w0), (e1, w1) in zip(pts, pts[1:]):
        if e0 <= error <= e1:
            s = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(w0) + s * (math.log(w1) - math.log(w0))), ""
    return None, ""


def nearest(runs: List[Dict[str, Any]], error: float) -> Optional[Dict[str, Any]]:
    """The run of the front nearest ``error`` (log scale), at most as large if one is."""
    good = [r for r in runs if math.isfinite(r["error"])]
    if not good:
        return None
    under = [r for r in good if r["error"] <= error]
    pool = under or good
    return min(pool, key=lambda r: abs(math.log(r["error"] / error)) + 1e-9 * r["wall"])


def report(rows: List[Dict[str, Any]], cases: List[str]) -> None:
    methods = ["scipy RK45", *(f"scipy {m}" for m in IMPLICIT)]
    print("\n## At equal error: SciPy's time over clearsim's default method's (RADAU5)")
    print("\n| model | rtol | slider error [m] | clearsim [ms] | vs SciPy RK45 | vs Radau | vs BDF | vs LSODA | vs best SciPy |")
    print("|---|---|---|---|---|---|---|---|---|")
    worst: Dict[str, float] = {}
    for case in cases:
        own = [r for r in rows if r["case"] == case and r["method"].endswith("(auto)") and math.isfinite(r["error"])]
        for r in sorted(own, key=lambda r: -r["rtol"]):
            cells, best = [], (math.inf, "")
            for meth in methods:
                w, mark = time_at([s for s in rows if s["case"] == case and s["method"] == meth], r["error"])
                if w is None:
                    cells.append("–")
                    continue
                ratio = w / r["wall"]
                cells.append(f"{mark}{ratio:.1f}×")
                if meth != "scipy RK45" and w < best[0]:
                    best = (w, mark)
                if r["rtol"] == DEFAULT_RTOL and meth == "scipy RK45":
                    worst["RK45"] = min(worst.get("RK45", math.inf), ratio)
            b = f"{best[1]}{best[0] / r['wall']:.1f}×" if math.isfinite(best[0]) else "–"
            if r["rtol"] == DEFAULT_RTOL and math.isfinite(best[0]):
                worst["best"] = min(worst.get("best", math.inf), best[0] / r["wall"])
            print(f"| {case} | {r['rtol']:.0e} | {r['error']:.2e} | {r['wall'] * 1e3:.2f} | " + " | ".join(cells) + f" | {b} |")
    if worst:
        print(f"\nAt the default rtol 1e-6, worst of the models: {worst.get('RK45', math.nan):.1f}× SciPy RK45, "
              f"{worst.get('best', math.nan):.1f}× SciPy's best implicit method (targets: 50×, 25×).")

    print("\n## At equal error: SciPy RK45's time over clearsim RK45's (the same method on both sides)")
    print("\n| model | rtol | slider error [m] | clearsim RK45 [ms] | vs SciPy RK45 |")
    print("|---|---|---|---|---|")
    for case in cases:
        own = [r for r in rows if r["case"] == case and r["method"] == "clearsim rk45" and math.isfinite(r["error"])]
        for r in sorted(own, key=lambda r: -r["rtol"]):
            w, mark = time_at([s for s in rows if s["case"] == case and s["method"] == "scipy RK45"], r["error"])
            cell = f"{mark}{w / r['wall']:.1f}×" if w is not None else "–"
            print(f"| {case} | {r['rtol']:.0e} | {r['error']:.2e} | {r['wall'] * 1e3:.2f} | {cell} |")

    print("\n## Per step, at the error of clearsim's default run (rtol 1e-6): the runs nearest it")
    print("\n| model | method | rtol | error [m] | steps | right-hand sides | Newton matrices | CPU [ms] | per step [µs] | per rhs [µs] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for case in cases:
        own = [r for r in rows if r["case"] == case and r["method"].endswith("(auto)") and r["rtol"] == DEFAULT_RTOL]
        if not own:
            continue
        e = own[0]["error"]
        names = sorted({r["method"] for r in rows if r["case"] == case}, key=lambda n: (not n.startswith("clearsim"), n))
        for meth in names:
            r = own[0] if meth == own[0]["method"] else nearest([s for s in rows if s["case"] == case and s["method"] == meth], e)
            if r is None:
                continue
            steps = r["steps"] if isinstance(r["steps"], int) else None
            per_step = f"{r['wall'] / steps * 1e6:.1f}" if steps else "–"
            per_rhs = f"{r['wall'] / r['rhs'] * 1e6:.2f}" if isinstance(r["rhs"], int) and r["rhs"] else "–"
            print(f"| {case} | {meth} | {r['rtol']:.0e} | {r['error']:.2e} | {r['steps'] or '–'} | {r['rhs']} | {r['jac'] if r['jac'] != '' else '–'} | "
                  f"{r['wall'] * 1e3:.2f} | {per_step} | {per_rhs} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer tolerances and repeats")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--budget", type=float, default=30.0, help="CPU-time budget of one SciPy run [s]")
    a = ap.parse_args()
    cases = a.cases.split(",")
    rows: List[Dict[str, Any]] = []
    for case in cases:
        rows += run_case(case, a.quick, a.budget)
    report(rows, cases)


if __name__ == "__main__":
    main()
