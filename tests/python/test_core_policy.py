"""The run policies the core owns (issue 29, "the Python layer is not thin"): which integrator
``integrator="auto"`` picks for a mechanism (rust/settings.rs, ``default_method``) and the output
grid of a spacing ``dt_out`` (``RunSettings::grid``, with its MAX_OUTPUTS check). Python passes
both through; these tests check what reaches the user: the resolved integrator's name, the same
output times as the grid Python used to build, and each bad setting named."""

from __future__ import annotations

import math
from pathlib import Path
from typing import List

import numpy as np
import pytest

import clearsim as cs
from clearsim import _core, models
from clearsim.batch import run_descriptions
from clearsim.scene import load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def driven() -> cs.Mechanism:
    """A driven crank: the cheapest run that records every output time asked for."""
    m = cs.Mechanism()
    m.add_body("crank", mass=1.0, inertia=0.01, position=(0.05, 0.0))
    m.revolute("ground", (0, 0), "crank", (-0.05, 0.0), name="pivot")
    return m.driver("crank", omega=0.1)


def old_python_grid(t0: float, t_end: float, dt_out: float) -> np.ndarray:
    """The grid ``Mechanism.run_settings`` built before the core did (same expression), of which a
    run recorded the times up to t_end (the core's filter in ``simulate``)."""
    n = int(math.floor((t_end - t0) / dt_out * (1 + 1e-12)))
    grid = t0 + dt_out * np.arange(n + 1)
    grid[-1] = min(grid[-1], t_end)  # a last point past t_end by rounding is t_end (the old run dropped it)
    return grid


# ------------------------------------------------------------------ integrator policy
def test_auto_is_decided_by_the_core_for_the_compiled_model():
    lub, dry = models.slider_crank("lubricated"), models.slider_crank("dry")
    assert _core.compile(lub.description()).default_integrator == "radau"
    assert _core.compile(dry.description()).default_integrator == "rk45"
    assert _core.compile(lub.idealized().description()).default_integrator == "rk45"
    assert (lub.default_integrator, dry.default_integrator) == ("radau", "rk45")
    # run_settings passes "auto" through; the run reports the method that ran.
    settings = lub.run_settings(2e-4)
    assert settings["integrator"] == "auto"
    raw = lub.compile().simulate(settings)
    assert raw["stats"]["integrator"] == "radau"
    assert driven().compile().simulate(driven().run_settings(0.01, integrator="rk4", step=1e-3))["stats"]["integrator"] == "rk4"


def test_result_says_which_integrator_ran():
    res = models.slider_crank("lubricated").simulate(2e-4, progress=False)
    assert res.stats["integrator"] == "radau" and "radau" in repr(res)
    assert "radau" in str(res.summary().get("integrator", res.stats["integrator"]))
    res, ideal = models.slider_crank("lubricated").simulate_with_ideal(2e-4)
    assert (res.stats["integrator"], ideal.stats["integrator"]) == ("radau", "rk45")


def test_a_batch_of_dry_and_lubricated_mechanisms_resolves_auto_per_mechanism():
    """One settings dict with ``"auto"`` shared by a dry and a lubricated mechanism: each runs
    with its own method, and each runs the same steps as when named explicitly."""
    dry, lub = models.slider_crank("dry"), models.slider_crank("lubricated")
    shared = dry.run_settings(2e-4)
    raws = run_descriptions([dry.description(), lub.description()], shared)
    assert [r["stats"]["integrator"] for r in raws] == ["rk45", "radau"]
    for m, raw, name in ((dry, raws[0], "rk45"), (lub, raws[1], "radau")):
        named = m.compile().simulate(m.run_settings(2e-4, integrator=name))
        assert raw["stats"]["steps"] == named["stats"]["steps"]
        assert np.array_equal(raw["q"], named["q"])


def test_auto_and_a_bad_name_through_the_api_and_a_scene_file(tmp_path):
    m = driven()
    assert m.simulate(0.01, integrator="auto", progress=False).stats["integrator"] == "rk45"
    with pytest.raises(cs.InputError) as info:
        m.simulate(0.01, integrator="euler", progress=False)
    assert info.value.field == "integrator" and "'euler'" in str(info.value) and "auto" in str(info.value)
    scene = load_scene_file(SCENES / "nine_bar_lubricated.toml")
    assert scene.simulation.integrator == "auto" and scene.mechanism.default_integrator == "radau"
    text = (SCENES / "slider_crank.toml").read_text(encoding="utf-8")
    assert 'integrator = "auto"' in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace('integrator = "auto"', 'integrator = "rk54"'), encoding="utf-8")
    with pytest.raises(cs.InputError) as info:
        load_scene_file(path)
    assert "integrator" in str(info.value) and "'rk54'" in str(info.value) and str(info.value).startswith(str(path))


