"""The names clearsim uses across its layers, defined once: the components of a pose, the
quantities a run reports of a body or a clearance joint with their SI units, the integrators
and the output channels (the Rust core's names, ``rust/settings.rs``).

Units: one vocabulary, written here once in Python text's spelling (``m/s²``, ``rad/s²``; ``1``
for a dimensionless quantity); the forms other places need are derived from it: files for other
tools (CSV headers, NetCDF attributes) write ASCII ``m/s^2`` (:func:`ascii_unit`), a unit inside
a file or column name ``m_per_s2`` (:func:`unit_in_name`).
"""

from __future__ import annotations

from typing import Dict, List, Tuple

from . import _core

#: The components of a body's pose q = (x, y, θ), in the order of the state and of every result
#: array: x, y [m] and theta [rad] (one word for them throughout: "component").
COMPONENTS: Tuple[str, str, str] = ("x", "y", "theta")
#: What a monitor of a point fixed on a body watches (``rust/monitor/target.rs``): the global x or
#: y component of its displacement, velocity or acceleration, or the magnitude of the vector (of
#: the error vector |P − P_ref| against a reference). The exported columns of a point are its x
#: and y (:data:`clearsim.points.POINT_COMPONENTS`).
POINT_MONITOR_COMPONENTS: Tuple[str, str, str] = ("x", "y", "magnitude")
#: What a study's errors are measured against (the core's ``ReferenceOf``,
#: ``rust/monitor/reference.rs``): each sample's own ideal twin (the paper's question: what do
#: the clearances add?) or the nominal design's ideal motion (a designer's: how far from the
#: nominal motion, link-length and pivot tolerances included?).
REFERENCES: Tuple[str, str] = ("own_ideal", "nominal")
#: The integrators of :meth:`clearsim.Mechanism.simulate` (``"auto"`` picks one per mechanism).
INTEGRATORS: Tuple[str, ...] = ("auto", "rk45", "rk4", "dop853", "radau", "rodas4")
#: How a load table runs between its points (the core's ``Interpolation``): straight lines, or
#: a C² cubic spline whose points do not end integration steps (:mod:`clearsim.forces`).
INTERPOLATIONS: Tuple[str, ...] = ("linear", "cubic")
#: The channels a run can store, and those it stores by default.
OUTPUTS: Tuple[str, ...] = ("states", "accelerations", "reactions", "joints", "violation", "energy", "film")
DEFAULT_OUTPUTS: Tuple[str, ...] = ("states", "accelerations", "joints", "violation")
#: The integrator's defaults, where they are defined (the core's ``Settings::default``):
#: relative and absolute tolerance [-, SI], the smallest step [s] and the step budget.
_RUN = _core.DEFAULTS["settings"]
RTOL: float = float(_RUN["rtol"])
ATOL: float = float(_RUN["atol"])
H_MIN: float = float(_RUN["h_min"])
MAX_STEPS: int = int(_RUN["max_steps"])

#: The columns of a clearance joint's stored channel (``Result.joint``), the core's order.
JOINT_COLUMNS: List[str] = list(_core.JOINT_COLUMNS)
#: Units of those columns (``"1"``: dimensionless).
JOINT_COLUMN_UNITS: Dict[str, str] = {
    "ex": "m", "ey": "m", "ex_dot": "m/s", "ey_dot": "m/s", "fx": "N", "fy": "N",
    "normal": "N", "tangential": "N", "film_xi": "N", "film_eta": "N", "w_dry": "1", "state": "1",
    "film_thickness": "m", "friction_torque": "N m", "friction_torque_bearing": "N m", "couette_torque": "N m",
    "poiseuille_torque": "N m", "power_loss": "W", "asperity_force": "N",
}  # fmt: skip
#: Units of the ``film`` channel's columns per clearance joint (``_core.FILM_COLUMNS``: oil flow
#: and peak pressure, :mod:`clearsim.film_readings`).
FILM_COLUMN_UNITS: Dict[str, str] = {"side_leakage": "m^3/s", "supply_flow": "m^3/s", "peak_pressure": "Pa", "peak_pressure_angle": "rad"}

