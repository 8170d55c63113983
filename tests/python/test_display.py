"""Short reprs and notebook displays (issue 28 item 8): every result class prints its key numbers
in a line (arrays by shape, never their values), shows a small HTML table in a notebook, and a
Mechanism shows its drawing."""

from __future__ import annotations

import numpy as np
import pytest

from clearsim import display, models
from clearsim.reliability import fosm, mc_bin_reliability
from clearsim.reliability.study import Evaluation, MonteCarloEstimate
from clearsim.reliability.uq import FormResult, SamplingResult, SobolResult, ToleranceResult

N = 2000  # samples: numpy would print every one of them (and more lines than a screen)
MAX = 400  # characters of a repr


def _check(obj, *numbers: str) -> str:
    text = repr(obj)
    assert len(text) <= MAX and "\n" not in text, text
    assert "array([" not in text and "..." not in text, text
    for n in numbers:
        assert n in text, (n, text)
    html = obj._repr_html_()
    assert html.startswith("<table") and "</table>" in html and html.count("<tr>") >= 3
    for n in numbers:
        assert n in html, (n, html)
    return text


def _mc_estimate() -> MonteCarloEstimate:
    rng = np.random.default_rng(1)
    peaks = rng.random(N)
    return MonteCarloEstimate(
        pf=0.0125, interval=(0.0081, 0.0192), cov=0.089, n_runs=N, failures=[(3, "step size underflow at t = 0.01 s"), (7, "x")],
        peaks=peaks, first_passage_times=np.full(N, np.nan), inputs={"B.clearance": rng.random(N), "A.clearance": rng.random(N)},
        on_failure="fail", bounds=(0.0115, 0.0125), wall_time=12.5, traces=[],
    )  # fmt: skip


def test_monte_carlo_estimate_prints_its_numbers_not_its_arrays():
    text = _check(_mc_estimate(), "0.0125", "0.0081", "0.0192", str(N))
    assert "failures=2" in text and f"peaks=array({N},)" in text and f"B.clearance: array({N},)" in text


def test_reliability_results():
    u = np.zeros(2)
    _check(FormResult(beta=2.326, pf=0.01, design_point={"A.clearance": 6.1e-4, "B.clearance": 5.5e-4}, design_point_u=u,
                      importance={"A.clearance": 0.8, "B.clearance": 0.2}, n_runs=37, wall_time=3.0), "2.326", "0.01", "37")  # fmt: skip
    _check(SamplingResult(pf=3.2e-4, cov=0.1, interval=(2.6e-4, 3.8e-4), n_runs=1280, wall_time=9.0, method="importance sampling",
                          design_point_u=np.zeros(N)), "0.00032", "0.00026", "1280")  # fmt: skip
    _check(SobolResult(first={"A": 0.7, "B": 0.2}, total={"A": 0.78, "B": 0.25}, first_interval={"A": (0.6, 0.8), "B": (0.1, 0.3)},
                       total_interval={"A": (0.7, 0.9), "B": (0.2, 0.3)}, n_runs=2000, wall_time=1.0), "0.78", "2000")  # fmt: skip
    _check(ToleranceResult(name="B.clearance", value=4.9e-4, interval=(4.8e-4, 5.0e-4), reliability=0.9999, form_value=4.85e-4,
                           check=None, history=[(5e-4, 3.0)] * 50, n_runs=250, wall_time=30.0), "0.00049", "0.9999", "250")  # fmt: skip
    _check(Evaluation(values=np.ones((N, 1)), first_passage=np.ones((N, 1)), failures=[(1, "x")]), f"array({N},)")


def test_fosm_and_monte_carlo_bins():
    angle = np.linspace(0.0, 360.0, N, endpoint=False)
    err = 1e-3 * np.sin(np.radians(angle)) ** 2
    res = fosm(err, angle, (0.0, 2e-3))
    _check(res, f"{res.min_reliability:.4g}", f"{res.min_angle:.4g}")
    bins = mc_bin_reliability(np.abs(err)[None, :].repeat(20, axis=0), angle, upper=2e-3)
    _check(bins, "0.002", "20")


