"""``clearsim reliability scene.toml``: run the methods of a scene's ``[study]`` (or of the study
its ``[reliability]`` is the short form of) and write CSV tables, a figure and a short text report."""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from statistics import NormalDist
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..csvfile import column_name, file_unit, report_header, write_rows
from ..errors import ClearsimError, InputError, check_choice
from ..schema import INPUT_UNITS, REFERENCES

#: Why FOSM leaves an output of a series system out (said on stdout and in report.md).
FOSM_SKIPS = "FOSM compares an error with an allowable range [0, limit]; an output with a lower limit (a film thickness) has none, so it is not analysed"

FOSM_NOTE = (
    "FOSM (the paper's method, Eqs. P27–P32) is pointwise in time: per crank-angle bin it compares the "
    "mean and spread of |error| in that bin, over the cycle of the nominal mechanism, with the allowable "
    "range [0, limit] (μ_S = limit/2, σ_S = limit/6), so it answers 'how reliable is the output at this "
    "angle'. The first-passage probability p_f asks whether |error| exceeds the limit anywhere in the "
    "analysed window, over the random inputs. The two are different questions: FOSM's per-bin reliability "
    "neither bounds nor estimates p_f."
)


@dataclass
class Run:
    """What one ``clearsim reliability`` run has found so far: the rows of ``reliability.csv``
    (one per method, plus one per failure mode on a series system) and each method's result."""

    study: Any
    settings: Any
    n: int
    echo: Any
    rows: List[Dict[str, Any]] = field(default_factory=list)
    found: Dict[str, Any] = field(default_factory=dict)

    def row(self, method: str, res: Any, beta: Optional[float] = None, mode: str = "system", of: Any = None) -> None:
        """A row of ``res``; ``of``: the system estimate whose runs a mode's estimate shares (its
        runs and wall time are reported). β is FORM's index, else the generalised reliability
        index −Φ⁻¹(p_f) (Ditlevsen)."""
        lo, hi = getattr(res, "interval", (math.nan, math.nan))
        whole = mode == "system"
        if whole and len(self.study.outputs) == 1:
            mode = self.study.mode_names[0]
        runs_of = of if of is not None else res
        self.rows.append({"method": method, "pf": res.pf, "interval_low": lo, "interval_high": hi, "cov": getattr(res, "cov", math.nan),
                          "beta": beta if beta is not None else getattr(res, "beta", generalised_beta(res.pf)), "runs": getattr(runs_of, "n_runs", 0),
                          "wall_time_s": getattr(runs_of, "wall_time", math.nan), "mode": mode})  # fmt: skip
        if whole:
            self.echo(f"{method:20s} p_f = {res.pf:.4g}  runs = {res.n_runs}  ({res.wall_time:.1f} s)")
        else:
            self.echo(f"{'':20s}   {mode}: p_f = {res.pf:.4g}")


def generalised_beta(pf: float) -> float:
    """β = −Φ⁻¹(p_f) [-] (inf at p_f = 0, −inf at 1, NaN if p_f is not a probability)."""
    if not 0.0 <= pf <= 1.0:
        return math.nan
    return math.inf if pf == 0.0 else -math.inf if pf == 1.0 else -NormalDist().inv_cdf(pf)


def _monte_carlo(r: Run) -> None:
    mc = r.found["monte_carlo"] = r.study.monte_carlo(r.n, seed=r.settings.seed)
    r.row("monte_carlo", mc)
    if len(mc.modes) > 1:
        for m in mc.modes:
            r.row("monte_carlo", m, mode=m.name, of=mc)
    if mc.failures:
        r.echo(f"  {len(mc.failures)} runs failed (counted as exceedances): {mc.failure_reasons()}")


def _form(r: Run) -> None:
    fr = r.found["form"] = r.study.form(step=r.settings.step)
    r.row("form", fr)
    for name, m in zip(getattr(fr, "mode_names", []), getattr(fr, "modes", [])):
        r.row("form", m, mode=name)


def _importance_sampling(r: Run) -> None:
    if "form" not in r.found:
        _form(r)
    r.found["importance_sampling"] = res = r.study.importance_sampling(cov=r.settings.cov, seed=r.settings.seed, design_point=r.found["form"])
    r.row("importance_sampling", res)