#: The quantities of a body coordinate (its extremes, its error against the ideal mechanism)
#: and their units: (of x and y, of theta).
BODY_QUANTITY_UNITS: Dict[str, Tuple[str, str]] = {
    "displacement": ("m", "rad"),
    "velocity": ("m/s", "rad/s"),
    "acceleration": ("m/s²", "rad/s²"),
}
BODY_QUANTITIES: Tuple[str, ...] = tuple(BODY_QUANTITY_UNITS)
#: The quantities of a clearance joint a study (:mod:`clearsim.reliability`) watches, and their
#: units. Its ``film_thickness`` is the smallest gap over the study's window derived from the
#: monitored eccentricity's peak, h_min = c (1 − ε_max) [m] (docs/physics.md §4), not the core's
#: film-thickness reading of :data:`READING_MONITOR_UNITS`.
JOINT_QUANTITY_UNITS: Dict[str, str] = {
    "eccentricity": "1",
    "force": "N",
    "contact_force": "N",
    "film_force": "N",
    "film_thickness": "m",
}
JOINT_QUANTITIES: Tuple[str, ...] = tuple(JOINT_QUANTITY_UNITS)
#: The quantities of a clearance joint the core's monitors track for
#: :meth:`clearsim.Result.extremes` (``rust/monitor/mod.rs``, ``Quantity``), and their units: the
#: eccentricity ratio e/c and the force magnitudes on the journal...
JOINT_MONITOR_UNITS: Dict[str, str] = {"eccentricity": "1", "force": "N", "contact_force": "N", "film_force": "N"}
#: ... and the bearing readings of a lubricated joint (:mod:`clearsim.joint_readings`). Here
#: ``film_thickness`` is the reading h = c − |e| [m] itself, tracked at every step (its minimum:
#: ``Result.bearing_summary``'s ``min_film_thickness``), not a study's h_min from ε_max.
READING_MONITOR_UNITS: Dict[str, str] = {"film_thickness": "m", "friction_torque": "N m", "power_loss": "W"}
#: What the core's monitors track of an ideal joint's or driver's reaction on its second body
#: (``Target::Reaction``, rust/monitor/target.rs): its force (component x, y or magnitude) and
#: its couple, and their units.
REACTION_MONITOR_UNITS: Dict[str, str] = {"force": "N", "torque": "N m"}


#: The SI unit of a description field a study can make random (``B.clearance`` → m), by the
#: field's name in the description (``rust/description.rs``); ``1``: dimensionless.
INPUT_UNITS: Dict[str, str] = {
    "clearance": "m", "journal_radius": "m", "length": "m", "slider_length": "m", "corner_radius": "m",
    "roughness": "m", "e0": "m", "mass": "kg", "inertia": "kg m^2", "angle": "rad", "omega": "rad/s", "v0": "m/s", "v1": "m/s",
    "impact_speed_floor": "m/s", "youngs_modulus": "Pa", "journal_youngs_modulus": "Pa", "hardness": "Pa", "poisson_ratio": "1",
    "journal_poisson_ratio": "1", "restitution": "1", "friction": "1", "boundary_friction": "1", "boundary_slip": "m/s", "coefficient": "1", "eps0": "1",
    "eps_max": "1", "ambient": "K", "initial": "K", "viscosity": "Pa s", "angle0": "rad", "heat_capacity": "J/K", "heat_transfer": "W/K",
}  # fmt: skip


def body_unit(quantity: str, component: str) -> str:
    """The SI unit of ``quantity`` (:data:`BODY_QUANTITIES`) of a body's ``component``."""
    return BODY_QUANTITY_UNITS[quantity][1 if component == "theta" else 0]


#: Units as files for other tools write them (ASCII).
ASCII_UNITS: Dict[str, str] = {"m/s²": "m/s^2", "rad/s²": "rad/s^2"}


def ascii_unit(unit: str) -> str:
    """``unit`` as a CSV header or a NetCDF attribute writes it (``m/s²`` → ``m/s^2``)."""
    return ASCII_UNITS.get(unit, unit)


def unit_in_name(unit: str) -> str:
    """``unit`` as part of a file or column name: ``m/s²`` → ``m_per_s2``, ``N m`` → ``N_m``."""
    return ascii_unit(unit).replace("/", "_per_").replace("^", "").replace(" ", "_")


__all__ = [
    "INPUT_UNITS",
    "ASCII_UNITS",
    "BODY_QUANTITIES",
    "BODY_QUANTITY_UNITS",
    "COMPONENTS",
    "DEFAULT_OUTPUTS",
    "INTEGRATORS",
    "INTERPOLATIONS",
    "JOINT_COLUMNS",
    "JOINT_COLUMN_UNITS",
    "FILM_COLUMN_UNITS",
    "JOINT_QUANTITIES",
    "JOINT_QUANTITY_UNITS",
    "JOINT_MONITOR_UNITS",
    "REACTION_MONITOR_UNITS",
    "OUTPUTS",
    "POINT_MONITOR_COMPONENTS",
    "READING_MONITOR_UNITS",
    "REFERENCES",
    "ascii_unit",
    "body_unit",
    "unit_in_name",
]
