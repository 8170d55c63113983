"""The ``[reliability]`` table of a scene file: the short form of ``[study] methods = ["fosm"]``.

It is read and checked here, then set up as the equivalent :class:`~clearsim.reliability.Study`
(:func:`alias_study`): no random inputs; one output per analysed quantity, the body component's
error against the ideal mechanism, with the upper end of its allowable range as the limit; the
window from ``t_start`` (moved up to the next bin edge of the crank angle |ω| t, t from t = 0
whatever the run's ``t0``: docs/physics.md §6) to the end of the run. :func:`scene_fosm` computes ``SceneRun.reliability`` through
:meth:`Study.fosm_all <clearsim.reliability.Study.fosm_all>`: one run of the nominal mechanism whose
step monitors track every quantity, so no number depends on ``dt_out`` (docs/physics.md §6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Optional, Tuple

from ..errors import InputError
from ..mechanism import Mechanism
from ..reliability.fosm import BIN_WIDTH, FosmResult
from ..reliability.outputs import Limit, Output
from ..schema import COMPONENTS
from .builder import _Builder
from .settings import ERROR_QUANTITIES, SimulationSettings, _drive_speed
from .study import StudySettings, study_of
from .toml_reader import dotted_key

#: The quantities ``[reliability.allowable]`` takes: errors of a body coordinate.
RELIABILITY_QUANTITIES: Tuple[str, ...] = tuple(ERROR_QUANTITIES.values())
_RELIABILITY_KEYS = ("body", "component", "bin_width", "omega", "t_start", "allowable")


@dataclass
class ReliabilitySettings:
    """The ``[reliability]`` table: FOSM reliability of one body coordinate (docs/physics.md §6).

    ``allowable`` maps ``displacement`` / ``velocity`` / ``acceleration`` to the allowable
    error range (Δv, Δu) [m, m/s, m/s² (rad… for ``theta``)]; ``omega`` [rad/s] gives the crank
    angle |ω| t [deg] (t from t = 0, whatever ``[simulation].t0``); the analysis starts at
    ``t_start`` [s]; ``bin_width`` [deg].
    :meth:`study` gives the equivalent ``[study]`` settings.
    """

    body: str
    component: str
    allowable: Dict[str, Tuple[float, float]]
    omega: float
    bin_width: float = BIN_WIDTH
    t_start: float = 0.0

    def study(self, simulation: SimulationSettings) -> StudySettings:
        """The equivalent ``[study]`` (methods ``["fosm"]``) of a run with ``simulation``."""
        return alias_study(self, simulation)


def alias_study(rel: ReliabilitySettings, sim: SimulationSettings) -> StudySettings:
    """``[reliability]`` as ``[study]`` settings: one output per analysed quantity, no random
    inputs, the window from ``t_start`` or the run's ``t0`` (at the next bin edge of |ω| t, t from
    t = 0: the same bins whatever ``t0``) to ``t_end``.
    A window shorter than one crank turn is an :class:`InputError` (some bins would see no time:
    ``Scene.run`` reports it in ``SceneRun.reliability_failure``, and runs the rest)."""
    period = 2.0 * math.pi / abs(rel.omega)
    bin_time = period * rel.bin_width / 360.0
    start = max(rel.t_start, sim.t0)
    start = math.ceil(start / bin_time - 1e-9) * bin_time  # a bin edge of |ω| t (§6), not of |ω| (t − t0)
    turns = (sim.t_end - start) / period
    if not turns >= 1.0 - 1e-9:
        raise InputError(
            f"[reliability] needs at least one whole crank turn (2π/|ω| = {period:.6g} s) from t_start to "
            f"t_end, the run gives {max(turns, 0.0):.3g} (from {start:.6g} s to {sim.t_end:.6g} s): raise t_end or cycles in "
            "[simulation] or lower t_start",
            field="reliability.t_start", value=rel.t_start,
        )  # fmt: skip
    quantities = list(rel.allowable)
    return StudySettings(
        outputs=[Output(body=rel.body, component=rel.component, quantity=q) for q in quantities],
        limits=[Limit(rel.allowable[q][1]) for q in quantities], omega=rel.omega, inputs={}, cycles=turns,
        skip_cycles=start / period, methods=["fosm"], bin_width=rel.bin_width,
        allowable=[rel.allowable[q] for q in quantities], t0=sim.t0,
    )  # fmt: skip


def scene_fosm(rel: ReliabilitySettings, mech: Mechanism, sim: SimulationSettings, progress: bool = False) -> Dict[str, FosmResult]:
    """``{quantity: FosmResult}`` of ``[reliability]`` through :meth:`Study.fosm_all` (the
    nominal mechanism, one run monitoring every quantity at every step; the same numbers
    whatever ``dt_out``)."""
    settings = alias_study(rel, sim)
    study = study_of(settings, mech, sim, progress)
    results = study.fosm_all(allowable=settings.allowable)
    return {o.quantity: res for o, res in zip(settings.outputs, results)}


def read_reliability(b: _Builder, m: Mechanism) -> Optional[ReliabilitySettings]:
    """The ``[reliability]`` table, checked (errors at the key's line); ``None`` if absent."""
    t = b.top.table("reliability", _RELIABILITY_KEYS)
    if t is None:
        return None
    if not m.clearance_joint_names:
        raise t.error(None, "invalid [reliability]: the mechanism has no clearance joint (errors are clearance − ideal)")
    body = t.string("body", choices=m.body_names)
    a = t.table("allowable", tuple(RELIABILITY_QUANTITIES))
    if a is None:
        # No silent default: the paper's limits are in m, m/s and m/s², wrong for most outputs.
        raise t.error(
            None,
            "missing table [reliability.allowable]: give [lower, upper] of the |error| for each analysed "
            "quantity in its unit (m, m/s, m/s² for x and y; rad, rad/s, rad/s² for theta)",
        )
    allowable: Dict[str, Tuple[float, float]] = {}
    for q in RELIABILITY_QUANTITIES:
        if q in a:
            lo, hi = a.numbers(q, length=2)
            if not (lo < hi and hi > 0.0 and math.isfinite(lo) and math.isfinite(hi)):
                raise a.error(q, f"invalid {dotted_key(a.where, q)} = {[lo, hi]!r}: must be [lower, upper] of |error| with lower < upper and upper > 0", [lo, hi])
            allowable[q] = (lo, hi)
    if not allowable:
        raise a.error(None, "invalid [reliability.allowable]: give at least one of " + ", ".join(RELIABILITY_QUANTITIES))
    omega = t.number("omega", None)
    if omega is None:
        omega = _drive_speed(m, b.drivers)
        if omega is None:
            raise t.error(None, "missing key 'omega' in [reliability] (no constant-speed driver to take it from)")
    if omega == 0.0 or not math.isfinite(omega):
        raise t.error("omega", f"invalid reliability.omega = {omega!r}: must be a non-zero drive speed [rad/s]", omega)
    bin_width = t.number("bin_width", BIN_WIDTH)
    if not 0.0 < bin_width <= 360.0:
        raise t.error("bin_width", f"invalid reliability.bin_width = {bin_width!r}: must lie in (0, 360] degrees", bin_width)
    return ReliabilitySettings(
        body=body, component=t.string("component", choices=COMPONENTS), allowable=allowable, omega=omega,
        bin_width=bin_width, t_start=t.number("t_start", 0.0),
    )  # fmt: skip


__all__ = ["RELIABILITY_QUANTITIES", "ReliabilitySettings", "alias_study", "read_reliability", "scene_fosm"]
