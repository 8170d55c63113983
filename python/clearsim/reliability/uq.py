"""Rare events, sensitivity and tolerance design on OpenTURNS (``pip install clearsim[uq]``).

clearsim supplies the model — a :class:`~clearsim.reliability.model.Model` whose vectorised
limit-state function ``g(u)`` runs a batch of simulations in parallel — and OpenTURNS supplies
the algorithms. Everything happens in the standard normal space ``u`` of the independent inputs
(``x = F⁻¹(Φ(u))``, docs/physics.md §6): OpenTURNS sees a standard normal vector, the event
``g(u) ≤ 0`` and a function that it evaluates a sample at a time (finite-difference gradients
included), so every batch of points becomes one parallel batch of runs.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
from scipy import optimize, special

from ..errors import InputError, check_positive
from .model import Model, check_on_failure
from .. import display

__all__ = ["FormResult", "SamplingResult", "SobolResult", "ToleranceResult", "form", "importance_sampling", "subset", "sobol", "tolerance"]


def _ot() -> Any:
    try:
        import openturns as ot
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("FORM, importance sampling, subset simulation, Sobol indices and tolerance design need OpenTURNS: pip install clearsim[uq]") from exc
    return ot


def _seed(seed: Optional[int]) -> None:
    if seed is not None:
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise InputError(f"invalid seed = {seed!r}: must be a non-negative integer", field="seed", value=seed)
        _ot().RandomGenerator.SetSeed(int(seed))


def _event(model: Model, on_failure: str, step: float = 0.05) -> Tuple[Any, Any]:
    """OpenTURNS' view of the model: the function u ↦ g(u) (evaluated a sample at a time, with
    centred finite-difference gradients of step ``step`` in u) and the event g ≤ 0."""
    ot = _ot()
    check_on_failure(on_failure)
    if on_failure == "exclude":
        raise InputError("invalid on_failure = 'exclude': only crude Monte Carlo can leave failed runs out; use 'fail' or 'raise'", field="on_failure", value=on_failure)
    d = model.dimension
    if d < 1:
        raise InputError("the study has no random input: give at least one distribution", field="inputs", value=list(model.inputs))

    def g_sample(u: Any) -> Any:
        return np.asarray(model.limit_state(np.asarray(u, dtype=float), on_failure), dtype=float).reshape(-1, 1)

    f = ot.PythonFunction(d, 1, func_sample=g_sample)
    f.setGradient(ot.CenteredFiniteDifferenceGradient(ot.Point(d, float(step)), f.getEvaluation()))
    y = ot.CompositeRandomVector(f, ot.RandomVector(ot.Normal(d)))
    return f, ot.ThresholdEvent(y, ot.LessOrEqual(), 0.0)


@dataclass
class FormResult:
    """FORM: the design point (most probable failure point) in physical units and in the
    standard normal space, the reliability index β (negative when the mean point already fails),
    p_f ≈ Φ(−β), the importance factors α_i² (sum 1) by input, and the cost."""

    beta: float
    pf: float
    design_point: Dict[str, float]
    design_point_u: np.ndarray
    importance: Dict[str, float]
    n_runs: int
    wall_time: float
    converged: bool = True

    def __repr__(self) -> str:
        return display.text(self, "pf", "beta", "design_point", "importance", "n_runs", "converged", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "pf", "beta", "design_point", "importance", "n_runs", "converged", "wall_time")

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf


def form(model: Model, *, start: Optional[Sequence[float]] = None, step: float = 0.05, max_iterations: int = 50, on_failure: str = "fail") -> FormResult:
    """First-order reliability method (OpenTURNS ``FORM`` with the Abdo–Rackwitz search).

    ``start``: the search's starting point in u (default: the mean point, u = 0); ``step``: the
    finite-difference step in u of the gradients (larger than round-off and step-control noise
    of the simulations: 0.05 by default); ``max_iterations`` of the search."""
    ot = _ot()
    t0, runs0 = time.perf_counter(), model.n_runs
    f, event = _event(model, on_failure, check_positive("step", step))
    d = model.dimension
    solver = ot.AbdoRackwitz()
    solver.setMaximumIterationNumber(int(max_iterations))
    solver.setMaximumAbsoluteError(1e-4)
    solver.setMaximumConstraintError(1e-4)
    solver.setStartingPoint(ot.Point(d, 0.0) if start is None else ot.Point([float(v) for v in start]))
    algo = ot.FORM(solver, event)
    algo.run()
    res = algo.getResult()
    u_star = np.array(res.getStandardSpaceDesignPoint(), dtype=float)
    beta = float(res.getGeneralisedReliabilityIndex())
    pf = float(res.getEventProbability())
    norm = float(np.linalg.norm(u_star))
    alpha2 = (u_star / norm) ** 2 if norm > 0 else np.full(d, 1.0 / d)
    x_star = {k: float(v[0]) for k, v in model.values(u_star[None, :]).items()}
    opt = res.getOptimizationResult()
    converged = opt.getIterationNumber() < int(max_iterations)
    return FormResult(beta, pf, x_star, u_star, dict(zip(model.random_names, map(float, alpha2))), model.n_runs - runs0, time.perf_counter() - t0, converged)


@dataclass
class SamplingResult:
    """A simulation estimate of p_f: the estimate, its coefficient of variation, a 95 %
    interval (normal approximation, clipped at 0), the number of runs and the wall time."""

    pf: float
    cov: float
    interval: Tuple[float, float]
    n_runs: int
    wall_time: float
    method: str
    design_point_u: Optional[np.ndarray] = None
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return display.text(self, "method", "pf", "interval", "cov", "n_runs", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "method", "pf", "interval", "cov", "n_runs", "wall_time")

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf


def _interval(pf: float, cov: float) -> Tuple[float, float]:
    half = 1.959963984540054 * pf * cov if math.isfinite(cov) else math.inf
    return max(0.0, pf - half), min(1.0, pf + half)


def importance_sampling(
    model: Model, *, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0, design_point: Any = None, block: int = 64, on_failure: str = "fail"
) -> SamplingResult:
    """Importance sampling around the FORM design point (a unit normal centred on it, in u),
    in blocks of ``block`` runs until the coefficient of variation reaches ``cov`` or
    ``max_runs`` runs are spent. ``design_point``: a :class:`FormResult` or a point in u (default:
    FORM is run first; its runs are counted)."""
    ot = _ot()
    t0, runs0 = time.perf_counter(), model.n_runs
    cov = check_positive("cov", cov)
    block = max(1, int(block))
    if design_point is None:
        design_point = form(model, on_failure=on_failure)
    u_star = np.asarray(design_point.design_point_u if isinstance(design_point, FormResult) else design_point, dtype=float).reshape(-1)
    _seed(seed)
    _, event = _event(model, on_failure)
    d = model.dimension
    instrumental = ot.Normal(ot.Point(u_star), ot.Point(d, 1.0), ot.CorrelationMatrix(d))
    algo = ot.ProbabilitySimulationAlgorithm(event, ot.ImportanceSamplingExperiment(instrumental))
    algo.setMaximumCoefficientOfVariation(cov)
    algo.setBlockSize(block)
    algo.setMaximumOuterSampling(max(1, int(max_runs) // block))
    algo.run()
    r = algo.getResult()
    pf, c = float(r.getProbabilityEstimate()), float(r.getCoefficientOfVariation())
    c = c if pf > 0 else math.inf
    return SamplingResult(pf, c, _interval(pf, c), model.n_runs - runs0, time.perf_counter() - t0, "importance sampling", u_star)


def subset(model: Model, *, seed: Optional[int] = 0, n_per_level: int = 1000, conditional_probability: float = 0.1, block: int = 100, on_failure: str = "fail") -> SamplingResult:
    """Subset simulation (OpenTURNS ``SubsetSampling``): ``n_per_level`` runs per level, each
    level conditioned on the worst ``conditional_probability`` of the last; needs no design
    point and no gradient."""
    ot = _ot()
    t0, runs0 = time.perf_counter(), model.n_runs
    _seed(seed)
    _, event = _event(model, on_failure)
    block = max(1, min(int(block), int(n_per_level)))
    algo = ot.SubsetSampling(event)
    algo.setBlockSize(block)
    algo.setMaximumOuterSampling(max(1, int(n_per_level) // block))
    algo.setConditionalProbability(float(conditional_probability))
    algo.run()
    r = algo.getResult()
    pf, c = float(r.getProbabilityEstimate()), float(r.getCoefficientOfVariation())
    levels = int(algo.getStepsNumber()) if hasattr(algo, "getStepsNumber") else None
    return SamplingResult(pf, c, _interval(pf, c), model.n_runs - runs0, time.perf_counter() - t0, "subset simulation", extra={"levels": levels})


@dataclass
class SobolResult:
    """First-order and total Sobol indices of the output, by input, with bootstrap 95 %
    intervals, from ``n × (d + 2)`` runs (Martinez's estimators)."""

    first: Dict[str, float]
    total: Dict[str, float]
    first_interval: Dict[str, Tuple[float, float]]
    total_interval: Dict[str, Tuple[float, float]]
    n_runs: int
    wall_time: float

    def __repr__(self) -> str:
        return display.text(self, "first", "total", "n_runs", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "first", "total", "n_runs", "wall_time")


def sobol(model: Model, n: int, *, seed: Optional[int] = 0, on_failure: str = "fail") -> SobolResult:
    """Sobol indices of the limit-state value (for a :class:`~clearsim.reliability.Study`,
    ``1 − peak/limit``: the same indices as the peak output itself, as they do not change under an
    affine map; a failed run enters as ``g = −1``). Computed in the standard normal space: for
    independent inputs the indices are those of the physical inputs."""
    ot = _ot()
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise InputError(f"invalid n = {n!r}: must be an integer ≥ 2", field="n", value=n)
    t0, runs0 = time.perf_counter(), model.n_runs
    _seed(seed)
    f, _ = _event(model, on_failure)
    d = model.dimension
    x = ot.SobolIndicesExperiment(ot.Normal(d), int(n)).generate()
    y = f(x)
    algo = ot.MartinezSensitivityAlgorithm(x, y, int(n))
    names = model.random_names
    s1, st = algo.getFirstOrderIndices(), algo.getTotalOrderIndices()
    i1, it = algo.getFirstOrderIndicesInterval(), algo.getTotalOrderIndicesInterval()

    def interval(iv: Any) -> Dict[str, Tuple[float, float]]:
        lo, hi = iv.getLowerBound(), iv.getUpperBound()
        return {k: (float(lo[i]), float(hi[i])) for i, k in enumerate(names)}

    return SobolResult(
        {k: float(s1[i]) for i, k in enumerate(names)}, {k: float(st[i]) for i, k in enumerate(names)},
        interval(i1), interval(it), model.n_runs - runs0, time.perf_counter() - t0,
    )  # fmt: skip


@dataclass
class ToleranceResult:
    """Tolerance design: the largest mean ``value`` of input ``name`` (its spread kept) whose
    reliability is still ``reliability``; ``interval`` its 95 % uncertainty from the importance
    sampling check at the FORM answer (``form_value``); ``history`` (value, β) of each FORM."""

    name: str
    value: float
    interval: Tuple[float, float]
    reliability: float
    form_value: float
    check: Optional[SamplingResult]
    history: List[Tuple[float, float]]
    n_runs: int
    wall_time: float

    def __repr__(self) -> str:
        return display.text(self, "name", "value", "interval", "reliability", "form_value", "n_runs", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "name", "value", "interval", "reliability", "form_value", "n_runs", "wall_time")


def tolerance(
    model: Model, name: str, reliability: float, *, bracket: Optional[Tuple[float, float]] = None, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0
) -> ToleranceResult:
    """The largest mean of input ``name`` for which P(no exceedance) ≥ ``reliability``.

    1. FORM at trial means inside ``bracket`` (default: ½× to 2× today's mean), each started from
       the last design point; Brent's method finds the mean where β = Φ⁻¹(reliability) (to 0.1 %
       of the bracket).
    2. Importance sampling at that mean to ``cov`` checks the FORM answer: the local slope dβ/dmean
       from the FORM runs turns the sampled β and its 95 % interval into the returned value and
       interval. The response must worsen as the mean grows (a clearance, a load); otherwise the
       bracket's ends do not straddle the target and an :class:`InputError` says so.
    """
    if name not in model.inputs:
        raise InputError(f"invalid name = {name!r}: not an input (known: {', '.join(model.inputs)})", field="name", value=name)
    r = float(reliability)
    if not 0.0 < r < 1.0:
        raise InputError(f"invalid reliability = {reliability!r}: must lie in (0, 1)", field="reliability", value=reliability)
    t0, runs0 = time.perf_counter(), model.n_runs
    base = model.inputs[name]
    v0 = base.nominal
    if bracket is None:
        if v0 == 0.0:
            raise InputError(f"missing bracket: the mean of {name!r} is 0, give (low, high) to search", field="bracket", value=None)
        bracket = (0.5 * v0, 2.0 * v0) if v0 > 0 else (2.0 * v0, 0.5 * v0)
    lo, hi = float(bracket[0]), float(bracket[1])
    if not lo < hi:
        raise InputError(f"invalid bracket = {bracket!r}: needs low < high", field="bracket", value=bracket)
    beta_target = float(special.ndtri(r))
    history: List[Tuple[float, float]] = []
    last_u: List[Any] = [None]

    def trial(v: float) -> Model:
        return model.with_input(name, base.with_mean(v))

    def h(v: float) -> float:
        m = trial(v)
        res = form(m, start=last_u[0])
        last_u[0] = res.design_point_u if res.converged else None
        history.append((v, res.beta))
        return res.beta - beta_target

    h_lo, h_hi = h(lo), h(hi)
    if h_lo < 0 or h_hi > 0:
        raise InputError(
            f"invalid bracket = ({lo:g}, {hi:g}): β there is {h_lo + beta_target:.3g} and {h_hi + beta_target:.3g}, "
            f"which do not straddle the target β = {beta_target:.3g} (reliability {r}) with β falling as the mean grows",
            field="bracket", value=bracket,
        )  # fmt: skip
    v_form = float(optimize.brentq(h, lo, hi, xtol=1e-3 * (hi - lo), maxiter=30))
    # Local slope dβ/dv from the two FORM evaluations closest to the answer.
    pts = sorted(history, key=lambda p: abs(p[0] - v_form))[:2]
    slope = (pts[0][1] - pts[1][1]) / (pts[0][0] - pts[1][0]) if pts[0][0] != pts[1][0] else math.nan
    m_star = trial(v_form)
    fr = form(m_star, start=last_u[0])
    check = importance_sampling(m_star, cov=cov, max_runs=max_runs, seed=seed, design_point=fr)
    if check.pf > 0 and math.isfinite(slope) and slope < 0:
        beta_is = -float(special.ndtri(check.pf))
        b_hi = -float(special.ndtri(max(check.interval[0], 1e-300)))
        b_lo = -float(special.ndtri(check.interval[1]))
        value = v_form + (beta_target - beta_is) / slope
        ends = sorted((v_form + (beta_target - b_hi) / slope, v_form + (beta_target - b_lo) / slope))
        interval = (float(ends[0]), float(ends[1]))
    else:
        value, interval = v_form, (math.nan, math.nan)
    return ToleranceResult(name, float(value), interval, r, v_form, check, history, model.n_runs - runs0, time.perf_counter() - t0)
