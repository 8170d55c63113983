"""The result of a run: numpy arrays on the output grid (SI units)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core, display, plausibility
from .errors import InputError, check_choice
from .dynamics.readings import DynamicsReadings
from .joint_reactions import JointReactions, Tracked, reaction_monitors
from .joint_readings import JointReadings
from .points import PointsLike, TrackedPoint, check_point, point_motion, tracked_points
from .schema import BODY_QUANTITY_UNITS, COMPONENTS as _COMPONENTS, JOINT_COLUMNS, JOINT_MONITOR_UNITS, POINT_MONITOR_COMPONENTS, READING_MONITOR_UNITS

_COL = {name: k for k, name in enumerate(JOINT_COLUMNS)}
CONTACT_STATES = {0: "free or film", 1: "transition", 2: "contact"}

# What Result.extremes reports, per body (each of x, y, theta) and per clearance joint, with the
# units (clearsim.schema): BODY_QUANTITY_UNITS (x and y | theta), the joint's JOINT_MONITOR_UNITS,
# and the bearing readings a run tracks at every lubricated joint, READING_MONITOR_UNITS
# (clearsim.joint_readings; film_thickness there is the reading h = c − |e|).


@dataclass(frozen=True)
class Extremes:
    """The largest and smallest value of one quantity over a run and when they occur
    (:meth:`Result.extremes`): tracked at every integration step, not read off the stored
    outputs, so they do not depend on the output grid."""

    max: float
    t_max: float  # [s]
    min: float
    t_min: float  # [s]
    quantity: str
    unit: str

    def __str__(self) -> str:
        u = "" if self.unit == "1" else f" {self.unit}"  # a ratio (e/c) has no unit to write
        return f"{self.quantity}: max {self.max:.6g}{u} at t = {self.t_max:.6g} s, min {self.min:.6g}{u} at t = {self.t_min:.6g} s"


def extreme_monitors(
    which: Union[bool, Sequence[Any]],
    body_names: Sequence[str],
    joint_names: Sequence[str],
    t0: float,
    t_end: float,
    constraints: Sequence[Tuple[str, str]] = (),
) -> List[Dict[str, Any]]:
    """The core monitors (rust/monitor/, ``exact``) that track :meth:`Result.extremes` of the
    bodies, clearance joints and ideal joints or drivers (``constraints``: (name, kind) in the
    core's order) named in ``which`` (``True``: all of them), and of the points given there as
    ``(body, (x, y))`` (body frame [m]), over [t0, t_end] [s]."""
    if not t_end > t0:
        raise InputError(f"invalid extremes_from = {t0!r}: must be before t_end = {t_end!r} [s]", field="extremes_from", value=t0)
    held = [n for n, _ in constraints]
    names = list(body_names) + list(joint_names) + held if which is True else ([] if which is False else list(which))
    known = ", ".join(list(body_names) + list(joint_names) + held)
    for name in names:
        if isinstance(name, (tuple, list)):
            if len(name) != 2 or name[0] not in body_names:
                raise InputError(f"invalid extremes = {name!r}: a point is (body, (x, y)) on one of the bodies ({', '.join(body_names)})", field="extremes", value=name)
            check_point(name[1], "extremes")
        elif not isinstance(name, str) or (name not in body_names and name not in joint_names and name not in held):
            raise InputError(f"invalid extremes = {name!r}: no such body, joint or driver (known: {known}); a point is (body, (x, y))", field="extremes", value=name)
    # Four samples a step screen it for extremes (the step's ends are exact, the searches find
    # what lies between): the same extremes as eight to round-off, at a third less cost.
    span = {"t_start": t0, "bin_width": t_end - t0, "exact": True, "samples_per_step": 4}
    out: List[Dict[str, Any]] = []
    seen = set()
    for name in names:
        key = (name[0], check_point(name[1], "extremes")) if isinstance(name, (tuple, list)) else name
        if key in seen:
            continue
        seen.add(key)
        if isinstance(key, tuple):
            b = list(body_names).index(key[0])
            out += [{"body": b, "point": list(key[1]), "component": c, "quantity": q, **span} for c in POINT_MONITOR_COMPONENTS for q in BODY_QUANTITY_UNITS]
        elif key in body_names:
            b = list(body_names).index(key)
            out += [{"coordinate": 3 * b + c, "quantity": q, **span} for c in range(3) for q in BODY_QUANTITY_UNITS]
        elif key in held:
            k = held.index(key)
            out += reaction_monitors(k, constraints[k][1], span)
        else:
            j = list(joint_names).index(key)
            out += [{"coordinate": j, "quantity": q, **span} for q in (*JOINT_MONITOR_UNITS, *READING_MONITOR_UNITS)]
    return out


class Result(JointReadings, JointReactions, DynamicsReadings):
    """Outputs of one simulation.

    Attributes
    ----------
    t:
        Output times [s], shape (N,).
    stats:
        ``integrator`` (the method used, ``"auto"`` resolved), ``steps``, ``rejected_steps``,
        ``steps_to_switch`` (steps redone so as to end where a contact starts or ends or
        the friction ramp turns),
        ``rhs_evaluations``, ``jacobians`` (Newton / Jacobian matrices built by the stiff
        methods), ``force_evaluations`` (evaluations of the clearance joints' force laws by every
        part of the run: right-hand sides, Newton matrices, outputs, tracked readings; a count of
        work for ``benches/perf_fingerprint.py``), ``min_step``, ``max_step`` [s],
        ``t_reached`` [s], ``wall_time`` [s].
    impacts:
        Number of impacts located per clearance joint.
    failure:
        The :class:`clearsim.SimulationError` that ended the run early, or ``None``.
    """

    def __init__(self, raw: Dict[str, Any], body_names: List[str], joint_names: List[str]) -> None:
        self._raw = raw
        self.body_names = list(body_names)
        self.joint_names = list(joint_names)
        self.t: np.ndarray = raw["t"]
        self.stats: Dict[str, Any] = dict(raw["stats"])
        self.impacts: Dict[str, int] = dict(zip(self.joint_names, raw.get("impacts", [])))
        self.failure = raw.get("error")
        self.q0: np.ndarray = raw["q0"]
        self.qd0: np.ndarray = raw["qd0"]
        self._given: Optional[Dict[str, Any]] = None  # the mechanism's description, bodies named
        self._read: Optional[Dict[str, Any]] = None
        #: The monitors the run was given (its settings' ``monitors``); set by Mechanism.simulate.
        self.monitor_specs: List[Dict[str, Any]] = []
        #: Named body points (:class:`clearsim.points.TrackedPoint`) that :meth:`plot_mechanism`,
        #: :meth:`animate`, :meth:`to_pandas` and :meth:`save` show when given no ``points``: a
        #: scene's ``[outputs] points`` (set by its run); empty otherwise.
        self.tracked_points: List[TrackedPoint] = []

    @property
    def description(self) -> Optional[Dict[str, Any]]:
        """The mechanism's description as the core read it (plain data: bodies by index, the
        ground ``None``, every default filled in; ``_core.resolve``), for drawings, readings and
        exports; ``None`` for a result made without its mechanism. Set by ``Mechanism.simulate``
        with the mechanism's own description (bodies by name), read by the core on first use."""
        if self._read is None and self._given is not None:
            self._read = _core.resolve(self._given)
        return self._read

    @description.setter
    def description(self, value: Optional[Dict[str, Any]]) -> None:
        self._given, self._read = value, None

    def __repr__(self) -> str:
        status = "complete" if self.failure is None else f"stopped early: {self.failure}"
        steps = f"{self.stats.get('integrator', '?')} in {self.stats.get('steps', 0)} steps"
        bearings = self.bearing_summary() if self.bearings_tracked else {}
        films = "".join(f", {j}: h_min {b['min_film_thickness'] * 1e6:.3g} µm, mean loss {b['mean_power_loss']:.3g} W" for j, b in bearings.items())
        return f"<clearsim.Result {len(self.t)} outputs, t ∈ [{self.t[0] if len(self.t) else 0:g}, {self.t[-1] if len(self.t) else 0:g}] s, {steps}{films}, {status}>"

    def _repr_html_(self) -> str:
        s = self.summary()
        t = f"[{self.t[0]:.6g}, {self.t[-1]:.6g}] s" if len(self.t) else "none"
        rows = [("outputs", f"{s['outputs']}, t ∈ {t}"), ("integrator", s.get("integrator", "?")),
                ("steps", f"{s.get('steps', 0)} ({s.get('rejected_steps', 0)} rejected)"), ("wall time [s]", s.get("wall_time", math.nan)),
                ("impacts", ", ".join(f"{j}: {n}" for j, n in self.impacts.items()) or "–")]  # fmt: skip
        if "max_constraint_violation" in s:
            rows.append(("max ‖Φ‖ [m]", s["max_constraint_violation"]))
        for joint, b in s.get("bearings", {}).items():
            rows.append((f"{joint}: min film [µm], peak / mean loss [W]", f"{b['min_film_thickness'] * 1e6:.4g} at t = {b['t_min_film']:.6g} s, {b['peak_power_loss']:.4g} / {b['mean_power_loss']:.4g}"))
        rows.append(("status", "complete" if self.failure is None else f"stopped early: {self.failure}"))
        return display.table("clearsim.Result", rows)

    @property
    def completed(self) -> bool:
        return self.failure is None

    # ------------------------------------------------------------------ access helpers
    def _channel(self, key: str, what: str) -> np.ndarray:
        if key not in self._raw:
            raise InputError(f"invalid output = {what!r}: this run did not store it (pass outputs=[..., {what!r}])", field="outputs", value=what)
        return self._raw[key]

    def _body(self, body: str) -> int:
        try:
            return self.body_names.index(body)
        except ValueError:
            raise InputError(f"invalid body = {body!r}: no such body (known: {', '.join(self.body_names)})", field="body", value=body) from None

    def _joint(self, joint: str) -> int:
        try:
            return self.joint_names.index(joint)
        except ValueError:
            known = ", ".join(self.joint_names) or "none"
            raise InputError(f"invalid joint = {joint!r}: no such clearance joint (known: {known})", field="joint", value=joint) from None

    # ------------------------------------------------------------------ bodies
    def position(self, body: str) -> np.ndarray:
        """(N, 3) array of x [m], y [m], θ [rad] of the body's centroid."""
        k = self._body(body)
        return self._channel("q", "states")[:, 3 * k : 3 * k + 3]

    def velocity(self, body: str) -> np.ndarray:
        """(N, 3) array of ẋ, ẏ [m/s], θ̇ [rad/s]."""
        k = self._body(body)
        return self._channel("qd", "states")[:, 3 * k : 3 * k + 3]

    def acceleration(self, body: str) -> np.ndarray:
        """(N, 3) array of ẍ, ÿ [m/s²], θ̈ [rad/s²] (from the KKT solve at each output time)."""
        k = self._body(body)
        return self._channel("qdd", "accelerations")[:, 3 * k : 3 * k + 3]

    @property
    def reactions(self) -> np.ndarray:
        """(N, rows) Lagrange multipliers λ (needs ``outputs=[..., "reactions"]``), one column per
        constraint equation in the order of docs/physics.md §1, *Reactions*; by name and in
        newtons: :meth:`joint_force`, :meth:`joint_torque`, :meth:`driver_torque`."""
        return self._channel("lambda", "reactions")

    def energy(self) -> Dict[str, np.ndarray]:
        """Energy bookkeeping [J] at each output (needs ``outputs=[..., "energy"]``;
        docs/physics.md §10.5).

        Stored: ``kinetic``, ``gravity`` (−Σ m g·r), ``spring`` (elastic energy of the springs).
        Work done on the mechanism since t0, integrated along every accepted step (not from the
        stored outputs): ``load`` (applied forces and torques), ``motor``, ``driver`` (the
        prescribed-motion drivers), ``damper`` (≤ 0), ``contact`` (normal contact and film
        forces of the clearance joints) and ``friction`` (≤ 0). Derived: ``dissipated``
        = −(damper + contact + friction) and ``balance`` = kinetic + gravity + spring − Σ work,
        constant up to the integration error and the work of the constraint stabilisation.
        """
        e = self._channel("energy", "energy")
        out = {name: e[:, k] for k, name in enumerate(_core.ENERGY_COLUMNS)}
        out["dissipated"] = -(out["damper"] + out["contact"] + out["friction"])
        out["balance"] = e[:, :3].sum(axis=1) - e[:, 3:].sum(axis=1)
        return out

    def wear(self, joint: str, surface: str = "bearing") -> Tuple[np.ndarray, np.ndarray]:
        """Archard wear of a clearance joint whose :class:`Dry` law has ``wear=Archard(...)``
        (docs/physics.md §12): ``(angle, depth)``, the bin centres [rad] counter-clockwise from
        the ``surface``'s body x axis (``"bearing"`` or ``"journal"``) and the worn depth [m]
        there, accumulated over the run (integrated along every step, not from the outputs)."""
        if surface not in ("bearing", "journal"):
            raise InputError(f"invalid surface = {surface!r}: must be 'bearing' or 'journal'", field="surface", value=surface)
        k = self._joint(joint)
        books = self._raw.get("wear") or []
        book = books[k] if k < len(books) else None
        if book is None:
            raise InputError(f"invalid joint = {joint!r}: its dry law models no wear (give Dry(wear=clearsim.Archard(...)))", field="joint", value=joint)
        depth = np.asarray(book[surface])
        angle = (np.arange(len(depth)) + 0.5) * (2 * np.pi / len(depth))
        return angle, depth

    def wear_volume(self, joint: str) -> float:
        """Total worn volume of a joint [m³] (see :meth:`wear`)."""
        self.wear(joint)
        return float(self._raw["wear"][self._joint(joint)]["volume"])

    @property
    def constraint_violation(self) -> np.ndarray:
        """(N,) ‖Φ‖₂ of the constraint equations at each output [m, rad]."""
        return self._channel("violation", "violation")[:, 0]

    @property
    def velocity_violation(self) -> np.ndarray:
        """(N,) ‖Φ̇‖₂ at each output."""
        return self._channel("violation", "violation")[:, 1]

    # ------------------------------------------------------------------ clearance joints
    def _joint_cols(self, joint: str, cols: List[str]) -> np.ndarray:
        j = self._joint(joint)
        data = self._channel("joints", "joints")
        return data[:, j, [_COL[c] for c in cols]]

    def eccentricity(self, joint: str) -> np.ndarray:
        """(N, 2) eccentricity vector e = r_Pj − r_Pi [m] (journal centre relative to the
        bearing centre, global frame). Divide by the clearance for the orbit in units of c."""
        return self._joint_cols(joint, ["ex", "ey"])

    def eccentricity_rate(self, joint: str) -> np.ndarray:
        """(N, 2) ė [m/s]."""
        return self._joint_cols(joint, ["ex_dot", "ey_dot"])

    def joint_force(self, joint: str) -> np.ndarray:
        """(N, 2) force [N] the joint exerts on its second body, global frame; the first body (or
        the ground) takes the opposite (docs/physics.md §1, *Reactions*). A clearance joint: its
        total force on the journal (contact, friction, film), stored by default. An ideal joint
        (needs ``outputs=[..., "reactions"]``): a revolute joint's force on ``body_b`` at its
        point (an ideal joint made from a clearance joint: on the journal, as the clearance
        joint's); a prismatic joint's normal force on the slider (``body_b``), perpendicular to
        the guide, at the slider's point, whose couple is :meth:`joint_torque`. A driver's torque
        is :meth:`driver_torque`."""
        if joint in self.joint_names:
            return self._joint_cols(joint, ["fx", "fy"])
        return self.ideal_joint_force(joint)

    def contact_force(self, joint: str) -> np.ndarray:
        """(N, 2) dry normal force F_N and friction force F_t [N] (before the transition blend)."""
        return self._joint_cols(joint, ["normal", "tangential"])

    def film_force(self, joint: str) -> np.ndarray:
        """(N, 2) film force components (F_ξ along n, F_η along t) [N] (before the blend)."""
        return self._joint_cols(joint, ["film_xi", "film_eta"])

    def contact_state(self, joint: str) -> np.ndarray:
        """(N,) int: 0 free flight or film, 1 film-to-contact transition band, 2 contact."""
        return self._joint_cols(joint, ["state"])[:, 0].astype(int)

    def dry_weight(self, joint: str) -> np.ndarray:
        """(N,) weight of the dry law in the transition blend (P18)."""
        return self._joint_cols(joint, ["w_dry"])[:, 0]

    def error(self, ideal: "Result", body: str, quantity: str = "displacement", point: Optional[Sequence[float]] = None) -> np.ndarray:
        """Error of a body's motion against the ideal mechanism's run on the same output grid
        (docs/physics.md §5), over the outputs both runs have: without ``point``, the (N, 3)
        error of the body's centroid and angle, this response minus the ideal one for
        ``quantity`` = ``"displacement"`` [m, m, rad], ``"velocity"`` [m/s, m/s, rad/s] or
        ``"acceleration"`` [m/s², m/s², rad/s²]; with ``point=(x, y)`` [m] (in the body's frame,
        as joints take theirs), the (N, 2) error of that point's global x, y [m, m/s or m/s²]
        (:meth:`point`)."""
        check_choice("quantity", quantity, list(BODY_QUANTITY_UNITS))
        n = min(len(self.t), len(ideal.t))
        if not np.allclose(self.t[:n], ideal.t[:n], rtol=0, atol=1e-12 * (1 + abs(float(self.t[n - 1])) if n else 1)):
            raise InputError("invalid ideal: it was not run on the same output grid", field="ideal", value=ideal)
        if point is not None:
            return self.point(body, point, quantity)[:n] - ideal.point(body, point, quantity)[:n]
        getters = {"displacement": Result.position, "velocity": Result.velocity, "acceleration": Result.acceleration}
        get = getters[quantity]
        return get(self, body)[:n] - get(ideal, body)[:n]

    # ------------------------------------------------------------------ points
    def point(self, body: str, point: Sequence[float], quantity: str = "displacement") -> np.ndarray:
        """(N, 2) global motion of the point ``point`` = (x, y) [m] fixed on ``body`` (in the
        body's frame, as joints take theirs), from the stored outputs: ``quantity``
        ``"displacement"`` its position r + A p [m], ``"velocity"`` ṙ + θ̇ B p [m/s] or
        ``"acceleration"`` r̈ + θ̈ B p − θ̇² A p [m/s²] (A the body's rotation, B p = A p turned
        +90°; docs/physics.md §5, *Points*). ``point=(0, 0)`` is the centroid. Needs the
        ``"states"`` output, and ``"accelerations"`` for the acceleration (both stored by default)."""
        check_choice("quantity", quantity, list(BODY_QUANTITY_UNITS))
        k = self._body(body)
        self._check_output_point(body, point)
        cols = slice(3 * k, 3 * k + 3)
        pose = self._channel("q", "states")[:, cols]
        rate = self._channel("qd", "states")[:, cols] if quantity != "displacement" else None
        accel = self._channel("qdd", "accelerations")[:, cols] if quantity == "acceleration" else None
        return point_motion(pose, rate, accel, point, quantity)  # type: ignore[arg-type]

    def _check_output_point(self, body: str, point: Sequence[float]) -> None:
        """A :class:`~clearsim.PlausibilityWarning` (once per result and point) if ``point``
        looks given in mm or in the global frame (:func:`clearsim.plausibility.output_point_findings`)."""
        if self.description is None:
            return
        xy = check_point(point, "point")
        warned: set = self.__dict__.setdefault("_warned_points", set())
        if (body, xy) not in warned:
            warned.add((body, xy))
            plausibility.warn_new(plausibility.output_point_findings(self.description, body, xy, "point"), set())

    def errors_table(self, ideal: "Result", bodies: Optional[Sequence[str]] = None, points: Optional[PointsLike] = None, quantities: Optional[Sequence[str]] = None) -> Any:
        """The errors against the ideal run ``ideal`` (:meth:`error`) as a pandas DataFrame
        indexed by time ``t`` [s]: per body in ``bodies`` (default: every body, unless ``points``
        are given) the columns ``<body>.<quantity>_error.<x|y|theta>``, per named point of
        ``points`` (``{"tool": ("coupler", (0.1, 0.02))}``, body frame [m]) the columns
        ``<name>.<quantity>_error.<x|y>``, for each ``quantity`` (default ``"displacement"``,
        ``"velocity"`` and ``"acceleration"``); ``df.attrs["units"]`` gives each column's unit.
        The same columns as ``clearsim run``'s ``errors.csv``. Needs pandas
        (``pip install 'clearsim[io]'``)."""
        from . import export

        return export.errors_table(self, ideal, bodies, points, quantities)

    # ------------------------------------------------------------------ extremes
    def extremes(self, name: str, quantity: str, component: Optional[str] = None, point: Optional[Sequence[float]] = None) -> Extremes:
        """Largest and smallest value of a body's ``quantity`` (``"displacement"``,
        ``"velocity"`` or ``"acceleration"`` of ``component`` ``"x"``, ``"y"`` or ``"theta"``),
        of a point's on a body (``point=(x, y)``, body frame [m]: its global ``"x"``, ``"y"`` or
        the ``"magnitude"`` of its displacement, velocity or acceleration vector, m, m/s, m/s²)
        of an ideal joint's or driver's reaction on its second body (``"force"``, ``component``
        ``"x"``, ``"y"`` or ``"magnitude"`` (default) [N], global frame; ``"torque"`` of a driver
        or prismatic joint [N m]; :meth:`reaction_summary`)
        or of a clearance joint's (``"eccentricity"`` ratio e/c, ``"force"`` on the journal,
        ``"contact_force"`` F_N, ``"film_force"``, magnitudes [N]; ``"film_thickness"`` [m], the
        reading h = c − |e| (not a study's window minimum c (1 − ε_max), :data:`clearsim.schema.JOINT_QUANTITY_UNITS`),
        ``"friction_torque"`` on the journal [N m], ``"power_loss"`` [W]) and their times [s], over the run.

        Tracked at every accepted integration step and located between steps on the exact
        quantity (accelerations from the KKT solve, as stored; docs/performance.md, "Peaks"), so
        they are independent of ``dt_out`` and at least every stored output. The run must ask for
        them: ``simulate(..., extremes=["slider", "pin", "O2", "motor", ("crank", (0.05, 0.0))])`` (or
        ``extremes=True`` for every body, joint and driver), over the whole run or from ``extremes_from``
        [s] on (e.g. the last revolution).
        """
        match: Dict[str, Any]
        if point is not None:
            if name not in self.body_names:
                raise InputError(f"invalid name = {name!r}: a point lies on a body (known: {', '.join(self.body_names)})", field="name", value=name)
            check_choice("quantity", quantity, list(BODY_QUANTITY_UNITS))
            check_choice("component", component, list(POINT_MONITOR_COMPONENTS), "(a point's)")
            at = list(check_point(point, "point"))
            match = {"body": self.body_names.index(name), "point": at, "component": component}
            unit = BODY_QUANTITY_UNITS[quantity][0]
            what = f"{name} ({at[0]:g}, {at[1]:g}).{component} {quantity}"
            asked = f"({name!r}, ({at[0]:g}, {at[1]:g}))"
        elif name in self.body_names:
            check_choice("quantity", quantity, list(BODY_QUANTITY_UNITS))
            check_choice("component", component, list(_COMPONENTS), "(a body's quantity has three)")
            c = _COMPONENTS.index(str(component))
            match = {"coordinate": 3 * self.body_names.index(name) + c}
            unit = BODY_QUANTITY_UNITS[quantity][c == 2]
            what, asked = f"{name}.{component} {quantity}", repr(name)
        elif name in self.joint_names:
            check_choice("quantity", quantity, list(JOINT_MONITOR_UNITS) + list(READING_MONITOR_UNITS))
            if component is not None:
                raise InputError(f"invalid component = {component!r}: a joint's {quantity} has none (give component=None)", field="component", value=component)
            match = {"coordinate": self.joint_names.index(name)}
            unit = {**JOINT_MONITOR_UNITS, **READING_MONITOR_UNITS}[quantity]
            what, asked = f"{name} {quantity}", repr(name)
        elif self.description is not None and name in [n for n, _ in self._constraints()]:
            match, unit, what = self._reaction_match(name, quantity, component)
            asked = repr(name)
        else:
            held = [n for n, _ in self._constraints()] if self.description is not None else []
            known = ", ".join(self.body_names + self.joint_names + held)
            raise InputError(f"invalid name = {name!r}: no such body, joint or driver (known: {known})", field="name", value=name)
        found = self._tracked(match, quantity)
        if found is not None:
            return Extremes(*found, what, unit)
        raise InputError(
            f"invalid name = {name!r}: this run did not track its extremes (pass extremes=[{asked}] or extremes=True to simulate)", field="name", value=name
        )

    def _tracked(self, match: Dict[str, Any], quantity: str) -> Optional[Tracked]:
        """(max, t_max, min, t_min) of the exact monitor of ``quantity`` whose spec has the fields
        of ``match`` (a point's only when ``match`` names one), or None if the run did not track it."""
        results = self._raw.get("monitors") or []
        for spec, found in zip(self.monitor_specs, results):
            if spec.get("exact") and spec["quantity"] == quantity and not spec.get("reference") and all(spec.get(k) == v for k, v in match.items()):
                if "point" in spec and "point" not in match or "constraint" in spec and "constraint" not in match:
                    continue
                return float(found["max"]), float(found["t_max"]), float(found["min"]), float(found["t_min"])
        return None

    # ------------------------------------------------------------------ data out
    def plot_mechanism(self, t: float, *, magnify: Optional[float] = None, ax: Any = None, points: Optional[PointsLike] = None, trace: bool = False) -> Any:
        """A figure of the mechanism at time ``t`` [s] of the run (positions interpolated
        between stored outputs), clearances magnified (``magnify``; default: the largest
        clearance drawn at 2 % of the mechanism's size, the factor written beside each joint).
        ``points`` (``{"tool": ("coupler", (0.1, 0.02))}``, body frame [m]; default: the
        :attr:`tracked_points`, a scene's ``[outputs] points``) are marked and named; with
        ``trace=True`` each one's path over the whole run is drawn too (from every stored output)."""
        from . import draw, draw_points

        self._need_description()
        named = self._points(points)
        if trace and not named:
            raise InputError("invalid trace = True: no points to trace (give points={name: (body, (x, y))})", field="trace", value=trace)
        q = draw.states_at(self, np.array([float(t)]))[0]
        marks = (lambda a: draw_points.add_to_pose(a, self, q, named, trace)) if named else None
        return draw.plot_pose(self.description, q, magnify=magnify, t=float(t), ax=ax, marks=marks)  # type: ignore[arg-type]

    def _points(self, points: Optional[PointsLike]) -> List[TrackedPoint]:
        """The named points of ``points``, checked, or the :attr:`tracked_points` when ``None``."""
        return list(self.tracked_points) if points is None else tracked_points(points, self.body_names)

    def animate(self, path: Any, *, speed: float = 1.0, magnify: Optional[float] = None, fps: int = 25, points: Optional[PointsLike] = None, **kwargs: Any) -> Any:
        """Animate the run into ``path`` (``.gif``, or ``.mp4`` with ffmpeg) at ``speed`` × real
        time, clearances magnified, with each clearance joint's journal orbit in an inset
        (:func:`clearsim.draw.animate`); ``points`` (as :meth:`plot_mechanism`) are marked and
        draw their path as the run goes. Returns the path."""
        from . import draw

        self._need_description()
        kwargs["points"] = self._points(points)
        return draw.animate(self, path, speed=speed, magnify=magnify, fps=fps, **kwargs)

    def _need_description(self) -> None:
        if self.description is None:
            raise InputError("this result does not carry its mechanism (make it with Mechanism.simulate)", field="result", value=None)

    def to_pandas(self, points: Optional[PointsLike] = None) -> Any:
        """A pandas DataFrame indexed by time ``t`` [s], one column per stored output
        (``slider9.y`` [m], ``slider9.y_dot`` [m/s], ``A.ex`` [m], ...; with ``"reactions"``
        stored, each ideal joint's ``fx``, ``fy`` [N] (a prismatic one also ``torque`` [N m]) and
        each driver's ``torque`` [N m], as :meth:`joint_force`), and per named point of
        ``points`` (``{"tool": ("coupler", (0.1, 0.02))}``) ``tool.x``, ``tool.x_dot``,
        ``tool.x_ddot``, ... (:meth:`point`); ``df.attrs["units"]`` gives the units. Errors
        against an ideal run: :meth:`errors_table`. Needs pandas (``pip install 'clearsim[io]'``)."""
        from . import export

        return export.to_pandas(self, self._points(points))

    def to_xarray(self) -> Any:
        """An xarray Dataset over ``time`` [s] with ``position``/``velocity``/``acceleration``
        on (time, body, coordinate), the clearance-joint quantities and the constraint violation,
        units and long names as attributes. Needs xarray (``pip install 'clearsim[io]'``)."""
        from . import export

        return export.to_xarray(self)

    def save(self, path: Any, points: Optional[PointsLike] = None) -> Any:
        """Write to ``.csv`` (units in the column names; the columns of :meth:`to_pandas`, with
        ``points`` as there) or ``.nc`` (NetCDF, via xarray; no points); returns the path."""
        from . import export

        return export.save(self, path, self._points(points))

    def summary(self) -> Dict[str, Any]:
        out: Dict[str, Any] = dict(self.stats)
        out["outputs"] = int(len(self.t))
        out["impacts"] = dict(self.impacts)
        if "violation" in self._raw and len(self.t):
            out["max_constraint_violation"] = float(np.max(self.constraint_violation))
        # The bearing summary when the run tracked it (simulate(..., bearings=True)).
        bearings = self.bearing_summary() if self.bearings_tracked else {}
        if bearings:
            out["bearings"] = bearings
        reactions = self.reaction_summary()
        if reactions:
            out["reactions"] = reactions
        out["failure"] = None if self.failure is None else str(self.failure)
        return out


