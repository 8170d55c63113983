"""``clearsim paper``'s entry point, :func:`run_paper_study`: run the study's cases (cases.py,
runs.py), analyse them (analysis.py), check the paper's trends (trends.py) and write the figures,
CSV files (files.py) and ``report.md`` (report.py). The study itself: :mod:`clearsim.paper`.
"""


from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np

from ..csvfile import column_name
from ..errors import InputError, check_choice
from .analysis import _analyse, _film_runs, _max_ecc
from .cases import CASES, CLEARANCE_CASES, CLEARANCE_STUDY, FILM_RUN_BUDGET_S, GRID_DEG, GRID_DEG_QUICK, PRINTED_FORM_STEPS, QUANTITIES, SPEED_STUDY, UNIT, _ideal_key, film_cases
from .files import _error_files, _orbit_files, _reliability_files, _summary_csvs, _write_csv
from .report import _films_section, _report
from .runs import Run, Runs, run_cases
from .trends import _trends

__all__ = ["run_paper_study"]


# ====================================================================== entry point


def run_paper_study(
    out_dir: Path, cycles: int = 3, quick: bool = False, progress: bool = True, film: str = "long", compare_films: bool = True,
    printed_form_steps: int = PRINTED_FORM_STEPS,
) -> Path:
    """Run the paper's study (docs/physics.md §7) and write figures, CSV files and ``report.md`` to ``out_dir``.

    Parameters
    ----------
    out_dir:
        Output directory (created if missing).
    cycles:
        Crank cycles per run (default 3, as in the paper); the first is treated as a start-up
        transient for the pooled statistics when there are two or more.
    quick:
        Smoke-test mode: one cycle and a 2° output grid (``cycles`` is ignored).
    progress:
        Show a progress bar over the runs (:mod:`clearsim.progress`).
    film:
        Film model of the lubricated joints (``clearsim.Lubricated.film``): ``"long"`` (default,
        the paper's model corrected), ``"short"``, ``"finite"`` (L/D = 2.5 from the Reynolds
        equation) or ``"long_paper"`` (the printed closed forms).
    compare_films:
        Also run the lubricated cases under the other film models and compare them in the report
        (in the background, while the figures are drawn).
    printed_form_steps:
        Step budget of each run with the paper's printed closed forms (``film="long_paper"``),
        which stall the integrator: the default, ten times what the corrected long bearing needs
        for a whole run, shows the stall in about half a second per run.

    Returns
    -------
    pathlib.Path
        The path of ``report.md``.
    """
    if isinstance(cycles, bool) or not isinstance(cycles, (int, np.integer)) or cycles < 1:
        raise InputError(f"invalid cycles = {cycles!r}: must be a positive integer", field="cycles", value=cycles)
    cycles = 1 if quick else int(cycles)
    grid_deg = GRID_DEG_QUICK if quick else GRID_DEG
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()

    from ..joints import FILM_MODELS

    check_choice("film", film, FILM_MODELS)
    if isinstance(printed_form_steps, bool) or not isinstance(printed_form_steps, (int, np.integer)) or printed_form_steps < 1:
        raise InputError(f"invalid printed_form_steps = {printed_form_steps!r}: must be a positive integer", field="printed_form_steps", value=printed_form_steps)
    # The film-comparison runs start first and go on in the background (the core releases the
    # GIL) while the study's own runs, then its figures (one Python thread), take the rest.
    pending = Runs(film_cases(film), cycles, grid_deg, min(2, os.cpu_count() or 1), FILM_RUN_BUDGET_S, printed_form_steps) if compare_films else None
    try:
        runs = run_cases(cycles, grid_deg, progress, film, printed_form_steps)
        return _study(out, runs, pending, cycles, quick, grid_deg, progress, film, printed_form_steps, start)
    finally:
        if pending is not None:
            pending.close()


