"""The largest Lyapunov exponent of a mechanism's motion, clearances, impacts and friction
included: two nearby trajectories renormalised every interval (Benettin et al. 1980), the shadow
run integrated by the core beside the run itself (``rust/simulate/lyapunov.rs``; docs/physics.md
§13). :func:`lyapunov` runs it; :func:`estimate` turns the booked growths into an exponent with
its confidence interval.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple

import numpy as np

from .. import batch
from ..errors import InputError, check_finite
from ..lazy import lazy
from ..schema import ATOL, RTOL
from .period import forcing_period

stats = lazy("scipy.stats")

#: Default distance d0 kept between the runs: this many times the integration's error ν = atol +
#: rtol × the largest body position (m), and at most this fraction of the smallest clearance (so
#: the shadow stays in the linear range of the contact); below ``D0_LEAST`` × ν the tolerances are
#: too loose for an exponent (the two runs' own errors would be what is measured).
D0_NOISE = 1e3
D0_CLEARANCE = 1e-3
D0_LEAST = 30.0
#: Batches of intervals the confidence interval is formed from (batch means).
BATCHES = 10


@dataclass(frozen=True)
class LyapunovExponent:
    """The largest Lyapunov exponent of a run and how well it converged.

    ``exponent`` [1/s]: λ = Σ ln(d_k/d0) / (n τ) over the n intervals of length τ
    (``renormalize_every`` [s]) after ``start`` [s]; > 0 chaotic, ≈ 0 quasi-periodic (or a
    neutral direction), < 0 a stable periodic motion. ``interval`` (low, high) [1/s]: its 95 %
    confidence interval by batch means over ``BATCHES`` batches of intervals (Student t).
    ``convergence`` (t [s], λ(t) [1/s]): the running estimate after each interval. ``log_growth``:
    ln(d_k/d0) of each interval. ``failure``: why the shadow stopped early, if it did (the
    intervals before count). ``result``: the run (a :class:`clearsim.Result`)."""

    exponent: float
    interval: Tuple[float, float]
    convergence: Tuple[np.ndarray, np.ndarray]
    log_growth: np.ndarray
    start: float
    renormalize_every: float
    d0: float
    failure: Optional[BaseException] = None
    result: Any = field(default=None, repr=False, compare=False)

    @property
    def per_period(self) -> float:
        """λ τ: the mean growth exponent per interval (per forcing period by default) [-]."""
        return self.exponent * self.renormalize_every

    @property
    def half_width(self) -> float:
        """Half the width of :attr:`interval` [1/s]."""
        return 0.5 * (self.interval[1] - self.interval[0])

    def plot(self, ax: Any = None) -> Any:
        """The running estimate with its final interval (:func:`clearsim.plots.dynamics.plot_lyapunov`)."""
        from ..plots.dynamics import plot_lyapunov

        return plot_lyapunov(self, ax=ax)


def estimate(book: Dict[str, Any], start: float, every: float, d0: float, result: Any = None) -> LyapunovExponent:
    """The :class:`LyapunovExponent` from the core's book (its ``t``, ``log_growth``, ``error``)."""
    g = np.asarray(book["log_growth"], dtype=float)
    t = np.asarray(book["t"], dtype=float)
    n = len(g)
    if n == 0:
        nan = float("nan")
        return LyapunovExponent(nan, (nan, nan), (t, g), g, start, every, d0, book.get("error"), result)
    running = np.cumsum(g) / (every * np.arange(1, n + 1))
    lam = float(running[-1])
    b = min(BATCHES, n // 2)
    if b >= 2:
        size = n // b
        means = g[n - b * size :].reshape(b, size).sum(axis=1) / (size * every)
        half = float(stats.t.ppf(0.975, b - 1) * np.std(means, ddof=1) / math.sqrt(b))
    else:
        half = float("inf")
    return LyapunovExponent(lam, (lam - half, lam + half), (t, running), g, start, every, d0, book.get("error"), result)


def integration_error(mechanism: Any, rtol: float, atol: float) -> float:
    """ν = atol + rtol × the largest |x|, |y| of the bodies as given [m]: what the integrator may
    get wrong in a position, so what two nearby runs can be told apart by."""
    bodies = mechanism.description()["bodies"]
    size = max((abs(float(c)) for b in bodies for c in b["position"]), default=0.0)
    return atol + rtol * size


def default_d0(mechanism: Any, rtol: float, atol: float) -> float:
    """d0 [m, rad]: ``D0_NOISE`` × :func:`integration_error`, at most ``D0_CLEARANCE`` × the
    smallest clearance; an InputError when that is below ``D0_LEAST`` × the error."""
    noise = integration_error(mechanism, rtol, atol)
    d0 = D0_NOISE * noise
    desc = mechanism.description()
    gaps = [float(j["clearance"]) for j in desc.get("clearance_joints", [])] + [float(j["clearance"]) for j in desc.get("prismatic_clearance_joints", [])]
    if gaps:
        d0 = min(d0, D0_CLEARANCE * min(gaps))
    if d0 < D0_LEAST * noise:
        need = (D0_CLEARANCE * min(gaps) / D0_LEAST - atol) / max(noise - atol, 1e-300) * rtol
        raise InputError(
            f"invalid rtol = {rtol!r}: for a Lyapunov exponent the two runs must stay {d0:.3g} m apart (1e-3 of the clearance "
            f"{min(gaps):.3g} m), {d0 / noise:.3g} × the integration error {noise:.3g} m; use rtol ≤ {need:.2g} (and atol ≪ {d0 / D0_LEAST:.2g})",
            field="rtol", value=rtol,
        )  # fmt: skip
    return d0


def shadow_spec(mechanism: Any, start: float, every: Optional[float], d0: Optional[float], velocity_scale: Optional[float], rtol: float, atol: float) -> Dict[str, float]:
    """The core's ``lyapunov`` settings (defaults: τ the forcing period, Ω = 2π/τ, :func:`default_d0`)."""
    every = forcing_period(mechanism) if every is None else check_finite("renormalize_every", every)
    return {
        "start": float(start),
        "interval": float(every),
        "d0": default_d0(mechanism, rtol, atol) if d0 is None else check_finite("d0", d0),
        "velocity_scale": 2 * math.pi / every if velocity_scale is None else check_finite("velocity_scale", velocity_scale),
    }


def lyapunov(
    m: Any,
    t_end: float,
    transient: float = 0.0,
    *,
    renormalize_every: Optional[float] = None,
    d0: Optional[float] = None,
    velocity_scale: Optional[float] = None,
    **options: Any,
) -> LyapunovExponent:
    """The largest Lyapunov exponent [1/s] of mechanism ``m``'s motion from ``transient`` [s]
    to ``t_end`` [s] (a :class:`LyapunovExponent`).

    A shadow run starts ``d0`` away at ``transient`` and is put back at that distance every
    ``renormalize_every`` τ [s] (default: the forcing period, :func:`forcing_period`), in the
    norm √(Σ δq² + Σ (δq̇/Ω)²) over the bodies' coordinates [m, rad], Ω = ``velocity_scale``
    [rad/s] (default 2π/τ); ``d0`` defaults to 1000 × the integration error atol + rtol × the
    largest body position, at most 1e-3 × the smallest clearance (tolerances too loose to keep
    it 30 × above that error are an InputError saying which rtol would do). Both runs locate their own impacts and friction switches, so the exponent holds
    through them (docs/physics.md §13). Other keyword arguments are :meth:`Mechanism.simulate`'s
    (integrator, rtol, atol, ...); the run stores only its states every τ unless told otherwise."""
    t_end = check_finite("t_end", t_end)
    transient = check_finite("transient", transient)
    t0 = float(options.get("t0", 0.0))
    if not t0 <= transient < t_end:
        raise InputError(f"invalid transient = {transient!r}: must lie in [t0, t_end) = [{t0}, {t_end}) s", field="transient", value=transient)
    spec = shadow_spec(m, transient, renormalize_every, d0, velocity_scale, float(options.get("rtol", RTOL)), float(options.get("atol", ATOL)))
    options.setdefault("outputs", ["states"])
    if options.get("t_out") is None and options.get("dt_out") is None:
        options["dt_out"] = spec["interval"]
    options.pop("progress", None)
    settings = m.run_settings(t_end, **options)
    settings["lyapunov"] = spec
    raw = batch.run_descriptions([m.description()], [settings])[0]
    res, failure = batch.finish(m, raw, settings)
    book = raw["lyapunov"] if not isinstance(raw, BaseException) else {"t": [], "log_growth": [], "error": raw}
    out = estimate(book, spec["start"], spec["interval"], spec["d0"], res)
    if failure is not None and out.failure is None:
        out = LyapunovExponent(out.exponent, out.interval, out.convergence, out.log_growth, out.start, out.renormalize_every, out.d0, failure, res)
    return out


__all__ = ["LyapunovExponent", "default_d0", "estimate", "integration_error", "lyapunov", "shadow_spec"]
