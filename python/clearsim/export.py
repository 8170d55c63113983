"""Results out of clearsim: pandas, xarray, CSV and NetCDF, with names and SI units.

``Result.to_pandas()``, ``Result.to_xarray()`` and ``Result.save(path)`` call these. pandas and
xarray (and netCDF4 for ``.nc`` files) are optional: ``pip install 'clearsim[io]'``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List, Protocol, Tuple

import numpy as np

from . import _core
from .csvfile import write_columns
from .errors import InputError
from .schema import BODY_QUANTITY_UNITS, COMPONENTS, FILM_COLUMN_UNITS, JOINT_COLUMN_UNITS, JOINT_COLUMNS, ascii_unit


class Result(Protocol):
    """What the writers read of a :class:`clearsim.Result` (result.py calls them, so they name
    the result by what they use rather than import it)."""

    _raw: Dict[str, Any]
    t: np.ndarray
    body_names: List[str]
    joint_names: List[str]
    stats: Dict[str, Any]
    failure: Any

    @property
    def completed(self) -> bool: ...

#: Old name of :data:`clearsim.schema.COMPONENTS` here.
COORDINATES = COMPONENTS
#: (variable, raw key, long name, units of x, y, θ)
def _units(quantity: str) -> Tuple[str, str, str]:
    """The ASCII units of x, y and θ of a body quantity (:data:`clearsim.schema.BODY_QUANTITY_UNITS`)."""
    xy, theta = (ascii_unit(u) for u in BODY_QUANTITY_UNITS[quantity])
    return (xy, xy, theta)


BODY_VARIABLES: Tuple[Tuple[str, str, str, Tuple[str, str, str]], ...] = (
    ("position", "q", "centroid position and angle", _units("displacement")),
    ("velocity", "qd", "centroid velocity and angular velocity", _units("velocity")),
    ("acceleration", "qdd", "centroid acceleration and angular acceleration", _units("acceleration")),
)
#: Units of the clearance-joint columns (old name of :data:`clearsim.schema.JOINT_COLUMN_UNITS`).
JOINT_UNITS: Dict[str, str] = JOINT_COLUMN_UNITS
_SUFFIX = {"position": "", "velocity": "_dot", "acceleration": "_ddot"}


def _require(module: str) -> Any:
    try:
        return __import__(module)
    except ImportError:
        raise ImportError(f"{module} is needed for this export: pip install 'clearsim[io]'") from None


def columns(res: "Result") -> List[Tuple[str, str, np.ndarray]]:
    """Every stored output as (column name, units, values over res.t): ``slider9.y`` [m],
    ``slider9.y_dot`` [m/s], ``slider9.y_ddot`` [m/s²], ``A.ex`` [m], ..., ``violation`` [-]."""
    raw = res._raw
    out: List[Tuple[str, str, np.ndarray]] = []
    for var, key, _, units in BODY_VARIABLES:
        if key not in raw:
            continue
        for b, body in enumerate(res.body_names):
            for k, (coord, unit) in enumerate(zip(COORDINATES, units)):
                out.append((f"{body}.{coord}{_SUFFIX[var]}", unit, raw[key][:, 3 * b + k]))
    if "joints" in raw:
        for j, joint in enumerate(res.joint_names):
            for c, col in enumerate(JOINT_COLUMNS):
                out.append((f"{joint}.{col}", JOINT_UNITS.get(col, "1"), raw["joints"][:, j, c]))
    if "film" in raw:
        for j, joint in enumerate(res.joint_names):
            for c, col in enumerate(_core.FILM_COLUMNS):
                out.append((f"{joint}.{col}", FILM_COLUMN_UNITS[col], raw["film"][:, j, c]))
    if "violation" in raw:
        out.append(("constraint_violation", "m or rad", raw["violation"][:, 0]))
        out.append(("velocity_violation", "m/s or rad/s", raw["violation"][:, 1]))
    return out


def to_pandas(res: "Result") -> Any:
    """A DataFrame indexed by time [s] (index name ``t``), one column per stored output
    (see :func:`columns`); ``df.attrs["units"]`` maps each column to its units."""
    pd = _require("pandas")
    cols = columns(res)
    df = pd.DataFrame({name: values for name, _, values in cols}, index=pd.Index(res.t, name="t"))
    df.attrs["units"] = {"t": "s", **{name: unit for name, unit, _ in cols}}
    return df


def to_xarray(res: "Result") -> Any:
    """An xarray Dataset over ``time`` [s]: ``position``, ``velocity``, ``acceleration`` on
    (time, body, coordinate) with coordinate = x, y, theta; ``clearance_joint`` on (time, joint,
    quantity) for clearance joints; ``constraint_violation``. Units and long names in attrs."""
    xr = _require("xarray")
    raw = res._raw
    data: Dict[str, Any] = {}
    for var, key, long_name, units in BODY_VARIABLES:
        if key in raw:
            values = raw[key].reshape(len(res.t), len(res.body_names), 3)
            data[var] = (("time", "body", "coordinate"), values, {"long_name": long_name, "units": ", ".join(units), "units_by_coordinate": list(units)})
    coords: Dict[str, Any] = {"time": ("time", res.t, {"units": "s", "long_name": "time"}), "body": list(res.body_names), "coordinate": list(COORDINATES)}
    if "joints" in raw and res.joint_names:
        data["clearance_joint"] = (("time", "joint", "quantity"), raw["joints"], {"long_name": "clearance-joint quantities", "units_by_quantity": [JOINT_UNITS.get(c, "1") for c in JOINT_COLUMNS]})
        coords["joint"] = list(res.joint_names)
        coords["quantity"] = list(JOINT_COLUMNS)
    if "violation" in raw:
        data["constraint_violation"] = (("time",), raw["violation"][:, 0], {"long_name": "norm of the constraint equations", "units": "m or rad"})
    attrs = {"integrator": str(res.stats.get("integrator", "")), "completed": int(res.completed), "software": "clearsim"}
    if res.failure is not None:
        attrs["failure"] = str(res.failure)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def save(res: "Result", path: "str | Path") -> Path:
    """Write the result to ``.csv`` (one column per output, units in the header: ``slider9.y [m]``)
    or ``.nc`` (NetCDF through xarray). Returns the path."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        write_columns(path, [("t", "s", res.t)] + columns(res))
    elif suffix in (".nc", ".netcdf"):
        ds = to_xarray(res)
        # NetCDF attributes take strings and numbers; lists of unit strings are joined.
        for var in ds.data_vars.values():
            for key in [k for k, v in var.attrs.items() if isinstance(v, list)]:
                var.attrs[key] = ", ".join(var.attrs[key])
        ds.to_netcdf(path)
    else:
        raise InputError(f"invalid path = {str(path)!r}: save writes .csv or .nc files", field="path", value=str(path))
    return path
