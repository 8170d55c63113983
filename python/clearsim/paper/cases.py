"""The paper study's cases (docs/physics.md §7): which nine-bar runs it makes (joints,
clearance, drive speed, film model), their output grids and the constants they share."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ..models import nine_bar
from ..schema import BODY_QUANTITIES, body_unit

#: The quantities of slider 9's y error the study analyses, and their SI units (clearsim.schema).
QUANTITIES: Tuple[str, ...] = BODY_QUANTITIES
UNIT: Dict[str, str] = {q: body_unit(q, "y") for q in QUANTITIES}
SLIDER = "slider9"
AXIS_Y = 1
JOINTS = ("A", "B")
GRID_DEG = 0.5  # [deg] output grid of the full study
GRID_DEG_QUICK = 2.0  # [deg] output grid of the quick study
VISCOSITY = 0.4  # [Pa s]
BEARING_LENGTH = 0.05  # [m]
TRANSITION_FRACTION = 0.05  # e0 = 0.05 c (docs/physics.md §4, the Lubricated default)
_ANGLE_TOL = 1e-6  # [deg]

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


def _grid(case: Case, cycles: int, grid_deg: float) -> np.ndarray:
    """Output times [s] of ``cycles`` crank cycles every ``grid_deg`` degrees of crank angle."""
    n = int(round(360.0 / grid_deg)) * cycles
    return np.linspace(0.0, cycles * case.period, n + 1)


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


def _with_film(case: Case, film: str) -> Case:
    """The case with its lubricated joints on ``film`` (a key of :data:`FILM_LABEL`; dry and
    ideal cases unchanged)."""
    if case.joints != "lubricated":
        return case
    if film == "finite_none":
        return dataclasses.replace(case, film="finite", supply="none")
    return dataclasses.replace(case, film=film)
