"""What a run tells about its dynamics: the methods of :class:`clearsim.Result` for Poincaré
sections (:meth:`DynamicsReadings.poincare`, from the samples the core recorded at exact times,
``simulate(..., sections=...)``) and spectra (:meth:`DynamicsReadings.spectrum`, over whole
periods of the stored output grid). SI units.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ..errors import InputError, check_choice, check_finite
from ..schema import BODY_QUANTITIES, COMPONENTS, body_unit
from .spectrum import Spectrum, spectrum as _spectrum

#: Relative tolerance on a period asked of :meth:`DynamicsReadings.poincare` being a whole
#: multiple of the recorded one (and on its phase).
_MULTIPLE_TOL = 1e-9
#: What :meth:`DynamicsReadings.spectrum` reads of a clearance joint: its stored columns and units.
JOINT_SIGNALS: Dict[str, Tuple[Tuple[str, str], str]] = {
    "eccentricity": (("ex", "ey"), "m"),
    "eccentricity_rate": (("ex_dot", "ey_dot"), "m/s"),
    "force": (("fx", "fy"), "N"),
}


def section_spec(sections: Union[float, Tuple[float, float], Any]) -> Dict[str, float]:
    """The core's section settings from ``period`` [s] or ``(period, phase)`` (phase [rad]); the
    core checks the values (period positive, both finite)."""
    if isinstance(sections, (tuple, list)):
        if len(sections) != 2:
            raise InputError(f"invalid sections = {sections!r}: give period [s] or (period [s], phase [rad])", field="sections", value=sections)
        period, phase = sections
    else:
        period, phase = sections, 0.0
    return {"period": _float("sections.period", period), "phase": _float("sections.phase", phase)}


def _float(field: str, value: Any) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"invalid {field} = {value!r}: must be a number", field=field, value=value) from None


class DynamicsReadings:
    """Methods of :class:`clearsim.Result`: Poincaré sections and spectra."""

    _raw: Dict[str, Any]
    body_names: List[str]
    joint_names: List[str]
    t: np.ndarray
    description: Optional[Dict[str, Any]]
    #: A section's period [s] and phase [rad] (set on the results :meth:`poincare` returns).
    section_period: Optional[float] = None
    section_phase: Optional[float] = None

    def poincare(self, period: Optional[float] = None, phase: Optional[float] = None, *, after: Optional[float] = None) -> Any:
        """The Poincaré (stroboscopic) section of the run: a :class:`clearsim.Result` whose
        samples are the states (and every channel the run stored: accelerations, joints) at the
        exact times t_k = (k + phase/2π) · period [s] in the run, read as any result
        (``sec.t``, ``sec.position(body)``, ``sec.eccentricity(joint)``).

        The run must have recorded them: ``m.simulate(..., sections=(period, phase))``; the core
        evaluates the dense output of the step that holds each t_k, so they do not depend on
        ``dt_out``. ``period`` may be a whole multiple of the recorded one (and ``phase`` any
        that lands on recorded times): every m-th section. Default: the recorded sections.
        ``after`` [s]: only the sections at or after that time (the motion after a transient)."""
        raw = self._raw.get("sections")
        spec = self._section_settings()
        if raw is None or spec is None:
            raise InputError(
                "invalid result: this run recorded no Poincaré sections: run it with simulate(..., sections=(period [s], phase [rad]))",
                field="sections", value=None,
            )  # fmt: skip
        rec_period, rec_phase = spec["period"], spec["phase"]
        period = rec_period if period is None else check_finite("period", period)
        phase = rec_phase * period / rec_period if phase is None else check_finite("phase", phase)
        if period <= 0:
            raise InputError(f"invalid period = {period!r}: must be positive [s]", field="period", value=period)
        m = period / rec_period
        if abs(m - round(m)) > _MULTIPLE_TOL * max(1.0, m) or round(m) < 1:
            raise InputError(f"invalid period = {period!r}: the run recorded sections every {rec_period!r} s; ask for a whole multiple of it", field="period", value=period)
        m = int(round(m))
        t = np.asarray(raw["t"], dtype=float)
        # The asked times t = (k + phase/2π) period among the recorded ones (k + phase_r/2π) period_r.
        offset = (phase / (2 * math.pi)) * period - (rec_phase / (2 * math.pi)) * rec_period
        shift = offset / rec_period
        if abs(shift - round(shift)) > _MULTIPLE_TOL * max(1.0, abs(shift)):
            raise InputError(f"invalid phase = {phase!r}: its times fall between the recorded sections (period {rec_period!r} s, phase {rec_phase!r} rad)", field="phase", value=phase)
        k_rec = np.rint(t / rec_period - rec_phase / (2 * math.pi)).astype(np.int64)
        keep = np.mod(k_rec - int(round(shift)), m) == 0
        if after is not None:
            keep &= t >= check_finite("after", after)
        rows = {key: (np.asarray(v)[keep] if isinstance(v, np.ndarray) and len(v) == len(t) else v) for key, v in raw.items()}
        out = dict(self._raw)
        for key in ("q", "qd", "qdd", "lambda", "joints", "violation", "energy", "temperature", "monitors", "sections", "lyapunov"):
            out.pop(key, None)
        out.update(rows)
        out["error"] = None
        sec = type(self)(out, self.body_names, self.joint_names)  # type: ignore[call-arg]
        sec.description = self.description
        sec.section_period, sec.section_phase = float(period), float(phase)
        return sec

    def _section_settings(self) -> Optional[Dict[str, float]]:
        spec = self._raw.get("section_settings")
        return dict(spec) if spec is not None else None

    def spectrum(
        self,
        name: str,
        quantity: str = "acceleration",
        component: str = "x",
        *,
        period: Optional[float] = None,
        cycles: Optional[int] = None,
        window: str = "hann",
        point: Optional[Sequence[float]] = None,
    ) -> Spectrum:
        """The amplitude spectrum of a body's ``quantity`` (``"displacement"``, ``"velocity"``,
        ``"acceleration"``) ``component`` (``"x"``, ``"y"``, ``"theta"``) — of its ``point``
        (x, y) [m] in the body's frame, component ``"x"`` or ``"y"``, when given
        (:meth:`clearsim.Result.point`) — or of a clearance joint's ``"eccentricity"``, ``"eccentricity_rate"`` or ``"force"`` component ``"x"`` or
        ``"y"``: a windowed FFT over the last ``cycles`` whole periods of the stored output grid
        (default: all whole periods), amplitudes in the quantity's unit (:class:`Spectrum`).

        ``period`` [s]: the fundamental (default: the mechanism's forcing period,
        :func:`clearsim.dynamics.forcing_period`). The grid must be uniform with a whole number of
        samples a period (``dt_out = period / N``), so that every harmonic falls on a bin; lines
        below the Nyquist frequency N/(2 period) are then independent of N."""
        from .period import forcing_period

        values, unit, label = self._signal(name, quantity, component, point)
        if period is None:
            if self.description is None:
                raise InputError("invalid period = None: this result does not carry its mechanism; give period= [s]", field="period", value=None)
            period = forcing_period(self.description)
        return _spectrum(self.t, values, period, cycles=cycles, window=window, unit=unit, label=label)

    def phase_portrait(self, name: str, component: str = "x", ax: Any = None) -> Any:
        """A phase-portrait figure: a body's ``component`` against its rate (``"x"``, ``"y"`` [m,
        m/s] or ``"theta"`` [rad, rad/s]), or a clearance joint's e_x against e_y [mm] (its orbit;
        ``component`` unused), over the stored outputs, with the Poincaré section's points on top
        when the run recorded sections (:func:`clearsim.plots.dynamics.plot_phase_portrait`)."""
        from ..plots.dynamics import plot_phase_portrait

        has_sections = self._raw.get("sections") is not None and self._section_settings() is not None
        sec = self.poincare() if has_sections else None
        if name in self.joint_names:
            get = lambda r: np.asarray(getattr(r, "eccentricity")(name)) * 1e3  # noqa: E731
            e = get(self)
            pts = None if sec is None else (get(sec)[:, 0], get(sec)[:, 1])
            return plot_phase_portrait(e[:, 0], e[:, 1], f"{name} e_x [mm]", f"{name} e_y [mm]", pts, title=f"orbit of {name}", ax=ax)
        check_choice("component", component, COMPONENTS)
        k = COMPONENTS.index(component)
        unit = "rad" if component == "theta" else "m"
        x, v = (np.asarray(getattr(self, "position")(name))[:, k], np.asarray(getattr(self, "velocity")(name))[:, k])
        pts = None if sec is None else (sec.position(name)[:, k], sec.velocity(name)[:, k])
        return plot_phase_portrait(x, v, f"{name}.{component} [{unit}]", f"{name}.{component} rate [{unit}/s]", pts, title=f"{name} {component}", ax=ax)

    def _signal(self, name: str, quantity: str, component: str, point: Optional[Sequence[float]] = None) -> Tuple[np.ndarray, str, str]:
        """A stored scalar signal: (values, unit, label)."""
        if point is not None:
            check_choice("component", component, ("x", "y"))
            values = getattr(self, "point")(name, point, quantity)[:, ("x", "y").index(component)]
            return np.asarray(values, dtype=float), body_unit(quantity, component), f"{name} point {tuple(point)} {component} {quantity}"
        if name in self.body_names:
            check_choice("quantity", quantity, BODY_QUANTITIES)
            check_choice("component", component, COMPONENTS)
            get = {"displacement": "position", "velocity": "velocity", "acceleration": "acceleration"}[quantity]
            values = getattr(self, get)(name)[:, COMPONENTS.index(component)]
            return np.asarray(values, dtype=float), body_unit(quantity, component), f"{name} {component} {quantity}"
        if name in self.joint_names:
            check_choice("quantity", quantity, list(JOINT_SIGNALS))
            check_choice("component", component, ("x", "y"))
            (cols, unit) = JOINT_SIGNALS[quantity]
            values = getattr(self, "_joint_cols")(name, [cols[("x", "y").index(component)]])[:, 0]
            return np.asarray(values, dtype=float), unit, f"{name} {component} {quantity}"
        known = ", ".join(self.body_names + self.joint_names)
        raise InputError(f"invalid name = {name!r}: no such body or clearance joint (known: {known})", field="name", value=name)


__all__ = ["DynamicsReadings", "JOINT_SIGNALS", "section_spec"]
