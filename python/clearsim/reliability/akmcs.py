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
(N ← N (CoV/cov)²) and learning resumes on it. The runs stop at ``max_runs`` (with a
:class:`ReliabilityWarning` if U had not reached 2).

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
from dataclasses import dataclass
from typing import Any, List, Optional, Tuple, Union

import numpy as np

from ..errors import InputError, ReliabilityError, ReliabilityWarning, check_positive
from .bridge import check_model, normal_interval, ot
from .form import form, limit_state_noise, system_form
from .sampling import SamplingResult
from ..lazy import lazy

linalg = lazy("scipy.linalg")
special = lazy("scipy.special")

__all__ = ["Kriging", "ak_mcs", "ak_is", "COVARIANCES", "STOP_U", "INITIAL_POINTS"]

#: Covariance models of the Kriging surrogate.
COVARIANCES = ("matern52", "squared_exponential")
#: Learning stops when every candidate has U = |μ|/σ ≥ STOP_U (Echard et al. 2011).
STOP_U = 2.0
#: Size of AK-MCS's first design of experiments, drawn from the population (Echard et al. 2011).
INITIAL_POINTS = 12
#: Candidates predicted together (bounds the memory: CHUNK × training points).
CHUNK = 65536
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

    def variance(self, c: np.ndarray) -> np.ndarray:
        """Posterior variance of the latent function at ``c`` (universal Kriging: the trend's
        estimation included), ≥ 0."""
        out = np.empty(c.shape[0])
        for a in range(0, c.shape[0], CHUNK):
            ks = self._cross(c[a : a + CHUNK])
            v = linalg.solve_triangular(self.chol, ks.T, lower=True)
            trend = 1.0 - ks @ self.kinv_1
            out[a : a + CHUNK] = self.amplitude**2 - np.sum(v * v, axis=0) + trend**2 / self.one_kinv_1
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


@dataclass
class _Population:
    """Candidates in u and their importance weights (1 for Monte Carlo)."""

    u: np.ndarray
    weight: np.ndarray
    centres: np.ndarray
    mixture: np.ndarray

    def grow(self, n: int, rng: np.random.Generator) -> None:
        u, w = _draw(self.centres, self.mixture, n, rng)
        self.u = np.vstack([self.u, u])
        self.weight = np.concatenate([self.weight, w])

    def estimate(self, failed: np.ndarray) -> Tuple[float, float]:
        """p̂_f and its coefficient of variation from the candidates' classification."""
        terms = np.where(failed, self.weight, 0.0)
        n = terms.size
        pf = float(terms.mean())
        if pf <= 0:
            return 0.0, math.inf
        return pf, float(terms.std(ddof=1) / math.sqrt(n) / pf)


