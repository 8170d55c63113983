"""Errors against the nominal design's motion (``Study(reference="nominal")``, issue 36 item 3):
a link-length tolerance moves the output away from the nominal motion, which a study measured
against each sample's own ideal twin cannot see. Checked on the ideal slider-crank (no
clearance: the own-ideal error is the integration error alone), whose slider position is
x(θ) = r cos θ + sqrt(l² − r² sin² θ): with a rod of length l instead of l0 it is off by
sqrt(l² − r² sin² θ) − sqrt(l0² − r² sin² θ), largest at sin² θ = 1 (θ = 90°, inside a whole
crank cycle), so the peak error is |sqrt(l² − r²) − sqrt(l0² − r²)| exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError

R, L0, SIGMA = 0.05, 0.12, 1e-3


def _slider_crank(rod: float) -> clearsim.Mechanism:
    return clearsim.models.slider_crank(joints="ideal", rod_length=rod)


def _peak(rod: np.ndarray) -> np.ndarray:
    """The closed form of the peak slider error against the nominal rod L0."""
    return np.abs(np.sqrt(rod**2 - R**2) - math.sqrt(L0**2 - R**2))


def _study(reference: str, limit: float = 1.4e-3) -> rel.Study:
    return rel.Study(_slider_crank, {"rod": rel.Normal(L0, SIGMA)}, rel.Output(body="slider", component="x"), rel.Limit(limit), reference=reference, progress=False)


def test_a_link_length_counts_against_the_nominal_motion_only():
    rods = np.array([L0 - 2e-3, L0, L0 + 0.7e-3, L0 + 3e-3])
    own = _study("own_ideal").evaluate({"rod": rods})[0].peaks
    nominal = _study("nominal").evaluate({"rod": rods})[0].peaks
    assert np.all(own < 1e-6), own  # the sample against its own ideal twin: integration error only (rtol 1e-6)
    np.testing.assert_allclose(nominal, _peak(rods), rtol=2e-4, atol=2e-7)
    assert nominal[1] < 1e-6  # the nominal sample is its own reference


def test_monte_carlo_on_a_normal_link_length_matches_the_closed_form():
    limit = 1.4e-3
    mc = _study("nominal", limit).monte_carlo(300, seed=3)
    rods = mc.inputs["rod"]
    np.testing.assert_allclose(mc.peaks, _peak(rods), rtol=2e-4, atol=2e-7)
    # p_f = P(|sqrt(l² − r²) − sqrt(l0² − r²)| > limit) for l ~ N(l0, σ): two tails.
    base = math.sqrt(L0**2 - R**2)
    hi, lo = math.sqrt((base + limit) ** 2 + R**2), math.sqrt((base - limit) ** 2 + R**2)
    exact = stats.norm.cdf((lo - L0) / SIGMA) + stats.norm.sf((hi - L0) / SIGMA)
    assert mc.pf == pytest.approx(np.mean(_peak(rods) > limit), abs=1 / 300)
    assert mc.interval[0] <= exact <= mc.interval[1], (mc.pf, mc.interval, exact)
    assert _study("own_ideal", limit).monte_carlo(50, seed=3).pf == 0.0


def _tails(limit: float) -> tuple:
    """The rod lengths [m] at which the peak error reaches ``limit``: too long, too short."""
    base = math.sqrt(L0**2 - R**2)
    return math.sqrt((base + limit) ** 2 + R**2), math.sqrt((base - limit) ** 2 + R**2)


def test_form_and_importance_sampling_find_both_tails_of_the_closed_form():
    """The rod fails too long and too short: FORM's mirrored check finds the second design point
    and answers the union of the two tails, p_f = Φ((lo − l0)/σ) + Φ(−(hi − l0)/σ) = 0.203 (the
    first-order answer is exact here but for the search's tolerance); importance sampling around
    both design points brackets it. On main FORM gave the nearer tail alone."""
    limit = 1.4e-3
    study = _study("nominal", limit)
    hi, lo = _tails(limit)
    exact = stats.norm.cdf((lo - L0) / SIGMA) + stats.norm.sf((hi - L0) / SIGMA)
    res = study.form()
    assert isinstance(res, rel.SystemFormResult) and res.mirrored == [1], res
    rods = sorted(m.design_point["rod"] for m in res.modes)
    assert rods == pytest.approx([lo, hi], abs=0.02 * SIGMA)
    assert res.pf == pytest.approx(exact, rel=2e-2)
    is_ = study.importance_sampling(design_point=res, cov=0.1, seed=0)
    assert is_.extra["centres"] == 2
    assert is_.interval[0] <= exact <= is_.interval[1], (is_.pf, is_.interval, exact)


def test_a_build_with_other_bodies_than_its_nominal_is_named():
    def build(rod: float) -> clearsim.Mechanism:
        m = _slider_crank(rod)
        if rod > L0:
            m.add_body("extra", mass=0.01, inertia=1e-6, position=(0.3, 0.0))
            m.revolute("ground", (0.3, 0.0), "extra", (0.0, 0.0), name="extra-pin")
        return m

    study = rel.Study(build, {"rod": rel.Normal(L0, SIGMA)}, rel.Output(body="slider", component="x"), rel.Limit(1e-3), reference="nominal", progress=False)
    with pytest.raises(InputError, match="extra"):
        study.evaluate({"rod": [L0 + 1e-3]})
    with pytest.raises(InputError, match="reference"):
        rel.Study(build, {"rod": rel.Normal(L0, SIGMA)}, rel.Output(body="slider", component="x"), rel.Limit(1e-3), reference="ideal")


def test_the_core_refuses_a_nominal_with_other_bodies():
    # Straight through the batch: the sample's error names the bodies only one side has.
    from clearsim import _core

    sample, nominal = _slider_crank(L0), clearsim.models.slider_crank(joints="ideal")
    nominal.add_body("extra", mass=0.01, inertia=1e-6, position=(0.3, 0.0))
    nominal.revolute("ground", (0.3, 0.0), "extra", (0.0, 0.0), name="extra-pin")
    s = sample.run_settings(0.01, t_out=[0.0, 0.01], outputs=["states"])
    s["reference"] = {"t_start": 0.0, "t_end": 0.01, "intervals": 100}
    s["monitors"] = [{"coordinate": 6, "quantity": "displacement", "t_start": 0.0, "bin_width": 0.01, "reference": "nominal"}]
    (out,) = _core.run_batch([sample.description()], [s], 1, nominal.description())
    assert isinstance(out, InputError) and "'extra' only in the reference" in str(out), out
    (out,) = _core.run_batch([sample.description()], [s], 1)
    assert isinstance(out, InputError) and "no nominal mechanism" in str(out), out


SCENE_STUDY = """
[study]
reference = "{reference}"
cycles = 0.25
methods = ["monte_carlo"]
samples = 4

[[study.output]]
body = "slider"
component = "x"
quantity = "displacement"
limit = 1e-3

[[study.output]]
body = "rod"
point = [0.02, 0.03]
component = "magnitude"
quantity = "velocity"
limit = 1.0

[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3
std = 0.02e-3
"""


def _scene(tmp_path, reference: str):
    from pathlib import Path

    from clearsim.scene import load_scene_file

    text = (Path(__file__).resolve().parents[2] / "scenes" / "slider_crank.toml").read_text(encoding="utf-8")
    file = tmp_path / "study.toml"
    file.write_text(text + SCENE_STUDY.format(reference=reference), encoding="utf-8")
    return file, load_scene_file


def test_a_scene_names_its_reference_and_point_outputs(tmp_path):
    file, load = _scene(tmp_path, "nominal")
    study = load(file).study_model(progress=False)
    assert study.reference == "nominal"
    assert study.outputs[1] == rel.Output(body="rod", point=(0.02, 0.03), component="magnitude", quantity="velocity")
    file, load = _scene(tmp_path, "nominals")
    with pytest.raises(InputError, match="reference") as info:
        load(file)
    assert getattr(info.value, "line", None)


def test_the_command_line_says_which_reference(tmp_path, capsys):
    from clearsim.cli import main

    file, _ = _scene(tmp_path, "own_ideal")
    out = tmp_path / "out"
    assert main(["reliability", str(file), "-o", str(out), "--no-plots", "--reference", "nominal"]) == 0
    printed = capsys.readouterr().out
    assert "nominal design's ideal motion" in printed
    assert '`reference = "nominal"`' in (out / "report.md").read_text(encoding="utf-8")
