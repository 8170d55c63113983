"""Monte Carlo statistics: Wilson intervals, the first-passage probability and per-bin Monte
Carlo reliability next to FOSM (docs/physics.md §6). Running the simulations is left to the
caller; these functions only do the statistics."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, NamedTuple, Optional, Tuple

import numpy as np

from ..errors import InputError, check_finite
from .. import display
from .fosm import (
    BIN_WIDTH,
    FosmResult,
    _as_finite_array,
    _assign_bins,
    _Bins,
    _check_bin_width,
    _check_range,
    _fosm_bins,
    allowable_statistics,
    normal_ppf,
)


def failure_reasons(failures: List[Tuple[int, str]]) -> Dict[str, int]:
    """How many runs failed for each kind of reason: the message up to ' at t =', from
    ``(sample, reason)`` pairs."""
    counts: Dict[str, int] = {}
    for _, reason in failures:
        key = reason.split(" at t =")[0]
        counts[key] = counts.get(key, 0) + 1
    return counts


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

    def __repr__(self) -> str:
        return display.text(self, "overall", "lower", "upper", "confidence", "bin_width", "bin_starts", "n_samples")

    def _repr_html_(self) -> str:
        return display.html(self, "overall", "lower", "upper", "confidence", "bin_width", "bin_starts", "n_samples")

    def to_rows(self) -> List[Dict[str, float]]:
        """The :func:`compare_fosm_mc` table."""
        return compare_fosm_mc(self)


def mc_bin_reliability(
    abs_errors: Any,
    crank_angle_deg: Any,
    upper: float,
    lower: float = 0.0,
    bin_width: float = BIN_WIDTH,
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
    and ``nominal_R``. In a CSV file, :func:`clearsim.csvfile.report_header` heads them as
    clearsim's files do (``bin_start [deg]``, ``bin_centre [deg]``, ``samples``, the rest bare).
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
