"""What the ideal joints and drivers carry: the force and torque each exerts on its second body,
read by name (the core's ``reactions`` channel, ``Constraint::reaction`` in
rust/constraints/mod.rs, from the Lagrange multipliers λ; docs/physics.md §1, *Reactions*).

:class:`JointReactions` holds the methods of :class:`clearsim.Result` for them; a clearance
joint's force is its own reading (:meth:`clearsim.Result.joint_force`, the ``joints`` channel).
Sign: the force and torque *on the second body* — ``body_b`` of a revolute or prismatic joint
(the journal of an ideal joint made from a clearance joint, the slider of a prismatic joint),
the driven body of a driver — in the global frame, counter-clockwise torques positive; the first
body (or the ground) takes the opposite.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .errors import InputError


class JointReactions:
    """Methods of :class:`clearsim.Result` for the reactions of its ideal joints and drivers
    (needs ``outputs=[..., "reactions"]``)."""

    joint_names: List[str]
    t: np.ndarray
    _raw: Dict[str, Any]
    description: Optional[Dict[str, Any]]

    def _channel(self, key: str, what: str) -> np.ndarray:  # pragma: no cover - Result's
        raise NotImplementedError

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
        """The largest force of every joint and torque of every driver over the stored outputs
        (not tracked between them: a finer ``dt_out`` can only raise a peak), each with its
        ``kind`` (``clearance``, ``revolute``, ``prismatic``, ``driver``): per joint
        ``peak_force`` [N] (of |F|) and ``t_peak_force`` [s] — clearance joints from the ``joints``
        channel, ideal joints with ``"reactions"`` stored (a prismatic joint also ``peak_torque``
        [N m], of |T|, and its time) — and per driver ``peak_torque`` [N m] (signed: the value of
        largest magnitude) and ``t_peak_torque`` [s]. Empty when nothing is stored or no output."""
        out: Dict[str, Dict[str, Any]] = {}
        if not len(self.t):
            return out
        joints = self._raw.get("joints")
        for j, name in enumerate(self.joint_names):
            if joints is not None:  # a prismatic clearance joint: each slider end ("G front", "G rear")
                out[name] = {"kind": "clearance", **_peak(np.hypot(joints[:, j, 4], joints[:, j, 5]), self.t, "force")}
        if "reactions" not in self._raw or self.description is None:
            return out
        for k, (name, kind) in enumerate(self._constraints()):
            r = self._raw["reactions"][:, k, :]
            if kind == "driver":
                out[name] = {"kind": kind, **_peak(r[:, 2], self.t, "torque", signed=True)}
            else:
                out[name] = {"kind": kind, **_peak(np.hypot(r[:, 0], r[:, 1]), self.t, "force")}
                if kind == "prismatic":
                    out[name].update(_peak(np.abs(r[:, 2]), self.t, "torque"))
        return out


def _peak(values: np.ndarray, t: np.ndarray, what: str, signed: bool = False) -> Dict[str, Any]:
    """``{peak_<what>: value, t_peak_<what>: time}`` of the largest |value| (NaN outputs skipped)."""
    mag = np.where(np.isfinite(values), np.abs(values), -np.inf)
    k = int(np.argmax(mag))
    if not math.isfinite(float(mag[k])):
        return {f"peak_{what}": math.nan, f"t_peak_{what}": math.nan}
    return {f"peak_{what}": float(values[k]) if signed else float(mag[k]), f"t_peak_{what}": float(t[k])}


__all__ = ["JointReactions"]
