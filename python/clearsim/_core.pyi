"""Type stub of the native module ``clearsim._core`` (Rust, pyo3). Use the ``clearsim`` facade."""

import sys
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

if sys.version_info >= (3, 11):
    from typing import NotRequired, TypedDict
else:
    from typing_extensions import NotRequired, TypedDict

class Outputs(TypedDict, total=False):
    """Which outputs a run stores (absent: states, accelerations, joints, violation)."""

    states: bool
    accelerations: bool
    #: λ ("lambda", one column per constraint row) and "reactions" (N, ideal joints + drivers, 3):
    #: each one's force x, y [N] and couple [N m] on its second body (rust/constraints, Constraint::reaction)
    reactions: bool
    joints: bool
    violation: bool
    energy: bool
    film: bool

class ReferenceGrid(TypedDict):
    """The grid the reference runs record on (rust/monitor/reference.rs): ``intervals`` equal
    intervals over [t_start, t_end] [s] (numpy's linspace); ``record``: the run's result also
    gives each reference at its output times (``"reference": {"own_ideal": {"q", "qd", "qdd"}}``)."""

    t_start: float
    t_end: float
    intervals: int
    record: NotRequired[bool]

class Monitor(TypedDict):
    """One monitored output (rust/monitor/): what it watches — ``coordinate`` (a body coordinate,
    3 per body: x, y, θ; or a clearance joint's index for a joint quantity), or ``body`` with
    ``point`` (body frame [m]) and ``component`` (x, y, magnitude) — its error against the
    reference it names (``own_ideal``: the run's own mechanism made ideal; ``nominal``: the
    batch's nominal description made ideal; the core makes the runs), or the quantity itself,
    in time bins from ``t_start`` [s]."""

    coordinate: NotRequired[int]
    body: NotRequired[int]
    point: NotRequired[Sequence[float]]
    component: NotRequired[str]  # x, y, magnitude (a point's)
    # displacement, velocity, acceleration; eccentricity, force, contact_force, film_force,
    # film_thickness, friction_torque, power_loss (a clearance joint's)
    quantity: str
    t_start: float
    bin_width: float
    bins: NotRequired[int]
    limit: NotRequired[Optional[float]]
    reference: NotRequired[Optional[str]]  # own_ideal, nominal
    samples_per_step: NotRequired[int]
    exact: NotRequired[bool]  # extremes located on the exact quantity between samples

class Sections(TypedDict):
    """Poincaré sections (rust/simulate/sections.rs): the run's channels at the exact times
    (k + phase/2π) · period [s] in [t0, t_end]; the result's "sections" holds them (t, q, qd, qdd,
    joints, ... as the result's own)."""

    period: float
    phase: NotRequired[float]  # rad

class Lyapunov(TypedDict):
    """A shadow run for the largest Lyapunov exponent (rust/simulate/lyapunov.rs): from ``start``
    [s], ``d0`` [m, rad] away in the norm √(Σ δq² + Σ (δq̇/velocity_scale)²), renormalised every
    ``interval`` [s]; the result's "lyapunov" holds t, log_growth, steps, rhs_evaluations, error."""

    start: float
    interval: float
    d0: float
    velocity_scale: float  # rad/s

