"""FOSM dynamic-accuracy reliability, paper Eqs. (27)–(32) (docs/physics.md §6).

The *allowable* error Δ (strength) and the *actual* error δ (stress) are taken as normal; the
reliability is ``R = P(Δ − δ > 0)`` (P27). With the allowable range ``[Δv, Δu]``::

    μ_S = (Δu + Δv) / 2                      (P31)
    σ_S = (Δu − Δv) / 6                      (P32)
    β   = (μ_S − μ_s) / sqrt(σ_S² + σ_s²)    (P30, reliability index)
    R   = Φ(β)                               (P29–P30)

where ``μ_s, σ_s`` are the mean and standard deviation of the actual error. The paper does not
say how ``μ_s, σ_s`` are formed; ours (docs/physics.md §6) is: per crank-angle bin (default 18°), the mean
and the population standard deviation of |error| over the analysed cycles in that bin (crank
angle taken modulo 360°).

Crank angle: ``|ω| t`` [deg] with t measured from t = 0, the time of the pose the user gives
(:func:`crank_angle_at`), whatever time a run starts from and however many turns it skips — not the
driver's own angle θ0 + ω t. A window of monitor time bins opens on a bin edge of that angle
(:func:`window_start_turns`) and :func:`bin_fold` says which crank-angle bin each time bin is.

Bin convention: bin edges are at ``k · bin_width`` degrees; a sample at angle ``a`` belongs to
``[k·w, (k+1)·w)`` with ``k = floor(a / w)``. A bin is reported by its **start angle**
(``bin_starts``, the "angle" of the paper's 198°, 216°, 270°, … minima) and, for plotting, by its
centre (``bin_centres``). If ``bin_width`` does not divide 360° the last bin of a cycle is
shorter (it ends at 360°).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..errors import InputError, check_finite
from .. import display
from ..lazy import lazy

special = lazy("scipy.special")

#: The paper's allowable error ranges ``(Δv, Δu)`` of the slider (section 5): displacement [m],
#: velocity [m/s], acceleration [m/s²].
PAPER_ALLOWABLE: Dict[str, Tuple[float, float]] = {
    "displacement": (0.0, 0.004),
    "velocity": (0.0, 0.6),
    "acceleration": (0.0, 200.0),
}

#: The paper's crank-angle bins [deg]: the default bin width of every per-bin estimate.
BIN_WIDTH = 18.0

ArrayLike = Union[float, Sequence[float], np.ndarray]
Allowable = Union[str, Tuple[float, float], Sequence[float]]

_EDGE_TOL = 1e-9  # [deg] a sample this close below an edge counts as on the edge (round-off)


def normal_cdf(x: ArrayLike) -> Union[float, np.ndarray]:
    """Standard normal CDF Φ(x) (``scipy.special.ndtr``); a float for a scalar argument."""
    out = special.ndtr(np.asarray(x, dtype=float))
    return float(out) if np.ndim(out) == 0 else out


def normal_ppf(p: ArrayLike) -> Union[float, np.ndarray]:
    """Inverse standard normal CDF Φ⁻¹(p) for p in [0, 1] (±inf at 0 and 1;
    ``scipy.special.ndtri``)."""
    arr = np.asarray(p, dtype=float)
    bad = ~((arr >= 0.0) & (arr <= 1.0))  # also catches NaN
    if np.any(bad):
        v = np.atleast_1d(arr)[np.atleast_1d(bad)][0]
        raise InputError(f"invalid p = {v!r}: a probability must lie in [0, 1]", field="p", value=v)
    out = special.ndtri(arr)
    return float(out) if np.ndim(out) == 0 else out


def _check_range(lower: Any, upper: Any, lower_field: str = "allowable.lower", upper_field: str = "allowable.upper") -> Tuple[float, float]:
    """Finite ``lower < upper``, else :class:`InputError` naming the offending field."""
    lo = check_finite(lower_field, lower)
    hi = check_finite(upper_field, upper)
    if not lo < hi:
        raise InputError(f"invalid {lower_field} = {lower!r}: must be below {upper_field} = {upper!r}", field=lower_field, value=lower)
    return lo, hi


def _resolve_allowable(allowable: Allowable) -> Tuple[float, float]:
    if isinstance(allowable, str):
        if allowable not in PAPER_ALLOWABLE:
            raise InputError(
                f"invalid allowable = {allowable!r}: must be (lower, upper) or one of {', '.join(PAPER_ALLOWABLE)}",
                field="allowable",
                value=allowable,
            )
        return PAPER_ALLOWABLE[allowable]
    try:
        lo, hi = allowable  # type: ignore[misc]
    except (TypeError, ValueError):
        raise InputError(f"invalid allowable = {allowable!r}: must be a pair (lower, upper)", field="allowable", value=allowable) from None
    return _check_range(lo, hi)


def allowable_statistics(lower: float, upper: float) -> Tuple[float, float]:
    """Mean and standard deviation of the allowable error from its range ``[Δv, Δu]``.

    ``μ_S = (Δu + Δv)/2`` (P31), ``σ_S = (Δu − Δv)/6`` (P32) — the range is taken as ±3σ.
    Units are those of the error (m, m/s or m/s²).

    >>> allowable_statistics(0.0, 0.6)
    (0.3, 0.1)
    """
    lo, hi = _check_range(lower, upper)
    return (hi + lo) / 2.0, (hi - lo) / 6.0


def reliability_index(mu_S: ArrayLike, sigma_S: ArrayLike, mu_s: ArrayLike, sigma_s: ArrayLike) -> Union[float, np.ndarray]:
    """Reliability index ``β = (μ_S − μ_s) / sqrt(σ_S² + σ_s²)`` (P30); R = Φ(β).

    ``S`` = allowable error (strength), ``s`` = actual error (stress), all in the same unit.
    Broadcasts over arrays; returns a float when every argument is a scalar.
    """
    args = [np.asarray(a, dtype=float) for a in (mu_S, sigma_S, mu_s, sigma_s)]
    for name, a in zip(("mu_S", "sigma_S", "mu_s", "sigma_s"), args):
        if np.any(np.isnan(a)):
            raise InputError(f"invalid {name} = nan: must be a number", field=name, value=float("nan"))
    for name, a in (("sigma_S", args[1]), ("sigma_s", args[3])):
        if np.any(a < 0.0):
            v = float(a[a < 0.0].flat[0])
            raise InputError(f"invalid {name} = {v!r}: a standard deviation cannot be negative", field=name, value=v)
    denom = np.sqrt(args[1] ** 2 + args[3] ** 2)
    if np.any(denom == 0.0):
        raise InputError("invalid sigma_S = 0: sigma_S and sigma_s are both zero, β is undefined", field="sigma_S", value=0.0)
    beta = (args[0] - args[2]) / denom
    return float(beta) if beta.ndim == 0 else beta


def _check_bin_width(bin_width: Any) -> float:
    w = check_finite("bin_width", bin_width)
    if not 0.0 < w <= 360.0:
        raise InputError(f"invalid bin_width = {bin_width!r}: must be in (0, 360] degrees", field="bin_width", value=bin_width)
    return w


def _as_finite_array(name: str, value: Any, ndim: Optional[Tuple[int, ...]] = None) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"invalid {name}: must be an array of numbers", field=name, value=value) from None
    if ndim is not None and arr.ndim not in ndim:
        raise InputError(f"invalid {name}: must have {' or '.join(map(str, ndim))} dimension(s), got shape {arr.shape}", field=name, value=arr.shape)
    if arr.size == 0:
        raise InputError(f"invalid {name}: empty array", field=name, value=arr.shape)
    bad = ~np.isfinite(arr)
    if np.any(bad):
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        v = float(arr[idx])
        raise InputError(f"invalid {name}{list(idx)} = {v!r}: must be finite", field=name, value=v)
    return arr


@dataclass(frozen=True)
class _Bins:
    """Assignment of samples to crank-angle bins."""

    index: np.ndarray  # bin of each sample (same shape as the angles)
    starts: np.ndarray  # [deg] bin start angles
    centres: np.ndarray  # [deg]
    cycle: np.ndarray  # cycle of each bin (0 when pooled)


def _assign_bins(angle: np.ndarray, width: float, per_cycle: bool) -> _Bins:
    """Bins of width ``width`` [deg] with edges at k·width inside each 360° cycle."""
    n_in_cycle = int(math.ceil(360.0 / width - 1e-9))
    starts1 = np.arange(n_in_cycle) * width
    ends1 = np.minimum(starts1 + width, 360.0)
    a = angle + _EDGE_TOL
    cyc = np.floor(a / 360.0)
    within = np.clip(np.floor((a - 360.0 * cyc) / width).astype(np.int64), 0, n_in_cycle - 1)
    if not per_cycle:
        return _Bins(within, starts1, (starts1 + ends1) / 2.0, np.zeros(n_in_cycle, dtype=np.int64))
    c0 = int(cyc.min())
    cycles = np.arange(c0, int(cyc.max()) + 1)
    index = (cyc.astype(np.int64) - c0) * n_in_cycle + within
    starts = (360.0 * cycles[:, None] + starts1[None, :]).ravel()
    centres = (360.0 * cycles[:, None] + ((starts1 + ends1) / 2.0)[None, :]).ravel()
    return _Bins(index, starts, centres, np.repeat(cycles, n_in_cycle))


def crank_angle_at(t: Any, omega: float) -> np.ndarray:
    """The crank angle [deg] of every per-bin answer at times ``t`` [s]: ``|ω| t`` with t from
    t = 0 (the given pose's time) whatever the run's start, unwrapped (docs/physics.md §6)."""
    return np.degrees(abs(float(omega)) * np.asarray(t, dtype=float))


def window_start_turns(turns: float, bin_width: float) -> float:
    """The first bin edge of the crank angle |ω| t at or after ``turns`` crank turns, in turns:
    where an analysed window of time bins ``bin_width`` [deg] wide opens, so that each time bin
    is one crank-angle bin (docs/physics.md §6)."""
    edges = turns * 360.0 / bin_width
    return math.ceil(edges - _EDGE_TOL * max(1.0, abs(edges))) * bin_width / 360.0


def bin_fold(start_turns: float, bin_width: float, n_time_bins: int) -> np.ndarray:
    """The crank-angle bin (0 … ⌈360/bin_width⌉ − 1, edges at k·bin_width of |ω| t modulo 360°)
    of each of ``n_time_bins`` monitor time bins ``bin_width`` [deg] wide from a window opening
    at ``start_turns`` turns (a bin edge, :func:`window_start_turns`): the bin each time bin
    starts in (one and the same bin when ``bin_width`` divides 360°)."""
    per_cycle = int(math.ceil(360.0 / bin_width - 1e-9))
    first = int(round(start_turns * 360.0 / bin_width))
    k = first + np.arange(int(n_time_bins))
    if abs(360.0 / bin_width - round(360.0 / bin_width)) < 1e-9:
        return k % per_cycle
    return np.clip(np.floor(((k * bin_width) % 360.0 + _EDGE_TOL) / bin_width).astype(np.int64), 0, per_cycle - 1)


def _binned_moments(values: np.ndarray, index: np.ndarray, n_bins: int, ddof: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Count, mean and standard deviation of ``values`` per bin (two-pass; NaN for empty bins)."""
    v = values.ravel()
    i = index.ravel()
    counts = np.bincount(i, minlength=n_bins)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.bincount(i, weights=v, minlength=n_bins) / counts
        dev2 = np.bincount(i, weights=(v - mean[i]) ** 2, minlength=n_bins)
        var = dev2 / (counts - ddof)
    var[counts <= ddof] = np.where(counts[counts <= ddof] > 0, 0.0, np.nan)
    mean[counts == 0] = np.nan
    return counts, mean, np.sqrt(var)


@dataclass
class FosmResult:
    """FOSM dynamic-accuracy reliability per crank-angle bin (P27–P32, docs/physics.md §6).

    Angles in degrees; ``mu_s``, ``sigma_s``, ``mu_S``, ``sigma_S`` in the unit of the error
    (m, m/s or m/s²). Empty bins (no sample) have ``count`` 0 and NaN statistics and are ignored
    by the minimum.

    Attributes
    ----------
    bin_starts:
        Start angle of each bin [deg] — the angle at which the paper reports minima.
    bin_centres:
        Centre angle of each bin [deg] (for plotting).
    cycle:
        Cycle number of each bin (``floor(angle/360)``; all 0 for the pooled bins).
    count:
        Number of samples in each bin.
    mu_s, sigma_s:
        Mean and standard deviation of |error| per bin.
    beta, reliability:
        Reliability index β (P30) and R = Φ(β) per bin.
    mu_S, sigma_S:
        Allowable-error statistics (P31–P32).
    bin_width:
        Bin width [deg].
    min_reliability, min_angle, min_centre, min_beta:
        The smallest R, its bin start angle [deg], bin centre [deg] and β.
    per_cycle:
        With ``fosm(..., per_cycle=True)``: the same analysis with one set of bins per cycle
        (angles 0 … 360·cycles); else ``None``.
    """

    bin_starts: np.ndarray
    bin_centres: np.ndarray
    cycle: np.ndarray
    count: np.ndarray
    mu_s: np.ndarray
    sigma_s: np.ndarray
    beta: np.ndarray
    reliability: np.ndarray
    mu_S: float
    sigma_S: float
    bin_width: float
    min_reliability: float = field(init=False)
    min_angle: float = field(init=False)
    min_centre: float = field(init=False)
    min_beta: float = field(init=False)
    per_cycle: Optional["FosmResult"] = None

    def __repr__(self) -> str:
        return display.text(self, "min_reliability", "min_beta", "min_angle", "bin_width", "bin_starts", "mu_S", "sigma_S")

    def _repr_html_(self) -> str:
        return display.html(self, "min_reliability", "min_beta", "min_angle", "bin_width", "bin_starts", "mu_S", "sigma_S")

    def __post_init__(self) -> None:
        k = _nanargmin(self.reliability, self.beta)
        self.min_reliability = float(self.reliability[k])
        self.min_angle = float(self.bin_starts[k])
        self.min_centre = float(self.bin_centres[k])
        self.min_beta = float(self.beta[k])

    def cycle_minima(self) -> List[Dict[str, float]]:
        """Minimum reliability of each cycle: ``cycle``, ``angle`` (bin start [deg]),
        ``centre`` [deg], ``beta``, ``reliability`` (like the paper's Fig. 11a discussion)."""
        rows: List[Dict[str, float]] = []
        for c in np.unique(self.cycle):
            sel = np.flatnonzero((self.cycle == c) & (self.count > 0))
            if sel.size == 0:
                continue
            k = sel[_nanargmin(self.reliability[sel], self.beta[sel])]
            rows.append(
                {
                    "cycle": int(c),
                    "angle": float(self.bin_starts[k]),
                    "centre": float(self.bin_centres[k]),
                    "beta": float(self.beta[k]),
                    "reliability": float(self.reliability[k]),
                }
            )
        return rows

    def to_rows(self) -> List[Dict[str, float]]:
        """One dict per bin, for ``csv.DictWriter``: ``cycle``, ``angle_deg`` (bin start),
        ``centre_deg``, ``count``, ``mu_s``, ``sigma_s``, ``mu_S``, ``sigma_S``, ``beta``,
        ``reliability``."""
        return [
            {
                "cycle": int(self.cycle[k]),
                "angle_deg": float(self.bin_starts[k]),
                "centre_deg": float(self.bin_centres[k]),
                "count": int(self.count[k]),
                "mu_s": float(self.mu_s[k]),
                "sigma_s": float(self.sigma_s[k]),
                "mu_S": self.mu_S,
                "sigma_S": self.sigma_S,
                "beta": float(self.beta[k]),
                "reliability": float(self.reliability[k]),
            }
            for k in range(len(self.bin_starts))
        ]


def _nanargmin(reliability: np.ndarray, beta: np.ndarray) -> int:
    """Index of the smallest R (ties, e.g. R rounding to 1.0, broken by the smallest β)."""
    ok = np.isfinite(beta)
    if not np.any(ok):
        raise InputError("invalid error: no bin holds a sample", field="error", value=None)
    r = np.where(ok, reliability, np.inf)
    cand = np.flatnonzero(r == r.min())
    return int(cand[np.argmin(beta[cand])])


def _fosm_bins(abs_err: np.ndarray, bins: _Bins, mu_S: float, sigma_S: float, width: float, ddof: int) -> FosmResult:
    n = len(bins.starts)
    count, mu_s, sigma_s = _binned_moments(abs_err, bins.index, n, ddof)
    beta = np.full(n, np.nan)
    ok = count > 0
    beta[ok] = (mu_S - mu_s[ok]) / np.sqrt(sigma_S**2 + sigma_s[ok] ** 2)
    rel = np.full(n, np.nan)
    rel[ok] = normal_cdf(beta[ok])
    return FosmResult(bins.starts, bins.centres, bins.cycle, count, mu_s, sigma_s, beta, rel, mu_S, sigma_S, width)


def _check_angles(crank_angle: Any, n: int, name: str = "crank_angle", increasing: bool = False) -> np.ndarray:
    ang = _as_finite_array(name, crank_angle, ndim=(1,))
    if ang.shape[0] != n:
        raise InputError(f"invalid {name}: has {ang.shape[0]} samples but error has {n}", field=name, value=ang.shape[0])
    if increasing and np.any(np.diff(ang) < 0.0):
        k = int(np.flatnonzero(np.diff(ang) < 0.0)[0]) + 1
        raise InputError(
            f"invalid {name}[{k}] = {ang[k]!r}: must be unwrapped and non-decreasing (got {ang[k - 1]!r} before it); "
            "pass e.g. degrees(|ω| t) rather than an angle wrapped to [0, 360)",
            field=name,
            value=float(ang[k]),
        )
    return ang


def fosm(
    error: ArrayLike,
    crank_angle: ArrayLike,
    allowable: Allowable,
    bin_width: float = BIN_WIDTH,
    per_cycle: bool = False,
    ddof: int = 0,
) -> FosmResult:
    """FOSM reliability of one output per crank-angle bin (P27–P32, docs/physics.md §6).

    Parameters
    ----------
    error:
        Error samples of one output over time (clearance − ideal response, any sign) [m, m/s or
        m/s²]; the statistics use |error|.
    crank_angle:
        Crank angle of each sample [deg], unwrapped and non-decreasing (e.g. ``degrees(|ω| t)``
        with t from t = 0, :func:`crank_angle_at`,
        possibly over several cycles). Pass only the samples of the cycles to analyse (drop the
        start-up transient by slicing).
    allowable:
        Allowable error range ``(Δv, Δu)`` in the unit of ``error``, or a key of
        :data:`PAPER_ALLOWABLE` (``"displacement"``, ``"velocity"``, ``"acceleration"``).
    bin_width:
        Bin width [deg], in (0, 360]. Edges at k·bin_width; bins reported by start angle.
    per_cycle:
        Also bin each cycle separately (``result.per_cycle``, angles 0 … 360·cycles). A sample
        exactly at 360·k (e.g. the end point of an output grid of whole cycles) opens the first
        bin of cycle k; drop it (``endpoint=False``) to avoid a one-sample cycle.
    ddof:
        Delta degrees of freedom of σ_s (0: population standard deviation of the bin's samples).

    Returns
    -------
    FosmResult
        Bins of one cycle (angle modulo 360°) pooled over all cycles, with the minimum R.
    """
    err = _as_finite_array("error", error, ndim=(1,))
    ang = _check_angles(crank_angle, err.shape[0], increasing=per_cycle)
    width = _check_bin_width(bin_width)
    if isinstance(ddof, bool) or not isinstance(ddof, (int, np.integer)) or ddof < 0:
        raise InputError(f"invalid ddof = {ddof!r}: must be a non-negative integer", field="ddof", value=ddof)
    lo, hi = _resolve_allowable(allowable)
    mu_S, sigma_S = allowable_statistics(lo, hi)
    abs_err = np.abs(err)
    result = _fosm_bins(abs_err, _assign_bins(ang, width, False), mu_S, sigma_S, width, ddof)
    if per_cycle:
        result.per_cycle = _fosm_bins(abs_err, _assign_bins(ang, width, True), mu_S, sigma_S, width, ddof)
    return result




def fosm_from_monitors(
    monitors: Sequence[Mapping[str, Any]], fold: np.ndarray, bin_starts: np.ndarray, bin_centres: np.ndarray, cycle: np.ndarray, mu_S: float, sigma_S: float, width: float
) -> FosmResult:
    """FOSM (P27–P32) per crank-angle bin from the integrator's monitor bins (the one place this
    is computed): the monitors' time bins ``k`` are folded onto crank-angle bin ``fold[k]``, and
    per bin μ_s = Σ∫|e|dt / Σ∫dt, σ_s² = Σ∫e²dt / Σ∫dt − μ_s² over the monitors (runs) and the
    analysed cycles, so neither depends on a stored output grid; ``count`` is the number of
    (run, time bin) pairs that saw the bin."""
    n_bins = len(bin_starts)
    n_time = len(fold)
    integral = np.zeros((3, n_bins))
    count = np.zeros(n_bins, dtype=int)
    for mon in monitors:
        for row, key in enumerate(("bin_abs", "bin_sq", "bin_time")):
            np.add.at(integral[row], fold, np.asarray(mon[key], dtype=float)[:n_time])
        np.add.at(count, fold, (np.asarray(mon["bin_time"], dtype=float)[:n_time] > 0).astype(int))
    with np.errstate(invalid="ignore", divide="ignore"):
        mu_s = integral[0] / integral[2]
        sigma_s = np.sqrt(np.maximum(integral[1] / integral[2] - mu_s**2, 0.0))
    # A window shorter than a turn leaves bins no run saw: NaN there, as fosm() leaves empty bins.
    seen = integral[2] > 0.0
    beta = np.full(n_bins, np.nan)
    rel = np.full(n_bins, np.nan)
    if np.any(seen):
        beta[seen] = np.asarray(reliability_index(mu_S, sigma_S, mu_s[seen], sigma_s[seen]), dtype=float)
        rel[seen] = normal_cdf(beta[seen])
    return FosmResult(np.asarray(bin_starts, dtype=float), np.asarray(bin_centres, dtype=float), np.asarray(cycle), count, mu_s, sigma_s, beta, rel, mu_S, sigma_S, width)
