"""Building a scene file's Mechanism entry by entry (:mod:`clearsim.scene`), every error located
at its file, line and key."""

from __future__ import annotations

import dataclasses
import math
import re
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from ..errors import InputError
from ..forces import Harmonic
from ..joints import Archard, Dry, Lubricated, Thermal, Vogel
from ..mechanism import Mechanism
from ..schema import INTERPOLATIONS
from .toml_reader import REQUIRED, Source, Table, dotted_key

_FORCE_KEYS = {
    "spring": ("type", "name", "body_a", "point_a", "body_b", "point_b", "stiffness", "damping", "free_length", "force_table"),
    "rotational_spring": ("type", "name", "body_a", "body_b", "stiffness", "damping", "angle0"),
    "force": ("type", "name", "body", "point", "value", "frame"),
    "torque": ("type", "name", "body", "value", "reaction"),
    "motor": ("type", "name", "body", "stall_torque", "no_load_speed", "angle0", "reaction"),
}
_MECHANISM_KEYS = ("name", "description", "gravity", "baumgarte")
_BODY_KEYS = ("name", "mass", "inertia", "position", "angle", "ends", "velocity")
_JOINT_KEYS = {"revolute": ("type", "name", "bodies", "points"), "prismatic": ("type", "name", "bodies", "points", "axis")}
_DRIVER_KEYS = ("name", "body", "omega", "rpm", "angle0", "polynomial", "times", "angles", "harmonic")
#: The keys of a harmonic load or driver law (clearsim.Harmonic): offset + amplitude cos(omega t + phase).
_HARMONIC_KEYS = ("amplitude", "omega", "phase", "offset")
_PRISMATIC_CLEARANCE_KEYS = (
    "type", "name", "guide_body", "guide_point", "slider_body", "axis", "clearance", "slider_length", "corner_radius", "model", "dry",
)  # fmt: skip
_CLEARANCE_KEYS = (
    "type", "name", "bearing_body", "bearing_point", "journal_body", "journal_point",
    "journal_radius", "clearance", "initial_eccentricity", "model", "dry", "lubricated",
)  # fmt: skip
# Builder field → scene key, for errors raised by Mechanism methods.
_FIELD_KEYS = {"body_a": "bodies", "body_b": "bodies", "point_a": "points", "point_b": "points", "driver": None}
# How error messages name an element (the core's rust/names.rs, label) → its scene table.
_ELEMENT_KINDS = {"clearance joint": "clearance_joint", "revolute": "joint", "prismatic": "joint", "spring": "force", "rotational spring": "force", "torque": "force", "motor": "force"}


#: What a lubricated joint's table must give (Lubricated's defaults of them are the paper's bearing).
_FILM_REQUIRED = ("viscosity", "length")


def _model_fields(cls: type) -> Tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(cls))


def _named(owner: str, err: InputError) -> str:
    """``err``'s reason with its field named as the element's (``invalid viscosity = -0.2`` →
    ``invalid clearance joint 'A'.viscosity = -0.2``): the model is built before its joint."""
    head = f"invalid {err.field} ="
    return f"invalid {owner}.{err.reason[len('invalid '):]}" if err.field and err.reason.startswith(head) else err.reason


def _read_model(table: Table, cls: type, owner: str) -> Any:
    """A :class:`Dry` or :class:`Lubricated` from a sub-table using the dataclass's field names;
    ``owner`` names it in errors (``clearance joint 'A'``)."""
    kwargs: Dict[str, Any] = {}
    for f in dataclasses.fields(cls):
        if f.name not in table:
            continue
        if f.name == "dry":
            sub = table.table("dry", _model_fields(Dry))
            assert sub is not None
            kwargs["dry"] = _read_model(sub, Dry, f"{owner}.dry")
        elif f.name == "wear":
            sub = table.table("wear", ("coefficient", "hardness", "length", "feedback"))
            assert sub is not None
            try:
                kwargs["wear"] = Archard(sub.number("coefficient"), sub.number("hardness"), sub.number("length"), sub.boolean("feedback", False))
            except InputError as err:
                raise sub.error((err.field or "").split(".")[-1] or None, err.reason, err.value) from None
        elif f.name == "viscosity" and isinstance(table.data.get("viscosity"), dict):
            sub = table.table("viscosity", ("vogel",))
            assert sub is not None
            try:
                kwargs["viscosity"] = Vogel(*sub.numbers("vogel", length=3))
            except InputError as err:
                raise sub.error("vogel", err.reason, err.value) from None
        elif f.name == "thermal":
            sub = table.table("thermal", _model_fields(Thermal))
            assert sub is not None
            try:
                kwargs["thermal"] = Thermal(sub.number("ambient"), sub.number("heat_capacity"), sub.number("heat_transfer"), sub.number("initial", None))
            except InputError as err:
                raise sub.error((err.field or "").split(".")[-1] or None, err.reason, err.value) from None
        elif isinstance(f.default, str):
            kwargs[f.name] = table.string(f.name)
        else:
            kwargs[f.name] = table.number(f.name)
    try:
        return cls(**kwargs)
    except InputError as err:
        raise table.error(err.field or None, _named(owner, err), err.value) from None


