"""Simulation estimates of a rare p_f on OpenTURNS: importance sampling around the design
point(s) and subset simulation. On a series system, importance sampling draws from a mixture of
unit normals centred on every mode's design point, weighted by each mode's Φ(−β_i), so that no
mode's failure region is left unsampled (docs/reliability.md, "Several failure modes")."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .. import display
from ..errors import check_positive
from .bridge import ModelLike, event, normal_interval, ot, seed_ot
from .form import FormResult, SystemFormResult, form, system_form
from ..lazy import lazy

special = lazy("scipy.special")

__all__ = ["SamplingResult", "importance_sampling", "subset"]


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


def _centres(model: ModelLike, design_point: Any) -> Tuple[List[np.ndarray], List[float]]:
    """The instrumental density's centres in u and their weights."""
    if isinstance(design_point, SystemFormResult):
        weights = [float(special.ndtr(-m.beta)) for m in design_point.modes]
        return [np.asarray(m.design_point_u, dtype=float) for m in design_point.modes], weights
    if isinstance(design_point, FormResult):
        return [np.asarray(design_point.design_point_u, dtype=float)], [1.0]
    arr = np.atleast_2d(np.asarray(design_point, dtype=float))
    return [row for row in arr], [1.0] * arr.shape[0]


def importance_sampling(
    model: ModelLike, *, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0, design_point: Any = None, block: int = 64, on_failure: str = "fail",
    step: Any = "auto",
) -> SamplingResult:  # fmt: skip
    """Importance sampling around the design point (a unit normal centred on it, in u; on a
    series system a mixture over the modes' design points), in blocks of ``block`` runs until
    the coefficient of variation reaches ``cov`` or ``max_runs`` runs are spent.
    ``design_point``: a :class:`FormResult`, a :class:`SystemFormResult`, a point in u or an
    array of points (a mixture with equal weights); default: FORM is run first (with ``step``),
    its runs counted."""
    t = ot()
    t0, runs0 = time.perf_counter(), model.n_runs
    cov = check_positive("cov", cov)
    block = max(1, int(block))
    if design_point is None:
        design_point = system_form(model, step=step, on_failure=on_failure) if len(model.mode_names) > 1 else form(model, step=step, on_failure=on_failure)
    centres, weights = _centres(model, design_point)
    seed_ot(seed)
    _, ev = event(model, on_failure)
    d = model.dimension
    parts = [t.Normal(t.Point([float(v) for v in c]), t.Point(d, 1.0), t.CorrelationMatrix(d)) for c in centres]
    if len(parts) == 1:
        instrumental = parts[0]
    else:
        w = np.asarray(weights, dtype=float)
        w = w / w.sum() if w.sum() > 0 else np.full(w.size, 1.0 / w.size)
        instrumental = t.Mixture(parts, t.Point([float(v) for v in w]))
    algo = t.ProbabilitySimulationAlgorithm(ev, t.ImportanceSamplingExperiment(instrumental))
    algo.setMaximumCoefficientOfVariation(cov)
    algo.setBlockSize(block)
    algo.setMaximumOuterSampling(max(1, int(max_runs) // block))
    algo.run()
    r = algo.getResult()
    pf, c = float(r.getProbabilityEstimate()), float(r.getCoefficientOfVariation())
    c = c if pf > 0 else math.inf
    return SamplingResult(pf, c, normal_interval(pf, c), model.n_runs - runs0, time.perf_counter() - t0, "importance sampling", centres[int(np.argmax(weights))],
                          extra={"centres": len(centres)})  # fmt: skip


def subset(model: ModelLike, *, seed: Optional[int] = 0, n_per_level: int = 1000, conditional_probability: float = 0.1, block: int = 100, on_failure: str = "fail") -> SamplingResult:
    """Subset simulation (OpenTURNS ``SubsetSampling``): ``n_per_level`` runs per level, each
    level conditioned on the worst ``conditional_probability`` of the last; needs no design
    point and no gradient."""
    t = ot()
    t0, runs0 = time.perf_counter(), model.n_runs
    seed_ot(seed)
    _, ev = event(model, on_failure)
    block = max(1, min(int(block), int(n_per_level)))
    algo = t.SubsetSampling(ev)
    algo.setBlockSize(block)
    algo.setMaximumOuterSampling(max(1, int(n_per_level) // block))
    algo.setConditionalProbability(float(conditional_probability))
    algo.run()
    r = algo.getResult()
    pf, c = float(r.getProbabilityEstimate()), float(r.getCoefficientOfVariation())
    levels = int(algo.getStepsNumber()) if hasattr(algo, "getStepsNumber") else None
    return SamplingResult(pf, c, normal_interval(pf, c), model.n_runs - runs0, time.perf_counter() - t0, "subset simulation", extra={"levels": levels})
