"""Running a mechanism: the second half of :class:`clearsim.Mechanism` (a mixin), from the
compiled Rust model to a :class:`clearsim.Result` — the state layout, the right-hand side and
its Newton matrix for other integrators, the run settings (:class:`RunOptions`), ``simulate``
and ``simulate_with_ideal``. The core decides how a run goes: it resolves the names, compiles,
assembles the pose given once and checks it, and words a failed run's hint; Python turns its
findings into :class:`~clearsim.PlausibilityWarning` and its errors into the exceptions of
:mod:`clearsim.errors`. ``simulate`` is one core call once the mechanism is compiled. SI units
throughout.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np

from . import _core, plausibility
from .errors import InputError, InterruptedRun, check_choice, check_finite
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


def _check_options(where: str, options: Dict[str, Any]) -> None:
    """A keyword of ``options`` that :class:`RunOptions` does not know is a TypeError naming the
    method the user called (``simulate``), not an internal one, with the nearest known name."""
    known = list(RunOptions.__annotations__)
    for key in options:
        if key not in known:
            import difflib

            near = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean {near[0]!r}?" if near else f" (its keywords: progress, {', '.join(known)})"
            raise TypeError(f"Mechanism.{where}() got an unexpected keyword argument {key!r}{hint}")


class Running:
    """What a :class:`clearsim.Mechanism` does with its description: compile, run, check."""

    _compiled: Any
    if TYPE_CHECKING:  # provided by Mechanism (mechanism.py, the class that mixes this in)
        _bodies: List[Dict[str, Any]]
        _clearance: List[Dict[str, Any]]
        _warned: set

        @property
        def body_names(self) -> List[str]: ...
        @property
        def clearance_joint_names(self) -> List[str]: ...
        def description(self) -> Dict[str, Any]: ...
        def _description(self) -> Dict[str, Any]: ...
        def _changed(self) -> None: ...
        def idealized(self) -> "Running": ...
        def _body(self, field: str, name: str, allow_ground: bool = True) -> Optional[int]: ...

    #: Largest distance the assembly may move a body from the pose given, as a fraction of the
    #: mechanism's span (the extent of the bodies' positions); a larger move (or a turn of more
    #: than 0.5 rad) is an :class:`~clearsim.AssemblyError` before the run. ``None`` accepts any
    #: pose. Smaller mismatches (a joint's points more than 1 % of the span apart, a body turned
    #: by more than 2°) draw a :class:`clearsim.errors.PlausibilityWarning` (``rust/pose.rs``).
    _assembly_tolerance: Optional[float] = 0.2

    @property
    def assembly_tolerance(self) -> Optional[float]:
        """See :attr:`_assembly_tolerance`: the pose check's tolerance (``None``: none)."""
        return self._assembly_tolerance

    @assembly_tolerance.setter
    def assembly_tolerance(self, value: Optional[float]) -> None:
        self._assembly_tolerance = None if value is None else check_finite("assembly_tolerance", value)
        self._compiled = None  # the pose check is part of the compiled model

    def warn_output_point(self, body: str, point: Sequence[float], field: str, locate: Optional[Callable[[str], str]] = None) -> None:
        """A :class:`~clearsim.PlausibilityWarning` (once per mechanism) if the output point
        ``point`` [m] on ``body``, named ``field``, looks given in mm or in the global frame
        (:func:`clearsim.plausibility.output_point_findings`); ``locate`` words the message
        (a scene prefixes its file and line)."""
        found = plausibility.output_point_findings(self._description(), body, point, field)
        plausibility.warn_new([(f, locate(m) if locate else m) for f, m in found], self._warned)

    def held_reactions(self) -> List[Tuple[str, str]]:
        """(name, kind) of every ideal joint (``revolute``, ``prismatic``) and driver
        (``driver``) in the core's order (joints, then drivers): what ``simulate(extremes=)``
        can track the reaction of (``Result.reaction_summary``)."""
        desc = self.description()
        return [(j["name"], j["kind"]) for j in desc["joints"]] + [(d["name"], "driver") for d in desc["drivers"]]

    def compile(self) -> "_core.CompiledModel":
        """The compiled Rust model (cached until the mechanism changes). The core resolves the
        names, validates, compiles, assembles the pose given once and checks it (against
        :attr:`assembly_tolerance`); what looks wrong (a size in mm against the mechanism's span,
        a joint point in the wrong frame) is a :class:`~clearsim.PlausibilityWarning` here, once
        per mechanism."""
        if self._compiled is None:
            compiled = _core.compile(self._description(), self.assembly_tolerance)
            self._compiled = compiled
            plausibility.warn_new(compiled.warnings, self._warned)
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
        marks = (lambda a: draw_points.mark_pose(a, self.body_names, q, named)) if named else None
        return draw.plot_pose(self._description(), q, magnify=magnify, t=float(t), ax=ax, marks=marks)

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
            settings["monitors"] = extreme_monitors(extremes, self.body_names, self.clearance_joint_names, start, t_end, self.held_reactions())
            for spec in settings["monitors"]:
                if "point" in spec and spec["component"] == "x" and spec["quantity"] == "displacement":  # once a point
                    self.warn_output_point(self.body_names[spec["body"]], spec["point"], "extremes point")
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
            :meth:`Result.driver_torque`), ``"joints"``, ``"violation"``, ``"energy"`` (the
            energy books, :meth:`Result.energy`), ``"film"`` (each lubricated joint's oil flow
            and peak pressure, :meth:`Result.flow`, :meth:`Result.peak_pressure`; a finite film
            solves its Reynolds equation at each output) (default: all but ``"reactions"``,
            ``"energy"`` and ``"film"``).
        h_max, h_min, max_steps:
            Step limits [s] and the step budget.
        max_seconds:
            Wall-time budget of the run [s] (default none): a run over it stops with a
            :class:`clearsim.SimulationError` ("wall-time budget ... used up at t = ...") and
            keeps its partial result.
        extremes, extremes_from:
            Bodies, clearance joints, ideal joints, drivers and points ``(body, (x, y))`` (body
            frame [m]) whose peaks to track at every step (``True``: every body, joint and
            driver), for :meth:`Result.extremes` and :meth:`Result.reaction_summary` (an ideal
            joint's force or a driver's torque costs a KKT solve at each of the step's four
            points), over the run or from ``extremes_from`` [s] on (the window of
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
        _check_options("simulate", dict(kwargs))
        settings = self.run_settings(t_end, **kwargs)
        compiled = self.compile()  # the pose check's AssemblyError comes from compiled.simulate
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
        _check_options("simulate_with_ideal", dict(kwargs))
        settings = self.run_settings(t_end, **kwargs)
        compiled = self.compile()
        ideal = self.idealized()
        # ``integrator="auto"`` resolves per mechanism: the ideal one has no film (nor joints).
        ideal_kwargs: Dict[str, Any] = dict(kwargs)
        if ideal_kwargs.get("extremes") not in (None, True, False):
            ideal_kwargs["extremes"] = [n for n in ideal_kwargs["extremes"] if (n[0] if isinstance(n, (tuple, list)) else n) in ideal.body_names]
        ideal_settings = ideal.run_settings(t_end, **ideal_kwargs)
        # The compiled mechanism runs as it is (its pose assembled once, at its compile; the pose
        # check first) beside its twin, compiled in the core: two assemblies, one a mechanism.
        actual, twin = compiled.simulate_with_ideal(settings, ideal._description(), ideal_settings)  # read only: no copies
        if isinstance(actual, BaseException):
            raise actual
        if isinstance(twin, BaseException):
            raise twin
        return self._finish(actual, settings), ideal._finish(twin, ideal_settings)

    def check_assembly(self, t0: float = 0.0) -> np.ndarray:
        """Assemble at ``t0`` [s] and return q0 there, after checking the pose given (the pose
        at t = 0, the drivers' reference time; a start ``t0`` ≠ 0 follows the drivers from it):
        a body that its assembly at t = 0 moves far (see :attr:`assembly_tolerance`) is an
        :class:`~clearsim.AssemblyError` naming the body, how far it moved and the joint whose
        points lie furthest apart at the poses given; a joint whose two points lie more than 1 %
        of the mechanism's span apart, or a body turned by more than 2°, a
        :class:`clearsim.errors.PlausibilityWarning` naming the joint and both points (body
        frame and global), when the mechanism compiles. A joint point given in the global
        instead of the body frame, or a wrong length, is the usual cause. The core checks it
        (``rust/pose.rs``); :meth:`simulate` checks it before it runs."""
        compiled = self.compile()
        compiled.check_pose()
        return np.asarray(compiled.initial_state(float(t0)), dtype=float)[: 3 * len(self._bodies)]

    def _finish(self, raw: Dict[str, Any], settings: Optional[Dict[str, Any]] = None) -> Result:
        if settings is not None and "sections" in settings:
            raw["section_settings"] = settings["sections"]
        res = Result(raw, self.body_names, self.clearance_joint_names)
        res.description = self._description()  # the mechanism's own (not a copy): read it, do not change it
        res.monitor_specs = list(settings.get("monitors", [])) if settings is not None else []
        err = raw.get("error")
        if err is not None:
            err.result = res
            hint = getattr(err, "hint", None)  # the core's, chosen by the kind of failure
            if isinstance(err, InterruptedRun):
                # A crawl the user stopped by hand gets the same advice as one out of budget.
                tail = f"; {hint}" if hint else ""
                warnings.warn(f"clearsim: {err}; returning the partial result{tail}", RuntimeWarning, stacklevel=3)
                return res
            if hint:
                err.args = (f"{err.args[0] if err.args else ''}; {hint}",)
            raise err
        return res


__all__ = ["RunOptions", "Running", "COMPONENTS", "INTEGRATORS", "OUTPUTS", "DEFAULT_OUTPUTS", "MAX_OUTPUTS"]