class RunSettings(TypedDict):
    """The settings dict of one run (rust/settings.rs; built by ``Mechanism.run_settings``).
    Unknown keys are an ``InputError``."""

    # auto (radau when a clearance joint is lubricated, else rk45: resolved per mechanism, also in
    # a batch), rk45 (Dormand–Prince 5(4)), dop853, rodas4, radau (Radau IIA, RADAU5), rk4; the result's
    # stats["integrator"] names the one that ran.
    integrator: str
    t_end: float
    t0: NotRequired[float]
    step: NotRequired[float]
    rtol: NotRequired[float]
    atol: NotRequired[float]
    h0: NotRequired[float]
    h_max: NotRequired[float]
    h_min: NotRequired[float]
    max_steps: NotRequired[int]
    # Output times [s]; without them the core builds the grid t0 + k dt_out up to t_end
    # (dt_out [s], default (t_end - t0)/1000, at most 1e7 outputs: DEFAULTS["settings"]["max_outputs"]).
    # Giving both is an InputError.
    t_out: NotRequired[Sequence[float]]
    dt_out: NotRequired[float]
    outputs: NotRequired[Outputs]
    max_seconds: NotRequired[float]
    monitors: NotRequired[List[Monitor]]
    # The grid of the reference runs, needed when a monitor names a reference.
    reference: NotRequired[ReferenceGrid]
    # A time [s] in [t0, t_end] at which the wear books are also read: each result's "wear"
    # entry then has bearing_at_mark, journal_at_mark [m] and volume_at_mark [m³].
    wear_mark: NotRequired[float]
    # Track the bearing summary of every lubricated joint along the steps (rust/simulate/bearings.rs):
    # the result's "bearings" then lists per clearance joint None (dry) or min_film_thickness [m],
    # t_min_film [s], peak_power_loss [W], t_peak_power_loss [s], mean_power_loss [W], energy_loss [J],
    # window_start and window_end [s] (the window they cover).
    bearings: NotRequired[bool]
    # The start [s] of the bearing summary's window, in [t0, t_end) (absent: t0).
    bearings_from: NotRequired[float]
    sections: NotRequired[Sections]
    lyapunov: NotRequired[Lyapunov]

__version__: str
JOINT_COLUMNS: List[str]
ENERGY_COLUMNS: List[str]
#: Per clearance joint and output of the ``film`` channel: side_leakage, supply_flow [m³/s],
#: peak_pressure [Pa], peak_pressure_angle [rad] (rust/clearance/readings.rs).
FILM_COLUMNS: List[str]

