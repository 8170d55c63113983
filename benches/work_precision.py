"""Work–precision study: error of the slider's displacement and acceleration against wall time.

For the nine-bar (dry, lubricated μ = 0.4 Pa s and the stiff hard case μ = 0.04 Pa s; 0.5 mm;
one cycle) and the slider-crank (dry, lubricated; one cycle), against a DOP853 reference at
rtol 1e-12: clearsim's RK4 at several steps, RK45, DOP853, RADAU5 and RODAS4 at several tolerances, and
SciPy's RK45, DOP853 and Radau driving ``m.rhs``. Writes ``docs/work_precision.csv`` and
``docs/work_precision.png`` (plus one PNG per case from ``clearsim.plots.plot_work_precision``).

Usage: ``python benches/work_precision.py [--quick] [--cases nine_bar_lubricated,...] [--replot]``
(a few minutes; not part of CI). SciPy runs are stopped after ``--budget`` seconds each.

Errors are taken over the whole cycle and over the *predictable window*: outputs before the
first time at which the reference and a second DOP853 reference at 10× its tolerance differ by
more than ``HORIZON_DX``. The dry models are sensitive to perturbations (sequences of impacts
amplify a 1e-12 m difference to 1e-5 m within a cycle), so past that time the error measures the
sensitivity, not the method; the plot and the speed-ups use the windowed errors.

Note: ``m.rhs`` has no impact memory (δ̇⁽⁻⁾ is the current approach speed), so on the dry models
SciPy integrates a slightly different contact law; its error there includes that difference.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fixtures import CYCLE, MODELS  # noqa: E402

DOCS = Path(__file__).resolve().parent.parent / "docs"

#: case -> (fixture, slider body, axis of motion, RK4 steps [s])
CASES = {
    "nine_bar_dry": ("nine_bar_dry", "slider9", 1, [2e-5, 1e-5, 5e-6, 2e-6]),
    "nine_bar_lubricated": ("nine_bar_lubricated", "slider9", 1, [4e-5, 2e-5, 1e-5, 5e-6]),
    "nine_bar_lubricated_mu004": ("nine_bar_lubricated_mu004", "slider9", 1, [4e-5, 2e-5, 1e-5, 5e-6]),
    "slider_crank_dry": ("slider_crank_dry", "slider", 0, [2e-6, 1e-6, 5e-7, 2e-7]),
    "slider_crank_lubricated": ("slider_crank_lubricated", "slider", 0, [1e-6, 5e-7, 2e-7, 1e-7]),
}

TOLS = {
    "rk45": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
    "dop853": [1e-4, 1e-6, 1e-8, 1e-10],
    "rodas4": [1e-2, 1e-3, 1e-4, 1e-5, 1e-6],
    "radau": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
    "scipy_RK45": [1e-3, 1e-4, 1e-6, 1e-8],
    "scipy_DOP853": [1e-4, 1e-6, 1e-8],
    "scipy_Radau": [1e-3, 1e-4, 1e-5],
}


#: [m] Difference of the two references that ends the predictable window.
HORIZON_DX = 1e-9


class Budget(Exception):
    pass


def errors(pos, acc, ref_pos, ref_acc, window):
    """Max |error| of displacement and acceleration over all outputs and over ``window``."""
    dx, da = np.abs(pos - ref_pos), np.abs(acc - ref_acc)
    return float(dx.max()), float(da.max()), float(dx[window].max()), float(da[window].max())


def predictable_window(t, ref_pos, second_pos):
    """Outputs before the first time the two references differ by more than ``HORIZON_DX``."""
    apart = np.abs(second_pos - ref_pos) > HORIZON_DX
    return t < (t[np.argmax(apart)] if apart.any() else np.inf)


def run_case(case, quick, budget, rows):
    fixture, slider, axis, rk4_steps = CASES[case]
    m = MODELS[fixture]()
    family = "nine_bar" if case.startswith("nine") else "slider_crank"
    t_end = CYCLE[family]
    t = np.linspace(0.0, t_end, 1001)
    coord = "xy"[axis]
    i_pos, i_vel = m.state_index(slider, coord), m.state_index(slider, coord, velocity=True)
    # The reference: DOP853 at rtol 1e-12; a lubricated journal crossing the small-eccentricity
    # regularisation (ε^m for ε < ε0, non-smooth at ε0) can underflow the step there, then the
    # next tolerance is used (recorded in the CSV's note column).
    for ref_tol in (1e-12, 1e-11, 1e-10):
        try:
            ref = m.simulate(t_end, integrator="dop853", rtol=ref_tol, atol=ref_tol * 1e-3, t_out=t)
            break
        except Exception as e:
            print(f"reference at rtol {ref_tol:g} failed: {e}"[:160])
    ref_pos, ref_acc = ref.position(slider)[:, axis], ref.acceleration(slider)[:, axis]
    second = m.simulate(t_end, integrator="dop853", rtol=10 * ref_tol, atol=10 * ref_tol * 1e-3, t_out=t)
    window = predictable_window(t, ref_pos, second.position(slider)[:, axis])
    window_end = float(t[window][-1])
    print(f"\n== {case}: reference DOP853 {ref_tol:g}, {ref.stats['steps']} steps, {ref.stats['wall_time']:.2f} s; "
          f"predictable window [0, {window_end:.4g}] s of {t_end:.4g} s", flush=True)

    def record(method, param, wall, stats, pos, acc, note=""):
        ep, ea, wp, wa = errors(pos, acc, ref_pos, ref_acc, window) if pos is not None else (math.nan,) * 4
        row = dict(case=case, method=method, param=param, wall_time=wall, err_displacement=ep, err_acceleration=ea,
                   window_end=window_end, err_displacement_window=wp, err_acceleration_window=wa,
                   steps=stats.get("steps", ""), rhs_evals=stats.get("rhs_evaluations", ""),
                   note=(note + f" ref rtol {ref_tol:g}" if ref_tol != 1e-12 else note).strip())
        rows.append(row)
        print(f"{method:>14} {param:>9.1e}  {wall:9.4f} s  err_x={ep:9.2e} m  err_a={ea:9.2e} m/s²  "
              f"(window {wp:9.2e} m, {wa:9.2e} m/s²)  steps={row['steps']} {note}", flush=True)

    def own(integrator, param, **kw):
        t0 = time.perf_counter()
        try:
            r = m.simulate(t_end, integrator=integrator, t_out=t, **kw)
            wall = time.perf_counter() - t0
            record(integrator, param, wall, r.stats, r.position(slider)[:, axis], r.acceleration(slider)[:, axis])
        except Exception as e:  # a failed run is a data point too
            record(integrator, param, time.perf_counter() - t0, getattr(getattr(e, "result", None), "stats", {}) or {}, None, None,
                   note=f"failed: {type(e).__name__}")

    for h in rk4_steps[: 2 if quick else None]:
        own("rk4", h, step=h)
    for integ in ("rk45", "dop853", "radau", "rodas4"):
        for tol in TOLS[integ][: 3 if quick else None]:
            kw = dict(rtol=tol, atol=tol * 1e-3)
            if integ in ("rodas4", "radau"):
                kw["max_steps"] = 60_000
            own(integ, tol, **kw)

    y0 = m.initial_state()
    for method in ("RK45", "DOP853", "Radau"):
        for tol in TOLS[f"scipy_{method}"][: 2 if quick else None]:
            calls = [0]
            t0 = time.perf_counter()

            def f(tt, y):
                calls[0] += 1
                if calls[0] % 256 == 0 and time.perf_counter() - t0 > budget:
                    raise Budget()
                return m.rhs(tt, y)

            try:
                sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=tol, atol=tol * 1e-3, t_eval=t)
                wall = time.perf_counter() - t0
                if not sol.success:
                    raise RuntimeError(sol.message)
                pos = sol.y[i_pos]
                acc = np.array([m.rhs(tt, sol.y[:, i])[i_vel] for i, tt in enumerate(sol.t)])
                record(f"scipy_{method}", tol, wall, {"steps": sol.t.size and len(sol.t), "rhs_evaluations": sol.nfev}, pos, acc,
                       note="no impact memory" if "dry" in case else "")
                rows[-1]["steps"] = ""
            except Budget:
                record(f"scipy_{method}", tol, time.perf_counter() - t0, {"rhs_evaluations": calls[0]}, None, None, note=f"stopped after {budget:.0f} s")
            except Exception as e:
                record(f"scipy_{method}", tol, time.perf_counter() - t0, {}, None, None, note=f"failed: {e}"[:80])


#: The errors the plot and the speed-ups compare: over the predictable window.
EX, EA = "err_displacement_window", "err_acceleration_window"


def speedups(rows):
    """clearsim RK45 vs SciPy RK45 at the same tolerance (hence about the same error)."""
    out = []
    for r in rows:
        if r["method"] != "rk45":
            continue
        for s in rows:
            if s["case"] == r["case"] and s["method"] == "scipy_RK45" and s["param"] == r["param"] and math.isfinite(s[EX]):
                out.append((r["case"], r["param"], s["wall_time"] / r["wall_time"], r[EX], s[EX]))
    return out


def equal_error_speedups(rows, method, baseline):
    """For each run of ``method``: wall time of the fastest ``baseline`` run whose displacement and
    acceleration errors are both at most this run's, divided by this run's time (None when no
    baseline run is that accurate)."""
    out = []
    ok = lambda r: math.isfinite(r[EX]) and math.isfinite(r[EA])
    for r in rows:
        if r["method"] != method or not ok(r):
            continue
        times = [s["wall_time"] for s in rows if s["case"] == r["case"] and s["method"] == baseline and ok(s)
                 and s[EX] <= r[EX] and s[EA] <= r[EA]]
        out.append((r["case"], r["param"], min(times) / r["wall_time"] if times else None, r[EX], r[EA]))
    return out


def plot(rows, cases):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(cases), figsize=(4.2 * len(cases), 7.5), squeeze=False)
    spans = {}
    methods = ["rk4", "rk45", "dop853", "radau", "rodas4", "scipy_RK45", "scipy_DOP853", "scipy_Radau"]
    markers = dict(zip(methods, "osD*^vPX"))
    for j, case in enumerate(cases):
        ends = {r["window_end"] for r in rows if r["case"] == case}
        t_win = min(ends) if ends else math.inf
        t_cycle = CYCLE["nine_bar" if case.startswith("nine") else "slider_crank"]
        span = "one cycle" if t_win >= t_cycle * (1 - 2e-3) else f"t ≤ {t_win:.3g} s of {t_cycle:.3g} s"
        spans[case] = span
        for i, (key, unit) in enumerate([(EX, "m"), (EA, "m/s²")]):
            ax = axes[i, j]
            for meth in methods:
                pts = sorted((r["wall_time"], r[key]) for r in rows if r["case"] == case and r["method"] == meth and r[key] > 0 and math.isfinite(r[key]))
                if pts:
                    ax.loglog(*zip(*pts), marker=markers[meth], ls="--" if meth.startswith("scipy") else "-", label=meth)
            ax.set_title(f"{case}\n{'displacement' if i == 0 else 'acceleration'}, {span}", fontsize=9)
            ax.set_xlabel("wall time [s]")
            ax.set_ylabel(f"max |error| [{unit}]")
            ax.grid(True, which="both", alpha=0.3)
    handles = {}
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    labels = [m for m in methods if m in handles]
    fig.legend([handles[m] for m in labels], labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(DOCS / "work_precision.png", dpi=110)
    try:
        from clearsim.plots import plot_work_precision

        for case in cases:
            sub = [dict(r, error=r[EX]) for r in rows if r["case"] == case]
            f = plot_work_precision(sub, y="error", annotate="param", title=f"{case}: slider displacement, {spans[case]}")
            f.savefig(DOCS / f"work_precision_{case}.png", dpi=110)
    except Exception as e:  # the plotting helper is optional
        print("plot_work_precision unavailable:", e)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--budget", type=float, default=60.0)
    ap.add_argument("--replot", action="store_true", help="only redraw the figures from docs/work_precision.csv")
    a = ap.parse_args()
    cases = a.cases.split(",")
    if a.replot:
        with open(DOCS / "work_precision.csv") as fh:
            numeric = ("wall_time", "param", "window_end", "err_displacement", "err_acceleration", EX, EA)
            rows = [dict(r, **{k: float(r[k]) for k in numeric}) for r in csv.DictReader(fh)]
        plot(rows, [c for c in cases if any(r["case"] == c for r in rows)])
        return
    rows = []
    DOCS.mkdir(exist_ok=True)
    for case in cases:
        try:
            run_case(case, a.quick, a.budget, rows)
        except Exception as e:
            print(f"case {case} failed: {e}")
        with open(DOCS / "work_precision.csv", "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    print("\nclearsim RK45 vs SciPy RK45 on m.rhs (same rtol):")
    for case, tol, ratio, e1, e2 in speedups(rows):
        print(f"  {case:28s} rtol {tol:.0e}: {ratio:7.1f}x faster  (errors {e1:.2e} vs {e2:.2e} m)")
    for method, baseline in [("radau", "rk45"), ("radau", "scipy_Radau"), ("radau", "scipy_RK45"), ("rk45", "scipy_RK45")]:
        print(f"\n{method} vs {baseline} at equal or better error (displacement and acceleration):")
        for case, tol, ratio, e1, e2 in equal_error_speedups(rows, method, baseline):
            txt = f"{ratio:7.1f}x faster" if ratio else f"no {baseline} run that accurate"
            print(f"  {case:28s} rtol {tol:.0e}: {txt}  (errors {e1:.2e} m, {e2:.2e} m/s²)")
    plot(rows, cases)
    print("wrote", DOCS / "work_precision.csv", DOCS / "work_precision.png")


if __name__ == "__main__":
    main()
