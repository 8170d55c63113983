"""The slider-crank with a dry clearance swept over crank speed (docs/examples.md, "Periodic or
chaotic?"): its bifurcation diagram, Poincaré maps of a periodic and a chaotic speed, and the
largest Lyapunov exponent over speed, with the wall time.

    python benches/bifurcation_slider_crank.py                 # 200 speeds × (20 + 100) cycles
    python benches/bifurcation_slider_crank.py --speeds 40 --no-figures

The mechanism is docs/physics.md §8's (Flores et al.: crank 0.05 m, rod 0.12 m, c = 0.5 mm at
the rod-slider pin, c_e = 0.9, no gravity) with a lightly lubricated-looking dry friction
c_f = 0.03 (at the §8 default c_f = 0.1 every speed from 100 to 600 rad/s settles on one
period; frictionless, every one is chaotic). Tolerances rtol 1e-8, atol 1e-11: the pin sits
0.17 m from the origin, so rtol 1e-6 lets its position wander by 0.2 µm a step, which makes a
periodic motion look chaotic (docs/physics.md §13). Figures go to docs/ (``--figures DIR``).
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import time
from pathlib import Path

import numpy as np

import clearsim
from clearsim import dynamics, models
from clearsim.plots import save
from clearsim.plots.dynamics import plot_poincare_panels

DOCS = Path(__file__).resolve().parents[1] / "docs"
FRICTION = 0.03
TOL = dict(rtol=1e-8, atol=1e-11)


def build(omega: float) -> clearsim.Mechanism:
    """The §8 slider-crank at crank speed ``omega`` [rad/s] with c_f = FRICTION."""
    return models.slider_crank("dry", clearance=0.5e-3, rpm=omega * 60 / (2 * math.pi), dry=clearsim.Dry(friction=FRICTION))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--speeds", type=int, default=200)
    ap.add_argument("--low", type=float, default=100.0, help="rad/s")
    ap.add_argument("--high", type=float, default=600.0, help="rad/s")
    ap.add_argument("--cycles", type=int, default=100)
    ap.add_argument("--transient", type=int, default=20)
    ap.add_argument("--lyapunov", choices=("auto", "true", "false"), default="true")
    ap.add_argument("--figures", type=Path, default=DOCS)
    ap.add_argument("--no-figures", action="store_true")
    args = ap.parse_args()
    speeds = np.linspace(args.low, args.high, args.speeds)
    lyap = {"auto": "auto", "true": True, "false": False}[args.lyapunov]
    t = time.perf_counter()
    cpu = resource.getrusage(resource.RUSAGE_SELF)
    b = dynamics.bifurcation(build, speeds, "crank speed", transient_cycles=args.transient, cycles=args.cycles,
                             output=("rod-slider", "eccentricity_x"), lyapunov=lyap, **TOL)  # fmt: skip
    wall = time.perf_counter() - t
    end = resource.getrusage(resource.RUSAGE_SELF)
    used = (end.ru_utime - cpu.ru_utime) + (end.ru_stime - cpu.ru_stime)
    cores = os.cpu_count() or 1
    print(f"{args.speeds} speeds × ({args.transient} + {args.cycles}) cycles, lyapunov={args.lyapunov}: {wall:.1f} s wall on {cores} cores, "
          f"{used:.1f} s CPU ({used / args.speeds:.2f} s a speed: {used / cores:.1f} s wall on {cores} free cores; "
          f"200 speeds: {200 * used / args.speeds / cores:.0f} s)")
    print("kinds:", b.counts(), "failures:", len(b.failures))
    start = 0
    for i in range(1, len(speeds) + 1):
        if i == len(speeds) or b.kind[i] != b.kind[start]:
            print(f"  {speeds[start]:.1f}–{speeds[i - 1]:.1f} rad/s: {b.kind[start]}")
            start = i
    ok = np.isfinite(b.exponent)
    if np.any(ok):
        print(f"λ from {np.nanmin(b.exponent):.1f} to {np.nanmax(b.exponent):.1f} 1/s")
    if args.no_figures:
        return
    fig = b.plot(parameter_label="crank speed ω [rad/s]", scale=1e3, unit="mm", title=f"Slider-crank, dry pin c = 0.5 mm, c_f = {FRICTION}: e_x at top dead centre")
    print(save(fig, args.figures / "bifurcation_slider_crank.png"))
    panels = []
    for want in ("period-", "chaotic"):
        i = next((i for i, k in enumerate(b.kind) if k.startswith(want)), None)
        if i is not None:
            e = b.section(i).eccentricity("rod-slider") / 0.5e-3
            panels.append((e[:, 0], e[:, 1], f"ω = {speeds[i]:.0f} rad/s: {b.kind[i]}"))
    if panels:
        fig = plot_poincare_panels(panels, "e_x / c", "e_y / c", title=f"The journal at top dead centre, {args.cycles} cycles", circle=1.0)
        print(save(fig, args.figures / "poincare_slider_crank.png"))


if __name__ == "__main__":
    main()