class CompiledModel:
    """A validated, compiled mechanism."""

    @property
    def default_integrator(self) -> str:
        """What integrator="auto" picks for this model: "radau" when a clearance joint is
        lubricated, else "rk45" (rust/settings.rs, default_method)."""
    @property
    def state_dim(self) -> int:
        """Length of y = (q, q̇, T…): 6 per body, then one oil temperature per clearance joint
        with a heat model, in joint order (rust/clearance/thermal.rs)."""
    @property
    def constraint_rows(self) -> int: ...
    @property
    def dof(self) -> int: ...
    @property
    def contact_stiffness(self) -> List[float]:
        """K [N/m^n] of each revolute clearance joint's K δⁿ; for Dry(stiffness_form="cylindrical")
        the scale π E* L [N/m] of its line-contact law (docs/physics.md §3)."""
    def initial_state(self, t0: float) -> npt.NDArray[np.float64]: ...
    def rhs(self, t: float, y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def jacobian(self, t: float, y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def simulate(
        self, settings: Union[RunSettings, Mapping[str, Any]], progress: Optional[Callable[[float], None]] = None, nominal: Optional[Mapping[str, Any]] = None
    ) -> Dict[str, Any]:
        """Run the model (after the pose check: its AssemblyError raised first); monitors
        measured against its own ideal twin (or the ideal of the ``nominal`` description) get
        their reference run here."""
    def simulate_with_ideal(
        self, settings: Union[RunSettings, Mapping[str, Any]], ideal: Mapping[str, Any], ideal_settings: Union[RunSettings, Mapping[str, Any]]
    ) -> Tuple[Any, Any]:
        """Run the model (after the pose check) and, beside it, its ideal twin (the description
        ``ideal``, compiled in the core) with ``ideal_settings``: ``(result, ideal)``, each a
        result dict or the exception that prevented that run."""
    @property
    def warnings(self) -> List[Tuple[str, str]]:
        """What is valid but looks like a mistake, as (field, message): sizes against the
        mechanism's span (rust/compile/plausibility.rs), the pose given (rust/pose.rs)."""
    def check_pose(self) -> None:
        """Raise the pose check's AssemblyError (a body the assembly moved too far), if any."""
    def film_field(
        self, joint: int, y: npt.NDArray[np.float64], temperature: Optional[float] = None, content: Optional[npt.NDArray[np.float64]] = None
    ) -> Optional[Dict[str, Any]]:
        """The film pressure of clearance joint ``joint`` (index) in the state ``y``: theta [rad],
        z [m], pressure (nθ, nz) [Pa], peak_pressure [Pa], peak_angle [rad], side_leakage and
        supply_flow [m³/s]; ``temperature`` [K] for a viscosity that follows it; ``content`` the
        film content a run recorded (``cavitation="jfo"``; without it a flooded film). None if dry."""

def compile(description: Union[str, Mapping[str, Any]], assembly_tolerance: Optional[float] = 0.2) -> CompiledModel:
    """Resolve the names, validate and compile a description (plain data or its JSON text), read
    by serde; assemble its pose given once and check it against ``assembly_tolerance`` (a
    fraction of the mechanism's span; None accepts any pose)."""

def check_element(group: str, entry: Mapping[str, Any]) -> None:
    """Check one element as it is added (group: bodies, joints, drivers, clearance_joints,
    prismatic_clearance_joints, forces; or dry, lubricated for a model alone): its own values,
    by the compile's checks (InputError naming the field); its references are the compile's."""

def resolve(description: Union[str, Mapping[str, Any]]) -> Dict[str, Any]:
    """The description as the core reads it: bodies by index (the ground None), every default
    filled in."""

def findings(description: Union[str, Mapping[str, Any]]) -> List[Tuple[str, str]]:
    """What looks like a unit slip against the mechanism's size, as (field, message), of a
    description not yet valid as a whole (what explains an element refused as it is added)."""

def output_point_finding(description: Union[str, Mapping[str, Any]], body: str, point: Tuple[float, float], field: str) -> Optional[Tuple[str, str]]:
    """What looks wrong in an output point ``point`` (body frame [m]) on body ``body``, as
    (field, message) naming ``field``: further from the centroid than 10 × the mechanism's span
    (mm?), or further than 1.5 × the body's reach (its joints' farthest) while within that of the
    centroid when read as a global point at the pose given (the global frame?); ``None`` when nothing does or there is no such body."""

def assembly_count() -> int:
    """Poses given assembled by this process (one per compiled model; for tests)."""

#: R_j/c from which a lubricated joint counts as a µm film (rust/simulate/diagnosis.rs).
MICROMETRE_FILM_RATIO: float

def check_settings(settings: Union[RunSettings, Mapping[str, Any]]) -> None:
    """Check run settings as a run does (InputError naming the setting), without running."""

def idealize(description: Union[str, Mapping[str, Any]]) -> Dict[str, Any]:
    """The ideal counterpart of a description (every clearance joint an ideal joint; the one
    implementation, rust/description.rs), as plain data with every default filled in and the
    bodies named as in a Mechanism's description."""

#: The defaults of the clearance-joint parameters, defined in the core (rust/description.rs):
#: ``{"dry": {...}, "lubricated": {...}, "prismatic_clearance": {"corner_radius": ...}}``; and
#: the run settings' (rust/integrate, rust/settings.rs): ``{"settings": {"rtol", "atol",
#: "h_min", "max_steps", "max_outputs"}}``.
DEFAULTS: Dict[str, Dict[str, Any]]

def run_batch(
    descriptions: Sequence[Union[str, Mapping[str, Any]]],
    settings: Union[RunSettings, Mapping[str, Any], Sequence[Union[RunSettings, Mapping[str, Any]]]],
    threads: int = 0,
    nominal: Optional[Union[str, Mapping[str, Any]]] = None,
) -> List[Union[Dict[str, Any], BaseException]]:
    """Run the descriptions on ``threads`` threads (0: all cores), each distinct reference run
    that the monitors name made once and shared (rust/batch.rs); ``nominal``: the nominal
    design's description, for monitors measured against its ideal. One result dict or the
    exception that prevented the run, per description."""


def film_force(
    film: str,
    viscosity: float,
    journal_radius: float,
    clearance: float,
    length: float,
    eps: float,
    eps_dot: float,
    wedge: float,
    supply: str = "widest_gap",
) -> Tuple[float, float]:
    """Film force (F_ξ, F_η) [N] on the journal (docs/physics.md §4); film one of long, short,
    long_paper, finite; SI units, ε̇ [1/s], wedge speed [rad/s]; supply (finite film) widest_gap
    or none."""

def finite_table_counts() -> Tuple[int, int]:
    """Finite-bearing tables (solved, loaded from the disk cache) by this process so far."""