def test_monte_carlo_result_and_result():
    from clearsim import monte_carlo

    m = models.slider_crank("dry")
    r = m.simulate(0.004, dt_out=1e-5, progress=False)
    text = _check(r, "401", "rk45")
    assert text.startswith("<clearsim.Result")
    from clearsim.reliability import Normal

    mc = monte_carlo(lambda clearance: models.slider_crank("dry", clearance=clearance), {"clearance": Normal(5e-4, 2e-5)}, 3, body="slider",
                     component="x", allowable={"displacement": (0.0, 1e-3)}, omega=523.6, cycles=1.0, seed=0, points_per_cycle=400)  # fmt: skip
    _check(mc, "samples", "completed", "p_f displacement")


def test_short_values():
    assert display.short(np.arange(1e6)) == "array(1000000,)"
    assert display.short({"a": np.ones(3), "b": 2.0}) == "{a: array(3,), b: 2}"
    assert display.short([(1, "why")] * 1000) == "[1000 items]"
    assert display.short(1.23456789e-5) == "1.235e-05"


def test_mechanism_repr_and_drawing():
    m = models.nine_bar("dry")
    text = repr(m)
    assert len(text) <= MAX and "8 bodies" in text and "A dry" in text and "B dry" in text
    png = m._repr_png_()
    assert png is not None and png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
    # A mechanism that does not assemble shows its text only (no exception in the notebook).
    broken = m.copy()
    broken._joints[0]["point_a"] = [50.0, 0.0]
    broken._changed()  # (changed behind the API's back: forget the cached description)
    assert broken._repr_png_() is None and repr(broken).startswith("<clearsim.Mechanism")


@pytest.mark.parametrize("name", ["FosmResult", "MonteCarloBins", "MonteCarloEstimate", "FormResult", "SamplingResult", "SobolResult", "ToleranceResult", "Evaluation", "MonteCarloResult", "Result"])
def test_every_result_class_defines_its_displays(name):
    import clearsim.montecarlo as mc
    import clearsim.reliability.estimates as es
    import clearsim.reliability.fosm as fo
    import clearsim.reliability.study as st
    import clearsim.reliability.uq as uq
    import clearsim.result as rs

    cls = next(getattr(mod, name) for mod in (mc, es, fo, st, uq, rs) if hasattr(mod, name))
    assert "_repr_html_" in vars(cls) and ("__repr__" in vars(cls))


def test_figures_display_as_pictures_without_pyplot():
    """A notebook shows clearsim's figures as PNG pictures in a fresh kernel: IPython's display
    (a formatter with no printer registered for matplotlib figures, as before pyplot is imported)
    finds a picture, not only '<Figure size 600x500 with 1 Axes>'."""
    from IPython.core.formatters import DisplayFormatter

    from clearsim import plots

    m = models.slider_crank("dry")
    r = m.simulate(0.004, dt_out=1e-4, progress=False)
    e = r.eccentricity("rod-slider")
    formatter = DisplayFormatter()
    for fig in (m.plot(), r.plot_mechanism(0.002), plots.plot_journal_orbits({"rod-slider": (e[:, 0], e[:, 1])}, clearance=5e-4)):
        data, _ = formatter.format(fig)
        assert data.get("image/png", b"")[:8] == b"\x89PNG\r\n\x1a\n", list(data)


def test_a_film_pressure_prints_its_numbers_not_its_field():
    """``res.pressure(joint, t)`` (walk 6: a pump's big end) printed its θ × z field, 120 × 41
    numbers over hundreds of lines; now one line with the time, the peak and the flows, arrays by
    their shape, and a small table in a notebook."""
    import clearsim

    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", omega=100.0)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=0.02, clearance=4e-5, model=clearsim.Lubricated(viscosity=0.05, length=0.02, film="short"))
    m.force("rotor", (0, 0), (0.0, -400.0))
    field = m.simulate(0.01, dt_out=1e-3, progress=False).pressure("pin", 0.01)
    text = _check(field, "pin", f"{field.peak_pressure:.4g}", "array(")
    assert text.startswith("FilmPressure(")
