"""Scene files: a planar mechanism and its run, described in TOML.

``load_scene(path)`` gives the :class:`~clearsim.Mechanism`; ``load_scene_file(path)`` gives a
:class:`Scene` with the mechanism plus the run, output and reliability settings (what
``clearsim run`` uses). SI units throughout: m, kg, s, rad (angles of the crank in the
``[reliability]`` block in degrees, as in the paper).

Format
------
Every table and key is listed below; anything else is an error naming the key, the file and the
line. ``[[...]]`` tables may repeat. Points on a body are in the body's frame (from its
centroid, at angle 0); points on ``"ground"`` (the fixed frame) are global::

    [mechanism]                      # optional
    name = "my press"                # free text (optional)
    description = "..."              # free text (optional)
    gravity = [0.0, -9.81]           # m/s² (default (0, -9.81))
    baumgarte = [50.0, 50.0]         # α, β [1/s] (default 50, 50)

    [[body]]                         # one per rigid body
    name = "crank"
    mass = 0.30                      # kg
    inertia = 1.0e-4                 # kg m², about the centroid
    position = [0.025, 0.0]          # m, approximate (the assembly at t0 refines it) ...
    angle = 0.0                      # rad (default 0)
    # ... or, for a link: ends = [[0.0, 0.0], [0.05, 0.0]]  (centroid at mid-length,
    #     angle of the line ends[0] → ends[1]); not together with position/angle.
    velocity = [0.0, 0.0, 0.0]       # optional guess (ẋ, ẏ, θ̇)

    [[joint]]                        # ideal joints
    type = "revolute"                # or "prismatic"
    name = "crank-ground"            # optional (default revolute1, prismatic1, ...)
    bodies = ["ground", "crank"]
    points = [[0.0, 0.0], [-0.025, 0.0]]
    # prismatic only: axis = [1.0, 0.0]  (guide direction in the first body's frame);
    # the second body (the slider) moves on the line through the first point.

    [[driver]]                       # θ(t) of a body: exactly one of
    body = "crank"
    omega = 523.6                    # rad/s, θ = angle0 + ω t (angle0 [rad], default the
    angle0 = 0.0                     #   body's angle), or rpm = 5000 instead of omega,
    # polynomial = [c0, c1, c2]      # θ = Σ c_k t^k, or
    # times = [...], angles = [...]  # samples [s], [rad] through a natural cubic spline
    name = "crank-drive"             # optional

    [[clearance_joint]]              # revolute joint with radial clearance (docs/physics.md §2)
    type = "revolute"                # default; or "prismatic" (docs/physics.md §11): name,
                                     #   guide_body, guide_point, slider_body, axis, clearance
                                     #   (gap − slider thickness) [m], slider_length [m],
                                     #   corner_radius [m] (default 1e-3), [clearance_joint.dry]
    name = "rod-slider"
    bearing_body = "slider"          # the hole, radius journal_radius + clearance
    bearing_point = [0.0, 0.0]
    journal_body = "rod"             # the pin
    journal_point = [0.06, 0.0]
    journal_radius = 9.5e-3          # m
    clearance = 0.5e-3               # m, radial
    initial_eccentricity = [0.0, 0.0]  # m, global (default centred)
    model = "dry"                    # or "lubricated" (default "dry")
    [clearance_joint.dry]            # optional: fields of clearsim.Dry
    restitution = 0.9
    friction = 0.1
    # wear = { coefficient = 1e-4, hardness = 2e9, length = 0.02, feedback = true }
    #                                # Archard wear (docs/physics.md §12), needed by [study.life]
    # [clearance_joint.lubricated]   # with model = "lubricated": fields of clearsim.Lubricated,
    # viscosity = 0.4                #   its dry law in [clearance_joint.lubricated.dry]
    # roughness = 0.5e-6             # m, composite RMS σ: Greenwood–Tripp asperities where
    # boundary_friction = 0.12       #   h < 4σ with friction μ_b, in place of the band e0
    # viscosity = {vogel = [6.4e-5, 900.0, 164.0]}  # or Vogel's μ = a exp(b/(T − c)) [Pa s, K, K]
    #                                #   of the oil temperature, which needs:
    # [clearance_joint.lubricated.thermal]  # C dT/dt = P_loss − hA (T − T_ambient), docs/physics.md §4
    # ambient = 313.15               # K
    # heat_capacity = 50.0           # J/K, C
    # heat_transfer = 1.0            # W/K, hA
    # initial = 313.15               # K (default: ambient); read back as Result.temperature

    [[force]]                        # force elements and loads (docs/physics.md §10); type =
    type = "spring"                  #   spring | rotational_spring | force | torque | motor
    name = "return-spring"           # optional (default spring1, force1, ...)
    body_a = "ground"                # spring: between point_a of body_a and point_b of body_b
    point_a = [0.3, 0.0]
    body_b = "slider"
    point_b = [0.0, 0.0]
    stiffness = 2000.0               # N/m (or force_table = {deflection = [m], force = [N]})
    damping = 5.0                    # N s/m (default 0)
    # free_length = 0.15             # m (default: the distance assembled at t = 0)
    # rotational_spring: body_a, body_b, stiffness [N m/rad], damping [N m s/rad], angle0 [rad]

    [[force]]
    type = "force"                   # an applied force at point (body frame) of body:
    body = "slider"
    point = [0.0, 0.0]
    value = [-50.0, 0.0]             # N (fx, fy), constant, or a table in time or a driver's angle:
    # value = { driver = "crank-drive", angle = [0.0, 2.6, 2.8, 3.1], fx = [0.0, 0.0, -400.0, 0.0], period = 6.283185307179586 }
    # value = { t = [0.0, 0.01], fy = [0.0, 100.0] }
    # frame = "body"                 # components turn with the body (default "global")
    # torque: body, value [N m] (number or table with torque = [...]), reaction (optional body)
    # motor: body, stall_torque [N m], no_load_speed [rad/s], angle0 [rad], reaction
    #   (default "ground"): turns the body by torque, instead of a [[driver]]

    [simulation]
    t_end = 0.4                      # s, or: cycles = 3 (× period [s], default 2π/|ω| of
                                     #   the first constant-speed driver; period = ... to set it)
    integrator = "auto"              # auto (radau if lubricated, else rk45) | rk45 | dop853 | radau | rodas4 | rk4 (needs step [s])
    rtol = 1e-6
    atol = 1e-9
    dt_out = 1e-4                    # s, output grid (default (t_end − t0)/1000)
    # t0, step, h_max, h_min, max_steps: as Mechanism.simulate
    outputs = ["reactions"]          # extra channels to store (those [outputs] and
                                     #   [reliability] need are added automatically)

    [outputs]                        # what `clearsim run` writes and plots
    bodies = ["slider"]              # body histories (default: none)
    quantities = ["position", "velocity", "acceleration"]   # default all three
    components = ["x"]               # of x, y, theta (default all three)
    joints = ["rod-slider"]          # clearance joints (default: all)
    joint_quantities = ["eccentricity", "force"]  # + eccentricity_rate, contact_force,
                                                  #   film_force, state, film_thickness,
                                                  #   friction_torque, power_loss
    ideal = true                     # also run the ideal mechanism; write its response and
                                     #   the errors (default: true if there are clearance joints)
    csv = true                       # default true
    plots = true                     # default true

    [reliability]                    # optional: FOSM dynamic-accuracy reliability (docs/physics.md §6)
    body = "slider"
    component = "x"                  # x | y | theta
    bin_width = 18.0                 # deg
    omega = 523.6                    # rad/s; crank angle = |ω| (t − t0) in degrees
                                     #   (default: the first constant-speed driver)
    t_start = 0.0                    # s, analyse from here on (drop a start-up transient)
    [reliability.allowable]          # required: [Δv, Δu] of |error| per analysed quantity,
                                     #   in its unit (theta: rad, rad/s, rad/s²)
    displacement = [0.0, 0.004]      # m
    velocity = [0.0, 0.6]            # m/s
    acceleration = [0.0, 200.0]      # m/s²

    [study]                          # optional: `clearsim reliability scene.toml` (docs/physics.md §6;
                                     #   every option: python -m pydoc clearsim.reliability.scene)
    body = "slider"                  # the output: a body coordinate's error against the ideal
    component = "x"                  #   mechanism (x | y | theta) ...
    # joint = "rod-slider"           # ... or a clearance joint's quantity instead
    quantity = "displacement"        # displacement | velocity | acceleration; a joint:
                                     #   eccentricity | force | contact_force | film_force
    limit = 1.0e-3                   # required: the largest acceptable peak, in its unit (m here)
    cycles = 1.0                     # analysed crank turns ...
    skip_cycles = 1.0                # ... after this many start-up turns (default 0)
    # omega = 523.6                  # rad/s (default: the first constant-speed driver)
    methods = ["form", "importance_sampling"]   # of monte_carlo, form, importance_sampling,
                                     #   subset, sobol, fosm, ak_mcs, ak_is (max_runs = 150:
                                     #   their budget); [study.life]: p_f against cycles
    samples = 1000                   # Monte Carlo samples; Sobol base size
    cov = 0.1                        # importance sampling's target coefficient of variation
    seed = 0
    # bin_width = 18.0               # deg: FOSM's crank-angle bins (methods = [..., "fosm"])
    # sobol_method = "saltelli"      # or "pce"; step = 0.05: FORM's gradient step in u
    # [[study.output]]               # several outputs (a series system) instead of the one
    # body = "slider"                #   above: body/component or joint, quantity, limit and
    # ...                            #   side = "above" (default) or "below"
    [[study.input]]                  # one per random input
    path = "rod-slider.clearance"    # element.field of the mechanism (Mechanism.with_values), SI
    distribution = "normal"          # normal | lognormal (mean, std) | uniform (low, high)
    mean = 0.5e-3                    #   | truncated_normal (mean, std, low, high)
    std = 0.05e-3
    [study.tolerance]                # optional: the largest mean of one input that still
    input = "rod-slider.clearance"   #   meets a reliability
    reliability = 0.9999
    # bracket = [0.3e-3, 0.6e-3]     # where to look (default ½× to 2× its mean)

Elements may come in any order: names that refer to other elements (a joint's bodies, a load
table's driver) are resolved when the whole file is read. A value that is valid but looks like
a unit slip (a journal radius in mm, a viscosity in cP) is a :class:`clearsim.PlausibilityWarning`
naming the file and line. Example scenes: ``scenes/`` (``docs/examples.md``).

TOML is read with :mod:`tomllib` (Python ≥ 3.11) or the ``tomli`` package.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core, display
from .errors import InputError, PlausibilityWarning, SimulationError
from .mechanism import Mechanism
from .schema import COMPONENTS, OUTPUTS
from .reliability.fosm import BIN_WIDTH
from .result import Result
from .scene_builder import _Builder
from .toml_reader import Table, dotted_key, read_toml

PathLike = Union[str, Path]

#: The body channels ``[outputs].quantities`` names and the unit of each component x, y, theta
#: (ASCII, as the CSV headers write them). Not :data:`clearsim.schema.BODY_QUANTITIES`, the
#: quantities of an error or extreme (``"displacement"`` where a channel says ``"position"``).
BODY_CHANNELS: Dict[str, Tuple[str, str, str]] = {
    "position": ("m", "m", "rad"),
    "velocity": ("m/s", "m/s", "rad/s"),
    "acceleration": ("m/s^2", "m/s^2", "rad/s^2"),
}
#: The clearance-joint channels ``[outputs].joint_quantities`` names: their columns (name, unit).
JOINT_CHANNELS: Dict[str, Tuple[Tuple[str, str], ...]] = {
    "eccentricity": (("ex", "m"), ("ey", "m"), ("eps", "-")),
    "eccentricity_rate": (("ex_dot", "m/s"), ("ey_dot", "m/s")),
    "force": (("fx", "N"), ("fy", "N")),
    "contact_force": (("normal", "N"), ("tangential", "N")),
    "film_force": (("film_xi", "N"), ("film_eta", "N")),
    "state": (("state", "-"), ("w_dry", "-")),
    "film_thickness": (("film_thickness", "m"),),
    "friction_torque": (("friction_torque", "N m"), ("friction_torque_bearing", "N m")),
    "power_loss": (("power_loss", "W"),),
}
#: Body quantity → the name of its error against the ideal mechanism (as in
#: :meth:`Result.error` and the reliability analysis).
ERROR_QUANTITIES: Dict[str, str] = {"position": "displacement", "velocity": "velocity", "acceleration": "acceleration"}
RELIABILITY_QUANTITIES: Tuple[str, ...] = tuple(ERROR_QUANTITIES.values())
#: Old names of :data:`BODY_CHANNELS` and :data:`JOINT_CHANNELS` (deprecated: the reliability
#: package and :mod:`clearsim.schema` use these names for output quantities).
BODY_QUANTITIES = BODY_CHANNELS
JOINT_QUANTITIES = JOINT_CHANNELS
_CHANNEL_OF = {"position": "states", "velocity": "states", "acceleration": "accelerations"}



# ====================================================================== settings
@dataclass
class SimulationSettings:
    """The ``[simulation]`` table: the arguments of :meth:`Mechanism.simulate` (SI units).

    ``t_end`` [s] is given or ``t0 + cycles · period``; ``outputs`` lists the channels to
    store (already including those the outputs and the reliability analysis need).
    """

    t_end: float
    integrator: str = "auto"
    rtol: float = 1e-6
    atol: float = 1e-9
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
    """The ``[outputs]`` table: what ``clearsim run`` writes (CSV) and plots (PNG)."""

    bodies: List[str] = field(default_factory=list)
    quantities: List[str] = field(default_factory=lambda: list(BODY_CHANNELS))
    components: List[str] = field(default_factory=lambda: list(COMPONENTS))
    joints: List[str] = field(default_factory=list)
    joint_quantities: List[str] = field(default_factory=lambda: ["eccentricity", "force"])
    ideal: bool = False
    csv: bool = True
    plots: bool = True


@dataclass
class ReliabilitySettings:
    """The ``[reliability]`` table: FOSM reliability of one body coordinate (docs/physics.md §6).

    ``allowable`` maps ``displacement`` / ``velocity`` / ``acceleration`` to the allowable
    error range (Δv, Δu) [m, m/s, m/s² (rad… for ``theta``)]; ``omega`` [rad/s] gives the crank
    angle |ω| (t − t0) [deg]; samples before ``t_start`` [s] are left out; ``bin_width`` [deg].
    """

    body: str
    component: str
    allowable: Dict[str, Tuple[float, float]]
    omega: float
    bin_width: float = BIN_WIDTH
    t_start: float = 0.0


@dataclass
class SceneRun:
    """The runs of a scene: the clearance run, the ideal run (if made) and the errors.

    ``errors[(body, quantity)]`` (quantity ``displacement``, ``velocity``, ``acceleration``) is
    the (N, 3) error clearance − ideal [SI] of :meth:`Result.error` (common part of both runs); ``reliability[quantity]`` the :class:`clearsim.reliability.FosmResult`.
    ``failure`` is the :class:`SimulationError` that stopped the clearance run early, if any
    (``result`` then holds the partial result).
    """

    scene: "Scene"
    result: Result
    ideal: Optional[Result] = None
    errors: Dict[Tuple[str, str], np.ndarray] = field(default_factory=dict)
    reliability: Dict[str, Any] = field(default_factory=dict)
    failure: Optional[SimulationError] = None

    def __repr__(self) -> str:
        return display.text(self, "result", "ideal", "errors", "reliability", "failure")


@dataclass
class Scene:
    """A mechanism with the run, output and reliability settings of a scene file."""

    mechanism: Mechanism
    simulation: SimulationSettings
    outputs: OutputSettings
    reliability: Optional[ReliabilitySettings] = None
    #: The ``[study]`` table (random inputs, one output and its limit; ``clearsim reliability``):
    #: a :class:`clearsim.reliability.scene.StudySettings`.
    study: Optional[Any] = None
    name: str = ""
    description: str = ""
    path: Optional[Path] = None
    _ideal: Optional[Mechanism] = field(default=None, repr=False, compare=False)

    def with_overrides(self, *, t_end: Optional[float] = None, integrator: Optional[str] = None) -> "Scene":
        """A copy with another ``t_end`` [s] and/or integrator (validated)."""
        sim = dataclasses.replace(
            self.simulation,
            t_end=self.simulation.t_end if t_end is None else float(t_end),
            integrator=self.simulation.integrator if integrator is None else integrator,
        )
        self.mechanism.run_settings(sim.t_end, **sim.kwargs())  # raises InputError if invalid
        return dataclasses.replace(self, simulation=sim)

    def simulate(self) -> Result:
        """Run the mechanism with the scene's settings."""
        return self.mechanism.simulate(self.simulation.t_end, **self.simulation.kwargs())

    def ideal_mechanism(self) -> Mechanism:
        """The ideal counterpart of the mechanism (clearance joints → revolute joints)."""
        if self._ideal is None:
            self._ideal = self.mechanism.idealized()
        return self._ideal

    def run(self, ideal: Optional[bool] = None, progress: bool = False) -> SceneRun:
        """Run the scene: the ideal mechanism first (if ``ideal``, default from ``[outputs]``,
        or if ``[reliability]`` needs it), then the mechanism; errors and FOSM reliability.

        A :class:`SimulationError` of the clearance run is kept in ``SceneRun.failure`` with
        the partial result, not raised (the errors cover the part that was computed); one of the
        ideal run is raised. ``progress`` shows a bar (:mod:`clearsim.progress`) when more than one run is made.
        """
        has_clearance = bool(self.mechanism.clearance_joint_names)
        want_ideal = has_clearance and ((self.outputs.ideal if ideal is None else ideal) or self.reliability is not None)
        jobs: List[Tuple[str, Mechanism]] = [("ideal", self.ideal_mechanism())] if want_ideal else []
        jobs.append(("clearance" if has_clearance else "run", self.mechanism))
        results: Dict[str, Result] = {}
        failure: Optional[SimulationError] = None
        desc = self.path.stem if self.path is not None else "clearsim"
        for label, mech in _progress(jobs, progress, desc=desc):
            try:
                results[label] = mech.simulate(self.simulation.t_end, progress=progress, **self.simulation.kwargs())
            except SimulationError as err:
                if label == "ideal" or err.result is None:
                    raise
                results[label], failure = err.result, err
        run = SceneRun(self, results[jobs[-1][0]], results.get("ideal"), failure=failure)
        if run.ideal is not None and len(run.result.t):
            bodies = set(self.outputs.bodies) | ({self.reliability.body} if self.reliability else set())
            for body in sorted(bodies):
                for quantity, error in ERROR_QUANTITIES.items():
                    if _CHANNEL_OF[quantity] in self.simulation.outputs:
                        run.errors[(body, error)] = run.result.error(run.ideal, body, error)
            if self.reliability is not None:
                run.reliability = self._fosm(run)
        return run

    def _fosm(self, run: SceneRun) -> Dict[str, Any]:
        from . import reliability as rel  # imported here: only scenes with [reliability] need it

        spec = self.reliability
        assert spec is not None
        c = COMPONENTS.index(spec.component)
        out: Dict[str, Any] = {}
        for quantity, allowable in spec.allowable.items():
            error = run.errors[(spec.body, quantity)][:, c]
            t = run.result.t[: len(error)]
            keep = t >= spec.t_start
            if np.any(keep):
                angle = np.degrees(abs(spec.omega) * (t[keep] - self.simulation.t0))
                out[quantity] = rel.fosm(error[keep], angle, allowable, bin_width=spec.bin_width)
        return out


