"""Figures of a motion's long-run dynamics (:mod:`clearsim.dynamics`): Poincaré sections,
phase portraits, bifurcation diagrams with the largest Lyapunov exponent, its convergence, and
amplitude spectra."""

from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Tuple, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from .theme import OKABE_ITO, new_figure, style

#: Colour of each kind of motion in a bifurcation diagram.
KIND_COLOURS: Dict[str, str] = {"chaotic": OKABE_ITO["vermillion"], "quasi-periodic": OKABE_ITO["orange"], "period>16": OKABE_ITO["reddish_purple"], "failed": "#999999"}


def _kind_colour(kind: str) -> str:
    if kind.startswith("period-"):
        return OKABE_ITO["blue"]
    return KIND_COLOURS.get(kind, OKABE_ITO["black"])


def _axes(ax: Optional[Axes], width: float = 5.5, height: float = 4.2) -> Tuple[Figure, Axes]:
    if ax is not None:
        return cast(Figure, ax.figure), ax
    fig = new_figure(width, height)
    return fig, fig.add_subplot(1, 1, 1)


def plot_poincare(x: np.ndarray, y: np.ndarray, xlabel: str, ylabel: str, title: str = "", ax: Optional[Axes] = None) -> Figure:
    """A Poincaré section: one dot per section point (x against y)."""
    with style():
        fig, ax = _axes(ax)
        ax.plot(np.asarray(x), np.asarray(y), ".", ms=3.0, color=OKABE_ITO["blue"])
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        if title:
            ax.set_title(title)
    return fig


def plot_phase_portrait(
    x: np.ndarray, v: np.ndarray, xlabel: str, vlabel: str, sections: Optional[Tuple[np.ndarray, np.ndarray]] = None, title: str = "", ax: Optional[Axes] = None
) -> Figure:
    """A phase portrait: the trajectory (x, v) as a line, and its section points on top if given."""
    with style():
        fig, ax = _axes(ax)
        ax.plot(np.asarray(x), np.asarray(v), lw=0.6, color=OKABE_ITO["sky_blue"], label="trajectory")
        if sections is not None:
            ax.plot(np.asarray(sections[0]), np.asarray(sections[1]), ".", ms=5.0, color=OKABE_ITO["vermillion"], label="Poincaré section")
            ax.legend(loc="upper right")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(vlabel)
        if title:
            ax.set_title(title)
    return fig


def plot_bifurcation(b: Any, ax: Optional[Axes] = None, parameter_label: Optional[str] = None, scale: float = 1.0, unit: Optional[str] = None, title: str = "") -> Figure:
    """A bifurcation diagram (:class:`clearsim.dynamics.Bifurcation`): the section points of the
    output over the parameter, coloured by the kind of motion, and below it the largest
    Lyapunov exponent with its 95 % interval where one was computed. ``scale`` multiplies the
    output (``unit`` its label after scaling)."""
    has_exp = bool(np.any(np.isfinite(b.exponent)))
    with style():
        bottom: Optional[Axes] = None
        if ax is not None:
            fig, top = _axes(ax)
        else:
            fig = new_figure(7.5, 6.0 if has_exp else 4.2)
            if has_exp:
                top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (2.2, 1.0)})
            else:
                top = fig.add_subplot(1, 1, 1)
        seen = set()
        ms = 2.5 if len(b.values) < 50 else 1.2
        for v, pts, kind in zip(b.values, b.points, b.kind):
            seen.add("periodic" if kind.startswith("period-") else kind)
            top.plot(np.full(len(pts), v), np.asarray(pts) * scale, ".", ms=ms, mew=0, color=_kind_colour(kind), alpha=0.8)
        top.set_ylabel(f"{b.output} [{unit or b.unit}]")
        handles = [top.plot([], [], "o", color=_kind_colour("period-1" if k == "periodic" else k), label=k)[0] for k in sorted(seen)]
        top.legend(handles=handles, loc="best", fontsize=8)
        if title:
            top.set_title(title)
        last = top
        if bottom is not None:
            ok = np.isfinite(b.exponent)
            bottom.axhline(0.0, color="#666666", lw=0.8)
            bottom.errorbar(b.values[ok], b.exponent[ok], yerr=np.abs(b.exponent_interval[ok].T - b.exponent[ok]), fmt=".", ms=3.0, lw=0.6, color=OKABE_ITO["black"])
            bottom.set_ylabel("largest Lyapunov\nexponent [1/s]")
            last = bottom
        last.set_xlabel(parameter_label or b.parameter)
    return fig


