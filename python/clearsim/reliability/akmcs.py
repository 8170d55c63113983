"""Few runs: active-learning Kriging reliability on OpenTURNS (docs/reliability.md, "Few runs").

A Kriging (Gaussian process) surrogate of the limit state g(u) in the standard normal space
classifies a large population of candidate points as failed (μ ≤ 0) or safe, and the model is
run only where that classification is uncertain:

* **AK-MCS** (Echard, Gayton & Lemaire 2011): candidates are a Monte Carlo population of the
  standard normal; p̂_f = #{μ ≤ 0}/N.
* **AK-IS** (Echard, Gayton, Lemaire & Relun 2013): candidates drawn from the importance
  density N(u*, I) around the FORM design point u* (FORM's runs start the design of
  experiments); p̂_f = mean of 1{μ ≤ 0} φ(u)/φ(u − u*). For rare events (p_f ≈ 1e-4 needs
  4·10⁶ Monte Carlo candidates for a 5 % CoV, ~10⁴ around u*).

Learning (both): fit the Kriging model (constant trend, Matérn 5/2 or squared-exponential
covariance, hyper-parameters by maximum likelihood: ``ot.GaussianProcessFitter``), evaluate the
U function U(u) = |μ(u)|/σ(u) on every candidate and run the model at the candidate of
smallest U, until min U ≥ 2 (every candidate's sign right with probability Φ(2) = 0.977).
Then, if the estimate's coefficient of variation exceeds ``cov``, the population grows
(N ← N (CoV/cov)², or ×10 while no candidate is classified failed: Echard et al. grow it until
the CoV target is met, up to ``max_population``) and learning resumes on it. The runs stop at
``max_runs`` (with a :class:`ReliabilityWarning` if U had not reached 2).

A rare event needs tens of millions of candidates (p_f = 7e-6 at a CoV of 0.05: 5.7·10⁷). They
are drawn block by block and never kept (:mod:`.akpopulation`): a pass of the surrogate over
them keeps the estimate's sums and the few candidates whose bound of U, |μ|/(an upper bound of
σ from the covariances already computed for μ), is below 2; σ is computed only for those. The
learning steps between two passes run on those candidates alone (each pass costs N predictions),
and the next pass checks that no other candidate's U has fallen below 2.

A series system (several failure modes) gets one Kriging model per mode and the system's learning
function of AK-SYS (Fauriat & Gayton 2014): at each candidate the mode with the smallest mean
decides, U = |μ_i*|/σ_i*. A noisy limit state (dry impacts) is fitted with its measured noise
σ_g as observation noise (the U function uses the latent function's σ). As σ stays above
σ_g/√k at its k-fold evaluated neighbourhood, the candidates next to g = 0 never reach U = 2
there: learning on a noisy limit state also stops when the surrogate's bounds (p_f with every
candidate within 2σ of g = 0 counted safe, and failed) differ by no more than ``cov`` × p̂_f.

The bulk predictions on the candidates are computed here (numpy, in chunks) from the fitted
covariance model, trend and training points; they agree with OpenTURNS' own predictions
(``GaussianProcessRegression`` and ``GaussianProcessConditionalCovariance``, tested).
"""

from __future__ import annotations

import math
import time
import warnings
from functools import partial
from typing import Any, List, Optional, Tuple, Union

import numpy as np

from ..errors import InputError, ReliabilityError, ReliabilityWarning, check_positive
from .bridge import check_model, normal_interval, ot
from .form import form, limit_state_noise, system_form
from .akpopulation import STOP_U, Population, Scan, scan
from .sampling import SamplingResult
from ..lazy import lazy

linalg = lazy("scipy.linalg")
special = lazy("scipy.special")

__all__ = ["Kriging", "ak_mcs", "ak_is", "COVARIANCES", "STOP_U", "INITIAL_POINTS"]

