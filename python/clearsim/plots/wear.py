"""Wear figures: the Archard wear depth around a clearance joint's bearing and journal."""

from __future__ import annotations

from typing import Any, Optional

import matplotlib as mpl
import numpy as np
from matplotlib.figure import Figure

from .theme import new_figure, style


def plot_wear(result: Any, joint: str, title: Optional[str] = None) -> Figure:
    """Archard wear depth of a clearance joint (``Dry(wear=Archard(...))``) around the bearing
    and the journal, in µm against the angle from each body's x axis (polar axes, one per
    surface; docs/physics.md §12)."""
    with style():
        fig = new_figure(8.0, 4.2)
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
