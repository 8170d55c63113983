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

    def __init__(self, b: float, sigma: float, a: float = 1.0) -> None:
        self.a, self.b, self.sigma = a, b, sigma

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        peak = wear[:, 0] + self.sigma * u[:, 0]
        return BlockOutcome(self.a - peak, peak[:, None], wear.copy(), wear + self.b * self.window_cycles)


class GrowingWear(LinearWear):
    """dw/dN = b (1 + w / w0): w(N) = w0 (e^{b N / w0} − 1) (the worn clearance speeds wear up)."""

    def __init__(self, b: float, w0: float) -> None:
        super().__init__(b, 0.0, a=1e9)
        self.w0 = w0

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        w = wear[:, 0]
        rate = self.b * (1.0 + w / self.w0)  # over one cycle: small against w0 / b
        return BlockOutcome(self.a - w, wear.copy(), wear.copy(), wear + rate[:, None] * self.window_cycles)


def test_linear_wear_gives_the_closed_form_pf_over_life():
    a, b, sigma, n = 1.0, 1e-3, 0.2, 20000
    u = np.random.default_rng(1).standard_normal((n, 1))
    cycles = [0, 200, 500, 800, 1000, 1200, 1500]
    res = life(LinearWear(b, sigma, a), u, cycles, max_growth=None, confidence=0.999)  # 7 points checked at once
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
    limited = life(LinearWear(b, sigma, a), u[:100], cycles, max_growth=0.05)
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
        res = life(GrowingWear(b, w0), u, [n_end], **limits)
        return float(res.peaks[0, -1, 0]) / exact - 1.0

    coarse, fine = error(max_growth=0.05), error(max_growth=0.025)
    assert -0.04 < coarse < -0.015 and 1.7 < coarse / fine < 2.3
    runs = life(GrowingWear(b, w0), u, [n_end], max_growth=None, max_jump=20.0).n_runs
    assert runs == 51  # 0 and 50 jumps of 20 cycles


def test_life_rejects_bad_input():
    with pytest.raises(InputError) as err:
        life(LinearWear(1e-3, 0.1), np.zeros((2, 1)), [-1.0])
    assert err.value.field == "cycles"
    with pytest.raises(InputError) as err:
        life(LinearWear(1e-3, 0.1), np.zeros((2, 1)), [10.0], max_jump=0.0)
    assert err.value.field == "max_jump"


def _worn_slider_crank_study(limit: float = 0.6e-3):
    import clearsim
    from clearsim import Archard, Dry
    from clearsim import reliability as rel

    def build(clearance: float) -> "clearsim.Mechanism":
        # k = 1e-2: 40 cycles wear ~25 µm (a long life's depth in a few turns).
        return clearsim.models.slider_crank("dry", clearance=clearance, dry=Dry(wear=Archard(1e-2, 2e9, 0.02, feedback=True)))

    return rel.Study(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, rel.Output(body="slider", component="x"), limit=limit,
                     omega=5000 * 2 * math.pi / 60, cycles=1.0, skip_cycles=1.0, progress=False)  # fmt: skip


def test_a_short_real_life_runs_and_wears():
    """Four samples of a worn dry slider-crank over 40 cycles: the unworn blocks are the
    study's Monte Carlo runs (the same peaks), the worn volume grows in proportion to the
    cycles (Archard under a steady load: the bearing's summed depth at 40 cycles is twice that
    at 20 within 3 %; measured 1.99-2.01), and the peaks and p_f grow with wear."""
    study = _worn_slider_crank_study()
    res = study.life([0, 20, 40], n=4, seed=3)
    mc = study.monte_carlo(4, seed=3)
    assert np.allclose(res.peaks[:, 0, 0], mc.peaks, rtol=1e-12)
    assert res.surfaces == ["rod-slider bearing", "rod-slider journal"]
    assert np.all(res.depth[:, 0] == 0) and np.all(res.depth[:, 2] > res.depth[:, 1]) and np.all(res.depth[:, 1] > 0)
    assert res.worn is not None
    bearing_40 = res.worn[:, :360].sum(axis=1)
    assert res.depth[:, 2, 0] == pytest.approx(res.worn[:, :360].max(axis=1))
    # Summed depth at 20 cycles, from a second life stopped there (same samples, same blocks up to 20).
    res20 = study.life([0, 20], n=4, seed=3)
    assert res20.worn is not None and np.allclose(res20.peaks[:, :, 0], res.peaks[:, :2, 0])
    assert bearing_40 / res20.worn[:, :360].sum(axis=1) == pytest.approx(np.full(4, 2.0), rel=0.03)
    assert np.all(np.diff(res.pf) >= 0) and res.pf[-1] > res.pf[0]
    assert res.n_runs == res.blocks.sum() and np.all(res.blocks >= 3)
    assert np.all(np.nanmean(res.peaks[:, 2, 0]) > np.nanmean(res.peaks[:, 0, 0]))
    # The same lives as a model of u (for AK-MCS, FORM, ...): g ≤ 0 exactly for the samples failed by 40 cycles.
    from clearsim.reliability.distributions import input_stream

    u = input_stream(3, "clearance").standard_normal(4)[:, None]
    g = study.life_model(40).limit_state(u)
    only40 = study.life([40], n=4, seed=3)  # the same blocks as the model's lives
    assert np.array_equal(g, only40.g_min[:, 0]) and np.array_equal(g <= 0, only40.failure_cycles <= 40)


