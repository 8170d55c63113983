"""Film pressure figures: a lubricated joint's film pressure at one output time, unrolled over the
bearing (θ × z map for the finite film, p(θ) for the long and short ones) and as a polar plot
around the bearing (docs/physics.md §4, "Oil flow and pressure")."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
from matplotlib.figure import Figure

from .theme import new_figure, style


def plot_film_pressure(field: Any, title: Optional[str] = None) -> Figure:
    """The film pressure ``field`` (:class:`clearsim.film_readings.FilmPressure`, from
    :meth:`clearsim.Result.pressure`) in MPa: left, unrolled against θ from the widest gap [deg]
    (a colour map over the axial position z [mm] for the finite film, the mid-plane curve for the
    long and short films); right, the mid-plane pressure around the bearing in the global frame
    (polar, the widest gap and the peak marked)."""
    theta = np.asarray(field.theta)
    p = np.asarray(field.p) * 1e-6
    mid = p if p.ndim == 1 else p[:, p.shape[1] // 2]
    with style():
        fig = new_figure(10.0, 4.2)
        ax = fig.add_subplot(1, 2, 1)
        deg = np.degrees(theta)
        if p.ndim == 2 and field.z is not None:
            z = np.asarray(field.z) * 1e3
            mesh = ax.pcolormesh(deg, z, p.T, shading="gouraud", cmap="viridis")
            fig.colorbar(mesh, ax=ax, label="Pressure [MPa]")
            ax.set_ylabel("Axial position z [mm]")
            ax.grid(False)
        else:
            ax.plot(deg, mid, color="C0")
            ax.fill_between(deg, mid, alpha=0.25, color="C0")
            ax.set_ylabel("Pressure [MPa]")
        if np.isfinite(field.peak_angle):
            ax.axvline(np.degrees(field.peak_angle), color="C1", lw=0.8, ls="--")
        ax.set_xlim(0.0, 360.0)
        ax.set_xticks(np.arange(0, 361, 90))
        ax.set_xlabel("θ from the widest gap [deg]")
        ax.set_title(f"{field.film} film, unrolled", fontsize=10)
        polar = fig.add_subplot(1, 2, 2, projection="polar")
        angle = np.append(field.gap_angle + theta, field.gap_angle + theta[0])
        radius = np.append(mid, mid[0])
        polar.fill(angle, radius, alpha=0.3, color="C0")
        polar.plot(angle, radius, color="C0", lw=1.2)
        top = max(float(radius.max()), 1e-12)
        polar.plot([field.gap_angle, field.gap_angle], [0.0, top], color="0.4", lw=0.8, ls=":", label="widest gap")
        if np.isfinite(field.peak_angle):
            a = field.gap_angle + field.peak_angle
            polar.plot([a, a], [0.0, field.peak_pressure * 1e-6], color="C1", lw=1.0, label=f"peak {field.peak_pressure * 1e-6:.3g} MPa")
        polar.set_title("mid-plane, global frame [MPa]", fontsize=10, pad=12)
        polar.tick_params(labelsize=8)
        polar.legend(loc="lower left", bbox_to_anchor=(0.8, -0.05), fontsize=8)
        flow = f", side leakage {field.side_leakage * 1e6:.3g} cm³/s" if field.side_leakage else ""
        fig.suptitle(title or f"Film pressure of '{field.joint}' at t = {field.t:.6g} s{flow}", fontsize=11)
    return fig
