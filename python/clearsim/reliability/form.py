"""FORM on limit states that may be noisy, and the first-order reliability of a series system.

A simulated limit state is not smooth at small scales: dry impacts, event location and step-size
control make ``g`` jitter when the inputs move by 1e-3 of their spread. FORM here is the improved
Hasofer–Lind–Rackwitz–Fiessler search (Zhang & Der Kiureghian 1995; docs/reliability.md, "Noisy
limit states"), with three guards against that noise:

1. the noise σ_g of the limit state is measured before the search (9 runs): g on 9 points 0.01 apart
   (in u) along a random direction, a quadratic fitted by least squares, σ_g its residual
   standard deviation;
2. the gradient is a finite difference taken in one batch of runs (in parallel) with the step
   ``h = 35 σ_g / |∇g|`` (the gradient's noise ≤ 2 % of its size), clipped to [0.001, 0.5]:
   forward differences of step 2h (d runs) while 2h ≤ :data:`FORWARD_STEP`, the regression over
   ``u ± h e_i`` (2d runs) above; ``step=`` fixes h instead. Each iteration runs the full HL-RF
   step and the gradient there as one batch of d + 1 runs;
3. the search stops when u moves by less than the tolerance on the surface (|g|/|∇g| within it),
   or after two moves in a row within the noise's wander with |g| within 3 × the noise g carries
   after a step (σ_g and the gradient's error times the move); β = α·u* + g(u*)/|∇g|, the
   distance to the limit state linearised at u*. A design point off the surface by more than
   the tolerance is accepted with a :class:`ReliabilityWarning` that gives β's uncertainty from
   the noise, ``σ_g / |∇g|``; a search that does not converge, or
   whose β the noise leaves uncertain by more than 10 %, raises :class:`ReliabilityError` naming
   its best point and what to use instead.

A limit state may fail on both sides of the mean point (against the nominal design a link too short
and one too long both move the output): after the search converges at u*, g is evaluated at the
mirrored point −u* (one run); when a straight line through g(0) and g(−u*) predicts a failure on
that side adding at least :data:`MIRROR_SHARE` of Φ(−β), a second search starts there, and a second
design point found there makes the answer a series system of the two (:class:`SystemFormResult`,
its modes named ``"<mode>"`` and ``"<mode> (mirrored)"``).

A series system (the mechanism fails when any mode fails) gets FORM per mode (each with its
mirrored check) and, from the design points, the correlation ρ_ij = α_i·α_j of their linearised
margins, the first-order series probability ``1 − Φ_m(β; ρ)`` and Ditlevsen's bounds.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from .. import display
from ..errors import InputError, ReliabilityError, ReliabilityWarning, check_positive
from .bridge import ModelLike, check_model
from ..lazy import lazy

special = lazy("scipy.special")
stats = lazy("scipy.stats")

__all__ = ["FormResult", "SystemFormResult", "form", "system_form", "limit_state_noise", "ditlevsen_bounds", "series_probability"]

#: Spacing in u of the noise-measuring points and their number.
NOISE_SPACING = 0.01
NOISE_POINTS = 9
#: Gradient step h = STEP_FACTOR · σ_g / |∇g| (the regression gradient's noise ≤ 2 % of |∇g|),
#: clipped to [MIN_STEP, MAX_STEP] in u.
STEP_FACTOR = 35.0
MIN_STEP, MAX_STEP = 1e-3, 0.5
#: The first gradient's step in u (before |∇g| is known).
FIRST_STEP = 0.05
#: Gradients by forward differences of step 2h (d runs) while 2h is at most this, by centred
#: differences of step h (2d runs) above it.
FORWARD_STEP = 0.025
#: A design point is on the limit state when |g| ≤ G_TOLERANCE · max(1, |g(start)|), or within
#: NOISE_BAND σ_g of it on a noisy limit state (then with a warning).
G_TOLERANCE = 1e-4
NOISE_BAND = 3.0
#: A limit state whose noise exceeds this fraction of |g| and of |∇g| (per unit of u) at the start
#: has no gradient to follow.
NOISE_MARGIN = 0.2
#: Beyond this uncertainty of β from the noise (relative, at least 1 in u) there is no design
#: point to speak of: FORM raises.
BETA_NOISE_LIMIT = 0.1
#: The search stays within |u| ≤ U_MAX: Φ(−37) ≈ 6e-300, about the smallest probability a double
#: holds, and beyond it an input's F⁻¹(Φ(u)) is infinite (an HL-RF step from a nearly flat
#: limit state far from failure can jump there).
U_MAX = 37.0
#: The mirrored side −u* is searched when a straight line through g(0) and g(−u*) predicts a
#: failure there at a distance t with Φ(−t) ≥ MIRROR_SHARE · Φ(−β), and its design point is kept
#: when it adds at least that share of the first one's Φ(−β).
MIRROR_SHARE = 0.01
#: Two design points whose directions agree this closely (α₁·α₂) are one.
SAME_DIRECTION = 0.95


@dataclass
class FormResult:
    """FORM: the design point (most probable failure point) in physical units and in the
    standard normal space, the reliability index β (negative when the mean point already fails),
    p_f ≈ Φ(−β), the importance factors α_i² (sum 1) by input, and the cost.

    ``noise``: the limit state's measured noise σ_g (in g's scale, g = 1 − peak/limit for a
    study); ``step``: the gradient step in u used last; ``g_design``: g at the design point;
    ``beta_noise``: β's uncertainty from the noise, σ_g / |∇g|; ``accepted_at_noise``: whether
    the design point was accepted within the noise band rather than the nominal tolerance."""

    beta: float
    pf: float
    design_point: Dict[str, float]
    design_point_u: np.ndarray
    importance: Dict[str, float]
    n_runs: int
    wall_time: float
    converged: bool = True
    noise: float = 0.0
    step: float = math.nan
    g_design: float = math.nan
    beta_noise: float = 0.0
    accepted_at_noise: bool = False
    iterations: int = 0

    def __repr__(self) -> str:
        return display.text(self, "pf", "beta", "design_point", "importance", "n_runs", "converged", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "pf", "beta", "design_point", "importance", "n_runs", "converged", "wall_time")

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf

    @property
    def alpha(self) -> np.ndarray:
        """The unit normal α = −∇g/|∇g| at the design point (u* = β α; the linearised margin is
        β − α·u)."""
        # u*/|u*| with β's sign, not u*/β: β carries the off-surface correction g/|∇g| (a point
        # accepted at the noise level), so u*/β was not a unit vector and ρ = α_i·α_j left [−1, 1].
        norm = float(np.linalg.norm(self.design_point_u))
        return self.design_point_u * (math.copysign(1.0, self.beta) / norm) if norm > 0 and self.beta != 0 else np.zeros_like(self.design_point_u)


def limit_state_noise(model: ModelLike, u0: np.ndarray, on_failure: str = "fail", seed: int = 0) -> float:
    """The noise σ_g of the limit state near ``u0``: g on :data:`NOISE_POINTS` points
    :data:`NOISE_SPACING` apart along a random direction (one batch), minus a least-squares
    quadratic; σ_g is the residual's standard deviation (6 degrees of freedom)."""
    d = u0.size
    p = np.random.default_rng(seed).standard_normal(d)
    p /= np.linalg.norm(p)
    s = (np.arange(NOISE_POINTS) - NOISE_POINTS // 2) * NOISE_SPACING
    g = model.limit_state(u0[None, :] + s[:, None] * p[None, :], on_failure)
    ok = np.isfinite(g)
    if ok.sum() < 4:
        return 0.0
    v = np.vander(s[ok], 3)
    coef, *_ = np.linalg.lstsq(v, g[ok], rcond=None)
    resid = g[ok] - v @ coef
    return float(math.sqrt(np.sum(resid**2) / max(1, ok.sum() - 3)))


def _gradient(model: ModelLike, u: np.ndarray, h: float, on_failure: str, g_u: Optional[float] = None) -> Tuple[float, np.ndarray]:
    """g(u) and its gradient by finite differences of step h in u, one batch of runs: forward
    differences of step 2h (d runs, and u itself unless ``g_u`` = g(u) is known) while 2h ≤
    :data:`FORWARD_STEP`, whose noise then equals the centred difference's at h and whose
    truncation error (of order h |∇g|/β) stays below it; otherwise the regression over
    ``u ± h e_i`` (2d runs, + 1), which for a design symmetric about u is the centred difference."""
    d = u.size
    forward = 2.0 * h <= FORWARD_STEP
    offsets = 2.0 * h * np.eye(d) if forward else np.vstack([h * np.eye(d), -h * np.eye(d)])
    pts = u + offsets if g_u is not None else np.vstack([u, u + offsets])
    g = np.asarray(model.limit_state(pts, on_failure), dtype=float)
    g0, g = (float(g_u), g) if g_u is not None else (float(g[0]), g[1:])
    if forward:
        return g0, (g - g0) / (2.0 * h)
    return g0, (g[:d] - g[d:]) / (2.0 * h)


def _gradient_noise(noise: float, h: float, d: int) -> float:
    """The norm of the finite-difference gradient's error from the noise σ_g at the step h."""
    return math.sqrt(d) * noise / (math.sqrt(2.0) * h)


class _Shown:
    """The model seen through FORM's progress bar (:func:`clearsim.progress.bar`, shown when the
    model's ``progress`` is on, a study's by default): the runs made so far, the iteration, |u|
    and g. Everything else is the model's."""

    def __init__(self, model: ModelLike, desc: str) -> None:
        from ..progress import bar

        self._model = model
        shown = getattr(model, "progress", getattr(getattr(model, "parent", None), "progress", False))
        self._bar = bar(None, desc, "run", enabled=bool(shown))

    def __getattr__(self, name: str) -> Any:
        return getattr(self._model, name)

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        g = self._model.limit_state(u, on_failure)
        self._bar.update(int(np.size(g)))
        return g

    def note(self, iteration: int, u: np.ndarray, g: float, h: float) -> None:
        self._bar.set_postfix_str(f"iteration {iteration}, |u| {float(np.linalg.norm(u)):.4g}, g {g:.3g}, step {h:.3g}", refresh=True)  # once an iteration: shown at once

    def close(self) -> None:
        self._bar.close()


def form(
    model: ModelLike, *, start: Optional[Sequence[float]] = None, step: Union[float, str] = "auto", max_iterations: int = 50, on_failure: str = "fail",
    tolerance: float = 1e-3, mirror: bool = True,
) -> Union[FormResult, "SystemFormResult"]:  # fmt: skip
    """First-order reliability method: the design point u* nearest the origin on g(u) = 0 by the
    improved HL-RF search (each iteration one parallel batch of d + 1 runs, or 2d + 1 for a
    centred gradient), β = |u*| (signed), p_f ≈ Φ(−β).

    ``start``: the starting point in u (default: the mean point, u = 0); ``step``: the gradient
    step in u, ``"auto"`` (default: from the measured noise, see the module docs) or a number;
    ``max_iterations`` of the search; ``tolerance``: convergence when u moves by less than this
    (in u). ``mirror`` (default on): look for a second design point on the other side of the mean
    point (one run at −u*; a second search only where a failure there is predicted); when one is
    found the answer is the series system of the two design points, a :class:`SystemFormResult`.
    Raises :class:`ReliabilityError` when the search does not converge. A progress bar (a
    study's ``progress``) counts the runs and shows the iteration, |u| (β once converged) and g."""
    t0, runs0 = time.perf_counter(), model.n_runs
    name = model.mode_names[0]
    shown = _Shown(model, f"FORM {name}" if hasattr(model, "parent") else "FORM")  # a series system's mode: named
    try:
        first, g_start = _search(shown, start, step, max_iterations, on_failure, tolerance)
        second = _mirrored(shown, first, g_start if start is None else math.nan, step, max_iterations, on_failure, tolerance) if mirror else None
    finally:
        shown.close()
    if second is None:
        first.n_runs, first.wall_time = model.n_runs - runs0, time.perf_counter() - t0  # the check's runs counted
        return first
    return _series([first, second], [name, f"{name} (mirrored)"], model.n_runs - runs0, time.perf_counter() - t0, mirrored=[1])


def _mirrored(
    model: Any, first: FormResult, g_mean: float, step: Union[float, str], max_iterations: int, on_failure: str, tolerance: float
) -> Optional[FormResult]:  # fmt: skip
    """A second design point on the other side of the mean point, or None: g at −u* (and at the
    mean point when the search did not start there), one batch; where g falls from the mean point
    towards −u*, the straight line through the two predicts g = 0 at the distance t along −α, and
    when Φ(−t) ≥ :data:`MIRROR_SHARE` Φ(−β) a second search starts at −t α. Its design point is
    kept when it lies in another direction (α₁·α₂ < :data:`SAME_DIRECTION`) and adds at least
    that share; a second search that fails gives a ReliabilityWarning and the first answer."""
    beta, u1 = first.beta, np.asarray(first.design_point_u, dtype=float)
    if not (first.converged and 0.0 < beta < U_MAX):
        return None  # the mean point fails (β ≤ 0) or no failure was reached: no other side to look at
    points = [-u1] if math.isfinite(g_mean) else [-u1, np.zeros_like(u1)]
    g = model.limit_state(np.vstack(points), on_failure)
    g_far, g0 = float(g[0]), (g_mean if math.isfinite(g_mean) else float(g[1]))
    if not (g0 > g_far and g0 > 0.0):
        return None  # g does not fall towards −u*: no failure predicted on that side
    t = min(beta * g0 / (g0 - g_far), U_MAX)
    p_first = float(special.ndtr(-beta))
    if float(special.ndtr(-t)) < MIRROR_SHARE * p_first:
        return None
    alpha = first.alpha
    try:
        second, _ = _search(model, -t * alpha, step, max_iterations, on_failure, tolerance)  # its own noise: the other side may be rougher
    except ReliabilityError as err:
        warnings.warn(
            f"FORM: g falls from {g0:.3g} at the mean point to {g_far:.3g} at the mirrored design point −u* (u* = {_fmt(u1)}, β = {beta:.4g}), "
            f"predicting a failure on that side too, but no second design point was found there ({err}). p_f = Φ(−β) counts one side only: "
            f"check it with monte_carlo, subset or ak_mcs, which need no design point.",
            ReliabilityWarning, stacklevel=3,
        )  # fmt: skip
        return None
    if not second.converged or float(second.alpha @ alpha) >= SAME_DIRECTION or second.pf < MIRROR_SHARE * p_first:
        return None
    return second


def _search(model: Any, start: Any, step: Union[float, str], max_iterations: int, on_failure: str, tolerance: float) -> Tuple[FormResult, float]:
    """:func:`form`'s search on ``model`` (a :class:`_Shown`): the design point and g at the start."""
    t0, runs0 = time.perf_counter(), model.n_runs
    check_model(model, on_failure)
    d = model.dimension
    auto = isinstance(step, str)
    if auto and step != "auto":
        raise InputError(f"invalid step = {step!r}: give 'auto' or a step in the standard normal space (e.g. 0.05)", field="step", value=step)
    h = FIRST_STEP if auto else check_positive("step", step)
    if isinstance(max_iterations, bool) or int(max_iterations) < 1:
        raise InputError(f"invalid max_iterations = {max_iterations!r}: must be a positive integer", field="max_iterations", value=max_iterations)
    u = np.zeros(d) if start is None else np.asarray([float(v) for v in start], dtype=float)
    if u.size != d:
        raise InputError(f"invalid start: {u.size} values for {d} random inputs", field="start", value=list(u))
    noise = limit_state_noise(model, u, on_failure)
    g, grad = _gradient(model, u, h, on_failure)
    g_start = g
    if auto:
        h_first, h = h, _step(noise, grad, h)
        if h > 2.0 * h_first:  # the first step was too small for the noise: that gradient is noisy, take it again
            g, grad = _gradient(model, u, h, on_failure)
    g_scale = max(1.0, abs(g))
    if noise > NOISE_MARGIN * max(abs(g), float(np.linalg.norm(grad))):
        raise _no_convergence(model, (abs(g), u, g, grad), noise, f"the limit state's noise σ_g = {noise:.3g} is not small against its value g = {g:.3g} and slope |∇g| = {float(np.linalg.norm(grad)):.3g} at the start")
    best = (abs(g), u.copy(), g, grad.copy())
    history: List[float] = []
    converged = False
    capped = 0  # iterations in a row that ended on the sphere |u| = U_MAX still safe
    settled = 0  # iterations in a row whose move was within the noise's wander
    iteration = 0
    for iteration in range(1, int(max_iterations) + 1):
        norm2 = float(grad @ grad)
        if not (norm2 > 0 and math.isfinite(norm2)):
            raise _no_convergence(model, best, noise, f"the gradient of g vanished or is not finite at u = {_fmt(u)} (g flat at the step h = {h:.3g}: try a larger step=)")
        direction = (grad @ u - g) / norm2 * grad - u  # HL-RF step
        # Line search on the merit ½|u|² + c|g| (Zhang & Der Kiureghian 1995), c > |u|/|∇g|, to
        # within the noise g carries after a step: σ_g and the gradient's error times the step.
        c = 2.0 * max(float(np.linalg.norm(u)) / math.sqrt(norm2), 1.0)
        slack = c * NOISE_BAND * (noise + _gradient_noise(noise, h, d) * float(np.linalg.norm(direction)))
        merit0 = 0.5 * float(u @ u) + c * abs(g)
        # The full step and the gradient there go as one batch (accepted in most iterations);
        # a step the merit refuses is halved, one run a trial, and its gradient taken after.
        lam = 1.0
        trial = _clipped(u + direction)
        g_t, grad_t = _gradient(model, trial, h, on_failure)
        if 0.5 * float(trial @ trial) + c * abs(g_t) > merit0 + slack:
            for _ in range(4):
                lam *= 0.5
                trial = _clipped(u + lam * direction)
                g_t = float(model.limit_state(trial[None, :], on_failure)[0])
                if 0.5 * float(trial @ trial) + c * abs(g_t) <= merit0 + slack:
                    break
            g_t, grad_t = _gradient(model, trial, h, on_failure, g_u=g_t)
        moved = float(np.linalg.norm(trial - u))
        u, g, grad = trial, g_t, grad_t
        if auto:
            h = _step(noise, grad, h)
        if abs(g) < best[0]:
            best = (abs(g), u.copy(), g, grad.copy())
        history.append(moved)
        model.note(iteration, u, g, h)
        capped = capped + 1 if (float(np.linalg.norm(u)) >= U_MAX * (1 - 1e-9) and g > 0) else 0
        if capped >= 3:
            warnings.warn(
                f"FORM: the limit state is not reached within |u| ≤ {U_MAX:g} (g = {g:.3g} > 0 at u = {_fmt(u)}): the output stays "
                f"within its limit out to inputs of probability Φ(−{U_MAX:g}); reported as β = {U_MAX:g}, p_f = Φ(−{U_MAX:g}) (first order: at most this).",
                ReliabilityWarning, stacklevel=2,
            )  # fmt: skip
            x_far = {k: float(v[0]) for k, v in model.values(u[None, :]).items()}
            imp_far = dict(zip(model.random_names, map(float, (u / U_MAX) ** 2)))
            return FormResult(U_MAX, float(special.ndtr(-U_MAX)), x_far, u.copy(), imp_far, model.n_runs - runs0, time.perf_counter() - t0, False, noise, h, g,
                              0.0, False, iteration), g_start  # fmt: skip
        radius, norm_grad = float(np.linalg.norm(u)), math.sqrt(float(grad @ grad) or 1.0)
        # On the surface: within the tolerance of it in u (|g|/|∇g|, β's first-order error), or
        # within the noise of g after this step (σ_g and the gradient's error times the move).
        on_surface = (
            abs(g) <= G_TOLERANCE * g_scale or abs(g) / norm_grad <= tolerance * max(1.0, radius)
            or abs(g) <= NOISE_BAND * (noise + _gradient_noise(noise, h, d) * moved)
        )  # fmt: skip
        # How far u moves from one iteration to the next from the noise alone: the gradient's
        # direction is uncertain by about √d σ_g / (√2 h |∇g|), which turns u* on the sphere
        # |u| = β, plus g's own noise along the gradient, σ_g / |∇g|.
        wander = (_gradient_noise(noise, h, d) * radius + noise) / norm_grad
        if moved < tolerance * max(1.0, radius) and on_surface:
            converged = True
            break
        # A move within the noise's wander: converged when the last move was one too (a move
        # that is the search's own, on a curved limit state, shrinks from one to the next).
        settled = settled + 1 if moved < NOISE_BAND * wander else 0
        if settled >= 2 and on_surface:
            converged = True
            break
    if not converged:
        # One more look at the noise where the search ended: the start may have been smoother.
        if auto:
            noise_here = limit_state_noise(model, best[1], on_failure, seed=1)
            if abs(best[2]) <= NOISE_BAND * noise_here:
                noise = max(noise, noise_here)
                u, g, grad = best[1], best[2], best[3]
                converged = True
        if not converged:
            moves = ", ".join(f"{m:.3g}" for m in history[-3:])
            raise _no_convergence(model, best, noise, f"no design point after {iteration} iterations (the last moves of u: {moves}; |g| at the best point {best[0]:.3g}, noise σ_g = {noise:.3g})")
    norm_grad = float(np.linalg.norm(grad))
    alpha = -grad / norm_grad
    # β: the distance from the origin to the limit state linearised at u* (α·u* on the surface;
    # off it by |g|/|∇g|, which this corrects to first order).
    beta = float(alpha @ u) + g / norm_grad
    beta_noise = noise / norm_grad if norm_grad > 0 else math.inf
    accepted_at_noise = abs(g) > G_TOLERANCE * g_scale and abs(g) / norm_grad > tolerance * max(1.0, float(np.linalg.norm(u)))
    grad_noise = _gradient_noise(noise, h, d)  # the finite-difference gradient's own noise
    if norm_grad < 3.0 * grad_noise:
        raise _no_convergence(model, (abs(g), u, g, grad), noise, f"the gradient |∇g| = {norm_grad:.3g} is lost in its noise ({grad_noise:.3g} at the step h = {h:.3g} from σ_g = {noise:.3g})")
    if beta_noise > BETA_NOISE_LIMIT * max(1.0, abs(beta)):
        raise _no_convergence(model, (abs(g), u, g, grad), noise, f"the limit state's noise σ_g = {noise:.3g} makes β = {beta:.3g} uncertain by ±{beta_noise:.2g} (σ_g / |∇g|)")
    if accepted_at_noise:
        warnings.warn(
            f"FORM: design point accepted at the noise level of the limit state: |g(u*)| = {abs(g):.3g} is within {NOISE_BAND:g} × its noise "
            f"(σ_g = {noise:.3g} measured, and the gradient's error over the last step) but {abs(g) / norm_grad:.2g} off the surface in u, above "
            f"the tolerance {tolerance * max(1.0, float(np.linalg.norm(u))):.2g}; β = {beta:.4g} is uncertain by about "
            f"±{beta_noise:.2g} from the noise alone. Check p_f by importance sampling around this point.",
            ReliabilityWarning, stacklevel=2,
        )  # fmt: skip
    pf = float(special.ndtr(-beta))
    x_star = {k: float(v[0]) for k, v in model.values(u[None, :]).items()}
    imp = dict(zip(model.random_names, map(float, alpha**2)))
    return FormResult(beta, pf, x_star, u.copy(), imp, model.n_runs - runs0, time.perf_counter() - t0, True, noise, h, g, beta_noise, accepted_at_noise, iteration), g_start


def _clipped(u: np.ndarray) -> np.ndarray:
    """``u`` drawn back onto the sphere |u| = :data:`U_MAX` when beyond it."""
    radius = float(np.linalg.norm(u))
    return u * (U_MAX / radius) if radius > U_MAX else u


def _step(noise: float, grad: np.ndarray, h: float) -> float:
    norm = float(np.linalg.norm(grad))
    if not (norm > 0 and math.isfinite(norm)):
        return min(MAX_STEP, 10 * h)
    return float(np.clip(STEP_FACTOR * noise / norm, MIN_STEP, MAX_STEP))


def _fmt(u: np.ndarray) -> str:
    return "[" + ", ".join(f"{v:.3g}" for v in u) + "]"


def _no_convergence(model: ModelLike, best: Tuple[float, np.ndarray, float, np.ndarray], noise: float, why: str) -> ReliabilityError:
    x = {k: float(v[0]) for k, v in model.values(best[1][None, :]).items()}
    where = ", ".join(f"{k} = {v:.6g}" for k, v in x.items())
    return ReliabilityError(
        f"FORM did not converge: {why}. The limit state is too noisy or too curved for a gradient search here. "
        f"Best point: u = {_fmt(best[1])} ({where}), g = {best[2]:.3g}. Instead use importance sampling around the best point "
        f"(study.importance_sampling(design_point=err.best)), AK-MCS (study.ak_mcs) or subset simulation (study.subset), "
        f"or give a larger step= (now chosen from the noise σ_g = {noise:.3g}).",
        method="form", best=best[1].copy(),
    )  # fmt: skip


# ---------------------------------------------------------------- series systems
@dataclass
class SystemFormResult:
    """FORM of a series system (failure when any mode fails): each mode's :class:`FormResult`
    (``modes``, named by ``mode_names``), the correlation ``rho`` of their linearised margins
    (ρ_ij = α_i·α_j), the first-order series probability ``pf = 1 − Φ_m(β; ρ)`` with its
    generalised ``beta = −Φ⁻¹(pf)``, and Ditlevsen's ``bounds`` on the same first-order terms.
    ``design_point``, ``design_point_u`` and ``importance`` are the dominant mode's (largest
    Φ(−β_i)). ``mirrored``: the indices of the modes that are a second design point of the same
    limit state as the mode before them, found on the other side of the mean point (a limit
    state that fails on both sides: :func:`form`'s mirrored check)."""

    modes: List[FormResult]
    mode_names: List[str]
    rho: np.ndarray
    pf: float
    beta: float
    bounds: Tuple[float, float]
    n_runs: int
    wall_time: float
    dominant: int = 0
    extra: Dict[str, Any] = field(default_factory=dict)
    mirrored: List[int] = field(default_factory=list)

    def __repr__(self) -> str:
        return display.text(self, "pf", "beta", "bounds", "mode_names", "n_runs", "wall_time")

    def _repr_html_(self) -> str:
        return display.html(self, "pf", "beta", "bounds", "mode_names", "n_runs", "wall_time")

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf

    @property
    def design_point(self) -> Dict[str, float]:
        return self.modes[self.dominant].design_point

    @property
    def design_point_u(self) -> np.ndarray:
        return self.modes[self.dominant].design_point_u

    @property
    def importance(self) -> Dict[str, float]:
        return self.modes[self.dominant].importance

    @property
    def converged(self) -> bool:
        return all(m.converged for m in self.modes)


def series_probability(beta: Any, rho: np.ndarray) -> float:
    """First-order probability of a series system of linear modes with indices ``beta`` and
    correlation ``rho``: ``1 − Φ_m(β; ρ)`` (multinormal CDF, scipy's Genz algorithm)."""
    b = np.asarray(beta, dtype=float)
    if b.size == 1:
        return float(special.ndtr(-b[0]))
    r = np.array(rho, dtype=float)
    r = 0.5 * (r + r.T)
    np.fill_diagonal(r, 1.0)
    # A nearly singular ρ (two modes with the same design direction): nudge to positive definite.
    w, v = np.linalg.eigh(r)
    if w.min() < 1e-10:
        r = (v * np.maximum(w, 1e-10)) @ v.T
        dd = np.sqrt(np.diag(r))
        r = r / np.outer(dd, dd)
    p_safe = float(stats.multivariate_normal(mean=np.zeros(b.size), cov=r, allow_singular=True, abseps=1e-10, releps=1e-8).cdf(b))
    return float(min(1.0, max(0.0, 1.0 - p_safe, float(special.ndtr(-b).max()))))


def ditlevsen_bounds(beta: Any, rho: np.ndarray) -> Tuple[float, float]:
    """Ditlevsen's bounds on the first-order series probability from the modes' P_i = Φ(−β_i)
    and their joint failure probabilities P_ij = Φ₂(−β_i, −β_j; ρ_ij), modes taken in the order
    of decreasing P_i:  P₁ + Σ_{i≥2} max(0, P_i − Σ_{j<i} P_ij) ≤ p_f ≤ Σ P_i − Σ_{i≥2} max_{j<i} P_ij."""
    b = np.asarray(beta, dtype=float)
    order = np.argsort(b)
    b = b[order]
    r = np.asarray(rho, dtype=float)[np.ix_(order, order)]
    p = special.ndtr(-b)
    m = b.size
    pij = np.zeros((m, m))
    for i in range(m):
        for j in range(i):
            rr = float(np.clip(r[i, j], -0.999999, 0.999999))
            pij[i, j] = pij[j, i] = float(stats.multivariate_normal(mean=[0.0, 0.0], cov=[[1.0, rr], [rr, 1.0]]).cdf([-b[i], -b[j]]))
    lower = float(p[0]) + sum(max(0.0, float(p[i]) - float(pij[i, :i].sum())) for i in range(1, m))
    upper = float(p.sum()) - sum(float(pij[i, :i].max()) for i in range(1, m))
    return min(1.0, lower), min(1.0, upper)


def system_form(
    model: ModelLike, *, step: Union[float, str] = "auto", max_iterations: int = 50, on_failure: str = "fail", mirror: bool = True
) -> SystemFormResult:  # fmt: skip
    """FORM on each failure mode of a series system (each mode's own search, runs shared by
    nothing but the counter; with ``mirror``, each mode's mirrored check, a second design point
    joining the system as a mode of its own), then the system's first-order probability and
    bounds."""
    t0, runs0 = time.perf_counter(), model.n_runs
    names: List[str] = []
    results: List[FormResult] = []
    mirrored: List[int] = []
    for i, name in enumerate(model.mode_names):
        try:
            res = form(model.mode(i), step=step, max_iterations=max_iterations, on_failure=on_failure, mirror=mirror)
        except ReliabilityError as err:
            raise ReliabilityError(f"mode {i} ({name}): {err}", method="form", best=err.best, mode=name) from None
        if isinstance(res, SystemFormResult):
            mirrored += [len(results) + k for k in res.mirrored]
            names += res.mode_names
            results += res.modes
        else:
            names.append(name)
            results.append(res)
    return _series(results, names, model.n_runs - runs0, time.perf_counter() - t0, mirrored)


def _series(results: List[FormResult], names: List[str], n_runs: int, wall_time: float, mirrored: List[int]) -> SystemFormResult:
    """The series system of the design points ``results``: ρ_ij = α_i·α_j, the first-order
    probability of their union and Ditlevsen's bounds."""
    beta = np.array([r.beta for r in results])
    alpha = np.array([r.alpha for r in results])
    rho = alpha @ alpha.T
    pf = series_probability(beta, rho)
    bounds = ditlevsen_bounds(beta, rho)
    dominant = int(np.argmin(beta))
    generalised = float(-special.ndtri(pf)) if 0 < pf < 1 else (math.inf if pf == 0 else -math.inf)
    return SystemFormResult(results, names, rho, pf, generalised, bounds, n_runs, wall_time, dominant, mirrored=list(mirrored))