def test_life_needs_wear_fed_back():
    import clearsim
    from clearsim import Archard, Dry
    from clearsim import reliability as rel

    def build(clearance: float) -> "clearsim.Mechanism":
        return clearsim.models.slider_crank("dry", clearance=clearance, dry=Dry(wear=Archard(1e-2, 2e9, 0.02)))

    study = rel.Study(build, {"clearance": rel.Normal(0.5e-3, 0.02e-3)}, rel.Output(body="slider", component="x"), limit=1e-3, omega=523.6, progress=False)
    with pytest.raises(InputError, match="feedback") as err:
        study.life([10], n=2)
    assert err.value.field == "clearance joint 'rod-slider'.wear.feedback"


def test_cli_writes_life_and_ak_results(tmp_path, capsys):
    """``clearsim reliability`` on a scene with a worn pin (``[clearance_joint.dry] wear = {...}``),
    ``[study.life]`` and the AK-MCS method: life.csv (p_f against cycles, never falling), life.png,
    the AK-MCS row of reliability.csv and their parts of report.md."""
    import csv
    from pathlib import Path

    pytest.importorskip("openturns")
    from clearsim.cli import main

    base = (Path(__file__).resolve().parents[2] / "scenes" / "slider_crank.toml").read_text()
    base = base.replace('v1 = 1e-2                             # m/s', 'v1 = 1e-2\nwear = { coefficient = 1e-2, hardness = 2e9, length = 0.02, feedback = true }', 1)
    assert "wear = {" in base
    study = """
[study]
body = "slider"
component = "x"
quantity = "displacement"
limit = 0.59e-3
skip_cycles = 1.0
methods = ["ak_mcs"]
max_runs = 12
samples = 4

[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3
std = 0.02e-3

[study.life]
cycles = [0, 20, 40]
reliability = 0.5
"""
    scene = tmp_path / "worn.toml"
    scene.write_text(base + study)
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "-q"]) == 0
    # 12 runs: 9 measure the noise, too few to learn, and it says so.
    assert "AK-MCS: the run budget ended before learning converged" in capsys.readouterr().err
    rows = list(csv.DictReader((out / "life.csv").open()))
    assert [float(r["cycles"]) for r in rows] == [0.0, 20.0, 40.0]
    pf = [float(r["pf"]) for r in rows]
    assert pf == sorted(pf) and float(rows[-1]["max_depth [m]"]) > float(rows[1]["max_depth [m]"]) > 0
    assert (out / "life.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    methods = [r["method"] for r in csv.DictReader((out / "reliability.csv").open())]
    assert methods == ["ak_mcs"]
    report = (out / "report.md").read_text()
    assert "Reliability over life" in report and "| 40 |" in report


class CountingWear(LinearWear):
    """:class:`LinearWear` that counts its rounds of blocks."""

    def __init__(self, b: float, sigma: float = 0.0, a: float = 1e9) -> None:
        super().__init__(b, sigma, a)
        self.rounds = 0

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        self.rounds += 1
        return super().__call__(u, wear)


def test_a_life_of_too_many_blocks_stops_after_its_first_round_and_says_why():
    """A pin that wears 1e-3 of its depth scale a cycle, jumps of 2 % of it (20 cycles): 1e5
    cycles take 5 001 blocks; above max_blocks (1 000) the life stops after one round with the
    estimate, the rate, the jump and what to change (the old code ran all 5 000 rounds)."""
    from clearsim.errors import ReliabilityWarning

    runner = CountingWear(1e-3)
    with pytest.raises(InputError) as err:
        life(runner, np.zeros((3, 1)), [0, 1e3, 1e4, 1e5], progress=False)
    assert runner.rounds == 1 and err.value.field == "max_blocks"
    msg = str(err.value)
    assert "about 5001 blocks" in msg and "0.001 m a cycle" in msg and "20 cycles" in msg and "max_growth" in msg
    assert "100 m deep" in msg  # 1e-3 × 1e5: the worn depth the life asks for, named
    # Raised budget: it runs (5 001 blocks: the block at 0 and 5 000 jumps), with a warning.
    with pytest.warns(ReliabilityWarning, match="about 5001 blocks"):
        res = life(CountingWear(1e-3), np.zeros((1, 1)), [0, 1e5], max_blocks=6000, progress=False)
    assert res.blocks[0] == 5001
    with pytest.raises(InputError, match="max_blocks"):
        life(runner, np.zeros((1, 1)), [10], max_blocks=0)


def test_the_estimate_names_the_jump_limit_that_binds():
    """Wear faster than max_growth in one analysed window: each block advances only the window,
    and the message says cycle jumping saves nothing; a small max_jump is named as the cap."""
    from clearsim.errors import ReliabilityWarning

    with pytest.warns(ReliabilityWarning, match="advances only the window's 1 cycles"):
        life(CountingWear(0.05), np.zeros((1, 1)), [0, 300], progress=False)
    with pytest.warns(ReliabilityWarning, match="max_jump = 1 caps each jump"):
        life(CountingWear(1e-6), np.zeros((1, 1)), [0, 300], max_jump=1.0, progress=False)
    with pytest.warns(ReliabilityWarning, match="250 requested cycle counts"):
        life(CountingWear(1e-6), np.zeros((1, 1)), np.arange(250.0), progress=False)


def test_a_sample_whose_wear_speeds_up_past_the_budget_is_stopped_and_counted():
    """dw/dN = b (1 + w/w0) grows e-fold every w0/b cycles: the first round's estimate (2 000
    cycles at 20 cycles a jump: 101 blocks) fits in 150, the sped-up life does not; the sample
    is stopped at 150 blocks, counted as failed with its reason (raise: a SimulationError)."""
    from clearsim.errors import SimulationError

    res = life(GrowingWear(1e-3, 0.5), np.zeros((2, 1)), [0, 2000], max_blocks=150, progress=False)
    assert list(res.blocks) == [150, 150] and res.pf[-1] == 1.0
    assert len(res.failures) == 2 and "max_blocks = 150" in res.failures[0][2]
    assert 0 < res.failures[0][1] < 2000 and np.all(res.g_min[:, -1] == -1.0)
    with pytest.raises(SimulationError, match="max_blocks = 150"):
        life(GrowingWear(1e-3, 0.5), np.zeros((1, 1)), [0, 2000], max_blocks=150, on_failure="raise", progress=False)


def test_life_shows_a_bar_advancing_per_round_of_blocks(monkeypatch):
    """The bar's total is the estimated rounds (21: the block at 0 and 20 jumps of 20 cycles)
    and it advances once per round."""
    import clearsim.reliability.life as life_module

    bars = []

    class Bar:
        def __init__(self, total: float, desc: str, unit: str = "run", *, enabled: bool = True, **kw: object) -> None:
            self.total, self.desc, self.enabled, self.n, self.totals = total, desc, enabled, 0, []
            bars.append(self)

        def update(self, k: int = 1) -> None:
            self.n += k

        def refresh(self) -> None:
            self.totals.append(self.total)

        def close(self) -> None:
            pass

    monkeypatch.setattr(life_module, "bar", Bar)
    res = life(CountingWear(1e-3), np.zeros((2, 1)), [0, 400])
    (b,) = bars
    assert b.enabled and "life" in b.desc and b.n == res.blocks.max() == 21 and b.totals[0] == 21


def test_cli_names_a_life_over_budget_and_keeps_the_other_results(tmp_path, capsys):
    """``clearsim reliability`` with ``[study.life]`` to 1e6 cycles on the k = 1e-2 pin (~0.6 µm a
    cycle, 10 µm a jump: ~7e4 blocks): the life stops after its first round, the Monte Carlo
    results are written, report.md names the cause and the command exits with an error."""
    import csv
    from pathlib import Path

    from clearsim.cli import main

    base = (Path(__file__).resolve().parents[2] / "scenes" / "slider_crank.toml").read_text()
    base = base.replace('v1 = 1e-2                             # m/s', 'v1 = 1e-2\nwear = { coefficient = 1e-2, hardness = 2e9, length = 0.02, feedback = true }', 1)
    study = """
[study]
body = "slider"
component = "x"
quantity = "displacement"
limit = 0.59e-3
skip_cycles = 1.0
methods = ["monte_carlo"]
samples = 3

[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3
std = 0.02e-3

[study.life]
cycles = [0, 1e6]
"""
    scene = tmp_path / "worn.toml"
    scene.write_text(base + study)
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "-q"]) != 0
    assert "max_blocks" in capsys.readouterr().err
    assert [r["method"] for r in csv.DictReader((out / "reliability.csv").open())] == ["monte_carlo"]
    report = (out / "report.md").read_text()
    assert "Reliability over life: not run to the end" in report and "| monte_carlo |" in report and "Stopped early" in report


def test_a_scene_sets_max_blocks_by_the_same_word(tmp_path):
    """``[study.life] max_blocks`` is ``Study.life(max_blocks=)``'s word; a bad value is named
    with its line."""
    from pathlib import Path

    from clearsim.errors import InputError
    from clearsim.scene import load_scene_file

    path = Path(__file__).resolve().parents[1] / "data" / "scenes" / "beam_pump.toml"
    assert load_scene_file(path).study.life.max_blocks == 400
    bad = tmp_path / "bad.toml"
    bad.write_text(path.read_text(encoding="utf-8").replace("max_blocks = 400", "max_blocks = 0"), encoding="utf-8")
    with pytest.raises(InputError, match="study.life.max_blocks = 0"):
        load_scene_file(bad)
