"""Tolerance design: the largest mean of one input (its spread kept) for which the reliability
is still a given value, by FORM at trial means (Brent's method on β) and an importance-sampling
check at the answer (docs/reliability.md)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, List, Optional, Tuple, Union


from .. import display
from ..errors import InputError
from .bridge import ModelLike
from .form import form
from .sampling import SamplingResult, importance_sampling
from ..lazy import lazy

optimize = lazy("scipy.optimize")
special = lazy("scipy.special")

__all__ = ["ToleranceResult", "tolerance"]


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
    model: ModelLike, name: str, reliability: float, *, bracket: Optional[Tuple[float, float]] = None, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0,
    step: Union[float, str] = "auto", on_failure: str = "fail",
) -> ToleranceResult:  # fmt: skip
    """The largest mean of input ``name`` for which P(no failure) ≥ ``reliability``.

    1. FORM at trial means inside ``bracket`` (default: ½× to 2× today's mean), each started from
       the last design point, with the gradient step ``step`` (``"auto"``: from the limit state's
       measured noise; see :func:`clearsim.reliability.form.form`); Brent's method finds the mean
       where β = Φ⁻¹(reliability) (to 0.1 % of the bracket).
    2. Importance sampling at that mean to ``cov`` checks the FORM answer: the local slope dβ/dmean
       from the FORM runs turns the sampled β and its 95 % interval into the returned value and
       interval. The response must worsen as the mean grows (a clearance, a load); otherwise the
       bracket's ends do not straddle the target and an :class:`InputError` says so.

    A FORM that cannot converge at a trial mean raises :class:`clearsim.ReliabilityError`.
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

    def trial(v: float) -> ModelLike:
        return model.with_input(name, base.with_mean(v))

    def h(v: float) -> float:
        res = form(trial(v), start=last_u[0], step=step, on_failure=on_failure)
        last_u[0] = res.design_point_u
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
    fr = form(m_star, start=last_u[0], step=step, on_failure=on_failure)
    check = importance_sampling(m_star, cov=cov, max_runs=max_runs, seed=seed, design_point=fr, on_failure=on_failure)
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
