"""Reliability methods against closed forms (linear limit states with normal inputs), and the
simulation study against crude Monte Carlo and across output densities."""

import math

import numpy as np
import pytest
from scipy import special, stats

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError
from clearsim.reliability import Normal

ot = pytest.importorskip("openturns", reason="the rare-event methods need clearsim[uq]")

# g = a0 − a·x with independent normal x: β = (a0 − a·μ)/sqrt(Σ a_i² σ_i²), p_f = Φ(−β),
# Sobol S_i = a_i² σ_i² / Σ (first = total for an additive model).
A0, A, MU, SIG = 5.5, np.array([1.0, 2.0]), np.array([1.0, 0.5]), np.array([0.5, 0.4])
BETA = (A0 - A @ MU) / math.sqrt(np.sum((A * SIG) ** 2))
PF = float(special.ndtr(-BETA))


def linear() -> rel.LimitState:
    return rel.LimitState(lambda x: A0 - A[0] * x["a"] - A[1] * x["b"], {"a": rel.Normal(MU[0], SIG[0]), "b": rel.Normal(MU[1], SIG[1]), "k": 3.0})


def test_closed_form_reference_is_a_rare_event():
    assert 3.5 < BETA < 4.5 and 1e-5 < PF < 1e-3


def test_form_is_exact_for_a_linear_limit_state():
    fr = linear().form()
    assert fr.beta == pytest.approx(BETA, rel=1e-4)
    assert fr.pf == pytest.approx(PF, rel=1e-3)
    w = (A * SIG) ** 2 / np.sum((A * SIG) ** 2)
    assert fr.importance["a"] == pytest.approx(w[0], abs=1e-4) and fr.importance["b"] == pytest.approx(w[1], abs=1e-4)
    # The design point lies on g = 0.
    x = fr.design_point
    assert A0 - A[0] * x["a"] - A[1] * x["b"] == pytest.approx(0.0, abs=1e-4)
    assert fr.n_runs > 0


# A limit state that fails on both sides of the mean point (as a link length does against the
# nominal design): g = 2.2 − |a − 0.3|, a standard normal, b idle. Failure for a ≥ 2.5 or
# a ≤ −1.9: p_f = Φ(−2.5) + Φ(−1.9) exactly, the nearer side alone Φ(−1.9) = 82 % of it.
TWO_SIDED_PF = float(special.ndtr(-2.5) + special.ndtr(-1.9))


def two_sided() -> rel.LimitState:
    return rel.LimitState(lambda x: 2.2 - np.abs(x["a"] - 0.3) + 0.0 * x["b"], {"a": rel.Normal(0.0, 1.0), "b": rel.Normal(0.0, 1.0)})


def test_form_finds_the_second_side_of_a_two_sided_limit_state():
    """FORM converges on the nearer side (a = −1.9); g at the mirrored point a = 1.9 is 0.6 against
    1.9 at the mean, so a second search starts on that side and finds a = 2.5: the answer is the
    series system of the two design points (ρ = −1: the union's p_f is the sum), within 1e-3 of
    the closed form. On main FORM gave Φ(−1.9) = 0.0287 against 0.0349."""
    res = two_sided().form()
    assert isinstance(res, rel.SystemFormResult), res
    assert res.mirrored == [1] and res.mode_names == ["g", "g (mirrored)"]
    assert sorted(float(m.design_point["a"]) for m in res.modes) == pytest.approx([-1.9, 2.5], abs=1e-3)
    assert res.rho[0, 1] == pytest.approx(-1.0, abs=1e-6)
    assert res.pf == pytest.approx(TWO_SIDED_PF, rel=1e-3)
    assert res.bounds[0] <= res.pf * (1 + 1e-9) and res.pf <= res.bounds[1] * (1 + 1e-9)
    # Importance sampling around FORM's answer samples both sides (a mixture of two centres).
    is_ = rel.uq.importance_sampling(two_sided(), cov=0.05, seed=1)
    assert is_.extra["centres"] == 2
    assert is_.interval[0] <= TWO_SIDED_PF <= is_.interval[1], (is_.pf, is_.interval, TWO_SIDED_PF)


def test_the_mirrored_check_adds_nothing_to_a_one_sided_limit_state():
    """One run at −u*, nothing else, where the other side does not fail (the linear limit state:
    g rises towards −u*) or fails too rarely to count (g = min(3 − a, (a + 6)/2): the other side at
    a = −6 adds Φ(−6)/Φ(−3) = 7e-7 of p_f, below the 1 % share that starts a second search)."""
    plain, checked = linear(), linear()
    off = plain.form(mirror=False)
    on = checked.form()
    assert isinstance(on, rel.FormResult) and on.beta == off.beta
    assert checked.n_runs == plain.n_runs + 1
    far = rel.LimitState(lambda x: np.minimum(3.0 - x["a"], 0.5 * (x["a"] + 6.0)) + 0.0 * x["b"], {"a": rel.Normal(0.0, 1.0), "b": rel.Normal(0.0, 1.0)})
    res = far.form()
    assert isinstance(res, rel.FormResult) and res.beta == pytest.approx(3.0, rel=1e-4)
    assert far.n_runs == res.n_runs  # the check's run counted in the result's


