"""Reliability over life (clearsim.reliability.life): cycle jumping and p_f against cycles on mock
block runners whose life has a closed form, and a short real life of a dry slider-crank."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from clearsim.errors import InputError
from clearsim.reliability.life import BlockOutcome, life


class LinearWear:
    """Wear state w grows by ``b`` per cycle whatever it is; the peak is w + σ u: failure when
    w + σ u > a, so after N cycles p_f(N) = Φ((b N − a)/σ)."""

    settle_cycles = 0.0
    window_cycles = 1.0
    state_size = 1
    depth_scale = 1.0

    def __init__(self, b: float, sigma: float) -> None:
        self.b, self.sigma, self.calls = b, sigma, 0

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        self.calls += 1
        w = wear[:, 0]
        return BlockOutcome(w + self.sigma * u[:, 0], wear.copy(), wear + self.b * self.window_cycles)


class GrowingWear(LinearWear):
    """dw/dN = b (1 + w / w0): w(N) = w0 (e^{b N / w0} − 1) (the worn clearance speeds wear up)."""

    def __init__(self, b: float, w0: float) -> None:
        super().__init__(b, 0.0)
        self.w0 = w0

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        self.calls += 1
        w = wear[:, 0]
        rate = self.b * (1.0 + w / self.w0)  # over one cycle: small against w0 / b
        return BlockOutcome(w.copy(), wear.copy(), wear + rate[:, None] * self.window_cycles)


def test_linear_wear_gives_the_closed_form_pf_over_life():
    a, b, sigma, n = 1.0, 1e-3, 0.2, 20000
    u = np.random.default_rng(1).standard_normal((n, 1))
    cycles = [0, 200, 500, 800, 1000, 1200, 1500]
    res = life(LinearWear(b, sigma), u, cycles, a, max_growth=None, confidence=0.999)  # 7 points checked at once
    exact = stats.norm.cdf((b * np.asarray(cycles) - a) / sigma)
    lo, hi = res.interval
    assert np.all((lo <= exact + 1e-12) & (exact <= hi + 1e-12)), (res.pf, exact)
    assert np.all(np.diff(res.pf) >= 0)  # failure is not undone
    # Life at R = 0.9: N = (a + σ Φ⁻¹(0.1)) / b, inside the order-statistic interval.
    n_r, (n_lo, n_hi) = res.life_at(0.9, confidence=0.999)
    expected = (a + sigma * stats.norm.ppf(0.1)) / b
    assert n_lo <= expected <= n_hi and n_r == pytest.approx(expected, rel=0.03)
    assert res.n_runs == n * len(cycles)  # no jump limit: blocks at the requested counts only
    # Jumps limited to 0.05 of growth (50 cycles): 31 blocks, the same answer (the rate is constant).
    limited = life(LinearWear(b, sigma), u[:100], cycles, a, max_growth=0.05)
    assert list(limited.blocks) == [31] * 100 and np.allclose(limited.peaks, res.peaks[:100])
    with pytest.raises(InputError, match="run a longer life"):
        res.life_at(1e-6)


def test_cycle_jumping_follows_a_growing_wear_rate():
    """dw/dN = b (1 + w/w0) over 1000 cycles (w grows e-fold): the jumps' Euler extrapolation
    is first order in the growth per jump (−2.4 % at 0.05 w0, half that at 0.025 w0), and
    ``max_jump`` caps the jumps in cycles."""
    b, w0, n_end = 1e-3, 1.0, 1000.0
    exact = w0 * math.expm1(b * n_end / w0)
    u = np.zeros((1, 1))

    def error(**limits: float) -> float:
        res = life(GrowingWear(b, w0), u, [n_end], 1e9, **limits)
        return float(res.peaks[0, -1]) / exact - 1.0

    coarse, fine = error(max_growth=0.05), error(max_growth=0.025)
    assert -0.04 < coarse < -0.015 and 1.7 < coarse / fine < 2.3
    runs = life(GrowingWear(b, w0), u, [n_end], 1e9, max_growth=None, max_jump=20.0).n_runs
    assert runs == 51  # 0 and 50 jumps of 20 cycles


def test_life_rejects_bad_input():
    with pytest.raises(InputError) as err:
        life(LinearWear(1e-3, 0.1), np.zeros((2, 1)), [-1.0], 1.0)
    assert err.value.field == "cycles"
    with pytest.raises(InputError) as err:
        life(LinearWear(1e-3, 0.1), np.zeros((2, 1)), [10.0], 1.0, max_jump=0.0)
    assert err.value.field == "max_jump"
