"""What the default tolerances buy: slider error after one cycle at default settings and at
tighter tolerances, against a DOP853 reference at rtol 1e-12, with the run time.

    python benches/default_accuracy.py

Prints a Markdown table (the README's "What the default tolerances buy"). The dry nine-bar is
chaotic (README, "Choosing an integrator"): its error is measured over the first 0.26 s only.
"""

from __future__ import annotations

import time

import numpy as np

from clearsim import models

CASES = {
    "slider-crank, dry": (lambda: models.slider_crank("dry"), "slider", 0.012, 0.012),
    "slider-crank, lubricated": (lambda: models.slider_crank("lubricated"), "slider", 0.012, 0.012),
    "nine-bar, dry": (lambda: models.nine_bar("dry"), "slider9", 0.4, 0.26),
    "nine-bar, lubricated": (lambda: models.nine_bar("lubricated"), "slider9", 0.4, 0.4),
}


def error(m, body: str, t_end: float, window: float, ref, **kw) -> tuple:
    t = np.linspace(0.0, window, 2001)
    t0 = time.perf_counter()
    r = m.simulate(t_end, t_out=t, progress=False, **kw)
    wall = time.perf_counter() - t0
    return float(np.max(np.abs(r.position(body)[:, :2] - ref.position(body)[:, :2]))), wall, r.stats["integrator"]


def main() -> None:
    print("| model | settings | method | max slider error [m] | of c | run [s] |")
    print("|---|---|---|---|---|---|")
    for name, (build, body, t_end, window) in CASES.items():
        m = build()
        c = m.description()["clearance_joints"][0]["clearance"]
        ref = m.simulate(t_end, t_out=np.linspace(0.0, window, 2001), integrator="dop853", rtol=1e-12, atol=1e-15, progress=False)
        for label, kw in [("default (rtol 1e-6)", {}), ("rtol 1e-8", dict(rtol=1e-8, atol=1e-11)), ("rtol 1e-10", dict(rtol=1e-10, atol=1e-13))]:
            err, wall, method = error(m, body, t_end, window, ref, **kw)
            print(f"| {name} | {label} | {method} | {err:.1e} | {err / c:.1e} | {wall:.3f} |")


if __name__ == "__main__":
    main()
