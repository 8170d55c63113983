"""Tests of clearsim.reliability: FOSM (paper P27–P32, docs/physics.md §6) and the Monte Carlo helpers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

import clearsim
from clearsim import InputError, models
from clearsim import reliability as rel
from clearsim.reliability import Normal, Output, Study

OMEGA = 5000 * 2 * math.pi / 60  # [rad/s] the slider-crank model's crank


def _dry(clearance: float) -> clearsim.Mechanism:
    return models.slider_crank("dry", clearance=clearance)


# ---------------------------------------------------------------------------------- FOSM basics
@pytest.mark.parametrize(
    "quantity, expected",
    [("displacement", (0.002, 0.0006667)), ("velocity", (0.3, 0.1)), ("acceleration", (100.0, 33.33))],
)
def test_paper_allowable_statistics(quantity, expected):
    # Spec §6: the paper's ranges give (0.002, 0.000667), (0.3, 0.1), (100, 33.33).
    mu, sigma = rel.allowable_statistics(*rel.PAPER_ALLOWABLE[quantity])
    assert mu == pytest.approx(expected[0], rel=1e-12)
    assert sigma == pytest.approx(expected[1], rel=1e-3)


def test_allowable_statistics_formula():
    # P31–P32 with a non-zero lower limit: μ_S = (5 + 1)/2 = 3, σ_S = (5 − 1)/6 = 2/3.
    assert rel.allowable_statistics(1.0, 5.0) == pytest.approx((3.0, 2.0 / 3.0))


def test_reliability_index_hand_computed():
    # μ_S = 0.3, σ_S = 0.1, μ_s = 0.06, σ_s = 0.075 → β = 0.24 / sqrt(0.01 + 0.005625) = 0.24 / 0.125 = 1.92
    assert rel.reliability_index(0.3, 0.1, 0.06, 0.075) == pytest.approx(1.92, rel=1e-12)
    beta = rel.reliability_index(0.3, 0.1, np.array([0.3, 0.06]), np.array([0.0, 0.075]))
    np.testing.assert_allclose(beta, [0.0, 1.92], rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(
    "beta, r_paper",
    # (β, R) pairs the paper reports in section 5 (read from a normal table, so ±1e-3).
    [(2.282, 0.9887), (0.484, 0.6861), (1.412, 0.9210), (-0.098, 0.4611), (2.864, 0.9980), (2.984, 0.9983),
     (2.419, 0.9922), (2.823, 0.9978), (1.358, 0.9127), (1.325, 0.9074), (1.027, 0.8471), (-0.6811, 0.2480),
     (1.431, 0.9226), (2.434, 0.9926), (2.834, 0.9977), (1.398, 0.9190), (1.635, 0.9489), (2.151, 0.9842)],
)
def test_normal_cdf_reproduces_paper_pairs(beta, r_paper):
    assert rel.normal_cdf(beta) == pytest.approx(r_paper, abs=1.5e-3)


def test_normal_cdf_and_ppf_against_scipy():
    x = np.linspace(-38.0, 8.0, 2001)
    np.testing.assert_allclose(rel.normal_cdf(x), stats.norm.cdf(x), rtol=1e-12, atol=1e-300)
    p = np.concatenate([np.logspace(-300, -1, 500), np.linspace(1e-3, 1 - 1e-3, 2001), 1.0 - np.logspace(-15, -1, 200)])
    np.testing.assert_allclose(rel.normal_ppf(p), stats.norm.ppf(p), rtol=1e-9, atol=1e-9)
    assert rel.normal_ppf(0.975) == pytest.approx(1.959963984540054, abs=1e-12)
    assert isinstance(rel.normal_ppf(0.3), float)
    assert rel.normal_ppf(0.0) == -math.inf and rel.normal_ppf(1.0) == math.inf
    # round trip
    np.testing.assert_allclose(rel.normal_cdf(rel.normal_ppf(p)), p, rtol=1e-12)


# ---------------------------------------------------------------------------------- binning
def test_fosm_hand_computed_bins():
    # Crafted displacement errors, allowable [0, 4 mm] → μ_S = 2 mm, σ_S = 4/6 mm.
    # bin [0, 18):   |e| = 1, 2, 3 mm  → μ_s = 2 mm, σ_s = sqrt(((1)² + 0 + (1)²)/3) mm = 0.8165 mm
    #                β = (2 − 2)/… = 0, R = 0.5
    # bin [18, 36):  |e| = 0.5, 0.5 mm (signs ignored) → μ_s = 0.5 mm, σ_s = 0
    #                β = (2 − 0.5)/(4/6) = 2.25, R = Φ(2.25) = 0.98777
    # bin [36, 54):  |e| = 1 mm once → β = (2 − 1)/(4/6) = 1.5, R = Φ(1.5) = 0.93319
    e = np.array([1e-3, -2e-3, 3e-3, 0.5e-3, -0.5e-3, 1e-3])
    a = np.array([0.0, 5.0, 17.9, 18.0, 30.0, 40.0])
    res = rel.fosm(e, a, (0.0, 0.004))
    assert res.bin_starts.shape == (20,)
    np.testing.assert_allclose(res.bin_starts[:3], [0.0, 18.0, 36.0])
    np.testing.assert_allclose(res.bin_centres[:3], [9.0, 27.0, 45.0])
    np.testing.assert_array_equal(res.count[:4], [3, 2, 1, 0])
    np.testing.assert_allclose(res.mu_s[:3], [2e-3, 0.5e-3, 1e-3], rtol=1e-12)
    np.testing.assert_allclose(res.sigma_s[:3], [math.sqrt(2 / 3) * 1e-3, 0.0, 0.0], rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(res.beta[:3], [0.0, 2.25, 1.5], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(res.reliability[:3], [0.5, 0.9877755273449553, 0.9331927987311419], rtol=1e-12)
    assert np.all(np.isnan(res.reliability[3:]))  # empty bins
    assert res.min_reliability == pytest.approx(0.5)
    assert res.min_angle == 0.0 and res.min_centre == 9.0 and res.min_beta == pytest.approx(0.0, abs=1e-12)
    rows = res.to_rows()
    assert rows[1]["angle_deg"] == 18.0 and rows[1]["beta"] == pytest.approx(2.25)
    assert set(rows[0]) >= {"angle_deg", "centre_deg", "mu_s", "sigma_s", "beta", "reliability", "mu_S", "sigma_S"}


def test_fosm_bins_of_piecewise_constant_signal():
    # |error| = a + b k in bin k (constant inside each bin, random sign) over 3 cycles:
    # μ_s = a + b k exactly, σ_s = 0, β_k = (μ_S − a − b k)/σ_S.
    rng = np.random.default_rng(1)
    ang = np.linspace(0.0, 3 * 360.0, 3 * 3600, endpoint=False)
    k = np.floor((ang % 360.0) / 18.0)
    a, b = 0.05, 0.01
    err = (a + b * k) * rng.choice([-1.0, 1.0], size=ang.size)
    res = rel.fosm(err, ang, "velocity")
    np.testing.assert_allclose(res.mu_s, a + b * np.arange(20), rtol=1e-12)
    np.testing.assert_allclose(res.sigma_s, 0.0, atol=1e-12)
    np.testing.assert_allclose(res.beta, (0.3 - a - b * np.arange(20)) / 0.1, rtol=1e-9)
    assert res.min_angle == 342.0  # largest error in the last bin
    assert np.all(res.count == 3 * 180)


def test_fosm_bin_mean_and_std_of_known_signal():
    # Within each bin |error| is uniform over a ramp of values: linear in angle from c_k to c_k + d.
    # With many evenly spaced samples, mean → c_k + d/2 and std → d/sqrt(12).
    n_per_bin = 20000
    ang = np.arange(20 * n_per_bin) * (18.0 / n_per_bin)
    k = np.floor(ang / 18.0)
    frac = (ang - 18.0 * k) / 18.0
    c = 10.0 + 5.0 * np.sin(np.radians(18.0 * k))
    d = 3.0
    err = c + d * frac
    res = rel.fosm(err, ang, (0.0, 200.0))
    ck = 10.0 + 5.0 * np.sin(np.radians(res.bin_starts))
    np.testing.assert_allclose(res.mu_s, ck + d / 2, rtol=1e-4)
    np.testing.assert_allclose(res.sigma_s, d / math.sqrt(12.0), rtol=1e-3)


def test_custom_bin_width_and_partial_last_bin():
    ang = np.arange(0.0, 360.0, 1.0)
    res = rel.fosm(np.full(ang.size, 1e-3), ang, "displacement", bin_width=25.0)
    assert len(res.bin_starts) == 15  # 14 full bins of 25° and a last one of 10°
    assert res.bin_starts[-1] == 350.0 and res.bin_centres[-1] == 355.0
    assert res.count[-1] == 10 and res.count[0] == 25


def test_per_cycle_minima_repeat_each_cycle():
    # Periodic |error| peaking at 200°: the minimum R sits in the 198° bin every cycle, like the
    # paper's 198°, 558°, 918° (Fig. 11a).
    ang = np.linspace(0.0, 3 * 360.0, 3 * 720, endpoint=False)
    err = 1e-3 * (1.2 + np.cos(np.radians(ang - 207.0))) * np.sign(np.sin(np.radians(7 * ang)) + 0.1)
    res = rel.fosm(err, ang, "displacement", per_cycle=True)
    assert res.min_angle == 198.0
    pc = res.per_cycle
    assert pc is not None and len(pc.bin_starts) == 60
    minima = pc.cycle_minima()
    assert [m["angle"] for m in minima] == [198.0, 558.0, 918.0]
    assert [m["cycle"] for m in minima] == [0, 1, 2]
    r = [m["reliability"] for m in minima]
    assert r[0] == pytest.approx(r[1], rel=1e-9) and r[1] == pytest.approx(r[2], rel=1e-9)
    assert r[0] == pytest.approx(res.min_reliability, rel=1e-9)
    assert pc.min_reliability == pytest.approx(res.min_reliability, rel=1e-9)


def test_edge_round_off_goes_to_the_bin_starting_there():
    # 18° computed through ω t may land at 17.999999999999996.
    ang = np.array([0.0, np.nextafter(18.0, 0.0), 18.0 + 1e-6])
    res = rel.fosm([1e-3, 2e-3, 2e-3], ang, "displacement")
    assert list(res.count[:2]) == [1, 2]


# ---------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(allowable=(0.004, 0.0)), "allowable.lower"),
        (dict(allowable=(0.001, 0.001)), "allowable.lower"),
        (dict(allowable=(0.0, float("nan"))), "allowable.upper"),
        (dict(allowable="torque"), "allowable"),
        (dict(bin_width=0.0), "bin_width"),
        (dict(bin_width=-18.0), "bin_width"),
        (dict(bin_width=float("nan")), "bin_width"),
        (dict(bin_width=400.0), "bin_width"),
        (dict(error=[1e-3, float("nan"), 0.0]), "error"),
        (dict(crank_angle=[0.0, 1.0]), "crank_angle"),
        (dict(crank_angle=[0.0, float("inf"), 2.0]), "crank_angle"),
        (dict(crank_angle=[0.0, 350.0, 10.0], per_cycle=True), "crank_angle"),
        (dict(error=[]), "error"),
    ],
)
def test_fosm_bad_input_names_field(kwargs, field):
    args = dict(error=[1e-3, 2e-3, 0.0], crank_angle=[0.0, 1.0, 2.0], allowable=(0.0, 0.004))
    args.update(kwargs)
    with pytest.raises(InputError) as info:
        rel.fosm(**args)
    assert info.value.field == field
    assert field.split(".")[0] in str(info.value)


def test_other_bad_inputs():
    with pytest.raises(InputError) as info:
        rel.allowable_statistics(1.0, 0.5)
    assert info.value.field == "allowable.lower" and info.value.value == 1.0
    with pytest.raises(InputError) as info:
        rel.normal_ppf(1.5)
    assert info.value.field == "p"
    with pytest.raises(InputError) as info:
        rel.normal_ppf(float("nan"))
    assert info.value.field == "p"
    with pytest.raises(InputError) as info:
        rel.reliability_index(1.0, -0.1, 0.0, 0.0)
    assert info.value.field == "sigma_S"
    with pytest.raises(InputError) as info:
        rel.wilson_interval(11, 10)
    assert info.value.field == "k"
    with pytest.raises(InputError) as info:
        rel.wilson_interval(1, 10, confidence=1.0)
    assert info.value.field == "confidence"
    with pytest.raises(InputError) as info:
        rel.first_passage_probability(np.ones((3, 4)), upper=0.0, lower=1.0)
    assert info.value.field == "lower"
    with pytest.raises(InputError) as info:
        rel.first_passage_probability(np.array([[0.0, np.nan]]), upper=1.0)
    assert info.value.field == "abs_errors"
    with pytest.raises(InputError) as info:
        rel.mc_bin_reliability(np.ones((3, 4)), np.arange(5.0), upper=2.0)
    assert info.value.field == "crank_angle_deg"
    with pytest.raises(InputError) as info:
        rel.mc_bin_reliability(np.ones((3, 4)), np.arange(4.0), upper=2.0, bin_width=0)
    assert info.value.field == "bin_width"
    with pytest.raises(InputError) as info:
        rel.Normal(0.0, -1.0)
    assert info.value.field == "Normal.std"
    with pytest.raises(InputError) as info:
        rel.Uniform(2.0, 1.0)
    assert info.value.field == "Uniform.low"
    with pytest.raises(InputError) as info:
        rel.LogNormal(0.0, 1.0)
    assert info.value.field == "LogNormal.mean"
    with pytest.raises(InputError) as info:
        rel.TruncatedNormal(0.0, 1.0, 1.0, 1.0)
    assert info.value.field == "TruncatedNormal.low"
    with pytest.raises(InputError) as info:
        rel.sample_inputs({"c": rel.Fixed(1.0)}, 0, seed=1)
    assert info.value.field == "n"


# ---------------------------------------------------------------------------------- distributions
def test_distributions_moments_and_reproducibility():
    dists = {
        "clearance": rel.LogNormal(5e-4, 5e-5),
        "length": rel.Normal(0.2, 0.001),
        "speed": rel.Uniform(4.0, 6.0),
        "friction": rel.TruncatedNormal(0.1, 0.05, 0.0, 0.15),
        "viscosity": rel.Fixed(0.4),
        "mass": 2.0,
    }
    n = 200_000
    s = rel.sample_inputs(dists, n, seed=7)
    assert set(s) == set(dists) and all(v.shape == (n,) for v in s.values())
    assert s["clearance"].mean() == pytest.approx(5e-4, rel=3e-3)
    assert s["clearance"].std() == pytest.approx(5e-5, rel=1e-2)
    assert np.all(s["clearance"] > 0)
    assert s["length"].mean() == pytest.approx(0.2, abs=2e-5) and s["length"].std() == pytest.approx(1e-3, rel=1e-2)
    assert s["speed"].min() >= 4.0 and s["speed"].max() < 6.0 and s["speed"].mean() == pytest.approx(5.0, abs=1e-2)
    tn = stats.truncnorm((0.0 - 0.1) / 0.05, (0.15 - 0.1) / 0.05, loc=0.1, scale=0.05)
    assert s["friction"].min() >= 0.0 and s["friction"].max() <= 0.15
    assert s["friction"].mean() == pytest.approx(tn.mean(), abs=3e-4)
    assert s["friction"].std() == pytest.approx(tn.std(), rel=1e-2)
    assert np.all(s["viscosity"] == 0.4) and np.all(s["mass"] == 2.0)
    # same seed → same samples, independent of the order and of the other inputs
    again = rel.sample_inputs({"speed": dists["speed"], "clearance": dists["clearance"]}, n, seed=7)
    np.testing.assert_array_equal(again["clearance"], s["clearance"])
    np.testing.assert_array_equal(again["speed"], s["speed"])
    other = rel.sample_inputs({"clearance": dists["clearance"]}, n, seed=8)
    assert not np.array_equal(other["clearance"], s["clearance"])


def test_truncated_normal_far_tail():
    # Interval [6σ, 7σ] above the mean: inverse-CDF sampling must stay inside and be precise.
    d = rel.TruncatedNormal(0.0, 1.0, 6.0, 7.0)
    x = d.sample(50_000, np.random.default_rng(3))
    assert x.min() >= 6.0 and x.max() <= 7.0
    assert x.mean() == pytest.approx(stats.truncnorm(6.0, 7.0).mean(), abs=3e-3)


# ---------------------------------------------------------------------------------- Wilson, MC
def test_wilson_interval_known_values():
    # Hand computation for k = 10, n = 100, 95 %: z = 1.959964, p̂ = 0.1,
    # centre = (0.1 + z²/200)/(1 + z²/100) = 0.119208/1.038415 = 0.114799,
    # half = z sqrt(0.0009 + z²/40000)/1.038415 = 0.059570 → [0.05523, 0.17437].
    lo, hi = rel.wilson_interval(10, 100)
    assert lo == pytest.approx(0.0552291, abs=1e-6) and hi == pytest.approx(0.1743657, abs=1e-6)
    # k = 0: lower bound exactly 0, upper z²/(n + z²)
    lo, hi = rel.wilson_interval(0, 50, 0.95)
    z2 = 1.959963984540054**2
    assert lo == 0.0 and hi == pytest.approx(z2 / (50 + z2), rel=1e-12)
    lo, hi = rel.wilson_interval(50, 50)
    assert hi == 1.0 and lo == pytest.approx(50 / (50 + z2), rel=1e-12)
    # arrays
    lo, hi = rel.wilson_interval(np.array([0, 10, 50]), 100)
    assert lo.shape == (3,) and np.all(lo <= np.array([0, 10, 50]) / 100) and np.all(hi >= np.array([0, 10, 50]) / 100)


def _x_times_g(n, seed, mu=0.5, sigma=1.0, step=1.0):
    """error = X g(t), X ~ N(mu, sigma²), g(t) = sin(θ) sampled every ``step`` degrees over one
    cycle (θ = 90° included, so max |g| = 1)."""
    rng = np.random.default_rng(seed)
    ang = np.arange(0.0, 360.0, step)
    g = np.sin(np.radians(ang))
    x = rng.normal(mu, sigma, n)
    return ang, g, x[:, None] * g[None, :]


def _p_abs_normal_exceeds(u, mu, sigma):
    """P(|X| > u) for X ~ N(mu, sigma²), exact."""
    return stats.norm.cdf((-u - mu) / sigma) + stats.norm.sf((u - mu) / sigma)


def test_first_passage_matches_exact_probability():
    u, mu, sigma = 1.5, 0.5, 1.0
    exact = _p_abs_normal_exceeds(u, mu, sigma)  # max_t |X g(t)| = |X|
    _, _, err = _x_times_g(20_000, seed=11, mu=mu, sigma=sigma, step=5.0)
    est = rel.first_passage_probability(err, upper=u, confidence=0.999)
    assert est.lo <= exact <= est.hi
    assert est.lo < est.p < est.hi
    p, lo, hi = est  # unpacks as a triple
    # The interval shrinks like 1/sqrt(n): width(4n)/width(n) ≈ 1/2.
    widths = []
    for n in (5_000, 20_000, 80_000):
        _, _, e = _x_times_g(n, seed=12, mu=mu, sigma=sigma, step=5.0)
        r = rel.first_passage_probability(e, upper=u)
        widths.append(r.hi - r.lo)
    assert widths[1] / widths[0] == pytest.approx(0.5, abs=0.05)
    assert widths[2] / widths[1] == pytest.approx(0.5, abs=0.05)


def test_first_passage_lower_limit():
    err = np.array([[0.5, 0.6, 0.7], [0.05, 0.6, 0.7], [0.5, 0.6, 1.1], [0.2, 0.2, 0.2]])
    est = rel.first_passage_probability(err, upper=1.0, lower=0.1)
    assert est.p == pytest.approx(0.5)  # rows 1 and 2 leave [0.1, 1.0]


def test_mc_bin_reliability_matches_exact_per_bin():
    u, mu, sigma, n = 0.9, 0.3, 0.6, 20_000
    ang, g, err = _x_times_g(n, seed=21, mu=mu, sigma=sigma)
    mc = rel.mc_bin_reliability(np.abs(err), ang, upper=u, confidence=0.999)
    assert len(mc.bin_starts) == 20 and np.all(mc.n_samples == n)
    for k in range(20):
        in_bin = (ang >= 18.0 * k) & (ang < 18.0 * (k + 1))
        gmax = np.abs(g[in_bin]).max()
        if gmax == 0.0:
            exact = 1.0
        else:  # P(|X| gmax ≤ u)
            exact = 1.0 - _p_abs_normal_exceeds(u / gmax, mu, sigma)
        assert mc.lo[k] <= exact <= mc.hi[k], (k, exact, mc.lo[k], mc.hi[k])
    # overall window reliability = 1 − first-passage probability
    exact_all = 1.0 - _p_abs_normal_exceeds(u, mu, sigma)
    assert mc.overall.lo <= exact_all <= mc.overall.hi
    # FOSM on the pooled samples: μ_s, σ_s of |X g| over the bin's samples
    k = 5
    in_bin = (ang >= 90.0) & (ang < 108.0)
    pooled = np.abs(err[:, in_bin])
    mu_S, sigma_S = rel.allowable_statistics(0.0, u)
    beta = (mu_S - pooled.mean()) / math.hypot(sigma_S, pooled.std())
    assert mc.fosm.beta[k] == pytest.approx(beta, rel=1e-9)
    rows = rel.compare_fosm_mc(mc)
    assert len(rows) == 20 and rows[k]["fosm_beta"] == pytest.approx(beta, rel=1e-9)
    assert {"angle_deg", "mc_R", "mc_lo", "mc_hi", "fosm_R", "fosm_in_ci"} <= set(rows[0])


def test_mc_bins_with_per_sample_angles_and_nominal_table():
    # Two samples at different speeds: each bin's n counts the samples that visit it.
    err = np.array([[0.0, 2.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]])
    ang = np.array([[0.0, 20.0, 40.0, 60.0], [0.0, 10.0, 20.0, 30.0]])
    mc = rel.mc_bin_reliability(err, ang, upper=1.0)
    np.testing.assert_array_equal(mc.n_samples[:4], [2, 2, 1, 1])
    np.testing.assert_allclose(mc.reliability[:4], [1.0, 0.5, 1.0, 1.0])
    assert np.isnan(mc.reliability[4])
    nominal = rel.fosm(err[1], ang[1], (0.0, 1.0))
    rows = rel.compare_fosm_mc(mc, nominal)
    assert rows[0]["nominal_R"] == pytest.approx(rel.normal_cdf(0.5 / (1 / 6)))
    with pytest.raises(InputError) as info:
        rel.compare_fosm_mc(mc, rel.fosm(err[1], ang[1], (0.0, 1.0), bin_width=30.0))
    assert info.value.field == "nominal"


def test_fosm_all_by_default_takes_the_outputs_fosm_applies_to():
    """``Study.fosm_all()`` on a series system of an error and a film thickness (a lower limit)
    analyses the error, bit for bit as ``fosm_all(outputs=[0])``; it analysed "every output" and
    so raised ``invalid output = 1`` for an output the user never named."""
    m_study = Study(lambda c: models.slider_crank("lubricated", clearance=c), {"c": Normal(0.5e-3, 0.01e-3)},
                    [Output(body="slider", component="x", quantity="displacement"), Output(joint="rod-slider", quantity="film_thickness")],
                    [1e-4, clearsim.reliability.Limit.below(1e-6)], cycles=0.25, progress=False)  # fmt: skip
    (res,) = m_study.fosm_all()
    (named,) = m_study.fosm_all(outputs=[0])
    np.testing.assert_array_equal(res.reliability, named.reliability)
    with pytest.raises(clearsim.InputError, match="lower limit"):
        m_study.fosm_all(outputs=[1])


def test_a_study_whose_build_does_not_take_an_input_says_so():
    """``Study(lambda cA: ..., {"cB": ...})`` (an input renamed in one place) is an InputError
    naming the inputs and build's parameters when the study is made, and a build that returns
    something else than a Mechanism one naming what it returned. Before: ``TypeError: <lambda>()
    got an unexpected keyword argument 'cB'``; ``AttributeError: 'tuple' object has no attribute
    'description'`` (or ``'check_assembly'``)."""
    with pytest.raises(clearsim.InputError, match=r"invalid inputs = \['cB'\]: build\(cA\) does not take them by name"):
        Study(lambda cA: _dry(cA), {"cB": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3, progress=False)
    for omega in (None, OMEGA):  # the nominal mechanism read at once, or first built by a method
        with pytest.raises(clearsim.InputError, match=r"invalid build: it returned a tuple, not a clearsim.Mechanism"):
            Study(lambda cA: (_dry(cA),), {"cA": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3, omega=omega, progress=False).fosm()
    study = Study(lambda cA, **rest: _dry(cA), {"cA": Normal(0.5e-3, 0.01e-3), "speed": 1.0}, Output(body="slider", component="x", quantity="displacement"), 1e-3, progress=False)
    assert study.omega == pytest.approx(OMEGA)
