"""Reliability figures: per-bin reliability against crank angle (one curve a case, the minima
labelled), several quantities in panels, and FOSM against Monte Carlo with the Monte Carlo
intervals. Plain numpy arrays, ``FosmResult`` or ``MonteCarloBins`` in, a figure out.
"""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Tuple, Union, cast

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..errors import InputError
from .theme import OKABE_ITO, as_array, check_same_length, legend_above, new_figure, outside_legend_ok, series_style, style, suptitle


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
    a = as_array(f"curves[{label!r}][0]", a)
    r = as_array(f"curves[{label!r}][1]", r)
    check_same_length(f"curves[{label!r}][1]", r, a.shape[0], "angle")
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
        fig = new_figure(7.0, 3.6 + 0.25 * max(0, len(curves) - 2))
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
        fig = new_figure(7.0, 2.7 * n + 0.8)
        axes = fig.subplots(n, 1, squeeze=False)[:, 0]
        for ax, (q, curves) in zip(axes, curves_by_quantity.items()):
            _reliability_axes(ax, curves, q, annotate)
        first = next(iter(curves_by_quantity.values()))
        styles = series_style(first)
        handles = [Line2D([], [], color=s["color"], linestyle=s["linestyle"], marker=s["marker"]) for s in styles.values()]
        # With a title on top, the shared legend goes below the panels so the two never overlap.
        where = "lower" if title else "upper"
        loc: Any = f"outside {where} center" if outside_legend_ok() else f"{where} center"  # a literal of the stubs
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
    a = as_array("angle_deg", angle_deg)
    n = a.shape[0]
    r_mc = as_array("mc_R", mc_R)
    lo = as_array("mc_lo", mc_lo)
    hi = as_array("mc_hi", mc_hi)
    for name, arr in (("mc_R", r_mc), ("mc_lo", lo), ("mc_hi", hi)):
        check_same_length(name, arr, n, "angle_deg")
    fosm_map: Dict[str, np.ndarray] = {}
    if isinstance(fosm_R, Mapping):
        for label, r in fosm_R.items():
            fosm_map[label] = as_array(f"fosm_R[{label!r}]", r)
    else:
        fosm_map["FOSM"] = as_array("fosm_R", fosm_R)
    for label, r in fosm_map.items():
        check_same_length(f"fosm_R[{label!r}]", r, n, "angle_deg")
    if bin_width is None:
        d = np.diff(np.unique(a))
        bin_width = float(np.min(d)) if d.size else 18.0
    w = float(bin_width)
    fosm_colours = [OKABE_ITO["blue"], OKABE_ITO["bluish_green"], OKABE_ITO["sky_blue"], OKABE_ITO["reddish_purple"]]
    mc_colour = OKABE_ITO["vermillion"]
    ci = f"{100 * confidence:g} % Wilson interval" if confidence else "Wilson interval"
    with style():
        fig = new_figure(7.0, 5.6)
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
        legend_above(ax, ncol=nf + 1)
        if np.any(~seen):
            axf.legend(loc="best")
        if title:
            suptitle(fig, title)
    return fig