def _draw(centres: np.ndarray, mixture: np.ndarray, n: int, rng: np.random.Generator) -> Tuple[np.ndarray, np.ndarray]:
    """``n`` points of the mixture Σ_j w_j N(c_j, I) and their weights φ(u)/h(u) (1 when the
    only centre is the origin: Monte Carlo)."""
    d = centres.shape[1]
    pick = rng.choice(len(mixture), size=n, p=mixture)
    u = rng.standard_normal((n, d)) + centres[pick]
    if len(mixture) == 1 and not np.any(centres):
        return u, np.ones(n)
    # log φ(u) − log h(u) = −log Σ_j w_j exp(c_j·u − |c_j|²/2)
    expo = u @ centres.T - 0.5 * np.sum(centres**2, axis=1)[None, :]
    top = expo.max(axis=1, keepdims=True)
    log_h_over_phi = top[:, 0] + np.log(np.exp(expo - top) @ mixture)
    return u, np.exp(-log_h_over_phi)


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
    model: Any, pop: _Population, doe_u: np.ndarray, doe_g: np.ndarray, *, rec: _Recorder, max_runs: int, cov: float, covariance: str, noise: float,
    max_population: int, rng: np.random.Generator, on_failure: str,
) -> Tuple[float, float, dict]:  # fmt: skip
    """The learning loop (module docstring) on ``pop`` from the design (doe_u, doe_g)."""
    modes = doe_g.shape[1]
    fits: List[Kriging] = []
    iterations, min_u, converged = 0, 0.0, False
    noisy = noise > 1e-9 * max(1e-300, float(np.nanstd(doe_g)))
    while True:
        fits = [Kriging(doe_u, doe_g[:, i], covariance, noise, fits[i] if fits else None) for i in range(modes)]
        mu = np.column_stack([k.mean(pop.u) for k in fits])
        decide = np.argmin(mu, axis=1)
        mu_sys = mu[np.arange(mu.shape[0]), decide]
        amp = np.array([k.amplitude for k in fits])[decide] + noise
        best, min_u = _smallest_u(fits, pop.u, mu_sys, decide, amp)
        pf, c = pop.estimate(mu_sys <= 0.0)
        settled = min_u >= STOP_U
        if noisy and not settled and pf > 0:
            # A noisy limit state keeps σ ≥ σ_g/√k at its design points, so candidates next to
            # g = 0 never reach U = 2: learning stops once the candidates within 2σ of the limit
            # state move p_f by no more than the Monte Carlo target, (p⁺ − p⁻) ≤ cov · p̂.
            bounds = _bounds(fits, pop, mu_sys, decide, amp)
            settled = bounds[1] - bounds[0] <= cov * pf
        if settled:
            if pf == 0.0:
                raise ReliabilityError(
                    f"AK: the surrogate classifies none of the {pop.u.shape[0]} candidates as failed after {doe_u.shape[0]} design points "
                    f"(every U ≥ {STOP_U:g}): p_f is below 1/{pop.u.shape[0]} or the design never reached the failure region; "
                    "use AK-IS (around the FORM design point) or a larger population", method="AK",
                )  # fmt: skip
            if c <= cov or pop.u.shape[0] >= max_population:
                converged = True
                break
            grow = int(min(max_population - pop.u.shape[0], max(pop.u.shape[0], math.ceil(pop.u.shape[0] * ((c if math.isfinite(c) else 2.0) / cov) ** 2 - pop.u.shape[0]))))
            pop.grow(grow, rng)
            continue
        if rec.count >= max_runs:
            break
        x = pop.u[best : best + 1]
        g = np.asarray(model.limit_states(x, on_failure), dtype=float).reshape(1, -1)
        iterations += 1
        doe_u, doe_g = np.vstack([doe_u, x]), np.vstack([doe_g, g])
    bounds = _bounds(fits, pop, mu_sys, decide, amp)
    info = {
        "design_u": doe_u, "design_g": doe_g, "population": int(pop.u.shape[0]), "iterations": iterations, "min_u": min_u,
        "converged": converged, "noise": noise, "surrogate": fits, "surrogate_bounds": bounds, "candidates": pop.u, "weights": pop.weight,
        "classified_failed": mu_sys <= 0.0,
    }  # fmt: skip
    if not converged:
        why = f"min U = {min_u:.3g} < {STOP_U:g}, surrogate bounds [{bounds[0]:.3g}, {bounds[1]:.3g}]" if min_u < STOP_U else f"the population's CoV {c:.3g} above cov = {cov:g} at max_population = {max_population}"
        warnings.warn(f"{'AK-IS' if np.any(pop.centres) else 'AK-MCS'}: the run budget ended before learning converged ({why}); p_f = {pf:.4g} may be off by more than its interval", ReliabilityWarning, stacklevel=3)
    return pf, c, info


def _bounds(fits: List[Kriging], pop: "_Population", mu: np.ndarray, decide: np.ndarray, amp: np.ndarray) -> Tuple[float, float]:
    """The estimate if every candidate within 2σ of the limit state were safe, and if it were
    failed (σ only where |μ| < 2 × the prior standard deviation: elsewhere U ≥ 2 whatever σ is)."""
    sigma = np.zeros(mu.size)
    near = np.flatnonzero(np.abs(mu) < STOP_U * amp)
    for i, k in enumerate(fits):
        sel = near[decide[near] == i]
        if sel.size:
            sigma[sel] = np.sqrt(k.variance(pop.u[sel]))
    return pop.estimate(mu + STOP_U * sigma <= 0.0)[0], pop.estimate(mu - STOP_U * sigma <= 0.0)[0]


