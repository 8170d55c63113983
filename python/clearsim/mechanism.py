"""Describing a planar mechanism: :class:`Mechanism` collects bodies, ideal joints, drivers,
clearance joints and force elements as plain data, kept in name order, each element checked by
the core as it is added (``_core.check_element``: its own values; the names it refers to are
resolved when the mechanism compiles, so elements may come in any order). Running it is
:mod:`clearsim.running`'s job, mixed in: ``simulate`` compiles it in the Rust core and
integrates it there with the GIL released.
SI units throughout: metres, kilograms, seconds, radians.
"""

from __future__ import annotations

import bisect
import copy
import math
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import forces as _forces
from . import _core, plausibility
from .errors import ClearsimError, InputError, SimulationError, check_finite
from .joints import Dry, Lubricated
from .running import DEFAULT_OUTPUTS, INTEGRATORS, MAX_OUTPUTS, OUTPUTS, RunOptions, Running  # noqa: F401 (re-exported)

GROUND = "ground"
Point = Sequence[float]


def _point(field: str, p: Any) -> List[float]:
    try:
        seq = list(p)
    except TypeError:
        raise InputError(f"invalid {field} = {p!r}: must be a pair (x, y)", field=field, value=p) from None
    if len(seq) != 2:
        raise InputError(f"invalid {field} = {p!r}: must be a pair (x, y)", field=field, value=p)
    return [check_finite(f"{field}[0]", seq[0]), check_finite(f"{field}[1]", seq[1])]




#: The defaults of ``add_body``'s position and angle (compared by identity to tell "not given").
_ORIGIN: Point = (0.0, 0.0)
_NO_ANGLE = float("0.0")


