"""The look every clearsim figure shares: the Okabe–Ito colour-blind-safe palette, report-sized
rcParams (:data:`RC`, applied by :func:`style`), series styled by the kind their label names
(:func:`series_style`: *dry* → vermillion/purple/orange solid lines, *lubricated* →
blue/green/sky-blue dashed, *ideal* → black dotted, anything else → the remaining palette
colours), figures built with ``Figure(...)`` (no pyplot state; :class:`NotebookFigure`, shown as
a picture in a notebook), legends above the axes, the
input checks of the plotting functions and :func:`save` (PNG, 150 dpi).
"""

from __future__ import annotations

import contextlib
import textwrap
from pathlib import Path
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, Union, cast

import matplotlib as mpl
import numpy as np
from cycler import cycler
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError

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

KIND_COLOURS: Dict[str, List[str]] = {
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



@contextlib.contextmanager
def style() -> Iterator[None]:
    """Context manager applying :data:`RC` (restores the previous rcParams on exit)."""
    with mpl.rc_context(cast(Any, RC)):  # the stubs want each key as a literal
        yield


def kind_of(label: str) -> str:
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
        kind = kind_of(label)
        k = seen.get(kind, 0)
        seen[kind] = k + 1
        colours = KIND_COLOURS[kind]
        out[label] = {"color": colours[k % len(colours)], "linestyle": _KIND_LINESTYLE[kind], "marker": _KIND_MARKER[kind]}
    return out


class NotebookFigure(Figure):
    """A :class:`~matplotlib.figure.Figure` that shows itself as a picture when a notebook cell
    returns it, in a fresh kernel too: a bare ``Figure`` made without pyplot shows as
    ``<Figure size 600x500 with 1 Axes>`` until ``matplotlib.pyplot`` is imported (which registers
    IPython's display of figures; once it is, that display is used and this one stands aside)."""

    def _repr_png_(self) -> bytes:
        from .. import display

        return display.png(self)


def new_figure(width: float, height: float) -> Figure:
    """A figure of ``width`` × ``height`` inches with constrained layout, not registered with
    pyplot, that a notebook shows as a picture (:class:`NotebookFigure`)."""
    return NotebookFigure(figsize=(width, height), layout="constrained")


def suptitle(fig: Figure, title: str) -> None:
    """``fig.suptitle(title)`` on as many lines as it takes to fit the figure's width (a scene's
    long name would otherwise be cut off at both edges). Call inside :func:`style`."""
    from matplotlib.font_manager import FontProperties

    points = FontProperties(size=mpl.rcParams["figure.titlesize"]).get_size_in_points()
    chars = max(16, int(fig.get_figwidth() * 72.0 / (0.6 * points)))  # ~0.6 em a character
    fig.suptitle(textwrap.fill(title, chars))


def legend_above(ax: Axes, handles: Optional[Sequence[Any]] = None, labels: Optional[Sequence[str]] = None, ncol: Optional[int] = None) -> None:
    """Legend in a row above the axes, outside the data area (constrained layout makes room)."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return
    if labels is None:
        labels = [str(h.get_label()) for h in handles]
    n = len(handles)
    ax.legend(list(handles), list(labels), loc="lower center", bbox_to_anchor=(0.5, 1.01), ncol=ncol or min(n, 3), borderaxespad=0.2, handlelength=2.6)


def quantity_label(quantity: str, quantity_info: Optional[Mapping[str, Tuple[str, str, float]]]) -> Tuple[str, str, float]:
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


def as_array(name: str, value: Any) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"invalid {name}: must be an array of numbers", field=name, value=value) from None
    if arr.ndim != 1:
        raise InputError(f"invalid {name}: must be one-dimensional, got shape {arr.shape}", field=name, value=arr.shape)
    return arr


def check_same_length(name: str, arr: np.ndarray, n: int, ref: str) -> None:
    if arr.shape[0] != n:
        raise InputError(f"invalid {name}: has {arr.shape[0]} samples but {ref} has {n}", field=name, value=arr.shape[0])


def peak_abs(a: np.ndarray) -> float:
    finite = a[np.isfinite(a)]
    return float(np.max(np.abs(finite))) if finite.size else 0.0


def outside_legend_ok() -> bool:
    """Figure legends ``loc="outside ..."`` exist from matplotlib 3.7 on."""
    major, minor = (int(v) for v in mpl.__version__.split(".")[:2])
    return (major, minor) >= (3, 7)



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