def _progress(items: List[Any], enabled: bool, desc: str) -> Iterator[Any]:
    """``items``, with a progress bar when enabled and there is more than one."""
    from .progress import bar

    with bar(len(items), desc, "run", enabled=enabled and len(items) > 1) as b:
        for item in items:
            b.set_postfix_str(item[0] if isinstance(item, tuple) else str(item))
            yield item
            b.update(1)


# ====================================================================== reading a scene
_TOP_KEYS = (
    "mechanism", "body", "joint", "driver", "clearance_joint", "force", "simulation", "outputs", "reliability", "study",
)  # fmt: skip
_SIM_KEYS = (
    "t_end", "cycles", "period", "t0", "integrator", "rtol", "atol", "step", "dt_out", "h_max", "h_min", "max_steps", "outputs",
)  # fmt: skip
_OUTPUT_KEYS = ("bodies", "quantities", "components", "joints", "joint_quantities", "ideal", "csv", "plots")
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
        t_end=t_end, integrator=t.string("integrator", "auto"), rtol=t.number("rtol", 1e-6), atol=t.number("atol", 1e-9),
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
        quantities=t.strings("quantities", list(BODY_CHANNELS), choices=tuple(BODY_CHANNELS)),
        components=t.strings("components", list(COMPONENTS), choices=COMPONENTS),
        joints=t.strings("joints", list(joints), choices=joints),
        joint_quantities=t.strings("joint_quantities", ["eccentricity", "force"], choices=tuple(JOINT_CHANNELS)),
        ideal=t.boolean("ideal", bool(joints)),
        csv=t.boolean("csv", True),
        plots=t.boolean("plots", True),
    )
    return out


