"""AK-IS (and optionally AK-MCS) on the lubricated nine-bar's rare event against importance
sampling (issue 31, item 5; docs/reliability.md, "Few runs").

The README's study: peak |y error| of slider 9 over one crank cycle, limit 1.1 mm,
clearances of A and B independent N(0.5 mm, 0.05 mm): p_f ≈ 1e-4. Importance sampling
around the FORM design point to a CoV of 0.1 is the reference; AK-IS gets at most 150 model
runs, its own FORM included.

    python benches/ak_rare_event.py [limit_mm] [--mcs]     (about a minute on 2 cores; --mcs adds AK-MCS)
"""

import math
import sys
import time

import clearsim
from clearsim import reliability as rel

#: The README's rare event: p_f ≈ 1.1e-4 (limit in m; ``python benches/ak_rare_event.py 1.05`` for mm).
LIMIT = 1.1e-3


def build(cA, cB):
    return clearsim.models.nine_bar("lubricated", {"A": cA, "B": cB})


def study() -> rel.Study:
    return rel.Study(
        build, inputs={"cA": rel.Normal(0.5e-3, 0.05e-3), "cB": rel.Normal(0.5e-3, 0.05e-3)},
        output=rel.Output(body="slider9", component="y", quantity="displacement"), limit=LIMIT, omega=-5 * math.pi, cycles=1.0, progress=False,
    )  # fmt: skip


def show(name: str, r, wall: float, ref=None) -> None:
    ratio = f"  ×{r.pf / ref.pf:.3f} of IS" if ref is not None and ref.pf > 0 else ""
    print(f"{name:7s} p_f = {r.pf:.3e}  CoV = {r.cov:.3f}  95% [{r.interval[0]:.3e}, {r.interval[1]:.3e}]  runs = {r.n_runs}  {wall:.1f} s{ratio}")


def main() -> None:
    global LIMIT
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if args:
        LIMIT = float(args[0]) * 1e-3
    st = study()
    t = time.perf_counter()
    fr = st.form()
    is_ = st.importance_sampling(cov=0.1, design_point=fr, seed=0)
    wall = time.perf_counter() - t
    print(f"FORM    p_f = {fr.pf:.3e}  beta = {fr.beta:.3f}  runs = {fr.n_runs}")
    is_.n_runs += fr.n_runs
    show("IS", is_, wall)
    t = time.perf_counter()
    ak = study().ak_is(max_runs=150, seed=0)
    show("AK-IS", ak, time.perf_counter() - t, is_)
    x = ak.extra
    print(f"        design {x['design_u'].shape[0]} points (FORM's, thinned), {x['iterations']} learning runs, population {x['population']}, "
          f"min U {x['min_u']:.2f}, surrogate bounds [{x['surrogate_bounds'][0]:.3e}, {x['surrogate_bounds'][1]:.3e}], noise σ_g {x['noise']:.2g}")
    if "--mcs" in sys.argv:
        t = time.perf_counter()
        mcs = study().ak_mcs(max_runs=150, seed=0, cov=0.1, max_population=1_000_000)
        show("AK-MCS", mcs, time.perf_counter() - t, is_)
        x = mcs.extra
        print(f"        {x['iterations']} learning runs, population {x['population']}, min U {x['min_u']:.2f}, surrogate bounds "
              f"[{x['surrogate_bounds'][0]:.3e}, {x['surrogate_bounds'][1]:.3e}], noise σ_g {x['noise']:.2g}, converged {x['converged']}")


if __name__ == "__main__":
    main()