#: Covariance models of the Kriging surrogate.
COVARIANCES = ("matern52", "squared_exponential")
#: Size of AK-MCS's first design of experiments, drawn from the population (Echard et al. 2011).
INITIAL_POINTS = 12
#: Candidates predicted together (bounds the memory: CHUNK × training points; a block that stays
#: in cache: 8192 predicted 10⁶ candidates 4–5× faster than 65536 on 30 training points).
CHUNK = 8192
#: A population in which no candidate is classified failed grows by this factor (p_f below 1/N).
GROWTH = 10
#: Learning steps on one pass's unsure candidates before the whole population is passed over again.
INNER_STEPS = 10
#: AK-MCS's largest population by default: the CoV 0.05 of p_f = 1e-4 (N = (1 − p)/(p CoV²));
#: about 64 bytes a candidate at the peak (d = 2: 0.26 GB), 7 s of predictions on one core.
MAX_POPULATION = 100_000_000
#: Design points closer than this (in u) to one already in the design add nothing but
#: ill-conditioning (FORM's noise probe and gradient points) and are left out of the fit.
MIN_SPACING = 1e-3


class Kriging:
    """A Kriging model of one function of u fitted on OpenTURNS (constant trend, ``covariance``
    one of :data:`COVARIANCES`, hyper-parameters by maximum likelihood), with numpy predictions
    of the mean and the (universal-Kriging) variance on many points."""

    theta: np.ndarray
    amplitude: float

    def __init__(self, x: np.ndarray, y: np.ndarray, covariance: str = "matern52", noise: float = 0.0, start: Optional["Kriging"] = None) -> None:
        t = ot()
        self.x = np.asarray(x, dtype=float)
        self.y = np.asarray(y, dtype=float).reshape(-1)
        self.covariance = covariance
        n, d = self.x.shape
        spread = float(np.std(self.y)) or 1.0
        scale = list(start.theta) if start is not None else [1.0] * d
        amp = [start.amplitude] if start is not None else [spread]
        model = t.MaternModel(scale, amp, 2.5) if covariance == "matern52" else t.SquaredExponential(scale, amp)
        fitter = t.GaussianProcessFitter(t.Sample(self.x), t.Sample(self.y[:, None]), model, t.ConstantBasisFactory(d).build())
        if noise > 0:
            fitter.setNoise([float(noise) ** 2] * n)
        fitter.run()
        fitted = fitter.getResult()
        cm = fitted.getCovarianceModel()
        self.theta = np.array(cm.getScale(), dtype=float)
        self.amplitude = float(cm.getAmplitude()[0])
        self.beta = float(np.array(fitted.getTrendCoefficients()).ravel()[0])
        self.noise = float(noise)
        self._ot_result = fitted
        k = np.array(cm.discretize(t.Sample(self.x)), dtype=float) + self.noise**2 * np.eye(n)
        self.chol = np.linalg.cholesky(k)
        # L⁻¹, once: each candidate's variance is then a product, not a triangular solve (the
        # solves took 60 % of AK-MCS's time on 10⁶ candidates).
        self.chol_inv = np.asarray(linalg.solve_triangular(self.chol, np.eye(n), lower=True))
        ones = np.ones(n)
        self.alpha = self._solve(self.y - self.beta)
        self.kinv_1 = self._solve(ones)
        self.one_kinv_1 = float(ones @ self.kinv_1)

    def _solve(self, b: np.ndarray) -> np.ndarray:
        z = linalg.solve_triangular(self.chol, b, lower=True)
        return np.asarray(linalg.solve_triangular(self.chol.T, z, lower=False))

    def _cross(self, c: np.ndarray) -> np.ndarray:
        """Covariance between points ``c`` (m × d) and the training points (m × n)."""
        cs, xs = c / self.theta, self.x / self.theta
        r2 = cs @ xs.T
        r2 *= -2.0
        r2 += np.sum(cs * cs, axis=1)[:, None]
        r2 += np.sum(xs * xs, axis=1)[None, :]
        np.maximum(r2, 0.0, out=r2)
        if self.covariance == "matern52":
            r2 *= 5.0
            r = np.sqrt(r2)
            r2 /= 3.0
            r2 += r
            r2 += 1.0  # 1 + √5 ρ + 5ρ²/3
            np.negative(r, out=r)
            np.exp(r, out=r)
            r2 *= r
        else:
            r2 *= -0.5
            np.exp(r2, out=r2)
        r2 *= self.amplitude**2
        return r2

    def mean(self, c: np.ndarray) -> np.ndarray:
        """Posterior mean at ``c`` (m × d)."""
        out = np.empty(c.shape[0])
        for a in range(0, c.shape[0], CHUNK):
            out[a : a + CHUNK] = self.beta + self._cross(c[a : a + CHUNK]) @ self.alpha
        return out

    def mean_and_spread(self, c: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Posterior mean at ``c`` and an upper bound of its standard deviation, from the same
        covariances: the error of the Kriging predictor is at most that of predicting by the
        nearest training point alone (the only unbiased one-point predictor),
        σ² ≤ min_i 2 a² (1 − ρ(c, x_i)) + σ_n², a the amplitude, σ_n the noise. ``|μ|`` over it
        is a lower bound of U that spares most candidates their variance."""
        mean, spread = np.empty(c.shape[0]), np.empty(c.shape[0])
        a2 = self.amplitude**2
        for a in range(0, c.shape[0], CHUNK):
            ks = self._cross(c[a : a + CHUNK])
            mean[a : a + CHUNK] = self.beta + ks @ self.alpha
            spread[a : a + CHUNK] = np.sqrt(np.maximum(2.0 * (a2 - ks.max(axis=1)), 0.0) + self.noise**2)
        return mean, spread

    def variance(self, c: np.ndarray) -> np.ndarray:
        """Posterior variance of the latent function at ``c`` (universal Kriging: the trend's
        estimation included), ≥ 0."""
        out = np.empty(c.shape[0])
        for a in range(0, c.shape[0], CHUNK):
            ks = self._cross(c[a : a + CHUNK])
            v = ks @ self.chol_inv.T  # (L⁻¹ k_s)ᵀ: k_sᵀ K⁻¹ k_s = |L⁻¹ k_s|²
            trend = 1.0 - ks @ self.kinv_1
            out[a : a + CHUNK] = self.amplitude**2 - np.sum(v * v, axis=1) + trend**2 / self.one_kinv_1
        return np.maximum(out, 0.0)


class _Recorder:
    """Keeps every point the model runs while FORM searches (its modes' g), for the first design
    of experiments of AK-IS: the model's ``limit_states`` is wrapped on the instance for the
    duration of a ``with`` block (FORM and its per-mode views all run through it)."""

    def __init__(self, model: Any) -> None:
        self.model = model
        self.u: List[np.ndarray] = []
        self.g: List[np.ndarray] = []

    def __enter__(self) -> "_Recorder":
        inner = self.model.limit_states

        def recording(u: Any, on_failure: str = "fail") -> np.ndarray:
            pts = np.atleast_2d(np.asarray(u, dtype=float))
            g = np.asarray(inner(pts, on_failure), dtype=float).reshape(pts.shape[0], -1)
            self.u.append(pts.copy())
            self.g.append(g.copy())
            return g

        self.model.limit_states = recording
        return self

    def __exit__(self, *exc: Any) -> None:
        del self.model.limit_states  # the class's method again

    @property
    def count(self) -> int:
        """Points evaluated so far (model evaluations: runs for a Study, lives for a life model)."""
        return sum(u.shape[0] for u in self.u)


def _check(model: Any, max_runs: int, cov: float, covariance: str, on_failure: str) -> None:
    check_model(model, on_failure)
    if isinstance(max_runs, bool) or not isinstance(max_runs, (int, np.integer)) or max_runs < 2:
        raise InputError(f"invalid max_runs = {max_runs!r}: must be an integer ≥ 2", field="max_runs", value=max_runs)
    check_positive("cov", cov)
    if covariance not in COVARIANCES:
        raise InputError(f"invalid covariance = {covariance!r}: must be one of {', '.join(COVARIANCES)}", field="covariance", value=covariance)


def _spread(u: np.ndarray, k: int) -> np.ndarray:
    """Indices of ``k`` candidates spread over the population: the one nearest the origin, then
    each the farthest from those already taken (so the first design also sees the tails, where
    the failure region lies, not only the crowd at the mean)."""
    taken = [int(np.argmin(np.sum(u * u, axis=1)))]
    dist = np.sum((u - u[taken[0]]) ** 2, axis=1)
    for _ in range(k - 1):
        taken.append(int(np.argmax(dist)))
        dist = np.minimum(dist, np.sum((u - u[taken[-1]]) ** 2, axis=1))
    return np.asarray(taken)


def _thin(u: np.ndarray, g: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """The design without points within :data:`MIN_SPACING` of an earlier one."""
    keep: List[int] = []
    for i in range(u.shape[0]):
        if all(np.linalg.norm(u[i] - u[j]) >= MIN_SPACING for j in keep):
            keep.append(i)
    return u[keep], g[keep]


def _learn(
    model: Any, pop: Population, doe_u: np.ndarray, doe_g: np.ndarray, *, rec: _Recorder, max_runs: int, cov: float, covariance: str, noise: float,
    max_population: int, on_failure: str,
) -> Tuple[float, float, dict]:  # fmt: skip
    """The learning loop (module docstring) on ``pop`` from the design (doe_u, doe_g)."""
    modes = doe_g.shape[1]
    fits: List[Kriging] = []
    iterations, min_u, converged = 0, 0.0, False
    noisy = noise > 1e-9 * max(1e-300, float(np.nanstd(doe_g)))

    def refit() -> List[Kriging]:
        return [Kriging(doe_u, doe_g[:, i], covariance, noise, fits[i] if fits else None) for i in range(modes)]

    while True:
        if not fits or fits[0].x.shape[0] != doe_u.shape[0]:
            fits = refit()
        sc = scan(pop, partial(_classify, fits))
        near_u, near_mu, near_mode, near_lower, _ = sc.near()
        best, min_u = _smallest_u(fits, near_u, near_mu, near_mode, near_lower, sc.lowest)
        pf, c = sc.estimate()
        settled = min_u >= STOP_U
        if noisy and not settled and pf > 0:
            # A noisy limit state keeps σ ≥ σ_g/√k at its design points, so candidates next to
            # g = 0 never reach U = 2: learning stops once the candidates within 2σ of the limit
            # state move p_f by no more than the Monte Carlo target, (p⁺ − p⁻) ≤ cov · p̂.
            bounds = _bounds(fits, sc)
            settled = bounds[1] - bounds[0] <= cov * pf
        if settled:
            n = pop.size
            if pf == 0.0 and n >= max_population:
                raise ReliabilityError(
                    f"AK: the surrogate classifies none of the {n} candidates as failed after {doe_u.shape[0]} design points "
                    f"(every U ≥ {STOP_U:g}), and the population is at max_population = {max_population}: p_f is below about 1/{n} "
                    "or the design never reached the failure region; use AK-IS (around the FORM design point) or a larger max_population", method="AK",
                )  # fmt: skip
            if pf > 0.0 and (c <= cov or n >= max_population):
                converged = True  # learning has: a CoV above cov at max_population is said below
                break
            # Echard et al. (2011), stage 8: the population is too small for the target CoV (or
            # holds no failed candidate yet: ×GROWTH until one appears); add candidates, learn on.
            want = GROWTH * n if pf == 0.0 else math.ceil(n * (c / cov) ** 2)
            pop.grow(int(min(max_population, max(want, 2 * n)) - n))
            continue
        if rec.count >= max_runs:
            break
        # Learn on this pass's unsure candidates (the others had U ≥ 2) until they are sure, then
        # pass over the whole population again: a pass costs N predictions, a step here a few.
        for _ in range(INNER_STEPS):
            g = np.asarray(model.limit_states(best[None, :], on_failure), dtype=float).reshape(1, -1)
            iterations += 1
            doe_u, doe_g = np.vstack([doe_u, best[None, :]]), np.vstack([doe_g, g])
            if rec.count >= max_runs:
                break
            fits = refit()
            near_mu, near_mode, near_lower = _classify(fits, near_u)
            best, min_u = _smallest_u(fits, near_u, near_mu, near_mode, near_lower, (None, math.inf))
            if min_u >= STOP_U or (noisy and _band(fits, near_u, near_mu, near_mode, sc) <= cov * pf):
                break
    if fits[0].x.shape[0] != doe_u.shape[0]:  # the budget ended on a run: the surrogate with it
        fits = refit()
        sc = scan(pop, partial(_classify, fits))
        pf, c = sc.estimate()
        near_u, near_mu, near_mode, near_lower, _ = sc.near()
        min_u = _smallest_u(fits, near_u, near_mu, near_mode, near_lower, sc.lowest)[1]
    bounds = _bounds(fits, sc)
    candidates, weights, classified = sc.candidates()
    info = {
        "design_u": doe_u, "design_g": doe_g, "population": pop.size, "iterations": iterations, "min_u": min_u,
        "converged": converged, "noise": noise, "surrogate": fits, "surrogate_bounds": bounds, "candidates": candidates, "weights": weights,
        "classified_failed": classified,
    }  # fmt: skip
    name = "AK-MCS" if pop.monte_carlo else "AK-IS"
    if not converged:
        why = f"min U = {min_u:.3g} < {STOP_U:g}, surrogate bounds [{bounds[0]:.3g}, {bounds[1]:.3g}]"
        warnings.warn(f"{name}: the run budget ended before learning converged ({why}); p_f = {pf:.4g} may be off by more than its interval", ReliabilityWarning, stacklevel=3)
    elif c > cov:
        warnings.warn(f"{name}: the population stopped at max_population = {max_population} with the estimate's CoV {c:.3g} above cov = {cov:g} "
                      f"(p_f = {pf:.4g}: its interval is that wide; a larger max_population, or AK-IS, narrows it)", ReliabilityWarning, stacklevel=3)  # fmt: skip
    return pf, c, info


def _classify(fits: List[Kriging], u: np.ndarray) -> Tuple[np.ndarray, Optional[np.ndarray], np.ndarray]:
    """Each candidate's mean μ of the system (the mode of smallest mean decides: AK-SYS), that
    mode (``None`` for one), and a lower bound of its U = |μ|/σ (:meth:`Kriging.mean_and_spread`)."""
    pairs = [k.mean_and_spread(u) for k in fits]
    if len(pairs) == 1:
        mu, spread = pairs[0]
        mode = None
    else:
        means = np.column_stack([m for m, _ in pairs])
        mode = np.argmin(means, axis=1).astype(np.int16)
        rows = np.arange(means.shape[0])
        mu, spread = means[rows, mode], np.column_stack([sp for _, sp in pairs])[rows, mode]
    with np.errstate(divide="ignore", invalid="ignore"):
        lower = np.divide(np.abs(mu), spread, out=spread)
    lower[np.isnan(lower)] = math.inf  # on a training point of a noise-free fit: σ = 0
    return mu, mode, lower


def _sigma(fits: List[Kriging], u: np.ndarray, mode: Optional[np.ndarray]) -> np.ndarray:
    """The deciding mode's posterior standard deviation at candidates ``u``."""
    if mode is None:
        return np.sqrt(fits[0].variance(u))
    sigma = np.empty(u.shape[0])
    for i, k in enumerate(fits):
        sel = mode == i
        if sel.any():
            sigma[sel] = np.sqrt(k.variance(u[sel]))
    return sigma


def _bounds(fits: List[Kriging], sc: Scan) -> Tuple[float, float]:
    """The estimate if every candidate within 2σ of the limit state were safe, and if it were
    failed (σ only where the lower bound of U is below 2: elsewhere U ≥ 2 whatever σ is)."""
    u, _, mode, _, _ = sc.near()
    return sc.bounds(_sigma(fits, u, mode) if u.shape[0] else np.empty(0))


def _band(fits: List[Kriging], u: np.ndarray, mu: np.ndarray, mode: Optional[np.ndarray], sc: Scan) -> float:
    """p⁺ − p⁻ of the unsure candidates ``u`` of the pass ``sc`` under the present surrogate
    (``mu``: its means there): their weight within 2σ of g = 0 over the population's size."""
    if not u.shape[0]:
        return 0.0
    w = sc.near()[4]
    return float(np.sum(w[np.abs(mu) < STOP_U * _sigma(fits, u, mode)])) / sc.size


def _smallest_u(
    fits: List[Kriging], u: np.ndarray, mu: np.ndarray, mode: Optional[np.ndarray], lower: np.ndarray, lowest: Tuple[Optional[np.ndarray], float]
) -> Tuple[np.ndarray, float]:  # fmt: skip
    """The candidate of smallest U = |μ|/σ among ``u`` (means ``mu``, deciding ``mode``, lower
    bounds of U ``lower``) and its U, visiting those whose bound is below 2 by increasing bound,
    in chunks, and stopping once the bound passes min(best U so far, :data:`STOP_U`): σ is
    computed for a few candidates. When every bound is ≥ 2: ``lowest`` (the candidate of smallest
    bound, and it: every U is at least that) or the smallest bound among ``u``."""
    near = np.flatnonzero(lower < STOP_U)
    if not near.size:
        if lowest[0] is not None or not u.shape[0]:
            assert lowest[0] is not None
            return lowest[0], lowest[1]
        j = int(np.argmin(lower))
        return u[j].copy(), float(lower[j])
    order = near[np.argsort(lower[near], kind="stable")]
    best, best_u = int(order[0]), math.inf
    step = 16384
    for a in range(0, order.size, step):
        if lower[order[a]] >= min(best_u, STOP_U):
            break
        idx = order[a : a + step]
        sigma = _sigma(fits, u[idx], None if mode is None else mode[idx])
        with np.errstate(divide="ignore", invalid="ignore"):
            uu = np.where(sigma > 0, np.abs(mu[idx]) / sigma, math.inf)
        j = int(np.argmin(uu))
        if uu[j] < best_u:
            best, best_u = int(idx[j]), float(uu[j])
    return u[best].copy(), (best_u if math.isfinite(best_u) else float(lower[best]))


def _interval(pf: float, cov: float, bounds: Tuple[float, float]) -> Tuple[float, float]:
    """95 % interval: the population's Monte Carlo interval, widened to the surrogate's bounds
    (each with its own Monte Carlo half-width) where they reach beyond it."""
    lo, hi = normal_interval(pf, cov)
    half = 1.959963984540054 * (cov if math.isfinite(cov) else 0.0)
    return min(lo, max(0.0, bounds[0] * (1.0 - half))), max(hi, min(1.0, bounds[1] * (1.0 + half)))


def _noise(model: Any, noise: Union[float, str], u0: np.ndarray, on_failure: str) -> float:
    if isinstance(noise, str):
        if noise != "auto":
            raise InputError(f"invalid noise = {noise!r}: give 'auto' (measured) or the limit state's noise σ_g (≥ 0)", field="noise", value=noise)
        return limit_state_noise(model, u0, on_failure)
    v = float(noise)
    if not (math.isfinite(v) and v >= 0):
        raise InputError(f"invalid noise = {noise!r}: must be 'auto' or a number ≥ 0", field="noise", value=noise)
    return v


def ak_mcs(
    model: Any, *, max_runs: int = 150, seed: Optional[int] = 0, cov: float = 0.05, population: int = 10_000, max_population: int = MAX_POPULATION,
    covariance: str = "matern52", noise: Union[float, str] = "auto", initial: int = INITIAL_POINTS, on_failure: str = "fail",
) -> SamplingResult:  # fmt: skip
    """AK-MCS (module docstring): at most ``max_runs`` model evaluations (the noise probe's 9
    included with ``noise="auto"``; an evaluation is one run of a Study, one life of a life
    model: ``extra["evaluations"]``, while ``n_runs`` counts simulations), a first population of ``population`` standard normal candidates
    grown up to ``max_population`` until the estimate's CoV is ``cov`` (×10 while the surrogate
    classifies none as failed: a rare event needs ~(1 − p)/(p cov²) candidates; a
    :class:`ReliabilityWarning` if ``max_population`` stops it above ``cov``, a
    :class:`ReliabilityError` if none is failed even then). ``initial`` first design
    points spread over the population (nearest the origin, then farthest-first). The interval is
    the population's 95 % Monte Carlo interval, widened to the surrogate's bounds (``extra``:
    ``surrogate_bounds``, p_f with the candidates within 2σ of g = 0 counted safe / failed);
    ``extra`` also holds the design, the population size, the learning iterations and the last
    min U."""
    t0, runs0 = time.perf_counter(), model.n_runs
    _check(model, max_runs, cov, covariance, on_failure)
    d = model.dimension
    pop = Population(np.zeros((1, d)), np.ones(1), int(population), seed)
    with _Recorder(model) as rec:
        sigma_g = _noise(model, noise, np.zeros(d), on_failure)
        first = max(2, min(int(initial), int(max_runs) - rec.count - 1))
        head = pop.head(int(population))
        doe_u = head[_spread(head, first)]
        doe_g = np.asarray(model.limit_states(doe_u, on_failure), dtype=float).reshape(first, -1)
        pf, c, info = _learn(model, pop, doe_u, doe_g, rec=rec, max_runs=int(max_runs), cov=cov, covariance=covariance, noise=sigma_g,
                             max_population=int(max_population), on_failure=on_failure)  # fmt: skip
    info["evaluations"] = rec.count
    return SamplingResult(pf, c, _interval(pf, c, info["surrogate_bounds"]), model.n_runs - runs0, time.perf_counter() - t0, "AK-MCS", extra=info)


def ak_is(
    model: Any, *, max_runs: int = 150, seed: Optional[int] = 0, cov: float = 0.05, population: int = 10_000, max_population: int = 1_000_000,
    covariance: str = "matern52", design_point: Any = None, on_failure: str = "fail", step: Union[float, str] = "auto",
) -> SamplingResult:  # fmt: skip
    """AK-IS (module docstring): FORM first (its runs count and start the design; or give
    ``design_point``: a FORM result, whose runs are then not repeated, or a point in u, with a
    first design of 2d + 1 runs around it), then candidates from N(u*, I) (a mixture over the
    modes' design points for a series system, weighted by Φ(−β_i)). The limit state's noise is
    FORM's measured σ_g. At most ``max_runs`` runs in all."""
    t0, runs0 = time.perf_counter(), model.n_runs
    _check(model, max_runs, cov, covariance, on_failure)
    d = model.dimension
    with _Recorder(model) as rec:
        if design_point is None:
            design_point = system_form(model, step=step, on_failure=on_failure) if len(model.mode_names) > 1 else form(model, step=step, on_failure=on_failure)
        centres, weights = _centres(design_point, d)
        if rec.u:
            doe_u, doe_g = np.vstack(rec.u), np.vstack(rec.g)
        else:
            star = np.atleast_2d(centres[int(np.argmax(weights))])
            doe_u = np.vstack([star, star + 0.5 * np.eye(d), star - 0.5 * np.eye(d)])
            doe_g = np.asarray(model.limit_states(doe_u, on_failure), dtype=float).reshape(doe_u.shape[0], -1)
        ok = np.all(np.isfinite(doe_g), axis=1)
        doe_u, doe_g = _thin(doe_u[ok], doe_g[ok])
        modes = getattr(design_point, "modes", None)
        sigma_g = float(max([getattr(m, "noise", 0.0) for m in modes])) if modes else float(getattr(design_point, "noise", 0.0) or 0.0)
        mixture = np.asarray(weights, dtype=float) / float(np.sum(weights))
        pop = Population(centres, mixture, int(population), seed)
        pf, c, info = _learn(model, pop, doe_u, doe_g, rec=rec, max_runs=int(max_runs), cov=cov, covariance=covariance, noise=sigma_g,
                             max_population=int(max_population), on_failure=on_failure)  # fmt: skip
    info["form"] = design_point if hasattr(design_point, "beta") else None
    info["evaluations"] = rec.count
    return SamplingResult(pf, c, _interval(pf, c, info["surrogate_bounds"]), model.n_runs - runs0, time.perf_counter() - t0, "AK-IS", centres[int(np.argmax(mixture))], extra=info)


def _centres(design_point: Any, d: int) -> Tuple[np.ndarray, List[float]]:
    """The importance density's centres in u and their weights Φ(−β_i)."""
    modes = getattr(design_point, "modes", None)
    if modes:
        return np.array([np.asarray(m.design_point_u, dtype=float) for m in modes]), [float(special.ndtr(-m.beta)) for m in modes]
    if hasattr(design_point, "design_point_u"):
        return np.atleast_2d(np.asarray(design_point.design_point_u, dtype=float)), [1.0]
    arr = np.atleast_2d(np.asarray(design_point, dtype=float))
    if arr.shape[1] != d:
        raise InputError(f"invalid design_point: {arr.shape[1]} coordinates for {d} random inputs", field="design_point", value=arr.tolist())
    if not np.all(np.isfinite(arr)):
        raise ReliabilityError("AK-IS: the design point is not finite", method="AK-IS")
    return arr, [1.0] * arr.shape[0]