def _subset(r: Run) -> None:
    # The scene's `samples` is the runs per level here (it sizes Monte Carlo and Sobol alike).
    r.found["subset"] = res = r.study.subset(seed=r.settings.seed, n_per_level=r.n)
    r.row("subset", res)


def _sobol(r: Run) -> None:
    res = r.found["sobol"] = r.study.sobol(r.n, seed=r.settings.seed, method=r.settings.sobol_method)
    r.echo(f"{'sobol':20s} ({res.method}) runs = {res.n_runs}  ({res.wall_time:.1f} s); widest interval {res.widest:.2f}")


def _fosm(r: Run) -> None:
    """FOSM of every output it applies to (an upper limit), from one monitored run of the
    nominal mechanism, each against its allowable range (``[reliability]``'s, else [0, limit])."""
    study, allowable = r.study, r.settings.allowable
    chosen = [i for i, (o, lim) in enumerate(zip(study.outputs, study.limits)) if lim.side == "above" and o.quantity != "film_thickness"] or [0]
    results = study.fosm_all(outputs=chosen, allowable=[allowable[i] for i in chosen] if allowable is not None else None)
    r.found["fosm"] = res = results[0]
    r.found["fosm_outputs"] = {study.outputs[i].name: res_i for i, res_i in zip(chosen, results)}
    # The outputs FOSM does not apply to (a lower limit, such as a film thickness's): said, not dropped silently.
    skipped = r.found["fosm_skipped"] = [f"`{o.name}` ({o.label} {lim.text(o.unit)})" for i, (o, lim) in enumerate(zip(study.outputs, study.limits)) if i not in chosen]
    if skipped:
        r.echo(f"{'fosm':20s} skips {', '.join(s.replace('`', '') for s in skipped)}: {FOSM_SKIPS}")
    if len(study.outputs) == 1:
        r.echo(f"{'fosm':20s} min R = {res.min_reliability:.6f} at {res.min_angle:g}°")
        return
    for name, res_i in r.found["fosm_outputs"].items():
        r.echo(f"{'fosm':20s} {name}: min R = {res_i.min_reliability:.6f} (β = {res_i.min_beta:.3f}) at {res_i.min_angle:g}°")


def _ak(r: Run, method: str) -> None:
    res = r.found[method] = getattr(r.study, method)(max_runs=r.settings.max_runs, seed=r.settings.seed)
    r.row(method, res)
    r.echo(f"{'':20s}   {res.extra['iterations']} learning runs, {res.extra['population']} candidates, min U = {res.extra['min_u']:.2f}")


def _life(r: Run, out_dir: Path, plots: bool) -> List[Path]:
    """``[study.life]``: p_f against cycles into life.csv, life.png and the report."""
    from .life_plot import LIFE_HEADER, life_rows, plot_life

    ls = r.settings.life
    res = r.found["life"] = r.study.life(ls.cycles, ls.samples, seed=r.settings.seed, max_growth=ls.max_growth, max_jump=ls.max_jump, settle=ls.settle, max_blocks=ls.max_blocks)
    r.echo(f"{'life':20s} p_f at {res.cycles[-1]:g} cycles = {res.pf[-1]:.4g}  runs = {res.n_runs}  ({res.wall_time:.1f} s)")
    if ls.reliability is not None:
        try:
            r.found["life_at"] = res.life_at(ls.reliability)
        except Exception as err:  # the samples do not reach R within the cycles: say so
            r.found["life_at"] = str(err)
    files = [_write(out_dir / "life.csv", report_header(LIFE_HEADER, r.study.output.unit), life_rows(res))]
    if plots:
        plot_life(res, limit=r.study.limit, unit=r.study.output.unit, reliability=[ls.reliability] if ls.reliability else None, path=out_dir / "life.png")
        files.append(out_dir / "life.png")
    return files


#: The methods in the order they run: name → runner (extension point: a method added to
#: scene.METHODS gets its runner here, and its CSV/plot/report parts below).
METHOD_RUNNERS: Dict[str, Callable[[Run], None]] = {
    "monte_carlo": _monte_carlo, "form": _form, "importance_sampling": _importance_sampling, "subset": _subset, "sobol": _sobol, "fosm": _fosm,
    "ak_mcs": lambda r: _ak(r, "ak_mcs"), "ak_is": lambda r: _ak(r, "ak_is"),
}  # fmt: skip


