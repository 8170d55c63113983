"""The ``[simulation]`` and ``[outputs]`` tables of a scene file: their settings, the channel
names and units the outputs use, and the readers that check them (errors at the key's line).
SI units: s, m, rad."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

from .. import _core
from ..errors import InputError
from ..mechanism import Mechanism
from ..points import TrackedPoint, check_point
from ..schema import ATOL, COMPONENTS, JOINT_COLUMN_UNITS, OUTPUTS, RTOL
from .builder import _Builder
from .toml_reader import Table, dotted_key

#: The body channels ``[outputs].quantities`` names and the unit of each component x, y, theta
#: (ASCII, as the CSV headers write them). Not :data:`clearsim.schema.BODY_QUANTITIES`, the
#: quantities of an error or extreme (``"displacement"`` where a channel says ``"position"``).
BODY_CHANNELS: Dict[str, Tuple[str, str, str]] = {
    "position": ("m", "m", "rad"),
    "velocity": ("m/s", "m/s", "rad/s"),
    "acceleration": ("m/s^2", "m/s^2", "rad/s^2"),
}
#: The clearance-joint channels ``[outputs].joint_quantities`` names: their columns (name, unit).
_JOINT_CHANNEL_COLUMNS: Dict[str, Tuple[str, ...]] = {
    "eccentricity": ("ex", "ey", "eps"),
    "eccentricity_rate": ("ex_dot", "ey_dot"),
    "force": ("fx", "fy"),
    "contact_force": ("normal", "tangential"),
    "film_force": ("film_xi", "film_eta"),
    "state": ("state", "w_dry"),
    "film_thickness": ("film_thickness",),
    "friction_torque": ("friction_torque", "friction_torque_bearing"),
    "power_loss": ("power_loss",),
}
#: ``[outputs] joint_quantities`` → the CSV columns it writes, each with its unit (the units
#: of :data:`clearsim.schema.JOINT_COLUMN_UNITS`; ``eps`` = |e|/c is dimensionless).
JOINT_CHANNELS: Dict[str, Tuple[Tuple[str, str], ...]] = {
    quantity: tuple((c, {**JOINT_COLUMN_UNITS, "eps": "1"}[c]) for c in columns) for quantity, columns in _JOINT_CHANNEL_COLUMNS.items()
}
#: Body quantity → the name of its error against the ideal mechanism (as in
#: :meth:`Result.error` and the reliability analysis).
ERROR_QUANTITIES: Dict[str, str] = {"position": "displacement", "velocity": "velocity", "acceleration": "acceleration"}
RELIABILITY_QUANTITIES: Tuple[str, ...] = tuple(ERROR_QUANTITIES.values())
_CHANNEL_OF = {"position": "states", "velocity": "states", "acceleration": "accelerations"}


@dataclass
class SimulationSettings:
    """The ``[simulation]`` table: the arguments of :meth:`Mechanism.simulate` (SI units).

    ``t_end`` [s] is given or ``t0 + cycles · period``; ``outputs`` lists the channels to
    store (already including those the outputs and the reliability analysis need).
    """

    t_end: float
    integrator: str = "auto"
    rtol: float = RTOL
    atol: float = ATOL
    t0: float = 0.0
    step: Optional[float] = None
    dt_out: Optional[float] = None
    h_max: Optional[float] = None
    h_min: Optional[float] = None
    max_steps: Optional[int] = None
    outputs: Tuple[str, ...] = ("states", "accelerations", "joints", "violation")
    cycles: Optional[float] = None
    period: Optional[float] = None

    def kwargs(self) -> Dict[str, Any]:
        """Keyword arguments of :meth:`Mechanism.simulate` (all but ``t_end``)."""
        out: Dict[str, Any] = {"integrator": self.integrator, "rtol": self.rtol, "atol": self.atol, "t0": self.t0}
        for name in ("step", "dt_out", "h_max", "h_min", "max_steps"):
            value = getattr(self, name)
            if value is not None:
                out[name] = value
        out["outputs"] = list(self.outputs)
        return out


@dataclass
class OutputSettings:
    """The ``[outputs]`` table: what ``clearsim run`` writes (CSV) and plots (PNG). ``points``:
    named body points whose motion (global x, y of each of ``quantities``) is written beside
    the bodies' and whose errors beside theirs; ``reactions``: store the ideal joints' forces and
    drivers' torques (``reactions.csv``, peaks in the summary)."""

    bodies: List[str] = field(default_factory=list)
    points: List[TrackedPoint] = field(default_factory=list)
    reactions: bool = True
    quantities: List[str] = field(default_factory=lambda: list(BODY_CHANNELS))
    components: List[str] = field(default_factory=lambda: list(COMPONENTS))
    joints: List[str] = field(default_factory=list)
    joint_quantities: List[str] = field(default_factory=lambda: ["eccentricity", "force"])
    ideal: bool = False
    csv: bool = True
    plots: bool = True


_SIM_KEYS = (
    "t_end", "cycles", "period", "t0", "integrator", "rtol", "atol", "step", "dt_out", "h_max", "h_min", "max_steps", "outputs",
)  # fmt: skip
_OUTPUT_KEYS = ("bodies", "points", "quantities", "components", "joints", "joint_quantities", "reactions", "ideal", "csv", "plots")
_POINT_KEYS = ("name", "body", "point")
_RELIABILITY_KEYS = ("body", "component", "bin_width", "omega", "t_start", "allowable")
def _drive_speed(m: Mechanism, order: Sequence[str] = ()) -> Optional[float]:
    """ω [rad/s] of the first constant-speed driver (in the file's ``order`` of names, else by
    name), if any."""
    drivers = {d["name"]: d for d in m.description()["drivers"]}
    for name in [n for n in order if n in drivers] + sorted(drivers):
        if drivers[name]["law"]["kind"] == "constant_speed":
            return float(drivers[name]["law"]["omega"])
    return None


