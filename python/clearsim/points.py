"""Points fixed on a body (a tool tip, a coupler point, a needle) as outputs: their motion in the
global frame from a body's stored pose, rates and accelerations, and the named points a scene,
a table of errors or a drawing tracks. A point is given in the body's own frame [m], as joints
take theirs (docs/physics.md §1, "Coordinates"; §5, "Points").

For a body at r, θ with A = A(θ) the rotation and B p = A p turned +90°, the point p is at
r + A p, moves at ṙ + θ̇ B p and accelerates at r̈ + θ̈ B p − θ̇² A p.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, NamedTuple, Sequence, Tuple, Union

import numpy as np

from .errors import InputError, check_choice
from .schema import BODY_QUANTITIES, POINT_MONITOR_COMPONENTS

#: The components of a point's motion and the suffix of each quantity in exported column names
#: (``tool.x``, ``tool.x_dot``, ``tool.x_ddot``: as :meth:`clearsim.Result.to_pandas` names a body's).
POINT_COMPONENTS: Tuple[str, str] = ("x", "y")


class TrackedPoint(NamedTuple):
    """A named point fixed on a body: ``point`` (x, y) [m] in the body's frame."""

    name: str
    body: str
    point: Tuple[float, float]


#: What ``points=`` takes: ``{"tool": ("coupler", (0.1, 0.02))}``, or a sequence of
#: :class:`TrackedPoint` or ``(body, (x, y))`` pairs (named ``coupler(0.1, 0.02)``).
PointsLike = Union[Mapping[str, Tuple[str, Sequence[float]]], Sequence[Any]]


def check_point(point: Any, field: str = "point") -> Tuple[float, float]:
    """``(x, y)`` [m] as two finite floats, or :class:`InputError` naming ``field`` and the value."""
    try:
        values = [float(v) for v in point]
    except (TypeError, ValueError):
        values = []
    if len(values) != 2 or not all(math.isfinite(v) for v in values):
        raise InputError(f"invalid {field} = {point!r}: must be (x, y), two finite numbers [m] in the body's frame", field=field, value=point)
    return values[0], values[1]


def point_motion(pose: np.ndarray, rate: np.ndarray, accel: np.ndarray, point: Sequence[float], quantity: str) -> np.ndarray:
    """(N, 2) global position [m], velocity [m/s] or acceleration [m/s²] (``quantity``
    ``"displacement"``, ``"velocity"``, ``"acceleration"``) of the body-frame ``point`` of a
    body whose (N, 3) pose (x, y, θ), rates and accelerations are given (``rate`` is read for the
    velocity and acceleration, ``accel`` for the acceleration only; pass ``None`` otherwise)."""
    check_choice("quantity", quantity, BODY_QUANTITIES)
    px, py = check_point(point)
    th = pose[:, 2]
    c, s = np.cos(th), np.sin(th)
    ap = np.column_stack([c * px - s * py, s * px + c * py])  # A p
    if quantity == "displacement":
        return pose[:, :2] + ap
    bp = np.column_stack([-ap[:, 1], ap[:, 0]])  # B p: A p turned +90°
    w = rate[:, 2:3]
    if quantity == "velocity":
        return rate[:, :2] + w * bp
    return accel[:, :2] + accel[:, 2:3] * bp - w * w * ap


def check_point_output(body: Any, point: Any, component: Any, body_names: Sequence[str], field: str = "output") -> Tuple[float, float]:
    """A point output's ``point`` (body frame [m]) checked with its ``body`` (one of
    ``body_names``) and ``component`` (``"x"``, ``"y"`` or ``"magnitude"``), as every output that
    takes ``point=`` names it (``Output(body=, point=, component=)``, ``Result.error(point=)``);
    :class:`InputError` names ``field`` and the value."""
    if body not in body_names:
        raise InputError(f"invalid {field}.body = {body!r}: a point lies on a body (known: {', '.join(body_names)})", field=f"{field}.body", value=body)
    check_choice(f"{field}.component", component, POINT_MONITOR_COMPONENTS, "(a point's)")
    return check_point(point, f"{field}.point")


def point_name(body: str, point: Sequence[float]) -> str:
    """A point's name in tables and CSV headers: ``coupler(0.1,0.02)`` (body frame [m])."""
    return f"{body}({point[0]:g},{point[1]:g})"


def point_component(values: np.ndarray, component: str) -> np.ndarray:
    """(N,) ``component`` ``"x"``, ``"y"`` or ``"magnitude"`` (the vector's length) of (N, 2)
    point values (a motion or its error against a reference)."""
    if component == "magnitude":
        return np.hypot(values[:, 0], values[:, 1])
    return values[:, POINT_COMPONENTS.index(component)]


def raw_point_error(sample: Mapping[str, np.ndarray], reference: Mapping[str, np.ndarray], body: int, point: Sequence[float], quantity: str, component: str) -> np.ndarray:
    """(N,) ``component`` of the error of a point's ``quantity`` against a reference run, from
    two raw runs' (N, 3 × bodies) arrays ``q``, ``qd`` and (for accelerations) ``qdd`` on the
    same times, the point on body number ``body``."""
    cols = slice(3 * body, 3 * body + 3)

    def motion(raw: Mapping[str, np.ndarray]) -> np.ndarray:
        rate = raw["qd"][:, cols] if quantity != "displacement" else None
        accel = raw["qdd"][:, cols] if quantity == "acceleration" else None
        return point_motion(raw["q"][:, cols], rate, accel, point, quantity)  # type: ignore[arg-type]

    return point_component(motion(sample) - motion(reference), component)


def tracked_points(points: PointsLike, body_names: Sequence[str], field: str = "points") -> List[TrackedPoint]:
    """The named points of ``points`` (see :data:`PointsLike`), checked: each body known, each
    point two finite numbers, names unique. :class:`InputError` names the entry and value."""
    if isinstance(points, Mapping):
        items: List[Tuple[Any, Any]] = [(name, spec) for name, spec in points.items()]
    elif isinstance(points, (list, tuple)):
        items = [(p.name, (p.body, p.point)) if isinstance(p, TrackedPoint) else (None, p) for p in points]
    else:
        raise InputError(f"invalid {field} = {points!r}: give {{name: (body, (x, y))}} or a list of (body, (x, y))", field=field, value=points)
    out: List[TrackedPoint] = []
    for k, (name, spec) in enumerate(items):
        where = f"{field}[{name!r}]" if name is not None else f"{field}[{k}]"
        try:
            body, local = spec
        except (TypeError, ValueError):
            raise InputError(f"invalid {where} = {spec!r}: must be (body, (x, y))", field=where, value=spec) from None
        if body not in body_names:
            raise InputError(f"invalid {where}.body = {body!r}: no such body (known: {', '.join(body_names)})", field=f"{where}.body", value=body)
        xy = check_point(local, f"{where}.point")
        label = str(name) if name is not None else f"{body}({xy[0]:g}, {xy[1]:g})"
        if any(p.name == label for p in out):
            raise InputError(f"invalid {where}: the name {label!r} is used twice", field=where, value=label)
        out.append(TrackedPoint(label, str(body), xy))
    return out


def as_mapping(points: Sequence[TrackedPoint]) -> Dict[str, Tuple[str, Tuple[float, float]]]:
    """``{name: (body, (x, y))}`` of tracked points (the form ``points=`` takes)."""
    return {p.name: (p.body, p.point) for p in points}


__all__ = [
    "POINT_COMPONENTS", "PointsLike", "TrackedPoint", "as_mapping", "check_point", "check_point_output", "point_component", "point_motion", "point_name", "raw_point_error",
    "tracked_points",
]  # fmt: skip
