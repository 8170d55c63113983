"""Benchmark figures: work–precision diagrams (error against cost, one line an integrator)."""

from __future__ import annotations

import math
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple

import matplotlib as mpl
from matplotlib.figure import Figure

from ..errors import InputError
from .theme import OKABE_ITO, legend_above, new_figure, style, suptitle


# ====================================================================== work–precision
def plot_work_precision(
    rows: Iterable[Mapping[str, Any]],
    x: str = "wall_time",
    y: str = "error",
    group: str = "method",
    annotate: Optional[str] = None,
    x_label: str = "Wall time",
    x_unit: str = "s",
    y_label: str = "Error",
    y_unit: str = "m",
    title: Optional[str] = None,
) -> Figure:
    """Work–precision diagram: error against cost on log–log axes, one line per method.

    Parameters
    ----------
    rows:
        Records (e.g. benchmark CSV rows) with keys ``x`` (cost, default ``"wall_time"`` [s]),
        ``y`` (error, default ``"error"``) and ``group`` (line label, default ``"method"``).
        Rows with a non-positive or non-finite value are skipped (they cannot be shown on log axes).
    annotate:
        Key whose value is written next to each point (e.g. ``"rtol"``).
    x_label, x_unit, y_label, y_unit:
        Axis names and units (the units appear in brackets).
    """
    groups: Dict[str, List[Tuple[float, float, Any]]] = {}
    for i, row in enumerate(rows):
        for key in (x, y, group):
            if key not in row:
                raise InputError(f"invalid rows[{i}]: missing key {key!r}", field=f"rows[{i}].{key}", value=None)
        try:
            xv, yv = float(row[x]), float(row[y])
        except (TypeError, ValueError):
            raise InputError(f"invalid rows[{i}]: {x!r} and {y!r} must be numbers", field=f"rows[{i}]", value=(row[x], row[y])) from None
        if not (xv > 0 and yv > 0 and math.isfinite(xv) and math.isfinite(yv)):
            continue
        groups.setdefault(str(row[group]), []).append((xv, yv, row.get(annotate) if annotate else None))
    if not groups:
        raise InputError("invalid rows: no row with positive finite values to plot", field="rows", value=None)
    palette = [OKABE_ITO[c] for c in ("blue", "vermillion", "bluish_green", "orange", "reddish_purple", "sky_blue", "black")]
    markers = ["o", "s", "^", "D", "v", "P", "X"]
    with style():
        fig = new_figure(6.0, 4.4)
        ax = fig.subplots()
        for k, (name, pts) in enumerate(groups.items()):
            pts.sort(key=lambda p: p[0])
            xs = [p[0] for p in pts]
            ys = [p[1] for p in pts]
            ax.plot(xs, ys, marker=markers[k % len(markers)], color=palette[k % len(palette)], label=name)
            if annotate:
                for xv, yv, tag in pts:
                    if tag is not None:
                        ax.annotate(f"{tag:g}" if isinstance(tag, (int, float)) else str(tag), (xv, yv), xytext=(4, 3), textcoords="offset points", fontsize=7, color=palette[k % len(palette)])
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis, values in ((ax.xaxis, [p[0] for pts in groups.values() for p in pts]), (ax.yaxis, [p[1] for pts in groups.values() for p in pts])):
            if math.log10(max(values) / min(values)) < 2.0:  # few decades: label 1-2-5 plainly
                axis.set_major_formatter(mpl.ticker.FuncFormatter(_log_label))
                axis.set_minor_formatter(mpl.ticker.FuncFormatter(_log_label))
        ax.grid(True, which="minor", alpha=0.15)
        ax.set_xlabel(f"{x_label} [{x_unit}]")
        ax.set_ylabel(f"{y_label} [{y_unit}]")
        legend_above(ax, ncol=min(len(groups), 4))
        if title:
            suptitle(fig, title)
    return fig


def _log_label(value: float, _pos: Any = None) -> str:
    """``%g`` label for log-axis ticks whose mantissa is 1, 2 or 5, else none."""
    if value <= 0:
        return ""
    mant = value / 10.0 ** math.floor(math.log10(value) + 1e-9)
    return f"{value:g}" if any(abs(mant - m) < 1e-6 for m in (1.0, 2.0, 5.0)) else ""

