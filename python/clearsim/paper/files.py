"""The paper study's files: CSV tables (through :mod:`clearsim.csvfile`) and the figures
(Figs. 8–16) of ``clearsim paper``."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .. import plots
from ..csvfile import column_name, write_rows
from ..reliability import FosmResult
from ..schema import ascii_unit
from .analysis import Analysis, minima_with_paper
from .cases import CASES, CLEARANCE_CASES, Case, JOINTS, QUANTITIES, TRANSITION_FRACTION, UNIT, _short_label
from .runs import Run
from .trends import Trend
from .values import PEAKS

#: The columns of time [s] and crank angle |ω| t [deg] that open every curve's CSV file.
TIME, CRANK_ANGLE = column_name("t", "s"), column_name("crank_angle", "deg")


# ====================================================================== files
# Headers ``name [unit]`` (clearsim.csvfile.column_name; units as clearsim.schema spells them, in
# ASCII); a column whose unit varies by row names it in its ``error_unit`` column.


def _write_csv(path: Path, header: Sequence[str], rows: Sequence[Sequence[Any]]) -> Path:
    return write_rows(path, header, rows, blank_nonfinite=True)  # clearsim.csvfile: the one writer


def _columns_csv(path: Path, columns: Dict[str, np.ndarray]) -> Path:
    """Columns of possibly different lengths (a failed run stops early): shorter ones padded empty."""
    n = max(len(v) for v in columns.values())
    cols = [np.concatenate([np.asarray(v, dtype=float), np.full(n - len(v), np.nan)]) for v in columns.values()]
    rows = [[float(c[k]) for c in cols] for k in range(n)]
    return _write_csv(path, list(columns), rows)


def _csv_name(case: Case) -> str:
    return case.key.replace("-", "_")


def _shade_startup(axes: Sequence[Any], period: float, label_axis: Any = None, text_y: float = 0.03) -> None:
    """Grey band over the first crank cycle (the start-up transient left out of the pooled
    statistics), labelled inside ``label_axis`` if given."""
    from matplotlib.transforms import blended_transform_factory

    for ax in axes:
        ax.axvspan(0.0, period, color="0.93", zorder=0, linewidth=0)
    if label_axis is None:
        return
    label_axis.text(
        period / 2, text_y, "start-up cycle (not in pooled statistics)", transform=blended_transform_factory(label_axis.transData, label_axis.transAxes),
        ha="center", va="bottom", fontsize=8, color="0.35", zorder=1,
    )  # fmt: skip


def _error_files(out: Path, stem: str, an: Sequence[Analysis], study: str, title: str) -> List[Path]:
    longest = max(an, key=lambda a: len(a.t))
    cols: Dict[str, np.ndarray] = {TIME: longest.t, CRANK_ANGLE: longest.angle}
    for a in an:
        for q in QUANTITIES:
            cols[column_name(f"{_csv_name(a.case)}_{q}_error", UNIT[q])] = a.errors[q]
    csv_path = _columns_csv(out / f"{stem}.csv", cols)
    series = {_short_label(a.case, study): {q: a.errors[q] for q in QUANTITIES} for a in an}
    tmap = {_short_label(a.case, study): a.t for a in an}
    startup = an[0].first_cycle > 0
    if startup:
        title += "\ngrey band: start-up cycle, left out of the pooled statistics"
    fig = plots.plot_error_histories(tmap, series, title=title)
    if startup:
        _shade_startup(fig.axes, an[0].case.period)
    return [plots.save(fig, out / f"{stem}.png"), csv_path]


def _orbit_files(out: Path, stem: str, runs: Sequence[Run], labeller: Callable[[Case], str], title: str) -> List[Path]:
    orbits: Dict[str, Tuple[np.ndarray, np.ndarray]] = {}
    clearance: Dict[str, float] = {}
    band: Dict[str, Optional[float]] = {}
    longest = max(runs, key=lambda r: len(r.result.t))
    cols: Dict[str, np.ndarray] = {
        TIME: longest.result.t,
        CRANK_ANGLE: np.degrees(abs(longest.case.omega) * longest.result.t),
    }
    for joint in JOINTS:
        for run in runs:
            c = float(run.case.clearance)  # type: ignore[arg-type]
            label = f"joint {joint}, {labeller(run.case)}"
            e = run.result.eccentricity(joint)
            orbits[label] = (e[:, 0], e[:, 1])
            clearance[label] = c
            band[label] = TRANSITION_FRACTION * c if run.case.joints == "lubricated" else None
            name = f"{joint}_{_csv_name(run.case)}"
            cols[f"{name}_ex_over_c"] = e[:, 0] / c
            cols[f"{name}_ey_over_c"] = e[:, 1] / c
    fig = plots.plot_journal_orbits(orbits, clearance, transition_band=band, ncols=len(runs), title=title)
    return [plots.save(fig, out / f"{stem}.png"), _columns_csv(out / f"{stem}.csv", cols)]


def _reliability_rows(a: Analysis, scope: str, res: FosmResult, q: str) -> List[List[Any]]:
    return [
        [a.case.key, q, ascii_unit(UNIT[q]), scope, r["cycle"] + 1 if res.cycle.any() or scope.startswith("per_cycle") else "", r["angle_deg"], r["centre_deg"], r["count"], r["mu_s"], r["sigma_s"], r["mu_S"], r["sigma_S"], r["beta"], r["reliability"]]
        for r in res.to_rows()
    ]


RELIABILITY_HEADER = [
    "case", "quantity", "error_unit", "scope", "cycle", "bin_start [deg]", "bin_centre [deg]", "samples",
    "mu_s_error_unit", "sigma_s_error_unit", "mu_S_error_unit", "sigma_S_error_unit", "beta", "reliability",
]  # fmt: skip


def _reliability_files(
    out: Path, stem: str, an: Sequence[Analysis], study: str, per_cycle_displacement: bool, pooled_scope: str, titles: Dict[str, str]
) -> List[Path]:
    """Reliability figure (one panel per quantity, ``titles[quantity]`` above each) and its CSV."""
    rows: List[List[Any]] = []
    curves: Dict[str, Dict[str, Any]] = {q: {} for q in QUANTITIES}
    for a in an:
        label = _short_label(a.case, study)
        if a.per_cycle is not None:
            rows += _reliability_rows(a, "per_cycle_all_cycles", a.per_cycle, "displacement")
        for q in QUANTITIES:
            f = a.pooled[q]
            if f is not None:
                rows += _reliability_rows(a, pooled_scope, f, q)
            src = a.per_cycle if (q == "displacement" and per_cycle_displacement) else f
            if src is not None:
                curves[q][label] = (src.bin_starts, src.reliability)
    csv_path = _write_csv(out / f"{stem}.csv", RELIABILITY_HEADER, rows)
    curves = {q: c for q, c in curves.items() if c}
    paths = [csv_path]
    if curves:
        # panel titles instead of a suptitle: a suptitle collides with the panels' shared legend above them
        fig = plots.plot_reliability_panels(curves)
        w, h = fig.get_size_inches()
        fig.set_size_inches(max(w, 8.5), h + 0.3 * len(curves))
        for ax, q in zip(fig.axes, curves):
            ax.set_title(titles[q], loc="left")
        if per_cycle_displacement and "displacement" in curves and an[0].first_cycle > 0:
            _shade_startup([fig.axes[0]], 360.0, fig.axes[0], text_y=0.03)
        paths.insert(0, plots.save(fig, out / f"{stem}.png"))
    return paths



def _summary_csvs(out: Path, runs: Dict[str, Run], an: Dict[str, Analysis], trends: List[Trend]) -> List[Path]:
    run_rows = []
    for key, case in CASES.items():
        r = runs[key]
        s = r.result.stats
        run_rows.append(
            [
                key, case.joints, case.c_mm, case.omega, s.get("steps", 0), s.get("rejected_steps", 0), s.get("rhs_evaluations", 0),
                r.result.impacts.get("A", ""), r.result.impacts.get("B", ""), r.wall_time,
                float(np.max(r.result.constraint_violation)) if len(r.result.t) else float("nan"),
                float(s.get("t_reached", float("nan"))), "complete" if r.failure is None else r.failure,
            ]
        )  # fmt: skip
    runs_csv = _write_csv(
        out / "runs.csv",
        ["case", "joints", "clearance [mm]", "omega [rad/s]", "steps", "rejected_steps", "rhs_evaluations", "impacts_A", "impacts_B",
         "wall_time [s]", "max_constraint_violation", "t_reached [s]", "status"],
        run_rows,
    )  # fmt: skip
    peak_rows = []
    for key in CLEARANCE_CASES:
        a = an[key]
        for q in QUANTITIES:
            pk, pf = a.peak[q], a.peak_first[q]
            pv, pt = PEAKS[key][q]
            peak_rows.append(
                [
                    key, q, ascii_unit(UNIT[q]),
                    pk.value if pk else float("nan"), pk.time if pk else float("nan"),
                    pf.value if pf else float("nan"), pf.time if pf else float("nan"),
                    a.rms[q], pv, pt,
                ]
            )  # fmt: skip
    peaks_csv = _write_csv(
        out / "peaks.csv",
        ["case", "quantity", "error_unit", "peak_whole_run", "peak_time [s]", "peak_cycle1", "peak_cycle1_time [s]", "rms_analysed_cycles",
         "paper_peak", "paper_peak_time [s]"],
        peak_rows,
    )  # fmt: skip
    min_rows = [
        [
            a.case.key, q,
            f.min_angle if f else float("nan"), f.min_beta if f else float("nan"), f.min_reliability if f else float("nan"),
            pa, float("nan") if pb is None else pb, pr,
        ]
        for a, q, f, (pa, pb, pr) in minima_with_paper(an)
    ]  # fmt: skip
    minima_csv = _write_csv(
        out / "reliability_minima.csv",
        ["case", "quantity", "min_bin_start [deg]", "min_beta", "min_reliability", "paper_angle [deg]", "paper_beta", "paper_reliability"],
        min_rows,
    )
    trend_rows = [[t.number, t.statement, c.comparison, c.ours, c.paper, c.status] for t in trends for c in t.checks]
    trend_rows += [[t.number, t.statement, "overall", t.tally, "", t.status] for t in trends]
    trends_csv = _write_csv(out / "trends.csv", ["trend", "statement", "comparison", "ours", "paper", "status"], trend_rows)
    return [runs_csv, peaks_csv, minima_csv, trends_csv]
