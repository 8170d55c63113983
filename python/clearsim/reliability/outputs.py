"""What a reliability study watches: the analysed :class:`Output` (a body coordinate's or a body
point's error against the reference motion, or a clearance joint's quantity) and its :class:`Limit` (failure
when the output's peak passes above it, or its minimum falls below it).

A study with several outputs is a series system: it fails when any output passes its limit
(docs/reliability.md, "Several failure modes").
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ..errors import InputError, check_choice, check_finite, check_positive
from ..points import check_point, point_name
from ..schema import BODY_QUANTITIES, COMPONENTS, JOINT_QUANTITIES, JOINT_QUANTITY_UNITS, POINT_MONITOR_COMPONENTS, body_unit

__all__ = ["BODY_QUANTITIES", "JOINT_QUANTITIES", "Output", "Limit", "Modes", "as_limit"]

# BODY_QUANTITIES: the quantities of a body coordinate's error against the ideal mechanism;
# JOINT_QUANTITIES: those of a clearance joint (clearsim.schema, with their units).
SIDES = ("above", "below")


@dataclass(frozen=True)
class Output:
    """The analysed output: a body coordinate's or a body point's error against the reference
    motion (the study's ``reference``: each sample's ideal twin or the nominal design's ideal),
    or a clearance joint's quantity.

    ``Output(body="slider9", component="y", quantity="displacement" | "velocity" | "acceleration")``:
    |response − reference response| of the body's centroid in m, m/s, m/s² (``component="x"``/``"y"``)
    or rad, rad/s, rad/s² (``component="theta"``).

    ``Output(body="coupler", point=(0.1, 0.02), component="x" | "y" | "magnitude", quantity=...)``:
    the error of a point fixed on the body (body frame [m], as joints take their points): its
    global displacement r + A p, velocity ṙ + θ̇ B p or acceleration r̈ + θ̈ B p − θ̇² A p, its
    x or y component, or the magnitude of the error vector |P − P_ref| [m, m/s, m/s²].

    ``Output(joint="B", quantity="eccentricity" | "force" | "contact_force" | "film_force" |
    "film_thickness")``: the eccentricity ratio ε = e/c [-], the magnitude of the joint's total
    force [N], its dry normal force F_N [N], its film force magnitude [N], or the smallest gap
    h_min = c (1 − ε_max) [m] over the window (limit it from below: :meth:`Limit.below`).
    """

    body: Optional[str] = None
    component: Optional[str] = None
    joint: Optional[str] = None
    quantity: str = "displacement"
    #: A point fixed on ``body`` (body frame [m]); ``None``: the body's centroid.
    point: Optional[Tuple[float, float]] = None

    def __post_init__(self) -> None:
        if (self.body is None) == (self.joint is None):
            raise InputError("invalid Output: give exactly one of body= (with component=) or joint=", field="Output.body", value=self.body)
        if self.body is not None:
            if self.point is not None:
                object.__setattr__(self, "point", check_point(self.point, "Output.point"))
                check_choice("Output.component", self.component, POINT_MONITOR_COMPONENTS, "(a point's: there is no default)")
            else:
                check_choice("Output.component", self.component, COMPONENTS, "(there is no default)")
            if self.quantity not in BODY_QUANTITIES:
                raise InputError(f"invalid Output.quantity = {self.quantity!r}: a body output is one of {', '.join(BODY_QUANTITIES)}", field="Output.quantity", value=self.quantity)
        else:
            if self.point is not None:
                raise InputError(f"invalid Output.point = {self.point!r}: a joint output has no point (give body= with point=)", field="Output.point", value=self.point)
            if self.component is not None:
                raise InputError(f"invalid Output.component = {self.component!r}: a joint output has no component", field="Output.component", value=self.component)
            if self.quantity not in JOINT_QUANTITIES:
                raise InputError(f"invalid Output.quantity = {self.quantity!r}: a joint output is one of {', '.join(JOINT_QUANTITIES)}", field="Output.quantity", value=self.quantity)

    def target(self, body_names: List[str], joint_names: List[str]) -> Dict[str, Any]:
        """What the core's monitor watches for this output (``rust/monitor/target.rs``), by the
        index of its body (coordinate: 3 per body, x, y, θ) or clearance joint in a mechanism
        with these names; an unknown name is an InputError naming the known ones."""
        if self.body is not None:
            if self.body not in body_names:
                raise InputError(f"invalid Output.body = {self.body!r}: no such body (known: {', '.join(body_names)})", field="Output.body", value=self.body)
            b = body_names.index(self.body)
            if self.point is not None:
                return {"body": b, "point": list(self.point), "component": self.component}
            return {"coordinate": 3 * b + COMPONENTS.index(str(self.component))}
        if self.joint not in joint_names:
            raise InputError(f"invalid Output.joint = {self.joint!r}: no such clearance joint (known: {', '.join(joint_names) or 'none'})", field="Output.joint", value=self.joint)
        return {"coordinate": joint_names.index(str(self.joint))}

    @property
    def unit(self) -> str:
        """Unit of the output (and of its limit)."""
        if self.joint is not None:
            return JOINT_QUANTITY_UNITS[self.quantity]
        return body_unit(self.quantity, "x" if self.point is not None else str(self.component))

    @property
    def label(self) -> str:
        if self.joint is not None:
            return f"{self.quantity.replace('_', ' ')} of joint {self.joint}"
        if self.point is not None:
            return f"{self.component} {self.quantity} error of point ({self.point[0]:g}, {self.point[1]:g}) of {self.body}"
        return f"{self.component} {self.quantity} error of {self.body}"

    @property
    def name(self) -> str:
        """A short name for tables and CSV headers: ``slider9.y.displacement``,
        ``coupler(0.1,0.02).magnitude.displacement`` (a point, body frame [m]), ``B.eccentricity``."""
        if self.joint is not None:
            return f"{self.joint}.{self.quantity}"
        if self.point is not None:
            return f"{point_name(str(self.body), self.point)}.{self.component}.{self.quantity}"
        return f"{self.body}.{self.component}.{self.quantity}"

    @property
    def monitored(self) -> str:
        """The quantity the integrator's monitor tracks for this output."""
        return "eccentricity" if self.quantity == "film_thickness" else self.quantity


@dataclass(frozen=True)
class Limit:
    """The limit of one output: failure when the output's peak over the window passes ``value``
    (``side="above"``, the default: an error, a force) or when its minimum falls below ``value``
    (``side="below"``: a film thickness). ``value`` is in the output's unit: positive for an
    upper limit, non-zero for a lower one (a negative smallest gap is a penetration depth).

    ``Limit.above(1e-3)``, ``Limit.below(2e-6)``; a study also takes a bare number (above) or
    ``("below", 2e-6)``."""

    value: float
    side: str = "above"

    def __post_init__(self) -> None:
        check_choice("Limit.side", self.side, SIDES)
        if self.side == "above":
            object.__setattr__(self, "value", check_positive("Limit.value", self.value))
        elif check_finite("Limit.value", self.value) == 0.0:
            raise InputError("invalid Limit.value = 0: a lower limit must be non-zero (g is scaled by it)", field="Limit.value", value=self.value)

    @classmethod
    def above(cls, value: float) -> "Limit":
        """Failure when the output's peak exceeds ``value``."""
        return cls(value, "above")

    @classmethod
    def below(cls, value: float) -> "Limit":
        """Failure when the output's minimum falls below ``value``."""
        return cls(value, "below")

    def g(self, extreme: Any) -> np.ndarray:
        """The limit-state value of the output's extreme over the window (peak for ``above``,
        minimum for ``below``), scaled by the limit: ``1 − x/value`` or
        ``(x − value)/|value|``; failure when ``g ≤ 0``."""
        x = np.asarray(extreme, dtype=float)
        return 1.0 - x / self.value if self.side == "above" else (x - self.value) / abs(self.value)

    def exceeded(self, extreme: Any) -> np.ndarray:
        """Whether the extreme passes the limit (NaN: no)."""
        x = np.asarray(extreme, dtype=float)
        with np.errstate(invalid="ignore"):
            return (x > self.value) if self.side == "above" else (x < self.value)

    def text(self, unit: str) -> str:
        return f"{'≤' if self.side == 'above' else '≥'} {self.value:g} {unit}"


class Modes:
    """The failure modes of a study: its outputs with their limits (one each, or several: a
    series system), and the first of each as a study of one output names them."""

    outputs: List[Output]
    limits: List[Limit]

    @property
    def output(self) -> Output:
        """The analysed output (the first one of a system)."""
        return self.outputs[0]

    @property
    def limit(self) -> float:
        """The limit's value [output unit] (the first output's, for a system)."""
        return self.limits[0].value


def as_limit(value: Any, output: Output, field: str = "limit") -> Limit:
    """A study's limit of ``output`` given as a :class:`Limit`, a positive number (above) or
    ``("above" | "below", number)``."""
    if value is None:
        raise InputError(f"missing {field}: the limit of the {output.label} [{output.unit}] is required (there is no default)", field=field, value=None)
    if isinstance(value, Limit):
        limit = value
    elif isinstance(value, (tuple, list)):
        if len(value) != 2 or value[0] not in SIDES:
            raise InputError(f"invalid {field} = {value!r}: give a number, ('above', x), ('below', x) or Limit.above/below(x)", field=field, value=value)
        limit = Limit(check_finite(field, value[1]), str(value[0]))
    else:
        limit = Limit(check_positive(field, value), "above")
    if output.quantity == "film_thickness" and limit.side != "below":
        raise InputError(
            f"invalid {field} = {value!r}: a film thickness fails by getting thin; give Limit.below(h_allow) or ('below', h_allow) [m]",
            field=field, value=value,
        )  # fmt: skip
    return limit


def limits_and_outputs(output: Any, limit: Any) -> Tuple[list, list]:
    """The outputs and their limits of a study: one :class:`Output` with one limit, or lists of
    equal length (a series system)."""
    outs = list(output) if isinstance(output, (list, tuple)) else [output]
    if not outs:
        raise InputError("invalid output = []: give at least one Output", field="output", value=output)
    for k, o in enumerate(outs):
        if not isinstance(o, Output):
            where = "output" if len(outs) == 1 and not isinstance(output, (list, tuple)) else f"output[{k}]"
            raise InputError(f"invalid {where} = {o!r}: must be a clearsim.reliability.Output", field=where, value=o)
    if isinstance(output, (list, tuple)):
        if limit is None:
            raise InputError(f"missing limit: give one limit per output ({len(outs)})", field="limit", value=None)
        lims = list(limit) if isinstance(limit, (list, tuple)) and not (len(limit) == 2 and limit[0] in SIDES) else [limit]
        if len(lims) != len(outs):
            raise InputError(f"invalid limit = {limit!r}: {len(lims)} limits for {len(outs)} outputs", field="limit", value=limit)
        return outs, [as_limit(v, o, f"limit[{k}]") for k, (v, o) in enumerate(zip(lims, outs))]
    return outs, [as_limit(limit, outs[0])]
