"""The paper study's runs: its cases' mechanisms and settings handed to :mod:`clearsim.batch`
(the one batch runner), their results collected as :class:`Run` (a failed run kept with its
partial result and the reason it stopped)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence

from .. import batch
from ..result import Result
from .cases import CASES, PRINTED_FORM_STEPS, Case, _grid, _with_film


@dataclass
class Run:
    case: Case
    result: Result
    wall_time: float  # [s] the core's, assembly and integration
    failure: Optional[str] = None  # why the run stopped early (clearsim.SimulationError), if it did


def _longest_first(cases: Sequence[Case]) -> List[Case]:
    """Lubricated runs (stiff: the longest), then dry, then ideal; the slower drive first."""
    return sorted(cases, key=lambda c: ({"lubricated": 0, "dry": 1, "ideal": 2}[c.joints], c.omega))


class Runs:
    """Runs of ``cases`` started on ``threads`` threads (:func:`clearsim.batch.start`, longest
    first) with the study's settings: the integrator ``auto`` at rtol 1e-6, atol 1e-9, outputs
    every ``grid_deg`` degrees of crank angle over ``cycles`` cycles, a wall-time budget
    ``max_seconds`` [s] per run, and ``printed_steps`` steps for a run on the paper's printed
    closed forms (they stall: :data:`PRINTED_FORM_STEPS`). Leaving it as a context manager
    cancels the runs not yet started."""

    def __init__(
        self, cases: Sequence[Case], cycles: int, grid_deg: float, threads: Optional[int] = None, max_seconds: Optional[float] = None,
        printed_steps: Optional[int] = None,
    ) -> None:  # fmt: skip
        self.given = list(cases)
        self.cases = _longest_first(cases)
        self.mechanisms = [c.mechanism() for c in self.cases]
        self.settings: List[Dict[str, Any]] = []
        for case, mech in zip(self.cases, self.mechanisms):
            grid = _grid(case, cycles, grid_deg)
            budget: Dict[str, Any] = {} if max_seconds is None else {"max_seconds": max_seconds}
            if case.joints == "lubricated" and case.film == "long_paper":
                budget["max_steps"] = printed_steps or PRINTED_FORM_STEPS  # they stall (PRINTED_FORM_STEPS): a short run shows it
            self.settings.append(mech.run_settings(float(grid[-1]), t_out=grid, integrator="auto", rtol=1e-6, atol=1e-9, **budget))
        self.started = batch.start([m.description() for m in self.mechanisms], self.settings, threads)

    def results(self, progress: bool, what: str, by_film: bool) -> Dict[str, Run]:
        """The runs, a bar tick as each finishes, keyed by case (``"key|film"`` if ``by_film``).
        A run that stopped keeps its partial result and says why in ``failure``. In the order the
        cases were given."""
        key = (lambda c: f"{c.key}|{c.film_key}") if by_film else (lambda c: c.key)
        raws = self.started.results(progress, f"clearsim paper: {what}", [key(c) for c in self.cases])
        runs: Dict[str, Run] = {}
        for case, mech, settings, raw in zip(self.cases, self.mechanisms, self.settings, raws):
            result, failure = batch.finish(mech, raw, settings)
            runs[key(case)] = Run(case, result, float(result.stats.get("wall_time", float("nan"))), None if failure is None else str(failure))
        return {key(c): runs[key(c)] for c in self.given}

    def close(self) -> None:
        self.started.close()

    def __enter__(self) -> "Runs":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def run_cases(cycles: int, grid_deg: float, progress: bool, film: str = "long", printed_steps: Optional[int] = None) -> Dict[str, Run]:
    """Every run of the study (:data:`CASES`, lubricated joints on ``film``), on all cores."""
    with Runs([_with_film(c, film) for c in CASES.values()], cycles, grid_deg, printed_steps=printed_steps) as runs:
        return runs.results(progress, "runs", by_film=False)
