"""Bifurcation diagrams: one mechanism per value of a parameter, each run through the core's
batch (in parallel, the GIL released, with a progress bar), its Poincaré points after a
transient and whether the motion is periodic (and of which period), quasi-periodic or chaotic
(:mod:`clearsim.dynamics.classify`), the largest Lyapunov exponent where it decides
(:mod:`clearsim.dynamics.lyapunov`). Failed runs are counted with their reasons.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from .. import batch
from ..csvfile import write_columns, write_rows
from ..errors import InputError, check_choice
from ..points import check_point_output, point_component, point_name
from ..schema import ATOL, BODY_QUANTITIES, RTOL, COMPONENTS, body_unit
from .classify import TOL, Classification, classify, features
from .lyapunov import estimate, shadow_spec
from .period import forcing_period

#: Samples a period the classification compares (the Poincaré phase and SUB − 1 between).
SUB = 8
#: What ``output=`` may read of a clearance joint, and the unit.
JOINT_OUTPUTS = {"eccentricity": "1", "eccentricity_x": "m", "eccentricity_y": "m", "force": "N", "contact_force": "N"}

OutputSpec = Union[Tuple[str, str, str], Tuple[str, str]]


@dataclass
class Bifurcation:
    """A bifurcation diagram.

    ``values``: the parameter's values; ``points[i]``: the output at the Poincaré times of the
    analysed cycles of value i (``cycles`` + 1 points, fewer for a failed run); ``kind[i]``:
    ``"period-k"``, ``"quasi-periodic"``, ``"chaotic"``, ``"period>16"`` or ``"failed"``;
    ``period[i]`` k (0 when not periodic); ``exponent[i]`` [1/s] and ``exponent_interval[i]``
    (NaN where no shadow run was made); ``how[i]``: what decided the kind; ``failures``:
    (value, reason) of every run that stopped early (its points up to there are kept)."""

    parameter: str
    values: np.ndarray
    points: List[np.ndarray]
    kind: List[str]
    period: np.ndarray
    exponent: np.ndarray
    exponent_interval: np.ndarray
    how: List[str]
    failures: List[Tuple[float, str]]
    output: str
    unit: str
    periods: np.ndarray
    transient_cycles: int
    cycles: int
    wall_time: float
    sections: List[Any] = field(default_factory=list, repr=False)
    #: The output's point on its body (body frame [m]), or None.
    point: Optional[Tuple[float, float]] = None

    def counts(self) -> Dict[str, int]:
        """How many values of each kind."""
        out: Dict[str, int] = {}
        for k in self.kind:
            out[k] = out.get(k, 0) + 1
        return out

    def section(self, i: int) -> Any:
        """The Poincaré section of value ``i`` over the analysed cycles (a :class:`clearsim.Result`)."""
        return self.sections[i]

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The diagram (:func:`clearsim.plots.dynamics.plot_bifurcation`)."""
        from ..plots.dynamics import plot_bifurcation

        return plot_bifurcation(self, ax=ax, **kwargs)

    def to_csv(self, directory: Union[str, Path], unit: str = "") -> List[Path]:
        """``bifurcation_points.csv`` (value, cycle, output) and ``bifurcation_kinds.csv`` (value,
        kind, period, exponent and its interval) in ``directory``; the parameter's column headed
        with ``unit``."""
        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        vals = np.concatenate([np.full(len(p), v) for v, p in zip(self.values, self.points)]) if self.points else np.zeros(0)
        cyc = np.concatenate([np.arange(len(p)) for p in self.points]) if self.points else np.zeros(0)
        pts = np.concatenate(self.points) if self.points else np.zeros(0)
        a = write_columns(d / "bifurcation_points.csv", [(self.parameter, unit or None, vals), ("cycle", None, cyc), (self.output, self.unit, pts)])
        rows = [
            (v, k, p, e, lo, hi, h)
            for v, k, p, e, (lo, hi), h in zip(self.values, self.kind, self.period, self.exponent, self.exponent_interval, self.how)
        ]
        header = [f"{self.parameter} [{unit}]" if unit else self.parameter, "kind", "period", "exponent [1/s]", "exponent_low [1/s]", "exponent_high [1/s]", "how"]
        b = write_rows(d / "bifurcation_kinds.csv", header, rows, blank_nonfinite=True)
        return [a, b]


