"""Labels of a still drawing that do not overlap: each name moved, in turn, to the first of a
few spots around the point it names where it overlaps no label placed before it, no small
mark (a pin, a bearing, a drive's arrow, a support) and stays inside the axes (the spot that
overlaps least when none is free; a mark counts for less than a label)."""

from __future__ import annotations

from typing import Any, List, Sequence, Tuple

#: Weight of an overlap with a mark against one with a label, and the largest mark (share of
#: the axes' width or height: a big plate is no obstacle, it is drawn under its name).
_MARK_WEIGHT = 0.3
_MARK_SIZE = 0.15

#: Spots tried around a label's point: offset [points] and horizontal alignment, the label's
#: own offset first. Further rings repeat them farther out.
_SPOTS: Tuple[Tuple[float, float, str], ...] = (
    (4, 4, "left"), (4, -12, "left"), (-4, 4, "right"), (-4, -12, "right"), (0, 9, "center"), (0, -17, "center"),
)  # fmt: skip
_STEP = 11.0


def _overlap(a: Any, b: Any) -> float:
    """Area [pixel²] two display boxes share."""
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


def _outside(box: Any, frame: Any) -> float:
    """Area [pixel²] of ``box`` outside ``frame``."""
    return box.width * box.height - _overlap(box, frame)


def place_labels(ax: Any, labels: Sequence[Any], rings: int = 3) -> None:
    """Move the annotations ``labels`` on ``ax`` (text at an offset in points from the point it
    names) so that none overlaps another and each stays inside the axes, where a spot allows.
    Call once the axes' limits are set; the layout is computed first (a figure with constrained
    layout places its axes then)."""
    if not labels:
        return
    fig = ax.figure
    fig.draw_without_rendering()
    frame = ax.get_window_extent()
    marks = [p.get_window_extent() for p in ax.patches]
    marks = [m for m in marks if m.width < _MARK_SIZE * frame.width and m.height < _MARK_SIZE * frame.height]
    placed: List[Any] = []
    for label in labels:
        own = tuple(label.xyann) + (label.get_horizontalalignment(),)
        spots = [own] + [(dx, dy + _STEP * r if dy > 0 else dy - _STEP * r, ha) for r in range(rings) for dx, dy, ha in _SPOTS]
        best, best_cost = own, float("inf")
        for dx, dy, ha in spots:
            label.xyann = (dx, dy)
            label.set_horizontalalignment(ha)
            box = label.get_window_extent().expanded(1.0, 1.0)
            cost = sum(_overlap(box, other) for other in placed) + _outside(box, frame) + _MARK_WEIGHT * sum(_overlap(box, m) for m in marks)
            if cost < best_cost:
                best, best_cost = (dx, dy, ha), cost
            if cost == 0.0:
                break
        label.xyann = best[:2]
        label.set_horizontalalignment(best[2])
        placed.append(label.get_window_extent())


__all__ = ["place_labels"]