class _Builder:
    """Builds the Mechanism of a scene, entry by entry, locating every error in the file."""

    def __init__(self, src: Source, top: Table) -> None:
        self.src = src
        self.top = top
        self.entries: Dict[Tuple[str, str], Table] = {}  # (kind, name) → its table
        self.drivers: List[str] = []  # the drivers' names in the order of the file
        self.mechanism_table = top.table("mechanism", _MECHANISM_KEYS) or Table(src, ("mechanism",), {}, ())

    def call(self, table: Table, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        """``fn(*args, **kwargs)``, with an InputError relocated to ``table``'s key."""
        try:
            return fn(*args, **kwargs)
        except InputError as err:
            raise self.relocate(err, table) from None

    def relocate(self, err: InputError, table: Optional[Table]) -> InputError:
        """``err`` (raised by the builder or the Rust core) with the file and line."""
        fld = getattr(err, "field", "") or ""
        m = re.match(r"^(body|clearance joint|joint|driver|revolute|prismatic|force|spring|rotational spring|torque|motor) '([^']*)'\.(.+)$", fld)
        if m:
            kind = _ELEMENT_KINDS.get(m.group(1), m.group(1))
            table = self.entries.get((kind, m.group(2)), table)
            fld = m.group(3)
        parts = [re.sub(r"\[\d+\]$", "", p) for p in fld.split(".")] if fld else []
        while table is not None and len(parts) > 1 and isinstance(table.data.get(parts[0]), dict):  # a nested table: model.normal_law
            table, parts = table.table(parts[0], tuple(table.data[parts[0]])), parts[1:]
        if table is not None and parts and parts[-1] not in table.data:  # a model's field, named by the core without "model."
            table = next((table.table(k, tuple(v)) for k, v in table.data.items() if isinstance(v, dict) and parts[-1] in v), table)
        # The deepest part that is a key of the table (value.driver → value), else the last.
        key = next((p for p in reversed(parts) if table is not None and p in table.data), parts[-1] if parts else None)
        key = key if key is None or (table is not None and key in table.data) else _FIELD_KEYS.get(key, key)
        if table is None:
            return InputError(f"{self.src.path}: {err.reason}", field=err.field, value=err.value, file=str(self.src.path), line=None)
        return table.error(key, err.reason, err.value)

    def build(self) -> Mechanism:
        top = self.top
        mech_t = self.mechanism_table
        kwargs = {k: mech_t.point(k) for k in ("gravity", "baumgarte") if k in mech_t}
        m: Mechanism = self.call(mech_t, Mechanism, **kwargs)
        for t in top.array_of_tables("body", _BODY_KEYS):
            self.body(m, t)
        for t in top.array_of_tables("joint", sorted(set(_JOINT_KEYS["revolute"]) | set(_JOINT_KEYS["prismatic"]))):
            self._add("joint", m, self.joint, t)
        for t in top.array_of_tables("driver", _DRIVER_KEYS):
            self._add("driver", m, self.driver, t)
        for t in top.array_of_tables("clearance_joint", sorted(set(_CLEARANCE_KEYS) | set(_PRISMATIC_CLEARANCE_KEYS))):
            self._add("clearance_joint", m, self.clearance_joint, t)
        all_keys = sorted({k for keys in _FORCE_KEYS.values() for k in keys})
        for t in top.array_of_tables("force", all_keys):
            self._add("force", m, self.force_element, t)
        return m

    def _harmonic(self, table: Table) -> Harmonic:
        """``{amplitude = ..., omega = ..., phase = ..., offset = ...}`` (phase, offset default 0)."""
        return self.call(
            table, Harmonic, table.number("amplitude"), table.number("omega"), table.number("phase", 0.0), table.number("offset", 0.0)
        )

    def _load(self, t: Table, key: str, columns: Sequence[str]) -> Any:
        """A load: a number, a pair, an inline table (see :mod:`clearsim.forces`), or a harmonic
        ``{amplitude = ..., omega = ...}`` (a force: a pair whose components are numbers or such
        tables)."""
        value = t._get(key, REQUIRED)
        if isinstance(value, dict) and ("amplitude" in value or "omega" in value):
            sub = t.table(key, _HARMONIC_KEYS)
            assert sub is not None
            return self._harmonic(sub)
        if isinstance(value, list) and len(value) == 2 and any(isinstance(v, dict) for v in value) and columns != ("torque",):
            return tuple(
                self._harmonic(Table(t.src, t.where + (key, k), v, _HARMONIC_KEYS)) if isinstance(v, dict) else t._as_number(key, v)
                for k, v in enumerate(value)
            )
        if isinstance(value, dict):
            sub = t.table(key, ("t", "driver", "angle", "period", "interpolation", *columns))
            assert sub is not None
            out: Dict[str, Any] = {k: sub.numbers(k) for k in ("t", "angle", *columns) if k in sub}
            if "driver" in sub:
                out["driver"] = sub.string("driver")
            if "interpolation" in sub:
                out["interpolation"] = sub.string("interpolation", choices=INTERPOLATIONS)
            if "period" in sub:
                out["period"] = sub.number("period")
            return out
        return t.number(key) if columns == ("torque",) else t.point(key)

    def force_element(self, m: Mechanism, t: Table) -> None:
        kind = t.string("type", choices=tuple(_FORCE_KEYS))
        for key in t.data:
            if key not in _FORCE_KEYS[kind]:
                raise t.error(key, f"unknown key '{key}' in a {kind} [[force]] (known: {', '.join(_FORCE_KEYS[kind])})", t.data[key])
        name = t.string("name", None)
        self._register("force", name, t)
        if kind == "spring":
            table = None
            if "force_table" in t:
                sub = t.table("force_table", ("deflection", "force"))
                assert sub is not None
                table = {"deflection": sub.numbers("deflection"), "force": sub.numbers("force")}
            self.call(
                t, m.spring, t.string("body_a"), t.point("point_a"), t.string("body_b"), t.point("point_b"),
                t.number("stiffness", None), t.number("damping", 0.0), t.number("free_length", None), name, force_table=table,
            )  # fmt: skip
        elif kind == "rotational_spring":
            self.call(t, m.rotational_spring, t.string("body_a"), t.string("body_b"), t.number("stiffness"), t.number("damping", 0.0), t.number("angle0", None), name)
        elif kind == "force":
            self.call(t, m.force, t.string("body"), t.point("point", [0.0, 0.0]), self._load(t, "value", ("fx", "fy")), t.string("frame", "global"), name)
        elif kind == "torque":
            self.call(t, m.torque, t.string("body"), self._load(t, "value", ("torque",)), name, reaction=t.string("reaction", None))
        else:
            self.call(
                t, m.motor, t.string("body"), t.number("stall_torque"), t.number("no_load_speed"), t.number("angle0", None), name,
                reaction=t.string("reaction", "ground"),
            )  # fmt: skip

    def _register(self, kind: str, name: Optional[str], table: Table) -> None:
        if name is not None:
            self.entries[(kind, name)] = table

    def _add(self, kind: str, m: Mechanism, add: Callable[[Mechanism, Table], None], table: Table) -> None:
        """``add(m, table)``, then register the entry under the name the mechanism gave it
        (unnamed ones too), so an error found when the mechanism compiles points at its table."""
        before = set(m._names)
        add(m, table)
        for name in set(m._names) - before:
            self.entries.setdefault((kind, name), table)
            if kind == "driver":
                self.drivers.append(name)

    def body(self, m: Mechanism, t: Table) -> None:
        name = t.string("name")
        self._register("body", name, t)
        if "ends" in t:
            for key in ("position", "angle"):
                if key in t:
                    raise t.error(key, f"[[body]] '{name}': give either ends or position/angle, not both")
            where: Dict[str, Any] = {"ends": tuple(t.points("ends", 2))}
        else:
            where = {"position": t.point("position", [0.0, 0.0]), "angle": t.number("angle", 0.0)}
        self.call(
            t, m.add_body, name, mass=t.number("mass"), inertia=t.number("inertia"),
            velocity=t.numbers("velocity", None, length=3), **where,
        )  # fmt: skip

    def joint(self, m: Mechanism, t: Table) -> None:
        kind = t.string("type", choices=tuple(_JOINT_KEYS))
        for key in t.data:
            if key not in _JOINT_KEYS[kind]:
                raise t.error(key, f"unknown key '{key}' in a {kind} [[joint]] (known: {', '.join(_JOINT_KEYS[kind])})", t.data[key])
        name = t.string("name", None)
        self._register("joint", name, t)
        bodies = t.strings("bodies")
        if len(bodies) != 2:
            raise t.error("bodies", f"invalid {dotted_key(t.where, 'bodies')} = {bodies!r}: must name two bodies", bodies)
        (pa, pb) = t.points("points", 2)
        extra = {"axis": t.point("axis")} if "axis" in t else {}
        fn = m.revolute if kind == "revolute" else m.prismatic
        self.call(t, fn, bodies[0], pa, bodies[1], pb, name=name, **extra)

    def driver(self, m: Mechanism, t: Table) -> None:
        name = t.string("name", None)
        self._register("driver", name, t)
        body = t.string("body")
        if "rpm" in t:
            if "omega" in t:
                raise t.error("rpm", "invalid [[driver]]: give omega [rad/s] or rpm, not both")
            omega: Optional[float] = t.number("rpm") * 2 * math.pi / 60.0
        else:
            omega = t.number("omega", None)
        harmonic = t.table("harmonic", _HARMONIC_KEYS)
        kwargs = dict(
            omega=omega, angle0=t.number("angle0", None), polynomial=t.numbers("polynomial", None),
            times=t.numbers("times", None), angles=t.numbers("angles", None), name=name,
            law=None if harmonic is None else self._harmonic(harmonic),
        )  # fmt: skip
        self.call(t, m.driver, body, **kwargs)

    def clearance_joint(self, m: Mechanism, t: Table) -> None:
        kind = t.string("type", "revolute", choices=("revolute", "prismatic"))
        known = _CLEARANCE_KEYS if kind == "revolute" else _PRISMATIC_CLEARANCE_KEYS
        for key in t.data:
            if key not in known:
                raise t.error(key, f"unknown key '{key}' in a {kind} [[clearance_joint]] (known: {', '.join(known)})", t.data[key])
        name = t.string("name")
        self._register("clearance_joint", name, t)
        if kind == "prismatic":
            t.string("model", "dry", choices=("dry",))
            sub = t.table("dry", _model_fields(Dry))
            model = Dry() if sub is None else _read_model(sub, Dry, f"clearance joint '{name}'")
            self.call(
                t, m.prismatic_clearance, t.string("guide_body"), t.point("guide_point"), t.string("slider_body"), t.point("axis"),
                t.number("clearance"), t.number("slider_length"), model, name, corner_radius=t.number("corner_radius", 1e-3),
            )  # fmt: skip
            return
        kind = t.string("model", "dry", choices=("dry", "lubricated"))
        other = "lubricated" if kind == "dry" else "dry"
        if other in t:
            raise t.error(other, f"[clearance_joint.{other}] given but model = {kind!r} (set model = {other!r} or remove the table)")
        sub = t.table(kind, _model_fields(Dry if kind == "dry" else Lubricated))
        if kind == "lubricated":
            # A film is defined by its bearing's length and its oil: no default stands in for them.
            if sub is None:
                raise t.error("model", f"missing table [clearance_joint.lubricated] of clearance joint '{name}': its viscosity [Pa s] and length [m] define the film", kind)
            for key in _FILM_REQUIRED:
                if key not in sub:
                    sub.number(key)  # raises the missing key, named with the table's file and line
        model = (Dry() if kind == "dry" else Lubricated()) if sub is None else _read_model(sub, Dry if kind == "dry" else Lubricated, f"clearance joint '{name}'")
        self.call(
            t, m.clearance_joint, name, t.string("bearing_body"), t.point("bearing_point"),
            t.string("journal_body"), t.point("journal_point"), journal_radius=t.number("journal_radius"),
            clearance=t.number("clearance"), model=model, initial_eccentricity=t.point("initial_eccentricity", [0.0, 0.0]),
        )  # fmt: skip