class Mechanism(Running):
    """A planar mechanism of rigid bodies.

    Parameters
    ----------
    gravity:
        Gravitational acceleration (g_x, g_y) [m/s²]; ``(0, 0)`` for none.
    baumgarte:
        Baumgarte stabilisation coefficients (α, β) [1/s] of P26 (default 50, 50).

    Example
    -------
    >>> m = Mechanism(gravity=(0, -9.81))
    >>> m.add_body("link", mass=1.0, inertia=0.01, position=(0.1, 0.0))
    >>> m.revolute("ground", (0, 0), "link", (-0.1, 0))
    >>> res = m.simulate(0.5, dt_out=1e-3)
    """

    def __init__(self, gravity: Point = (0.0, -9.81), baumgarte: Tuple[float, float] = (50.0, 50.0)) -> None:
        self._gravity = _point("gravity", gravity)
        self._baumgarte = _point("baumgarte", baumgarte)
        self._bodies: List[Dict[str, Any]] = []
        self._index: Dict[str, int] = {}
        self._joints: List[Dict[str, Any]] = []
        self._drivers: List[Dict[str, Any]] = []
        self._clearance: List[Dict[str, Any]] = []
        self._forces: List[Dict[str, Any]] = []
        self._prismatic_clearance: List[Dict[str, Any]] = []
        self._names: set = set()
        self._motor_angles: Dict[str, float] = {}  # body → angle0 of a motor on it (applied when the body is added)
        self._warned: set = set()  # plausibility findings warned already (clearsim.plausibility)
        self._compiled: Any = None
        self._plain: Optional[Dict[str, Any]] = None  # the description, built once per change

    def __repr__(self) -> str:
        joints = ", ".join(f"{name} {c['kind']}" for name, c in self.contacts().items())
        counts = [(len(self._bodies), "body", "bodies"), (len(self._joints), "joint", "joints"), (len(self._drivers), "driver", "drivers"),
                  (len(self._forces), "force element", "force elements")]  # fmt: skip
        parts = [f"{n} {one if n == 1 else many}" for n, one, many in counts if n or one == "body"]
        parts.append(f"clearance joints: {joints}" if joints else "no clearance joint")
        return f"<clearsim.Mechanism {', '.join(parts)}>"

    def _repr_png_(self) -> Optional[bytes]:
        """The mechanism drawn at t = 0 (for notebooks); ``None`` (text instead) if it does not assemble."""
        from . import display

        try:
            from matplotlib.figure import Figure

            fig = Figure(figsize=(5.0, 3.6), layout="constrained")
            self.plot(0.0, ax=fig.add_subplot(1, 1, 1))
            return display.png(fig)
        except Exception:  # noqa: BLE001 — a picture is optional: the text repr stands in
            return None

    def __deepcopy__(self, memo: Dict[int, Any]) -> "Mechanism":
        # The compiled Rust model cannot be copied (nor pickled); a copy recompiles on demand.
        new = self.__class__.__new__(self.__class__)
        memo[id(self)] = new
        for key, value in self.__dict__.items():
            setattr(new, key, None if key == "_compiled" else copy.deepcopy(value, memo))
        return new

    @property
    def gravity(self) -> List[float]:
        """Gravitational acceleration (g_x, g_y) [m/s²]."""
        return list(self._gravity)

    @gravity.setter
    def gravity(self, value: Point) -> None:
        self._gravity = _point("gravity", value)
        self._changed()

    @property
    def baumgarte(self) -> List[float]:
        """Baumgarte stabilisation coefficients (α, β) [1/s]."""
        return list(self._baumgarte)

    @baumgarte.setter
    def baumgarte(self, value: Point) -> None:
        self._baumgarte = _point("baumgarte", value)
        self._changed()

    def _explain(self, group: str, entry: Dict[str, Any]) -> None:
        """Before the InputError of an element refused as it is added: the core's plausibility
        findings of the mechanism with it (a journal radius in mm, which put its film out of
        range), so that the warning naming the cause comes before the error it caused."""
        trial = dict(self._description())
        trial[group] = [*trial.get(group, []), entry]
        try:
            found = _core.findings(trial)
        except ClearsimError:
            return
        plausibility.warn_new(found, self._warned)

    def _changed(self) -> None:
        """Forget what was derived from the elements: the description and the compiled model."""
        self._compiled = None
        self._plain = None

    def __getstate__(self) -> Dict[str, Any]:
        # Pickling keeps the description; the compiled Rust model is rebuilt on demand.
        state = dict(self.__dict__)
        state["_compiled"] = None
        return state

    def __setstate__(self, state: Dict[str, Any]) -> None:
        state.setdefault("_forces", [])
        state.setdefault("_prismatic_clearance", [])
        state.setdefault("_motor_angles", {})
        state.setdefault("_warned", set())
        state.setdefault("_plain", None)
        for key in ("gravity", "baumgarte"):  # pickled before they were properties
            if key in state:
                state[f"_{key}"] = state.pop(key)
        self.__dict__.update(state)

    # ------------------------------------------------------------------ building
    def add_body(
        self,
        name: str,
        *,
        mass: float,
        inertia: float,
        position: Point = _ORIGIN,
        angle: float = _NO_ANGLE,
        velocity: Optional[Sequence[float]] = None,
        ends: Optional[Tuple[Point, Point]] = None,
    ) -> "Mechanism":
        """Add a rigid body with its reference point at the centroid.

        ``mass`` [kg] and ``inertia`` (about the centroid) [kg m²] must be positive.
        ``position`` [m] and ``angle`` [rad] (default the origin and 0) are approximate: the
        kinematic assembly at t = 0 makes them satisfy the joints (a run from t0 > 0 follows the
        drivers on from there). For a link, ``ends=((x1, y1),
        (x2, y2))`` [m] instead puts the centroid at mid-length and the angle along the line from
        the first end to the second (not together with ``position``/``angle``). ``velocity``
        (ẋ, ẏ, θ̇) is an optional guess, projected onto the constraints (drivers fix what they
        drive).
        """
        if ends is not None:
            for key, value, default in (("position", position, _ORIGIN), ("angle", angle, _NO_ANGLE)):
                if value is not default:  # given: the defaults are these very objects
                    raise InputError(
                        f"invalid body '{name}'.{key} = {value!r}: give either ends or position/angle, not both",
                        field=f"body '{name}'.{key}",
                        value=value,
                    )
            try:
                p, q = (_point(f"body '{name}'.ends[{k}]", e) for k, e in enumerate(ends))
            except (TypeError, ValueError):
                raise InputError(f"invalid body '{name}'.ends = {ends!r}: must be two points ((x1, y1), (x2, y2)) [m]", field=f"body '{name}'.ends", value=ends) from None
            if p == q:
                raise InputError(f"invalid body '{name}'.ends = {ends!r}: the two ends coincide", field=f"body '{name}'.ends", value=ends)
            position = ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
            angle = math.atan2(q[1] - p[1], q[0] - p[0])
        # Names are checked here, not only in the core: elements refer to bodies by name until the
        # core resolves them when the mechanism compiles, so a name must be unique and not "ground".
        if not isinstance(name, str) or not name:
            raise InputError(f"invalid body name = {name!r}: must be a non-empty string", field="name", value=name)
        if name == GROUND:
            raise InputError("invalid body name = 'ground': reserved for the fixed frame", field="name", value=name)
        if name in self._index:
            raise InputError(f"invalid body name = {name!r}: a body of that name exists already", field="name", value=name)
        body = {
            "name": name,
            # Numbers become floats here; their ranges (mass > 0, ...) are the core's checks
            # (rust/compile/validate.rs), made as the body is added.
            "mass": check_finite(f"body '{name}'.mass", mass),
            "inertia": check_finite(f"body '{name}'.inertia", inertia),
            "position": _point(f"body '{name}'.position", position),
            "angle": check_finite(f"body '{name}'.angle", angle),
        }
        if name in self._motor_angles:  # a motor added before its body sets its start angle
            body["angle"] = self._motor_angles[name]
        if velocity is not None:
            v = list(velocity)
            if len(v) != 3:
                raise InputError(f"invalid body '{name}'.velocity = {velocity!r}: must be (vx, vy, omega)", field=f"body '{name}'.velocity", value=velocity)
            body["velocity"] = [check_finite(f"body '{name}'.velocity[{k}]", x) for k, x in enumerate(v)]
        _core.check_element("bodies", body)
        _insert(self._bodies, body)
        self._index = {b["name"]: k for k, b in enumerate(self._bodies)}
        self._changed()
        return self

    def _body(self, field: str, name: str, allow_ground: bool = True) -> Optional[int]:
        if name == GROUND and allow_ground:
            return None
        if name not in self._index:
            known = ", ".join(self._index) or "none yet"
            raise InputError(f"invalid {field} = {name!r}: no such body (known: {known})", field=field, value=name)
        return self._index[name]

    def _ref(self, field: str, name: Any, allow_ground: bool = True) -> str:
        """A reference to a body by name, checked for its type now and resolved by the core when
        the mechanism compiles (``rust/names.rs``): bodies may be added later."""
        if not isinstance(name, str) or not name:
            raise InputError(f"invalid {field} = {name!r}: must be a body's name", field=field, value=name)
        if name == GROUND and not allow_ground:
            raise InputError(f"invalid {field} = 'ground': must be a moving body", field=field, value=name)
        return name

    def _new_name(self, kind: str, name: Optional[str]) -> str:
        if name is None:
            k = 1
            while f"{kind}{k}" in self._names:
                k += 1
            name = f"{kind}{k}"
        if not isinstance(name, str) or not name:
            raise InputError(f"invalid {kind} name = {name!r}: must be a non-empty string", field="name", value=name)
        if name in self._names:
            raise InputError(f"invalid {kind} name = {name!r}: a joint or driver of that name exists already", field="name", value=name)
        return name

    def _add(self, group: str, entries: List[Dict[str, Any]], entry: Dict[str, Any]) -> "Mechanism":
        """Add ``entry`` to the description list ``group`` (``entries``), once the core has
        checked its values (``_core.check_element``): a bad value is an :class:`InputError` at
        the call that gives it."""
        _core.check_element(group, entry)
        self._names.add(entry["name"])
        _insert(entries, entry)
        self._changed()
        return self

    def revolute(self, body_a: str, point_a: Point, body_b: str, point_b: Point, name: Optional[str] = None) -> "Mechanism":
        """Ideal revolute joint: ``point_a`` of ``body_a`` coincides with ``point_b`` of ``body_b``.

        Points are in the body's frame (from its centroid, at angle 0) [m]; on ``"ground"`` they
        are global coordinates.
        """
        a = self._ref("body_a", body_a)
        b = self._ref("body_b", body_b)
        entry = {"kind": "revolute", "name": self._new_name("revolute", name), "body_a": a, "point_a": _point("point_a", point_a), "body_b": b, "point_b": _point("point_b", point_b)}
        return self._add("joints", self._joints, entry)

    def prismatic(
        self,
        body_a: str,
        point_a: Point,
        body_b: str,
        point_b: Point,
        axis: Point = (1.0, 0.0),
        name: Optional[str] = None,
    ) -> "Mechanism":
        """Ideal prismatic (translational) joint: ``point_b`` of ``body_b`` (the slider) moves on
        the line through ``point_a`` of ``body_a`` (the guide, may be ``"ground"``) with direction
        ``axis`` (in body a's frame); the relative angle stays at its initial value."""
        a = self._ref("body_a", body_a)
        b = self._ref("body_b", body_b, allow_ground=False)
        ax = _point("axis", axis)
        entry = {"kind": "prismatic", "name": self._new_name("prismatic", name), "body_a": a, "point_a": _point("point_a", point_a), "axis": ax, "body_b": b,
                 "point_b": _point("point_b", point_b)}  # fmt: skip
        return self._add("joints", self._joints, entry)

    def driver(
        self,
        body: str,
        omega: Optional[float] = None,
        angle0: Optional[float] = None,
        *,
        polynomial: Optional[Sequence[float]] = None,
        times: Optional[Sequence[float]] = None,
        angles: Optional[Sequence[float]] = None,
        law: Optional[_forces.Harmonic] = None,
        name: Optional[str] = None,
    ) -> "Mechanism":
        """Drive a body's angle: θ = angle0 + ω t (``omega`` [rad/s]; ``angle0`` [rad] defaults
        to the body's angle), or θ = Σ cₖ tᵏ (``polynomial``), or θ sampled at ``times`` and
        interpolated by a natural cubic spline (``times``, ``angles``), or θ =
        offset + amplitude · cos(ω t + phase) (``law=clearsim.Harmonic(...)``, angles in rad)."""
        b = self._ref("body", body, allow_ground=False)
        given = sum(x is not None for x in (omega, polynomial, times, law))
        if given != 1:
            raise InputError(
                "invalid driver: give exactly one of omega, polynomial, times/angles or law", field="driver", value=body
            )
        if law is not None:
            if not isinstance(law, _forces.Harmonic):
                raise InputError(f"invalid law = {law!r}: must be a clearsim.Harmonic", field="law", value=law)
            entry: Dict[str, Any] = law.entry()
        elif omega is not None:
            # angle0 None: the body's angle, filled in when the mechanism compiles (the core's names.rs)
            entry = {"kind": "constant_speed", "omega": check_finite("omega", omega), "angle0": None if angle0 is None else check_finite("angle0", angle0)}
        elif polynomial is not None:
            entry = {"kind": "polynomial", "coefficients": [check_finite(f"polynomial[{k}]", c) for k, c in enumerate(polynomial)]}
        else:
            if angles is None:
                raise InputError("invalid angles = None: needed with times", field="angles", value=None)
            entry = {
                "kind": "samples",
                "times": [check_finite(f"times[{k}]", c) for k, c in enumerate(times)],  # type: ignore[arg-type]
                "angles": [check_finite(f"angles[{k}]", c) for k, c in enumerate(angles)],
            }
        return self._add("drivers", self._drivers, {"name": self._new_name("driver", name), "body": b, "law": entry})

    def clearance_joint(
        self,
        name: str,
        bearing_body: str,
        bearing_point: Point,
        journal_body: str,
        journal_point: Point,
        *,
        journal_radius: float,
        clearance: float,
        model: Union[Dry, Lubricated, None] = None,
        initial_eccentricity: Point = (0.0, 0.0),
    ) -> "Mechanism":
        """A revolute joint with radial clearance (docs/physics.md §2).

        The bearing (hole, radius R_j + c) is centred at ``bearing_point`` of ``bearing_body``;
        the journal (pin, radius ``journal_radius`` R_j [m]) at ``journal_point`` of
        ``journal_body``. ``clearance`` c = R_b − R_j [m]. ``model`` is :class:`Dry` (default)
        or :class:`Lubricated`. The journal starts at ``initial_eccentricity`` (global vector
        e = r_Pj − r_Pi [m]); (0, 0) is centred.
        """
        i = self._ref("bearing_body", bearing_body)
        j = self._ref("journal_body", journal_body)
        r_j = check_finite(f"clearance joint '{name}'.journal_radius", journal_radius)
        c = check_finite(f"clearance joint '{name}'.clearance", clearance)
        e_init = _point(f"clearance joint '{name}'.initial_eccentricity", initial_eccentricity)
        model = Dry() if model is None else model
        # The model object becomes plain data here: only a Dry or Lubricated can (serde carries dicts).
        if not isinstance(model, (Dry, Lubricated)):
            raise InputError(f"invalid model = {model!r}: must be clearsim.Dry(...) or clearsim.Lubricated(...)", field="model", value=model)
        entry = {
            "name": self._new_name("clearance", name),
            "bearing_body": i,
            "bearing_point": _point("bearing_point", bearing_point),
            "journal_body": j,
            "journal_point": _point("journal_point", journal_point),
            "journal_radius": r_j,
            "clearance": c,
            "model": model._as_dict(),
            "initial_eccentricity": e_init,
        }
        try:
            _core.check_element("clearance_joints", entry)  # invalid sizes: an InputError here
        except InputError:
            self._explain("clearance_joints", entry)
            raise
        # Valid but implausible (a unit slip, a film outside its laws' range): PlausibilityWarning.
        plausibility.warn_new(plausibility.joint_findings(name, r_j, c, model._as_dict()), self._warned)
        if isinstance(model, Lubricated):
            note = plausibility.micrometre_film_note(name, r_j, c, model.film)
            if note:
                warnings.warn(note, stacklevel=2)
        return self._add("clearance_joints", self._clearance, entry)

    def prismatic_clearance(
        self,
        guide_body: str,
        guide_point: Point,
        slider_body: str,
        axis: Point,
        clearance: float,
        slider_length: float,
        model: Optional[Dry] = None,
        name: Optional[str] = None,
        *,
        corner_radius: float = _core.DEFAULTS["prismatic_clearance"]["corner_radius"],
    ) -> "Mechanism":
        """A prismatic (translational) joint with clearance (docs/physics.md §11).

        The slider (``slider_body``, centred on its centroid) moves in a guide along the line
        through ``guide_point`` of ``guide_body`` (may be ``"ground"``) with direction ``axis``
        (guide frame). ``clearance`` [m] is the guide gap minus the slider's thickness: centred,
        the slider can move ±clearance/2 sideways. Its two ends, ``slider_length`` [m] apart
        and rounded with ``corner_radius`` [m], hit either guide surface with the dry law
        ``model`` (:class:`Dry`; its stiffness defaults to Hertz sphere-on-plane with the corner
        radius), with friction along the guide. Free flight, one-end and two-end contact follow.
        The joint's results are two contacts, ``"<name> front"`` (+axis end) and
        ``"<name> rear"``. It starts centred and aligned with the guide.
        """
        g = self._ref("guide_body", guide_body)
        s = self._ref("slider_body", slider_body, allow_ground=False)
        ax = _point("axis", axis)
        model = Dry() if model is None else model
        if not isinstance(model, Dry):
            raise InputError(f"invalid model = {model!r}: a prismatic clearance joint is dry: clearsim.Dry(...)", field="model", value=model)
        jname = self._new_name("prismatic_clearance", name)
        entry = {
            "name": jname, "guide_body": g, "guide_point": _point("guide_point", guide_point), "slider_body": s, "axis": ax,
            "clearance": check_finite(f"clearance joint '{jname}'.clearance", clearance),
            "slider_length": check_finite(f"clearance joint '{jname}'.slider_length", slider_length),
            "corner_radius": check_finite(f"clearance joint '{jname}'.corner_radius", corner_radius),
            "model": model._as_dict(),
        }  # fmt: skip
        return self._add("prismatic_clearance_joints", self._prismatic_clearance, entry)

    # ------------------------------------------------------------------ force elements (docs/physics.md §10)
    def _add_force(self, entry: Dict[str, Any]) -> "Mechanism":
        return self._add("forces", self._forces, entry)

    def _pair(self, body_a: str, body_b: str) -> Tuple[str, str]:
        return self._ref("body_a", body_a), self._ref("body_b", body_b)

    def spring(
        self,
        body_a: str,
        point_a: Point,
        body_b: str,
        point_b: Point,
        stiffness: Optional[float] = None,
        damping: float = 0.0,
        free_length: Optional[float] = None,
        name: Optional[str] = None,
        *,
        force_table: Optional[Dict[str, Sequence[float]]] = None,
    ) -> "Mechanism":
        """A translational spring-damper between ``point_a`` of ``body_a`` and ``point_b`` of
        ``body_b`` (either may be ``"ground"``; points in the body's frame [m]).

        Tension F = k (ℓ − ℓ₀) + c ℓ̇ [N] pulls the points together: ``stiffness`` k [N/m],
        ``damping`` c [N s/m], ``free_length`` ℓ₀ [m] (default: the distance in the mechanism
        assembled at t = 0, so no preload). A nonlinear spring gives
        ``force_table={"deflection": [m...], "force": [N...]}`` (tension against ℓ − ℓ₀,
        piecewise linear, held at the end values) instead of k.
        """
        a, b = self._pair(body_a, body_b)
        pa, pb = _point("point_a", point_a), _point("point_b", point_b)
        return self._add_force(_forces.spring(self._new_name("spring", name), a, pa, b, pb, stiffness, damping, free_length, force_table))

    def rotational_spring(
        self,
        body_a: str,
        body_b: str,
        stiffness: float,
        damping: float = 0.0,
        angle0: Optional[float] = None,
        name: Optional[str] = None,
    ) -> "Mechanism":
        """A rotational spring-damper between two bodies (or a body and ``"ground"``): torque on
        ``body_b`` T = −k (θ_b − θ_a − φ₀) − c (θ̇_b − θ̇_a) [N m], −T on ``body_a``.
        ``stiffness`` k [N m/rad], ``damping`` c [N m s/rad], ``angle0`` φ₀ [rad], the unloaded
        relative angle (default: the one assembled at t = 0)."""
        a, b = self._pair(body_a, body_b)
        return self._add_force(_forces.rotational_spring(self._new_name("rotational_spring", name), a, b, stiffness, damping, angle0))

    def force(self, body: str, point: Point, value: "_forces.Load", frame: str = "global", name: Optional[str] = None) -> "Mechanism":
        """An applied force at ``point`` of ``body`` (body frame [m]).

        ``value``: ``(F_x, F_y)`` [N], each a number or a :class:`clearsim.Harmonic`, or a load table in time or in a driver's angle
        (``{"t": [...], "fx": [...], "fy": [...]}``, ``{"driver": "drive1", "angle": [...],
        "fy": [...], "period": 2π}``; see :mod:`clearsim.forces`), e.g. a stamping load over
        part of the stroke. ``frame="body"``: the components turn with the body (a follower
        force)."""
        b = self._ref("body", body, allow_ground=False)
        p = _point("point", point)
        return self._add_force(_forces.applied_force(self._new_name("force", name), b, p, value, frame))

    def torque(self, body: str, value: "_forces.Load", name: Optional[str] = None, *, reaction: Optional[str] = None) -> "Mechanism":
        """An applied torque [N m] on ``body`` (counter-clockwise positive): a number, a
        :class:`clearsim.Harmonic` (offset + amplitude · cos(ω t + phase)) or a load
        table (``{"t": [...], "torque": [...]}`` or ``{"driver": ..., "angle": [...], "torque":
        [...]}``, see :mod:`clearsim.forces`). With ``reaction``, the opposite torque acts on
        that body."""
        b = self._ref("body", body, allow_ground=False)
        r = None if reaction is None else self._ref("reaction", reaction)
        return self._add_force(_forces.applied_torque(self._new_name("torque", name), b, value, r))

    def motor(
        self,
        body: str,
        stall_torque: float,
        no_load_speed: float,
        angle0: Optional[float] = None,
        name: Optional[str] = None,
        *,
        reaction: str = GROUND,
    ) -> "Mechanism":
        """A motor turning ``body`` by torque, its stator on ``reaction`` (default the ground):
        a linear speed–torque line T = T_stall (1 − ω/ω₀) from ``stall_torque`` T_stall > 0
        [N m] at rest to zero at ``no_load_speed`` ω₀ [rad/s] (its sign is the direction of
        rotation; above it the motor brakes). ``angle0`` [rad]: the body's angle at the start
        (default: as added). Unlike :meth:`driver` it leaves the speed free, so the crank slows
        at each impact; it starts from the body's ``velocity`` (default at rest). A load table
        can follow its angle: ``{"driver": <motor name>, "angle": ...}``."""
        b = self._ref("body", body, allow_ground=False)
        r = self._ref("reaction", reaction)
        if angle0 is not None:
            self._motor_angles[b] = check_finite("angle0", angle0)
            if b in self._index:
                self._bodies[self._index[b]]["angle"] = self._motor_angles[b]
        return self._add_force(_forces.motor(self._new_name("motor", name), b, r, stall_torque, no_load_speed))

    # ------------------------------------------------------------------ queries
    @property
    def body_names(self) -> List[str]:
        return [b["name"] for b in self._bodies]

    @property
    def clearance_joint_names(self) -> List[str]:
        """The clearance contacts in the order of the results' joint channels: each revolute
        clearance joint, then the two slider ends ``"<name> front"``, ``"<name> rear"`` of each
        prismatic one."""
        ends = [f"{p['name']} {end}" for p in self._prismatic_clearance for end in ("front", "rear")]
        return [c["name"] for c in self._clearance] + ends

    def contacts(self) -> Dict[str, Dict[str, Any]]:
        """Each clearance contact of :attr:`clearance_joint_names`: its free travel
        ``clearance`` [m] (c of a revolute joint, half the play of a prismatic one's slider end),
        ``kind`` (``"dry"``, ``"lubricated"`` or ``"guide"``) and its description entry."""
        out: Dict[str, Dict[str, Any]] = {}
        for c in self._clearance:
            out[c["name"]] = {"clearance": float(c["clearance"]), "kind": c["model"]["kind"], "entry": copy.deepcopy(c)}
        for p in self._prismatic_clearance:
            for end in ("front", "rear"):
                out[f"{p['name']} {end}"] = {"clearance": 0.5 * float(p["clearance"]), "kind": "guide", "entry": copy.deepcopy(p)}
        return out

    def description(self) -> Dict[str, Any]:
        """The plain-data description handed to the Rust core (a copy, yours to change), its
        elements in name order and referring to one another by name (``"ground"``: the fixed
        frame). The core resolves the names when the mechanism compiles (``_core.resolve`` gives
        the description as the core reads it): the order in which elements were added does not
        matter, and a name that refers to nothing is an :class:`InputError` naming the element
        and its field (``force 'gas'.value.driver``)."""
        return copy.deepcopy(self._description())

    def _description(self) -> Dict[str, Any]:
        """The description itself (not a copy: do not change it), built once per change of the
        mechanism and cached like the compiled model."""
        if self._plain is None:
            self._plain = {
                "gravity": list(self._gravity),
                "baumgarte": list(self._baumgarte),
                "bodies": copy.deepcopy(self._bodies),
                "joints": copy.deepcopy(self._joints),
                "drivers": copy.deepcopy(self._drivers),
                "clearance_joints": copy.deepcopy(self._clearance),
                "prismatic_clearance_joints": copy.deepcopy(self._prismatic_clearance),
                "forces": copy.deepcopy(self._forces),
            }
        return self._plain

    def copy(self) -> "Mechanism":
        """An independent copy (the compiled Rust model, if any, is not copied)."""
        compiled, self._compiled = self._compiled, None  # the compiled model is not copyable
        try:
            return copy.deepcopy(self)
        finally:
            self._compiled = compiled

    def with_values(self, values: Mapping[str, float]) -> "Mechanism":
        """A copy with numbers replaced by path: ``{"B.clearance": 6e-4, "B.viscosity": 0.3,
        "crank1.mass": 0.25, "drive1.omega": -16.0}``. A path is ``element.field``: the element
        by its name (body, joint, driver, clearance joint, force), the field the first key of
        that name in its description, looked up through its nested tables (a joint's model, its
        dry law, a driver's law) in SI units. Unknown or ambiguous paths, and values the element
        cannot take, are an :class:`InputError` naming them."""
        m = self.copy()
        changed = []
        for path, value in values.items():
            group, entry, owner, key = m._path(path)
            owner[key] = check_finite(str(path), value)
            changed.append((group, entry))
        for group, entry in changed:  # a value out of range is named here, by the core's checks
            _core.check_element(group, entry)
        m._changed()
        return m

    def value(self, path: str) -> Optional[float]:
        """The number that ``path`` (``"B.clearance"``, see :meth:`with_values`) names [SI]
        (``None`` for a number left to its default, e.g. a stiffness computed from the materials)."""
        _, _, owner, key = self._path(path)
        return None if owner[key] is None else float(owner[key])

    def _path(self, path: Any) -> Tuple[str, Dict[str, Any], Dict[str, Any], str]:
        """The element a path names (its description list and entry), the dict holding the
        number and its key; an :class:`InputError` naming the path if there is none."""
        groups = {"bodies": self._bodies, "joints": self._joints, "drivers": self._drivers, "clearance_joints": self._clearance,
                  "prismatic_clearance_joints": self._prismatic_clearance, "forces": self._forces}  # fmt: skip
        element, _, key = str(path).rpartition(".")
        if not element or not key:
            raise InputError(f"invalid path {path!r}: write it as element.field (e.g. 'B.clearance')", field="path", value=path)
        hits = [(group, e) for group, g in groups.items() for e in g if e.get("name") == element]
        if not hits:
            raise InputError(f"invalid path {path!r}: no element named {element!r}", field="path", value=path)
        owner = _find_key(hits[0][1], key)
        if owner is None or isinstance(owner[key], (bool, dict, list, str)):
            raise InputError(f"invalid path {path!r}: {element!r} has no number {key!r}", field="path", value=path)
        return hits[0][0], hits[0][1], owner, key

    def idealized(self) -> "Mechanism":
        """A copy with every clearance joint replaced by an ideal joint (docs/physics.md §5): a
        revolute one by a revolute joint, a prismatic one by a prismatic joint along its guide.
        The core idealises (``_core.idealize``, ``MechanismDesc::idealized``: the one
        implementation); the copy is rebuilt from the description it returns."""
        ideal = _core.idealize(self._description())  # bodies by name, as the description gives them
        m = self.copy()
        m._gravity, m._baumgarte = ideal["gravity"], ideal["baumgarte"]
        m._bodies, m._joints, m._drivers, m._forces = ideal["bodies"], ideal["joints"], ideal["drivers"], ideal["forces"]
        m._clearance, m._prismatic_clearance = ideal["clearance_joints"], ideal["prismatic_clearance_joints"]
        m._index = {b["name"]: k for k, b in enumerate(m._bodies)}
        m._changed()
        return m

__all__ = ["Mechanism", "GROUND", "SimulationError"]


def _insert(entries: List[Dict[str, Any]], entry: Dict[str, Any]) -> None:
    """Insert ``entry`` in ``entries``, kept sorted by name: the description, and so every
    answer, does not depend on the order in which the elements were defined."""
    k = bisect.bisect_right([e["name"] for e in entries], entry["name"])
    entries.insert(k, entry)


def _find_key(d: Dict[str, Any], key: str) -> Optional[Dict[str, Any]]:
    """The dict holding ``key``: ``d`` itself, else the first nested dict that has it (breadth first)."""
    queue = [d]
    while queue:
        cur = queue.pop(0)
        if key in cur:
            return cur
        queue += [v for v in cur.values() if isinstance(v, dict)]
    return None
