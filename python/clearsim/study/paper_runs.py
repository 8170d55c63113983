"""The paper study's cases, runs and their analysis (errors, peaks, FOSM per bin, film-model
comparison runs): the computing half of ``clearsim paper`` (:mod:`clearsim.study.paper`)."""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import Executor, Future, ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from ..errors import SimulationError
from ..models import nine_bar
from ..reliability import FosmResult, fosm
from ..reliability.fosm import BIN_WIDTH  # [deg] the paper's bins
from ..result import Result
from . import paper_values as PV


QUANTITIES: Tuple[str, ...] = ("displacement", "velocity", "acceleration")
UNIT = {"displacement": "m", "velocity": "m/s", "acceleration": "m/s²"}
CSV_UNIT = {"displacement": "m", "velocity": "m_per_s", "acceleration": "m_per_s2"}
SLIDER = "slider9"
AXIS_Y = 1
JOINTS = ("A", "B")
GRID_DEG = 0.5  # [deg] output grid of the full study
GRID_DEG_QUICK = 2.0  # [deg] output grid of the quick study
VISCOSITY = 0.4  # [Pa s]
BEARING_LENGTH = 0.05  # [m]
TRANSITION_FRACTION = 0.05  # e0 = 0.05 c (docs/physics.md §4, the Lubricated default)
_ANGLE_TOL = 1e-6  # [deg]
HOLDS, FAILS, NOT_EVALUABLE = "holds", "does not hold", "not evaluable"


# ====================================================================== cases


@dataclass(frozen=True)
class Case:
    """One run of the study: ``joints`` ∈ ideal/dry/lubricated, ``clearance`` [m] (None for
    ideal), ``omega`` [rad/s]."""

    key: str
    joints: str
    clearance: Optional[float]
    omega: float
    film: str = "long"  # film model of the lubricated joints (clearsim.Lubricated.film)
    supply: str = "widest_gap"  # ambient-pressure convention of a finite film (clearsim.Lubricated.supply)

    @property
    def film_key(self) -> str:
        """The film model as the comparison names it: ``film``, or ``"finite_none"`` for the
        finite film without its supply line."""
        return "finite_none" if self.film == "finite" and self.supply == "none" else self.film

    @property
    def speed(self) -> str:
        """``"5π"`` or ``"8π"``."""
        return f"{abs(self.omega) / math.pi:g}π"

    @property
    def kind(self) -> str:
        return {"lubricated": "lubricated", "dry": "dry", "ideal": "ideal"}[self.joints]

    @property
    def c_mm(self) -> float:
        return float("nan") if self.clearance is None else self.clearance * 1e3

    @property
    def period(self) -> float:
        """Crank period 2π/|ω| [s]."""
        return 2.0 * math.pi / abs(self.omega)

    @property
    def label(self) -> str:
        if self.joints == "ideal":
            return f"ideal, ω = −{self.speed} rad/s"
        return f"{self.kind}, c = {self.c_mm:g} mm, ω = −{self.speed} rad/s"

    def mechanism(self) -> Any:
        if self.joints == "ideal":
            return nine_bar("ideal", omega=self.omega)
        from ..joints import Lubricated

        lub = Lubricated(viscosity=VISCOSITY, length=BEARING_LENGTH, film=self.film, supply=self.supply)
        return nine_bar(self.joints, clearance=self.clearance, omega=self.omega, lubricated=lub)


def _case(joints: str, c_mm: Optional[float], speed: int) -> Case:
    short = {"dry": "dry", "lubricated": "lub", "ideal": "ideal"}[joints]
    key = f"ideal-{speed}pi" if c_mm is None else f"{short}-c{c_mm:g}-{speed}pi"
    return Case(key, joints, None if c_mm is None else c_mm * 1e-3, -speed * math.pi)


#: Every run of the study (the ideal run at 5π serves both studies).
CASES: Dict[str, Case] = {
    c.key: c
    for c in (
        _case("ideal", None, 5),
        _case("ideal", None, 8),
        _case("dry", 0.3, 5),
        _case("dry", 0.5, 5),
        _case("lubricated", 0.3, 5),
        _case("lubricated", 0.5, 5),
        _case("dry", 0.6, 5),
        _case("lubricated", 0.6, 5),
        _case("dry", 0.6, 8),
        _case("lubricated", 0.6, 8),
    )
}
CLEARANCE_STUDY = ("dry-c0.3-5pi", "dry-c0.5-5pi", "lub-c0.3-5pi", "lub-c0.5-5pi")
SPEED_STUDY = ("dry-c0.6-5pi", "dry-c0.6-8pi", "lub-c0.6-5pi", "lub-c0.6-8pi")
CLEARANCE_CASES = CLEARANCE_STUDY + SPEED_STUDY


def _ideal_key(case: Case) -> str:
    return f"ideal-{abs(case.omega) / math.pi:g}pi"


def _short_label(case: Case, study: str) -> str:
    """Legend label: what varies within the figure."""
    if study == "kind":
        return case.kind
    if study == "clearance":
        return f"{case.kind}, c = {case.c_mm:g} mm"
    return f"{case.kind}, ω = −{case.speed} rad/s"


# ====================================================================== running


@dataclass
class Run:
    case: Case
    result: Result
    wall_time: float  # [s] measured around Mechanism.simulate (assembly included)
    failure: Optional[str] = None


