"""What a bearing engineer reads off a clearance joint: film thickness, friction torque and power
loss over a run (the core's joint columns, rust/clearance/readings.rs) and, when the run asks for
it (``simulate(..., bearings=True)``), their summary: minimum film thickness, peak and mean power
loss, tracked at every integration step by the core (rust/simulate/bearings.rs).

:class:`JointReadings` holds the methods of :class:`clearsim.Result` for them (docs/physics.md §4,
"Film thickness, friction and power").
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .errors import InputError, check_choice
from .film_readings import FilmReadings, film_summary

#: Parts of :meth:`JointReadings.friction_torque` and the joint column each reads.
TORQUE_PARTS = {"total": "friction_torque", "couette": "couette_torque", "poiseuille": "poiseuille_torque"}


class JointReadings(FilmReadings):
    """Methods of :class:`clearsim.Result` for the readings of a clearance joint (needs the
    ``"joints"`` output, stored by default). A prismatic clearance joint's name gives its two slider
    ends as columns (front, rear)."""

    joint_names: List[str]
    body_names: List[str]
    t: np.ndarray
    _raw: Dict[str, Any]
    description: Optional[Dict[str, Any]]

    def _joint_cols(self, joint: str, cols: List[str]) -> np.ndarray:  # pragma: no cover - Result's
        raise NotImplementedError

    def _reading(self, joint: str, column: str) -> np.ndarray:
        ends = [f"{joint} front", f"{joint} rear"]
        if joint not in self.joint_names and all(e in self.joint_names for e in ends):
            return np.column_stack([self._joint_cols(e, [column])[:, 0] for e in ends])
        return self._joint_cols(joint, [column])[:, 0]

    def film_thickness(self, joint: str) -> np.ndarray:
        """(N,) smallest gap h = c − |e| [m] between journal and bearing (negative: penetration);
        for a prismatic clearance joint (N, 2), the gap at each slider end (front, rear)."""
        return self._reading(joint, "film_thickness")

    def friction_torque(self, joint: str, part: str = "total", body: str = "journal") -> np.ndarray:
        """(N,) friction torque [N m] about the ``body``'s (``"journal"`` or ``"bearing"``) joint
        centre, counter-clockwise positive (docs/physics.md §4, "Film thickness, friction and
        power"): the film's shear, ``part="couette"`` (the shear flow, Petroff's torque at the
        centre: the bearing gets its negative) plus ``"poiseuille"`` (the pressure flow, −e F_η/2
        on either body), in the transition band and in contact blended with the dry friction's
        moment (R_j F_t on the journal, −R_b F_t on the bearing). An output only: the dynamics
        apply the film force through the centres and do not apply this torque."""
        check_choice("part", part, list(TORQUE_PARTS))
        check_choice("body", body, ["journal", "bearing"])
        if part == "total":
            return self._reading(joint, "friction_torque" if body == "journal" else "friction_torque_bearing")
        values = self._reading(joint, TORQUE_PARTS[part])
        return -values if (part == "couette" and body == "bearing") else values

    def power_loss(self, joint: str) -> np.ndarray:
        """(N,) power dissipated in the joint [W] (≥ 0): the film's shear and pressure flow
        (2πμR³L(θ̇_j − θ̇_b)²/(c√(1 − ε²)) + (e/2)F_η W − cε̇F_ξ) and the dry friction's −F_t·slip,
        each by its share of the transition blend; a prismatic joint gives its ends (N, 2)."""
        return self._reading(joint, "power_loss")

    def asperity_force(self, joint: str) -> np.ndarray:
        """(N,) load the asperities carry [N] (≥ 0, pressing the journal back towards the centre) of
        a joint with ``Lubricated(roughness=σ)``: Greenwood & Tripp's pressure where the film is
        thinner than 4σ (docs/physics.md §4, *Roughness and mixed lubrication*); 0 without roughness."""
        return self._reading(joint, "asperity_force")

    def temperature(self, joint: str) -> np.ndarray:
        """(N,) effective oil temperature T [K] of a lubricated joint with
        ``Lubricated(thermal=clearsim.Thermal(...))`` at each output time: C dT/dt = P_loss −
        hA (T − T_ambient), advanced along every integration step (docs/physics.md §4, *Heat*)."""
        if joint not in self.joint_names:
            known = ", ".join(self.joint_names) or "none"
            raise InputError(f"invalid joint = {joint!r}: no such clearance joint (known: {known})", field="joint", value=joint)
        k = self.joint_names.index(joint)
        temps = self._raw.get("temperature")
        if temps is None or (self.description is not None and not self._has_thermal(joint)) or not np.isfinite(temps[:, k]).all():
            raise InputError(f"invalid joint = {joint!r}: it models no oil temperature (give Lubricated(thermal=clearsim.Thermal(...)))", field="joint", value=joint)
        return np.asarray(temps[:, k])

    def _has_thermal(self, joint: str) -> bool:
        for cj in (self.description or {}).get("clearance_joints", []):
            if cj.get("name") == joint:
                return bool(cj.get("model", {}).get("thermal"))
        return False

    def _crank_body(self) -> Optional[int]:
        """The body whose angle is the crank angle: the first driver's, else (a crank turned by
        torque) the first motor's; ``None`` without either."""
        d = self.description or {}
        drivers = d.get("drivers") or []
        motors = [f for f in d.get("forces") or [] if f.get("kind") == "motor"]
        if not drivers and not motors:
            return None
        body = (drivers or motors)[0]["body"]  # by name (a Mechanism's description) or index (the core's)
        return self.body_names.index(body) if isinstance(body, str) else int(body)

    def driver_angle(self, t: float) -> Optional[float]:
        """The first driver's body angle [deg] at ``t`` [s] (without a driver, the first motor's),
        interpolated between the stored outputs, carried on at the stored speed past them
        (``None`` without a driver or motor, or without stored states)."""
        q = self._raw.get("q")
        b = self._crank_body()
        if b is None or q is None or not len(self.t) or not math.isfinite(t):
            return None
        qd = self._raw.get("qd")
        if qd is not None and (t > self.t[-1] or t < self.t[0]):
            # Past the outputs (a run's end between two grid points): on with the stored speed.
            k = -1 if t > self.t[-1] else 0
            return float(np.degrees(q[k, 3 * b + 2] + qd[k, 3 * b + 2] * (t - self.t[k])))
        return float(np.degrees(np.interp(t, self.t, q[:, 3 * b + 2])))

    def crank_cycle(self) -> Tuple[float, float]:
        """The cycle over which the first driver's angle (without a driver, the first motor's) is
        reported, ``(start, period)`` [deg]: the longest period of the loads given as tables over
        that body's angle (a four-stroke gas force repeats every two turns: (0, 720)), from the
        table's first angle; else one turn (0, 360)."""
        b = self._crank_body()
        if b is None:
            return 0.0, 360.0
        found = load_periods(self.description, b)
        if not found:
            return 0.0, 360.0
        start, period = max(found, key=lambda sp: sp[1])
        return math.degrees(start), math.degrees(period)

    def _lubricated(self) -> List[str]:
        """Names of the lubricated clearance joints (a dry one has no film)."""
        return [cj["name"] for cj in (self.description or {}).get("clearance_joints", []) if cj["model"].get("kind") == "lubricated"]

    @property
    def bearings_tracked(self) -> bool:
        """Whether the run tracked the bearing summary (``simulate(..., bearings=True)``)."""
        return self._raw.get("bearings") is not None

    def bearing_summary(self) -> Dict[str, Dict[str, Any]]:
        """Per lubricated joint (a dry one has no film: it is left out even when ``extremes``
        tracks its gap, whose negative minimum is its penetration): ``min_film_thickness`` [m] with ``t_min_film`` [s] and
        ``min_film_crank_angle_deg`` (the first driver's angle then, or a motor's without one, over the loads'
        cycle :meth:`crank_cycle`: 0–720° under a four-stroke load table), located between the
        integration steps on the run's dense output; ``peak_power_loss`` [W] (with
        ``t_peak_power_loss`` [s]) and ``mean_power_loss`` [W] from the power loss at every
        integration step's end — all independent of ``dt_out``; with ``roughness`` σ also
        ``lambda`` = min film / σ (below ~3 the asperities carry load: mixed lubrication); with a
        heat model (``thermal``) also ``temperature_start`` and ``temperature_end`` [K], the oil
        temperature at the run's first and last output (the state itself there: independent of
        ``dt_out``). All over one window, which ``window_start`` and ``window_end`` [s] name: the
        run, or from ``simulate(extremes_from=)`` on (the window of :meth:`Result.extremes` too).
        With the ``film`` output as well (``outputs=[..., "film"]``) also ``peak_pressure`` [Pa]
        (its time and angle from the widest gap), ``mean_side_leakage`` and ``mean_supply_flow``
        [m³/s] over the outputs in the window (:func:`clearsim.film_readings.film_summary`); without it none.

        Tracked only when the run asks for it, ``simulate(..., bearings=True)`` (``clearsim run``
        does): a mechanism with a lubricated joint run without it raises an :class:`InputError`
        saying so. A mechanism without one gives ``{}``."""
        lubricated = self._lubricated() if self.description is not None else []
        tracked = self._raw.get("bearings")
        if tracked is None:
            if lubricated:
                raise InputError(
                    f"invalid bearings: this run did not track the bearing summary of {', '.join(repr(n) for n in lubricated)} "
                    "(pass bearings=True to simulate; it costs a force evaluation per joint and step, so runs do not pay for it unasked)",
                    field="bearings", value=False,
                )
            return {}
        out: Dict[str, Dict[str, Any]] = {}
        models = {cj["name"]: cj["model"] for cj in (self.description or {}).get("clearance_joints", [])}
        for j, name in enumerate(self.joint_names):
            found = tracked[j] if j < len(tracked) else None
            if found is None:
                continue  # a dry joint has no film (its gap's minimum, the penetration, is in Result.extremes)
            entry: Dict[str, Any] = {
                "window_start": float(found["window_start"]),
                "window_end": float(found["window_end"]),
                "min_film_thickness": float(found["min_film_thickness"]),
                "t_min_film": float(found["t_min_film"]),
                "peak_power_loss": float(found["peak_power_loss"]),
                "t_peak_power_loss": float(found["t_peak_power_loss"]),
                "mean_power_loss": float(found["mean_power_loss"]),
            }
            angle = self.driver_angle(entry["t_min_film"])
            if angle is not None:
                start, period = self.crank_cycle()
                entry["min_film_crank_angle_deg"] = start + (angle - start) % period
            sigma = models.get(name, {}).get("roughness")
            if sigma:
                entry["lambda"] = entry["min_film_thickness"] / float(sigma)
            temps = self._raw.get("temperature")
            if models.get(name, {}).get("thermal") and temps is not None and len(temps):
                entry["temperature_start"], entry["temperature_end"] = float(temps[0, j]), float(temps[-1, j])
            entry.update(film_summary(self, name, (entry["window_start"], entry["window_end"])))
            out[name] = entry
        return out


