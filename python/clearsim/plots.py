"""Report figures: error histories, journal orbits, reliability curves, FOSM vs Monte Carlo,
work–precision diagrams.

Every function takes plain numpy arrays and labels (no simulation objects), returns a
:class:`matplotlib.figure.Figure` and leaves no pyplot state behind: figures are built with
``Figure(...)`` directly, so nothing is registered with pyplot and nothing needs closing unless
you created it through pyplot yourself. Save with :func:`save` (PNG, 150 dpi).

Style (:func:`style`, :data:`RC`): report-sized fonts, light grid, units on every axis label,
legends above the axes (outside the data), constrained layout, and the Okabe–Ito colour-blind-safe
palette. Series are styled by the kind their label names (:func:`series_style`): *dry* →
vermillion/purple/orange solid lines, *lubricated* → blue/green/sky-blue dashed, *ideal* → black
dotted, anything else → the remaining palette colours, so a figure set stays consistent.
"""

from __future__ import annotations

import contextlib
import math
import textwrap
from pathlib import Path
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, Union, cast

import matplotlib as mpl
import numpy as np
from cycler import cycler
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle

from .errors import InputError

__all__ = [
    "OKABE_ITO",
    "QUANTITIES",
    "RC",
    "plot_error_histories",
    "plot_fosm_vs_mc",
    "plot_journal_orbits",
    "plot_reliability",
    "plot_reliability_panels",
    "plot_work_precision",
    "save",
    "series_style",
    "style",
    "suptitle",
]

#: Okabe & Ito (2008) colour-blind-safe palette.
OKABE_ITO: Dict[str, str] = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky_blue": "#56B4E9",
    "bluish_green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "reddish_purple": "#CC79A7",
}

_KIND_COLOURS: Dict[str, List[str]] = {
    "dry": [OKABE_ITO["vermillion"], OKABE_ITO["reddish_purple"], OKABE_ITO["orange"]],
    "lubricated": [OKABE_ITO["blue"], OKABE_ITO["bluish_green"], OKABE_ITO["sky_blue"]],
    "ideal": [OKABE_ITO["black"], "#666666"],
    "other": [OKABE_ITO["bluish_green"], OKABE_ITO["orange"], OKABE_ITO["reddish_purple"], OKABE_ITO["sky_blue"], "#666666"],
}
_KIND_LINESTYLE = {"dry": "-", "lubricated": "--", "ideal": ":", "other": "-."}
_KIND_MARKER = {"dry": "o", "lubricated": "s", "ideal": "^", "other": "D"}

#: rcParams applied inside every plotting function.
RC: Dict[str, Any] = {
    "font.size": 10,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 9,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "axes.grid": True,
    "grid.alpha": 0.4,
    "grid.linewidth": 0.6,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.prop_cycle": cycler(color=[OKABE_ITO[c] for c in ("blue", "vermillion", "bluish_green", "orange", "reddish_purple", "sky_blue", "black")]),
    "axes.formatter.useoffset": False,
    "axes.formatter.limits": (-3, 4),
    "lines.linewidth": 1.3,
    "lines.markersize": 4.5,
    "legend.frameon": False,
    "savefig.dpi": 150,
    "figure.dpi": 100,
}

#: Error quantities of the slider: axis label, unit and scale from SI (displacement shown in mm).
QUANTITIES: Dict[str, Tuple[str, str, float]] = {
    "displacement": ("Displacement error", "mm", 1e3),
    "velocity": ("Velocity error", "m/s", 1.0),
    "acceleration": ("Acceleration error", "m/s²", 1.0),
}

_SYMLOG_RATIO = 50.0  # peak ratio between series above which a panel switches to symlog


@contextlib.contextmanager
def style() -> Iterator[None]:
    """Context manager applying :data:`RC` (restores the previous rcParams on exit)."""
    with mpl.rc_context(cast(Any, RC)):  # the stubs want each key as a literal
        yield


