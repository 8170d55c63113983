"""``clearsim reliability scene.toml``: run the methods of a scene's ``[study]`` and write CSV
tables, a figure and a short text report."""

from __future__ import annotations

import csv
import math
import time
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from .scene import scene_study

FOSM_NOTE = (
    "FOSM (the paper's method, Eqs. P27–P32) is pointwise in time: per crank-angle bin it compares the "
    "mean and spread of |error| in that bin, over the cycle of the nominal mechanism, with the allowable "
    "range [0, limit] (μ_S = limit/2, σ_S = limit/6), so it answers 'how reliable is the output at this "
    "angle'. The first-passage probability p_f asks whether |error| exceeds the limit anywhere in the "
    "analysed window, over the random inputs. The two are different questions: FOSM's per-bin reliability "
    "neither bounds nor estimates p_f."
)


def run_study(scene: Any, out_dir: Path, *, methods: Optional[Sequence[str]] = None, samples: Optional[int] = None, progress: bool = True, plots: bool = True, echo: Any = print) -> List[Path]:
    """Run the study's methods, write ``reliability.csv`` (one row per method), ``sobol.csv``,
    ``samples.csv`` (Monte Carlo: inputs, peak, first-passage time), ``fosm.csv``,
    ``reliability.png`` and ``report.md`` into ``out_dir``; returns the files."""
    settings = scene.study
    study = scene_study(scene, progress=progress)
    methods = list(methods or settings.methods)
    n = int(samples or settings.samples)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows: List[Dict[str, Any]] = []
    found: Dict[str, Any] = {}
    unit = study.output.unit

    def row(method: str, res: Any, beta: Optional[float] = None) -> None:
        lo, hi = getattr(res, "interval", (math.nan, math.nan))
        rows.append({"method": method, "pf": res.pf, "interval_low": lo, "interval_high": hi, "cov": getattr(res, "cov", math.nan),
                     "beta": beta if beta is not None else getattr(res, "beta", math.nan), "runs": res.n_runs, "wall_time_s": res.wall_time})  # fmt: skip
        echo(f"{method:20s} p_f = {res.pf:.4g}  runs = {res.n_runs}  ({res.wall_time:.1f} s)")

    echo(f"{scene.name}: {study}")
    if "monte_carlo" in methods:
        mc = study.monte_carlo(n, seed=settings.seed)
        found["monte_carlo"] = mc
        row("monte_carlo", mc)
        if mc.failures:
            echo(f"  {len(mc.failures)} runs failed (counted as exceedances): {mc.failure_reasons()}")
    fr = None
    if "form" in methods or "importance_sampling" in methods:
        fr = study.form()
        found["form"] = fr
        row("form", fr)
    if "importance_sampling" in methods:
        is_ = study.importance_sampling(cov=settings.cov, seed=settings.seed, design_point=fr)
        found["importance_sampling"] = is_
        row("importance_sampling", is_)
    if "subset" in methods:
        ss = study.subset(seed=settings.seed)
        found["subset"] = ss
        row("subset", ss)
    if "sobol" in methods:
        t0 = time.perf_counter()
        found["sobol"] = study.sobol(n, seed=settings.seed)
        echo(f"{'sobol':20s} runs = {found['sobol'].n_runs}  ({time.perf_counter() - t0:.1f} s)")
    if "fosm" in methods:
        found["fosm"] = study.fosm()
        echo(f"{'fosm':20s} min R = {found['fosm'].min_reliability:.6f} at {found['fosm'].min_angle:g}°")
    if settings.tolerance is not None:
        name, r, bracket = settings.tolerance
        found["tolerance"] = tol = study.tolerance(name, r, bracket=bracket, cov=settings.cov, seed=settings.seed)
        echo(f"{'tolerance':20s} largest mean {name} = {tol.value:.6g} (95 % [{tol.interval[0]:.6g}, {tol.interval[1]:.6g}]) for R = {r}  runs = {tol.n_runs}")

    files: List[Path] = []
    if rows:
        files.append(_write(out_dir / "reliability.csv", list(rows[0]), [[r[k] for k in rows[0]] for r in rows]))
    if "sobol" in found:
        s = found["sobol"]
        files.append(_write(out_dir / "sobol.csv", ["input", "first", "first_low", "first_high", "total", "total_low", "total_high"],
                            [[k, s.first[k], *s.first_interval[k], s.total[k], *s.total_interval[k]] for k in s.first]))  # fmt: skip
    if "monte_carlo" in found:
        mc = found["monte_carlo"]
        names = list(mc.inputs)
        files.append(_write(out_dir / "samples.csv", names + [f"peak [{unit}]", "first_passage_time [s]"],
                            [[mc.inputs[k][i] for k in names] + [mc.peaks[i], mc.first_passage_times[i]] for i in range(mc.peaks.size)]))  # fmt: skip
    if "fosm" in found:
        fo = found["fosm"]
        files.append(_write(out_dir / "fosm.csv", ["bin_start_deg", "mu_s", "sigma_s", "beta", "reliability"],
                            [[a, m, s, b, r] for a, m, s, b, r in zip(fo.bin_starts, fo.mu_s, fo.sigma_s, fo.beta, fo.reliability)]))  # fmt: skip
    if plots:
        files.append(plot_study(study, found, out_dir / "reliability.png"))
    files.append(_report(scene, study, rows, found, out_dir / "report.md", files))
    return files


def _write(path: Path, header: Sequence[str], rows: Sequence[Sequence[Any]]) -> Path:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([f"{v:.10g}" if isinstance(v, (float, np.floating)) else v for v in r])
    return path


