"""Resolve the names by which a mechanism's elements refer to one another (a joint's bodies, a
driver's body, a load table's driver) into the indices of the Rust core's description, and back
(:func:`unresolve`, for a description the core hands back: the ideal counterpart).

This runs when the mechanism compiles (:meth:`clearsim.Mechanism.description`), not when an
element is added, so elements may be defined in any order. An unknown name is an
:class:`~clearsim.InputError` naming the element and its field, e.g. ``force 'gas'.value.driver``.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

from .errors import InputError

GROUND = "ground"

#: Per list of the description: the label of its elements and their fields naming a body
#: (field, ground allowed).
_BODY_FIELDS: Dict[str, List[Tuple[str, bool]]] = {
    "joints": [("body_a", True), ("body_b", True)],
    "drivers": [("body", False)],
    "clearance_joints": [("bearing_body", True), ("journal_body", True)],
    "prismatic_clearance_joints": [("guide_body", True), ("slider_body", False)],
}
#: A force element's kind → its label in messages and its body fields.
_FORCE_FIELDS: Dict[str, Tuple[str, List[Tuple[str, bool]]]] = {
    "spring_damper": ("spring", [("body_a", True), ("body_b", True)]),
    "rotational_spring_damper": ("rotational spring", [("body_a", True), ("body_b", True)]),
    "force": ("force", [("body", False)]),
    "torque": ("torque", [("body", False), ("reaction", True)]),
    "motor": ("motor", [("body", False), ("reaction", True)]),
}
#: A force element's load profiles (keys of its entry) that may be tables in a driver's angle.
_PROFILES = ("fx", "fy", "magnitude")


def label(group: str, entry: Dict[str, Any]) -> str:
    """How messages name an element: ``joint 'crank-rod'``, ``force 'gas'``, ..."""
    if group == "forces":
        kind = _FORCE_FIELDS.get(entry.get("kind", ""), ("force", []))[0]
    else:
        kind = {"joints": "joint", "drivers": "driver"}.get(group, "clearance joint")
    return f"{kind} '{entry.get('name', '?')}'"


def resolve(desc: Dict[str, Any]) -> Dict[str, Any]:
    """Replace body and driver names in ``desc`` (a deep copy: changed in place) by body indices
    (``None`` for the ground); fill a constant-speed driver's default ``angle0`` from its body's
    angle. Returns ``desc``."""
    names = [b["name"] for b in desc["bodies"]]
    index = {n: k for k, n in enumerate(names)}

    def body(where: str, name: Any, ground: bool) -> Optional[int]:
        if name == GROUND and ground:
            return None
        if name not in index:
            known = ", ".join((["ground"] if ground else []) + names) or "none"
            why = "the ground cannot be driven or slide" if name == GROUND else "no such body"
            raise InputError(f"invalid {where} = {name!r}: {why} (known: {known})", field=where, value=name)
        return index[name]

    for group, fields in _BODY_FIELDS.items():
        for entry in desc.get(group, []):
            for key, ground in fields:
                entry[key] = body(f"{label(group, entry)}.{key}", entry[key], ground)
    turned = {d["name"]: d["body"] for d in desc["drivers"]}  # driver → its body (resolved above)
    for entry in desc.get("forces", []):
        for key, ground in _FORCE_FIELDS[entry["kind"]][1]:
            if key in entry and not (key == "reaction" and entry[key] is None):
                entry[key] = body(f"{label('forces', entry)}.{key}", entry[key], ground)
        if entry["kind"] == "motor":
            turned[entry["name"]] = entry["body"]
    for entry in desc.get("forces", []):
        for key in _PROFILES:
            argument = (entry.get(key) or {}).get("argument") or {}
            if argument.get("kind") == "angle" and isinstance(argument.get("body"), str):  # a body by name (unresolve)
                argument["body"] = body(f"{label('forces', entry)}.{key}.argument.body", argument["body"], False)
            elif argument.get("kind") == "angle" and "driver" in argument:
                name = argument.pop("driver")
                if name not in turned:
                    known = ", ".join(turned) or "none"
                    where = f"{label('forces', entry)}.value.driver"
                    raise InputError(f"invalid {where} = {name!r}: no such driver or motor (known: {known})", field=where, value=name)
                argument["body"] = turned[name]
    for d in desc["drivers"]:
        law = d["law"]
        if law["kind"] == "constant_speed" and law.get("angle0") is None:
            law["angle0"] = float(desc["bodies"][d["body"]].get("angle", 0.0))
    return desc


def unresolve(desc: Dict[str, Any]) -> Dict[str, Any]:
    """The inverse of :func:`resolve` for a description the core hands back (its ideal
    counterpart, ``_core.idealize``): body indices in ``desc`` (changed in place) replaced by the
    bodies' names (``None``: ``"ground"``; a torque's or motor's ``reaction`` stays ``None``,
    which :func:`resolve` reads alike), a load table's angle argument naming its body. Returns
    ``desc``."""
    names = [b["name"] for b in desc["bodies"]]

    def name(i: Optional[int]) -> str:
        return GROUND if i is None else names[i]

    for group, fields in _BODY_FIELDS.items():
        for entry in desc.get(group, []):
            for key, _ in fields:
                entry[key] = name(entry[key])
    for entry in desc.get("forces", []):
        for key, _ in _FORCE_FIELDS[entry["kind"]][1]:
            if key in entry and not (key == "reaction" and entry[key] is None):
                entry[key] = name(entry[key])
        for key in _PROFILES:
            argument = (entry.get(key) or {}).get("argument") or {}
            if argument.get("kind") == "angle":
                argument["body"] = name(argument["body"])
    return desc


__all__ = ["GROUND", "label", "resolve", "unresolve"]
