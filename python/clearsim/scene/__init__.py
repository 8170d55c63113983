"""Scene files: a planar mechanism and its run, described in TOML.

``load_scene(path)`` gives the :class:`~clearsim.Mechanism`; ``load_scene_file(path)`` gives a
:class:`Scene` with the mechanism plus the run, output and reliability settings (what
``clearsim run`` uses). SI units throughout: m, kg, s, rad (angles of the crank in the
``[reliability]`` block in degrees, as in the paper).

The package's rooms, each importing only those listed before it: :mod:`.parameters` (the
``[parameters]`` table and its expressions), :mod:`.toml_reader` (TOML with line numbers),
:mod:`.builder` (the mechanism's tables), :mod:`.settings` (``[simulation]``, ``[outputs]``),
:mod:`.study` (``[study]`` and the :class:`~clearsim.reliability.Study` it sets up),
:mod:`.alias` (``[reliability]``, the short form of ``[study]`` with ``methods = ["fosm"]``),
:mod:`.sweep` (``[sweep]``, a bifurcation diagram for ``clearsim sweep``), :mod:`.loader`
(:class:`Scene`, :func:`load_scene_file`).

Format
------
Every table and key is listed below; anything else is an error naming the key, the file and the
line. ``[[...]]`` tables may repeat. Points on a body are in the body's frame (from its
centroid, at angle 0); points on ``"ground"`` (the fixed frame) are global::

    [parameters]                     # optional: named numbers (clearsim.scene.parameters)
    crank = 0.05                     # m; any numeric field below may be written as a name or an
    rod = 0.12                       #   expression of them: ends = [["crank", 0], ["crank + rod", 0]],
    half_rod = "rod / 2"             #   points = [["-half_rod", 0.0], ...] (+ - * / **, parentheses,
                                     #   sqrt sin cos tan asin acos atan atan2 hypot radians degrees, pi)

    [mechanism]                      # optional
    name = "my press"                # free text (optional)
    description = "..."              # free text (optional)
    gravity = [0.0, -9.81]           # m/s² (default (0, -9.81))
    baumgarte = [50.0, 50.0]         # α, β [1/s] (default 50, 50)

    [[body]]                         # one per rigid body
    name = "crank"
    mass = 0.30                      # kg
    inertia = 1.0e-4                 # kg m², about the centroid
    position = [0.025, 0.0]          # m, approximate (the assembly at t = 0 refines it) ...
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
    # times = [...], angles = [...]  # samples [s], [rad] through a natural cubic spline, or
    # harmonic = {amplitude = 0.3, omega = 20.0, phase = 0.0, offset = 0.0}
    #                                # θ = offset + amplitude cos(omega t + phase) [rad, rad/s]
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
    # viscosity = 0.4                #   Pa s, required; its dry law in [clearance_joint.lubricated.dry]
    # length = 0.05                  # m, the bearing's length, required
    # roughness = 0.5e-6             # m, composite RMS σ: Greenwood–Tripp asperities where
    # boundary_friction = 0.12       #   h < 4σ with friction μ_b, in place of the band e0
    # boundary_slip = 1e-4           # m/s, slip over which μ_b ramps up from standstill
    # cavitation = "jfo"             # with film = "finite": mass-conserving cavitation (the oil
    #                                #   content followed through the ruptured film)
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
    #   (interpolation = "cubic": a C² spline through the points, which then end no steps)
    # value = [{ amplitude = 20.0, omega = 30.0, phase = 0.0, offset = 0.0 }, 0.0]
    #                                # a component offset + amplitude cos(omega t + phase) [N, rad/s]
    # frame = "body"                 # components turn with the body (default "global")
    # torque: body, value [N m] (number, table with torque = [...], or harmonic
    #   { amplitude = 1.5, omega = 0.667 }), reaction (optional body)
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
    points = [{name = "tool", body = "rod", point = [0.02, 0.015]}]   # body points (body frame,
                                     #   m; or [[outputs.points]] tables): their global x, y of
                                     #   each quantity in bodies.csv, errors in errors.csv,
                                     #   paths in points.png (default: none)
    reactions = true                 # ideal joints' forces and drivers' torques in reactions.csv,
                                     #   peaks in the summary (default true)
    ideal = true                     # also run the ideal mechanism; write its response and
                                     #   the errors (default: true if there are clearance joints)
    csv = true                       # default true
    plots = true                     # default true

    [reliability]                    # optional: the paper's FOSM of the nominal run, printed by
                                     #   `clearsim run` (docs/physics.md §6): the short form of
                                     #   [study] methods = ["fosm"], one output per quantity below
    body = "slider"
    component = "x"                  # x | y | theta
    bin_width = 18.0                 # deg
    omega = 523.6                    # rad/s; crank angle = |ω| t in degrees, t from 0 (any t0)
                                     #   (default: the first constant-speed driver)
    t_start = 0.0                    # s, analyse from here (the next bin edge) to t_end, at least
                                     #   one crank turn (drop a start-up transient)
    [reliability.allowable]          # required: [Δv, Δu] of |error| per analysed quantity,
                                     #   in its unit (theta: rad, rad/s, rad/s²)
    displacement = [0.0, 0.004]      # m
    velocity = [0.0, 0.6]            # m/s
    acceleration = [0.0, 200.0]      # m/s²

    [study]                          # optional: `clearsim reliability scene.toml` (docs/physics.md §6;
                                     #   every option: python -m pydoc clearsim.scene.study)
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
    samples = 1000                   # Monte Carlo samples; subset runs per level; Sobol base size
    cov = 0.1                        # importance sampling's target coefficient of variation
    seed = 0
    # bin_width = 18.0               # deg: FOSM's crank-angle bins (methods = [..., "fosm"])
    # reference = "nominal"          # errors against the nominal design's motion (tolerances
                                     #   count) or "own_ideal" (default: each sample's ideal twin)
    # sobol_method = "saltelli"      # or "pce"; step = 0.05: FORM's gradient step in u
    # [[study.output]]               # several outputs (a series system) instead of the one
    # body = "slider"                #   above: body/component or joint, quantity, limit and
    # ...                            #   side = "above" (default) or "below"
    [[study.input]]                  # one per random input
    path = "rod-slider.clearance"    # element.field of the mechanism (Mechanism.with_values), SI,
    # parameter = "rod"              #   or a [parameters] name: each sample rebuilds the mechanism
                                     #   with it (a link length: every point written with it follows)
    distribution = "normal"          # normal | lognormal (mean, std) | uniform (low, high)
    mean = 0.5e-3                    #   | truncated_normal (mean, std, low, high)
    std = 0.05e-3
    [study.tolerance]                # optional: the largest mean of one input that still
    input = "rod-slider.clearance"   #   meets a reliability
    reliability = 0.9999
    # bracket = [0.3e-3, 0.6e-3]     # where to look (default ½× to 2× its mean)

    [sweep]                          # optional: `clearsim sweep scene.toml`, a bifurcation diagram
                                     #   (docs/physics.md §13; python -m pydoc clearsim.scene.sweep)
    parameter = "crank-drive.omega"  # element.field of the mechanism, SI units
    values = { start = 100.0, stop = 600.0, count = 200 }   # or a list of values
    output = { body = "slider", quantity = "acceleration", component = "x" }
                                     # or { joint = "rod-slider", quantity = "eccentricity" }
    transient_cycles = 20            # forcing periods before the Poincaré sections are taken
    cycles = 100                     # periods analysed; lyapunov = "auto" | true | false,
                                     #   period [s], phase [rad], tol, label: see clearsim.scene.sweep

A random link length is a ``[parameters]`` entry that the link's points are written with and a
``[[study.input]]`` with ``parameter =`` its name. The Python API's form of the same study is a
``build`` function: ``rel.Study(lambda rod: my_mechanism(rod), {"rod": rel.Normal(0.12, 1e-3)},
...)`` (docs/reliability.md); both give the same answers, bit for bit, with the same seed.

Elements may come in any order: names that refer to other elements (a joint's bodies, a load
table's driver) are resolved when the whole file is read. A value that is valid but looks like
a unit slip (a journal radius in mm, a viscosity in cP) is a :class:`clearsim.PlausibilityWarning`
naming the file and line. Example scenes: ``scenes/`` (``docs/examples.md``).

TOML is read with :mod:`tomllib` (Python ≥ 3.11) or the ``tomli`` package.

``clearsim reliability`` runs ``[study]``, or, on a scene without one, the study
``[reliability]`` stands for (:meth:`Scene.study_settings`: the same FOSM numbers ``clearsim
run`` prints). A scene may have both tables: they are read independently (``clearsim run`` the
nominal FOSM of ``[reliability]``, ``clearsim reliability`` the methods of ``[study]``), as
scenes written before ``[reliability]`` became an alias hold both; neither changes the other's
answers.
"""

from __future__ import annotations

from ..schema import COMPONENTS
from .alias import RELIABILITY_QUANTITIES, ReliabilitySettings
from .loader import PathLike, Scene, SceneRun, load_scene, load_scene_file
from .settings import BODY_CHANNELS, ERROR_QUANTITIES, JOINT_CHANNELS, OutputSettings, SimulationSettings
from .study import StudySettings

__all__ = [
    "BODY_CHANNELS",
    "COMPONENTS",
    "ERROR_QUANTITIES",
    "JOINT_CHANNELS",
    "OutputSettings",
    "PathLike",
    "RELIABILITY_QUANTITIES",
    "ReliabilitySettings",
    "Scene",
    "SceneRun",
    "SimulationSettings",
    "StudySettings",
    "load_scene",
    "load_scene_file",
]