#: What each reference answers (report lines; :data:`clearsim.schema.REFERENCES`).
REFERENCE_TEXT = {
    "own_ideal": "each sample's own ideal twin (what the clearances add)",
    "nominal": "the nominal design's ideal motion (how far from the nominal motion: every tolerance counts)",
}


def run_study(
    scene: Any, out_dir: Path, *, methods: Optional[Sequence[str]] = None, samples: Optional[int] = None, progress: bool = True, plots: bool = True,
    echo: Any = print, reference: Optional[str] = None,
) -> List[Path]:  # fmt: skip
    """Run the study's methods, write ``reliability.csv`` (one row per method, and per failure
    mode on a series system), ``sobol.csv``, ``samples.csv`` (Monte Carlo: inputs, each output's
    peak and first-passage time), ``fosm.csv``, ``reliability.png`` and ``report.md`` into
    ``out_dir``; returns the files. A method that stops with a clearsim error (FORM without a
    design point; a life, ``[study.life]``, over ``max_blocks``) is named in report.md, with the
    methods it left unrun, after the results found before it are written, then raised.
    ``reference`` (``"own_ideal"`` or ``"nominal"``) replaces the scene's ``[study] reference``."""
    settings = scene.study_settings()
    study = scene.study_model(progress=progress)
    if reference is not None:
        study.reference = check_choice("reference", reference, REFERENCES)
    chosen = list(methods or settings.methods)
    if not settings.inputs and set(chosen) != {"fosm"}:
        raise InputError(f"invalid methods = {chosen!r}: {scene.path or 'the scene'} has only [reliability] (the FOSM of the nominal mechanism, no random inputs): "
                         "give a [study] with [[study.input]] for the other methods", field="methods", value=chosen)  # fmt: skip
    if "fosm" in chosen and not any(lim.side == "above" and o.quantity != "film_thickness" for o, lim in zip(study.outputs, study.limits)):
        raise InputError(f"invalid methods = {chosen!r}: fosm compares an error with an allowable range [0, limit], and no output of {scene.path or 'the scene'} has an upper limit "
                         "(a film thickness's is a lower one): drop fosm", field="methods", value=chosen)  # fmt: skip
    r = Run(study, settings, int(samples or settings.samples), echo)
    out_dir.mkdir(parents=True, exist_ok=True)
    echo(f"{scene.name}: {study}")
    if any(o.body is not None for o in study.outputs):
        echo(f"{'reference':20s} errors against {REFERENCE_TEXT[study.reference]}")
    stop: Optional[ClearsimError] = None
    for name, runner in METHOD_RUNNERS.items():
        if name in chosen and not (name == "form" and name in r.found):
            try:
                runner(r)
            except ClearsimError as err:  # what the methods before it found is still written, then it is raised
                stop = err
                order = list(METHOD_RUNNERS)
                left = [m for m in order[order.index(name) + 1 :] if m in chosen]
                left += ["tolerance"] * (settings.tolerance is not None) + ["life"] * (settings.life is not None)
                r.found["method_error"] = (name, err, left)
                break
    if stop is None and settings.tolerance is not None:
        name, rel_target, bracket = settings.tolerance
        r.found["tolerance"] = tol = study.tolerance(name, rel_target, bracket=bracket, cov=settings.cov, seed=settings.seed, step=settings.step)
        echo(f"{'tolerance':20s} largest mean {name} = {tol.value:.6g} (95 % [{tol.interval[0]:.6g}, {tol.interval[1]:.6g}]) for R = {rel_target}  runs = {tol.n_runs}")
    rows, found = r.rows, r.found
    files: List[Path] = []
    life_error: Optional[ClearsimError] = None
    if settings.life is not None and stop is None:
        try:
            files = _life(r, out_dir, plots)
        except ClearsimError as err:  # the other methods' results are still written, then it is raised
            life_error = found["life_error"] = err
    if rows:
        files.append(_write(out_dir / "reliability.csv", report_header(rows[0]), [[row[k] for k in rows[0]] for row in rows]))
    if "sobol" in found:
        s = found["sobol"]
        conv = sorted(s.convergence)[:-1]
        files.append(_write(out_dir / "sobol.csv", ["input", "first", "first_low", "first_high", "total", "total_low", "total_high"] + [f"first_n{m}" for m in conv] + [f"total_n{m}" for m in conv],
                            [[k, s.first[k], *s.first_interval[k], s.total[k], *s.total_interval[k]] + [s.convergence[m][0][k] for m in conv] + [s.convergence[m][1][k] for m in conv] for k in s.first]))  # fmt: skip
    if "monte_carlo" in found:
        mc = found["monte_carlo"]
        names = list(mc.inputs)
        peaks = np.asarray(mc.peaks).reshape(mc.peaks.shape[0], -1)
        first = np.asarray(mc.first_passage_times).reshape(peaks.shape[0], -1)
        if len(study.outputs) == 1:
            head = [column_name("peak", study.output.unit), column_name("first_passage_time", "s")]
        else:
            head = [column_name(o.name, o.unit) for o in study.outputs] + [column_name(f"{o.name}.first_passage_time", "s") for o in study.outputs]
        files.append(_write(out_dir / "samples.csv", [input_column(k, getattr(scene, "parameter_units", {})) for k in names] + head, [[mc.inputs[k][i] for k in names] + list(peaks[i]) + list(first[i]) for i in range(peaks.shape[0])]))
    if "fosm" in found:
        # One output: its bins, mu_s [unit]; several (a system, or [reliability]'s quantities): a row
        # per output and bin, the unit in an error_unit column as in clearsim paper's tables.
        several = len(study.outputs) > 1
        units = {o.name: file_unit(o.unit) for o in study.outputs}
        stats = ["mu_s_error_unit", "sigma_s_error_unit"] if several else report_header(["mu_s", "sigma_s"], study.output.unit)
        files.append(_write(out_dir / "fosm.csv", ["output", "error_unit"] * several + report_header(["angle_deg"]) + stats + ["beta", "reliability"],
                            [[name, units[name]] * several + [a, m, s, b, rr] for name, fo in found["fosm_outputs"].items()
                             for a, m, s, b, rr in zip(fo.bin_starts, fo.mu_s, fo.sigma_s, fo.beta, fo.reliability)]))  # fmt: skip
    if plots:
        files.append(plot_study(study, found, out_dir / "reliability.png"))
    files.append(_report(scene, study, rows, found, out_dir / "report.md", files))
    if stop is not None:
        raise stop
    if life_error is not None:
        raise life_error
    return files


