"""Deprecated: :mod:`clearsim.paper.cases` (the cases), :mod:`clearsim.paper.runs` (running them
through :mod:`clearsim.batch`) and :mod:`clearsim.paper.analysis` (their analysis)."""

from __future__ import annotations

from ..paper.analysis import Analysis, Peak, _analyse, _film_runs, _max_ecc, _min_R, _r_beta, minima_with_paper
from ..paper.cases import (
    AXIS_Y, BEARING_LENGTH, CASES, CLEARANCE_CASES, CLEARANCE_STUDY, FILM_LABEL, FILM_RUN_BUDGET_S, FILMS, GRID_DEG, GRID_DEG_QUICK, JOINTS, PRINTED_FORM_STEPS,
    QUANTITIES, SLIDER, SPEED_STUDY, TRANSITION_FRACTION, UNIT, VISCOSITY, Case, film_cases,
)
from ..paper.runs import Run, run_cases as _run_all
from ..paper.trends import FAILS, HOLDS, NOT_EVALUABLE

#: The unit suffixes the paper's CSV columns carried before they were headed ``name [unit]``
#: (``…_error_m_per_s2``); nothing writes them now, kept so the old name still imports.
CSV_UNIT = {"displacement": "m", "velocity": "m_per_s", "acceleration": "m_per_s2"}

__all__ = [
    "AXIS_Y", "BEARING_LENGTH", "CASES", "CLEARANCE_CASES", "CLEARANCE_STUDY", "FILM_LABEL", "FILM_RUN_BUDGET_S", "FILMS", "GRID_DEG", "GRID_DEG_QUICK",
    "JOINTS", "PRINTED_FORM_STEPS", "QUANTITIES", "SLIDER", "SPEED_STUDY", "TRANSITION_FRACTION", "UNIT", "VISCOSITY", "Case", "film_cases",
    "CSV_UNIT", "Analysis", "Peak", "Run", "minima_with_paper", "HOLDS", "FAILS", "NOT_EVALUABLE",
    "_analyse", "_film_runs", "_max_ecc", "_min_R", "_r_beta", "_run_all",
]  # fmt: skip