def _study(
    out: Path, runs: Dict[str, Run], pending: Optional[Runs], cycles: int, quick: bool, grid_deg: float, progress: bool, film: str,
    printed_steps: int, start: float,
) -> Path:
    """Analysis, figures, CSV files and report of the runs; the film-comparison runs ``pending``
    are collected after the figures."""
    an = {key: _analyse(runs[key].case, runs[key], runs[_ideal_key(CASES[key])], cycles) for key in CLEARANCE_CASES}
    trends = _trends(an, cycles)
    pooled_scope = "pooled_cycle_1" if cycles == 1 else f"pooled_cycles_2-{cycles}"
    cyc = f"{cycles} cycle{'s' if cycles > 1 else ''}"

    files: List[Path] = []
    files += _error_files(out, "fig08_errors_clearance", [an[k] for k in CLEARANCE_STUDY], "clearance", f"Fig. 8: slider errors, ω = −5π rad/s, c = 0.3 / 0.5 mm ({cyc})")
    for stem, c in (("fig09_orbits_c0.3mm", "0.3"), ("fig10_orbits_c0.5mm", "0.5")):
        files += _orbit_files(
            out, stem, [runs[f"dry-c{c}-5pi"], runs[f"lub-c{c}-5pi"]], lambda case: case.kind,
            f"Fig. {stem[3:5].lstrip('0')}: journal-centre orbits, c = {c} mm, ω = −5π rad/s ({cyc})",
        )  # fmt: skip
    pooled_txt = "cycle 1 only" if cycles == 1 else f"pooled over cycles 2–{cycles}"
    files += _reliability_files(
        out, "fig11_reliability_clearance", [an[k] for k in CLEARANCE_STUDY], "clearance", True, pooled_scope,
        {
            "displacement": f"Fig. 11 (ω = −5π rad/s): (a) displacement reliability of each of the {cyc}",
            "velocity": f"(b) velocity reliability, bins of one cycle {pooled_txt}",
            "acceleration": f"(c) acceleration reliability, bins of one cycle {pooled_txt}",
        },
    )  # fmt: skip
    for stem, speed in (("fig12_errors_5pi", "5"), ("fig13_errors_8pi", "8")):
        files += _error_files(
            out, stem, [an[f"dry-c0.6-{speed}pi"], an[f"lub-c0.6-{speed}pi"]], "kind",
            f"Fig. {stem[3:5]}: slider errors, ω = −{speed}π rad/s, c = 0.6 mm ({cyc})",
        )  # fmt: skip
    for stem, speed in (("fig14_orbits_5pi", "5"), ("fig15_orbits_8pi", "8")):
        files += _orbit_files(
            out, stem, [runs[f"dry-c0.6-{speed}pi"], runs[f"lub-c0.6-{speed}pi"]], lambda case: case.kind,
            f"Fig. {stem[3:5]}: journal-centre orbits, c = 0.6 mm, ω = −{speed}π rad/s ({cyc})",
        )  # fmt: skip
    files += _reliability_files(
        out, "fig16_reliability_speed", [an[k] for k in SPEED_STUDY], "speed", False, pooled_scope,
        {
            "displacement": f"Fig. 16 (c = 0.6 mm): (a) displacement reliability, {pooled_txt}",
            "velocity": f"(b) velocity reliability, {pooled_txt}",
            "acceleration": f"(c) acceleration reliability, {pooled_txt}",
        },
    )  # fmt: skip
    files += _summary_csvs(out, runs, an, trends)
    films = _film_runs(runs, pending.results(progress, "film models", by_film=True), cycles, film) if pending is not None else None

    wall = time.perf_counter() - start
    report = out / "report.md"
    files.append(report)
    if films is not None:
        rows = [[k, f, *(a.peak_analysed[q] for q in QUANTITIES), _max_ecc(run), run.wall_time] for (k, f), (run, a) in films.items()]
        header = ["case", "film", *(column_name(f"peak_{q}_error", UNIT[q]) for q in QUANTITIES), "max_e_over_c", column_name("wall_time", "s")]
        files.append(_write_csv(out / "film_models.csv", header, rows))
    text = _report(out, runs, an, trends, cycles, quick, grid_deg, sorted(files), wall)
    if films is not None:
        marker = "## Files\n"
        text = text.replace(marker, _films_section(films, cycles, printed_steps) + "\n" + marker, 1)
    report.write_text(text, encoding="utf-8")
    return report