def _write(path: Path, header: Sequence[str], rows: Sequence[Sequence[Any]]) -> Path:
    return write_rows(path, header, rows)


#: Units of the numbers a ``[[study.input]]`` path names (``B.clearance``), by field (the SI
#: units of rust/description.rs), for samples.csv's header. A field not listed is headed by its
#: path alone. (Belongs with the other units in clearsim.schema.)


def input_column(path: str, parameter_units: Mapping[str, str] = {}) -> str:
    """samples.csv's header of a random input: ``B.clearance [m]`` (:data:`clearsim.schema.INPUT_UNITS`);
    a ``[parameters]`` name with the unit of the fields it is written in (``l5 [m]``,
    ``Scene.parameter_units``), or by itself where none is clear."""
    unit = INPUT_UNITS.get(path.rpartition(".")[2]) if "." in path else parameter_units.get(path)
    return column_name(path, unit)


def plot_study(study: Any, found: Dict[str, Any], path: Path) -> Path:
    """p_f by method (with intervals) and, from Monte Carlo, P(peak > limit) against the limit;
    FORM importance factors; Sobol indices."""
    from .. import plots

    estimates = [(k, found[k]) for k in ("monte_carlo", "form", "importance_sampling", "subset", "ak_mcs", "ak_is") if k in found]
    panels = ["pf"] * bool(estimates) + ["curve"] * ("monte_carlo" in found) + ["importance"] * ("form" in found) + ["sobol"] * ("sobol" in found)
    if not panels and "fosm" in found:  # FOSM alone ([reliability]): its reliability per bin, as clearsim run draws it
        return plots.save(plots.plot_reliability_panels({name: {"FOSM, nominal mechanism": res} for name, res in found["fosm_outputs"].items()}), path)
    if not panels:
        panels = ["pf"]
    with plots.style():
        fig = plots.new_figure(4.2 * len(panels), 3.6)
        axes = list(fig.subplots(1, len(panels), squeeze=False)[0])
        unit = study.output.unit
        if panels[0] == "pf":  # p_f by method with its 95 % interval (FORM: a point, no interval); none for Sobol alone
            _pf_panel(axes.pop(0), estimates, study, unit)
        if "monte_carlo" in found and not np.isfinite(found["monte_carlo"].peaks).any():
            _no_sample(axes.pop(0), found["monte_carlo"])  # every run failed: nothing to draw but why
        elif "monte_carlo" in found and len(study.outputs) == 1:
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
        elif "monte_carlo" in found:
            # A system: each mode's P(g_i ≤ x) against x, g_i the output's margin scaled by its limit.
            ax = axes.pop(0)
            values = found["monte_carlo"].peaks
            for i, (o, lim) in enumerate(zip(study.outputs, study.limits)):
                g = np.sort(lim.g(values[np.isfinite(values[:, i]), i]))
                ax.step(g, np.arange(1, g.size + 1) / max(g.size, 1), where="post", label=o.name)
            ax.axvline(0.0, color="C3", lw=0.8, ls="--")
            ax.set_yscale("log")
            ax.set_xlabel("margin g_i (0: at the limit)")
            ax.set_ylabel("P(g_i ≤ margin)")
            ax.set_title("Monte Carlo: each failure mode")
            ax.legend(fontsize=7)
        if "form" in found:
            ax = axes.pop(0)
            imp = found["form"].importance
            ax.bar(range(len(imp)), list(imp.values()), color="C0")
            ax.set_xticks(range(len(imp)), [_input_label(k) for k in imp])
            ax.set_ylim(0, 1)
            ax.set_title(f"FORM importance factors (β = {found['form'].beta:.2f})")
        if "sobol" in found:
            ax = axes.pop(0)
            s = found["sobol"]
            x = np.arange(len(s.first))
            ax.bar(x - 0.2, list(s.first.values()), 0.4, label="first order")
            ax.bar(x + 0.2, list(s.total.values()), 0.4, label="total")
            ax.set_xticks(x, [_input_label(k) for k in s.first])
            ax.set_ylim(0, 1.05)
            ax.set_title(f"Sobol indices of the peak ({s.n_runs} runs)")
            ax.legend(fontsize=7)
        return plots.save(fig, path)