def load_periods(description: Optional[Dict[str, Any]], body: int) -> List[Tuple[float, float]]:
    """``(first angle, period)`` [rad] of every periodic load table of ``description`` over the
    angle of ``body`` (rust/description.rs, ``TableArgument::Angle``)."""
    out: List[Tuple[float, float]] = []

    def walk(v: Any) -> None:
        if isinstance(v, dict):
            arg, table = v.get("argument"), v.get("table")
            if isinstance(arg, dict) and arg.get("kind") == "angle" and arg.get("body") == body and isinstance(table, dict):
                if table.get("period") and table.get("x"):
                    out.append((float(table["x"][0]), float(table["period"])))
            for item in v.values():
                walk(item)
        elif isinstance(v, list):
            for item in v:
                walk(item)

    walk((description or {}).get("forces") or [])
    return out


def summary_markdown(bearings: Optional[Dict[str, Dict[str, Any]]]) -> List[str]:
    """Lines of a Markdown table of :meth:`JointReadings.bearing_summary` (none if empty)."""
    if not bearings:
        return []

    def num(v: Any, scale: float = 1.0, fmt: str = ".4g") -> str:
        return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(float(v) * scale, fmt)

    # λ = h_min/σ for every table (– without roughness); the oil temperature when a joint models heat.
    heat = any("temperature_end" in b for b in bearings.values())
    film = any("peak_pressure" in b for b in bearings.values())
    head = "| lubricated joint | min film [µm] | λ = h_min/σ | at t [s] | crank angle [deg] | peak power loss [W] | mean power loss [W] |"
    head += " oil T start [K] | oil T end [K] |" if heat else ""
    head += " peak pressure [MPa] | mean side leakage [cm³/s] | mean supply flow [cm³/s] |" if film else ""
    windows = sorted({(b["window_start"], b["window_end"]) for b in bearings.values() if "window_start" in b})
    over = "; ".join(f"t = {a:.6g} to {b:.6g} s" for a, b in windows) or "the run"
    lines = ["", f"Bearings over {over} (minimum, peak and mean tracked at every integration step):", "", head, "|---" * head.count(" | ") + "|---|"]
    for joint, b in bearings.items():
        row = (
            f"| {joint} | {num(b.get('min_film_thickness'), 1e6)} | {num(b.get('lambda'), fmt='.3g')} | {num(b.get('t_min_film'), fmt='.6g')} | "
            f"{num(b.get('min_film_crank_angle_deg'), fmt='.1f')} | {num(b.get('peak_power_loss'))} | {num(b.get('mean_power_loss'))} |"
        )  # fmt: skip
        row += f" {num(b.get('temperature_start'), fmt='.5g')} | {num(b.get('temperature_end'), fmt='.5g')} |" if heat else ""
        row += f" {num(b.get('peak_pressure'), 1e-6)} | {num(b.get('mean_side_leakage'), 1e6)} | {num(b.get('mean_supply_flow'), 1e6)} |" if film else ""
        lines.append(row)
    return lines


__all__ = ["JointReadings", "summary_markdown"]