def _reader(
    output: OutputSpec, desc: Dict[str, Any], body_names: Sequence[str], joint_names: Sequence[str], point: Optional[Sequence[float]] = None
) -> Tuple[Callable[[Any], np.ndarray], str, str, bool, bool]:
    """A function of a section result giving the output, its name and unit, and whether it needs
    the accelerations and the joints channels; with ``point`` (body frame [m]) the output is that
    point's on the body (component ``"x"``, ``"y"`` or ``"magnitude"``, :meth:`clearsim.Result.point`)."""
    if not isinstance(output, (tuple, list)) or len(output) not in (2, 3):
        raise InputError(f"invalid output = {output!r}: give (body, quantity, component) or (clearance joint, quantity)", field="output", value=output)
    name = output[0]
    if point is not None:
        if len(output) != 3:
            raise InputError(f"invalid point = {point!r}: a point lies on a body: give output=(body, quantity, component)", field="point", value=point)
        _, quantity, component = output
        check_choice("output quantity", quantity, BODY_QUANTITIES)
        xy = check_point_output(name, point, component, body_names, "output")
        read_point = lambda sec: point_component(sec.point(name, xy, quantity), component)  # noqa: E731
        return read_point, f"{point_name(name, xy)}.{component}.{quantity}", body_unit(quantity, "x"), quantity == "acceleration", False
    if len(output) == 3:
        _, quantity, component = output
        if name not in body_names:
            raise InputError(f"invalid output = {output!r}: no body {name!r} (known: {', '.join(body_names)})", field="output", value=output)
        check_choice("output quantity", quantity, BODY_QUANTITIES)
        check_choice("output component", component, COMPONENTS)
        col = COMPONENTS.index(component)
        get = {"displacement": "position", "velocity": "velocity", "acceleration": "acceleration"}[quantity]
        return (lambda sec: getattr(sec, get)(name)[:, col]), f"{name}.{component}.{quantity}", body_unit(quantity, component), quantity == "acceleration", False
    _, quantity = output
    if name not in joint_names:
        raise InputError(f"invalid output = {output!r}: no clearance joint {name!r} (known: {', '.join(joint_names) or 'none'})", field="output", value=output)
    check_choice("output quantity", quantity, list(JOINT_OUTPUTS))
    clearance = next(float(j["clearance"]) for j in desc["clearance_joints"] if j["name"] == name)

    def read(sec: Any) -> np.ndarray:
        if quantity.startswith("eccentricity"):
            e = sec.eccentricity(name)
            return {"eccentricity": np.hypot(e[:, 0], e[:, 1]) / clearance, "eccentricity_x": e[:, 0], "eccentricity_y": e[:, 1]}[quantity]
        if quantity == "force":
            f = sec.joint_force(name)
            return np.hypot(f[:, 0], f[:, 1])
        return sec.contact_force(name)[:, 0]

    return read, f"{name}.{quantity}", JOINT_OUTPUTS[quantity], False, True


def _mechanisms(build: Any, values: np.ndarray, parameter: str) -> List[Any]:
    if callable(build) and not hasattr(build, "with_values"):
        return [build(float(v)) for v in values]
    if hasattr(build, "with_values"):
        return [build.with_values({parameter: float(v)}) for v in values]
    raise InputError(f"invalid build = {build!r}: a function of the value returning a Mechanism, or a Mechanism whose field parameter= names", field="build", value=build)


