"""What ``clearsim run`` writes of a scene's tracked points and of its joints' reactions: the
point columns of ``bodies.csv`` / ``bodies_ideal.csv``, the columns of ``reactions.csv``, the
peak joint forces and driver torques of ``summary.md`` and stdout, and ``points.png`` (the
mechanism with each point's path). :mod:`clearsim.cli` calls these."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .csvfile import column_name
from .export import reaction_columns
from .points import POINT_COMPONENTS
from .result import Result
from .schema import BODY_QUANTITY_UNITS

Columns = List[Tuple[str, np.ndarray]]  # (header "name [unit]", values (N,)), as clearsim.cli's
#: ``[outputs] quantities`` (channel names) → the quantity of a point's motion.
_QUANTITY_OF = {"position": "displacement", "velocity": "velocity", "acceleration": "acceleration"}


def point_components(components: Sequence[str]) -> List[str]:
    """The components of a point's motion written for ``[outputs] components``: its x and y
    among them, both if neither is asked for (a point has no angle)."""
    return [c for c in POINT_COMPONENTS if c in components] or list(POINT_COMPONENTS)


def point_columns(result: Result, points: Sequence[Any], quantities: Sequence[str], components: Sequence[str]) -> Columns:
    """``<point>.<quantity>.<x|y> [unit]`` of each tracked point (named as the bodies' columns
    of the same file: ``tool.position.x [m]``, ``tool.velocity.y [m/s]``)."""
    cols: Columns = []
    for p in points:
        for quantity in quantities:
            values = result.point(p.body, p.point, _QUANTITY_OF[quantity])
            unit = BODY_QUANTITY_UNITS[_QUANTITY_OF[quantity]][0]
            for c in point_components(components):
                cols.append((column_name(f"{p.name}.{quantity}.{c}", unit), values[:, POINT_COMPONENTS.index(c)]))
    return cols


def reaction_table(result: Result) -> Columns:
    """The columns of ``reactions.csv``: each ideal joint's ``fx``, ``fy`` [N] on its second body
    (a prismatic joint also its ``torque`` [N m]) and each driver's ``torque`` [N m]
    (:func:`clearsim.export.reaction_columns`)."""
    return [(column_name(name, unit), values) for name, unit, values in reaction_columns(result)]


def _num(v: Any, fmt: str = ".4g") -> str:
    return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(float(v), fmt)


def reaction_markdown(reactions: Optional[Dict[str, Dict[str, Any]]]) -> List[str]:
    """Lines of the table of peak joint forces and driver torques (``Result.reaction_summary``):
    tracked at every integration step, or (a row marked so) over the stored outputs."""
    if not reactions:
        return []
    starts = sorted({r["window_start"] for r in reactions.values() if r.get("tracked") and "window_start" in r})
    over = "tracked at every integration step" + (f" from t = {starts[0]:.6g} s" if starts and starts[0] else "")
    if not all(r.get("tracked") for r in reactions.values()):
        over += "; rows marked *stored outputs* over the stored outputs only"
    lines = [
        "",
        f"Peak joint forces (on each joint's second body) and driver torques, {over}:",
        "",
        "| joint or driver | peak force [N] | at t [s] | peak torque [N m] | at t [s] |",
        "|---|---|---|---|---|",
    ]
    for name, r in reactions.items():
        mark = "" if r.get("tracked") else " *stored outputs*"
        lines.append(f"| {name} ({r.get('kind', '?')}){mark} | {_num(r.get('peak_force'))} | {_num(r.get('t_peak_force'), '.6g')} | {_num(r.get('peak_torque'))} | {_num(r.get('t_peak_torque'), '.6g')} |")
    return lines


def reaction_text(reactions: Dict[str, Dict[str, Any]]) -> List[str]:
    """stdout lines of ``clearsim run``: the peak force of each joint and torque of each driver."""
    forces = [f"{name} {r['peak_force']:.4g} N" for name, r in reactions.items() if r.get("peak_force") is not None and math.isfinite(r["peak_force"])]
    torques = [f"{name} {r['peak_torque']:.4g} N m" for name, r in reactions.items() if r.get("kind") == "driver" and r.get("peak_torque") is not None]
    out = []
    if forces:
        out.append("peak joint force: " + ", ".join(forces))
    if torques:
        out.append("peak driver torque: " + ", ".join(torques))
    return out


def points_figure(result: Result, path: Path, title: str, magnify: Optional[float] = None) -> Path:
    """``points.png``: the mechanism at the run's first output with each tracked point marked and
    its path over the run traced."""
    from . import plots

    fig = result.plot_mechanism(float(result.t[0]), magnify=magnify, trace=True)
    text = f"{title}: paths of {', '.join(p.name for p in result.tracked_points)} over t ∈ [{result.t[0]:.4g}, {result.t[-1]:.4g}] s"
    # On as many lines as fit above the axes (~0.6 em a character at 9 pt, the axes ~70 % of the
    # figure): one line cut a long scene name off at both edges.
    chars = max(16, int(0.7 * fig.get_figwidth() * 72.0 / (0.6 * 9)))
    fig.axes[0].set_title(textwrap.fill(text, chars), fontsize=9)
    return plots.save(fig, path)


__all__ = ["point_columns", "point_components", "points_figure", "reaction_markdown", "reaction_table", "reaction_text"]