def _pf_panel(ax: Any, estimates: Sequence[Tuple[str, Any]], study: Any, unit: str) -> None:
    """p_f by method with its 95 % interval (FORM: a point, no interval)."""
    from matplotlib.ticker import NullFormatter

    for y, (k, r) in enumerate(estimates):
        lo, hi = getattr(r, "interval", (r.pf, r.pf))
        if r.pf > 0:
            ax.errorbar([r.pf], [y], xerr=[[r.pf - lo], [hi - r.pf]] if hi > lo else None, fmt="o", capsize=3, color=f"C{y}")
        ax.annotate(f"{r.pf:.3g}  ({r.n_runs} runs)", (r.pf if r.pf > 0 else 1e-300, y), textcoords="offset points", xytext=(0, 7), ha="center", fontsize=7)
    ax.set_yticks(range(len(estimates)), [k.replace("_", " ") for k, _ in estimates])
    ax.set_ylim(-0.6, len(estimates) - 0.3)
    shown = [v for _, r in estimates for v in (r.pf, *getattr(r, "interval", ())) if v > 0]
    if shown:  # else a log axis has nothing to show
        ax.set_xscale("log")
        # Whole decades, labelled at the decades only: within one decade matplotlib labels the
        # minor ticks (2×10⁻², 3×10⁻², ...), which run into each other.
        ax.set_xlim(10 ** math.floor(math.log10(min(shown))), 10 ** math.ceil(math.log10(max(shown)) + 1e-12))
        ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("probability of exceedance p_f")
    ax.set_title(f"p_f: peak > {study.limit:.3g} {unit}" if len(study.outputs) == 1 else f"p_f of the system ({len(study.outputs)} modes)")


