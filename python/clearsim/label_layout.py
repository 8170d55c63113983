"""Labels of a drawing that do not overlap: each label keeps its anchor (the joint, body or load
it names) and is pushed away from the labels it overlaps, in the drawing's own pixels.

Used by :mod:`clearsim.draw` once the axes' limits are set (a pose) and on every frame of an
animation; the extents are the renderer's (``Text.get_window_extent``), so the check is the same
one a reader's eye makes on the saved picture.
"""

from __future__ import annotations

from typing import Any, List, Sequence

import numpy as np

__all__ = ["separate", "extents", "overlaps", "renderer_of", "GAP", "ROUNDS"]

#: Pixels kept between two labels.
GAP = 1.0
#: Rounds of pushing at most (each moves every overlapping pair apart once).
ROUNDS = 60


def renderer_of(fig: Any) -> Any:
    """The renderer that draws ``fig`` (an Agg canvas is attached to a figure that has none)."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def extents(labels: Sequence[Any], renderer: Any) -> np.ndarray:
    """(n, 4) boxes [x0, y0, x1, y1] in pixels of the visible ``labels`` as ``renderer`` draws them."""
    boxes = [label.get_window_extent(renderer) for label in labels]
    return np.array([[b.x0, b.y0, b.x1, b.y1] for b in boxes], dtype=float).reshape(-1, 4)


def overlaps(boxes: np.ndarray, gap: float = 0.0) -> List[tuple]:
    """The pairs (i, j), i < j, of boxes closer than ``gap`` pixels (overlapping when ``gap`` = 0)."""
    return [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes)) if _overlap(boxes[i], boxes[j], gap)]


def separate(labels: Sequence[Any], renderer: Any, dpi: float, obstacles: Sequence[Any] = ()) -> bool:
    """Move the visible ``labels`` (annotations placed by an offset in points from their anchor)
    apart until no two overlap, and off the ``obstacles`` (artists that stay where they are: the
    magnified bearings a label names): each overlapping pair of labels is pushed along the axis
    of its smaller overlap, half each way; a label on an obstacle moves off it alone; repeated
    for at most :data:`ROUNDS` rounds. Deterministic: the same drawing gives the same layout.
    Returns whether a label moved."""
    shown = [label for label in labels if label is not None and label.get_visible() and label.get_text()]
    if not shown:
        return False
    boxes = extents(shown, renderer)
    fixed = extents([o for o in obstacles if o.get_visible()], renderer)
    moves = np.zeros((len(shown), 2))
    for _ in range(ROUNDS):
        placed = boxes + np.hstack([moves, moves])
        pairs = overlaps(placed, GAP)
        hits = [(i, j) for i in range(len(placed)) for j in range(len(fixed)) if _overlap(placed[i], fixed[j], GAP)]
        if not pairs and not hits:
            break
        for i, j in pairs:
            step = _push(boxes[i] + np.tile(moves[i], 2), boxes[j] + np.tile(moves[j], 2))
            moves[i] -= step / 2
            moves[j] += step / 2
        for i, j in hits:
            moves[i] -= _push(boxes[i] + np.tile(moves[i], 2), fixed[j])
    scale = 72.0 / float(dpi)  # pixels → points, the unit of the offsets
    for label, (mx, my) in zip(shown, moves):
        if mx or my:
            ox, oy = label.xyann
            label.xyann = (ox + mx * scale, oy + my * scale)
    return bool(np.any(moves))


def _overlap(a: np.ndarray, b: np.ndarray, gap: float) -> bool:
    return bool(a[0] < b[2] + gap and b[0] < a[2] + gap and a[1] < b[3] + gap and b[1] < a[3] + gap)


def _push(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """How far box ``b`` must move from box ``a`` [pixels] to clear it by :data:`GAP`: along the
    axis of the smaller overlap, the way ``b`` already lies (upwards/rightwards on a tie)."""
    dx = min(a[2], b[2]) - max(a[0], b[0]) + GAP
    dy = min(a[3], b[3]) - max(a[1], b[1]) + GAP
    if dy <= dx:
        return np.array([0.0, dy if (b[1] + b[3]) >= (a[1] + a[3]) else -dy])
    return np.array([dx if (b[0] + b[2]) >= (a[0] + a[2]) else -dx, 0.0])
