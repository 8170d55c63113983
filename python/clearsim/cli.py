"""The ``clearsim`` command line (also ``python -m clearsim``).

Subcommands::

    clearsim run SCENE.toml [-o OUTDIR] [--no-plots] [--t-end T] [--integrator NAME] [-q]
    clearsim reliability SCENE.toml [-o OUTDIR] [--methods LIST] [--samples N] [-q]
    clearsim sweep SCENE.toml [-o OUTDIR] [--count N] [--cycles N] [--transient-cycles N] [-q]
    clearsim paper [-o OUTDIR] [--quick] [--cycles N] [-q]
    clearsim info
    clearsim --version

``run`` writes into OUTDIR (default ``clearsim-<scene name>``): CSV files with a header row
naming every column and its unit (``bodies.csv``, ``bodies_ideal.csv`` — bodies and tracked
points —, ``errors.csv``, ``joints.csv``, ``reactions.csv``, ``reliability_<quantity>.csv``),
PNG figures and ``summary.json`` / ``summary.md``. A :class:`clearsim.ClearsimError` is printed as one line on stderr with exit
code 2 (no traceback); a failed simulation also writes its partial results. Any other failure
(a bug) is one line too, with exit code 1; ``--debug`` adds the traceback. A failure while the
outputs are written stops only that output: the others and the summary (``summary.md`` of
``run``, ``report.md`` of ``reliability`` and ``paper``) are still written and name what failed.
Warnings (e.g. :class:`clearsim.PlausibilityWarning`) are printed as ``clearsim: warning: ...``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
import time
import traceback
import warnings
from pathlib import Path
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import __version__, cli_readings, models
from .csvfile import column_name, report_header, write_columns, write_rows
from .cli_support import EXIT_ERROR, EXIT_FAILURE, OutputsFailed, _describe, _positive_float, _positive_int, _summary_on_failure
from .export import error_columns
from .errors import ClearsimError
from .film_readings import film_columns
from .joint_readings import summary_markdown
from .schema import INTEGRATORS, REFERENCES, body_unit
from .sweep_command import add_sweep_parser
from .scene import BODY_CHANNELS, COMPONENTS, ERROR_QUANTITIES, JOINT_CHANNELS, Scene, SceneRun, load_scene_file

class _Steps:
    """The outputs of a command, each written on its own: one that fails does not stop the others."""

    def __init__(self) -> None:
        self.files: List[Path] = []
        self.failed: List[Tuple[str, BaseException]] = []

    def __call__(self, what: str, write: Callable[[], Union[Path, List[Path]]]) -> None:
        try:
            written = write()
        except Exception as err:  # noqa: BLE001 — recorded, named in the summary and re-raised at the end
            self.failed.append((what, err))
            return
        self.files += written if isinstance(written, list) else [written]

_THETA_INFO = {  # plot labels of the error of an angle (plots.QUANTITIES covers x and y)
    "displacement": ("Angle error", "rad", 1.0),
    "velocity": ("Angular velocity error", "rad/s", 1.0),
    "acceleration": ("Angular acceleration error", "rad/s²", 1.0),
}


# ====================================================================== tables of columns
Columns = List[Tuple[str, np.ndarray]]  # (header "name [unit]", values (N,))


def _unit(quantity: str, component: str) -> str:
    return BODY_CHANNELS[quantity][COMPONENTS.index(component)]


def _body_columns(run: SceneRun, which: str) -> Columns:
    """Columns of the selected body quantities, then of the tracked points' (``[outputs]
    points``): ``which`` = ``"result"``, ``"ideal"`` or ``"errors"`` (clearance − ideal,
    :func:`clearsim.export.error_columns`: the columns of ``Result.errors_table``)."""
    out = run.scene.outputs
    if which == "errors":
        names = list(out.bodies) + [p.name for p in out.points]
        keys = [(name, ERROR_QUANTITIES[q]) for name in names for q in out.quantities]
        ordered = {key: run.errors[key] for key in keys if key in run.errors}
        return [(column_name(name, unit), values) for name, unit, values in error_columns(ordered, out.components)]
    result = run.result if which == "result" else run.ideal
    assert result is not None
    cols: Columns = []
    for body in out.bodies:
        for quantity in out.quantities:
            data = getattr(result, quantity)(body)
            for component in out.components:
                c = COMPONENTS.index(component)
                cols.append((column_name(f"{body}.{quantity}.{component}", _unit(quantity, component)), data[:, c]))
    return cols + cli_readings.point_columns(result, out.points, out.quantities, out.components)


def _joint_columns(run: SceneRun) -> Columns:
    """Columns of the selected clearance-joint quantities (eccentricity also as ε = e/c), and the
    oil temperature [K] of every selected joint with a heat model (its only reading)."""
    result, out = run.result, run.scene.outputs
    clearance = _clearances(run.scene)
    getters = {
        "eccentricity_rate": result.eccentricity_rate,
        "force": result.joint_force,
        "contact_force": result.contact_force,
        "film_force": result.film_force,
        "film_thickness": lambda j: result.film_thickness(j)[:, None],
        "friction_torque": lambda j: np.column_stack([result.friction_torque(j), result.friction_torque(j, body="bearing")]),
        "power_loss": lambda j: result.power_loss(j)[:, None],
    }
    heated = {c["name"] for c in run.scene.mechanism.description()["clearance_joints"] if c["model"].get("thermal")}
    cols: Columns = []
    for joint in out.joints:
        for quantity in out.joint_quantities:
            if quantity == "eccentricity":
                e = result.eccentricity(joint)
                data = np.column_stack([e, np.hypot(e[:, 0], e[:, 1]) / clearance[joint]])
            elif quantity == "state":
                data = np.column_stack([result.contact_state(joint), result.dry_weight(joint)])
            else:
                data = getters[quantity](joint)
            for k, (name, unit) in enumerate(JOINT_CHANNELS[quantity]):
                cols.append((column_name(f"{joint}.{name}", unit), data[:, k]))  # ε, state: [1] (csvfile.DIMENSIONLESS)
        if joint in heated:
            cols.append((column_name(f"{joint}.temperature", "K"), result.temperature(joint)))
        cols += _film_columns(run, joint)
    return cols


def _film_columns(run: SceneRun, joint: str) -> Columns:
    """A lubricated joint's oil flow and peak pressure, when the run stored them (``[simulation]
    outputs = ["film"]``: :func:`clearsim.film_readings.film_columns`)."""
    return [(column_name(f"{joint}.{name}", unit), values) for name, unit, values in film_columns(run.result, joint)]


def _clearances(scene: Scene) -> Dict[str, float]:
    """Free travel of each clearance contact [m] (c, or half a guide's play)."""
    return {name: c["clearance"] for name, c in scene.mechanism.contacts().items()}


def write_csv(path: Path, t: np.ndarray, columns: Columns) -> Path:
    """A CSV file (:mod:`clearsim.csvfile`): ``t [s]`` and the columns, header row ``name [unit]``,
    over the samples every column has."""
    n = min([len(t)] + [len(v) for _, v in columns])
    return write_columns(path, [("t", "s", t[:n])] + [(name, None, np.asarray(v, dtype=float)[:n]) for name, v in columns])


# ====================================================================== figures
def _model_label(scene: Scene) -> str:
    """``dry``, ``lubricated`` or ``dry + lubricated``: picks the series style of clearsim.plots."""
    kinds = sorted({c["model"]["kind"] for c in scene.mechanism.description()["clearance_joints"]})
    return " + ".join(kinds) if kinds else "mechanism"


def _figures(run: SceneRun, out_dir: Path, step: _Steps) -> None:
    """PNG figures, each its own step: body histories (with the ideal response), errors,
    journal orbits (in units of the clearance) and FOSM reliability."""
    from matplotlib.figure import Figure

    from . import plots

    scene, result, out = run.scene, run.result, run.scene.outputs
    label = _model_label(scene)
    title = scene.name

    def history(body: str, component: str) -> Path:
        c = COMPONENTS.index(component)
        series = {label: result}
        if run.ideal is not None:
            series["ideal"] = run.ideal
        styles = plots.series_style(series)
        with plots.style():
            fig = Figure(figsize=(7.0, 2.3 * len(out.quantities) + 0.6), layout="constrained")
            axes = fig.subplots(len(out.quantities), 1, sharex=True, squeeze=False)[:, 0]
            for ax, quantity in zip(axes, out.quantities):
                for name, res in series.items():
                    st = styles[name]
                    ax.plot(res.t, getattr(res, quantity)(body)[:, c], color=st["color"], linestyle=st["linestyle"], label=name)
                ax.set_ylabel(f"{quantity.capitalize()} {component} [{_unit(quantity, component).replace('^2', '²')}]")
            axes[-1].set_xlabel("Time [s]")
            axes[0].legend(loc="lower center", bbox_to_anchor=(0.5, 1.01), ncol=len(series))
            plots.suptitle(fig, f"{title}: {body}")
        return plots.save(fig, out_dir / f"{body}_{component}.png")

    def error(body: str, component: str, errors: Dict[str, np.ndarray]) -> Path:
        n = len(next(iter(errors.values())))
        fig = plots.plot_error_histories(
            result.t[:n], {label: errors}, quantities=list(errors),
            quantity_info=_THETA_INFO if component == "theta" else None, title=f"{title}: {body} {component} error",
        )  # fmt: skip
        return plots.save(fig, out_dir / f"{body}_{component}_error.png")

    def orbits() -> Path:
        contacts = scene.mechanism.contacts()
        names = {j: f"{j} ({contacts[j]['kind']})" for j in out.joints}
        orbit = {names[j]: tuple(result.eccentricity(j).T) for j in out.joints}
        clearance = {names[j]: contacts[j]["clearance"] for j in out.joints}
        band = {names[j]: _transition_band(contacts[j]["entry"]) for j in out.joints if contacts[j]["kind"] == "lubricated"}
        fig = plots.plot_journal_orbits(orbit, clearance, transition_band=band or None, title=title)
        return plots.save(fig, out_dir / "orbits.png")

    def pressure(joint: str) -> Path:
        # The film at its peak pressure over the run.
        k = int(np.argmax(result.peak_pressure(joint)))
        fig = plots.plot_film_pressure(result.pressure(joint, float(result.t[k])), title=f"{title}: film pressure of '{joint}' at its peak")
        return plots.save(fig, out_dir / f"{joint}_pressure.png")

    def reliability() -> Path:
        spec = scene.reliability
        assert spec is not None
        # No title: plot_reliability_panels puts its legend where a suptitle would go.
        fig = plots.plot_reliability_panels({q: {f"{label}, {spec.body} {spec.component}": res} for q, res in run.reliability.items()})
        return plots.save(fig, out_dir / "reliability.png")

    for body in out.bodies:
        for component in out.components:
            step(f"{body}_{component}.png", lambda: history(body, component))
            c = COMPONENTS.index(component)
            errors = {ERROR_QUANTITIES[q]: run.errors[(body, ERROR_QUANTITIES[q])][:, c] for q in out.quantities if (body, ERROR_QUANTITIES[q]) in run.errors}
            if errors:
                step(f"{body}_{component}_error.png", lambda: error(body, component, errors))
    if out.joints and len(result.t):
        step("orbits.png", orbits)
    for joint in out.joints:
        # The picture solves the film from the stored state at its peak (needs "states").
        if _film_columns(run, joint) and "q" in result._raw:
            step(f"{joint}_pressure.png", lambda: pressure(joint))
    if run.reliability:
        step("reliability.png", reliability)
    if out.points and len(result.t):
        step("points.png", lambda: cli_readings.points_figure(result, out_dir / "points.png", title))
        for p in out.points:
            for component in cli_readings.point_components(out.components):
                c = ("x", "y").index(component)
                errors = {ERROR_QUANTITIES[q]: run.errors[(p.name, ERROR_QUANTITIES[q])][:, c] for q in out.quantities if (p.name, ERROR_QUANTITIES[q]) in run.errors}
                if errors:
                    step(f"{p.name}_{component}_error.png", lambda: error(p.name, component, errors))


def _transition_band(joint: Dict[str, Any]) -> float:
    """Width e0 [m] of a lubricated joint's film-to-contact band (default 5 % of c, docs/physics.md §4)."""
    e0 = joint["model"].get("e0")
    return 0.05 * float(joint["clearance"]) if e0 is None else float(e0)


# ====================================================================== summary
def _finite(value: Any) -> Any:
    """JSON-safe: non-finite floats → None, numpy scalars → Python numbers, recursively."""
    if isinstance(value, dict):
        return {str(k): _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def summarize(run: SceneRun) -> Dict[str, Any]:
    """Summary of a scene run: run statistics, impacts, maximum constraint violation, maximum
    |error| per body output, and the minimum FOSM reliability per quantity."""
    scene = run.scene
    out: Dict[str, Any] = {
        "scene": scene.name,
        "file": str(scene.path) if scene.path else None,
        "clearsim_version": __version__,
        "t0": scene.simulation.t0,  # the run covers [t0, t_end] s
        "t_end": scene.simulation.t_end,
        # The integrator that ran (the core resolves "auto" per mechanism), and what was asked.
        "integrator": str(run.result.stats.get("integrator", scene.simulation.integrator)),
        "integrator_setting": scene.simulation.integrator,
        "run": run.result.summary(),
    }
    if run.ideal is not None:
        out["ideal_run"] = run.ideal.summary()
    if run.errors:
        out["max_abs_error"] = {name: float(np.max(np.abs(values))) if len(values) else None for name, _, values in error_columns(run.errors, scene.outputs.components)}
    if run.reliability:
        spec = scene.reliability
        assert spec is not None
        out["reliability"] = {
            "body": spec.body,
            "component": spec.component,
            "bin_width_deg": spec.bin_width,
            "minimum": {
                q: {"reliability": r.min_reliability, "beta": r.min_beta, "angle_deg": r.min_angle, "allowable": list(spec.allowable[q])}
                for q, r in run.reliability.items()
            },
        }
    if run.reliability_failure:
        out["reliability_failure"] = run.reliability_failure
    return _finite(out)


def _window(summary: Dict[str, Any]) -> str:
    """The run's time window as summary.md states it: t_end alone for a run from 0."""
    t0 = summary.get("t0", 0.0)
    return f"t_end = {summary['t_end']:g} s" if not t0 else f"t0 = {t0:g} s, t_end = {summary['t_end']:g} s"


def _markdown(summary: Dict[str, Any], files: Sequence[Path]) -> str:
    run = summary["run"]
    lines = [
        f"# {summary['scene']}",
        "",
        f"Scene file `{summary['file']}`, clearsim {summary['clearsim_version']}, "
        f"integrator {summary['integrator']}{' (auto)' if summary.get('integrator_setting') == 'auto' else ''}, {_window(summary)}.",
        "",
        "| run | outputs | steps | rejected | min step [s] | wall time [s] | max ‖Φ‖ | impacts |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for label, key in (("clearance", "run"), ("ideal", "ideal_run")):
        r = summary.get(key)
        if r is None:
            continue
        impacts = ", ".join(f"{j}: {n}" for j, n in r.get("impacts", {}).items()) or "–"
        viol = r.get("max_constraint_violation")
        lines.append(
            f"| {label} | {r['outputs']} | {r['steps']} | {r['rejected_steps']} | {r['min_step']:.3g} | "
            f"{r['wall_time']:.3g} | {'–' if viol is None else f'{viol:.3g}'} | {impacts} |"
        )
    lines += summary_markdown(run.get("bearings"))
    lines += cli_readings.reaction_markdown(run.get("reactions"))
    if run.get("failure"):
        lines += ["", f"**The run stopped early:** {run['failure']}"]
    if "max_abs_error" in summary:
        lines += ["", "| output (clearance − ideal) | max abs error [SI] |", "|---|---|"]
        lines += [f"| {k} | {'–' if v is None else f'{v:.4g}'} |" for k, v in summary["max_abs_error"].items()]
    rel = summary.get("reliability")
    if rel:
        lines += [
            "",
            f"FOSM dynamic-accuracy reliability of {rel['body']} {rel['component']} ({rel['bin_width_deg']:g}° bins):",
            "",
            "| quantity | allowable | min R | β | at crank angle [deg] |",
            "|---|---|---|---|---|",
        ]
        for q, m in rel["minimum"].items():
            r_min = "–" if m["reliability"] is None else f"{m['reliability']:.6f}"
            beta = "–" if m["beta"] is None else f"{m['beta']:.3f}"
            lines.append(f"| {q} | [{m['allowable'][0]:g}, {m['allowable'][1]:g}] | {r_min} | {beta} | {m['angle_deg']:g} |")
    if summary.get("reliability_failure"):
        lines += ["", f"**[reliability]:** {summary['reliability_failure']}"]
    lines += ["", "Files: " + ", ".join(f"`{p.name}`" for p in files), ""]
    if summary.get("not_written"):
        lines += ["**Not written** (the run's other outputs are complete):", ""]
        lines += [f"- `{name}`: {why}" for name, why in summary["not_written"].items()] + [""]
    return "\n".join(lines)


def write_run(
    run: SceneRun, out_dir: Path, plots: bool = True, extra: Sequence[Tuple[str, Callable[[], Path]]] = ()
) -> List[Path]:
    """Write the CSV files, figures (if ``plots`` and the scene asks for them), the ``extra``
    outputs ((file name, writer) pairs, e.g. an animation) and the summaries of a scene run into
    ``out_dir``; returns the paths written.

    Each output is written on its own: if one fails, the others and the summaries (which name
    the failed ones) are still written, then :class:`OutputsFailed` is raised."""
    out_dir.mkdir(parents=True, exist_ok=True)
    scene, result = run.scene, run.result
    step = _Steps()
    if scene.outputs.csv:
        if scene.outputs.bodies or scene.outputs.points:
            step("bodies.csv", lambda: write_csv(out_dir / "bodies.csv", result.t, _body_columns(run, "result")))
            if run.ideal is not None:
                ideal = run.ideal
                step("bodies_ideal.csv", lambda: write_csv(out_dir / "bodies_ideal.csv", ideal.t, _body_columns(run, "ideal")))
            step("errors.csv", lambda: _errors_csv(run, out_dir))
        if scene.outputs.joints:
            step("joints.csv", lambda: write_csv(out_dir / "joints.csv", result.t, _joint_columns(run)))
        reactions = cli_readings.reaction_table(result)
        if reactions:
            step("reactions.csv", lambda: write_csv(out_dir / "reactions.csv", result.t, reactions))
        for quantity, fosm in run.reliability.items():
            step(f"reliability_{quantity}.csv", lambda: _fosm_csv(out_dir / f"reliability_{quantity}.csv", fosm, _fosm_unit(scene, quantity)))
    if plots and scene.outputs.plots:
        _figures(run, out_dir, step)
    for what, write in extra:
        step(what, write)
    summary = summarize(run)
    files = step.files + [out_dir / "summary.json", out_dir / "summary.md"]
    summary["files"] = [p.name for p in files]
    if step.failed:
        summary["not_written"] = {what: _describe(err) for what, err in step.failed}
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    (out_dir / "summary.md").write_text(_markdown(summary, files), encoding="utf-8")
    if step.failed:
        (what, err), more = step.failed[0], [w for w, _ in step.failed[1:]]
        also = f" (and {len(more)} more: {', '.join(more)})" if more else ""
        message = f"writing {what} failed: {_describe(err)}{also}; summary.md in {out_dir} lists what was written"
        raise OutputsFailed(message, step.failed, files)
    return files


def _errors_csv(run: SceneRun, out_dir: Path) -> List[Path]:
    errors = _body_columns(run, "errors")
    return [write_csv(out_dir / "errors.csv", run.result.t, errors)] if errors else []


def _fosm_unit(scene: Scene, quantity: str) -> str:
    """The unit of the error FOSM analyses: ``quantity``'s (displacement, ...) of ``[reliability]``'s component."""
    assert scene.reliability is not None
    return body_unit(quantity, scene.reliability.component)


def _fosm_csv(path: Path, fosm: Any, unit: str) -> Path:
    """``FosmResult.to_rows()`` under the headers of every FOSM table (``bin_start [deg]``,
    ``mu_s [m]``, ...: :func:`clearsim.csvfile.report_header`)."""
    rows = fosm.to_rows()
    return write_rows(path, report_header(rows[0], unit), [list(r.values()) for r in rows])


# ====================================================================== commands
#: ``clearsim run --animate`` without ``--speed``: frames per crank turn (one per 15°), the
#: fewest and most frames, and the frame rate [1/s]; without a crank period, real time.
FRAMES_PER_CYCLE, MIN_FRAMES, MAX_FRAMES, ANIMATION_FPS = 24, 50, 400, 25


def animation_frames(span: float, period: Optional[float]) -> int:
    """Frames of an animation of a run ``span`` [s] long: :data:`FRAMES_PER_CYCLE` a crank turn
    of ``period`` [s], else real time at :data:`ANIMATION_FPS`, within [MIN_FRAMES, MAX_FRAMES]."""
    wanted = span / period * FRAMES_PER_CYCLE if period else span * ANIMATION_FPS
    return int(min(MAX_FRAMES, max(MIN_FRAMES, math.ceil(wanted - 1e-9))))


def _crank_period(scene: Scene) -> Optional[float]:
    """The crank turn [s]: ``[simulation].period``, else 2π/|ω| of the first constant-speed driver (by name)."""
    if scene.simulation.period:
        return float(scene.simulation.period)
    speeds = [float(d["law"]["omega"]) for d in scene.mechanism.description()["drivers"] if d["law"]["kind"] == "constant_speed"]
    return 2 * math.pi / abs(speeds[0]) if speeds and speeds[0] != 0 else None


def _cmd_run(args: argparse.Namespace) -> int:
    scene = load_scene_file(args.scene).with_overrides(t_end=args.t_end, integrator=args.integrator)
    out_dir = Path(args.output) if args.output else Path(f"clearsim-{Path(args.scene).stem}")
    run = scene.run(progress=not args.quiet)
    extra: List[Tuple[str, Callable[[], Path]]] = []
    if args.animate:
        span = float(run.result.t[-1] - run.result.t[0]) if len(run.result.t) else 1.0
        frames = animation_frames(span, _crank_period(scene))
        speed = args.speed or max(span, 1e-9) * ANIMATION_FPS / frames
        extra.append((Path(args.animate).name, lambda: run.result.animate(args.animate, speed=speed, magnify=args.magnify, fps=ANIMATION_FPS, max_frames=frames if not args.speed else 400)))
    failed: Optional[OutputsFailed] = None
    try:
        files = write_run(run, out_dir, plots=not args.no_plots, extra=extra)
    except OutputsFailed as err:
        failed, files = err, err.files
    if not args.quiet:
        r = run.result.summary()
        print(f"{scene.name}: {r['outputs']} outputs to t = {r['t_reached']:g} s in {r['steps']} steps ({r['wall_time']:.3g} s)")
        if run.result.impacts:
            print("impacts: " + ", ".join(f"{j} {n}" for j, n in run.result.impacts.items()))
        for joint, b in r.get("bearings", {}).items():
            extra_b = (f", λ = {b['lambda']:.3g}" if "lambda" in b else "") + (f", oil {b['temperature_start']:.5g} → {b['temperature_end']:.5g} K" if "temperature_end" in b else "")
            if "min_film_crank_angle_deg" in b:
                extra_b = f" at {b['min_film_crank_angle_deg']:.1f}°" + extra_b
            if "peak_pressure" in b:  # the film output was asked for: its peak and flows too
                extra_b += f", peak pressure {b['peak_pressure'] * 1e-6:.4g} MPa, side leakage {b['mean_side_leakage'] * 1e6:.4g} cm³/s (supply {b['mean_supply_flow'] * 1e6:.4g})"
            print(f"bearing {joint}: min film {b['min_film_thickness'] * 1e6:.4g} µm{extra_b}, mean power loss {b['mean_power_loss']:.4g} W (t = {b['window_start']:.6g} to {b['window_end']:.6g} s)")
        for text in cli_readings.reaction_text(r.get("reactions", {})):
            print(text)
        for q, res in run.reliability.items():
            print(f"FOSM {q}: min R = {res.min_reliability:.6f} (β = {res.min_beta:.3f}) at {res.min_angle:g}°")
        if run.reliability_failure:
            print(f"[reliability]: {run.reliability_failure}")
        print(f"wrote {len(files)} files to {out_dir}")
    if run.failure is not None:
        t_reached = run.result.stats.get("t_reached", float("nan"))
        print(f"clearsim: simulation failed: {_describe(run.failure)}; partial results (to t = {t_reached:g} s) written to {out_dir}", file=sys.stderr)
        return EXIT_ERROR
    if failed is not None:
        raise failed
    return 0


def _cmd_reliability(args: argparse.Namespace) -> int:
    from .reliability.report import run_study

    scene = load_scene_file(args.scene)
    if scene.study is None and scene.reliability is None:  # [reliability] alone: its FOSM, the study it stands for
        print(f"clearsim: error: {args.scene} has no [study] table (random inputs, output and limit) nor [reliability] (python -m pydoc clearsim.scene)", file=sys.stderr)
        return EXIT_ERROR
    out_dir = Path(args.output) if args.output else Path(f"clearsim-{Path(args.scene).stem}-reliability")
    methods = args.methods.split(",") if args.methods else None
    echo = (lambda *a, **k: None) if args.quiet else print
    with _summary_on_failure(out_dir, "clearsim reliability", "report.md"):
        files = run_study(scene, out_dir, methods=methods, samples=args.samples, progress=not args.quiet, plots=not args.no_plots, echo=echo, reference=args.reference)
    echo(f"wrote {len(files)} files to {out_dir}")
    return 0


def _cmd_paper(args: argparse.Namespace) -> int:
    try:
        from .paper import run_paper_study
    except ImportError as err:
        if not (err.name or "").startswith("clearsim.paper"):
            raise
        print("clearsim: error: the paper study (clearsim.paper) is not available in this installation", file=sys.stderr)
        return EXIT_ERROR
    with _summary_on_failure(Path(args.output), "clearsim paper", "report.md"):
        out = run_paper_study(Path(args.output), cycles=args.cycles, quick=args.quick, progress=not args.quiet, film=args.film, compare_films=not args.no_film_comparison)
    if not args.quiet:
        print(f"paper study written to {out}")
    return 0


def _first_line(obj: Any) -> str:
    """The docstring's first paragraph as plain text (reST ``literals`` and :role:`x` unwrapped)."""
    import re

    text = " ".join((obj.__doc__ or "").strip().split("\n\n")[0].split())
    text = re.sub(r":[a-z]+:`~?([^`]+)`", r"\1", text)
    return text.replace("``", "")


def _cmd_info(args: argparse.Namespace) -> int:
    from .joints import FILM_MODELS, NORMAL_LAWS

    print(f"clearsim {__version__}: planar mechanisms with dry and lubricated revolute clearance joints")
    print("\nModels (clearsim.models):")
    for name in models.__all__:
        obj = getattr(models, name)
        if callable(obj):
            print(f"  {name:14s} {_first_line(obj)}")
    print(f"\nIntegrators: {', '.join(INTEGRATORS)}")
    print(f"Dry contact laws: {', '.join(NORMAL_LAWS)}")
    print(f"Lubricated film models: {', '.join(FILM_MODELS)}")
    scenes = Path(__file__).resolve().parents[2] / "scenes"  # a source checkout
    if scenes.is_dir():
        print(f"\nScenes ({scenes}):")
        for path in sorted(scenes.glob("*.toml")):
            print(f"  {path.name}")
    print("\nScene file format: python -m pydoc clearsim.scene")
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``clearsim`` command."""
    parser = argparse.ArgumentParser(
        prog="clearsim", description="Planar mechanisms with dry and lubricated revolute clearance joints."
    )
    parser.add_argument("--version", action="version", version=f"clearsim {__version__}")
    parser.add_argument("--debug", action="store_true", help="print the traceback of a failure")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    run = sub.add_parser("run", help="run a scene file: CSV, figures and a summary", description="Run a scene file (TOML).")
    run.add_argument("scene", metavar="SCENE.toml", help="scene file (format: python -m pydoc clearsim.scene)")
    run.add_argument("-o", "--output", metavar="OUTDIR", help="output directory (default clearsim-<scene>)")
    run.add_argument("--no-plots", action="store_true", help="write no figures")
    run.add_argument("--t-end", type=_positive_float, metavar="T", help="end time [s] instead of the scene's")
    run.add_argument("--integrator", choices=INTEGRATORS, help="integrator instead of the scene's")
    run.add_argument("--animate", metavar="FILE", help="also animate the run into FILE (.gif, or .mp4 with ffmpeg)")
    run.add_argument(
        "--speed", type=_positive_float, default=None, metavar="S",
        help=f"animation speed × real time (default: {FRAMES_PER_CYCLE} frames a crank turn, or real time without a constant-speed "
        f"driver, at {ANIMATION_FPS} frames/s, {MIN_FRAMES} to {MAX_FRAMES} frames)",
    )  # fmt: skip
    run.add_argument("--magnify", type=_positive_float, metavar="M", help="clearance magnification in pictures (default: automatic)")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress bar, no summary on stdout")
    run.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="print the traceback of a failure")
    run.set_defaults(func=_cmd_run)

    rel = sub.add_parser(
        "reliability", help="reliability of a scene's [study]: Monte Carlo, FORM, importance sampling, subset, AK-MCS/AK-IS, Sobol, life",
        description="Run the [study] of a scene file (random inputs; one output and its limit, or several as a series "
        "system): p_f by each method, Sobol indices, tolerance design, p_f over life ([study.life]); writes CSV tables, "
        "reliability.png and report.md.",
    )  # fmt: skip
    rel.add_argument("scene", metavar="SCENE.toml", help="scene file with a [study] table, or [reliability] (its short form: FOSM) (format: python -m pydoc clearsim.scene)")
    rel.add_argument("-o", "--output", metavar="OUTDIR", help="output directory (default clearsim-<scene>-reliability)")
    rel.add_argument("--methods", metavar="LIST", help="comma-separated, instead of the scene's: monte_carlo,form,importance_sampling,subset,sobol,fosm,ak_mcs,ak_is")
    rel.add_argument("--samples", type=_positive_int, metavar="N", help="Monte Carlo samples / subset runs per level / Sobol base size instead of the scene's")
    rel.add_argument(
        "--reference", choices=REFERENCES, help="what body and point errors are measured against, instead of the scene's [study] reference: "
        "own_ideal (each sample's ideal twin: what the clearances add) or nominal (the nominal design's ideal motion: every tolerance counts)",
    )  # fmt: skip
    rel.add_argument("--no-plots", action="store_true", help="write no figure")
    rel.add_argument("-q", "--quiet", action="store_true", help="no progress bars, nothing on stdout")
    rel.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="print the traceback of a failure")
    rel.set_defaults(func=_cmd_reliability)

    paper = sub.add_parser("paper", help="reproduce the paper's study", description="Reproduce the paper's study (docs/physics.md §7).")
    paper.add_argument("-o", "--output", metavar="OUTDIR", default="clearsim-paper", help="output directory (default clearsim-paper)")
    paper.add_argument("--quick", action="store_true", help="coarser, faster runs (a smoke test)")
    paper.add_argument("--cycles", type=_positive_int, default=3, metavar="N", help="crank cycles per run (default 3)")
    paper.add_argument("--film", choices=("long", "short", "finite", "long_paper"), default="long", help="film model of the lubricated joints (default long)")
    paper.add_argument("--no-film-comparison", action="store_true", help="skip the runs comparing the film models")
    paper.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    paper.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="print the traceback of a failure")
    paper.set_defaults(func=_cmd_paper)

    add_sweep_parser(sub)

    info = sub.add_parser("info", help="version and model catalogue", description="Print the version and the model catalogue.")
    info.set_defaults(func=_cmd_info)
    return parser


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``clearsim`` command; returns the exit code (0; 2 on a clearsim error;
    1 on any other failure). A failure is one line on stderr; ``--debug`` adds the traceback."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return EXIT_ERROR
    debug = bool(getattr(args, "debug", False))
    with _warnings_as_lines():
        try:
            return int(args.func(args))
        except ClearsimError as err:
            if debug:
                traceback.print_exc()
            print(f"clearsim: error: {err}", file=sys.stderr)
            return EXIT_ERROR
        except KeyboardInterrupt:
            print("clearsim: interrupted", file=sys.stderr)
            return 130
        except Exception as err:  # noqa: BLE001 — a bug: one line, the traceback with --debug
            if debug:
                traceback.print_exc()
            cause = str(err) if isinstance(err, OutputsFailed) else _describe(err)
            print(f"clearsim: error: {cause}{'' if debug else ' (--debug prints the traceback)'}", file=sys.stderr)
            return EXIT_FAILURE


@contextlib.contextmanager
def _warnings_as_lines() -> Iterator[None]:
    """Warnings printed as ``clearsim: warning: <message>``, without the source line."""
    def show(message: Any, category: Any, filename: str, lineno: int, file: Any = None, line: Optional[str] = None) -> None:
        print(f"clearsim: warning: {message}", file=sys.stderr)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


__all__ = ["EXIT_ERROR", "EXIT_FAILURE", "OutputsFailed", "build_parser", "main", "summarize", "write_csv", "write_run"]


if __name__ == "__main__":
    raise SystemExit(main())
