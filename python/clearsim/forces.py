"""Force elements and loads (docs/physics.md §10): what a mechanism carries besides gravity.

Each function here checks its inputs and returns the plain-data entry of the description's
``"forces"`` list; the :class:`~clearsim.Mechanism` methods ``spring_damper``,
``rotational_spring_damper``, ``force``, ``torque`` and ``motor`` call them. Everything is
evaluated in the Rust core (tables too), so a load costs a few nanoseconds a step. SI units:
N, N m, N/m, N s/m, rad, rad/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from .errors import InputError, check_finite, check_positive

#: The independent variable of a load table: time, or the angle of a body or driver.
TIME = "time"


@dataclass(frozen=True)
class Table:
    """A piecewise-linear function y(x), for loads and nonlinear springs.

    Parameters
    ----------
    x, y:
        Sample points (x strictly increasing) and values. Between points y is interpolated
        linearly; outside [x₀, x_last] it keeps its end value.
    of:
        What x is: ``"time"`` [s] (default), or the name of a driver or a body, whose absolute
        angle θ [rad] is then x (an engine's gas force over the crank angle, a stamping load over
        part of the stroke). Ignored for a spring's force–deflection table (x is the deflection
        ℓ − ℓ₀ [m]).
    period:
        If given, x is wrapped into [x₀, x₀ + period) first: ``period=2*math.pi`` repeats a load
        every crank revolution (``4*math.pi`` for a four-stroke engine), whichever way the crank
        turns.

    Example
    -------
    >>> stroke = Table(x=np.radians([0, 150, 180, 210, 360]), y=[0, 0, -2000, 0, 0],
    ...                of="drive1", period=2 * math.pi)
    """

    x: Sequence[float]
    y: Sequence[float]
    of: str = TIME
    period: Optional[float] = None

    def plain(self, field: str) -> Dict[str, Any]:
        """The table's checked plain data (``x``, ``y``, ``period``)."""
        x = [check_finite(f"{field}.x[{k}]", v) for k, v in enumerate(np.asarray(self.x, dtype=float).ravel())]
        y = [check_finite(f"{field}.y[{k}]", v) for k, v in enumerate(np.asarray(self.y, dtype=float).ravel())]
        if len(x) < 2 or len(x) != len(y):
            raise InputError(
                f"invalid {field} = Table with {len(x)} x and {len(y)} y: needs at least 2 points and as many y as x",
                field=f"{field}.x",
                value=len(x),
            )
        for k in range(1, len(x)):
            if not x[k] > x[k - 1]:
                raise InputError(f"invalid {field}.x[{k}] = {x[k]!r}: x must increase strictly (x[{k - 1}] = {x[k - 1]!r})", field=f"{field}.x", value=x[k])
        out: Dict[str, Any] = {"x": x, "y": y, "period": None}
        if self.period is not None:
            p = check_positive(f"{field}.period", self.period)
            if x[-1] - x[0] > p * (1 + 1e-12):
                raise InputError(f"invalid {field}.period = {p!r}: must cover the table's span {x[-1] - x[0]!r}", field=f"{field}.period", value=p)
            out["period"] = p
        return out


def _profile(field: str, value: Union[float, Table], angle_body: Callable[[str, str], int]) -> Dict[str, Any]:
    """A constant or a table, as the core's ``Profile``."""
    if isinstance(value, Table):
        if value.of == TIME:
            argument: Dict[str, Any] = {"kind": "time"}
        else:
            argument = {"kind": "angle", "body": angle_body(f"{field}.of", value.of)}
        return {"kind": "table", "argument": argument, "table": value.plain(field)}
    return {"kind": "constant", "value": check_finite(field, value)}


