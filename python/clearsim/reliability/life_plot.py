"""The figure of a reliability-over-life result: p_f against operating cycles with its interval,
and the samples' peaks and worn depth against cycles (docs/reliability.md, "Reliability over
life")."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Sequence, Union

import numpy as np

__all__ = ["plot_life", "life_rows", "LIFE_HEADER"]

#: The keys of :func:`life_rows`'s columns (one row per requested cycle count); ``life.csv``
#: heads them ``name [unit]`` (:func:`clearsim.csvfile.report_header`: ``mean_peak [m]``,
#: ``mean_depth [m]``).
LIFE_HEADER = ["cycles", "pf", "interval_low", "interval_high", "reliability", "mean_peak", "max_peak", "mean_depth_m", "max_depth_m"]


def life_rows(res: Any) -> list:
    """``life.csv``'s rows: per cycle count, p_f with its interval, R, the samples' mean and
    largest peak of the first output and their mean and largest worn depth over all surfaces."""
    peaks = np.asarray(res.peaks)[:, :, 0] if res.peaks.shape[2] else np.full(res.g.shape, np.nan)
    depth = np.nanmax(res.depth, axis=2) if res.depth.shape[2] else np.full(res.g.shape, np.nan)
    rows = []
    for j, n in enumerate(res.cycles):
        p, d = peaks[:, j], depth[:, j]
        ok_p, ok_d = p[np.isfinite(p)], d[np.isfinite(d)]
        rows.append([float(n), float(res.pf[j]), float(res.interval[0][j]), float(res.interval[1][j]), 1.0 - float(res.pf[j]),
                     float(ok_p.mean()) if ok_p.size else np.nan, float(ok_p.max()) if ok_p.size else np.nan,
                     float(ok_d.mean()) if ok_d.size else np.nan, float(ok_d.max()) if ok_d.size else np.nan])  # fmt: skip
    return rows


def plot_life(res: Any, *, limit: Optional[float] = None, unit: str = "", reliability: Optional[Sequence[float]] = None, title: Optional[str] = None,
              path: Union[None, str, Path] = None) -> Any:  # fmt: skip
    """Three panels against operating cycles: p_f with its 95 % interval (and the cycles at
    which R falls to each of ``reliability``, with their intervals, where the samples reach
    it); each sample's peak of the first output (``limit`` drawn); each sample's largest worn
    depth [µm]. Saved to ``path`` when given; returns the figure."""
    from .. import plots

    with plots.style():
        fig = plots.new_figure(12.6, 3.6)
        ax_p, ax_peak, ax_d = fig.subplots(1, 3)
        n = res.cycles
        lo, hi = res.interval
        ax_p.fill_between(n, lo, hi, color="C0", alpha=0.25, lw=0, label="95 % interval")
        ax_p.plot(n, res.pf, "o-", color="C0", ms=3, label=f"p_f ({res.g.shape[0]} samples)")
        for k, r in enumerate(reliability or []):
            try:
                at, (a, b) = res.life_at(r)
            except Exception:  # the samples do not reach R: nothing to mark
                continue
            ax_p.axhline(1.0 - r, color=f"C{k + 3}", lw=0.7, ls=":")
            ax_p.errorbar([at], [1.0 - r], xerr=[[at - a], [min(b, n[-1]) - at]], fmt="s", color=f"C{k + 3}", capsize=3, label=f"R = {r:g} at {at:.4g} cycles")
        ax_p.set_xlabel("operating cycles")
        ax_p.set_ylabel("p_f (failure by then)")
        ax_p.set_ylim(bottom=0)
        ax_p.legend(fontsize=7)
        if res.peaks.shape[2]:
            ax_peak.plot(n, res.peaks[:, :, 0].T, color="0.4", lw=0.6, alpha=0.6)
        if limit is not None:
            ax_peak.axhline(limit, color="C3", lw=0.8, ls="--", label=f"limit {limit:.3g} {unit}")
            ax_peak.legend(fontsize=7)
        ax_peak.set_xlabel("operating cycles")
        ax_peak.set_ylabel(f"peak of {res.outputs[0] if res.outputs else 'the output'} [{unit}]")
        if res.depth.shape[2]:
            ax_d.plot(n, 1e6 * np.nanmax(res.depth, axis=2).T, color="C1", lw=0.6, alpha=0.6)
        ax_d.set_xlabel("operating cycles")
        ax_d.set_ylabel("largest worn depth [µm]")
        fig.suptitle(title or f"Reliability over life ({res.n_runs} runs, {res.blocks.mean():.1f} blocks a sample)", fontsize=9)
        if path is not None:
            plots.save(fig, Path(path))
        return fig