def _simulation(b: _Builder, m: Mechanism, needed: Sequence[str]) -> SimulationSettings:
    t = b.top.table("simulation", _SIM_KEYS)
    if t is None:
        raise b.src.error((), "simulation", "missing table [simulation] (with t_end [s] or cycles)")
    t0 = t.number("t0", 0.0)
    cycles = t.number("cycles", None)
    period = t.number("period", None)
    if "t_end" in t:
        for key in ("cycles", "period"):
            if key in t:
                raise t.error(key, "invalid [simulation]: give t_end or cycles (× period), not both")
        t_end = t.number("t_end")
    elif cycles is not None:
        if period is None:
            omega = _drive_speed(m, b.drivers)
            if not omega:
                raise t.error("cycles", "invalid [simulation]: cycles needs period = ... [s] (no constant-speed driver to take it from)")
            period = 2 * math.pi / abs(omega)
        t_end = t0 + cycles * period
    else:
        raise t.error(None, "missing key 't_end' (or 'cycles') in [simulation]")
    extra = t.strings("outputs", [], choices=OUTPUTS)
    outputs = tuple(k for k in OUTPUTS if k in set(extra) | set(needed))
    sim = SimulationSettings(
        t_end=t_end, integrator=t.string("integrator", "auto"), rtol=t.number("rtol", RTOL), atol=t.number("atol", ATOL),
        t0=t0, step=t.number("step", None), dt_out=t.number("dt_out", None), h_max=t.number("h_max", None),
        h_min=t.number("h_min", None), max_steps=t.integer("max_steps", None), outputs=outputs, cycles=cycles, period=period,
    )  # fmt: skip
    try:
        _core.check_settings(m.run_settings(sim.t_end, **sim.kwargs()))  # the core's checks, located in the file
    except InputError as err:
        field = err.field if err.field in t else ("cycles" if err.field == "t_end" and cycles is not None else None)
        raise t.error(field, err.reason, err.value) from None
    return sim


def _outputs(b: _Builder, m: Mechanism) -> OutputSettings:
    t = b.top.table("outputs", _OUTPUT_KEYS) or Table(b.src, ("outputs",), {}, ())
    joints = m.clearance_joint_names
    out = OutputSettings(
        bodies=t.strings("bodies", [], choices=m.body_names),
        points=_points(t, m),
        reactions=t.boolean("reactions", True),
        quantities=t.strings("quantities", list(BODY_CHANNELS), choices=tuple(BODY_CHANNELS)),
        components=t.strings("components", list(COMPONENTS), choices=COMPONENTS),
        joints=t.strings("joints", list(joints), choices=joints),
        joint_quantities=t.strings("joint_quantities", ["eccentricity", "force"], choices=tuple(JOINT_CHANNELS)),
        ideal=t.boolean("ideal", bool(joints)),
        csv=t.boolean("csv", True),
        plots=t.boolean("plots", True),
    )
    return out



def _points(t: Table, m: Mechanism) -> List[TrackedPoint]:
    """``[outputs] points``: ``points = [{name = "tool", body = "coupler", point = [0.1, 0.02]}]``
    (or the same as ``[[outputs.points]]`` tables), each point [m] in its body's frame; names
    unique and not a body's or joint's (they head columns beside those)."""
    taken = set(m.body_names) | set(m.clearance_joint_names) | {j["name"] for j in m.description()["joints"]} | {d["name"] for d in m.description()["drivers"]}
    out: List[TrackedPoint] = []
    for k, entry in enumerate(t.array_of_tables("points", _POINT_KEYS)):
        try:
            name = entry.string("name")
            if not name or name in taken or any(p.name == name for p in out):
                why = "must not be empty" if not name else "is already the name of a body, joint or point"
                raise entry.error("name", f"invalid {dotted_key(entry.where, 'name')} = {name!r}: {why}", name)
            body = entry.string("body", choices=m.body_names)
            xy = entry.point("point")
            try:
                xy = check_point(xy, dotted_key(entry.where, "point"))
            except InputError as err:
                raise entry.error("point", err.reason, xy) from None
        except InputError as err:
            raise _at_inline_entry(t, k, err) from None
        # A point in mm or in the global frame: a warning located at its line.
        m.warn_output_point(body, xy, dotted_key(entry.where, "point"), lambda msg: str(_at_inline_entry(t, k, entry.error("point", msg))))
        out.append(TrackedPoint(name, body, xy))
    return out


def _at_inline_entry(t: Table, k: int, err: InputError) -> InputError:
    """``err`` located at entry ``k`` of an inline ``points = [{...}, {...}]`` array (the reader
    finds a key's first line in the table: entry 0's); as it is for ``[[outputs.points]]``."""
    lines = t.src.lines
    start = t.src.line(t.where, "points")
    if start is None or not re.match(r"\s*points\s*=\s*\[", lines[start - 1]) or getattr(err, "line", None) is None:
        return err
    depth, seen = 0, -1
    for n in range(start - 1, len(lines)):
        for ch in lines[n].split("#", 1)[0]:
            if ch == "{":
                depth += 1
                seen += depth == 1
                if depth == 1 and seen == k:
                    prefix = f"{t.src.path}:{getattr(err, 'line', None)}: "
                    reason = str(err)[len(prefix) :] if str(err).startswith(prefix) else str(err)
                    return InputError(f"{t.src.path}:{n + 1}: {reason}", field=err.field, value=err.value, file=str(t.src.path), line=n + 1)
            elif ch == "}":
                depth -= 1
            elif ch == "]" and depth == 0:
                return err
    return err
