"""The paper study's analysis of its runs: slider 9's y errors against the ideal mechanism
(docs/physics.md §5), their peaks and RMS, FOSM reliability per 18° bin (§6), and the
film-model comparison runs analysed alike."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, Iterator, Optional, Tuple

import numpy as np

from ..reliability import FosmResult, fosm
from ..reliability.fosm import BIN_WIDTH  # [deg] the paper's bins
from .cases import AXIS_Y, CASES, CLEARANCE_CASES, FILMS, JOINTS, QUANTITIES, SLIDER, Case, _ANGLE_TOL, _ideal_key
from .runs import Run
from .values import MINIMA


@dataclass
class Peak:
    value: float  # signed error at the largest |error|
    time: float  # [s]
    angle: float  # [deg]


@dataclass
class Analysis:
    """Errors and reliability of one clearance case."""

    case: Case
    t: np.ndarray  # [s]
    angle: np.ndarray  # [deg] crank angle |ω| t
    errors: Dict[str, np.ndarray]  # slider y error per quantity (SI)
    analysed: np.ndarray  # mask of the samples of the analysed cycles
    first_cycle: int  # first analysed cycle (0-based)
    pooled: Dict[str, Optional[FosmResult]]  # per 18° bin, pooled over the analysed cycles
    per_cycle: Optional[FosmResult]  # displacement, one set of bins per cycle, all cycles
    peak: Dict[str, Optional[Peak]]  # whole run
    peak_first: Dict[str, Optional[Peak]]  # within the first cycle
    rms: Dict[str, float]  # over the analysed cycles
    peak_analysed: Dict[str, float]  # max |error| over the analysed cycles
    peak_analysed_signed: Dict[str, Optional[Peak]] = field(default_factory=dict)

    @property
    def peak_analysed_at(self) -> Optional[Peak]:
        """The acceleration peak over the analysed cycles."""
        return self.peak_analysed_signed.get("acceleration")


def _peak(t: np.ndarray, angle: np.ndarray, e: np.ndarray, mask: np.ndarray) -> Optional[Peak]:
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return None
    k = int(idx[np.argmax(np.abs(e[idx]))])
    return Peak(float(e[k]), float(t[k]), float(angle[k]))


def _analyse(case: Case, run: Run, ideal: Run, cycles: int) -> Analysis:
    res, ref = run.result, ideal.result
    n = min(len(res.t), len(ref.t))
    t = np.asarray(res.t[:n], dtype=float)
    angle = np.degrees(abs(case.omega) * t)
    errors = {q: np.asarray(res.error(ref, SLIDER, q)[:n, AXIS_Y], dtype=float) for q in QUANTITIES}
    first = 1 if cycles >= 2 else 0
    inside = angle < 360.0 * cycles - _ANGLE_TOL  # the end point would open a one-sample cycle
    analysed = inside & (angle >= 360.0 * first - _ANGLE_TOL)
    pooled: Dict[str, Optional[FosmResult]] = {}
    for q in QUANTITIES:
        pooled[q] = fosm(errors[q][analysed], angle[analysed], q, bin_width=BIN_WIDTH) if np.any(analysed) else None
    per_cycle = None
    if np.any(inside):
        per_cycle = fosm(errors["displacement"][inside], angle[inside], "displacement", bin_width=BIN_WIDTH, per_cycle=True).per_cycle
    first_cycle = angle < 360.0 - _ANGLE_TOL
    return Analysis(
        case=case,
        t=t,
        angle=angle,
        errors=errors,
        analysed=analysed,
        first_cycle=first,
        pooled=pooled,
        per_cycle=per_cycle,
        peak={q: _peak(t, angle, errors[q], np.ones(n, dtype=bool)) for q in QUANTITIES},
        peak_first={q: _peak(t, angle, errors[q], first_cycle) for q in QUANTITIES},
        rms={q: float(np.sqrt(np.mean(errors[q][analysed] ** 2))) if np.any(analysed) else float("nan") for q in QUANTITIES},
        peak_analysed={q: float(np.max(np.abs(errors[q][analysed]))) if np.any(analysed) else float("nan") for q in QUANTITIES},
        peak_analysed_signed={q: _peak(t, angle, errors[q], analysed) for q in QUANTITIES},
    )


def _film_runs(runs: Dict[str, Run], extra: Dict[str, Run], cycles: int, film: str) -> Dict[Tuple[str, str], Tuple[Run, Analysis]]:
    """Every lubricated case under every film model (``extra``: the runs of :func:`film_cases`,
    keyed ``"key|film"``), analysed against the same ideal runs. The printed closed forms
    (long_paper) stall the integrator (their spurious receding force chatters): they ran
    :data:`PRINTED_FORM_STEPS` steps and report how far they got."""
    lub = [k for k in CLEARANCE_CASES if CASES[k].joints == "lubricated"]
    out: Dict[Tuple[str, str], Tuple[Run, Analysis]] = {}
    for k in lub:
        for f in FILMS:
            run = runs[k] if f == film else extra[f"{k}|{f}"]
            out[(k, f)] = (run, _analyse(run.case, run, runs[_ideal_key(CASES[k])], cycles))
    return out


def _max_ecc(run: Run) -> float:
    c = float(run.case.clearance or float("nan"))
    return max(float(np.max(np.hypot(*run.result.eccentricity(j).T))) for j in JOINTS) / c


def _r_beta(f: Optional[FosmResult]) -> str:
    return "–" if f is None else f"{f.min_reliability:.4f} (β {f.min_beta:.3f})"


def _min_R(a: Analysis, q: str) -> float:
    f = a.pooled[q]
    return float("nan") if f is None else f.min_reliability


def minima_with_paper(an: Dict[str, Analysis]) -> Iterator[Tuple[Analysis, str, Optional[FosmResult], Tuple[float, Optional[float], float]]]:
    """For each clearance-study case and quantity: its analysis, the quantity, our pooled FOSM
    result and the paper's (angle [deg], β or None, R) of the minimum reliability."""
    for key in CLEARANCE_CASES:
        for q in QUANTITIES:
            yield an[key], q, an[key].pooled[q], MINIMA[key][q]
