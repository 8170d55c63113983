"""FORM's runs and answers: a two-sided limit state (the mirrored design point), noisy limit
states, and walk 5's feeder six-bar against the nominal design.

    python benches/form_runs.py rod        # rod length against the nominal slider-crank: both tails, closed form
    python benches/form_runs.py noisy      # noisy linear (2 inputs) and noisy curved (6 inputs) limit states
    python benches/form_runs.py feeder     # the feeder six-bar, 6 inputs, quarter-turn window: runs per search

``rod``: the ideal slider-crank (r = 50 mm, l0 = 120 mm) with a rod ~ N(l0, 1 mm) against its
nominal motion, limit 1.4 mm: it fails too short and too long; p_f = Φ((lo − l0)/σ) +
Φ(−(hi − l0)/σ) = 0.2031 closed form (tests/python/test_reliability_nominal.py). Prints each
design point, FORM's p_f and runs, and importance sampling's (CoV 0.1) after it.
``noisy``: the noisy linear limit states of tests/python/test_reliability_robust.py (noise 1e-3
on g, fresh or a fixed rough function, scales 1 and 5.5: β = 3.70999 exact) and
g = 3 − Σu_i/√6 + 0.05 u_1² + 1e-3 noise in 6 inputs (β = 3.06174, from SLSQP).
``feeder``: tests/data/scenes/feeder_six_bar.toml with the window of walk 5's quick run
(``skip_cycles = 0.25``, ``cycles = 0.25``, limit 0.2 mm, rtol 1e-5, atol 1e-8); every batch
FORM runs is printed (its size, |u| and g), then the answer.
"""

from __future__ import annotations

import math
import pathlib
import sys
import tempfile
import time
import warnings
from typing import Any

import numpy as np
from scipy import stats

from clearsim import reliability as rel

ROOT = pathlib.Path(__file__).resolve().parents[1]


def show(fr: Any) -> None:
    for name, m in zip(getattr(fr, "mode_names", ["g"]), getattr(fr, "modes", [fr])):
        print(f"  design point {name}: β = {m.beta:.4f}, {m.n_runs} runs, {m.iterations} iterations, σ_g = {m.noise:.2g}, u* = {np.round(m.design_point_u, 3)}")
    print(f"FORM p_f = {fr.pf:.4g} (β = {fr.beta:.4f}), {fr.n_runs} runs")


def rod() -> None:
    import clearsim

    r, l0, sigma, limit = 0.05, 0.12, 1e-3, 1.4e-3
    base = math.sqrt(l0**2 - r**2)
    hi, lo = math.sqrt((base + limit) ** 2 + r**2), math.sqrt((base - limit) ** 2 + r**2)
    exact = stats.norm.cdf((lo - l0) / sigma) + stats.norm.sf((hi - l0) / sigma)
    study = rel.Study(lambda rod: clearsim.models.slider_crank(joints="ideal", rod_length=rod), {"rod": rel.Normal(l0, sigma)},
                      rel.Output(body="slider", component="x"), rel.Limit(limit), reference="nominal", progress=False)  # fmt: skip
    print(f"closed form: tails at rod {lo * 1e3:.3f} and {hi * 1e3:.3f} mm, p_f = {exact:.4f}")
    fr = study.form()
    show(fr)
    res = study.importance_sampling(design_point=fr, cov=0.1, seed=0)
    print(f"importance sampling p_f = {res.pf:.4f} [{res.interval[0]:.4f}, {res.interval[1]:.4f}], {res.n_runs} runs, {res.extra['centres']} centres")


def noisy() -> None:
    sys.path.insert(0, str(ROOT / "tests" / "python"))
    from test_reliability_robust import BETA, noisy_linear

    warnings.simplefilter("ignore")
    for kind in ("random", "rough"):
        for scale in (1.0, 5.5):
            fr = noisy_linear(1e-3, scale, kind=kind).form()
            print(f"noisy linear, {kind}, scale {scale}: β = {fr.beta:.5f} ({100 * (fr.beta / BETA - 1):+.3f} % of {BETA:.5f}), {fr.n_runs} runs")
    rng = np.random.default_rng(0)

    def curved(x: Any) -> Any:
        return 3.0 - sum(x[k] for k in "abcdef") / math.sqrt(6.0) + 0.05 * x["a"] ** 2 + 1e-3 * rng.standard_normal(x["a"].size)

    fr = rel.LimitState(curved, {k: rel.Normal(0.0, 1.0) for k in "abcdef"}).form()
    print(f"noisy curved, 6 inputs: β = {fr.beta:.5f} ({100 * (fr.beta / 3.0617411 - 1):+.3f} % of 3.06174), {fr.n_runs} runs")


def feeder() -> None:
    from clearsim.scene import load_scene_file

    text = (ROOT / "tests" / "data" / "scenes" / "feeder_six_bar.toml").read_text(encoding="utf-8")
    for old, new in (("rtol = 1e-6", "rtol = 1e-5"), ("atol = 1e-9", "atol = 1e-8"), ("limit = 0.3e-3", "limit = 0.2e-3"),
                     ("skip_cycles = 1.0", "skip_cycles = 0.25"), ("cycles = 1.0", "cycles = 0.25")):  # fmt: skip
        if old not in text:
            raise SystemExit(f"feeder_six_bar.toml no longer has {old!r}: update this bench")
        text = text.replace(old, new, 1)
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "feeder_quick.toml"
        path.write_text(text, encoding="utf-8")
        study = load_scene_file(path).study_model(progress=False)
    plain = study.limit_state

    def traced(u: Any, on_failure: str = "fail") -> Any:
        g = plain(u, on_failure)
        u = np.atleast_2d(u)
        print(f"  batch of {u.shape[0]:2d}: |u| = {np.linalg.norm(u[0]):.4f}, g = {g[0]:+.5f}", flush=True)
        return g

    study.limit_state = traced  # type: ignore[method-assign]
    t = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fr = study.form()
    for w in caught:
        print(f"warning: {w.message}")
    show(fr)
    print(f"{time.perf_counter() - t:.1f} s")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "rod"
    {"rod": rod, "noisy": noisy, "feeder": feeder}.get(what, lambda: sys.exit(__doc__))()