def _input_label(path: str) -> str:
    """A random input's name under a bar, one line per part of its path (``big-end`` over
    ``clearance``): four inputs' paths side by side run into each other."""
    return path.replace(".", "\n")


def _no_sample(ax: Any, mc: Any) -> None:
    """The Monte Carlo panel when no sample succeeded: why, by reason and count."""
    reasons = "\n".join(textwrap.fill(f"{n} × {why}", 58) for why, n in mc.failure_reasons().items())
    ax.text(0.5, 0.5, f"no sample succeeded ({len(mc.failures)} of {mc.n_runs} failed):\n\n{reasons}", transform=ax.transAxes, ha="center", va="center", fontsize=7)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title("Monte Carlo: p_f against the limit")


def _report(scene: Any, study: Any, rows: List[Dict[str, Any]], found: Dict[str, Any], path: Path, files: List[Path]) -> Path:
    outs = "; ".join(f"{o.label} {lim.text(o.unit)} (`{o.name}`)" for o, lim in zip(study.outputs, study.limits))
    kind = "Output" if len(study.outputs) == 1 else "Outputs (a series system: it fails when any output passes its limit)"
    lines = [f"# Reliability: {scene.name}", "", f"{kind}: {outs}; {study.cycles:g} cycle(s) after {study.skip_cycles:g}.", ""]
    if any(o.body is not None for o in study.outputs):
        lines += [f"Errors measured against {REFERENCE_TEXT[study.reference]} (`reference = \"{study.reference}\"`).", ""]
    lines += ["Random inputs:", ""]
    settings = scene.study_settings()
    for name, d in study.inputs.items():
        if name in settings.inputs:
            lines.append(f"- `{name}`: {d}")
    if not settings.inputs:
        lines.append("none: `[reliability]`, the short form of `[study]` with `methods = [\"fosm\"]`, analyses the nominal mechanism.")
    if rows:
        lines += ["", "| method | mode | p_f | 95 % interval | CoV | β | runs | wall time [s] |", "|---|---|---|---|---|---|---|---|"]
        for r in rows:
            lines.append(f"| {r['method']} | {r['mode']} | {r['pf']:.4g} | [{r['interval_low']:.3g}, {r['interval_high']:.3g}] | {r['cov']:.3g} | {r['beta']:.3g} | {r['runs']} | {r['wall_time_s']:.1f} |")
        lines += ["", "β: FORM's reliability index, for the sampling methods the generalised index −Φ⁻¹(p_f); a series system's mode rows share its runs."]
    mc = found.get("monte_carlo")
    if mc is not None and mc.failures:
        lines += ["", f"Monte Carlo: {len(mc.failures)} of {mc.n_runs} runs failed ({'counted as exceedances' if mc.on_failure == 'fail' else 'left out'}): "
                  + "; ".join(f"{n} × {why}" for why, n in mc.failure_reasons().items())]  # fmt: skip
    if "form" in found:
        fr = found["form"]
        lines += ["", "FORM design point: " + ", ".join(f"`{k}` = {v:.6g}" for k, v in fr.design_point.items()),
                  "importance factors: " + ", ".join(f"`{k}` {v:.2f}" for k, v in fr.importance.items())]  # fmt: skip
        for i in getattr(fr, "mirrored", []):
            m = fr.modes[i]
            lines += ["", f"A second FORM design point on the other side of the inputs' means (`{fr.mode_names[i]}`: the limit state fails on both sides, "
                      f"as a tolerance does against the nominal design), β = {m.beta:.4g}: " + ", ".join(f"`{k}` = {v:.6g}" for k, v in m.design_point.items()),
                      "p_f below is the union of both sides; importance sampling samples around both design points."]  # fmt: skip
        if hasattr(fr, "modes"):
            lines += ["", f"Series system, first order: p_f = {fr.pf:.4g} (Ditlevsen's bounds [{fr.bounds[0]:.4g}, {fr.bounds[1]:.4g}]); "
                      "the design point above is the dominant mode's. Correlation of the modes' linearised margins ρ = α_i·α_j:", ""]
            lines += ["| | " + " | ".join(fr.mode_names) + " |", "|---" * (len(fr.mode_names) + 1) + "|"]
            lines += [f"| {a} | " + " | ".join(f"{fr.rho[i, j]:.3f}" for j in range(len(fr.mode_names))) + " |" for i, a in enumerate(fr.mode_names)]
        noisy = [m for m in getattr(fr, "modes", [fr]) if getattr(m, "accepted_at_noise", False)]
        if noisy:
            lines += ["", "FORM accepted " + ", ".join(f"β = {m.beta:.3g} ± {m.beta_noise:.2g}" for m in noisy) + " at the noise level of the limit state (σ_g measured): check p_f by importance sampling."]
    if "sobol" in found:
        s = found["sobol"]
        conv = sorted(s.convergence)
        lines += ["", f"Sobol indices ({s.method}, n = {s.n}, {s.n_runs} runs; first-order at n = {', '.join(map(str, conv))} to show convergence):", "",
                  "| input | first | 95 % | total | 95 % | first at " + ", ".join(map(str, conv)) + " |", "|---|---|---|---|---|---|"]  # fmt: skip
        lines += [f"| `{k}` | {s.first[k]:.3f} | [{s.first_interval[k][0]:.2f}, {s.first_interval[k][1]:.2f}] | {s.total[k]:.3f} | "
                  f"[{s.total_interval[k][0]:.2f}, {s.total_interval[k][1]:.2f}] | " + ", ".join(f"{s.convergence[m][0][k]:.2f}" for m in conv) + " |" for k in s.first]  # fmt: skip
        if s.widest > 0.2:
            lines += ["", f"Intervals up to {s.widest:.2f} wide: the indices are not yet readable; see docs/reliability.md on choosing n."]
    if "tolerance" in found:
        t = found["tolerance"]
        lines += ["", f"Tolerance: the largest mean of `{t.name}` with reliability {t.reliability} is {t.value:.6g} (95 % [{t.interval[0]:.6g}, {t.interval[1]:.6g}]; FORM alone {t.form_value:.6g}; {t.n_runs} runs)."]
    if "life" in found:
        lf = found["life"]
        lines += ["", f"Reliability over life ({lf.g.shape[0]} samples, Archard wear fed back, cycle jumping: {lf.blocks.mean():.1f} blocks a sample, {lf.n_runs} runs; "
                  "docs/reliability.md, \"Reliability over life\"):", "", "| cycles | p_f | 95 % interval |", "|---|---|---|"]  # fmt: skip
        lines += [f"| {n:g} | {p:.4g} | [{a:.3g}, {b:.3g}] |" for n, p, a, b in zip(lf.cycles, lf.pf, *lf.interval)]
        at = found.get("life_at")
        if isinstance(at, tuple):
            lines += ["", f"Reliability falls to {study_settings_reliability(scene)} at {at[0]:.4g} cycles (95 % [{at[1][0]:.4g}, {at[1][1]:.4g}])."]
        elif at is not None:
            lines += ["", f"Life at R = {study_settings_reliability(scene)}: {at}"]
    if "method_error" in found:
        name, err, left = found["method_error"]
        lines += ["", f"Stopped at {name}: {err}" + (f" Not run: {', '.join(left)}." if left else "")]
    if "life_error" in found:
        lines += ["", f"Reliability over life: not run to the end: {found['life_error']}"]
    if "fosm" in found:
        for name, fo in found["fosm_outputs"].items():
            which = f" `{name}`" if len(study.outputs) > 1 else ""
            lines += ["", f"FOSM{which} (nominal mechanism, {fo.bin_width:g}° bins, allowable μ_S = {fo.mu_S:.6g}, σ_S = {fo.sigma_S:.6g}): "
                      f"minimum reliability {fo.min_reliability:.6f} (β = {fo.min_beta:.3f}) at {fo.min_angle:g}°."]  # fmt: skip
        if found.get("fosm_skipped"):
            lines += ["", f"FOSM skipped {', '.join(found['fosm_skipped'])}: {FOSM_SKIPS}."]
    lines += ["", FOSM_NOTE, "", "Files: " + ", ".join(p.name for p in files) + ", report.md", ""]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def study_settings_reliability(scene: Any) -> Any:
    """The reliability ``[study.life]`` asks the life for."""
    settings = scene.study_settings()
    return settings.life.reliability if settings.life is not None else None
