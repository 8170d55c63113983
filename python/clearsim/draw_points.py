"""Tracked points in the pictures of a mechanism: a mark and the point's name at its place in the
pose drawn, and its path over a run (:meth:`clearsim.Result.plot_mechanism` with ``trace=True``;
in :func:`clearsim.draw.animate` the path grows frame by frame). The points are body-frame points
(:class:`clearsim.points.TrackedPoint`), placed from the body coordinates q like the joints."""

from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from .points import TrackedPoint

#: Colour of a tracked point's mark and path (Okabe–Ito orange: apart from the bodies' blue, the
#: clearances' vermillion, the loads' green and the drives' purple).
POINT_COLOUR = "#E69F00"


def place(q: np.ndarray, body: int, point: Sequence[float]) -> np.ndarray:
    """Global position [m] of the body-frame ``point`` of body index ``body`` at coordinates q
    (one pose (3 n,) or many (N, 3 n): then (N, 2))."""
    q = np.asarray(q, dtype=float)
    x, y, th = q[..., 3 * body], q[..., 3 * body + 1], q[..., 3 * body + 2]
    c, s = np.cos(th), np.sin(th)
    return np.stack([x + c * point[0] - s * point[1], y + s * point[0] + c * point[1]], axis=-1)


class PointMarks:
    """The marks (and, with ``paths``, the traced paths) of tracked points on ``ax``: :meth:`update`
    moves them to a pose and draws each path up to a sample, creating no artist (an animation
    redraws only :attr:`artists`)."""

    def __init__(self, ax: Any, body_names: Sequence[str], points: Sequence[TrackedPoint], paths: Optional[List[np.ndarray]] = None, labels: bool = True) -> None:
        self.points = list(points)
        self.bodies = [list(body_names).index(p.body) for p in self.points]
        self.paths = paths
        self.artists: List[Any] = []
        self._marks: List[Any] = []
        self._labels: List[Any] = []
        self._traces: List[Any] = []
        for p in self.points:
            if paths is not None:
                self._traces.append(ax.plot([], [], color=POINT_COLOUR, lw=1.2, zorder=3)[0])
            self._marks.append(ax.plot([], [], "o", ms=5, markerfacecolor=POINT_COLOUR, markeredgecolor="black", markeredgewidth=0.8, zorder=7)[0])
            if labels:
                self._labels.append(ax.annotate(p.name, (0.0, 0.0), xytext=(5, -9), textcoords="offset points", fontsize=7, color="black", zorder=7))
        self.artists = self._traces + self._marks + self._labels

    @property
    def markers(self) -> List[Any]:
        """The points' markers (what labels are kept off)."""
        return list(self._marks)

    @property
    def labels(self) -> List[Any]:
        """The points' name labels (annotations, laid out with a drawing's)."""
        return list(self._labels)

    def update(self, q: np.ndarray, upto: Optional[int] = None) -> None:
        """Marks at the pose ``q``; each path over its first ``upto`` samples (all: ``None``)."""
        for k, (p, b) in enumerate(zip(self.points, self.bodies)):
            at = place(q, b, p.point)
            self._marks[k].set_data([at[0]], [at[1]])
            if self._labels:
                self._labels[k].xy = (float(at[0]), float(at[1]))
            if self.paths is not None:
                path = self.paths[k] if upto is None else self.paths[k][: max(1, upto)]
                self._traces[k].set_data(path[:, 0], path[:, 1])

    def extent(self, q: np.ndarray) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """Lower-left and upper-right corners [m] of the marks at ``q`` and of the whole paths."""
        pts = [place(q, b, p.point)[None, :] for p, b in zip(self.points, self.bodies)] + list(self.paths or [])
        if not pts:
            return None
        arr = np.concatenate(pts)
        arr = arr[np.all(np.isfinite(arr), axis=1)]
        return (arr.min(axis=0), arr.max(axis=0)) if len(arr) else None


def paths_of(result: Any, points: Sequence[TrackedPoint]) -> List[np.ndarray]:
    """Each point's (N, 2) global path over the stored outputs of ``result`` [m]."""
    return [result.point(p.body, p.point) for p in points]


def widen(ax: Any, corners: Optional[Tuple[np.ndarray, np.ndarray]], pad: float = 0.05) -> None:
    """Grow the axes' limits to hold ``corners`` with a margin of ``pad`` × their span."""
    if corners is None:
        return
    lo, hi = corners
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    span = float(np.hypot(*(hi - lo))) or max(x1 - x0, y1 - y0)
    m = pad * span
    ax.set_xlim(min(x0, lo[0] - m), max(x1, hi[0] + m))
    ax.set_ylim(min(y0, lo[1] - m), max(y1, hi[1] + m))


def add_to_pose(ax: Any, result: Any, q: np.ndarray, points: Sequence[TrackedPoint], trace: bool) -> PointMarks:
    """Mark ``points`` on a pose drawn from ``result`` at coordinates ``q`` (and, with ``trace``,
    their paths over the whole run), widening the axes to hold them."""
    return mark_pose(ax, result.body_names, q, points, paths_of(result, points) if trace else None)


def mark_pose(ax: Any, body_names: Sequence[str], q: np.ndarray, points: Sequence[TrackedPoint], paths: Optional[List[np.ndarray]] = None) -> PointMarks:
    """Mark ``points`` (and draw ``paths``, if given) on a pose drawn at coordinates ``q``,
    widening the axes to hold them."""
    marks = PointMarks(ax, body_names, points, paths)
    marks.update(q)
    widen(ax, marks.extent(q))
    return marks


__all__ = ["POINT_COLOUR", "PointMarks", "add_to_pose", "mark_pose", "paths_of", "place", "widen"]