def bifurcation(
    build: Any,
    values: Union[Sequence[float], np.ndarray],
    parameter: str = "parameter",
    *,
    transient_cycles: int = 50,
    cycles: int = 100,
    output: OutputSpec,
    point: Optional[Sequence[float]] = None,
    period: Union[None, float, Callable[[float], float]] = None,
    phase: float = 0.0,
    lyapunov: Union[bool, str] = "auto",
    tol: float = TOL,
    executor: Any = None,
    progress: bool = True,
    **options: Any,
) -> Bifurcation:
    """A :class:`Bifurcation` over ``values`` of a parameter.

    ``build``: a function ``value → Mechanism``, or a :class:`clearsim.Mechanism` with
    ``parameter`` the path of the field to set (``"crank-drive.omega"``, as
    :meth:`Mechanism.with_values` reads it); otherwise ``parameter`` only names the axis. Each
    mechanism runs ``transient_cycles`` + ``cycles`` periods of its forcing (``period`` [s]: a
    number, a function of the value, or by default :func:`forcing_period` of each mechanism);
    its sections at t_n = (n + ``phase``/2π) T (phase [rad]) after the transient give the points
    of ``output``: ``(body, quantity, component)`` (``("slider", "acceleration", "x")``) or
    ``(clearance joint, quantity)`` with quantity ``"eccentricity"`` (ratio e/c),
    ``"eccentricity_x"``/``"_y"`` [m], ``"force"`` or ``"contact_force"`` [N]; with ``point=(x, y)``
    (body frame [m], as ``Output(body=, point=, component=)`` names one) the body output is that
    point's, component ``"x"``, ``"y"`` or ``"magnitude"`` (``("coupler", "velocity", "x"),
    point=(0.1, 0.02)``: m, m/s, m/s²).

    ``lyapunov``: ``"auto"`` (default) runs a shadow (:func:`clearsim.dynamics.lyapunov`) over the
    same cycles for the values that are not periodic, to tell chaos from a torus (unless the
    tolerances are too loose for an exponent: then, as with ``False``, the section's neighbour
    test decides and ``how`` says why); ``True`` for every value (the exponent over the whole
    diagram, twice the runs; too loose tolerances are an InputError). ``tol``: a repeat within this fraction of each feature's
    range is periodic. Other keyword arguments are :meth:`Mechanism.simulate`'s (integrator,
    rtol, atol, ...) and ``executor`` / ``progress`` those of the batch
    (:func:`clearsim.batch.run_all`)."""
    vals = np.asarray(values, dtype=float).ravel()
    if len(vals) == 0 or not np.all(np.isfinite(vals)):
        raise InputError("invalid values: give one or more finite numbers", field="values", value=values)
    if not (isinstance(transient_cycles, (int, np.integer)) and transient_cycles >= 0):
        raise InputError(f"invalid transient_cycles = {transient_cycles!r}: must be a whole number ≥ 0", field="transient_cycles", value=transient_cycles)
    if not (isinstance(cycles, (int, np.integer)) and cycles >= 4):
        raise InputError(f"invalid cycles = {cycles!r}: must be a whole number ≥ 4", field="cycles", value=cycles)
    if lyapunov not in (True, False, "auto"):
        raise InputError(f"invalid lyapunov = {lyapunov!r}: True, False or 'auto'", field="lyapunov", value=lyapunov)
    start = time.perf_counter()
    mechs = _mechanisms(build, vals, parameter)
    first = mechs[0]
    read, out_name, unit, accel, joints = _reader(output, first.description(), first.body_names, first.clearance_joint_names, point)
    if point is not None:  # in mm or in the global frame: a PlausibilityWarning
        first.warn_output_point(output[0], point, "point")
    periods = np.array([float(period(float(v))) if callable(period) else (float(period) if period is not None else forcing_period(m)) for v, m in zip(vals, mechs)])
    if not np.all(periods > 0):
        raise InputError(f"invalid period: {periods.min()!r} s; periods must be positive", field="period", value=float(periods.min()))
    phase = float(phase)
    channels = ["states"] + (["accelerations"] if accel else []) + (["joints"] if (joints or first.clearance_joint_names) else [])
    options = dict(options)
    options.setdefault("outputs", channels)
    atol = float(options.get("atol", ATOL))
    noise = (float(options.get("rtol", RTOL)), atol)
    no_exponent = ""
    if lyapunov is True:  # tolerances too loose for an exponent: an InputError before anything runs
        shadow_spec(first, transient_cycles * periods[0], periods[0], None, None, noise[0], atol)
    elif lyapunov == "auto":
        try:
            shadow_spec(first, transient_cycles * periods[0], periods[0], None, None, noise[0], atol)
        except InputError as err:  # the section's own test decides, and says why
            lyapunov, no_exponent = False, f"; no exponent: {err.reason}"
    settings = []
    for m, T in zip(mechs, periods):
        t_end = (transient_cycles + cycles) * T
        s = m.run_settings(t_end, t_out=[t_end], sections=(T / SUB, (SUB * phase) % (2 * math.pi)), **options)
        if lyapunov is True:
            s["lyapunov"] = shadow_spec(m, transient_cycles * T, T, None, None, noise[0], atol)
        settings.append(s)
    raws = batch.run_all([m.description() for m in mechs], settings, executor, None, progress, "bifurcation")
    n = len(vals)
    points: List[np.ndarray] = [np.zeros(0)] * n
    kinds: List[str] = ["failed"] * n
    period_k = np.zeros(n, dtype=int)
    lam = np.full(n, np.nan)
    lam_iv = np.full((n, 2), np.nan)
    how = [""] * n
    failures: List[Tuple[float, str]] = []
    sections: List[Any] = [None] * n
    cyc: List[Optional[np.ndarray]] = [None] * n
    feature_kinds: List[str] = []
    for i, (m, raw, s, T) in enumerate(zip(mechs, raws, settings, periods)):
        if isinstance(raw, BaseException):
            failures.append((float(vals[i]), str(raw)))
            how[i] = str(raw)
            continue
        res, failure = batch.finish(m, raw, s)
        if failure is not None:
            failures.append((float(vals[i]), str(failure)))
            how[i] = str(failure)
        t_from = transient_cycles * T * (1 - 1e-12)
        sec = res.poincare(T, phase, after=t_from)
        sections[i] = sec
        points[i] = np.asarray(read(sec), dtype=float)
        if failure is not None:
            continue
        sub = res.poincare(after=sec.t[0] - 1e-9 * T) if len(sec.t) else res.poincare(after=t_end_of(s))
        idx = np.arange(min(len(sub.t), cycles * SUB))
        if len(idx) < cycles * SUB:
            kinds[i], how[i] = "failed", f"{len(idx)} of {cycles * SUB} section samples recorded"
            failures.append((float(vals[i]), how[i]))
            continue
        jt = sub._raw.get("joints") if sub.joint_names else None
        f, kinds_of_features = features(sub._raw["q"][idx], None if jt is None else jt[idx])
        cyc[i] = f.reshape(cycles, SUB, -1)
        feature_kinds = kinds_of_features
        if "lyapunov" in raw:
            ex = estimate(raw["lyapunov"], transient_cycles * T, T, s["lyapunov"]["d0"])
            lam[i], lam_iv[i] = ex.exponent, ex.interval
        c = _classify(cyc[i], feature_kinds, tol, noise, lam[i], lam_iv[i], T)  # type: ignore[arg-type]
        kinds[i], period_k[i], how[i] = c.kind, c.period, c.how + ("" if c.period else no_exponent)
    if lyapunov == "auto":
        todo = [i for i in range(n) if cyc[i] is not None and kinds[i] != "failed" and period_k[i] == 0]
        if todo:
            more = []
            for i in todo:
                T = periods[i]
                s = mechs[i].run_settings((transient_cycles + cycles) * T, t_out=[(transient_cycles + cycles) * T], **dict(options, outputs=["states"]))
                s["lyapunov"] = shadow_spec(mechs[i], transient_cycles * T, T, None, None, noise[0], atol)
                more.append(s)
            raws2 = batch.run_all([mechs[i].description() for i in todo], more, executor, None, progress, "Lyapunov exponents")
            for i, raw, s in zip(todo, raws2, more):
                if isinstance(raw, BaseException) or raw.get("lyapunov") is None:
                    how[i] += f"; the shadow run failed: {raw if isinstance(raw, BaseException) else raw.get('error')}"
                    continue
                ex = estimate(raw["lyapunov"], s["lyapunov"]["start"], s["lyapunov"]["interval"], s["lyapunov"]["d0"])
                lam[i], lam_iv[i] = ex.exponent, ex.interval
                if ex.failure is not None:
                    failures.append((float(vals[i]), f"Lyapunov shadow: {ex.failure}"))
                c = _classify(cyc[i], feature_kinds, tol, noise, lam[i], lam_iv[i], periods[i])  # type: ignore[arg-type]
                kinds[i], period_k[i], how[i] = c.kind, c.period, c.how
    return Bifurcation(
        parameter, vals, points, kinds, period_k, lam, lam_iv, how, failures, out_name, unit, periods,
        int(transient_cycles), int(cycles), time.perf_counter() - start, sections, None if point is None else (float(point[0]), float(point[1])),
    )  # fmt: skip


def t_end_of(settings: Dict[str, Any]) -> float:
    return float(settings["t_end"])


def _classify(cycles: np.ndarray, kinds: List[str], tol: float, noise: Tuple[float, float], lam: float, iv: np.ndarray, period: float) -> Classification:
    rtol, atol = noise
    if math.isfinite(lam):
        return classify(cycles, kinds=kinds, tol=tol, rtol=rtol, atol=atol, exponent=float(lam), interval=(float(iv[0]), float(iv[1])), period=float(period))
    return classify(cycles, kinds=kinds, tol=tol, rtol=rtol, atol=atol)


__all__ = ["Bifurcation", "JOINT_OUTPUTS", "SUB", "bifurcation"]
