"""The names clearsim uses across its layers, defined once: the components of a pose, the
quantities a run reports of a body or a clearance joint with their SI units, the integrators
and the output channels (the Rust core's names, ``rust/settings.rs``).

Units: one spelling per layer. Python text (docstrings, labels, error messages) writes
``m/s²`` and ``rad/s²``; files written for other tools (CSV headers, NetCDF attributes) write
ASCII ``m/s^2`` and ``rad/s^2`` (:data:`ASCII_UNITS`); a unit inside a file name is ``m_per_s2``.
"""

from __future__ import annotations

from typing import Dict, List, Tuple

from . import _core

#: The components of a body's pose q = (x, y, θ), in the order of the state and of every result
#: array: x, y [m] and theta [rad] (one word for them throughout: "component").
COMPONENTS: Tuple[str, str, str] = ("x", "y", "theta")
#: The integrators of :meth:`clearsim.Mechanism.simulate` (``"auto"`` picks one per mechanism).
INTEGRATORS: Tuple[str, ...] = ("auto", "rk45", "rk4", "dop853", "radau", "rodas4")
#: The channels a run can store, and those it stores by default.
OUTPUTS: Tuple[str, ...] = ("states", "accelerations", "reactions", "joints", "violation", "energy")
DEFAULT_OUTPUTS: Tuple[str, ...] = ("states", "accelerations", "joints", "violation")

#: The columns of a clearance joint's stored channel (``Result.joint``), the core's order.
JOINT_COLUMNS: List[str] = list(_core.JOINT_COLUMNS)
#: Units of those columns (``"1"``: dimensionless).
JOINT_COLUMN_UNITS: Dict[str, str] = {
    "ex": "m", "ey": "m", "ex_dot": "m/s", "ey_dot": "m/s", "fx": "N", "fy": "N",
    "normal": "N", "tangential": "N", "film_xi": "N", "film_eta": "N", "w_dry": "1", "state": "1",
    "film_thickness": "m", "friction_torque": "N m", "friction_torque_bearing": "N m", "couette_torque": "N m",
    "poiseuille_torque": "N m", "power_loss": "W", "asperity_force": "N",
}  # fmt: skip

#: The quantities of a body coordinate (its extremes, its error against the ideal mechanism)
#: and their units: (of x and y, of theta).
BODY_QUANTITY_UNITS: Dict[str, Tuple[str, str]] = {
    "displacement": ("m", "rad"),
    "velocity": ("m/s", "rad/s"),
    "acceleration": ("m/s²", "rad/s²"),
}
BODY_QUANTITIES: Tuple[str, ...] = tuple(BODY_QUANTITY_UNITS)
#: The quantities of a clearance joint a study or the extremes watch, and their units.
#: ``film_thickness`` is the smallest gap over a window, h_min = c (1 − ε_max) [m], from the
#: monitored eccentricity's peak (docs/physics.md §4).
JOINT_QUANTITY_UNITS: Dict[str, str] = {
    "eccentricity": "-",
    "force": "N",
    "contact_force": "N",
    "film_force": "N",
    "film_thickness": "m",
}
JOINT_QUANTITIES: Tuple[str, ...] = tuple(JOINT_QUANTITY_UNITS)

def body_unit(quantity: str, component: str) -> str:
    """The SI unit of ``quantity`` (:data:`BODY_QUANTITIES`) of a body's ``component``."""
    return BODY_QUANTITY_UNITS[quantity][1 if component == "theta" else 0]


#: Units as files for other tools write them (ASCII).
ASCII_UNITS: Dict[str, str] = {"m/s²": "m/s^2", "rad/s²": "rad/s^2"}


def ascii_unit(unit: str) -> str:
    """``unit`` as a CSV header or a NetCDF attribute writes it (``m/s²`` → ``m/s^2``)."""
    return ASCII_UNITS.get(unit, unit)


__all__ = [
    "ASCII_UNITS",
    "BODY_QUANTITIES",
    "BODY_QUANTITY_UNITS",
    "COMPONENTS",
    "DEFAULT_OUTPUTS",
    "INTEGRATORS",
    "JOINT_COLUMNS",
    "JOINT_COLUMN_UNITS",
    "JOINT_QUANTITIES",
    "JOINT_QUANTITY_UNITS",
    "OUTPUTS",
    "ascii_unit",
    "body_unit",
]
