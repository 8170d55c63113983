"""Periodic, quasi-periodic or chaotic: what a motion's Poincaré sections say
(docs/physics.md §13).

The section points are the pose at t_n = (n + phase/2π) T and at ``sub`` evenly spaced times
of each period between them, as features: per body x, y, cos θ, sin θ and per clearance joint
e_x, e_y — positions only: a motion whose poses repeat at every sampled phase repeats, and the
velocities of a journal in stiff contact carry the contact's fast, tolerance-sized vibration
(ṅ ≈ its frequency × the position error), which would hide a period. Each is scaled by its
range over all those samples (so a
clearance's millimetres count as much as a crank's metres), but by no less than ``FLOOR`` of
the largest range among the features of its kind (positions, directions, eccentricities): a
coordinate that stays put (a ball held on a vertical line) does not count its round-off as
motion.

* **period-k** (k ≤ 16): the smallest k such that every sample repeats k periods later within
  ``tol`` (default 1e-3) of its feature's scale plus the integration's own error there,
  atol + rtol × the largest body position (for positions and eccentricities) or 1 (for
  directions): a journal 0.17 m from the origin integrated at rtol 1e-5 is known to ±2 µm,
  whatever its clearance.
* otherwise, with the largest Lyapunov exponent λ (:mod:`clearsim.dynamics.lyapunov`):
  **chaotic** when its 95 % interval lies above 0 and λT > ``CHAOS_PER_PERIOD``,
  **quasi-periodic** when it holds 0 (a torus: λ = 0), and **period>16** when it lies below 0
  (a stable motion that has not repeated within 16 periods: a longer period, or a transient
  not over);
* without an exponent, the section itself: each point's nearest neighbour (not its own next or
  previous one) and how fast the two part over the next periods: on a torus the map is a smooth
  rotation and nearby points stay near (≈ 0 a period), on a strange attractor they part
  (> ``NEIGHBOUR_LOG_GROWTH``) — a coarse estimate of λT from the section (Rosenstein et al.
  1993) for when no shadow run was made.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

#: Longest period the clustering looks for [periods].
MAX_PERIOD = 16
#: Default tolerance of a repeat, relative to each feature's range.
TOL = 1e-3
#: λT above which an exponent whose interval excludes 0 is chaos, not a slow drift [-].
CHAOS_PER_PERIOD = 0.01
#: Growth of neighbouring section points' log-distance a period above which the section is
#: chaotic [-] (the Hénon map's 0.42 a step is found as 0.40, tori as ≤ 0.015), and the periods it
#: follows them.
NEIGHBOUR_LOG_GROWTH = 0.1
NEIGHBOUR_STEPS = 3
#: Smallest scale of a feature, relative to the largest range among the features of its kind.
FLOOR = 1e-4
#: Which values set the integration error of a feature of each kind (the error of e = r_j − r_b
#: is that of the positions, not a fraction of e).
NOISE_GROUP = {"position": "position", "eccentricity": "position", "direction": "direction"}
#: The kinds of :func:`features`, in its column order per body and per joint.
BODY_KINDS = ("position", "position", "direction", "direction")
JOINT_KINDS = ("eccentricity", "eccentricity")


@dataclass(frozen=True)
class Classification:
    """``kind``: ``"period-k"``, ``"quasi-periodic"``, ``"chaotic"`` or ``"period>16"``;
    ``period`` k (0 when not periodic); ``repeat``: the scaled distance of the best repeat
    (k periods later) [-]; ``how``: what decided it."""

    kind: str
    period: int
    repeat: float
    how: str


def features(q: np.ndarray, joints: Optional[np.ndarray]) -> Tuple[np.ndarray, List[str]]:
    """The section features (samples × features) of poses q (samples × 3 per body) and the
    joints' stored columns (samples × joints × columns; ``None`` without clearance joints), and
    the kind of each feature."""
    q = np.asarray(q, dtype=float)
    cols: List[np.ndarray] = []
    kinds: List[str] = []
    for b in range(q.shape[1] // 3):
        th = q[:, 3 * b + 2]
        cols += [q[:, 3 * b], q[:, 3 * b + 1], np.cos(th), np.sin(th)]
        kinds += BODY_KINDS
    if joints is not None and np.size(joints):
        j = np.asarray(joints, dtype=float)
        for k in range(j.shape[1]):
            cols += [j[:, k, 0], j[:, k, 1]]
            kinds += JOINT_KINDS
    return (np.stack(cols, axis=1) if cols else np.zeros((len(q), 0))), kinds


def _scales(f: np.ndarray, kinds: Optional[Sequence[str]], rtol: float, atol: float) -> Tuple[np.ndarray, np.ndarray]:
    """Each feature's scale (its range, at least ``FLOOR`` × the largest of its kind) and its
    integration error atol + rtol × the largest magnitude of its noise group."""
    span = np.ptp(f, axis=0) if len(f) else np.zeros(f.shape[1])
    size = np.max(np.abs(f), axis=0) if len(f) else np.zeros(f.shape[1])
    labels: List[object] = list(range(f.shape[1])) if kinds is None else list(kinds)
    scale = np.array(span, dtype=float)
    noise = np.zeros(f.shape[1])
    groups: dict = {}
    for i, k in enumerate(labels):
        groups.setdefault(NOISE_GROUP.get(k, k) if isinstance(k, str) else k, []).append(i)  # type: ignore[arg-type]
    for kind in set(labels):
        idx = [i for i, k in enumerate(labels) if k == kind]
        scale[idx] = np.maximum(span[idx], FLOOR * span[idx].max())
    for idx in groups.values():
        noise[idx] = atol + rtol * size[idx].max()
    return scale, noise


def scaled(f: np.ndarray, kinds: Optional[Sequence[str]] = None) -> np.ndarray:
    """Features divided by their scale (:func:`_scales`); a kind that does not move is dropped."""
    scale, _ = _scales(f, kinds, 0.0, 0.0)
    keep = scale > 0
    return f[:, keep] / scale[keep]


def repeat_distances(cycles: np.ndarray, allowance: Optional[np.ndarray] = None, max_period: int = MAX_PERIOD) -> np.ndarray:
    """d_k for k = 1 … max_period (at most half the cycles): the largest difference between a
    sample and the one k periods later at the same phase, less ``allowance`` (per feature, ≥ 0),
    over all samples and features (``cycles``: cycles × sub × features, already scaled)."""
    n = cycles.shape[0]
    out = []
    free = 0.0 if allowance is None else allowance
    for k in range(1, min(max_period, n // 2) + 1):
        out.append(float(np.max(np.maximum(np.abs(cycles[k:] - cycles[:-k]) - free, 0.0))) if cycles.size else 0.0)
    return np.asarray(out)


def neighbour_growth(points: np.ndarray, steps: int = NEIGHBOUR_STEPS) -> float:
    """How fast neighbouring section points part [per period]: each point's nearest neighbour
    (not within one period of it), the mean log-distance of the pairs' images 0 … ``steps``
    periods later, and the slope of its least-squares line (Rosenstein, Collins & De Luca 1993):
    ≈ λT on a strange attractor, ≈ 0 on a torus (``points``: cycles × features, scaled)."""
    n = len(points)
    if n < steps + 8:
        return float("nan")
    x = points[: n - steps]
    d = np.sqrt(((x[:, None, :] - x[None, :, :]) ** 2).sum(axis=2))
    idx = np.arange(n - steps)
    d[np.abs(idx[:, None] - idx[None, :]) <= 1] = np.inf
    nb = np.argmin(d, axis=1)
    logs = [float(np.mean(np.log(np.maximum(np.sqrt(((points[idx + j] - points[nb + j]) ** 2).sum(axis=1)), 1e-300)))) for j in range(steps + 1)]
    return float(np.polyfit(np.arange(steps + 1), logs, 1)[0])


def classify(
    cycles: np.ndarray,
    *,
    kinds: Optional[Sequence[str]] = None,
    tol: float = TOL,
    rtol: float = 0.0,
    atol: float = 0.0,
    exponent: Optional[float] = None,
    interval: Optional[Tuple[float, float]] = None,
    period: Optional[float] = None,
) -> Classification:
    """The :class:`Classification` of a motion from its section features ``cycles`` (cycles ×
    sub-samples a period × features, from :func:`features`, unscaled; ``kinds`` the features'
    kinds, default each its own; ``rtol``, ``atol``: the run's tolerances, whose error a repeat
    may have on top of ``tol``); ``exponent`` [1/s] with its ``interval`` and the forcing
    ``period`` [s] when a shadow run measured it."""
    c, s, d = cycles.shape
    scale, noise = _scales(cycles.reshape(c * s, d), kinds, rtol, atol)
    keep = scale > 0
    flat = (cycles[:, :, keep] / scale[keep])
    dist = repeat_distances(flat, noise[keep] / scale[keep])
    hit = np.nonzero(dist <= tol)[0]
    if len(hit):
        k = int(hit[0]) + 1
        return Classification(f"period-{k}", k, float(dist[k - 1]), f"repeats after {k} period(s) within {dist[k - 1]:.2g} of each feature's range beyond the integration error (tol {tol:g})")
    best = float(np.min(dist)) if len(dist) else float("nan")
    if exponent is not None and interval is not None and math.isfinite(exponent):
        lo, hi = interval
        per = exponent * (period or 1.0)
        if lo > 0 and per > CHAOS_PER_PERIOD:
            return Classification("chaotic", 0, best, f"λ = {exponent:.4g} 1/s (95 % [{lo:.3g}, {hi:.3g}]) > 0")
        if hi < 0:
            return Classification("period>16", 0, best, f"λ = {exponent:.4g} 1/s < 0 but no repeat within {MAX_PERIOD} periods")
        return Classification("quasi-periodic", 0, best, f"λ = {exponent:.4g} 1/s (95 % [{lo:.3g}, {hi:.3g}]) holds 0")
    growth = neighbour_growth(flat[:, 0, :])
    if math.isfinite(growth) and growth > NEIGHBOUR_LOG_GROWTH:
        return Classification("chaotic", 0, best, f"neighbouring section points part by e^{growth:.2f} a period (no exponent computed)")
    return Classification("quasi-periodic", 0, best, f"neighbouring section points stay together (e^{growth:.2f} a period; no exponent computed)")


__all__ = ["Classification", "MAX_PERIOD", "TOL", "classify", "features", "neighbour_growth", "repeat_distances", "scaled"]
