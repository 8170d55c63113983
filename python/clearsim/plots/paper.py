"""The paper's figures: error histories of the slider against the ideal mechanism (one panel a
quantity) and the journal orbits of the clearance joints (eccentricity ratio in the clearance
circle). Plain numpy arrays and labels in, a :class:`matplotlib.figure.Figure` out.
"""

from __future__ import annotations

import math
from typing import Any, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle

from ..errors import InputError
from .theme import KIND_COLOURS, as_array, check_same_length, kind_of, legend_above, new_figure, outside_legend_ok, peak_abs, quantity_label, series_style, style, suptitle

_SYMLOG_RATIO = 50.0  # peak ratio between series above which a panel switches to symlog


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
        fig = new_figure(7.0, 2.3 * len(quantities) + 0.6)
        axes = fig.subplots(len(quantities), 1, sharex=True, squeeze=False)[:, 0]
        for ax, q in zip(axes, quantities):
            name, unit, factor = quantity_label(q, quantity_info)
            curves: List[Tuple[str, np.ndarray, np.ndarray]] = []
            for label, data in series.items():
                if q not in data:
                    continue
                tt = as_array(f"t[{label!r}]" if isinstance(t, Mapping) else "t", t[label] if isinstance(t, Mapping) else t)
                y = as_array(f"series[{label!r}][{q!r}]", data[q]) * factor
                check_same_length(f"series[{label!r}][{q!r}]", y, tt.shape[0], "t")
                curves.append((label, tt, y))
            peaks = [p for p in (peak_abs(y) for _, _, y in curves) if p > 0.0]
            use_symlog = scale == "symlog" or (scale == "auto" and len(peaks) > 1 and max(peaks) / min(peaks) > _SYMLOG_RATIO)
            # draw the largest first so the smallest (typically lubricated) curve stays on top
            order = sorted(curves, key=lambda c: -peak_abs(c[2]))
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
        legend_above(axes[0], [hmap[lab] for lab in order_labels], order_labels, ncol=2 if len(order_labels) > 3 else len(order_labels))
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
    if not isinstance(orbits, Mapping):
        raise InputError(f"invalid orbits = {type(orbits).__name__}: must be a mapping {{panel label: (e_x, e_y)}} [m], e.g. {{'A': res.eccentricity('A').T}}",
                         field="orbits", value=type(orbits).__name__)  # fmt: skip
    if not orbits:
        raise InputError("invalid orbits: no orbit to plot", field="orbits", value=orbits)
    labels = list(orbits)
    missing = [k for k in labels if isinstance(clearance, Mapping) and k not in clearance]
    if missing:
        raise InputError(f"invalid clearance: no value for {', '.join(map(repr, missing))} (one per orbit, or one number) [m]", field="clearance", value=missing)
    n = len(labels)
    ncols = ncols or (1 if n == 1 else 2)
    nrows = int(math.ceil(n / ncols))
    with style():
        fig = new_figure(3.3 * ncols + 0.3, 3.3 * nrows + 0.6)
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
            x = as_array(f"orbits[{label!r}][0]", ex) / c
            y = as_array(f"orbits[{label!r}][1]", ey) / c
            check_same_length(f"orbits[{label!r}][1]", y, x.shape[0], "e_x")
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
            colour = KIND_COLOURS[kind_of(label)][0]  # same colour for every panel of a kind
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
        fig.legend(handles, names, loc="outside lower center" if outside_legend_ok() else "lower center", ncol=len(names) if ncols > 1 else 2)
        if title:
            suptitle(fig, title)
    return fig