def _kind(label: str) -> str:
    low = label.lower()
    if "ideal" in low or "rigid" in low:
        return "ideal"
    if "lub" in low or "film" in low or "oil" in low:
        return "lubricated"
    if "dry" in low or "contact" in low:
        return "dry"
    return "other"


def series_style(labels: Iterable[str]) -> Dict[str, Dict[str, Any]]:
    """Line style of each label: colour, linestyle and marker by the kind its text names
    (``dry``, ``lub…``, ``ideal``); several labels of one kind get successive colours."""
    seen: Dict[str, int] = {}
    out: Dict[str, Dict[str, Any]] = {}
    for label in labels:
        kind = _kind(label)
        k = seen.get(kind, 0)
        seen[kind] = k + 1
        colours = _KIND_COLOURS[kind]
        out[label] = {"color": colours[k % len(colours)], "linestyle": _KIND_LINESTYLE[kind], "marker": _KIND_MARKER[kind]}
    return out


def _new_figure(width: float, height: float) -> Figure:
    return Figure(figsize=(width, height), layout="constrained")


def suptitle(fig: Figure, title: str) -> None:
    """``fig.suptitle(title)`` on as many lines as it takes to fit the figure's width (a scene's
    long name would otherwise be cut off at both edges). Call inside :func:`style`."""
    from matplotlib.font_manager import FontProperties

    points = FontProperties(size=mpl.rcParams["figure.titlesize"]).get_size_in_points()
    chars = max(16, int(fig.get_figwidth() * 72.0 / (0.6 * points)))  # ~0.6 em a character
    fig.suptitle(textwrap.fill(title, chars))