# ------------------------------------------------------------------ output grid
def triples() -> List[tuple]:
    rng = np.random.default_rng(29)
    out = [(0.0, 0.3, 0.1), (0.0, 0.012, 0.012 / 200), (-0.2, 0.1, 0.01), (0.5, 0.7, 0.2 / 7), (1e3, 1e3 + 0.05, 1e-3), (0.0, 0.05, None)]
    for _ in range(300):
        t0 = float(rng.choice([0.0, -rng.random(), 100 * rng.random()]))
        span = float(10 ** rng.uniform(-3, 0))
        count = float(rng.choice([7.0, 10.0, 200.0, 3 + 500 * rng.random()]))
        dt = span / count if rng.random() < 0.5 else max(round(span / count, 4), 1e-4)
        out.append((t0, t0 + span, dt))
    return out


def test_output_times_are_the_grid_python_built_bit_for_bit():
    """The core builds the dt_out grid now; the times a run records are the floats the old
    Python grid gave (numpy's ``t0 + dt_out * arange(n + 1)``), bit for bit, except a last point
    past t_end by rounding, which is t_end (a run from 0 to 0.3 s at dt_out = 0.1 s ends at 0.3 s;
    it used to end at 0.2 s)."""
    m = driven()
    compiled = m.compile()
    for t0, t_end, dt in triples():
        settings = m.run_settings(t_end, t0=t0, dt_out=dt, outputs=["states"])
        assert "t_out" not in settings and settings.get("dt_out") == dt
        t = compiled.simulate(settings)["t"]
        want = old_python_grid(t0, t_end, (t_end - t0) / 1000.0 if dt is None else dt)
        assert t.shape == want.shape and np.array_equal(t.view(np.int64), want.view(np.int64)), (t0, t_end, dt)
    # Times given are kept as given (and dt_out is ignored then, as before).
    settings = m.run_settings(0.01, t_out=[0.0, 0.004, 0.01], dt_out=1.0)
    assert "dt_out" not in settings
    assert compiled.simulate(settings)["t"].tolist() == [0.0, 0.004, 0.01]


@pytest.mark.parametrize(
    "dt_out, words",
    [(0.0, "must be positive"), (-1e-3, "must be positive"), (math.nan, "must be a finite number"), (math.inf, "must be a finite number"),
     (1e-10, "gives 1e+08 outputs over [0.0, 0.01] s, more than 1e+07; choose a coarser grid")],
    ids=["zero", "negative", "nan", "inf", "too many outputs"],
)  # fmt: skip
def test_bad_dt_out_is_named_through_the_api(dt_out, words):
    with pytest.raises(cs.InputError) as info:
        driven().simulate(0.01, dt_out=dt_out, progress=False)
    err = info.value
    assert err.field == "dt_out" and f"invalid dt_out = {dt_out!r}: " in str(err) and words in str(err), str(err)
    assert cs.mechanism.MAX_OUTPUTS == 1e7


def test_too_many_outputs_counts_them_like_python_did():
    with pytest.raises(cs.InputError, match=r"invalid dt_out = 3e-09: gives 3\.33e\+07 outputs over \[0\.0, 0\.1\] s, more than 1e\+07"):
        driven().simulate(0.1, dt_out=3e-9, progress=False)


@pytest.mark.parametrize("value", ["0.0", "-0.001", "nan", "1e-12"])
def test_bad_dt_out_is_located_in_a_scene_file(tmp_path, value):
    text = (SCENES / "nine_bar.toml").read_text(encoding="utf-8")
    old = "dt_out = 2e-4"
    assert old in text
    path = tmp_path / "scene.toml"
    path.write_text(text.replace(old, f"dt_out = {value}"), encoding="utf-8")
    line = text[: text.index(old)].count("\n") + 1
    with pytest.raises(cs.InputError) as info:
        load_scene_file(path)
    msg = str(info.value)
    assert msg.startswith(f"{path}:{line}: ") and "dt_out" in msg, msg


def test_a_run_records_its_end_when_the_grid_lands_there_within_rounding():
    """0.1 × 3 = 0.30000000000000004 > 0.3: the run's last output is t_end = 0.3 s itself (it
    was 0.2 s, the final state dropped)."""
    res = driven().simulate(0.3, dt_out=0.1, progress=False)
    assert res.t.tolist() == [0.0, 0.1, 0.2, 0.3]
