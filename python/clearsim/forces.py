"""Force elements and loads (docs/physics.md §10): what a mechanism carries besides gravity.

Each function here turns its inputs into the plain-data entry of the description's ``"forces"``
list (numbers into floats, a load table's columns into the core's tables: what must be known to
write the entry); the core checks their values as each is added (``rust/compile/validate.rs``:
signs, strictly increasing tables, periods; one validator); the :class:`~clearsim.Mechanism` methods ``spring``, ``rotational_spring``,
``force``, ``torque`` and ``motor`` call them. Everything is evaluated in the Rust core (tables
too), so a load costs nanoseconds a step. SI units: N, N m, N/m, N s/m, rad, rad/s.

Load tables
-----------
A load that varies is a dict of equally long lists, piecewise linear between the points and held
at its end values outside them:

- in time: ``{"t": [s...], "fx": [N...], "fy": [N...]}`` (a torque: ``"torque": [N m...]``);
- in a driver's angle: ``{"driver": "drive1", "angle": [rad...], "fx": [...], "fy": [...]}``,
  the absolute angle θ of the body that driver (or motor) turns;
- ``"period"`` (optional) repeats the table every period of its variable, e.g. ``2π`` for a
  load that comes back each crank revolution (``4π`` for a four-stroke engine's gas force),
  whichever way the crank turns. Its last point is joined to its first one period on, so the
  first point need not sit at 0. Without it, a crank-angle table covers one revolution only.
- ``"interpolation"`` (optional): ``"linear"`` (default) or ``"cubic"``, a C² cubic spline
  through the points (not-a-knot; periodic with a ``"period"``, whose point at x₀ + period, if
  given, repeats the first value). A linear time table ends an integration step at every point
  (its corners); a cubic one only where it is held at its ends (a periodic one never), so a
  densely sampled smooth load (a rotating load given every 0.5°) costs far fewer steps
  (``python benches/rotating_load.py``).

A component left out of a force table is zero.

Harmonic loads and motions
--------------------------
:class:`Harmonic` ``(amplitude, omega, phase=0.0, offset=0.0)`` is the smooth periodic value
offset + amplitude · cos(omega · t + phase), omega in rad/s: a torque (``m.torque(body,
Harmonic(...))``), a force component (``m.force(body, point, (Harmonic(...), 0.0))``) or a
driver's angle law (``m.driver(body, law=Harmonic(...))``), evaluated in the core with no table
(the driven pendulum of Baker & Gollub, a vibrating support). The core checks its numbers
(omega positive, all finite) when the mechanism compiles.
"""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError, check_choice, check_finite
from .schema import INTERPOLATIONS


def _number(field: str, value: Any) -> float:
    """``float(value)``, or an InputError naming ``field`` for what is not a number (a NaN or an
    infinity passes: the core names it with its element when the mechanism compiles)."""
    if isinstance(value, bool):
        raise InputError(f"invalid {field} = {value!r}: must be a number", field=field, value=value)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"invalid {field} = {value!r}: must be a number", field=field, value=value) from None


@dataclass(frozen=True)
class Harmonic:
    """offset + amplitude · cos(omega · t + phase): a smooth periodic load or motion.

    ``omega`` [rad/s] (> 0), ``phase`` [rad]; ``amplitude`` and ``offset`` in the unit of what
    it gives: N for a force component, N m for a torque, rad for a driver's angle. Evaluated in
    the Rust core (no table); ``h(t)`` evaluates it here, ``h.period`` is 2π/ω [s]."""

    amplitude: float
    omega: float
    phase: float = 0.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        for name in ("amplitude", "omega", "phase", "offset"):
            object.__setattr__(self, name, _number(name, getattr(self, name)))

    @property
    def period(self) -> float:
        """2π/ω [s]."""
        return 2 * math.pi / self.omega

    def __call__(self, t: Any) -> Any:
        """The value at time(s) ``t`` [s]."""
        return self.offset + self.amplitude * np.cos(self.omega * np.asarray(t, dtype=float) + self.phase)

    def entry(self) -> Dict[str, Any]:
        """The core's plain data (``Profile::Harmonic``, ``AngleLaw::Harmonic``)."""
        return {"kind": "harmonic", "amplitude": self.amplitude, "omega": self.omega, "phase": self.phase, "offset": self.offset}


#: A load: a constant, a table (see the module docstring) or a :class:`Harmonic`.
Load = Union[float, Sequence[Any], Mapping[str, Any], Harmonic]
#: A body as an entry names it: a body's name (or "ground"), resolved to its index by the core
#: when the mechanism compiles (rust/names.rs), so elements may be added in any order.
BodyRef = Optional[str]


def _numbers(field: str, values: Any) -> List[float]:
    try:
        arr = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"invalid {field} = {values!r}: must be a list of numbers", field=field, value=values) from None
    return [check_finite(f"{field}[{k}]", v) for k, v in enumerate(arr)]


