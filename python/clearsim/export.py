"""Results out of clearsim: pandas, xarray, CSV and NetCDF, with names and SI units.

``Result.to_pandas()``, ``Result.to_xarray()`` and ``Result.save(path)`` call these. pandas and
xarray (and netCDF4 for ``.nc`` files) are optional: ``pip install 'clearsim[io]'``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Protocol, Sequence, Tuple

import numpy as np

from . import _core
from .csvfile import write_columns
from .errors import InputError, check_choice
from .points import POINT_COMPONENTS, PointsLike, tracked_points
from .schema import BODY_QUANTITIES, BODY_QUANTITY_UNITS, COMPONENTS, FILM_COLUMN_UNITS, JOINT_COLUMN_UNITS, JOINT_COLUMNS, ascii_unit


class Result(Protocol):
    """What the writers read of a :class:`clearsim.Result` (result.py calls them, so they name
    the result by what they use rather than import it)."""

    _raw: Dict[str, Any]
    t: np.ndarray
    body_names: List[str]
    joint_names: List[str]
    stats: Dict[str, Any]
    failure: Any
    description: Optional[Dict[str, Any]]

    @property
    def completed(self) -> bool: ...

    def point(self, body: str, point: Sequence[float], quantity: str = ...) -> np.ndarray: ...

    def error(self, ideal: Any, body: str, quantity: str = ..., point: Optional[Sequence[float]] = ...) -> np.ndarray: ...

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
_SUFFIX = {"position": "", "velocity": "_dot", "acceleration": "_ddot"}


def _require(module: str, what: str = "this export") -> Any:
    """The optional ``module``, or an ImportError naming the extra that installs it."""
    try:
        return __import__(module)
    except ImportError:
        raise ImportError(f"{module} is needed for {what}: pip install 'clearsim[io]'") from None


#: The units of a reaction's columns (:meth:`clearsim.Result.joint_force`, ``driver_torque``).
REACTION_UNITS: Dict[str, str] = {"fx": "N", "fy": "N", "torque": "N m"}


def reaction_columns(res: "Result") -> List[Tuple[str, str, np.ndarray]]:
    """With ``"reactions"`` stored: per ideal joint ``A.fx``, ``A.fy`` [N] (the force on its
    second body, global; a prismatic joint also ``G.torque`` [N m], its couple) and per driver
    ``drive.torque`` [N m], in the core's order (joints, then drivers)."""
    raw, desc = res._raw, res.description
    if "reactions" not in raw or desc is None:
        return []
    out: List[Tuple[str, str, np.ndarray]] = []
    kinds = [(j["name"], j["kind"]) for j in desc["joints"]] + [(d["name"], "driver") for d in desc["drivers"]]
    for k, (name, kind) in enumerate(kinds):
        wanted = {"revolute": ("fx", "fy"), "prismatic": ("fx", "fy", "torque"), "driver": ("torque",)}[kind]
        for c, col in enumerate(REACTION_UNITS):
            if col in wanted:
                out.append((f"{name}.{col}", REACTION_UNITS[col], raw["reactions"][:, k, c]))
    return out


def point_columns(res: "Result", points: Optional[PointsLike]) -> List[Tuple[str, str, np.ndarray]]:
    """Per named point (:data:`clearsim.points.PointsLike`) its global ``tool.x``, ``tool.y``
    [m], ``tool.x_dot``, ``tool.y_dot`` [m/s] (with states stored) and ``tool.x_ddot``,
    ``tool.y_ddot`` [m/s²] (with accelerations stored)."""
    if not points:
        return []
    out: List[Tuple[str, str, np.ndarray]] = []
    stored = {"displacement": "q" in res._raw, "velocity": "q" in res._raw, "acceleration": "qdd" in res._raw and "q" in res._raw}
    taken = set(res.body_names) | set(res.joint_names) | {name.split(".")[0] for name, _, _ in reaction_columns(res)}
    for p in tracked_points(points, res.body_names):
        if p.name in taken:  # its columns would overwrite the body's or joint's of the same name
            raise InputError(f"invalid points[{p.name!r}]: {p.name!r} is already a body's or joint's name; name the point otherwise", field="points", value=p.name)
        for var, quantity in zip(_SUFFIX, BODY_QUANTITIES):
            if stored[quantity]:
                values = res.point(p.body, p.point, quantity)
                unit = BODY_QUANTITY_UNITS[quantity][0]
                out += [(f"{p.name}.{c}{_SUFFIX[var]}", unit, values[:, k]) for k, c in enumerate(POINT_COMPONENTS)]
    return out


def error_columns(errors: Mapping[Tuple[str, str], np.ndarray], components: Sequence[str] = COMPONENTS) -> List[Tuple[str, str, np.ndarray]]:
    """Columns ``<name>.<quantity>_error.<component>`` with units of errors against the ideal run
    (clearance − ideal), keyed by (body or point name, quantity): an (N, 3) body error gives the
    ``components`` asked for, an (N, 2) point error its x and y among them (both if neither is)."""
    out: List[Tuple[str, str, np.ndarray]] = []
    for (name, quantity), err in errors.items():
        names = COMPONENTS if err.shape[1] == 3 else POINT_COMPONENTS
        chosen = [c for c in names if c in components] or list(names)
        for c in chosen:
            unit = BODY_QUANTITY_UNITS[quantity][c == "theta"]
            out.append((f"{name}.{quantity}_error.{c}", unit, err[:, names.index(c)]))
    return out