def test_importance_sampling_reaches_its_cov_and_brackets_the_exact_pf():
    res = rel.uq.importance_sampling(linear(), cov=0.05, max_runs=50000, seed=1)
    assert res.cov <= 0.05
    assert res.interval[0] <= PF <= res.interval[1]
    assert res.n_runs < 5000  # crude MC would need ~4e5 runs for the same CoV


def test_subset_simulation_matches_the_exact_pf():
    res = rel.uq.subset(linear(), seed=2, n_per_level=2000)
    assert abs(res.pf - PF) < 3 * res.cov * PF
    assert res.n_runs >= 2000 * 3


def test_sobol_indices_of_an_additive_model():
    res = rel.uq.sobol(linear(), 4000, seed=3)
    w = (A * SIG) ** 2 / np.sum((A * SIG) ** 2)
    for i, k in enumerate("ab"):
        assert res.first[k] == pytest.approx(w[i], abs=0.05)
        assert res.total[k] == pytest.approx(w[i], abs=0.05)
    assert res.n_runs == 4000 * (2 + 2)


def test_tolerance_design_finds_the_closed_form_mean():
    # Largest mean of a with Φ(β) = R: μ_a = (a0 − a_b μ_b − Φ⁻¹(R)·s)/a_a, s = sqrt(Σ a²σ²).
    R = 0.999
    s = math.sqrt(np.sum((A * SIG) ** 2))
    exact = (A0 - A[1] * MU[1] - special.ndtri(R) * s) / A[0]
    res = rel.uq.tolerance(linear(), "a", R, bracket=(0.5, 6.0), cov=0.05, seed=4)
    assert res.form_value == pytest.approx(exact, abs=2e-3 * 5.5)
    assert res.interval[0] <= exact <= res.interval[1]
    assert res.n_runs > 0


def test_tolerance_bracket_that_does_not_straddle_is_named():
    with pytest.raises(InputError) as e:
        rel.uq.tolerance(linear(), "a", 0.999, bracket=(0.5, 1.0))
    assert e.value.field == "bracket"


def test_scipy_distributions_are_inputs():
    m = rel.LimitState(lambda x: 3.0 - x["w"], {"w": stats.weibull_min(2.0, scale=1.0)})
    fr = m.form()
    exact = stats.weibull_min(2.0, scale=1.0).sf(3.0)
    assert fr.pf == pytest.approx(exact, rel=0.3)  # FORM on a curved (non-normal) limit state
    res = rel.uq.importance_sampling(m, cov=0.05, seed=5, design_point=fr)
    assert res.interval[0] <= exact <= res.interval[1]


def test_inputs_map_through_the_standard_normal_space_exactly_in_the_tails():
    d = rel.LogNormal(1e-3, 2e-4)
    u = np.array([-8.0, -1.0, 0.0, 2.0, 8.0])
    x = d.from_standard_normal(u)
    assert np.allclose(d.to_standard_normal(x), u, atol=1e-8)
    assert np.allclose(x[1:4], d.dist.ppf(special.ndtr(u[1:4])), rtol=1e-12)
    assert x[-1] > x[-2] > 0  # the far upper tail kept (Φ(8) rounds to 1)


# ------------------------------------------------------------------ simulation study
OMEGA = -5 * math.pi  # nine-bar drive speed [rad/s]


def nine_bar(cA, cB):
    return clearsim.models.nine_bar("lubricated", {"A": cA, "B": cB})


def study(limit, quantity="displacement", cycles=0.25, **kw):
    return rel.Study(
        nine_bar,
        inputs={"cA": rel.Normal(0.5e-3, 0.05e-3), "cB": rel.Normal(0.5e-3, 0.05e-3)},
        output=rel.Output(body="slider9", component="y", quantity=quantity),
        limit=limit, omega=OMEGA, cycles=cycles, progress=False, **kw,
    )  # fmt: skip


def test_peak_comes_from_every_step_not_from_the_output_grid():
    st = study(1e-3, quantity="acceleration")
    ev, traces = st.evaluate({"cA": [0.55e-3], "cB": [0.45e-3]}, keep_traces=1)
    assert not ev.failures
    # A dense trace of the same run: its largest |error| can only be at most the tracked peak
    # (which also sees between samples), and close to it.
    m = nine_bar(0.55e-3, 0.45e-3)
    period = 2 * math.pi / abs(OMEGA)
    t = np.linspace(0, 0.25 * period, 3601)
    res, ideal = m.simulate_with_ideal(t[-1], t_out=t, outputs=["states", "accelerations"])
    dense = np.max(np.abs(res.error(ideal, "slider9", "acceleration")[:, 1]))
    assert dense <= ev.peaks[0] * (1 + 1e-3)
    assert dense >= 0.97 * ev.peaks[0]