def _table(field: str, value: Mapping[str, Any], columns: Sequence[str]) -> Tuple[Dict[str, Any], Dict[str, List[float]]]:
    """The argument and the checked columns of a load table."""
    keys = set(value)
    if "t" in keys and "driver" not in keys:
        argument: Dict[str, Any] = {"kind": "time"}
        xs = _numbers(f"{field}.t", value["t"])
        xkey = "t"
    elif "driver" in keys and "angle" in keys and "t" not in keys:
        driver = value["driver"]
        if not isinstance(driver, str) or not driver:
            raise InputError(f"invalid {field}.driver = {driver!r}: must be the name of a driver or motor", field=f"{field}.driver", value=driver)
        argument = {"kind": "angle", "driver": driver}  # its body is found when the mechanism compiles
        xs = _numbers(f"{field}.angle", value["angle"])
        xkey = "angle"
    else:
        raise InputError(
            f"invalid {field} = {dict(value)!r}: a table is {{'t': [...], ...}} in time or {{'driver': name, 'angle': [...], ...}} in a driver's angle",
            field=field,
            value=dict(value),
        )
    allowed = {xkey, "driver", "period", "interpolation", *columns}
    unknown = sorted(keys - allowed)
    if unknown:
        raise InputError(f"invalid {field}: unknown key {unknown[0]!r} (known: {', '.join(sorted(allowed - {'driver'} if xkey == 't' else allowed))})", field=f"{field}.{unknown[0]}", value=unknown[0])
    if not any(c in keys for c in columns):
        raise InputError(f"invalid {field}: gives no values (expected {' and/or '.join(columns)})", field=field, value=dict(value))
    period = None if value.get("period") is None else check_finite(f"{field}.period", value["period"])
    interpolation = check_choice(f"{field}.interpolation", value.get("interpolation", "linear"), INTERPOLATIONS)
    # A column left out is zero at every point; the core checks the lengths, the order of the
    # points and the period (validate_table).
    cols = {c: _numbers(f"{field}.{c}", value[c]) if c in value else [0.0] * len(xs) for c in columns}
    return {"argument": argument, "x": xs, "period": period, "interpolation": interpolation}, cols


def _profile(head: Dict[str, Any], ys: List[float]) -> Dict[str, Any]:
    table: Dict[str, Any] = {"x": head["x"], "y": ys, "period": head["period"]}
    if head["interpolation"] != "linear":  # the default is left out: descriptions stay as they were
        table["interpolation"] = head["interpolation"]
    return {"kind": "table", "argument": head["argument"], "table": table}


def _constant(field: str, v: Any) -> Dict[str, Any]:
    if isinstance(v, Harmonic):
        return v.entry()
    return {"kind": "constant", "value": check_finite(field, v)}


def spring(
    name: str, body_a: BodyRef, point_a: List[float], body_b: BodyRef, point_b: List[float],
    stiffness: Optional[float], damping: float, free_length: Optional[float], force_table: Optional[Mapping[str, Any]],
) -> Dict[str, Any]:  # fmt: skip
    """The entry of a translational spring-damper (see :meth:`Mechanism.spring`)."""
    table = None
    if force_table is not None:
        if stiffness not in (None, 0.0):
            raise InputError(f"invalid stiffness = {stiffness!r}: give either a stiffness or a force_table, not both", field="stiffness", value=stiffness)
        if not isinstance(force_table, Mapping) or set(force_table) != {"deflection", "force"}:
            raise InputError(
                f"invalid force_table = {force_table!r}: must be {{'deflection': [m...], 'force': [N...]}}", field="force_table", value=force_table
            )
        table = {"x": _numbers("force_table.deflection", force_table["deflection"]), "y": _numbers("force_table.force", force_table["force"]), "period": None}
        stiffness = 0.0
    elif stiffness is None:
        raise InputError("invalid stiffness = None: give a stiffness [N/m] or a force_table", field="stiffness", value=None)
    return {
        "kind": "spring_damper", "name": name, "body_a": body_a, "point_a": point_a, "body_b": body_b, "point_b": point_b,
        "stiffness": check_finite("stiffness", stiffness), "damping": check_finite("damping", damping),
        "free_length": None if free_length is None else check_finite("free_length", free_length), "force_table": table,
    }  # fmt: skip


def rotational_spring(name: str, body_a: BodyRef, body_b: BodyRef, stiffness: float, damping: float, angle0: Optional[float]) -> Dict[str, Any]:
    """The entry of a rotational spring-damper (see :meth:`Mechanism.rotational_spring`)."""
    return {
        "kind": "rotational_spring_damper", "name": name, "body_a": body_a, "body_b": body_b,
        "stiffness": check_finite("stiffness", stiffness), "damping": check_finite("damping", damping),
        "angle0": None if angle0 is None else check_finite("angle0", angle0),
    }  # fmt: skip


def applied_force(name: str, body: str, point: List[float], value: Load, frame: str) -> Dict[str, Any]:
    """The entry of an applied force (see :meth:`Mechanism.force`)."""
    if isinstance(value, Mapping):
        head, cols = _table("value", value, ("fx", "fy"))
        fx, fy = _profile(head, cols["fx"]), _profile(head, cols["fy"])
    else:
        try:
            vx, vy = value  # type: ignore[misc]
        except (TypeError, ValueError):
            raise InputError(f"invalid value = {value!r}: must be (fx, fy) [N] (each a number or a Harmonic) or a load table", field="value", value=value) from None
        fx, fy = _constant("value[0]", vx), _constant("value[1]", vy)
    return {"kind": "force", "name": name, "body": body, "point": point, "frame": frame, "fx": fx, "fy": fy}


def applied_torque(name: str, body: str, value: Load, reaction: BodyRef) -> Dict[str, Any]:
    """The entry of an applied torque (see :meth:`Mechanism.torque`)."""
    if isinstance(value, Mapping):
        head, cols = _table("value", value, ("torque",))
        magnitude = _profile(head, cols["torque"])
    else:
        magnitude = _constant("value", value)
    return {"kind": "torque", "name": name, "body": body, "reaction": reaction, "magnitude": magnitude}


def motor(name: str, body: str, reaction: BodyRef, stall_torque: float, no_load_speed: float) -> Dict[str, Any]:
    """The entry of a motor (see :meth:`Mechanism.motor`)."""
    w0 = check_finite("no_load_speed", no_load_speed)
    return {"kind": "motor", "name": name, "body": body, "reaction": reaction, "stall_torque": check_finite("stall_torque", stall_torque), "no_load_speed": w0}