def _reliability(b: _Builder, m: Mechanism) -> Optional[ReliabilitySettings]:
    t = b.top.table("reliability", _RELIABILITY_KEYS)
    if t is None:
        return None
    if not m.clearance_joint_names:
        raise t.error(None, "invalid [reliability]: the mechanism has no clearance joint (errors are clearance − ideal)")
    body = t.string("body", choices=m.body_names)
    a = t.table("allowable", tuple(RELIABILITY_QUANTITIES))
    if a is None:
        # No silent default: the paper's limits are in m, m/s and m/s², wrong for most outputs.
        raise t.error(
            None,
            "missing table [reliability.allowable]: give [lower, upper] of the |error| for each analysed "
            "quantity in its unit (m, m/s, m/s² for x and y; rad, rad/s, rad/s² for theta)",
        )
    else:
        allowable: Dict[str, Tuple[float, float]] = {}
        for q in RELIABILITY_QUANTITIES:
            if q in a:
                lo, hi = a.numbers(q, length=2)
                if not lo < hi:
                    raise a.error(q, f"invalid {dotted_key(a.where, q)} = {[lo, hi]!r}: must be [lower, upper] with lower < upper", [lo, hi])
                allowable[q] = (lo, hi)
        if not allowable:
            raise a.error(None, "invalid [reliability.allowable]: give at least one of " + ", ".join(RELIABILITY_QUANTITIES))
    omega = t.number("omega", None)
    if omega is None:
        omega = _drive_speed(m, b.drivers)
        if omega is None:
            raise t.error(None, "missing key 'omega' in [reliability] (no constant-speed driver to take it from)")
    if omega == 0.0 or not math.isfinite(omega):
        raise t.error("omega", f"invalid reliability.omega = {omega!r}: must be a non-zero drive speed [rad/s]", omega)
    bin_width = t.number("bin_width", BIN_WIDTH)
    if not 0.0 < bin_width <= 360.0:
        raise t.error("bin_width", f"invalid reliability.bin_width = {bin_width!r}: must lie in (0, 360] degrees", bin_width)
    return ReliabilitySettings(
        body=body, component=t.string("component", choices=COMPONENTS), allowable=allowable, omega=omega,
        bin_width=bin_width, t_start=t.number("t_start", 0.0),
    )  # fmt: skip