def test_crude_monte_carlo_agrees_with_importance_sampling_on_a_moderate_event():
    st = study(0.75e-3)
    mc = st.monte_carlo(300, seed=0)
    assert 0.03 < mc.pf < 0.5, mc.pf
    is_ = st.importance_sampling(cov=0.1, seed=1)
    sd = math.hypot(mc.pf * mc.cov, is_.pf * is_.cov)
    assert abs(mc.pf - is_.pf) < 3 * sd, (mc.pf, is_.pf)
    fr = st.form()
    assert fr.importance["cA"] + fr.importance["cB"] == pytest.approx(1.0)


def test_joint_output_and_fosm_from_the_study():
    st = rel.Study(nine_bar, inputs={"cA": 0.5e-3, "cB": rel.Normal(0.5e-3, 0.02e-3)}, output=rel.Output(joint="B", quantity="eccentricity"), limit=0.99, omega=OMEGA, cycles=0.25, progress=False)
    ev, traces = st.evaluate({"cB": [0.5e-3]}, keep_traces=1)
    eps = traces[0].eccentricity("B")
    assert ev.peaks[0] >= eps.max() - 1e-9 and ev.peaks[0] < 1.0
    fo = study(4e-3, cycles=1.0).fosm(bin_width=18.0)
    assert fo.mu_S == pytest.approx(2e-3) and fo.sigma_S == pytest.approx(4e-3 / 6)
    assert np.all(np.isfinite(fo.reliability)) and len(fo.reliability) == 20


def test_failed_samples_are_counted_with_their_reason():
    def crank(r):
        return clearsim.models.slider_crank("dry", clearance=0.5e-3, crank_length=r)

    st = rel.Study(crank, inputs={"r": rel.Uniform(0.04, 0.2)}, output=rel.Output(body="slider", component="x"), limit=1.0, omega=2 * math.pi * 5000 / 60, cycles=0.2, progress=False, max_seconds=20)
    mc = st.monte_carlo(12, seed=0, on_failure="fail")
    r = mc.inputs["r"]
    failed = [k for k, _ in mc.failures]
    assert int(np.sum(r > 0.13)) >= 3 and set(np.flatnonzero(r > 0.13)) <= set(failed)
    assert all(r[k] > 0.12 for k in failed)  # a crank longer than its rod locks up
    assert all("step size underflow" in why or "lock" in why or "singular" in why for _, why in mc.failures)
    assert mc.pf == pytest.approx(len(mc.failures) / 12)  # nothing else exceeds 1 m
    ex = st.monte_carlo(12, seed=0, on_failure="exclude")
    assert ex.pf == 0.0 and ex.bounds == (0.0, len(ex.failures) / 12)
    with pytest.raises(clearsim.SimulationError):
        st.monte_carlo(12, seed=0, on_failure="raise")


def test_limits_and_outputs_are_required_and_named():
    with pytest.raises(InputError) as e:
        rel.Study(nine_bar, inputs={"cA": 1e-3, "cB": 1e-3}, output=rel.Output(body="slider9", component="y"), omega=OMEGA)
    assert e.value.field == "limit"
    with pytest.raises(InputError) as e:
        rel.Output(body="slider9")
    assert e.value.field == "Output.component"
    with pytest.raises(InputError) as e:
        rel.Output(joint="B", quantity="displacement")
    assert e.value.field == "Output.quantity"
    # omega defaults to the constant-speed driver (test_reliability_omega.py: none is an InputError).
    assert rel.Study(nine_bar, inputs={"cA": 1e-3, "cB": 1e-3}, output=rel.Output(body="slider9", component="y"), limit=1e-3).omega == OMEGA


def test_an_output_component_is_one_of_x_y_theta():
    with pytest.raises(clearsim.InputError, match="must be one of x, y, theta"):
        rel.Output(body="slider9", component="z")