def errors_table(res: "Result", ideal: "Result", bodies: Optional[Sequence[str]], points: Optional[PointsLike], quantities: Optional[Sequence[str]]) -> Any:
    """:meth:`clearsim.Result.errors_table`: a DataFrame of :func:`error_columns` over the
    outputs both runs have, ``df.attrs["units"]`` per column."""
    pd = _require("pandas")
    wanted = list(BODY_QUANTITIES) if quantities is None else [check_choice("quantities", q, list(BODY_QUANTITIES)) for q in quantities]
    named = tracked_points(points, res.body_names) if points else []
    body_list = list(res.body_names) if bodies is None and not named else list(bodies or [])
    errors: Dict[Tuple[str, str], np.ndarray] = {}
    for body in body_list:
        for q in wanted:
            errors[(body, q)] = res.error(ideal, body, q)
    for p in named:
        for q in wanted:
            errors[(p.name, q)] = res.error(ideal, p.body, q, point=p.point)
    cols = error_columns(errors)
    n = min(len(res.t), len(ideal.t))
    df = pd.DataFrame({name: values for name, _, values in cols}, index=pd.Index(res.t[:n], name="t"))
    df.attrs["units"] = {"t": "s", **{name: unit for name, unit, _ in cols}}
    return df


def columns(res: "Result", points: Optional[PointsLike] = None) -> List[Tuple[str, str, np.ndarray]]:
    """Every stored output as (column name, units, values over res.t): ``slider9.y`` [m],
    ``slider9.y_dot`` [m/s], ``slider9.y_ddot`` [m/s²], ``A.ex`` [m], ..., ``violation`` [-],
    then the reactions (:func:`reaction_columns`) and the ``points`` (:func:`point_columns`)."""
    raw = res._raw
    out: List[Tuple[str, str, np.ndarray]] = []
    for var, key, _, units in BODY_VARIABLES:
        if key not in raw:
            continue
        for b, body in enumerate(res.body_names):
            for k, (coord, unit) in enumerate(zip(COMPONENTS, units)):
                out.append((f"{body}.{coord}{_SUFFIX[var]}", unit, raw[key][:, 3 * b + k]))
    if "joints" in raw:
        for j, joint in enumerate(res.joint_names):
            for c, col in enumerate(JOINT_COLUMNS):
                out.append((f"{joint}.{col}", JOINT_COLUMN_UNITS.get(col, "1"), raw["joints"][:, j, c]))
    if "film" in raw:
        for j, joint in enumerate(res.joint_names):
            for c, col in enumerate(_core.FILM_COLUMNS):
                out.append((f"{joint}.{col}", FILM_COLUMN_UNITS[col], raw["film"][:, j, c]))
    if "violation" in raw:
        out.append(("constraint_violation", "m or rad", raw["violation"][:, 0]))
        out.append(("velocity_violation", "m/s or rad/s", raw["violation"][:, 1]))
    return out + reaction_columns(res) + point_columns(res, points)


def to_pandas(res: "Result", points: Optional[PointsLike] = None) -> Any:
    """A DataFrame indexed by time [s] (index name ``t``), one column per stored output
    (see :func:`columns`); ``df.attrs["units"]`` maps each column to its units."""
    pd = _require("pandas")
    cols = columns(res, points)
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
    coords: Dict[str, Any] = {"time": ("time", res.t, {"units": "s", "long_name": "time"}), "body": list(res.body_names), "coordinate": list(COMPONENTS)}
    if "joints" in raw and res.joint_names:
        data["clearance_joint"] = (("time", "joint", "quantity"), raw["joints"], {"long_name": "clearance-joint quantities", "units_by_quantity": [JOINT_COLUMN_UNITS.get(c, "1") for c in JOINT_COLUMNS]})
        coords["joint"] = list(res.joint_names)
        coords["quantity"] = list(JOINT_COLUMNS)
    if "violation" in raw:
        data["constraint_violation"] = (("time",), raw["violation"][:, 0], {"long_name": "norm of the constraint equations", "units": "m or rad"})
    if "reactions" in raw and res.description is not None:
        names = [j["name"] for j in res.description["joints"]] + [d["name"] for d in res.description["drivers"]]
        long_name = "force (x, y) and torque each ideal joint and driver exerts on its second body (global frame)"
        data["reaction"] = (("time", "constraint", "reaction_component"), raw["reactions"], {"long_name": long_name, "units_by_component": list(REACTION_UNITS.values())})
        coords["constraint"] = names
        coords["reaction_component"] = list(REACTION_UNITS)
    attrs = {"integrator": str(res.stats.get("integrator", "")), "completed": int(res.completed), "software": "clearsim"}
    if res.failure is not None:
        attrs["failure"] = str(res.failure)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def save(res: "Result", path: "str | Path", points: Optional[PointsLike] = None) -> Path:
    """Write the result to ``.csv`` (one column per output, units in the header: ``slider9.y [m]``;
    ``points`` as :func:`point_columns`) or ``.nc`` (NetCDF 4 through xarray and netCDF4: an
    ImportError naming ``pip install 'clearsim[io]'`` when either is missing). Returns the path."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        write_columns(path, [("t", "s", res.t)] + columns(res, points))
    elif suffix in (".nc", ".netcdf"):
        # Both before anything is written: without netCDF4 xarray would fall back to another
        # engine (scipy's NetCDF 3) or fail with its own message.
        for module in ("xarray", "netCDF4"):
            _require(module, f"saving {path.name} (NetCDF 4 through xarray)")
        ds = to_xarray(res)
        # NetCDF attributes take strings and numbers; lists of unit strings are joined.
        for var in ds.data_vars.values():
            for key in [k for k, v in var.attrs.items() if isinstance(v, list)]:
                var.attrs[key] = ", ".join(var.attrs[key])
        ds.to_netcdf(path, engine="netcdf4")
    else:
        raise InputError(f"invalid path = {str(path)!r}: save writes .csv or .nc files", field="path", value=str(path))
    return path