def _needed_channels(outputs: OutputSettings, reliability: Optional[ReliabilitySettings]) -> List[str]:
    needed = ["violation"]
    if outputs.bodies:
        needed += [_CHANNEL_OF[q] for q in outputs.quantities]
    if outputs.joints:
        needed.append("joints")
    if reliability is not None:
        needed += [_CHANNEL_OF[b] for b, e in ERROR_QUANTITIES.items() if e in reliability.allowable]
    return needed


def load_scene_file(path: PathLike) -> Scene:
    """Read a scene file: the mechanism and its run, output and reliability settings.

    Raises :class:`InputError` ``"FILE:LINE: message"`` (attributes ``file``, ``line``,
    ``field``, ``value``) for invalid TOML, unknown keys, wrong types, missing keys and values
    the mechanism builder or the Rust core rejects.
    """
    path = Path(path)
    src, data = read_toml(path)
    top = Table(src, (), data, _TOP_KEYS)
    builder = _Builder(src, top)

    def emit(caught: List[warnings.WarningMessage]) -> None:
        for w in caught:  # a plausibility warning located in the file, like an error
            if isinstance(w.message, PlausibilityWarning):
                where = builder.relocate(InputError(str(w.message), field=getattr(w.message, "field", "")), None)
                warnings.warn(PlausibilityWarning(str(where)), stacklevel=3)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)

    failed: Optional[InputError] = None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mech = builder.build()
        try:
            # The Rust core's checks, located in the file. Not mech.compile(): a cached compiled
            # model would make Mechanism.idealized() (a deepcopy) fail.
            _core.compile(mech.description())
        except InputError as err:
            failed = err
    # The warnings first: a unit slip they name (a journal radius in mm) is often the cause
    # of the error that follows (an L/D outside the finite film's table).
    emit(caught)
    if failed is not None:
        raise builder.relocate(failed, None) from None
    name = builder.mechanism_table.string("name", path.stem)
    description = builder.mechanism_table.string("description", "")
    outputs = _outputs(builder, mech)
    reliability = _reliability(builder, mech)
    sim = _simulation(builder, mech, _needed_channels(outputs, reliability))
    study = None
    if "study" in builder.top:
        from .reliability.scene import STUDY_KEYS, parse_study  # only scenes with [study] need it; its keys live there

        study = parse_study(builder.top.table("study", STUDY_KEYS), mech, _drive_speed(mech, builder.drivers))
    # The ideal counterpart is made now: Mechanism.idealized() deep-copies, which fails once the
    # mechanism holds a compiled Rust model (after a run).
    return Scene(mech, sim, outputs, reliability, study=study, name=name, description=description, path=path, _ideal=mech.idealized())


def load_scene(path: PathLike) -> Mechanism:
    """The :class:`Mechanism` of a scene file (see :func:`load_scene_file` and the module
    docstring for the format)."""
    return load_scene_file(path).mechanism


__all__ = [
    "BODY_CHANNELS",
    "BODY_QUANTITIES",
    "JOINT_CHANNELS",
    "JOINT_QUANTITIES",
    "OutputSettings",
    "ReliabilitySettings",
    "Scene",
    "SceneRun",
    "SimulationSettings",
    "load_scene",
    "load_scene_file",
]
