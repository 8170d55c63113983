"""``clearsim sweep SCENE.toml``: the bifurcation diagram of a scene's ``[sweep]`` table
(:mod:`clearsim.scene.sweep`, :func:`clearsim.dynamics.bifurcation`), written as CSV
(``bifurcation_points.csv``, ``bifurcation_kinds.csv``), PNG (``bifurcation.png``,
``poincare.png``: the sections of a periodic and a chaotic value when there are) and a short
``report.md``."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from .cli_support import EXIT_ERROR, _positive_int, _summary_on_failure
from .points import point_component, point_name
from .scene import load_scene_file
from .scene.loader import Scene


def _run_options(scene: Scene) -> Dict[str, Any]:
    """The ``[simulation]`` settings a sweep's runs use: the integrator and its tolerances."""
    kw = scene.simulation.kwargs()
    return {k: kw[k] for k in ("integrator", "rtol", "atol", "h_max", "h_min", "max_steps", "step") if k in kw}


def _poincare_figure(b: Any, out_dir: Path, output: Sequence[str]) -> Optional[Path]:
    """The sections of one periodic and one chaotic value (the first of each), in the plane of
    the output and its body's velocity (a point's: its own; a joint's: e_x, e_y); ``output`` is
    the sweep's ``(body, quantity, component)`` or ``(joint, quantity)``."""
    from .plots import save
    from .plots.dynamics import plot_poincare_panels

    picks = []
    for want in ("period-", "chaotic"):
        i = next((i for i, k in enumerate(b.kind) if k.startswith(want) and b.sections[i] is not None), None)
        if i is not None:
            picks.append(i)
    if not picks:
        return None
    name = output[0]
    panels = []
    for i in picks:
        sec = b.sections[i]
        if name in sec.joint_names:
            c = next(float(j["clearance"]) for j in sec.description["clearance_joints"] if j["name"] == name)
            e = sec.eccentricity(name) / c
            x, y, xl, yl = e[:, 0], e[:, 1], f"{name} e_x / c", f"{name} e_y / c"
        elif b.point is not None:
            comp, label = output[2], point_name(name, b.point)
            x, y = (point_component(sec.point(name, b.point, q), comp) for q in ("displacement", "velocity"))
            xl, yl = f"{label} displacement.{comp} [m]", f"{label} velocity.{comp} [m/s]"
        else:
            comp = output[2]
            k = ("x", "y", "theta").index(comp)
            x, y = sec.position(name)[:, k], sec.velocity(name)[:, k]
            xl, yl = f"{name}.{comp} [{'rad' if comp == 'theta' else 'm'}]", f"{name}.{comp} rate [{'rad/s' if comp == 'theta' else 'm/s'}]"
        panels.append((x, y, f"{b.parameter} = {b.values[i]:.6g}: {b.kind[i]}"))
    fig = plot_poincare_panels(panels, xl, yl, title="Poincaré sections", circle=1.0 if name in b.sections[picks[0]].joint_names else None)
    return save(fig, out_dir / "poincare.png")


def _report(b: Any, scene: Scene, unit: str, files: List[Path], seconds: float) -> str:
    counts = b.counts()
    unit = f" {unit}" if unit else ""
    lines = [f"# Bifurcation diagram: {scene.name}", ""]
    lines.append(f"{len(b.values)} values of `{b.parameter}` from {b.values.min():.6g} to {b.values.max():.6g}{unit}, "
                 f"{b.transient_cycles} transient + {b.cycles} analysed forcing periods each; output `{b.output}` [{b.unit}]; "
                 f"{seconds:.1f} s wall time.")  # fmt: skip
    lines += ["", "| kind | values |", "|---|---|"] + [f"| {k} | {n} |" for k, n in sorted(counts.items())]
    ranges = []
    start = 0
    for i in range(1, len(b.values) + 1):
        if i == len(b.values) or b.kind[i] != b.kind[start]:
            lo, hi = b.values[start], b.values[i - 1]
            ranges.append(f"- {lo:.6g} … {hi:.6g}{unit}: {b.kind[start]}" if i - 1 > start else f"- {lo:.6g}{unit}: {b.kind[start]}")
            start = i
    lines += ["", "Kinds along the parameter:", ""] + ranges
    if b.failures:
        lines += ["", f"{len(b.failures)} runs stopped early (their points up to there are kept):", ""]
        lines += [f"- {v:.6g}: {why}" for v, why in b.failures]
    ok = np.isfinite(b.exponent)
    if np.any(ok):
        k = int(np.nanargmax(b.exponent))
        lines += ["", f"Largest Lyapunov exponent computed for {int(ok.sum())} values; the largest {b.exponent[k]:.4g} 1/s at {b.values[k]:.6g}{unit}."]
    lines += ["", "How each kind is decided: docs/physics.md §13 (sections repeating within a tolerance of each feature's range; "
              "the largest Lyapunov exponent where they do not).", "", "Files: " + ", ".join(f"`{p.name}`" for p in files)]  # fmt: skip
    return "\n".join(lines) + "\n"


