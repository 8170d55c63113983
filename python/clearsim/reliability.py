"""Dynamic-accuracy reliability of a mechanism output (docs/physics.md §6, paper section 4).

First-order second moment (FOSM) method, paper Eqs. (27)–(32)
----------------------------------------------------------------
The *allowable* error Δ (strength) and the *actual* error δ (stress) are taken as normal; the
reliability is ``R = P(Δ − δ > 0)`` (P27). With the allowable range ``[Δv, Δu]``::

    μ_S = (Δu + Δv) / 2                      (P31)
    σ_S = (Δu − Δv) / 6                      (P32)
    β   = (μ_S − μ_s) / sqrt(σ_S² + σ_s²)    (P30, reliability index)
    R   = Φ(β)                               (P29–P30)

where ``μ_s, σ_s`` are the mean and standard deviation of the actual error. The paper does not
say how ``μ_s, σ_s`` are formed; ours (docs/physics.md §6) is: per crank-angle bin (default 18°), the mean
and the population standard deviation of |error| over all samples of the analysed cycles that
fall in that bin (crank angle taken modulo 360°).

Bin convention
--------------
Bin edges are at ``k · bin_width`` degrees (k = 0, 1, …); a sample at angle ``a`` belongs to the
bin ``[k·w, (k+1)·w)`` with ``k = floor(a / w)`` (a sample exactly on an edge belongs to the bin
that *starts* there). A bin is reported by its **start angle** (``bin_starts``, the "angle" of
the paper's 198°, 216°, 270°, … minima) and, for plotting, by its centre (``bin_centres``). If
``bin_width`` does not divide 360° the last bin of a cycle is shorter (it ends at 360°).

Monte Carlo (beyond the paper)
------------------------------
Distributions of random inputs (:class:`Fixed`, :class:`Normal`, :class:`Uniform`,
:class:`LogNormal`, :class:`TruncatedNormal`), :func:`sample_inputs`, the Wilson score interval,
the first-passage probability that |error| leaves the allowable range anywhere
(:func:`first_passage_probability`), and per-bin Monte Carlo reliability next to FOSM
(:func:`mc_bin_reliability`, :func:`compare_fosm_mc`). Running the simulations is left to the
caller; these functions only do the statistics.

This module depends on numpy only (Φ from :func:`math.erfc`, Φ⁻¹ by Acklam's rational
approximation refined by one Halley step).
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from .errors import InputError, check_finite

__all__ = [
    "PAPER_ALLOWABLE",
    "Distribution",
    "Estimate",
    "Fixed",
    "FosmResult",
    "LogNormal",
    "MonteCarloBins",
    "Normal",
    "TruncatedNormal",
    "Uniform",
    "allowable_statistics",
    "compare_fosm_mc",
    "first_passage_probability",
    "fosm",
    "mc_bin_reliability",
    "normal_cdf",
    "normal_ppf",
    "reliability_index",
    "sample_inputs",
    "wilson_interval",
]

#: The paper's allowable error ranges ``(Δv, Δu)`` of the slider (section 5): displacement [m],
#: velocity [m/s], acceleration [m/s²].
PAPER_ALLOWABLE: Dict[str, Tuple[float, float]] = {
    "displacement": (0.0, 0.004),
    "velocity": (0.0, 0.6),
    "acceleration": (0.0, 200.0),
}

ArrayLike = Union[float, Sequence[float], np.ndarray]
Allowable = Union[str, Tuple[float, float], Sequence[float]]

_SQRT2 = math.sqrt(2.0)
_SQRT2PI = math.sqrt(2.0 * math.pi)
_EDGE_TOL = 1e-9  # [deg] a sample this close below an edge counts as on the edge (round-off)


# ====================================================================== normal distribution
_erfc = np.vectorize(math.erfc, otypes=[float])


def normal_cdf(x: ArrayLike) -> Union[float, np.ndarray]:
    """Standard normal CDF Φ(x) = ½ erfc(−x/√2) (accurate in both tails).

    Returns a float for a scalar argument, else an array of the argument's shape.
    """
    if np.ndim(x) == 0:
        return 0.5 * math.erfc(-float(x) / _SQRT2)  # type: ignore[arg-type]
    return 0.5 * _erfc(-np.asarray(x, dtype=float) / _SQRT2)


# Acklam's coefficients (relative error < 1.15e-9 before refinement).
_A = (-3.969683028665376e01, 2.209460984245205e02, -2.759285104469687e02, 1.383577518672690e02, -3.066479806614716e01, 2.506628277459239e00)
_B = (-5.447609879822406e01, 1.615858368580409e02, -1.556989798598866e02, 6.680131188771972e01, -1.328068155288572e01)
_C = (-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e00, -2.549732539343734e00, 4.374664141464968e00, 2.938163982698783e00)
_D = (7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e00, 3.754408661907416e00)
_P_LOW = 0.02425


def _ppf_lower(p: np.ndarray) -> np.ndarray:
    """Φ⁻¹(p) for 0 < p ≤ 0.5 (so that the refinement works where Φ is accurate)."""
    x = np.empty_like(p)
    tail = p < _P_LOW
    if np.any(tail):
        q = np.sqrt(-2.0 * np.log(p[tail]))
        x[tail] = (((((_C[0] * q + _C[1]) * q + _C[2]) * q + _C[3]) * q + _C[4]) * q + _C[5]) / (
            (((_D[0] * q + _D[1]) * q + _D[2]) * q + _D[3]) * q + 1.0
        )
    mid = ~tail
    if np.any(mid):
        q = p[mid] - 0.5
        r = q * q
        x[mid] = (((((_A[0] * r + _A[1]) * r + _A[2]) * r + _A[3]) * r + _A[4]) * r + _A[5]) * q / (
            ((((_B[0] * r + _B[1]) * r + _B[2]) * r + _B[3]) * r + _B[4]) * r + 1.0
        )
    # One Halley step on Φ(x) − p = 0: u = (Φ(x) − p)/φ(x), x ← x − u/(1 + x u/2).
    e = 0.5 * _erfc(-x / _SQRT2) - p
    u = e * _SQRT2PI * np.exp(0.5 * x * x)
    return x - u / (1.0 + 0.5 * x * u)


def normal_ppf(p: ArrayLike) -> Union[float, np.ndarray]:
    """Inverse standard normal CDF Φ⁻¹(p) for p in [0, 1] (±inf at 0 and 1).

    Acklam's rational approximation refined by one Halley step (agrees with
    ``scipy.stats.norm.ppf`` to ~1e-15 relative); the upper half is computed as −Φ⁻¹(1 − p),
    which is exact in floating point for p ≥ 0.5.
    """
    scalar = np.ndim(p) == 0
    arr = np.atleast_1d(np.asarray(p, dtype=float))
    bad = ~((arr >= 0.0) & (arr <= 1.0))  # also catches NaN
    if np.any(bad):
        v = arr[bad][0]
        raise InputError(f"invalid p = {v!r}: a probability must lie in [0, 1]", field="p", value=v)
    out = np.empty_like(arr)
    out[arr == 0.0] = -np.inf
    out[arr == 1.0] = np.inf
    lower = (arr > 0.0) & (arr <= 0.5)
    upper = (arr > 0.5) & (arr < 1.0)
    if np.any(lower):
        out[lower] = _ppf_lower(arr[lower])
    if np.any(upper):
        out[upper] = -_ppf_lower(1.0 - arr[upper])
    return float(out[0]) if scalar else out.reshape(np.shape(p))


# ====================================================================== FOSM (P27–P32)
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

    def __post_init__(self) -> None:
        k = _nanargmin(self.reliability, self.beta)
        self.min_reliability = float(self.reliability[k])
        self.min_angle = float(self.bin_starts[k])
        self.min_centre = float(self.bin_centres[k])
        self.min_beta = float(self.beta[k])

    @property
    def angle(self) -> np.ndarray:
        """Alias of :attr:`bin_starts` [deg]."""
        return self.bin_starts

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
    bin_width: float = 18.0,
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
        Crank angle of each sample [deg], unwrapped and non-decreasing (e.g. ``degrees(|ω| t)``,
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


# ====================================================================== Monte Carlo inputs
class Distribution:
    """Base class of the random-input distributions: ``sample(n, rng)`` → array of n draws."""

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError


def _nonneg(field_name: str, value: Any) -> float:
    v = check_finite(field_name, value)
    if v < 0.0:
        raise InputError(f"invalid {field_name} = {value!r}: must not be negative", field=field_name, value=value)
    return v


@dataclass(frozen=True)
class Fixed(Distribution):
    """A deterministic value (every draw equals ``value``)."""

    value: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", check_finite("Fixed.value", self.value))

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        return np.full(_check_n(n), self.value)


@dataclass(frozen=True)
class Normal(Distribution):
    """Normal distribution with mean ``mean`` and standard deviation ``std`` (≥ 0)."""

    mean: float
    std: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mean", check_finite("Normal.mean", self.mean))
        object.__setattr__(self, "std", _nonneg("Normal.std", self.std))

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        return rng.normal(self.mean, self.std, _check_n(n)) if self.std > 0 else np.full(_check_n(n), self.mean)


@dataclass(frozen=True)
class Uniform(Distribution):
    """Uniform distribution on ``[low, high)`` (low < high)."""

    low: float
    high: float

    def __post_init__(self) -> None:
        lo, hi = _check_range(self.low, self.high, "Uniform.low", "Uniform.high")
        object.__setattr__(self, "low", lo)
        object.__setattr__(self, "high", hi)

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        return rng.uniform(self.low, self.high, _check_n(n))


@dataclass(frozen=True)
class LogNormal(Distribution):
    """Log-normal distribution given by the mean (> 0) and standard deviation of the variable
    itself (not of its logarithm): ``σ_ln² = ln(1 + (std/mean)²)``, ``μ_ln = ln(mean) − σ_ln²/2``.
    Suits strictly positive inputs such as clearances and viscosities."""

    mean: float
    std: float

    def __post_init__(self) -> None:
        m = check_finite("LogNormal.mean", self.mean)
        if m <= 0.0:
            raise InputError(f"invalid LogNormal.mean = {self.mean!r}: must be positive", field="LogNormal.mean", value=self.mean)
        object.__setattr__(self, "mean", m)
        object.__setattr__(self, "std", _nonneg("LogNormal.std", self.std))

    @property
    def log_params(self) -> Tuple[float, float]:
        """``(μ_ln, σ_ln)`` of ln X."""
        s2 = math.log1p((self.std / self.mean) ** 2)
        return math.log(self.mean) - 0.5 * s2, math.sqrt(s2)

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        mu, s = self.log_params
        return rng.lognormal(mu, s, _check_n(n)) if s > 0 else np.full(_check_n(n), self.mean)


@dataclass(frozen=True)
class TruncatedNormal(Distribution):
    """Normal distribution ``N(mean, std²)`` restricted to ``[low, high]``.

    ``mean`` and ``std`` are those of the parent (untruncated) normal, as in
    ``scipy.stats.truncnorm``; the truncated variable's own mean and std differ unless the bounds
    are far away. Sampled by inverting the CDF (exact, no rejection), on the mirrored side when
    the interval lies in the upper tail so that far tails keep their precision.
    """

    mean: float
    std: float
    low: float
    high: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mean", check_finite("TruncatedNormal.mean", self.mean))
        s = check_finite("TruncatedNormal.std", self.std)
        if s <= 0.0:
            raise InputError(f"invalid TruncatedNormal.std = {self.std!r}: must be positive", field="TruncatedNormal.std", value=self.std)
        object.__setattr__(self, "std", s)
        lo = float(self.low)
        hi = float(self.high)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise InputError(
                f"invalid TruncatedNormal.low = {self.low!r}: must be below TruncatedNormal.high = {self.high!r}",
                field="TruncatedNormal.low",
                value=self.low,
            )
        object.__setattr__(self, "low", lo)
        object.__setattr__(self, "high", hi)

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        a = (self.low - self.mean) / self.std
        b = (self.high - self.mean) / self.std
        flip = a > 0.0  # interval in the upper tail: sample −X on [−b, −a] instead
        if flip:
            a, b = -b, -a
        pa, pb = normal_cdf(a), normal_cdf(b)
        if not pb > pa:
            raise InputError(
                f"invalid TruncatedNormal.low = {self.low!r}: the interval [{self.low!r}, {self.high!r}] has no probability under N({self.mean!r}, {self.std!r}²)",
                field="TruncatedNormal.low",
                value=self.low,
            )
        u = rng.uniform(pa, pb, _check_n(n))
        z = np.clip(normal_ppf(np.clip(u, 0.0, 1.0)), a, b)
        if flip:
            z = -z
        return self.mean + self.std * z


def _check_n(n: Any) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    return int(n)


def sample_inputs(distributions: Mapping[str, Union[Distribution, float]], n: int, seed: Optional[int] = None) -> Dict[str, np.ndarray]:
    """Draw ``n`` independent samples of each named random input.

    Each name gets its own random stream seeded by ``(seed, crc32(name))``, so the samples of an
    input do not depend on the order of the mapping or on which other inputs are present
    (common random numbers across studies). Plain numbers are taken as :class:`Fixed`.

    Returns ``{name: array of shape (n,)}``, in the units of the distributions.
    """
    n = _check_n(n)
    if seed is None:
        base = int(np.random.SeedSequence().entropy)  # type: ignore[arg-type]
    else:
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise InputError(f"invalid seed = {seed!r}: must be a non-negative integer", field="seed", value=seed)
        base = int(seed)
    out: Dict[str, np.ndarray] = {}
    for name, dist in distributions.items():
        if not isinstance(dist, Distribution):
            dist = Fixed(check_finite(f"distributions[{name!r}]", dist))
        rng = np.random.default_rng([base, zlib.crc32(str(name).encode("utf-8"))])
        out[name] = dist.sample(n, rng)
    return out


# ====================================================================== Monte Carlo statistics
class Estimate(NamedTuple):
    """A probability with its confidence interval ``[lo, hi]``."""

    p: float
    lo: float
    hi: float


def wilson_interval(k: Any, n: Any, confidence: float = 0.95) -> Tuple[Any, Any]:
    """Wilson score interval of a binomial proportion k/n.

    ``centre = (p̂ + z²/2n)/(1 + z²/n)``, ``half = z sqrt(p̂(1−p̂)/n + z²/4n²)/(1 + z²/n)`` with
    ``z = Φ⁻¹((1 + confidence)/2)``. Works for k = 0 and k = n (unlike the Wald interval).
    ``k`` and ``n`` may be arrays (broadcast); returns floats for scalars.
    """
    conf = check_finite("confidence", confidence)
    if not 0.0 < conf < 1.0:
        raise InputError(f"invalid confidence = {confidence!r}: must be in (0, 1)", field="confidence", value=confidence)
    kk = np.asarray(k, dtype=float)
    nn = np.asarray(n, dtype=float)
    if np.any(~np.isfinite(nn)) or np.any(nn < 1) or np.any(nn != np.round(nn)):
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    if np.any(~np.isfinite(kk)) or np.any(kk < 0) or np.any(kk > nn) or np.any(kk != np.round(kk)):
        raise InputError(f"invalid k = {k!r}: must be an integer in [0, n]", field="k", value=k)
    z = float(normal_ppf(0.5 * (1.0 + conf)))
    ph = kk / nn
    denom = 1.0 + z * z / nn
    centre = (ph + z * z / (2.0 * nn)) / denom
    half = z * np.sqrt(ph * (1.0 - ph) / nn + z * z / (4.0 * nn * nn)) / denom
    lo = np.where(kk == 0, 0.0, np.clip(centre - half, 0.0, 1.0))
    hi = np.where(kk == nn, 1.0, np.clip(centre + half, 0.0, 1.0))
    if lo.ndim == 0:
        return float(lo), float(hi)
    return lo, hi


def _abs_error_matrix(abs_errors: Any) -> np.ndarray:
    arr = _as_finite_array("abs_errors", abs_errors, ndim=(2,))
    return np.abs(arr)


def _check_limits(upper: Any, lower: Any) -> Tuple[float, float]:
    return _check_range(lower, upper, "lower", "upper")


def first_passage_probability(abs_errors: Any, upper: float, lower: float = 0.0, confidence: float = 0.95, failed: int = 0) -> Estimate:
    """Probability that |error| leaves ``[lower, upper]`` anywhere in the analysed window.

    Parameters
    ----------
    abs_errors:
        Array (n_samples, n_times) of |error| of one output, one row per Monte Carlo sample
        (absolute values are taken, so signed errors may be passed). NaN is rejected: drop or
        re-run failed simulations explicitly.
    upper, lower:
        Allowable range of |error| (``Δu``, ``Δv``), same unit as the errors.
    confidence:
        Confidence level of the Wilson interval.
    failed:
        Samples whose simulation failed, counted as leaving the range (they are drawn samples:
        leaving them out would bias the estimate towards the samples that run).

    Returns
    -------
    Estimate
        ``(p, lo, hi)``: fraction of samples that leave the range at least once, with its
        Wilson interval. The reliability over the window is ``1 − p``.
    """
    err = _abs_error_matrix(abs_errors)
    lo_lim, hi_lim = _check_limits(upper, lower)
    out = np.any((err > hi_lim) | (err < lo_lim), axis=1)
    k = int(out.sum()) + int(failed)
    n = int(out.size) + int(failed)
    lo, hi = wilson_interval(k, n, confidence)
    return Estimate(k / n, float(lo), float(hi))


@dataclass
class MonteCarloBins:
    """Monte Carlo reliability per crank-angle bin, next to FOSM on the pooled samples.

    Angles in degrees (bins as in :func:`fosm`: edges at k·bin_width, reported by start angle).

    Attributes
    ----------
    bin_starts, bin_centres, cycle:
        As in :class:`FosmResult`.
    n_samples:
        Number of Monte Carlo samples that have at least one time sample in each bin.
    reliability, lo, hi:
        Fraction of those samples whose |error| stays within ``[lower, upper]`` at every time
        sample of the bin, with its Wilson interval (``confidence``).
    fosm:
        FOSM (P27–P32) from the mean and standard deviation of |error| pooled over all samples
        and times of each bin, with ``mu_S, sigma_S`` from ``[lower, upper]``.
    overall:
        Reliability over the whole window (1 − first-passage probability) with its interval.
    """

    bin_starts: np.ndarray
    bin_centres: np.ndarray
    cycle: np.ndarray
    n_samples: np.ndarray
    reliability: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    fosm: FosmResult
    overall: Estimate
    lower: float
    upper: float
    confidence: float
    bin_width: float

    def to_rows(self) -> List[Dict[str, float]]:
        """The :func:`compare_fosm_mc` table."""
        return compare_fosm_mc(self)


def mc_bin_reliability(
    abs_errors: Any,
    crank_angle_deg: Any,
    upper: float,
    lower: float = 0.0,
    bin_width: float = 18.0,
    confidence: float = 0.95,
    per_cycle: bool = False,
    failed: int = 0,
) -> MonteCarloBins:
    """Per-bin Monte Carlo reliability: P(lower ≤ |error| ≤ upper over the whole bin).

    Parameters
    ----------
    abs_errors:
        Array (n_samples, n_times) of |error| (absolute values are taken).
    crank_angle_deg:
        Crank angle [deg] of each time sample: shape (n_times,) shared by all samples, or
        (n_samples, n_times) when the samples have different speeds. Taken modulo 360° unless
        ``per_cycle``.
    upper, lower:
        Allowable range ``[Δv, Δu]`` of |error| (same unit as the errors).
    bin_width:
        Bin width [deg] (edges at k·bin_width).
    confidence:
        Confidence level of the Wilson intervals.
    per_cycle:
        One set of bins per cycle instead of pooling the cycles modulo 360°.
    failed:
        Samples whose simulation failed: counted as unreliable in every bin and in the
        overall estimate (FOSM's pooled moments use the completed samples only).
    """
    err = _abs_error_matrix(abs_errors)
    n_s, n_t = err.shape
    ang = _as_finite_array("crank_angle_deg", crank_angle_deg, ndim=(1, 2))
    if ang.shape[-1] != n_t or (ang.ndim == 2 and ang.shape[0] != n_s):
        raise InputError(
            f"invalid crank_angle_deg: shape {ang.shape} does not match abs_errors {err.shape} (need ({n_t},) or {err.shape})",
            field="crank_angle_deg",
            value=ang.shape,
        )
    width = _check_bin_width(bin_width)
    lo_lim, hi_lim = _check_limits(upper, lower)
    conf = check_finite("confidence", confidence)
    if not 0.0 < conf < 1.0:
        raise InputError(f"invalid confidence = {confidence!r}: must be in (0, 1)", field="confidence", value=confidence)

    # All angles are binned together, so that every sample shares one cycle numbering.
    bins = _assign_bins(ang.ravel(), width, per_cycle)
    index = bins.index.reshape(ang.shape)
    index2 = np.broadcast_to(index, err.shape)
    n_bins = len(bins.starts)

    # per (sample, bin): does the sample have points in the bin, and does it leave the range there
    flat = (np.arange(n_s)[:, None] * n_bins + index2).ravel()
    present = np.bincount(flat, minlength=n_s * n_bins).reshape(n_s, n_bins) > 0
    viol = ((err > hi_lim) | (err < lo_lim)).ravel().astype(float)
    left = np.bincount(flat, weights=viol, minlength=n_s * n_bins).reshape(n_s, n_bins) > 0
    n_in = present.sum(axis=0) + int(failed)
    k_ok = (present & ~left).sum(axis=0)
    rel = np.full(n_bins, np.nan)
    lo = np.full(n_bins, np.nan)
    hi = np.full(n_bins, np.nan)
    has = n_in > 0
    rel[has] = k_ok[has] / n_in[has]
    if np.any(has):
        lo[has], hi[has] = wilson_interval(k_ok[has], n_in[has], conf)

    mu_S, sigma_S = allowable_statistics(lo_lim, hi_lim)
    pooled = _fosm_bins(err, _Bins(index2, bins.starts, bins.centres, bins.cycle), mu_S, sigma_S, width, 0)
    fp = first_passage_probability(err, hi_lim, lo_lim, conf, failed=failed)
    overall = Estimate(1.0 - fp.p, 1.0 - fp.hi, 1.0 - fp.lo)
    return MonteCarloBins(bins.starts, bins.centres, bins.cycle, n_in, rel, lo, hi, pooled, overall, lo_lim, hi_lim, conf, width)


def compare_fosm_mc(mc: MonteCarloBins, nominal: Optional[FosmResult] = None) -> List[Dict[str, Any]]:
    """Side-by-side table of FOSM and Monte Carlo reliability per bin (list of dicts).

    Columns: ``cycle``, ``angle_deg`` (bin start), ``centre_deg``, ``n_samples``, ``mc_R``,
    ``mc_lo``, ``mc_hi`` (Monte Carlo with Wilson interval), ``fosm_beta``, ``fosm_R`` (FOSM on
    the pooled Monte Carlo samples), ``fosm_in_ci`` (whether ``fosm_R`` lies in the interval) and,
    when ``nominal`` (e.g. :func:`fosm` of the nominal run, same bins) is given, ``nominal_beta``
    and ``nominal_R``.
    """
    if nominal is not None and (
        len(nominal.bin_starts) != len(mc.bin_starts) or not np.allclose(nominal.bin_starts, mc.bin_starts)
    ):
        raise InputError(
            "invalid nominal: its bins differ from the Monte Carlo bins (use the same bin_width and per_cycle)",
            field="nominal",
            value=len(nominal.bin_starts),
        )
    rows: List[Dict[str, Any]] = []
    for k in range(len(mc.bin_starts)):
        f_r = float(mc.fosm.reliability[k])
        row: Dict[str, Any] = {
            "cycle": int(mc.cycle[k]),
            "angle_deg": float(mc.bin_starts[k]),
            "centre_deg": float(mc.bin_centres[k]),
            "n_samples": int(mc.n_samples[k]),
            "mc_R": float(mc.reliability[k]),
            "mc_lo": float(mc.lo[k]),
            "mc_hi": float(mc.hi[k]),
            "fosm_beta": float(mc.fosm.beta[k]),
            "fosm_R": f_r,
            "fosm_in_ci": bool(mc.lo[k] <= f_r <= mc.hi[k]),
        }
        if nominal is not None:
            row["nominal_beta"] = float(nominal.beta[k])
            row["nominal_R"] = float(nominal.reliability[k])
        rows.append(row)
    return rows