def _smallest_u(fits: List[Kriging], u: np.ndarray, mu: np.ndarray, decide: np.ndarray, amp: np.ndarray) -> Tuple[int, float]:
    """The candidate of smallest U = |μ|/σ and its U, visiting candidates by increasing
    |μ|/amplitude (a lower bound of U, as σ ≤ the prior standard deviation) in chunks and
    stopping once that bound passes min(best U so far, :data:`STOP_U`): σ is computed for a few
    candidates, not the population."""
    bound = np.abs(mu) / amp
    order = np.argsort(bound)
    best, best_u = int(order[0]), math.inf
    step = 16384
    for a in range(0, order.size, step):
        if bound[order[a]] >= min(best_u, STOP_U):
            break
        idx = order[a : a + step]
        sigma = np.empty(idx.size)
        for i, k in enumerate(fits):
            sel = decide[idx] == i
            if sel.any():
                sigma[sel] = np.sqrt(k.variance(u[idx[sel]]))
        with np.errstate(divide="ignore", invalid="ignore"):
            uu = np.where(sigma > 0, np.abs(mu[idx]) / sigma, math.inf)
        j = int(np.argmin(uu))
        if uu[j] < best_u:
            best, best_u = int(idx[j]), float(uu[j])
    return best, best_u


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
    model: Any, *, max_runs: int = 150, seed: Optional[int] = 0, cov: float = 0.05, population: int = 10_000, max_population: int = 1_000_000,
    covariance: str = "matern52", noise: Union[float, str] = "auto", initial: int = INITIAL_POINTS, on_failure: str = "fail",
) -> SamplingResult:  # fmt: skip
    """AK-MCS (module docstring): at most ``max_runs`` model evaluations (the noise probe's 9
    included with ``noise="auto"``; an evaluation is one run of a Study, one life of a life
    model: ``extra["evaluations"]``, while ``n_runs`` counts simulations), a first population of ``population`` standard normal candidates
    grown up to ``max_population`` until the estimate's CoV is ``cov``. ``initial`` first design
    points spread over the population (nearest the origin, then farthest-first). The interval is
    the population's 95 % Monte Carlo interval, widened to the surrogate's bounds (``extra``:
    ``surrogate_bounds``, p_f with the candidates within 2σ of g = 0 counted safe / failed);
    ``extra`` also holds the design, the population size, the learning iterations and the last
    min U."""
    t0, runs0 = time.perf_counter(), model.n_runs
    _check(model, max_runs, cov, covariance, on_failure)
    rng = np.random.default_rng(seed)
    d = model.dimension
    pop = _Population(*_draw(np.zeros((1, d)), np.ones(1), int(population), rng), centres=np.zeros((1, d)), mixture=np.ones(1))
    with _Recorder(model) as rec:
        sigma_g = _noise(model, noise, np.zeros(d), on_failure)
        first = max(2, min(int(initial), int(max_runs) - rec.count - 1))
        doe_u = pop.u[_spread(pop.u, first)]
        doe_g = np.asarray(model.limit_states(doe_u, on_failure), dtype=float).reshape(first, -1)
        pf, c, info = _learn(model, pop, doe_u, doe_g, rec=rec, max_runs=int(max_runs), cov=cov, covariance=covariance, noise=sigma_g,
                             max_population=int(max_population), rng=rng, on_failure=on_failure)  # fmt: skip
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
    rng = np.random.default_rng(seed)
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
        pop = _Population(*_draw(centres, mixture, int(population), rng), centres=centres, mixture=mixture)
        pf, c, info = _learn(model, pop, doe_u, doe_g, rec=rec, max_runs=int(max_runs), cov=cov, covariance=covariance, noise=sigma_g,
                             max_population=int(max_population), rng=rng, on_failure=on_failure)  # fmt: skip
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