def _legend_above(ax: Axes, handles: Optional[Sequence[Any]] = None, labels: Optional[Sequence[str]] = None, ncol: Optional[int] = None) -> None:
    """Legend in a row above the axes, outside the data area (constrained layout makes room)."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return
    if labels is None:
        labels = [str(h.get_label()) for h in handles]
    n = len(handles)
    ax.legend(list(handles), list(labels), loc="lower center", bbox_to_anchor=(0.5, 1.01), ncol=ncol or min(n, 3), borderaxespad=0.2, handlelength=2.6)


def _quantity(quantity: str, quantity_info: Optional[Mapping[str, Tuple[str, str, float]]]) -> Tuple[str, str, float]:
    info = dict(QUANTITIES)
    if quantity_info:
        info.update(quantity_info)
    if quantity not in info:
        raise InputError(
            f"invalid quantity = {quantity!r}: must be one of {', '.join(info)} (or describe it in quantity_info as (label, unit, scale))",
            field="quantity",
            value=quantity,
        )
    return info[quantity]


def _array(name: str, value: Any) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"invalid {name}: must be an array of numbers", field=name, value=value) from None
    if arr.ndim != 1:
        raise InputError(f"invalid {name}: must be one-dimensional, got shape {arr.shape}", field=name, value=arr.shape)
    return arr


def _check_same_length(name: str, arr: np.ndarray, n: int, ref: str) -> None:
    if arr.shape[0] != n:
        raise InputError(f"invalid {name}: has {arr.shape[0]} samples but {ref} has {n}", field=name, value=arr.shape[0])


def _peak(a: np.ndarray) -> float:
    finite = a[np.isfinite(a)]
    return float(np.max(np.abs(finite))) if finite.size else 0.0


# ====================================================================== error histories
def plot_error_histories(
    t: Union[np.ndarray, Sequence[float], Mapping[str, Any]],
    series: Mapping[str, Mapping[str, Any]],
    quantities: Sequence[str] = ("displacement", "velocity", "acceleration"),
    scale: str = "auto",
    title: Optional[str] = None,
    quantity_info: Optional[Mapping[str, Tuple[str, str, float]]] = None,
) -> Figure:
    """Stacked panels of output errors against time (like the paper's Figs. 8, 12, 13).

    Parameters
    ----------
    t:
        Time [s], shape (N,), shared by all series — or ``{label: t}`` per series.
    series:
        ``{label: {quantity: error array (N,)}}`` in SI units: displacement [m] (plotted in mm),
        velocity [m/s], acceleration [m/s²]. Labels naming ``dry``/``lubricated``/``ideal`` get
        the consistent styles of :func:`series_style`.
    quantities:
        Panels from top to bottom (keys of :data:`QUANTITIES` or of ``quantity_info``).
    scale:
        ``"auto"`` (a panel whose series peaks differ by more than 50× — dry ~1000 m/s² against
        lubricated ~1 m/s² — gets a symmetric-log y axis so that the small curve stays visible),
        ``"linear"`` or ``"symlog"``.
    quantity_info:
        Extra or overriding ``{quantity: (axis label, unit, scale from SI)}``.
    """
    if scale not in ("auto", "linear", "symlog"):
        raise InputError(f"invalid scale = {scale!r}: must be auto, linear or symlog", field="scale", value=scale)
    if not series:
        raise InputError("invalid series: no series to plot", field="series", value=series)
    quantities = list(quantities)
    if not quantities:
        raise InputError("invalid quantities: empty", field="quantities", value=quantities)
    styles = series_style(series)
    with style():
        fig = _new_figure(7.0, 2.3 * len(quantities) + 0.6)
        axes = fig.subplots(len(quantities), 1, sharex=True, squeeze=False)[:, 0]
        for ax, q in zip(axes, quantities):
            name, unit, factor = _quantity(q, quantity_info)
            curves: List[Tuple[str, np.ndarray, np.ndarray]] = []
            for label, data in series.items():
                if q not in data:
                    continue
                tt = _array(f"t[{label!r}]" if isinstance(t, Mapping) else "t", t[label] if isinstance(t, Mapping) else t)
                y = _array(f"series[{label!r}][{q!r}]", data[q]) * factor
                _check_same_length(f"series[{label!r}][{q!r}]", y, tt.shape[0], "t")
                curves.append((label, tt, y))
            peaks = [p for p in (_peak(y) for _, _, y in curves) if p > 0.0]
            use_symlog = scale == "symlog" or (scale == "auto" and len(peaks) > 1 and max(peaks) / min(peaks) > _SYMLOG_RATIO)
            # draw the largest first so the smallest (typically lubricated) curve stays on top
            order = sorted(curves, key=lambda c: -_peak(c[2]))
            for z, (label, tt, y) in enumerate(order):
                st = styles[label]
                ax.plot(tt, y, color=st["color"], linestyle=st["linestyle"], linewidth=0.9, label=label, zorder=2 + z)
            ax.axhline(0.0, color="0.3", linewidth=0.6, zorder=1)
            ylabel = f"{name} [{unit}]"
            if use_symlog and peaks:
                linthresh = 10.0 ** math.floor(math.log10(min(peaks)))
                ax.set_yscale("symlog", linthresh=linthresh, linscale=0.6)
                ylabel += "\n(symlog)"
            ax.set_ylabel(ylabel)
        axes[-1].set_xlabel("Time [s]")
        handles, labels = axes[0].get_legend_handles_labels()
        order_labels = [lab for lab in series if lab in labels]
        hmap = dict(zip(labels, handles))
        _legend_above(axes[0], [hmap[lab] for lab in order_labels], order_labels, ncol=2 if len(order_labels) > 3 else len(order_labels))
        if title:
            suptitle(fig, title)
    return fig


# ====================================================================== journal orbits
def plot_journal_orbits(
    orbits: Mapping[str, Tuple[Any, Any]],
    clearance: Union[float, Mapping[str, float]],
    transition_band: Union[None, float, Mapping[str, Optional[float]]] = None,
    ncols: Optional[int] = None,
    title: Optional[str] = None,
) -> Figure:
    """Journal-centre orbits normalised by the clearance (like the paper's Figs. 9, 10, 14, 15).

    Parameters
    ----------
    orbits:
        ``{panel label: (e_x, e_y)}``: eccentricity components [m] (journal centre relative to the
        bearing centre, e.g. ``Result.eccentricity(joint).T``), one panel per label.
    clearance:
        Radial clearance c [m] — one value, or ``{label: c}``.
    transition_band:
        Width e0 [m] of the film-to-contact transition band (P18); if given, the circle
        e = c + e0 is drawn dashed. One value or ``{label: e0}`` (a label left out, e.g. a
        dry joint's, gets no band).
    ncols:
        Panels per row (default: 2, or 1 for a single orbit).
    """
    if not orbits:
        raise InputError("invalid orbits: no orbit to plot", field="orbits", value=orbits)
    labels = list(orbits)
    n = len(labels)
    ncols = ncols or (1 if n == 1 else 2)
    nrows = int(math.ceil(n / ncols))
    with style():
        fig = _new_figure(3.3 * ncols + 0.3, 3.3 * nrows + 0.6)
        axes = fig.subplots(nrows, ncols, squeeze=False).ravel()
        for ax in axes[n:]:
            ax.set_visible(False)
        for ax, label in zip(axes, labels):
            c = clearance[label] if isinstance(clearance, Mapping) else clearance
            c = float(c)
            if not (c > 0.0 and math.isfinite(c)):
                raise InputError(f"invalid clearance = {c!r}: must be positive [m]", field="clearance", value=c)
            try:
                ex, ey = orbits[label]
            except (TypeError, ValueError):
                raise InputError(f"invalid orbits[{label!r}]: must be a pair (e_x, e_y) of arrays [m]", field="orbits", value=label) from None
            x = _array(f"orbits[{label!r}][0]", ex) / c
            y = _array(f"orbits[{label!r}][1]", ey) / c
            _check_same_length(f"orbits[{label!r}][1]", y, x.shape[0], "e_x")
            lim = 1.12
            ax.add_patch(Circle((0, 0), 1.0, fill=False, color="0.25", linewidth=1.2, zorder=1.5))
            # A mapping may leave panels out (a dry joint beside lubricated ones has no band).
            e0 = transition_band.get(label) if isinstance(transition_band, Mapping) else transition_band
            if e0 is not None:
                rb = 1.0 + float(e0) / c
                ax.add_patch(Circle((0, 0), rb, fill=False, color="0.45", linewidth=0.9, linestyle="--", zorder=1.5))
                lim = max(lim, rb + 0.08)
            finite = np.isfinite(x) & np.isfinite(y)
            if np.any(finite):
                lim = max(lim, 1.05 * float(np.max(np.hypot(x[finite], y[finite]))))
            colour = _KIND_COLOURS[_kind(label)][0]  # same colour for every panel of a kind
            ax.plot(x, y, color=colour, linewidth=0.6, alpha=0.9, zorder=2)
            if x.size:
                ax.plot(x[0], y[0], marker="o", color="k", markersize=5, linestyle="none", zorder=4)
                ax.plot(x[-1], y[-1], marker="s", markerfacecolor="white", markeredgecolor="k", markersize=5, linestyle="none", zorder=4)
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            ax.set_aspect("equal", adjustable="box")
            ax.set_title(label)
            ax.set_xlabel("$e_x/c$ [-]")
            ax.set_ylabel("$e_y/c$ [-]")
            ax.set_xticks([-1, -0.5, 0, 0.5, 1])
            ax.set_yticks([-1, -0.5, 0, 0.5, 1])
        handles = [
            Line2D([], [], color="0.25", linewidth=1.2),
            Line2D([], [], marker="o", color="k", linestyle="none"),
            Line2D([], [], marker="s", markerfacecolor="white", markeredgecolor="k", linestyle="none"),
        ]
        names = ["clearance circle e = c", "start", "end"]
        if transition_band is not None:
            handles.insert(1, Line2D([], [], color="0.45", linewidth=0.9, linestyle="--"))
            names.insert(1, "transition band e = c + e0")
        # One panel is narrow: the legend in two columns there.
        fig.legend(handles, names, loc="outside lower center" if _outside_ok() else "lower center", ncol=len(names) if ncols > 1 else 2)
        if title:
            suptitle(fig, title)
    return fig


def _outside_ok() -> bool:
    """Figure legends ``loc="outside ..."`` exist from matplotlib 3.7 on."""
    major, minor = (int(v) for v in mpl.__version__.split(".")[:2])
    return (major, minor) >= (3, 7)


# ====================================================================== reliability
def _curve(label: str, value: Any) -> Tuple[np.ndarray, np.ndarray]:
    """(angle [deg], R) from a pair, or from an object with ``bin_starts`` and ``reliability``
    (e.g. :class:`clearsim.reliability.FosmResult`)."""
    if hasattr(value, "bin_starts") and hasattr(value, "reliability"):
        a, r = value.bin_starts, value.reliability
    else:
        try:
            a, r = value
        except (TypeError, ValueError):
            raise InputError(f"invalid curves[{label!r}]: must be a pair (angle_deg, R)", field="curves", value=label) from None
    a = _array(f"curves[{label!r}][0]", a)
    r = _array(f"curves[{label!r}][1]", r)
    _check_same_length(f"curves[{label!r}][1]", r, a.shape[0], "angle")
    return a, r


def _angle_ticks(ax: Axes, amax: float) -> None:
    step = 90.0 if amax <= 360.0 + 1e-9 else (180.0 if amax <= 1080.0 + 1e-9 else 360.0)
    ax.set_xticks(np.arange(0.0, max(amax, 360.0) + 1e-9, step))


def _reliability_axes(ax: Axes, curves: Mapping[str, Any], quantity: str, annotate: bool) -> List[Tuple[Any, str]]:
    styles = series_style(curves)
    items: List[Tuple[Any, str]] = []
    minima: List[Tuple[float, float, str, Any]] = []
    amax = 0.0
    rmin = 1.0
    for label, value in curves.items():
        a, r = _curve(label, value)
        ok = np.isfinite(r)
        st = styles[label]
        (line,) = ax.plot(a[ok], r[ok], color=st["color"], linestyle=st["linestyle"], marker=st["marker"], markersize=3.5, linewidth=1.2)
        text = label
        if np.any(ok):
            amax = max(amax, float(np.max(a[ok])))
            j = int(np.flatnonzero(ok)[np.argmin(r[ok])])
            rmin = min(rmin, float(r[j]))
            text = f"{label} (min R = {r[j]:.4f} at {a[j]:g}°)"
            ax.plot(a[j], r[j], marker="*", markersize=12, color=st["color"], markeredgecolor="k", markeredgewidth=0.6, linestyle="none", zorder=5)
            if annotate:
                minima.append((float(a[j]), float(r[j]), f"{a[j]:g}°, R = {r[j]:.4f}", st["color"]))
        items.append((line, text))
    _angle_ticks(ax, amax)
    ax.set_xlim(-5.0, max(amax, 360.0) + 5.0)
    lo = min(rmin, 1.0)
    pad = max(0.2 * (1.0 - lo), 0.002)
    ax.set_ylim(lo - pad, 1.0 + 0.25 * pad)
    # Enough decimals that neighbouring tick labels differ (ticks at 0.925 must not read 0.93).
    ax.yaxis.set_major_formatter(mpl.ticker.FormatStrFormatter("%.3f"))
    ax.set_xlabel("Crank angle [deg]")
    ax.set_ylabel(f"{quantity.capitalize()} reliability R [-]" if quantity else "Reliability R [-]")
    _label_minima(ax, minima)
    return items


#: Where a minimum's label may go, in points from its star: below right first, then around it.
_LABEL_OFFSETS = [(6, -14), (6, 6), (-6, -14), (-6, 6), (6, -28), (-6, -28), (6, 20), (-6, 20), (6, -42), (-6, -42)]


def _label_minima(ax: Axes, minima: List[Tuple[float, float, str, Any]]) -> None:
    """Label each minimum (angle, R, text, colour) beside its star, at the first of
    :data:`_LABEL_OFFSETS` whose box overlaps no label placed before and stays inside the axes."""
    if not minima:
        return
    fig = cast(Figure, ax.figure)
    if not hasattr(fig.canvas, "get_renderer"):  # a bare Figure: measure text with Agg
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]  # Agg and the GUI canvases have it
    frame = ax.get_window_extent(renderer)
    placed: List[Any] = []
    for a, r, text, color in sorted(minima, key=lambda m: (m[1], m[0])):
        for dx, dy in _LABEL_OFFSETS:
            ann = ax.annotate(
                text,
                (a, r),
                xytext=(dx, dy),
                textcoords="offset points",
                ha="left" if dx > 0 else "right",
                fontsize=8,
                color=color,
                zorder=6,
                bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.8},
            )
            box = ann.get_window_extent(renderer)
            inside = frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
            if inside and not any(box.overlaps(other) for other in placed):
                placed.append(box)
                break
            ann.remove()
        else:  # nowhere free: the first place, overlapping
            ann = ax.annotate(text, (a, r), xytext=_LABEL_OFFSETS[0], textcoords="offset points", fontsize=8, color=color, zorder=6)
            placed.append(ann.get_window_extent(renderer))


def plot_reliability(curves: Mapping[str, Any], quantity: str = "displacement", annotate: bool = True, title: Optional[str] = None) -> Figure:
    """Reliability against crank angle with each curve's minimum marked (like Figs. 11, 16).

    Parameters
    ----------
    curves:
        ``{label: (angle [deg], R [-])}`` — e.g. ``(res.bin_starts, res.reliability)`` of
        :func:`clearsim.reliability.fosm` — or ``{label: FosmResult}``. Multi-cycle angles
        (0 … 360·cycles) are fine.
    quantity:
        Name of the output (``"displacement"``, ``"velocity"``, ``"acceleration"``) for the y label.
    annotate:
        Write the angle of each minimum next to its marker (the legend always gives R and angle).
    """
    if not curves:
        raise InputError("invalid curves: no curve to plot", field="curves", value=curves)
    with style():
        fig = _new_figure(7.0, 3.6 + 0.25 * max(0, len(curves) - 2))
        ax = fig.subplots()
        items = _reliability_axes(ax, curves, quantity, annotate)
        ax.legend([h for h, _ in items], [t for _, t in items], loc="lower center", bbox_to_anchor=(0.5, 1.01), ncol=1 if len(items) > 2 else len(items))
        if title:
            suptitle(fig, title)
    return fig


def plot_reliability_panels(
    curves_by_quantity: Mapping[str, Mapping[str, Any]], annotate: bool = True, title: Optional[str] = None
) -> Figure:
    """One reliability panel per quantity, stacked (``{quantity: {label: (angle, R)}}``), with a
    shared legend of the series labels; each panel's minima are marked and their angles written."""
    if not curves_by_quantity:
        raise InputError("invalid curves_by_quantity: nothing to plot", field="curves_by_quantity", value=curves_by_quantity)
    n = len(curves_by_quantity)
    with style():
        fig = _new_figure(7.0, 2.7 * n + 0.8)
        axes = fig.subplots(n, 1, squeeze=False)[:, 0]
        for ax, (q, curves) in zip(axes, curves_by_quantity.items()):
            _reliability_axes(ax, curves, q, annotate)
        first = next(iter(curves_by_quantity.values()))
        styles = series_style(first)
        handles = [Line2D([], [], color=s["color"], linestyle=s["linestyle"], marker=s["marker"]) for s in styles.values()]
        # With a title on top, the shared legend goes below the panels so the two never overlap.
        where = "lower" if title else "upper"
        loc: Any = f"outside {where} center" if _outside_ok() else f"{where} center"  # a literal of the stubs
        fig.legend(handles, list(styles), loc=loc, ncol=min(len(handles), 4))
        if title:
            suptitle(fig, title)
    return fig


# ====================================================================== FOSM vs Monte Carlo
def plot_fosm_vs_mc(
    angle_deg: Any,
    fosm_R: Union[Any, Mapping[str, Any]],
    mc_R: Any,
    mc_lo: Any,
    mc_hi: Any,
    quantity: str = "displacement",
    bin_width: Optional[float] = None,
    confidence: Optional[float] = None,
    title: Optional[str] = None,
) -> Figure:
    """FOSM and Monte Carlo reliability per crank-angle bin, side by side.

    Top panel: R [-] per bin — FOSM markers (one series per entry of ``fosm_R``) just left of
    the bin angle, Monte Carlo estimates with their confidence bars just right of it. Bottom
    panel: the failure probability 1 − R [-] on a log axis, where values near R = 1 differ;
    a Monte Carlo estimate of 0 (no failure seen) is drawn as an open marker at its upper bound.

    Parameters
    ----------
    angle_deg:
        Bin angle [deg] (start angles as in :func:`clearsim.reliability.fosm`), shape (B,).
    fosm_R:
        FOSM reliability per bin, shape (B,), or ``{label: R}`` for several FOSM variants (e.g.
        pooled Monte Carlo samples and the nominal run).
    mc_R, mc_lo, mc_hi:
        Monte Carlo reliability per bin and its confidence interval, shape (B,).
    bin_width:
        Bin width [deg] (sets the offsets; default: spacing of ``angle_deg``).
    confidence:
        Confidence level of the interval, for the legend (e.g. 0.95).
    """
    a = _array("angle_deg", angle_deg)
    n = a.shape[0]
    r_mc = _array("mc_R", mc_R)
    lo = _array("mc_lo", mc_lo)
    hi = _array("mc_hi", mc_hi)
    for name, arr in (("mc_R", r_mc), ("mc_lo", lo), ("mc_hi", hi)):
        _check_same_length(name, arr, n, "angle_deg")
    fosm_map: Dict[str, np.ndarray] = {}
    if isinstance(fosm_R, Mapping):
        for label, r in fosm_R.items():
            fosm_map[label] = _array(f"fosm_R[{label!r}]", r)
    else:
        fosm_map["FOSM"] = _array("fosm_R", fosm_R)
    for label, r in fosm_map.items():
        _check_same_length(f"fosm_R[{label!r}]", r, n, "angle_deg")
    if bin_width is None:
        d = np.diff(np.unique(a))
        bin_width = float(np.min(d)) if d.size else 18.0
    w = float(bin_width)
    fosm_colours = [OKABE_ITO["blue"], OKABE_ITO["bluish_green"], OKABE_ITO["sky_blue"], OKABE_ITO["reddish_purple"]]
    mc_colour = OKABE_ITO["vermillion"]
    ci = f"{100 * confidence:g} % Wilson interval" if confidence else "Wilson interval"
    with style():
        fig = _new_figure(7.0, 5.6)
        ax, axf = fig.subplots(2, 1, sharex=True)
        nf = len(fosm_map)
        offsets = (np.arange(nf) - nf) * w / (3.0 * (nf + 1)) if nf else np.array([])
        for k, (label, r) in enumerate(fosm_map.items()):
            col = fosm_colours[k % len(fosm_colours)]
            ok = np.isfinite(r)
            ax.plot(a[ok] + offsets[k], r[ok], marker="s", linestyle="none", color=col, label=label)
            pf = 1.0 - r[ok]
            pos = pf > 0
            axf.plot((a[ok] + offsets[k])[pos], pf[pos], marker="s", linestyle="none", color=col)
        ok = np.isfinite(r_mc)
        dx = w / 6.0
        ax.errorbar(
            a[ok] + dx, r_mc[ok], yerr=[r_mc[ok] - lo[ok], hi[ok] - r_mc[ok]], fmt="o", color=mc_colour, ecolor=mc_colour,
            elinewidth=1.0, capsize=2.5, label=f"Monte Carlo ({ci})",
        )
        pf, pf_lo, pf_hi = 1.0 - r_mc[ok], 1.0 - hi[ok], 1.0 - lo[ok]
        x = a[ok] + dx
        seen = pf > 0
        floor = float(np.min(pf_hi[pf_hi > 0])) / 10.0 if np.any(pf_hi > 0) else 1e-6
        axf.errorbar(
            x[seen], pf[seen], yerr=[pf[seen] - np.maximum(pf_lo[seen], floor), pf_hi[seen] - pf[seen]], fmt="o", color=mc_colour,
            ecolor=mc_colour, elinewidth=1.0, capsize=2.5,
        )
        if np.any(~seen):
            axf.plot(x[~seen], pf_hi[~seen], marker="v", markerfacecolor="white", markeredgecolor=mc_colour, linestyle="none", label="MC: no failure (upper bound)")
            axf.vlines(x[~seen], floor, pf_hi[~seen], color=mc_colour, linewidth=1.0)
        axf.set_yscale("log")
        ax.set_ylabel(f"{quantity.capitalize()} reliability R [-]" if quantity else "Reliability R [-]")
        axf.set_ylabel("Failure probability 1 − R [-]")
        axf.set_xlabel("Crank angle [deg]")
        _angle_ticks(axf, float(np.max(a)) if n else 360.0)
        axf.set_xlim(float(np.min(a)) - w / 2 if n else 0.0, float(np.max(a)) + w if n else 360.0)
        _legend_above(ax, ncol=nf + 1)
        if np.any(~seen):
            axf.legend(loc="best")
        if title:
            suptitle(fig, title)
    return fig


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
        fig = _new_figure(6.0, 4.4)
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
        _legend_above(ax, ncol=min(len(groups), 4))
        if title:
            suptitle(fig, title)
    return fig


def _log_label(value: float, _pos: Any = None) -> str:
    """``%g`` label for log-axis ticks whose mantissa is 1, 2 or 5, else none."""
    if value <= 0:
        return ""
    mant = value / 10.0 ** math.floor(math.log10(value) + 1e-9)
    return f"{value:g}" if any(abs(mant - m) < 1e-6 for m in (1.0, 2.0, 5.0)) else ""


# ====================================================================== saving
def save(fig: Figure, path: Union[str, Path], dpi: int = 150) -> Path:
    """Save ``fig`` (PNG unless the suffix says otherwise) at ``dpi`` and close it.

    Creates the parent directory. Figures from this module are not registered with pyplot, so
    closing only matters for pyplot figures, which are closed with ``pyplot.close``.
    Returns the path written.
    """
    p = Path(path)
    if not p.suffix:
        p = p.with_suffix(".png")
    p.parent.mkdir(parents=True, exist_ok=True)
    with style():
        fig.savefig(p, dpi=dpi)
    if getattr(fig.canvas, "manager", None) is not None:
        import matplotlib.pyplot as plt

        plt.close(fig)
    return p


def plot_wear(result: Any, joint: str, title: Optional[str] = None) -> Figure:
    """Archard wear depth of a clearance joint (``Dry(wear=Archard(...))``) around the bearing
    and the journal, in µm against the angle from each body's x axis (polar axes, one per
    surface; docs/physics.md §12)."""
    with style():
        fig = _new_figure(8.0, 4.2)
        for k, surface in enumerate(("bearing", "journal")):
            angle, depth = result.wear(joint, surface)
            ax = fig.add_subplot(1, 2, k + 1, projection="polar")
            closed_a, closed_d = np.append(angle, angle[0]), np.append(depth, depth[0]) * 1e6
            ax.fill(closed_a, closed_d, alpha=0.35, color=f"C{k}")
            ax.plot(closed_a, closed_d, color=f"C{k}", lw=1.2)
            ax.set_title(f"{surface}: max {depth.max() * 1e6:.3g} µm", fontsize=10, pad=12)
            ax.tick_params(labelsize=8)
            ax.set_rlabel_position(112.5)  # type: ignore[attr-defined]  # a PolarAxes
            ax.yaxis.set_major_locator(mpl.ticker.MaxNLocator(3))
        fig.suptitle(title or f"Wear of clearance joint '{joint}' (volume {result.wear_volume(joint):.3g} m³)", fontsize=11)

    return fig
