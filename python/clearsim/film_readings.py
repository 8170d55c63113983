"""The oil a lubricated joint passes and the pressure its film builds (docs/physics.md §4, "Oil flow
and pressure"): side leakage, supply flow and peak pressure over a run (the core's ``film``
channel, ``outputs=[..., "film"]``: rust/clearance/readings.rs) and the pressure field at an
output time (solved from the stored state when asked: ``CompiledModel.film_field``).

:class:`FilmReadings` holds these methods of :class:`clearsim.Result`; :func:`film_summary` adds
their summary to :meth:`clearsim.Result.bearing_summary`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _core, display
from .errors import InputError, check_choice

#: Column of each reading in the ``film`` channel (per joint and output time).
_FILM_COL = {name: k for k, name in enumerate(_core.FILM_COLUMNS)}


@dataclass(frozen=True, repr=False)
class FilmPressure:
    """The film pressure of a lubricated joint at one output time (:meth:`FilmReadings.pressure`).

    ``theta`` [rad] runs counter-clockwise from the widest gap (the film's frame, docs/physics.md
    §4); the widest gap points at ``gap_angle`` [rad] (global, counter-clockwise from x), so θ lies
    at the global angle ``gap_angle + theta``. ``p`` [Pa] is (nθ, nz) over ``z`` [m] (from the
    bearing's mid-plane) for the finite film, and (nθ,) at the mid-plane for the long and short
    films (``z`` is then None)."""

    t: float
    theta: np.ndarray
    z: Optional[np.ndarray]
    p: np.ndarray
    gap_angle: float
    peak_pressure: float
    peak_angle: float  # [rad], film frame
    side_leakage: float  # [m³/s]
    supply_flow: float  # [m³/s]
    joint: str
    film: str

    def __repr__(self) -> str:
        return display.text(self, *_SHOWN)

    def _repr_html_(self) -> str:
        return display.html(self, *_SHOWN)


#: What a :class:`FilmPressure` shows of itself (its field by shape only).
_SHOWN = ("joint", "t", "film", "peak_pressure", "peak_angle", "side_leakage", "supply_flow", "p")


class FilmReadings:
    """Methods of :class:`clearsim.Result` for a lubricated joint's oil flow and pressure."""

    joint_names: List[str]
    t: np.ndarray
    _raw: Dict[str, Any]
    description: Optional[Dict[str, Any]]

    def _joint(self, joint: str) -> int:  # pragma: no cover - Result's
        raise NotImplementedError

    def _film_model(self, joint: str) -> Dict[str, Any]:
        """The model of lubricated joint ``joint``; an :class:`InputError` naming a joint that has
        no film (a dry one: its channel holds zeros, which would read as a film that leaks nothing)."""
        self._joint(joint)
        models = {c["name"]: c["model"] for c in (self.description or {}).get("clearance_joints", [])}
        model = models.get(joint)
        if model is None or model.get("kind") != "lubricated":
            raise InputError(f"invalid joint = {joint!r}: it has no film (a lubricated revolute clearance joint has)", field="joint", value=joint)
        return model

    def _film_column(self, joint: str, column: str) -> np.ndarray:
        j = self._joint(joint)
        if self.description is not None:
            self._film_model(joint)
        data = self._raw.get("film")
        if data is None:
            raise InputError("invalid output = 'film': this run did not store it (pass outputs=[..., 'film'])", field="outputs", value="film")
        return np.asarray(data[:, j, _FILM_COL[column]])

    def flow(self, joint: str) -> np.ndarray:
        """(N, 2) oil flow of a lubricated joint [m³/s] at each output: the side leakage out of
        both ends of the bearing and the flow its supply must deliver (needs ``outputs=[...,
        "film"]``). The long film has no axial flow (both 0); the short and finite films keep
        the gap full where p > 0 and do not follow the oil through the ruptured zone, so their
        supply is the quasi-steady balance, equal to the side leakage (docs/physics.md §4,
        "Oil flow and pressure")."""
        return np.column_stack([self._film_column(joint, "side_leakage"), self._film_column(joint, "supply_flow")])

    def peak_pressure(self, joint: str) -> np.ndarray:
        """(N,) largest film pressure [Pa] at each output (needs ``outputs=[..., "film"]``)."""
        return self._film_column(joint, "peak_pressure")

    def peak_pressure_angle(self, joint: str, frame: str = "film") -> np.ndarray:
        """(N,) where the film pressure peaks [rad]: counter-clockwise from the widest gap
        (``frame="film"``) or from the global x axis (``"global"``); NaN where the film carries
        nothing (needs ``outputs=[..., "film"]``)."""
        check_choice("frame", frame, ["film", "global"])
        theta = self._film_column(joint, "peak_pressure_angle")
        if frame == "film":
            return theta
        return np.mod(self._gap_angle(joint) + theta, 2 * np.pi)

    def _gap_angle(self, joint: str) -> np.ndarray:
        """(N,) global angle of the widest gap [rad]: opposite the eccentricity vector."""
        e = self._raw["joints"][:, self._joint(joint), :2] if "joints" in self._raw else None
        if e is None:
            raise InputError("invalid output = 'joints': this run did not store it (pass outputs=[..., 'joints'])", field="outputs", value="joints")
        return np.arctan2(-e[:, 1], -e[:, 0])

    def pressure(self, joint: str, t: float) -> FilmPressure:
        """The film pressure of lubricated joint ``joint`` at the output time ``t`` [s] (the
        stored output nearest to it, within 1e-9 of the run; needs the ``"states"`` output),
        solved from the state stored there: θ × z for the finite film, θ for the long and short
        films (:class:`FilmPressure`). Computed when asked: a run pays nothing for it."""
        j = self._joint(joint)
        model = self._film_model(joint)
        q, qd = self._raw.get("q"), self._raw.get("qd")
        if q is None or qd is None:
            raise InputError("invalid output = 'states': this run did not store it (pass outputs=[..., 'states'])", field="outputs", value="states")
        k = _output_index(self.t, t)
        temps = self._raw.get("temperature")
        temperature = float(temps[k, j]) if temps is not None and math.isfinite(temps[k, j]) else None
        content = None
        if model.get("cavitation") == "jfo":
            # The film content the run recorded at that output (mass-conserving joints, in joint order).
            stored = self._raw.get("film_content")
            if stored is None:
                raise InputError("invalid output = 'film': a mass-conserving film's pressure needs the content the run recorded (pass outputs=[..., 'film'])", field="outputs", value="film")
            jfo = [c["name"] for c in self.description["clearance_joints"] if c["model"].get("cavitation") == "jfo"]  # type: ignore[index]
            content = np.ascontiguousarray(stored[k, jfo.index(joint)])
        # The state there: y = (q, q̇, T…), the oil temperatures of the joints with a heat model in
        # joint order (rust/clearance/thermal.rs).
        heated = [i for i, c in enumerate((self.description or {}).get("clearance_joints", [])) if c["model"].get("thermal")]
        y = np.concatenate([q[k], qd[k], [float(temps[k, i]) for i in heated] if temps is not None else []])
        field = self._compiled().film_field(j, y, temperature, content)
        assert field is not None
        e = self._raw["joints"][k, j, :2] if "joints" in self._raw else q[k, :2] * 0.0
        p = np.asarray(field["pressure"])
        film = str(model.get("film", "long"))
        return FilmPressure(
            t=float(self.t[k]), theta=np.asarray(field["theta"]), z=np.asarray(field["z"]) if film == "finite" else None,
            p=p if film == "finite" else p[:, 0], gap_angle=float(math.atan2(-e[1], -e[0])), peak_pressure=float(field["peak_pressure"]),
            peak_angle=float(field["peak_angle"]), side_leakage=float(field["side_leakage"]), supply_flow=float(field["supply_flow"]),
            joint=joint, film=film,
        )  # fmt: skip

    def _compiled(self) -> Any:
        """The run's mechanism compiled (once per result)."""
        compiled = self.__dict__.get("_compiled_model")
        if compiled is None:
            if self.description is None:
                raise InputError("this result does not carry its mechanism (make it with Mechanism.simulate)", field="result", value=None)
            compiled = _core.compile(self.description)
            self.__dict__["_compiled_model"] = compiled
        return compiled


def _output_index(t_out: np.ndarray, t: float) -> int:
    """Index of the stored output at time ``t`` [s], or an InputError naming ``t``."""
    if not len(t_out):
        raise InputError(f"invalid t = {t!r}: the run stored no outputs", field="t", value=t)
    k = int(np.argmin(np.abs(t_out - float(t))))
    span = float(t_out[-1] - t_out[0]) or 1.0
    if not abs(float(t_out[k]) - float(t)) <= 1e-9 * span + 1e-15:
        raise InputError(
            f"invalid t = {t!r}: not an output time (nearest {float(t_out[k]):.9g} s; the pressure is solved from a stored state)", field="t", value=t
        )
    return k


def film_columns(res: FilmReadings, joint: str) -> List[Tuple[str, str, np.ndarray]]:
    """``(name, unit, values)`` of a lubricated joint's film readings for a CSV file (``side_leakage``,
    ``supply_flow`` [m^3/s], ``peak_pressure`` [Pa], ``peak_pressure_angle`` [rad] from the widest
    gap), or none if the run did not store the ``film`` channel or the joint has no film."""
    models = {c["name"]: c["model"] for c in (res.description or {}).get("clearance_joints", [])}
    if res._raw.get("film") is None or models.get(joint, {}).get("kind") != "lubricated":
        return []
    flow = res.flow(joint)
    return [("side_leakage", "m^3/s", flow[:, 0]), ("supply_flow", "m^3/s", flow[:, 1]),
            ("peak_pressure", "Pa", res.peak_pressure(joint)), ("peak_pressure_angle", "rad", res.peak_pressure_angle(joint))]  # fmt: skip


def film_summary(res: FilmReadings, joint: str, window: Optional[Tuple[float, float]] = None) -> Dict[str, Any]:
    """The film readings' part of :meth:`clearsim.Result.bearing_summary` for ``joint`` when the
    run stored the ``film`` channel (else empty): ``peak_pressure`` [Pa] with ``t_peak_pressure``
    [s] and ``peak_pressure_angle_deg`` (from the widest gap), ``mean_side_leakage`` and
    ``mean_supply_flow`` [m³/s] (trapezoidal means over the outputs), over the outputs inside
    ``window`` = (start, end) [s], the summary's (default: all)."""
    if res._raw.get("film") is None or len(res.t) == 0:
        return {}
    inside = np.ones(len(res.t), dtype=bool)
    if window is not None:
        tol = 1e-9 * max(1.0, abs(float(res.t[-1])))
        inside = (res.t >= window[0] - tol) & (res.t <= window[1] + tol)
        if not inside.any():
            return {}
    p = res.peak_pressure(joint)[inside]
    q = res.flow(joint)[inside]
    k = int(np.argmax(p))
    t = res.t[inside]
    span = float(t[-1] - t[0])

    def mean(v: np.ndarray) -> float:
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)) / span) if span > 0 else float(v[0])

    angle = float(res.peak_pressure_angle(joint)[inside][k])
    return {
        "peak_pressure": float(p[k]),
        "t_peak_pressure": float(t[k]),
        "peak_pressure_angle_deg": math.degrees(angle) if math.isfinite(angle) else math.nan,
        "mean_side_leakage": mean(q[:, 0]),
        "mean_supply_flow": mean(q[:, 1]),
    }


__all__ = ["FilmPressure", "FilmReadings", "film_columns", "film_summary"]
