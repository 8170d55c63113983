"""Rare events on the lubricated nine-bar with random clearances (issue: reliability).

Peak |y error| of slider 9 over one crank cycle against the ideal mechanism; clearances of
joints A and B independent normal N(0.5 mm, 0.05 mm). Prints FORM, importance sampling and
subset simulation (p_f, runs, wall time), the Sobol table and a tolerance answer.

    python benches/rare_events.py [limit_mm] [--quick]
"""

import math
import sys
import time

import numpy as np

import clearsim
from clearsim import reliability as rel


def build(cA, cB):
    return clearsim.models.nine_bar("lubricated", {"A": cA, "B": cB})


def main() -> None:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    limit = float(args[0]) * 1e-3 if args else 1.05e-3
    study = rel.Study(
        build,
        inputs={"cA": rel.Normal(0.5e-3, 0.05e-3), "cB": rel.Normal(0.5e-3, 0.05e-3)},
        output=rel.Output(body="slider9", component="y", quantity="displacement"),
        limit=limit, omega=-5 * math.pi, cycles=1.0, progress=False,
    )  # fmt: skip
    print(f"{study}  (2 cores: {clearsim._core.__name__})")
    t = time.perf_counter()
    fr = study.form()
    print(f"FORM      p_f = {fr.pf:.3e}  beta = {fr.beta:.3f}  runs = {fr.n_runs}  {time.perf_counter() - t:.1f} s  design point "
          + ", ".join(f"{k} = {v * 1e3:.4f} mm" for k, v in fr.design_point.items())
          + "  importance " + ", ".join(f"{k} {v:.2f}" for k, v in fr.importance.items()))
    t = time.perf_counter()
    is_ = study.importance_sampling(cov=0.1, design_point=fr, seed=0)
    print(f"IS        p_f = {is_.pf:.3e}  CoV = {is_.cov:.3f}  95% [{is_.interval[0]:.3e}, {is_.interval[1]:.3e}]  runs = {is_.n_runs} (+{fr.n_runs} FORM)  {time.perf_counter() - t:.1f} s")
    if not quick:
        t = time.perf_counter()
        ss = study.subset(seed=0, n_per_level=1000)
        print(f"subset    p_f = {ss.pf:.3e}  CoV = {ss.cov:.3f}  runs = {ss.n_runs}  {time.perf_counter() - t:.1f} s")
        t = time.perf_counter()
        sob = study.sobol(1000, seed=0)
        print(f"Sobol     ({sob.n_runs} runs, {time.perf_counter() - t:.1f} s)")
        for k in sob.first:
            print(f"  {k}: first {sob.first[k]:.3f} [{sob.first_interval[k][0]:.3f}, {sob.first_interval[k][1]:.3f}]  total {sob.total[k]:.3f} [{sob.total_interval[k][0]:.3f}, {sob.total_interval[k][1]:.3f}]")
    t = time.perf_counter()
    tol = study.tolerance("cB", reliability=0.9999, bracket=(0.3e-3, 0.6e-3), cov=0.1)
    print(f"tolerance largest mean c_B for R = 0.9999: {tol.value * 1e3:.4f} mm, 95% [{tol.interval[0] * 1e3:.4f}, {tol.interval[1] * 1e3:.4f}] mm "
          f"(FORM {tol.form_value * 1e3:.4f} mm; IS check p_f = {tol.check.pf:.2e} ± {tol.check.cov:.2f})  runs = {tol.n_runs}  {time.perf_counter() - t:.1f} s")


if __name__ == "__main__":
    main()