def plot_lyapunov(ly: Any, ax: Optional[Axes] = None, title: str = "") -> Figure:
    """The running estimate λ(t) of a :class:`clearsim.dynamics.LyapunovExponent` and its final
    value with the 95 % interval."""
    t, running = ly.convergence
    with style():
        fig, ax = _axes(ax, 6.0, 3.6)
        ax.plot(t, running, color=OKABE_ITO["blue"], label="running estimate")
        lo, hi = ly.interval
        if np.isfinite(lo) and np.isfinite(hi):
            ax.axhspan(lo, hi, color=OKABE_ITO["sky_blue"], alpha=0.3, label=f"λ = {ly.exponent:.4g} 1/s, 95 % interval")
        ax.axhline(0.0, color="#666666", lw=0.8)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("λ [1/s]")
        ax.legend(loc="best")
        if title:
            ax.set_title(title)
    return fig


def plot_spectrum(spec: Any, ax: Optional[Axes] = None, max_order: Optional[float] = None, title: str = "") -> Figure:
    """The amplitude spectrum of a :class:`clearsim.dynamics.Spectrum` over the harmonic order
    (frequency × period), amplitudes on a log scale."""
    order = spec.order
    amp = spec.amplitude
    if max_order is not None:
        keep = order <= max_order
        order, amp = order[keep], amp[keep]
    with style():
        fig, ax = _axes(ax, 6.5, 3.6)
        ax.vlines(order, 0.0, amp, color=OKABE_ITO["blue"], lw=0.9)
        ax.set_yscale("log")
        pos = amp[amp > 0]
        if len(pos):
            ax.set_ylim(max(pos.max() * 1e-8, pos.min()), pos.max() * 2)
        ax.set_xlabel(f"harmonic order (frequency × {spec.period:.4g} s)")
        ax.set_ylabel(f"amplitude [{spec.unit}]")
        ax.set_title(title or spec.label)
    return fig


def plot_poincare_panels(panels: Sequence[Tuple[np.ndarray, np.ndarray, str]], xlabel: str, ylabel: str, title: str = "", circle: Optional[float] = None) -> Figure:
    """Several Poincaré sections side by side: ``(x, y, panel title)`` each; with ``circle`` (a
    radius, e.g. 1 for eccentricities in units of the clearance) each panel draws that circle and
    all share its equal-aspect limits."""
    with style():
        fig = new_figure(4.2 * len(panels), 4.0)
        for k, (x, y, name) in enumerate(panels):
            ax = fig.add_subplot(1, len(panels), k + 1)
            if circle is not None:
                a = np.linspace(0.0, 2 * np.pi, 361)
                ax.plot(circle * np.cos(a), circle * np.sin(a), color="#999999", lw=0.8)
                ax.set_aspect("equal")
                ax.set_xlim(-1.1 * circle, 1.1 * circle)
                ax.set_ylim(-1.1 * circle, 1.1 * circle)
            ax.plot(np.asarray(x), np.asarray(y), ".", ms=3.0, color=OKABE_ITO["blue"])
            ax.set_title(name)
            ax.set_xlabel(xlabel)
            if k == 0:
                ax.set_ylabel(ylabel)
        if title:
            fig.suptitle(title)
    return fig


__all__ = ["plot_bifurcation", "plot_lyapunov", "plot_phase_portrait", "plot_poincare", "plot_poincare_panels", "plot_spectrum"]
