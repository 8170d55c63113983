"""Lubricated slider-crank with µm clearances: which film models finish one crank revolution at
default settings, from which start, and why the long film's whirl crawls (docs/hard_cases.md,
after the table).

    python benches/micrometre_films.py             # the run table (≈ 4 min: crawls use their budget)
    python benches/micrometre_films.py damping     # F_ξ against ε̇ in the whirl, three films

Each run gets a wall-time budget (``--budget`` seconds, default 15); a run that uses it up is
reported with the time it reached. Starts: ``whirl`` (ε0 = 0.05) and ``wall`` (at rest at
ε0 = 0.99, the crank already at full speed).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import clearsim as cs
from clearsim import _core, models

REV = 60.0 / 5000.0  # one crank revolution [s]


def build(c: float, film: str, eps0: float) -> cs.Mechanism:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a µm long film warns when defined: this table is why
        m = models.slider_crank("lubricated", clearance=c, lubricated=cs.Lubricated(viscosity=0.4, length=0.04, film=film))
    m._clearance[0]["initial_eccentricity"] = [eps0 * c, 0.0]
    return m


def run(c: float, film: str, start: str, budget: float) -> str:
    m = build(c, film, 0.05 if start == "whirl" else 0.99)
    t0 = time.perf_counter()
    try:
        r = m.simulate(REV, dt_out=REV / 200, progress=False, max_seconds=budget)
        return f"finished in {r.stats['wall_time']:.2f} s, {r.stats['steps']} steps"
    except cs.SimulationError as e:
        why = "budget used up" if "wall-time" in str(e) else str(e).split(";")[0]
        return f"stopped at t = {e.t * 1e3:.3g} ms after {time.perf_counter() - t0:.1f} s ({why})"


def damping() -> None:
    rates = [-0.3, -0.2, -0.12, -0.06, -0.03, 0.0, 0.03]
    print("F_ξ [N] at ε = 0.046, wedge −4.8 rad/s, c = 1 µm, μ = 0.4 Pa·s, R = 9.5 mm, L = 40 mm\n")
    print("| film | " + " | ".join(f"ε̇ = {r:g} s⁻¹" for r in rates) + " |")
    print("|---" * (len(rates) + 1) + "|")
    for film in ("long", "short", "finite"):
        f = [_core.film_force(film, 0.4, 0.0095, 1e-6, 0.04, 0.046, r, -4.8)[0] for r in rates]
        print(f"| {film} | " + " | ".join(f"{x:,.0f}" for x in f) + " |")
    f = np.array([_core.film_force("long", 0.4, 0.0095, 1e-6, 0.04, 0.046, r, -4.8)[0] for r in (-0.3, -0.06)])
    print(f"\nlong film: dF_ξ/dė between ε̇ = −0.3 and −0.06 s⁻¹ = {(f[1] - f[0]) / 0.24 / 1e-6:.2g} N·s/m (negative damping)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", nargs="?", default="runs", choices=["runs", "damping"])
    ap.add_argument("--budget", type=float, default=15.0, help="wall-time budget of each run [s]")
    a = ap.parse_args()
    if a.what == "damping":
        damping()
        return
    print("| c [µm] | film | start | outcome |\n|---|---|---|---|")
    for c_um, film, start in [(1, "long", "whirl"), (2, "long", "whirl"), (3, "long", "whirl"), (5, "long", "whirl"), (1, "finite", "whirl"),
                              (2, "finite", "whirl"), (1, "short", "whirl"), (5, "long", "wall"), (3, "long", "wall"),
                              (1, "long", "wall"), (1, "finite", "wall"), (5, "finite", "wall"), (10, "finite", "wall"),
                              (20, "finite", "wall"), (5, "short", "wall"), (20, "short", "wall")]:  # fmt: skip
        print(f"| {c_um} | {film} | {start} | {run(c_um * 1e-6, film, start, a.budget)} |", flush=True)


if __name__ == "__main__":
    main()