def _grid(case: Case, cycles: int, grid_deg: float) -> np.ndarray:
    n = int(round(360.0 / grid_deg)) * cycles
    return np.linspace(0.0, cycles * case.period, n + 1)


def _simulate(case: Case, grid: np.ndarray, max_seconds: Optional[float] = None, printed_steps: Optional[int] = None) -> Run:
    mech = case.mechanism()
    if case.joints == "lubricated" and case.film == "finite":
        # Its table (shipped for L/D = 2.5, else solved once per machine, by one thread): not
        # part of the run's wall time.
        mech.compile()
    start = time.perf_counter()
    failure = None
    budget: Dict[str, Any] = {} if max_seconds is None else {"max_seconds": max_seconds}
    if case.joints == "lubricated" and case.film == "long_paper":
        budget["max_steps"] = printed_steps or PRINTED_FORM_STEPS  # they stall (PRINTED_FORM_STEPS): a short run shows it
    try:
        res = mech.simulate(float(grid[-1]), t_out=grid, integrator="auto", rtol=1e-6, atol=1e-9, progress=False, **budget)
    except SimulationError as err:
        res = getattr(err, "result", None)
        if res is None:
            raise
        failure = str(err)
    return Run(case, res, time.perf_counter() - start, failure)


def _with_film(case: Case, film: str) -> Case:
    """The case with its lubricated joints on ``film`` (a key of :data:`FILM_LABEL`; dry and
    ideal cases unchanged)."""
    import dataclasses

    if case.joints != "lubricated":
        return case
    if film == "finite_none":
        return dataclasses.replace(case, film="finite", supply="none")
    return dataclasses.replace(case, film=film)


def _submit(pool: Executor, cases: Sequence[Case], cycles: int, grid_deg: float, max_seconds: Optional[float] = None, printed_steps: Optional[int] = None) -> "Dict[Future[Run], Case]":
    """Start the runs of ``cases`` on ``pool`` (threads: the Rust core releases the GIL), longest first."""
    order = sorted(cases, key=lambda c: ({"lubricated": 0, "dry": 1, "ideal": 2}[c.joints], c.omega))
    return {pool.submit(_simulate, c, _grid(c, cycles, grid_deg), max_seconds, printed_steps): c for c in order}


def _collect(futures: "Dict[Future[Run], Case]", progress: bool, what: str, by_film: bool) -> Dict[str, Run]:
    """The runs as they finish, one bar tick each, keyed by case (``"key|film"`` if ``by_film``)."""
    from ..progress import bar as progress_bar

    runs: Dict[str, Run] = {}
    with progress_bar(len(futures), f"clearsim paper: {what}", "run", enabled=progress, delay=0.0, leave=True) as bar:
        for fut in as_completed(futures):
            run = fut.result()
            runs[f"{run.case.key}|{run.case.film_key}" if by_film else run.case.key] = run
            bar.set_postfix_str(run.case.key)
            bar.update(1)
    return runs


def _run_all(cycles: int, grid_deg: float, progress: bool, film: str = "long", printed_steps: Optional[int] = None) -> Dict[str, Run]:
    """Every run of the study (:data:`CASES`, lubricated joints on ``film``), on all cores."""
    cases = [_with_film(c, film) for c in CASES.values()]
    with ThreadPoolExecutor(max_workers=max(1, min(len(cases), os.cpu_count() or 1))) as pool:
        return _collect(_submit(pool, cases, cycles, grid_deg, printed_steps=printed_steps), progress, "runs", by_film=False)


# ====================================================================== analysis


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


# ====================================================================== film models
#: Step budget (accepted and rejected) of a run with the paper's printed closed forms: they
#: stall the integrator near t ≈ 0.09 s (steps of 1e-11 s: 44 000 steps in 5 s and runs of 20 s
#: or 60 s reach the same time), so a run of ten times the steps the corrected long bearing needs
#: for a whole 3-cycle case (1 000–1 350) shows the stall in about 0.5 s, the same on any machine.
PRINTED_FORM_STEPS = 10_000
#: Wall-time budget [s] of each film-comparison run, a safety net only (the others take 0.1 s).
FILM_RUN_BUDGET_S = 30.0
#: The film models the report compares on the lubricated runs: the finite film in its default
#: convention (ambient pressure on the line of the widest gap, as the paper's P12) and without
#: that line (``supply="none"``, a film periodic around the bearing; docs/physics.md §4).
FILMS: Tuple[str, ...] = ("long", "short", "finite", "finite_none", "long_paper")
FILM_LABEL = {
    "long": "long (Gümbel, corrected)",
    "short": "short (Ocvirk)",
    "finite": 'finite L/D = 2.5 (Reynolds, supply="widest_gap")',
    "finite_none": 'finite (supply="none")',
    "long_paper": "paper's printed P13–P14",
}


def film_cases(film: str) -> List[Case]:
    """The film-comparison runs: every lubricated case of the study under every film model but
    the study's own ``film`` (its runs are reused)."""
    lub = [k for k in CLEARANCE_CASES if CASES[k].joints == "lubricated"]
    return [_with_film(CASES[k], f) for k in lub for f in FILMS if f != film]


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
            yield an[key], q, an[key].pooled[q], PV.MINIMA[key][q]