def plot_study(study: Any, found: Dict[str, Any], path: Path) -> Path:
    """p_f by method (with intervals) and, from Monte Carlo, P(peak > limit) against the limit;
    FORM importance factors; Sobol indices."""
    from .. import plots

    estimates = [(k, found[k]) for k in ("monte_carlo", "form", "importance_sampling", "subset") if k in found]
    panels = ["pf"] * bool(estimates) + ["curve"] * ("monte_carlo" in found) + ["importance"] * ("form" in found) + ["sobol"] * ("sobol" in found)
    if not panels:
        panels = ["pf"]
    with plots.style():
        fig = plots._new_figure(4.2 * len(panels), 3.6)
        axes = list(fig.subplots(1, len(panels), squeeze=False)[0])
        unit = study.output.unit
        ax = axes.pop(0)
        # p_f by method with its 95 % interval (FORM: a point, no interval).
        for y, (k, r) in enumerate(estimates):
            lo, hi = getattr(r, "interval", (r.pf, r.pf))
            if r.pf > 0:
                ax.errorbar([r.pf], [y], xerr=[[r.pf - lo], [hi - r.pf]] if hi > lo else None, fmt="o", capsize=3, color=f"C{y}")
            ax.annotate(f"{r.pf:.3g}  ({r.n_runs} runs)", (r.pf if r.pf > 0 else 1e-300, y), textcoords="offset points", xytext=(0, 7), ha="center", fontsize=7)
        ax.set_yticks(range(len(estimates)), [k.replace("_", " ") for k, _ in estimates])
        ax.set_ylim(-0.6, len(estimates) - 0.3)
        ax.set_xscale("log")
        ax.set_xlabel("probability of exceedance p_f")
        ax.set_title(f"p_f: peak > {study.limit:.3g} {unit}")
        if "monte_carlo" in found:
            ax = axes.pop(0)
            peaks = np.sort(found["monte_carlo"].peaks[np.isfinite(found["monte_carlo"].peaks)])
            p = 1.0 - np.arange(peaks.size) / max(peaks.size, 1)
            ax.step(peaks, p, where="post", color="0.3")
            ax.axvline(study.limit, color="C3", lw=0.8, ls="--", label=f"limit {study.limit:.3g} {unit}")
            ax.set_yscale("log")
            ax.set_xlabel(f"limit [{unit}]")
            ax.set_ylabel("P(peak > limit)")
            ax.set_title("Monte Carlo: p_f against the limit")
            ax.legend(fontsize=7)
        if "form" in found:
            ax = axes.pop(0)
            imp = found["form"].importance
            ax.bar(list(imp), list(imp.values()), color="C0")
            ax.set_ylim(0, 1)
            ax.set_title(f"FORM importance factors (β = {found['form'].beta:.2f})")
        if "sobol" in found:
            ax = axes.pop(0)
            s = found["sobol"]
            x = np.arange(len(s.first))
            ax.bar(x - 0.2, list(s.first.values()), 0.4, label="first order")
            ax.bar(x + 0.2, list(s.total.values()), 0.4, label="total")
            ax.set_xticks(x, list(s.first))
            ax.set_ylim(0, 1.05)
            ax.set_title(f"Sobol indices of the peak ({s.n_runs} runs)")
            ax.legend(fontsize=7)
        return plots.save(fig, path)


def _report(scene: Any, study: Any, rows: List[Dict[str, Any]], found: Dict[str, Any], path: Path, files: List[Path]) -> Path:
    lines = [f"# Reliability: {scene.name}", "", f"Output: {study.output.label}; limit {study.limit:g} {study.output.unit}; "
             f"{study.cycles:g} cycle(s) after {study.skip_cycles:g}.", "", "Random inputs:", ""]  # fmt: skip
    for name, d in study.inputs.items():
        lines.append(f"- `{name}`: {d}")
    if rows:
        lines += ["", "| method | p_f | 95 % interval | CoV | β | runs | wall time [s] |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            lines.append(f"| {r['method']} | {r['pf']:.4g} | [{r['interval_low']:.3g}, {r['interval_high']:.3g}] | {r['cov']:.3g} | {r['beta']:.3g} | {r['runs']} | {r['wall_time_s']:.1f} |")
    if "form" in found:
        fr = found["form"]
        lines += ["", "FORM design point: " + ", ".join(f"`{k}` = {v:.6g}" for k, v in fr.design_point.items()),
                  "importance factors: " + ", ".join(f"`{k}` {v:.2f}" for k, v in fr.importance.items())]  # fmt: skip
    if "sobol" in found:
        s = found["sobol"]
        lines += ["", "| input | Sobol first | Sobol total |", "|---|---|---|"] + [f"| `{k}` | {s.first[k]:.3f} | {s.total[k]:.3f} |" for k in s.first]
    if "tolerance" in found:
        t = found["tolerance"]
        lines += ["", f"Tolerance: the largest mean of `{t.name}` with reliability {t.reliability} is {t.value:.6g} (95 % [{t.interval[0]:.6g}, {t.interval[1]:.6g}]; FORM alone {t.form_value:.6g}; {t.n_runs} runs)."]
    if "fosm" in found:
        fo = found["fosm"]
        lines += ["", f"FOSM (nominal mechanism, {fo.bin_width:g}° bins): minimum reliability {fo.min_reliability:.6f} (β = {fo.min_beta:.3f}) at {fo.min_angle:g}°."]
    lines += ["", FOSM_NOTE, "", "Files: " + ", ".join(p.name for p in files) + ", report.md", ""]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path
