"""How dry-impact acceleration peaks converge with the tolerance, and what the output grid does to
them: the dry slider-crank (clearsim.models.slider_crank("dry"), 5000 rpm, c = 0.5 mm) over
``--revs`` crank revolutions, for RK45 and DOP853 at rtol 1e-5 ... 1e-8 (atol = rtol/1000),
against DOP853 at rtol 1e-11; then the chaotic dry nine-bar over ``--nine-bar-revs`` revolutions.

    python benches/impact_peaks.py [--revs 12] [--nine-bar-revs 3]

Prints the Markdown tables of docs/performance.md, "Peaks". Columns: the slider's peak |ẍ| in the
first revolution (the first impact) and in the last (``Result.extremes`` with ``extremes_from``:
tracked at every step, located between steps), the same peak read off stored outputs at
dt_out = 1e-4 and 1e-5 s, the peak of ẍ averaged over 0.1 ms ((ẋ(t + 0.1 ms) − ẋ(t))/0.1 ms, from
outputs every 1 µs), the peak contact force of the last revolution, the slider's largest
displacement error against the reference over the run, steps and CPU time of the run (with
extremes, outputs only at its ends). Last, what tracking a body's extremes costs.
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any, Dict, List, Tuple

import numpy as np

from clearsim import models

RPM = 5000.0
PERIOD = 60.0 / RPM  # [s]
WINDOW = 1e-4  # [s] of the averaged acceleration
FINE = 1e-6  # [s] output grid of the averaged acceleration and the displacement error


def _peak(m: Any, t_end: float, start: float, **kw: Any) -> Tuple[float, float]:
    """Peak |ẍ| of the slider and peak contact force over [start, t_end] (extremes)."""
    res = m.simulate(t_end, dt_out=t_end, extremes=["slider", "rod-slider"], extremes_from=start, progress=False, **kw)
    a = res.extremes("slider", "acceleration", "x")
    return max(abs(a.max), abs(a.min)), res.extremes("rod-slider", "contact_force").max


def row(integrator: str, rtol: float, revs: int) -> Dict[str, Any]:
    m = models.slider_crank("dry")
    kw: Dict[str, Any] = dict(integrator=integrator, rtol=rtol, atol=rtol * 1e-3)
    t_end = revs * PERIOD
    last = (revs - 1) * PERIOD
    res = m.simulate(t_end, dt_out=FINE, outputs=["states"], progress=False, **kw)
    first_peak, _ = _peak(m, PERIOD, 0.0, **kw)
    c = time.process_time()
    last_peak, force = _peak(m, t_end, last, **kw)
    cpu = time.process_time() - c
    sampled = []
    for dt in (1e-4, 1e-5):
        r = m.simulate(t_end, dt_out=dt, outputs=["states", "accelerations"], progress=False, **kw)
        sampled.append(float(np.max(np.abs(r.acceleration("slider")[r.t >= last - 1e-12, 0]))))
    v, t = res.velocity("slider")[:, 0], res.t
    n = int(round(WINDOW / FINE))
    mean_acc = (v[n:] - v[:-n]) / WINDOW
    averaged = float(np.max(np.abs(mean_acc[t[:-n] >= last - 1e-12])))
    return dict(first=first_peak, last=last_peak, sampled=sampled, averaged=averaged, force=force, x=res.position("slider")[:, 0], steps=res.stats["steps"], cpu=cpu)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--revs", type=int, default=12, help="crank revolutions of the slider-crank (default 12)")
    ap.add_argument("--nine-bar-revs", type=int, default=3, help="crank revolutions of the nine-bar (default 3)")
    args = ap.parse_args()
    ref = row("dop853", 1e-11, args.revs)
    rows: List[Tuple[str, float, Dict[str, Any]]] = [("dop853", 1e-11, ref)]
    for integrator in ("rk45", "dop853"):
        for rtol in (1e-5, 1e-6, 1e-7, 1e-8):
            rows.append((integrator, rtol, row(integrator, rtol, args.revs)))
    ideal = models.slider_crank("ideal").simulate(PERIOD, dt_out=PERIOD, extremes=["slider"], rtol=1e-10, atol=1e-13, progress=False)
    a_ideal = ideal.extremes("slider", "acceleration", "x")
    print(f"Dry slider-crank, {args.revs} revolutions ({args.revs * PERIOD * 1e3:.0f} ms); the ideal mechanism's peak |ẍ| is {max(abs(a_ideal.max), abs(a_ideal.min)):.0f} m/s².\n")
    print(
        "| method | rtol | peak \\|ẍ\\| rev 1 [m/s²] | peak \\|ẍ\\| last rev [m/s²] | from outputs, dt_out 1e-4 / 1e-5 s | ẍ averaged over 0.1 ms, last rev | "
        "peak F_N last rev [N] | max slider x error [m] | steps | CPU [s] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")

    def rel(v: float, r: float) -> str:
        return "ref." if v is r else f"{(v - r) / r:+.1%}"

    for integrator, rtol, r in rows:
        err = float(np.max(np.abs(r["x"] - ref["x"])))
        print(
            f"| {integrator} | {rtol:.0e} | {r['first']:.0f} | {r['last']:.0f} ({rel(r['last'], ref['last'])}) | "
            f"{r['sampled'][0]:.0f} / {r['sampled'][1]:.0f} ({rel(r['sampled'][0], ref['last'])} / {rel(r['sampled'][1], ref['last'])}) | "
            f"{r['averaged']:.0f} ({rel(r['averaged'], ref['averaged'])}) | {r['force']:.0f} ({rel(r['force'], ref['force'])}) | "
            f"{'ref.' if r is ref else f'{err:.1e}'} | {r['steps']} | {r['cpu']:.2f} |"
        )
    print(f"\nCommand: python benches/impact_peaks.py --revs {args.revs}")
    chaotic(args.nine_bar_revs)


def chaotic(revs: int) -> None:
    """The dry nine-bar (clearsim.models.nine_bar("dry"), ω = −5π rad/s, two dry joints), whose
    impacts amplify any difference (README, "Choosing an integrator"): slider 9's peak ÿ in the
    first revolution and in the last, per tolerance."""
    period = 0.4  # [s]
    print(f"\nDry nine-bar, slider 9's ÿ, {revs} revolutions: largest and smallest value [m/s²] in the first and in the last revolution.\n")
    print("| method | rtol | rev 1: max / min | last rev: max / min | steps |")
    print("|---|---|---|---|---|")
    for integrator in ("rk45", "dop853"):
        for rtol in (1e-5, 1e-6, 1e-7, 1e-8, 1e-10):
            kw: Dict[str, Any] = dict(integrator=integrator, rtol=rtol, atol=rtol * 1e-3, progress=False)
            m = models.nine_bar("dry")
            first = m.simulate(period, dt_out=period, extremes=["slider9"], **kw).extremes("slider9", "acceleration", "y")
            res = m.simulate(revs * period, dt_out=revs * period, extremes=["slider9"], extremes_from=(revs - 1) * period, **kw)
            last = res.extremes("slider9", "acceleration", "y")
            print(f"| {integrator} | {rtol:.0e} | {first.max:.0f} / {first.min:.0f} | {last.max:.0f} / {last.min:.0f} | {res.stats['steps']} |")
    print(f"\nCommand: python benches/impact_peaks.py --nine-bar-revs {revs}")
    cost()


def cost() -> None:
    """What tracking one body's extremes (x, y, θ × displacement, velocity, acceleration) costs:
    CPU of one run with and without ``extremes=[body]``, best of five."""
    cases = [
        ("slider-crank, dry", lambda: models.slider_crank("dry"), "slider", 0.05),
        ("slider-crank, lubricated", lambda: models.slider_crank("lubricated"), "slider", 0.05),
        ("nine-bar, dry", lambda: models.nine_bar("dry"), "slider9", 0.4),
        ("nine-bar, lubricated", lambda: models.nine_bar("lubricated"), "slider9", 0.4),
    ]
    print("\nCost of `extremes=[body]` (CPU of one run, best of five; outputs every 0.1 ms).\n")
    print("| model | without [s] | with [s] | ratio |")
    print("|---|---|---|---|")
    for name, build, body, t_end in cases:
        m = build()
        m.compile()
        best = []
        for extra in ({}, {"extremes": [body]}):
            times = []
            for _ in range(5):
                c = time.process_time()
                m.simulate(t_end, dt_out=1e-4, progress=False, **extra)
                times.append(time.process_time() - c)
            best.append(min(times))
        print(f"| {name} | {best[0]:.4f} | {best[1]:.4f} | {best[1] / best[0]:.2f} |")


if __name__ == "__main__":
    main()
