"""Running a mechanism: the second half of :class:`clearsim.Mechanism` (a mixin), from the
compiled Rust model to a :class:`clearsim.Result` — the state layout, the right-hand side and
its Newton matrix for other integrators, the run settings (:class:`RunOptions`), ``simulate``
and ``simulate_with_ideal``. SI units throughout.
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any, Dict, List, NamedTuple, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np

from . import _core
from .batch import run_descriptions
from .errors import AssemblyError, ClearsimError, InputError, InterruptedRun, PlausibilityWarning, SimulationError, check_choice, check_finite
from .joints import MICROMETRE_FILM_RATIO
from .dynamics.readings import section_spec
from .points import PointsLike, tracked_points
from .result import Result, extreme_monitors
from .schema import ATOL, COMPONENTS, DEFAULT_OUTPUTS, H_MIN, INTEGRATORS, MAX_STEPS, OUTPUTS, RTOL

if TYPE_CHECKING:
    from typing_extensions import Unpack

class RunOptions(TypedDict, total=False):
    """The keyword arguments of :meth:`Mechanism.simulate` (all optional; see its docstring)."""

    integrator: str  # "auto", "rk45", "dop853", "radau", "rodas4" or "rk4"
    rtol: float
    atol: float
    step: Optional[float]  # [s], rk4 only
    dt_out: Optional[float]  # [s]
    t_out: Optional[Sequence[float]]  # [s]
    t0: float  # [s]
    outputs: Optional[Sequence[str]]
    h_max: Optional[float]  # [s]
    h_min: float  # [s]
    max_steps: int
    max_seconds: Optional[float]  # [s] of wall time
    extremes: Union[bool, Sequence[Any]]  # bodies, clearance joints and (body, (x, y)) points (Result.extremes)
    extremes_from: Optional[float]  # [s] start of the extremes' window (default t0)
    bearings: bool  # track the bearing summary (Result.bearing_summary)
    sections: Union[None, float, Tuple[float, float]]  # Poincaré sections: period [s] or (period [s], phase [rad])

#: Most outputs a dt_out grid may ask for (each holds every stored channel; the core's
#: ``MAX_OUTPUTS``, which checks it).
MAX_OUTPUTS: float = float(_core.DEFAULTS["settings"]["max_outputs"])


#: Largest rotation [rad] of a body by the assembly before the pose given counts as wrong.
ASSEMBLY_TURN = 0.5
#: Above these the pose given draws a :class:`clearsim.errors.PlausibilityWarning`: a joint whose
#: two points lie further apart than this fraction of the mechanism's span, or a body that the
#: assembly turns by more than this angle [rad] (docs/physics.md §1).
POSE_GAP_WARNING = 0.01
POSE_TURN_WARNING = math.radians(2.0)


class _Gap(NamedTuple):
    """A joint at the poses given: its name, its two bodies, how far its two points lie apart
    [m] (a prismatic joint: the slider's point off the guide line; a clearance joint: from its
    bearing's centre or its initial eccentricity, whichever is nearer) and each point as given
    (body frame) and where it lies (global)."""

    joint: str
    bodies: Tuple[Optional[int], Optional[int]]
    gap: float
    local: Tuple[Sequence[float], Sequence[float]]
    world: Tuple[np.ndarray, np.ndarray]


def _joint_gaps(desc: Dict[str, Any]) -> List[_Gap]:
    """The two-point joints (revolute, prismatic and clearance joints) at the poses given
    (before assembly), with the distance between their points."""
    bodies = desc["bodies"]

    def frame(body: Optional[int]) -> Tuple[np.ndarray, np.ndarray]:
        if body is None:
            return np.zeros(2), np.eye(2)
        b = bodies[body]
        c, s = math.cos(b.get("angle", 0.0)), math.sin(b.get("angle", 0.0))
        return np.asarray(b["position"], dtype=float), np.array([[c, -s], [s, c]])

    def at(body: Optional[int], point: Sequence[float]) -> np.ndarray:
        r, rot = frame(body)
        return r + rot @ np.asarray(point, dtype=float)

    out = []
    for j in desc["joints"]:
        a, b = at(j["body_a"], j["point_a"]), at(j["body_b"], j["point_b"])
        if j["kind"] == "revolute":
            gap = float(np.hypot(*(a - b)))
        elif j["kind"] == "prismatic":
            u = frame(j["body_a"])[1] @ np.asarray(j["axis"], dtype=float)
            gap = abs(float(u[0] * (b - a)[1] - u[1] * (b - a)[0])) / max(float(np.hypot(*u)), 1e-300)
        else:
            continue
        out.append(_Gap(j["name"], (j["body_a"], j["body_b"]), gap, (j["point_a"], j["point_b"]), (a, b)))
    for j in desc["clearance_joints"]:
        a, b = at(j["bearing_body"], j["bearing_point"]), at(j["journal_body"], j["journal_point"])
        # The journal may be given centred or at its initial eccentricity e0 (the assembly puts it there).
        e0 = np.asarray(j.get("initial_eccentricity", (0.0, 0.0)), dtype=float)
        gap = min(float(np.hypot(*(b - a))), float(np.hypot(*(b - a - e0))))
        out.append(_Gap(j["name"], (j["bearing_body"], j["journal_body"]), gap, (j["bearing_point"], j["journal_point"]), (a, b)))
    return out


def _points_text(g: _Gap, names: Sequence[str]) -> str:
    """Both points of a joint, as given (body frame) and where they lie (global) [m]."""

    def fmt(v: Any) -> str:
        return f"({float(v[0]):.4g}, {float(v[1]):.4g})"

    def body(i: Optional[int]) -> str:
        return "the ground" if i is None else f"body '{names[i]}'"

    return "; ".join(f"point {fmt(g.local[k])} on {body(g.bodies[k])} lies at {fmt(g.world[k])} (global)" for k in (0, 1))


class Running:
    """What a :class:`clearsim.Mechanism` does with its description: compile, run, check."""

    _compiled: Any
    #: The description the compiled model was built from (given to its results, which share it:
    #: a run copies no description) and the compiled model whose pose given was checked last.
    _compiled_description: Optional[Dict[str, Any]] = None
    _pose_checked_for: Any = None
    if TYPE_CHECKING:  # provided by Mechanism (mechanism.py, the class that mixes this in)
        _bodies: List[Dict[str, Any]]
        _clearance: List[Dict[str, Any]]

        @property
        def body_names(self) -> List[str]: ...
        @property
        def clearance_joint_names(self) -> List[str]: ...
        def description(self) -> Dict[str, Any]: ...
        def idealized(self) -> "Running": ...
        def _body(self, field: str, name: str, allow_ground: bool = True) -> Optional[int]: ...

    def compile(self) -> "_core.CompiledModel":
        """The compiled Rust model (cached until the mechanism changes)."""
        if self._compiled is None:
            desc = self.description()
            self._compiled = _core.compile(desc)
            self._compiled_description = desc
        return self._compiled

    @property
    def state_dim(self) -> int:
        """Length of the state y = (q, q̇, T…): 6 per body (q, then q̇), then the oil
        temperature [K] of each clearance joint with a heat model (``Lubricated(thermal=...)``),
        in the order of :attr:`clearance_joint_names` (docs/physics.md §4, *Heat*)."""
        return int(self.compile().state_dim)

    def state_index(self, body: str, component: str, velocity: bool = False) -> int:
        """Index in the state y = (q, q̇, T…) of ``body``'s pose ``component`` (``"x"``, ``"y"`` [m]
        or ``"theta"`` [rad]; with ``velocity=True`` its rate, m/s or rad/s). In
        ``m.rhs(t, y)`` the same index gives its rate (position) or acceleration (velocity)."""
        b = self._body("body", body, allow_ground=False)
        assert b is not None
        check_choice("component", component, COMPONENTS)
        return 3 * b + COMPONENTS.index(component) + (3 * len(self._bodies) if velocity else 0)

    def plot(self, t: float = 0.0, *, magnify: Optional[float] = None, ax: Any = None, points: Optional[PointsLike] = None) -> Any:
        """A figure of the mechanism as assembled at time ``t`` [s]: bodies, joints, drivers,
        force elements and the clearance joints magnified (``magnify``; default: the largest
        clearance drawn at 2 % of the mechanism's size, the factor written beside each joint),
        and the named ``points`` (``{"tool": ("coupler", (0.1, 0.02))}``, body frame [m]) marked.
        Check a scene you wrote with it before running."""
        from . import draw, draw_points

        named = tracked_points(points, self.body_names) if points is not None else []
        q = self.initial_state(float(t))[: 3 * len(self._bodies)]
        fig = draw.plot_pose(self.description(), q, magnify=magnify, t=float(t), ax=ax)
        if named:
            draw_points.mark_pose(fig.axes[0] if ax is None else ax, self.body_names, q, named)
        return fig

    def initial_state(self, t0: float = 0.0) -> np.ndarray:
        """Consistent state y0 = (q0, q̇0, T0…) at ``t0`` [s]: the pose given (the pose at t = 0,
        the drivers' reference time) assembled, then followed along the drivers to ``t0`` on its
        branch (docs/physics.md §1), and the oil temperatures at their ``initial`` values
        (:attr:`state_dim`); :class:`clearsim.AssemblyError` names a dead centre on the way."""
        return self.compile().initial_state(float(t0))

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """ẏ = f(t, y), for driving clearsim's model with an external integrator such as
        ``scipy.integrate.solve_ivp(m.rhs, ...)``. State layout: q = (x, y, θ) per body in
        name order (:attr:`body_names`; not the order added), then q̇ likewise (:meth:`state_index`),
        then the oil temperature T [K] of each clearance joint with a heat model, in the order of
        :attr:`clearance_joint_names` (its rate dT/dt [K/s] from the joint's heat balance;
        :attr:`state_dim`).
        No impact memory: δ̇⁽⁻⁾ is the current approach speed."""
        return self.compile().rhs(float(t), np.ascontiguousarray(y, dtype=float))

    def jacobian(self, t: float, y: np.ndarray) -> np.ndarray:
        """The stiff part of ∂f/∂y at (t, y) as a dense (n, n) array, ``[[0, I], [W_q, W_v]]``:
        the clearance joints' force derivatives mapped through the constrained mobility (the
        Newton matrix clearsim's ``"radau"`` uses); with heat models, bordered by the oil
        temperatures' rows and columns ``[[0, I, 0], [W_q, W_v, A_T], [G_q, G_v, G_T]]`` (the
        film's change with T through μ(T), the heat balance's change with the motion and T). The non-stiff remainder (pose dependence of
        the constraints, Baumgarte terms) is left out, which implicit methods tolerate:
        ``solve_ivp(m.rhs, ..., method="Radau", jac=m.jacobian)``. Units: 1/s² and 1/s."""
        return self.compile().jacobian(float(t), np.ascontiguousarray(y, dtype=float))

    # ------------------------------------------------------------------ running
    @property
    def default_integrator(self) -> str:
        """What ``integrator="auto"`` picks: ``"radau"`` when a clearance joint is lubricated (the
        film makes the problem stiff), else ``"rk45"`` (decided by the core for the compiled model,
        ``rust/settings.rs``, ``default_method``)."""
        return str(self.compile().default_integrator)

    def run_settings(
        self,
        t_end: float,
        *,
        integrator: str = "auto",
        rtol: float = RTOL,
        atol: float = ATOL,
        step: Optional[float] = None,
        dt_out: Optional[float] = None,
        t_out: Optional[Sequence[float]] = None,
        t0: float = 0.0,
        outputs: Optional[Sequence[str]] = None,
        h_max: Optional[float] = None,
        h_min: float = H_MIN,
        max_steps: int = MAX_STEPS,
        max_seconds: Optional[float] = None,
        extremes: Union[bool, Sequence[Any]] = False,
        extremes_from: Optional[float] = None,
        bearings: bool = False,
        sections: Union[None, float, Tuple[float, float]] = None,
    ) -> Dict[str, Any]:
        """The settings dict of a run (see :meth:`simulate`).

        The Rust core validates every setting, once per run or batch (``rust/settings.rs``,
        ``RunSettings::validate``): the integrator's name, tolerances, step limits, budgets, and
        it builds the output grid from ``dt_out`` (``RunSettings::grid``, default (t_end − t0)/1000)
        and resolves ``integrator="auto"`` per mechanism. Python checks only what it must know to
        write the dict: t0 and t_end (they bound the monitors written here), the times ``t_out``
        (sent as one buffer), the output channels named (written as flags) and the extremes' window."""
        t0 = check_finite("t0", t0)
        t_end = check_finite("t_end", t_end)
        if t_end <= t0:
            raise InputError(f"invalid t_end = {t_end!r}: must be greater than t0 = {t0}", field="t_end", value=t_end)
        grid: Optional[np.ndarray] = None
        if t_out is not None:
            grid = np.asarray(t_out, dtype=float)
            # Sent as one buffer of times (the core checks that they increase strictly; a NaN there
            # would read as "must increase", so it is named here).
            if grid.ndim != 1 or not np.all(np.isfinite(grid)):
                raise InputError("invalid t_out: must be a 1-D sequence of finite times", field="t_out", value=t_out)
        wanted = set(DEFAULT_OUTPUTS if outputs is None else outputs)
        unknown = wanted - set(OUTPUTS)
        if unknown:
            raise InputError(
                f"invalid outputs = {sorted(unknown)!r}: known outputs are {', '.join(OUTPUTS)}", field="outputs", value=sorted(unknown)
            )
        settings: Dict[str, Any] = {
            "integrator": integrator,
            "rtol": rtol,
            "atol": atol,
            "t0": t0,
            "t_end": t_end,
            "h_min": h_min,
            "max_steps": max_steps,
            "outputs": {k: (k in wanted) for k in OUTPUTS},
        }
        if grid is not None:
            settings["t_out"] = np.ascontiguousarray(grid)
        elif dt_out is not None:
            settings["dt_out"] = dt_out
        if step is not None:
            settings["step"] = step
        if h_max is not None:
            settings["h_max"] = h_max
        if max_seconds is not None:
            settings["max_seconds"] = max_seconds
        # One window for every reading tracked at each step: the extremes and the bearing summary.
        start = t0 if extremes_from is None else max(check_finite("extremes_from", extremes_from), t0)
        if extremes is not False:
            settings["monitors"] = extreme_monitors(extremes, self.body_names, self.clearance_joint_names, start, t_end)
        elif extremes_from is not None and not t_end > start:
            raise InputError(f"invalid extremes_from = {extremes_from!r}: must be before t_end = {t_end!r} [s]", field="extremes_from", value=extremes_from)
        if bearings:
            settings["bearings"] = True
            if start > t0:
                settings["bearings_from"] = start
        if sections is not None:
            settings["sections"] = section_spec(sections)
        return settings

    def simulate(self, t_end: float, progress: bool = True, **kwargs: Unpack[RunOptions]) -> Result:
        """Integrate from t0 (default 0) to ``t_end`` [s]. The pose given is the pose at t = 0;
        a run from t0 ≠ 0 starts where the drivers have taken it by then (so it continues the
        run from 0; docs/physics.md §1).

        Keyword arguments
        -----------------
        integrator:
            ``"auto"`` (default: ``"radau"`` when a clearance joint is lubricated, else
            ``"rk45"``; see :attr:`default_integrator`), ``"rk45"`` (Dormand–Prince 5(4),
            adaptive), ``"dop853"`` (8th order, for
            tight tolerances), ``"radau"`` (RADAU5: implicit Radau IIA of order 5, L-stable,
            with Newton matrices built from the clearance joints' force derivatives — the
            method for lubricated joints, whose film makes the problem stiff; faster than RK45
            at the same error there by the factors in the README's *Choosing an integrator*,
            slower on dry impacts), ``"rodas4"`` (L-stable
            Rosenbrock 4(3) with a finite-difference Jacobian, ``state_dim + 7`` right-hand
            sides per step) or ``"rk4"`` (classic, fixed ``step`` [s]).
        rtol, atol:
            Tolerances of the adaptive methods (default 1e-6, 1e-9).
        dt_out / t_out:
            Output grid spacing [s] (default (t_end − t0)/1000) or explicit output times [s]
            (increasing, inside [t0, t_end]; they take precedence over dt_out); outputs come from
            the dense output and never shorten a step.
        outputs:
            Channels to store: any of ``"states"``, ``"accelerations"``, ``"reactions"``
            (the ideal joints' forces and drivers' torques: :meth:`Result.joint_force`,
            :meth:`Result.driver_torque`), ``"joints"``, ``"violation"`` (default: all but
            ``"reactions"``).
        h_max, h_min, max_steps:
            Step limits [s] and the step budget.
        max_seconds:
            Wall-time budget of the run [s] (default none): a run over it stops with a
            :class:`clearsim.SimulationError` ("wall-time budget ... used up at t = ...") and
            keeps its partial result.
        extremes, extremes_from:
            Bodies, clearance joints and points ``(body, (x, y))`` (body frame [m]) whose peaks
            to track at every step (``True``: every body and joint), for
            :meth:`Result.extremes`, over the run or from ``extremes_from`` [s] on (the window of
            :meth:`Result.bearing_summary` too, which says it): independent of
            ``dt_out``, unlike the maximum of the stored outputs (a body costs 10–70 % more run
            time; docs/performance.md, "Peaks").
        bearings:
            Track the bearing summary of every lubricated joint (:meth:`Result.bearing_summary`:
            minimum film thickness located between the steps, peak and mean power loss at every
            step's end; independent of ``dt_out``), over the run or from ``extremes_from`` on
            (the summary's ``window_start``, ``window_end``). Off by default: it costs one force evaluation
            per joint and step where the method has none to reuse (RK45 and RADAU5 have one: 0.6–1.8 %
            more instructions per step; docs/performance.md, "What a run pays for").
        sections:
            Poincaré sections: ``period`` [s] or ``(period, phase)`` (phase [rad], default 0):
            the stored channels at the exact times t_k = (k + phase/2π) · period in [t0, t_end]
            (t counted from 0), from the integrator's dense output whatever ``dt_out``;
            :meth:`Result.poincare` reads them.

        progress:
            Show a progress bar (simulated time, with the time left) for runs that take longer
            than a second; ``clearsim.set_progress(False)`` or ``CLEARSIM_PROGRESS=0`` hides
            every bar (:mod:`clearsim.progress`).

        Raises :class:`clearsim.SimulationError` (with ``.result`` holding the partial result)
        if the run cannot go on; a Ctrl-C returns the partial result with a warning.
        """
        settings = self.run_settings(t_end, **kwargs)
        compiled = self.compile()
        self._checked_assembly(settings["t0"])
        from .progress import bar as progress_bar, progress_enabled

        if not (progress and progress_enabled()):
            return self._finish(compiled.simulate(settings), settings)
        t0 = settings["t0"]
        # Shown only for runs longer than a second; updated about every 50 ms from the core.
        with progress_bar(settings["t_end"] - t0, "simulating", "s", unit_scale=True) as bar:

            def advance(t: float) -> None:
                # ``update`` (not ``refresh``) honours the bar's one-second delay.
                bar.update(min(t - t0, bar.total) - bar.n)

            raw = compiled.simulate(settings, advance)
        return self._finish(raw, settings)

    def simulate_with_ideal(self, t_end: float, progress: bool = True, **kwargs: Unpack[RunOptions]) -> Tuple[Result, Result]:
        """Run this mechanism and its ideal counterpart (:meth:`idealized`) with the same
        settings on the same output grid, in parallel in the Rust core. Returns
        ``(result, ideal)``; ``result.error(ideal, body, quantity)`` gives the errors (docs/physics.md §5).
        The options are :meth:`simulate`'s; ``progress`` is accepted as there, but the pair runs
        as one batch in the core, which shows no bar."""
        settings = self.run_settings(t_end, **kwargs)
        self._checked_assembly(settings["t0"])
        ideal = self.idealized()
        # ``integrator="auto"`` resolves per mechanism: the ideal one has no film (nor joints).
        ideal_kwargs: Dict[str, Any] = dict(kwargs)
        if ideal_kwargs.get("extremes") not in (None, True, False):
            ideal_kwargs["extremes"] = [n for n in ideal_kwargs["extremes"] if (n[0] if isinstance(n, (tuple, list)) else n) in ideal.body_names]
        ideal_settings = ideal.run_settings(t_end, **ideal_kwargs)
        raws = run_descriptions([self.description(), ideal.description()], [settings, ideal_settings])
        actual, twin = raws
        if isinstance(actual, BaseException):
            raise actual
        if isinstance(twin, BaseException):
            raise twin
        return self._finish(actual, settings), ideal._finish(twin, ideal_settings)

    #: Largest distance the assembly may move a body from the pose given, as a fraction of the
    #: mechanism's span (the extent of the bodies' positions); a larger move (or a turn of more
    #: than 0.5 rad) is an :class:`AssemblyError` before the run. ``None`` accepts any pose.
    #: Smaller mismatches (a joint's points more than 1 % of the span apart, a body turned by more
    #: than 2°) draw a :class:`clearsim.errors.PlausibilityWarning`.
    assembly_tolerance: Optional[float] = 0.2

    def check_assembly(self, t0: float = 0.0) -> np.ndarray:
        """Assemble at ``t0`` [s] and return q0 there, after checking the pose given (the pose
        at t = 0, the drivers' reference time; a start ``t0`` ≠ 0 follows the drivers from it):
        a body that its assembly at t = 0 moves far (see :attr:`assembly_tolerance`) is an
        :class:`AssemblyError` naming the body, how far it moved and the joint whose points lie
        furthest apart at the poses given; a joint whose two points lie more than 1 % of the
        mechanism's span apart, or a body turned by more than 2°, a
        :class:`clearsim.errors.PlausibilityWarning` naming the joint and both points (body
        frame and global). A joint point given in the global instead of the body frame, or a
        wrong length, is the usual cause. Called by :meth:`simulate` before it runs."""
        self._check_shift(np.asarray(self.compile().initial_state(0.0), dtype=float)[: 3 * len(self._bodies)], stacklevel=3)
        return np.asarray(self.compile().initial_state(float(t0)), dtype=float)[: 3 * len(self._bodies)]

    def _check_shift(self, q0: np.ndarray, stacklevel: int = 4) -> None:
        """Compare the pose given with ``q0``, its assembly at t = 0."""
        tol = self.assembly_tolerance
        if tol is None or not np.all(np.isfinite(q0)):
            return
        guess = np.array([[*b["position"], b.get("angle", 0.0)] for b in self._bodies], dtype=float)
        pos = guess[:, :2]
        span = max(float(np.ptp(pos[:, 0]) + np.ptp(pos[:, 1])), 1e-3) if len(pos) > 1 else 1.0
        moved = np.hypot(q0[0::3] - guess[:, 0], q0[1::3] - guess[:, 1])
        turned = np.abs((q0[2::3] - guess[:, 2] + math.pi) % (2 * math.pi) - math.pi)
        k = int(np.argmax(moved / span + turned / ASSEMBLY_TURN))
        gaps = _joint_gaps(self.description())
        if moved[k] <= tol * span and turned[k] <= ASSEMBLY_TURN:
            self._warn_pose(gaps, turned, span, stacklevel + 1)
            return
        name = self._bodies[k]["name"]
        own = [g for g in gaps if k in g.bodies]
        culprit = max(own or gaps, key=lambda g: g.gap, default=None)
        joint = None
        because = ""
        if culprit is not None and culprit.gap > 0.05 * span:
            joint = culprit.joint
            because = f"; joint '{joint}' has its two points {culprit.gap:.3g} m apart at the poses given ({_points_text(culprit, self.body_names)})"
        raise AssemblyError(
            f"the assembly of the pose given (the pose at t = 0) moves body '{name}' by {moved[k]:.3g} m and {math.degrees(turned[k]):.3g}° "
            f"(tolerance: {tol:g} × the mechanism's span {span:.3g} m, or {math.degrees(ASSEMBLY_TURN):.3g}°)"
            f"{because}: check the joint points (body frame, not global) and the lengths, or give poses nearer the "
            "assembled ones (m.assembly_tolerance = None accepts any)",
            t=0.0, joint=joint, body=name, moved=float(moved[k]), turned=float(turned[k]), result=None,
            field=f"joint '{joint}'" if joint else f"body '{name}'.position", value=culprit.gap if joint and culprit else float(moved[k]),
        )  # fmt: skip

    def _warn_pose(self, gaps: List[_Gap], turned: np.ndarray, span: float, stacklevel: int) -> None:
        """A :class:`PlausibilityWarning` for a pose given that assembles but looks wrong: the
        joint whose points lie furthest apart beyond POSE_GAP_WARNING × span, or else the joint of
        a body the assembly turns by more than POSE_TURN_WARNING."""
        names = self.body_names
        far = [g for g in gaps if g.gap > POSE_GAP_WARNING * span]
        k = int(np.argmax(turned)) if len(turned) else 0
        if far:
            g = max(far, key=lambda g: g.gap)
            what = f"joint '{g.joint}' has its two points {g.gap:.3g} m apart ({100 * g.gap / span:.3g} % of the mechanism's span {span:.3g} m)"
        elif len(turned) and turned[k] > POSE_TURN_WARNING:
            own = [g for g in gaps if k in g.bodies]
            if not own:
                return
            g = max(own, key=lambda g: g.gap)
            what = f"the assembly turns body '{names[k]}' by {math.degrees(turned[k]):.3g}° (its joint '{g.joint}' has its points {g.gap:.3g} m apart)"
        else:
            return
        others = [f"'{o.joint}' {o.gap:.3g} m" for o in far if o is not g]
        also = f"; also apart: {', '.join(others)}" if others else ""
        warnings.warn(
            f"clearsim: the pose given looks wrong: {what}: {_points_text(g, names)}{also}. Joint points are given in each "
            "body's own frame (a point given in global coordinates, or a wrong length, is the usual cause); the run goes on "
            "from the assembled pose (m.assembly_tolerance = None silences this)",
            PlausibilityWarning,
            stacklevel=stacklevel,
        )

    def _checked_assembly(self, t0: float = 0.0) -> None:
        """:meth:`check_assembly` before a run from ``t0``: the pose given is checked at t = 0,
        whatever ``t0``, once per compiled model (the check depends on the mechanism alone: the
        runs after the first repeat neither its assembly nor its warnings); an assembly that fails
        altogether is left to the run, whose error carries the diagnosis and an empty partial
        result."""
        compiled = self.compile()
        if self._pose_checked_for is compiled:
            return
        try:
            q0 = np.asarray(compiled.initial_state(0.0), dtype=float)[: 3 * len(self._bodies)]
        except ClearsimError:
            return
        self._check_shift(q0)
        self._pose_checked_for = compiled

    def _finish(self, raw: Dict[str, Any], settings: Optional[Dict[str, Any]] = None) -> Result:
        if settings is not None and "sections" in settings:
            raw["section_settings"] = settings["sections"]
        res = Result(raw, self.body_names, self.clearance_joint_names)
        # The compiled model's description when there is one (shared, not copied per run).
        compiled_desc = self._compiled_description if self._compiled is not None else None
        res.description = compiled_desc if compiled_desc is not None else self.description()
        res.monitor_specs = list(settings.get("monitors", [])) if settings is not None else []
        err = raw.get("error")
        if err is not None:
            err.result = res
            hint = self._micrometre_film_hint(err)
            if isinstance(err, InterruptedRun):
                # A crawl the user stopped by hand gets the same advice as one out of budget.
                tail = f"; {hint}" if hint else ""
                warnings.warn(f"clearsim: {err}; returning the partial result{tail}", RuntimeWarning, stacklevel=3)
                return res
            if hint:
                err.args = (f"{err.args[0] if err.args else ''}; {hint}",)
            raise err
        return res

    def _micrometre_film_hint(self, err: SimulationError) -> Optional[str]:
        """What to try when a lubricated run stalls where the film model, not the solver, sets the
        pace (docs/hard_cases.md, after the table): a journal released at rest against the wall
        that cannot leave it (any clearance: the short film up to 20 µm, the finite up to 1 µm, the
        long up to 3 µm), and in a µm film (R/c ≥ MICROMETRE_FILM_RATIO) a half-speed whirl along the
        wall or the long film's whirl near the centre."""
        stalled = any(s in str(err) for s in ("wall-time budget", "maximum number of steps", "step size underflow", "interrupted"))
        joint = next((j for j in self.description()["clearance_joints"] if j["name"] == err.joint), None)
        if not stalled or joint is None or joint["model"]["kind"] != "lubricated" or err.eccentricity is None:
            return None
        ratio = joint["journal_radius"] / joint["clearance"]
        where = f"joint '{joint['name']}' has a {joint['clearance'] * 1e6:.3g} µm {joint['model']['film']!r} film (R/c = {ratio:.0f})"
        if err.eccentricity >= 0.9 and err.t == 0.0:
            return (
                f"hint: {where} and its journal was released at rest against the wall with the drive already at speed: "
                "the film pushes with a force so large and so nonlinear that the first steps cannot converge: start it "
                "centred or off the wall (docs/hard_cases.md lists the clearances each film releases from)"
            )
        if ratio < MICROMETRE_FILM_RATIO:
            return None
        if err.eccentricity >= 0.9:
            return (
                f"hint: {where} and its journal sits against the wall, likely whirling along it at half the shaft speed "
                "(wedge ≈ 0, no load capacity) where the squeeze film is as stiff as at contact: start it centred or off "
                "the wall (docs/hard_cases.md)"
            )
        if joint["model"]["film"] == "long" and err.eccentricity < 0.5:
            return (
                f"hint: {where}; a journal whirling near the centre of a µm long-bearing (half-Sommerfeld) film meets a "
                "negative squeeze damping and the run crawls: film='finite', supply='none' (the periodic film) damps it; the default supply line crawls like the long film (docs/hard_cases.md)"
            )
        return None


__all__ = ["RunOptions", "Running", "COMPONENTS", "INTEGRATORS", "OUTPUTS", "DEFAULT_OUTPUTS", "MAX_OUTPUTS"]

