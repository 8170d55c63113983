"""AK-IS and AK-MCS on the lubricated nine-bar's rare events against importance sampling (issue
31, item 5; issue 36, item 7; docs/reliability.md, "Few runs").

The README's study: peak |y error| of slider 9 over one crank cycle, clearances of A and B
independent N(0.5 mm, 0.05 mm); the limit 1.1 mm gives p_f ≈ 1e-4. For each limit, importance
sampling around the FORM design point to a CoV of 0.1 is the reference; AK-IS and AK-MCS get at
most 150 model runs each, called as a user would (``study.ak_mcs(max_runs=150)``: every other
setting its default). A method that raises is reported with its error. The last lines are a
Markdown table (event, FORM p_f, IS p_f, AK-MCS p_f, runs).

    python benches/ak_rare_event.py [limit_mm ...] [--mcs]     (about a minute an event on 2 cores)
"""

import math
import sys
import time
import warnings

import clearsim
from clearsim import reliability as rel

#: The README's rare event: p_f ≈ 1.1e-4 (limit in m; ``python benches/ak_rare_event.py 1.05`` for mm).
LIMIT = 1.1e-3


def build(cA, cB):
    return clearsim.models.nine_bar("lubricated", {"A": cA, "B": cB})


def study(limit: float = LIMIT) -> rel.Study:
    return rel.Study(
        build, inputs={"cA": rel.Normal(0.5e-3, 0.05e-3), "cB": rel.Normal(0.5e-3, 0.05e-3)},
        output=rel.Output(body="slider9", component="y", quantity="displacement"), limit=limit, omega=-5 * math.pi, cycles=1.0, progress=False,
    )  # fmt: skip


def show(name: str, r, wall: float, ref=None) -> None:
    ratio = f"  ×{r.pf / ref.pf:.3f} of IS" if ref is not None and ref.pf > 0 else ""
    print(f"{name:7s} p_f = {r.pf:.3e}  CoV = {r.cov:.3f}  95% [{r.interval[0]:.3e}, {r.interval[1]:.3e}]  runs = {r.n_runs}  {wall:.1f} s{ratio}")


def event(limit: float, mcs: bool) -> str:
    """Every method on one limit [m]; the table row."""
    print(f"--- limit {limit * 1e3:g} mm")
    st = study(limit)
    t = time.perf_counter()
    fr = st.form()
    is_ = st.importance_sampling(cov=0.1, design_point=fr, seed=0)
    wall = time.perf_counter() - t
    print(f"FORM    p_f = {fr.pf:.3e}  beta = {fr.beta:.3f}  runs = {fr.n_runs}")
    is_.n_runs += fr.n_runs
    show("IS", is_, wall)
    t = time.perf_counter()
    ak = study(limit).ak_is(max_runs=150, seed=0)
    show("AK-IS", ak, time.perf_counter() - t, is_)
    x = ak.extra
    print(f"        design {x['design_u'].shape[0]} points (FORM's, thinned), {x['iterations']} learning runs, population {x['population']}, "
          f"min U {x['min_u']:.2f}, surrogate bounds [{x['surrogate_bounds'][0]:.3e}, {x['surrogate_bounds'][1]:.3e}], noise σ_g {x['noise']:.2g}")
    row = f"| {limit * 1e3:g} mm | {fr.pf:.3e} | {is_.pf:.3e} |"
    if mcs:
        t = time.perf_counter()
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                mcs_ = study(limit).ak_mcs(max_runs=150, seed=0)
        except clearsim.ClearsimError as err:
            print(f"AK-MCS  {type(err).__name__}: {err}")
            return row + f" {type(err).__name__}: {str(err)[:60]}… | – |"
        show("AK-MCS", mcs_, time.perf_counter() - t, is_)
        x = mcs_.extra
        print(f"        {x['iterations']} learning runs, population {x['population']}, min U {x['min_u']:.2f}, surrogate bounds "
              f"[{x['surrogate_bounds'][0]:.3e}, {x['surrogate_bounds'][1]:.3e}], noise σ_g {x['noise']:.2g}, converged {x['converged']}")
        for w in caught:
            print(f"        warning: {w.message}")
        row += f" {mcs_.pf:.3e} (×{mcs_.pf / is_.pf:.2f}) | {mcs_.n_runs} |"
    return row


def main() -> None:
    limits = [float(a) * 1e-3 for a in sys.argv[1:] if not a.startswith("--")] or [LIMIT]
    rows = [event(limit, "--mcs" in sys.argv) for limit in limits]
    print("\n| event (limit) | FORM p_f | IS p_f (CoV 0.1) | AK-MCS p_f (× IS) | AK-MCS runs |\n|---|---|---|---|---|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
