"""What the ideal joints and drivers carry: the force and torque each exerts on its second body,
read by name (the core's ``reactions`` channel, ``Constraint::reaction`` in
rust/constraints/mod.rs, from the Lagrange multipliers λ; docs/physics.md §1, *Reactions*).

:class:`JointReactions` holds the methods of :class:`clearsim.Result` for them; a clearance
joint's force is its own reading (:meth:`clearsim.Result.joint_force`, the ``joints`` channel).
Their peaks are tracked at every integration step when the run asks (``simulate(extremes=[...,
"O2", "motor"])``: core monitors ``Target::Reaction``, located between steps on the dense output
like every extreme, rust/monitor/), so :meth:`JointReactions.reaction_summary` then does not
depend on ``dt_out``; without that it reads the stored outputs and says so (``tracked``: False).

Sign: the force and torque *on the second body* — ``body_b`` of a revolute or prismatic joint
(the journal of an ideal joint made from a clearance joint, the slider of a prismatic joint),
the driven body of a driver — in the global frame, counter-clockwise torques positive; the first
body (or the ground) takes the opposite.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .errors import InputError, check_choice
from .schema import POINT_MONITOR_COMPONENTS, REACTION_MONITOR_UNITS

#: A tracked extreme as :meth:`JointReactions._tracked` gives it: (max, t_max, min, t_min) [SI, s].
Tracked = Tuple[float, float, float, float]


def reaction_quantities(kind: str) -> List[Tuple[str, Optional[str]]]:
    """The (quantity, component) pairs tracked for an ideal joint or driver of ``kind``: a
    revolute joint's force (x, y and magnitude), a prismatic joint's also its couple, a driver's
    torque."""
    force = [("force", c) for c in POINT_MONITOR_COMPONENTS]
    return [("torque", None)] if kind == "driver" else force + ([("torque", None)] if kind == "prismatic" else [])


def reaction_monitors(k: int, kind: str, span: Dict[str, Any]) -> List[Dict[str, Any]]:
    """The core monitors (``constraint``: index ``k`` in the core's order, joints then drivers)
    that track the reaction of an ideal joint or driver of ``kind`` over ``span`` (the monitors'
    window and sampling)."""
    return [{"constraint": k, "quantity": q, **({"component": c} if c else {}), **span} for q, c in reaction_quantities(kind)]


class JointReactions:
    """Methods of :class:`clearsim.Result` for the reactions of its ideal joints and drivers
    (needs ``outputs=[..., "reactions"]``)."""

    joint_names: List[str]
    t: np.ndarray
    _raw: Dict[str, Any]
    description: Optional[Dict[str, Any]]

    def _channel(self, key: str, what: str) -> np.ndarray:  # pragma: no cover - Result's
        raise NotImplementedError

    def _tracked(self, match: Dict[str, Any], quantity: str) -> Optional[Tracked]:  # pragma: no cover - Result's
        raise NotImplementedError

    def _reaction_match(self, name: str, quantity: str, component: Optional[str]) -> Tuple[Dict[str, Any], str, str]:
        """The monitor fields, unit and words of the reaction ``quantity`` (``"force"`` of
        ``component`` x, y or magnitude (default), or ``"torque"``) of ideal joint or driver
        ``name`` (:meth:`clearsim.Result.extremes`)."""
        entries = self._constraints()
        k = [n for n, _ in entries].index(name)
        kind = entries[k][1]
        check_choice("quantity", quantity, [q for q, _ in reaction_quantities(kind)], f"(a {kind}'s reaction)")
        if quantity == "torque":
            if component is not None:
                raise InputError(f"invalid component = {component!r}: a {kind}'s torque has none (give component=None)", field="component", value=component)
            return {"constraint": k}, REACTION_MONITOR_UNITS["torque"], f"{name} torque"
        component = "magnitude" if component is None else component
        check_choice("component", component, list(POINT_MONITOR_COMPONENTS), "(a reaction force's)")
        return {"constraint": k, "component": component}, REACTION_MONITOR_UNITS["force"], f"{name} force.{component}"

    def _constraints(self) -> List[Tuple[str, str]]:
        """(name, kind) of every ideal joint (``revolute``, ``prismatic``) and driver
        (``driver``), in the order of the core's equations: the description's joints, then its
        drivers."""
        desc = self.description
        if desc is None:
            raise InputError("this result does not carry its mechanism (make it with Mechanism.simulate)", field="result", value=None)
        return [(j["name"], j["kind"]) for j in desc["joints"]] + [(d["name"], "driver") for d in desc["drivers"]]

    def _reaction(self, name: str, want: str) -> Tuple[np.ndarray, str]:
        """The (N, 3) reaction ``[fx, fy, torque]`` of the ideal joint or driver ``name`` and its
        kind; ``want`` ("joint" or "driver") words the error for an unknown name."""
        entries = self._constraints()
        names = [n for n, _ in entries]
        if name not in names:
            known = ", ".join(self.joint_names + [n for n, k in entries if k != "driver"]) if want == "joint" else ", ".join(n for n, k in entries if k == "driver")
            what = "joint (ideal or clearance)" if want == "joint" else "driver"
            raise InputError(f"invalid {want} = {name!r}: no such {what} (known: {known or 'none'})", field=want, value=name)
        k = names.index(name)
        return self._channel("reactions", "reactions")[:, k, :], entries[k][1]

    def ideal_joint_force(self, joint: str) -> np.ndarray:
        """(N, 2) force [N] the ideal (revolute or prismatic) joint ``joint`` exerts on its second
        body, global frame (see :meth:`clearsim.Result.joint_force`)."""
        values, kind = self._reaction(joint, "joint")
        if kind == "driver":
            raise InputError(f"invalid joint = {joint!r}: it is a driver, which exerts a torque: use driver_torque({joint!r})", field="joint", value=joint)
        return values[:, :2]

    def joint_torque(self, joint: str) -> np.ndarray:
        """(N,) couple [N m] an ideal joint exerts on its second body, counter-clockwise positive,
        besides its force through the joint's point: a prismatic joint's constraint torque (what
        keeps the slider from turning on its guide; the guide body takes the opposite), zero for a
        revolute joint. Needs ``outputs=[..., "reactions"]``. A clearance joint's moment is its
        friction torque (:meth:`clearsim.Result.friction_torque`)."""
        if joint in self.joint_names:
            raise InputError(f"invalid joint = {joint!r}: a clearance joint's moment is its friction torque: use friction_torque({joint!r})", field="joint", value=joint)
        values, kind = self._reaction(joint, "joint")
        if kind == "driver":
            raise InputError(f"invalid joint = {joint!r}: it is a driver: use driver_torque({joint!r})", field="joint", value=joint)
        return values[:, 2]

    def driver_torque(self, driver: str) -> np.ndarray:
        """(N,) torque [N m] the driver ``driver`` exerts on its driven body to hold the
        prescribed angle, counter-clockwise positive (−λ of its equation θ − f(t) = 0); the
        ground takes the opposite. Its power is this torque times the body's θ̇ (the ``driver``
        work of :meth:`clearsim.Result.energy`). Needs ``outputs=[..., "reactions"]``."""
        values, kind = self._reaction(driver, "driver")
        if kind != "driver":
            raise InputError(f"invalid driver = {driver!r}: it is a {kind} joint: use joint_force({driver!r})", field="driver", value=driver)
        return values[:, 2]

    def reaction_summary(self) -> Dict[str, Dict[str, Any]]:
        """The largest force of every joint and torque of every driver, each with its ``kind``
        (``clearance``, ``revolute``, ``prismatic``, ``driver``) and whether it was ``tracked``.

        Tracked (the run asked for it, ``simulate(extremes=[..., "A", "O2", "motor"])`` or
        ``extremes=True``; ``clearsim run`` does): at every integration step and between steps on
        the dense output, over the extremes' window from ``window_start`` [s] — independent of
        ``dt_out``. Per joint ``peak_force`` [N] (of |F|) and ``t_peak_force`` [s]; an ideal
        joint also ``max_fx``, ``min_fx``, ``max_fy``, ``min_fy`` [N] with their times
        (``t_max_fx``, ...); a driver ``peak_torque`` [N m] (signed: the value of largest
        magnitude) and ``t_peak_torque`` [s], with ``max_torque``, ``min_torque`` and their
        times; a prismatic joint also its couple's (``peak_torque`` of |T|, ``max_torque``, ...).

        Not tracked: the same peaks over the stored outputs (clearance joints from the ``joints``
        channel, ideal joints and drivers with ``"reactions"`` stored) — a finer ``dt_out`` can
        only raise them. Empty when nothing is tracked or stored."""
        out: Dict[str, Dict[str, Any]] = {}
        stored = len(self.t) > 0
        joints = self._raw.get("joints")
        for j, name in enumerate(self.joint_names):
            found = self._tracked({"coordinate": j}, "force")
            if found is not None:
                out[name] = {"kind": "clearance", "tracked": True, "peak_force": found[0], "t_peak_force": found[1], **self._window()}
            elif joints is not None and stored:  # a prismatic clearance joint: each slider end ("G front", "G rear")
                out[name] = {"kind": "clearance", "tracked": False, **_peak(np.hypot(joints[:, j, 4], joints[:, j, 5]), self.t, "force")}
        if self.description is None:
            return out
        reactions = self._raw.get("reactions") if stored else None
        for k, (name, kind) in enumerate(self._constraints()):
            entry = self._tracked_reaction(k, kind)
            if entry is not None:
                out[name] = {"kind": kind, "tracked": True, **entry, **self._window()}
            elif reactions is not None:
                r = reactions[:, k, :]
                if kind == "driver":
                    out[name] = {"kind": kind, "tracked": False, **_peak(r[:, 2], self.t, "torque", signed=True)}
                else:
                    out[name] = {"kind": kind, "tracked": False, **_peak(np.hypot(r[:, 0], r[:, 1]), self.t, "force")}
                    if kind == "prismatic":
                        out[name].update(_peak(np.abs(r[:, 2]), self.t, "torque"))
        return out

    def _window(self) -> Dict[str, Any]:
        """``window_start`` [s] of the tracked extremes (their monitors' start)."""
        specs: List[Dict[str, Any]] = getattr(self, "monitor_specs", [])
        starts = [float(s["t_start"]) for s in specs if s.get("exact")]
        return {"window_start": min(starts)} if starts else {}

    def _tracked_reaction(self, k: int, kind: str) -> Optional[Dict[str, Any]]:
        """The tracked peaks of constraint ``k`` (:meth:`reaction_summary`), or None if untracked."""
        entry: Dict[str, Any] = {}
        for quantity, component in reaction_quantities(kind):
            found = self._tracked({"constraint": k, **({"component": component} if component else {})}, quantity)
            if found is None:
                return None
            hi, t_hi, lo, t_lo = found
            if component == "magnitude":
                entry.update(peak_force=hi, t_peak_force=t_hi)
            elif quantity == "force":
                col = f"f{component}"
                entry.update({f"max_{col}": hi, f"t_max_{col}": t_hi, f"min_{col}": lo, f"t_min_{col}": t_lo})
            else:
                larger = abs(hi) >= abs(lo)
                peak = (hi if larger else lo) if kind == "driver" else max(abs(hi), abs(lo))
                entry.update(peak_torque=peak, t_peak_torque=t_hi if larger else t_lo, max_torque=hi, t_max_torque=t_hi, min_torque=lo, t_min_torque=t_lo)
        return entry


def _peak(values: np.ndarray, t: np.ndarray, what: str, signed: bool = False) -> Dict[str, Any]:
    """``{peak_<what>: value, t_peak_<what>: time}`` of the largest |value| (NaN outputs skipped)."""
    mag = np.where(np.isfinite(values), np.abs(values), -np.inf)
    k = int(np.argmax(mag))
    if not math.isfinite(float(mag[k])):
        return {f"peak_{what}": math.nan, f"t_peak_{what}": math.nan}
    return {f"peak_{what}": float(values[k]) if signed else float(mag[k]), f"t_peak_{what}": float(t[k])}


__all__ = ["JointReactions", "reaction_monitors", "reaction_quantities"]