def test_an_acceleration_output_does_not_depend_on_the_other_outputs_watched():
    """Each acceleration monitor refines its own worst point inside a step (one KKT solve) and
    keeps only its own value there: FOSM of outputs watched together in one run equals FOSM of
    each watched alone, bit for bit. Before, one monitor's refinement overwrote the others'
    estimates at its point, and the per-bin means moved by ~2e-5 relative with the company."""
    outs = [rel.Output(body=b, component=c, quantity="acceleration") for b, c in (("slider9", "y"), ("rod7", "x"), ("rocker6", "theta"))]

    def make(o, lim):
        return rel.Study(
            lambda cA, cB: clearsim.models.nine_bar("dry", {"A": cA, "B": cB}),
            inputs={"cA": rel.Normal(0.5e-3, 0.05e-3), "cB": rel.Normal(0.5e-3, 0.05e-3)},
            output=o, limit=lim, omega=OMEGA, cycles=0.5, progress=False,
        )  # fmt: skip

    together = make(outs, [1e4] * len(outs)).fosm_all()
    for k, o in enumerate(outs):
        alone = make(o, 1e4).fosm()
        np.testing.assert_array_equal(together[k].mu_s, alone.mu_s, err_msg=o.label)
        np.testing.assert_array_equal(together[k].sigma_s, alone.sigma_s, err_msg=o.label)


def test_normal_and_lognormal_inputs_stay_finite_far_in_the_tails():
    """``x = F⁻¹(Φ(u))`` of a Normal and a LogNormal input is the closed form at any u (mean + std u,
    exp(μ_ln + σ_ln u)). Before: Φ(u) rounded to 1 beyond u ≈ 38 and the input became inf, which a
    FORM step handed to the user's build (``clearance joint 'A'.clearance = inf``)."""
    from clearsim.reliability import LogNormal

    u = np.array([-50.0, -40.0, 0.0, 40.0, 50.0])
    assert np.allclose(Normal(40e-6, 4e-6).from_standard_normal(u), 40e-6 + 4e-6 * u, rtol=1e-14, atol=0.0)
    d = LogNormal(0.1, 0.01)
    mu, s = d.log_params
    assert np.allclose(d.from_standard_normal(u), np.exp(mu + s * u), rtol=1e-12, atol=0.0)


def test_form_of_a_series_system_with_a_mode_that_never_fails():
    """The toggle press's study, in miniature: a film mode that fails at β = −0.62 and a ram-error
    mode whose margin flattens out at g = 0.18 as the pin clearance grows (it never fails; its
    first HL-RF step from a slope of −0.0127 jumps to u ≈ 50). FORM keeps its search within
    |u| ≤ 37, reports the safe mode as β = 37 with a ReliabilityWarning, and the series p_f is the
    film mode's Φ(0.62); no input it asks for is non-finite. Before: the jump to u ≈ 50 made the
    clearance inf (then, with the closed-form transform, 50 iterations on at the tail), and the
    study stopped with the build's ``InputError``."""
    from clearsim.errors import ReliabilityWarning
    from clearsim.reliability import LimitState, LogNormal

    seen = []
    mu_ln, s_ln = LogNormal(0.1, 0.01).log_params

    def g(x):
        c, mu = x["c"], x["mu"]
        seen.append(np.concatenate([c, mu]))
        film = -0.0986 - 0.111 * (c - 40e-6) / 4e-6 + 0.0963 * (np.log(mu) - mu_ln) / s_ln  # linear in u
        ram = 0.18 + 0.46 * np.exp(-(c - 40e-6) / 145e-6)
        return [film, ram]

    model = LimitState(g, {"c": Normal(40e-6, 4e-6), "mu": LogNormal(0.1, 0.01)}, modes=["film", "ram"])
    with pytest.warns(ReliabilityWarning, match=r"not reached within \|u\| ≤ 37"):
        res = model.form()
    assert np.all(np.isfinite(np.concatenate(seen)))
    assert res.modes[1].beta == 37.0 and res.modes[1].pf < 1e-299
    assert res.modes[0].beta == pytest.approx(-0.0986 / math.hypot(0.111, 0.0963), rel=1e-3)
    assert res.pf == pytest.approx(res.modes[0].pf, rel=1e-9)


def test_form_alpha_is_a_unit_vector_off_the_surface() -> None:
    """α = u*/|u*| (β's sign): β carries the off-surface correction g/|∇g| of a point accepted at
    the noise level, so u*/β is no unit vector and series correlations α_i·α_j left [−1, 1]
    (the feeder's FORM report showed ρ₁₁ = 1.175, ρ₁₂ = −1.036)."""
    import numpy as np

    from clearsim.reliability.form import FormResult

    u = np.array([3.695, 0.4, -0.2])
    r = FormResult(beta=3.404, pf=3.3e-4, design_point={}, design_point_u=u, importance={}, n_runs=1, wall_time=0.0)
    assert np.linalg.norm(r.alpha) == pytest.approx(1.0, abs=1e-14)
    assert np.allclose(r.alpha, u / np.linalg.norm(u))
    r_neg = FormResult(beta=-1.0, pf=0.84, design_point={}, design_point_u=u, importance={}, n_runs=1, wall_time=0.0)
    assert np.allclose(r_neg.alpha, -u / np.linalg.norm(u))