def run_sweep(scene: Scene, out_dir: Path, *, count: Optional[int] = None, cycles: Optional[int] = None, transient_cycles: Optional[int] = None,
              progress: bool = True, plots: bool = True) -> List[Path]:  # fmt: skip
    """Run ``scene``'s ``[sweep]`` and write its files into ``out_dir``; ``count``, ``cycles``,
    ``transient_cycles`` replace the table's (``count``: that many values evenly over its range)."""
    import time

    from .dynamics import bifurcation

    sw = scene.sweep
    assert sw is not None
    values = np.asarray(sw.values, dtype=float)
    if count is not None:
        values = values if count == len(values) else np.linspace(values.min(), values.max(), count)
    out_dir.mkdir(parents=True, exist_ok=True)
    t = time.perf_counter()
    b = bifurcation(
        scene.mechanism, values, sw.parameter, transient_cycles=sw.transient_cycles if transient_cycles is None else transient_cycles,
        cycles=sw.cycles if cycles is None else cycles, output=sw.output, point=sw.point, period=sw.period, phase=sw.phase, lyapunov=sw.lyapunov,
        tol=sw.tol, progress=progress, **_run_options(scene),
    )  # fmt: skip
    seconds = time.perf_counter() - t
    files = b.to_csv(out_dir, unit=sw.unit)
    if plots:
        from .plots import save

        files.append(save(b.plot(parameter_label=f"{sw.label or sw.parameter} [{sw.unit}]" if sw.unit else (sw.label or sw.parameter), title=scene.name), out_dir / "bifurcation.png"))
        poincare = _poincare_figure(b, out_dir, sw.output)
        if poincare is not None:
            files.append(poincare)
    report = out_dir / "report.md"
    report.write_text(_report(b, scene, sw.unit, files, seconds), encoding="utf-8")
    return files + [report]


def _cmd_sweep(args: argparse.Namespace) -> int:
    scene = load_scene_file(args.scene)
    if scene.sweep is None:
        print(f"clearsim: error: {args.scene} has no [sweep] table (python -m pydoc clearsim.scene.sweep)", file=sys.stderr)
        return EXIT_ERROR
    out_dir = Path(args.output) if args.output else Path(f"clearsim-{Path(args.scene).stem}-sweep")
    with _summary_on_failure(out_dir, "clearsim sweep", "report.md"):
        files = run_sweep(scene, out_dir, count=args.count, cycles=args.cycles, transient_cycles=args.transient_cycles,
                          progress=not args.quiet, plots=not args.no_plots)  # fmt: skip
    if not args.quiet:
        print((out_dir / "report.md").read_text(encoding="utf-8"))
        print(f"wrote {len(files)} files to {out_dir}")
    return 0


def add_sweep_parser(sub: Any) -> None:
    """The ``sweep`` subcommand on the ``clearsim`` parser's subparsers ``sub``."""
    p = sub.add_parser(
        "sweep", help="a bifurcation diagram over a scene's [sweep] parameter: CSV, PNG and a report",
        description="Run the [sweep] of a scene file: one run per value of a mechanism field, its Poincaré sections after a "
        "transient, period-k / quasi-periodic / chaotic per value (docs/physics.md §13); writes bifurcation_points.csv, "
        "bifurcation_kinds.csv, bifurcation.png, poincare.png and report.md.",
    )  # fmt: skip
    p.add_argument("scene", metavar="SCENE.toml", help="scene file with a [sweep] table (format: python -m pydoc clearsim.scene.sweep)")
    p.add_argument("-o", "--output", metavar="OUTDIR", help="output directory (default clearsim-<scene>-sweep)")
    p.add_argument("--count", type=_positive_int, metavar="N", help="N values evenly over the table's range instead of its values")
    p.add_argument("--cycles", type=_positive_int, metavar="N", help="analysed forcing periods instead of the table's")
    p.add_argument("--transient-cycles", type=int, metavar="N", help="transient forcing periods instead of the table's")
    p.add_argument("--no-plots", action="store_true", help="write no figures")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar, nothing on stdout")
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="print the traceback of a failure")
    p.set_defaults(func=_cmd_sweep)


__all__ = ["add_sweep_parser", "run_sweep"]