def spring_damper(
    name: str, body_a: Optional[int], point_a: List[float], body_b: Optional[int], point_b: List[float],
    stiffness: float, damping: float, free_length: Optional[float], force_table: Optional[Union[Table, Sequence[Sequence[float]]]],
) -> Dict[str, Any]:  # fmt: skip
    """The entry of a translational spring-damper (see :meth:`Mechanism.spring_damper`)."""
    table = None
    if force_table is not None:
        if not isinstance(force_table, Table):
            try:
                xs, ys = force_table  # type: ignore[misc]
            except (TypeError, ValueError):
                raise InputError(
                    f"invalid force_table = {force_table!r}: give a Table(x=deflection, y=force) or a pair (deflections, forces)",
                    field="force_table",
                    value=force_table,
                ) from None
            force_table = Table(xs, ys)
        if stiffness != 0.0:
            raise InputError(f"invalid stiffness = {stiffness!r}: give either a stiffness or a force_table, not both", field="stiffness", value=stiffness)
        table = force_table.plain("force_table")
    return {
        "kind": "spring_damper", "name": name, "body_a": body_a, "point_a": point_a, "body_b": body_b, "point_b": point_b,
        "stiffness": _non_negative("stiffness", stiffness), "damping": _non_negative("damping", damping),
        "free_length": None if free_length is None else _non_negative("free_length", free_length), "force_table": table,
    }  # fmt: skip


def rotational_spring_damper(name: str, body_a: Optional[int], body_b: Optional[int], stiffness: float, damping: float, free_angle: Optional[float]) -> Dict[str, Any]:
    """The entry of a rotational spring-damper (see :meth:`Mechanism.rotational_spring_damper`)."""
    return {
        "kind": "rotational_spring_damper", "name": name, "body_a": body_a, "body_b": body_b,
        "stiffness": _non_negative("stiffness", stiffness), "damping": _non_negative("damping", damping),
        "free_angle": None if free_angle is None else check_finite("free_angle", free_angle),
    }  # fmt: skip


def applied_force(
    name: str, body: int, point: List[float], force: Optional[Sequence[float]], direction: Optional[Sequence[float]],
    magnitude: Optional[Union[float, Table]], frame: str, angle_body: Callable[[str, str], int],
) -> Dict[str, Any]:  # fmt: skip
    """The entry of an applied force (see :meth:`Mechanism.force`)."""
    if frame not in ("global", "body"):
        raise InputError(f"invalid frame = {frame!r}: must be 'global' or 'body'", field="frame", value=frame)
    if (force is None) == (direction is None and magnitude is None):
        raise InputError(
            "invalid force: give either force=(Fx, Fy) [N], or direction=(dx, dy) with magnitude= [N] (a number or a Table)",
            field="force",
            value=force,
        )
    if force is not None:
        fx, fy = (check_finite("force[0]", force[0]), check_finite("force[1]", force[1]))
        size = math.hypot(fx, fy)
        d = [fx / size, fy / size] if size > 0 else [1.0, 0.0]
        prof = {"kind": "constant", "value": size}
    else:
        if direction is None or magnitude is None:
            raise InputError("invalid force: direction and magnitude go together", field="direction", value=direction)
        d = [check_finite("direction[0]", direction[0]), check_finite("direction[1]", direction[1])]
        if math.hypot(*d) == 0.0:
            raise InputError(f"invalid direction = {direction!r}: must be a non-zero vector", field="direction", value=direction)
        prof = _profile("magnitude", magnitude, angle_body)
    return {"kind": "force", "name": name, "body": body, "point": point, "direction": d, "frame": frame, "magnitude": prof}


def applied_torque(name: str, body: int, torque: Union[float, Table], reaction: Optional[int], angle_body: Callable[[str, str], int]) -> Dict[str, Any]:
    """The entry of an applied torque (see :meth:`Mechanism.torque`)."""
    return {"kind": "torque", "name": name, "body": body, "reaction": reaction, "magnitude": _profile("torque", torque, angle_body)}


def motor(name: str, body: int, reaction: Optional[int], stall_torque: float, no_load_speed: float) -> Dict[str, Any]:
    """The entry of a motor (see :meth:`Mechanism.motor`)."""
    w0 = check_finite("no_load_speed", no_load_speed)
    if w0 == 0.0:
        raise InputError("invalid no_load_speed = 0.0: must not be zero (its sign is the direction of rotation)", field="no_load_speed", value=w0)
    return {"kind": "motor", "name": name, "body": body, "reaction": reaction, "stall_torque": check_positive("stall_torque", stall_torque), "no_load_speed": w0}


def _non_negative(field: str, value: float) -> float:
    v = check_finite(field, value)
    if v < 0:
        raise InputError(f"invalid {field} = {v!r}: must not be negative", field=field, value=v)
    return v
