"""The ``[sweep]`` table of a scene file, read and checked: a bifurcation diagram over one field
of the mechanism (``clearsim sweep``; :func:`clearsim.dynamics.bifurcation`).

::

    [sweep]                            # clearsim sweep scene.toml
    parameter = "crank-drive.omega"    # element.field of the mechanism, SI units
    values = { start = 100.0, stop = 600.0, count = 200 }   # or a list [v1, v2, ...]
    output = { body = "slider", quantity = "acceleration", component = "x" }
    # output = { body = "coupler", point = [0.1, 0.02], quantity = "velocity", component = "x" }
    #                                  # a point's on the body (body frame [m]): x | y | magnitude
    # output = { joint = "rod-slider", quantity = "eccentricity" }
    #                                  # eccentricity (e/c) | eccentricity_x | eccentricity_y [m]
    #                                  #   | force | contact_force [N]
    transient_cycles = 20              # forcing periods run before the sections are taken
    cycles = 100                       # periods analysed (section points per value)
    # period = 0.012                   # s (default: the forcing period of each mechanism)
    # phase = 0.0                      # rad of the period at which the sections are taken
    # lyapunov = "auto"                # auto (for the values not periodic) | true | false
    # tol = 1e-3                       # a repeat within this fraction of each feature's range
    # label = "crank speed"            # axis label (default: the parameter's path)

The integrator and its tolerances are ``[simulation]``'s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, List, Optional, Tuple, Union

import numpy as np

from ..errors import InputError
from ..mechanism import Mechanism
from ..points import check_point_output
from ..schema import INPUT_UNITS
from .toml_reader import Table

SWEEP_KEYS = ("parameter", "values", "output", "transient_cycles", "cycles", "period", "phase", "lyapunov", "tol", "label")
_VALUE_KEYS = ("start", "stop", "count")
_OUTPUT_KEYS = ("body", "point", "joint", "quantity", "component")


@dataclass(frozen=True)
class SweepSettings:
    """A scene's ``[sweep]``: the arguments of :func:`clearsim.dynamics.bifurcation`."""

    parameter: str
    values: List[float]
    output: Union[Tuple[str, str, str], Tuple[str, str]]
    transient_cycles: int = 20
    #: The output's point on its body (body frame [m]; ``output.point``), or None.
    point: Optional[Tuple[float, float]] = None
    cycles: int = 100
    period: Optional[float] = None
    phase: float = 0.0
    lyapunov: Union[bool, str] = "auto"
    tol: float = 1e-3
    label: str = ""

    @property
    def unit(self) -> str:
        """The parameter's unit (by its field's name, :data:`clearsim.schema.INPUT_UNITS`; "" if unknown)."""
        return INPUT_UNITS.get(self.parameter.rsplit(".", 1)[-1], "")


def parse_sweep(t: Table, mechanism: Mechanism) -> SweepSettings:
    """The ``[sweep]`` table ``t`` of a scene whose mechanism is ``mechanism`` (the parameter's
    path is checked on it: an unknown element or field is an error at its line)."""
    parameter = t.string("parameter")
    raw = t._get("values", None)
    if isinstance(raw, dict):
        sub = t.table("values", _VALUE_KEYS)
        assert sub is not None
        count = sub.integer("count")
        if count < 1:
            raise sub.error("count", f"invalid sweep.values.count = {count!r}: must be at least 1", count)
        values = [float(v) for v in np.linspace(sub.number("start"), sub.number("stop"), count)]
    else:
        values = t.numbers("values")
        if not values:
            raise t.error("values", "invalid sweep.values = []: give at least one value", values)
    try:
        mechanism.with_values({parameter: values[0]})
    except InputError as err:
        raise t.error("parameter", f"invalid sweep.parameter = {parameter!r}: {err.reason}", parameter) from None
    out = t.table("output", _OUTPUT_KEYS)
    if out is None:
        raise t.error(None, "missing key 'output' in [sweep] ({body, quantity, component} or {joint, quantity})")
    if ("body" in out) == ("joint" in out):
        raise out.error(None, "invalid sweep.output: give body (with quantity and component) or joint (with quantity)")
    output: Union[Tuple[str, str, str], Tuple[str, str]]
    point: Optional[Tuple[float, float]] = None
    if "body" in out:
        output = (out.string("body"), out.string("quantity"), out.string("component"))
        if "point" in out:
            try:
                point = check_point_output(output[0], out.numbers("point", length=2), output[2], mechanism.body_names, "sweep.output")
            except InputError as err:
                raise out.error(str(err.field).rsplit(".", 1)[-1], err.reason, err.value) from None
    else:
        if "point" in out:
            raise out.error("point", "invalid sweep.output.point: a point lies on a body (give body, point, quantity and component)")
        if "component" in out:
            raise out.error("component", "invalid sweep.output.component: a joint output has none (eccentricity_x, eccentricity_y for its parts)")
        output = (out.string("joint"), out.string("quantity"))
    lyap = t._get("lyapunov", "auto")
    if lyap not in ("auto", True, False):
        raise t.error("lyapunov", f"invalid sweep.lyapunov = {lyap!r}: must be \"auto\", true or false", lyap)
    return SweepSettings(
        parameter, values, output, transient_cycles=t.integer("transient_cycles", 20), cycles=t.integer("cycles", 100),
        period=t.number("period", None), phase=t.number("phase", 0.0), lyapunov=lyap, tol=t.number("tol", 1e-3),
        label=t.string("label", ""), point=point,
    )  # fmt: skip


__all__ = ["SWEEP_KEYS", "SweepSettings", "parse_sweep"]
