"""A reliability study of one mechanism output: the vectorised model and every method on it.

:class:`Study` turns ``build(**inputs) -> Mechanism``, the random inputs, one :class:`Output` and
its limit into a function of the inputs, the **peak** |error| (or peak joint quantity) over the
analysed window, computed by the integrator at every accepted step (``docs/physics.md`` §6: not
from stored output samples, so no answer depends on an output grid). Failure is ``peak > limit``;
the limit-state function is ``g = 1 − peak / limit`` (failure when ``g ≤ 0``).

Methods: crude :meth:`Study.monte_carlo`, the paper's per-bin :meth:`Study.fosm`, and — on
OpenTURNS (``pip install clearsim[uq]``), which works in the standard normal space of the inputs
— :meth:`Study.form`, :meth:`Study.importance_sampling`, :meth:`Study.subset`,
:meth:`Study.sobol` and the tolerance design :meth:`Study.tolerance`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple

import numpy as np

from ..errors import InputError, SimulationError, check_choice, check_finite, check_positive, renamed
from ..running import COMPONENTS
from .distributions import input_stream
from .model import Model, check_on_failure
from .estimates import failure_reasons, wilson_interval
from .fosm import FosmResult, allowable_statistics, normal_cdf, reliability_index

__all__ = ["Output", "Study", "Evaluation", "MonteCarloEstimate", "FosmResult"]

BODY_QUANTITIES = ("displacement", "velocity", "acceleration")
JOINT_QUANTITIES = ("eccentricity", "force", "contact_force", "film_force")
#: Points per crank cycle of the ideal reference trajectory that body errors are measured
#: against (cubic Hermite in between).
REFERENCE_POINTS_PER_CYCLE = 7200
#: Samples built and run together: bounds the memory of a study whatever its size.
CHUNK = 1024


@dataclass(frozen=True)
class Output:
    """The analysed output: a body coordinate's error against the ideal mechanism, or a clearance
    joint's quantity.

    ``Output(body="slider9", component="y", quantity="displacement" | "velocity" | "acceleration")``:
    |response − ideal response| in m, m/s, m/s² (``component="x"``/``"y"``) or rad, rad/s,
    rad/s² (``component="theta"``). ``axis=`` is the old name of ``component=``.

    ``Output(joint="B", quantity="eccentricity" | "force" | "contact_force" | "film_force")``:
    the eccentricity ratio ε = e/c [-], the magnitude of the joint's total force [N], its dry
    normal force F_N [N] or its film force magnitude [N].
    """

    body: Optional[str] = None
    component: Optional[str] = None
    joint: Optional[str] = None
    quantity: str = "displacement"
    #: Old name of ``component``.
    axis: Optional[str] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "component", renamed("axis", "component", self.axis, self.component, "Output."))
        object.__setattr__(self, "axis", None)
        if (self.body is None) == (self.joint is None):
            raise InputError("invalid Output: give exactly one of body= (with component=) or joint=", field="Output.body", value=self.body)
        if self.body is not None:
            check_choice("Output.component", self.component, COMPONENTS, "(there is no default)")
            if self.quantity not in BODY_QUANTITIES:
                raise InputError(f"invalid Output.quantity = {self.quantity!r}: a body output is one of {', '.join(BODY_QUANTITIES)}", field="Output.quantity", value=self.quantity)
        else:
            if self.component is not None:
                raise InputError(f"invalid Output.component = {self.component!r}: a joint output has no component", field="Output.component", value=self.component)
            if self.quantity not in JOINT_QUANTITIES:
                raise InputError(f"invalid Output.quantity = {self.quantity!r}: a joint output is one of {', '.join(JOINT_QUANTITIES)}", field="Output.quantity", value=self.quantity)

    @property
    def unit(self) -> str:
        """Unit of the output (and of its limit)."""
        if self.joint is not None:
            return "-" if self.quantity == "eccentricity" else "N"
        base = "rad" if self.component == "theta" else "m"
        return {"displacement": base, "velocity": f"{base}/s", "acceleration": f"{base}/s²"}[self.quantity]

    @property
    def label(self) -> str:
        if self.joint is not None:
            return f"{self.quantity} of joint {self.joint}"
        return f"{self.component} {self.quantity} error of {self.body}"


@dataclass
class Evaluation:
    """The model at N input points: each one's peak [output unit] over the analysed window, the
    first time [s] it exceeded the limit (NaN: never) and the runs that failed."""

    peaks: np.ndarray
    first_passage_times: np.ndarray
    failures: List[Tuple[int, str]]

    @property
    def failed(self) -> np.ndarray:
        mask = np.zeros(self.peaks.size, dtype=bool)
        for k, _ in self.failures:
            mask[k] = True
        return mask


@dataclass
class MonteCarloEstimate:
    """Crude Monte Carlo estimate of the probability that the output exceeds its limit.

    ``pf`` with its Wilson ``interval``; ``cov`` its coefficient of variation; ``n_runs``
    simulations; ``failures`` ``(sample, reason)`` of every run that failed, counted as exceedances
    (``on_failure="fail"``) or left out (``"exclude"``: ``bounds`` is then the range of p_f if
    every failed sample had stayed within / exceeded the limit). ``peaks`` and
    ``first_passage_times`` per sample (NaN for failed samples), ``inputs`` the sampled values,
    ``traces`` the full :class:`clearsim.Result` of the first ``keep_traces`` samples."""

    pf: float
    interval: Tuple[float, float]
    cov: float
    n_runs: int
    failures: List[Tuple[int, str]]
    peaks: np.ndarray
    first_passage_times: np.ndarray
    inputs: Dict[str, np.ndarray]
    on_failure: str
    bounds: Tuple[float, float]
    wall_time: float
    traces: List[Any] = field(default_factory=list)

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf

    def failure_reasons(self) -> Dict[str, int]:
        """How many runs failed for each kind of reason (the message up to ' at t =')."""
        return failure_reasons(self.failures)


class Study(Model):
    """Reliability of one output of a mechanism with random inputs.

    Parameters
    ----------
    build:
        ``build(**inputs) -> Mechanism`` for one set of input values.
    inputs:
        ``{name: distribution or number}``: :mod:`clearsim.reliability` distributions, frozen
        ``scipy.stats`` distributions or fixed numbers, in the units ``build`` expects.
    output:
        The analysed :class:`Output`.
    limit:
        Required: the largest acceptable peak of the output over the window, in the output's
        unit (:attr:`Output.unit`).
    omega:
        Drive speed [rad/s] defining the crank cycle: a number or the name of an input.
    cycles, skip_cycles:
        The analysed window: ``cycles`` crank turns after ``skip_cycles`` turns of start-up.
    bin_width:
        Crank-angle bins [deg] of the per-bin FOSM.
    integrator, rtol, atol:
        As in :meth:`clearsim.Mechanism.simulate`.
    max_steps, max_seconds:
        Budget of each run (steps; wall time [s]); a run that uses it up fails with its reason.
    executor:
        ``None``: in the Rust core on all local cores. Otherwise any ``concurrent.futures``-style
        executor (``ProcessPoolExecutor``, Dask's ``client.get_executor()``).
    progress:
        Progress bars on batches (``False`` silences them).
    """

    def __init__(
        self,
        build: Callable[..., Any],
        inputs: Mapping[str, Any],
        output: Output,
        limit: Optional[float] = None,
        *,
        omega: Any = None,
        cycles: float = 1.0,
        skip_cycles: float = 0.0,
        bin_width: float = 18.0,
        integrator: str = "auto",
        rtol: float = 1e-6,
        atol: float = 1e-9,
        max_steps: Optional[int] = None,
        max_seconds: Optional[float] = None,
        executor: Any = None,
        chunk_size: Optional[int] = None,
        progress: bool = True,
    ) -> None:
        if not callable(build):
            raise InputError(f"invalid build = {build!r}: must be a callable returning a Mechanism", field="build", value=build)
        if not isinstance(output, Output):
            raise InputError(f"invalid output = {output!r}: must be a clearsim.reliability.Output", field="output", value=output)
        if limit is None:
            raise InputError(f"missing limit: the largest acceptable {output.label} [{output.unit}] is required (there is no default)", field="limit", value=None)
        self.limit = check_positive("limit", limit)
        if not inputs:
            raise InputError("missing inputs: give at least one {name: distribution or number}", field="inputs", value=inputs)
        self.build = build
        self._set_inputs(inputs)
        self.output = output
        if omega is None:
            raise InputError("missing omega: give the drive speed [rad/s] or the name of the input that holds it", field="omega", value=None)
        if isinstance(omega, str) and omega not in self.inputs:
            raise InputError(f"invalid omega = {omega!r}: not an input; give the drive speed [rad/s] or an input's name", field="omega", value=omega)
        if not isinstance(omega, str) and (check_finite("omega", omega) == 0.0):
            raise InputError("invalid omega = 0: the drive speed must be non-zero", field="omega", value=omega)
        self.omega = omega
        self.cycles = check_positive("cycles", cycles)
        if not (math.isfinite(skip_cycles) and skip_cycles >= 0):
            raise InputError(f"invalid skip_cycles = {skip_cycles!r}: must be finite and not negative", field="skip_cycles", value=skip_cycles)
        self.skip_cycles = float(skip_cycles)
        self.bin_width = check_positive("bin_width", bin_width)
        self.run_options: Dict[str, Any] = dict(integrator=integrator, rtol=rtol, atol=atol)
        if max_steps is not None:
            self.run_options["max_steps"] = max_steps
        if max_seconds is not None:
            self.run_options["max_seconds"] = max_seconds
        self.executor = executor
        self.chunk_size = chunk_size
        self.progress = progress
        self._counter = [0]  # simulations of the mechanism with clearances so far (ideal twins aside)
        self._ideal: Dict[str, Any] = {}
        self._assembly_checked = False

    # ------------------------------------------------------------------ the model
    def __repr__(self) -> str:
        return f"Study({self.output.label} ≤ {self.limit:g} {self.output.unit}; random: {', '.join(self.random_names) or 'none'})"

    def _omega(self, params: Mapping[str, float]) -> float:
        w = float(params[self.omega]) if isinstance(self.omega, str) else float(self.omega)
        if w == 0.0 or not math.isfinite(w):
            raise InputError(f"invalid omega = {w!r}: the drive speed must be finite and non-zero", field="omega", value=w)
        return w

    def _window(self, params: Mapping[str, float]) -> Tuple[float, float, float]:
        period = 2.0 * math.pi / abs(self._omega(params))
        t0 = self.skip_cycles * period
        return t0, t0 + self.cycles * period, period

    def _target(self, m: Any) -> int:
        if self.output.body is not None:
            names = m.body_names
            if self.output.body not in names:
                raise InputError(f"invalid Output.body = {self.output.body!r}: no such body (known: {', '.join(names)})", field="Output.body", value=self.output.body)
            return 3 * names.index(self.output.body) + COMPONENTS.index(str(self.output.component))
        names = m.clearance_joint_names
        if self.output.joint not in names:
            raise InputError(f"invalid Output.joint = {self.output.joint!r}: no such clearance joint (known: {', '.join(names) or 'none'})", field="Output.joint", value=self.output.joint)
        return names.index(self.output.joint)

    def _check_first_assembly(self, m: Any, t0: float) -> None:
        """The pose check of ``Mechanism.simulate`` (a joint point in the wrong frame is an
        AssemblyError) and the assembly at the window's start ``t0`` (a dead centre before it is
        an AssemblyError naming it), on the first mechanism the study builds."""
        if not self._assembly_checked:
            m.check_assembly(t0)
            self._assembly_checked = True

    def _reference(self, m: Any, t0: float, t1: float, period: float) -> Any:
        """The ideal mechanism's response that body errors are measured against (run once per
        distinct ideal mechanism and window; random clearances do not change it)."""
        n = max(2, int(math.ceil(REFERENCE_POINTS_PER_CYCLE * (t1 - t0) / period)))
        key, desc, settings = m.reference_job(np.linspace(t0, t1, n + 1), **self.run_options)
        if key not in self._ideal:
            from .. import _core

            raw = _core.run_batch([desc], [settings], 1)[0]
            if isinstance(raw, BaseException) or raw.get("error") is not None:
                err = raw if isinstance(raw, BaseException) else raw["error"]
                self._ideal[key] = f"{err} (ideal mechanism)"
            else:
                self._ideal[key] = raw
        return self._ideal[key]

    def _monitor(self, col: int, t0: float, period: float, reference: Any) -> Dict[str, Any]:
        from ..montecarlo import _monitor_spec

        return _monitor_spec(reference, col, self.output.quantity, (0.0, self.limit), t0, period, self.cycles, self.bin_width)

    def _jobs(self, points: Mapping[str, np.ndarray], start: int, stop: int, keep: int) -> Tuple[List[Any], List[Any], Dict[int, str], List[Any]]:
        descriptions, settings, errors, mechs = [], [], {}, []
        for k in range(start, stop):
            params = {name: float(v[k]) for name, v in points.items()}
            m = self.build(**params)
            t0, t1, period = self._window(params)
            self._check_first_assembly(m, t0)
            col = self._target(m)
            reference = None
            if self.output.body is not None:
                reference = self._reference(m, t0, t1, period)
                if isinstance(reference, str):
                    errors[k] = reference
                    continue
            grid = np.linspace(t0, t1, int(round(360 * self.cycles)) + 1) if k < keep else np.array([t0, t1])
            s = m.run_settings(t1, t_out=grid, outputs=["states"] if k >= keep else None, **self.run_options)
            s["monitors"] = [self._monitor(col, t0, period, reference)]
            descriptions.append(m.description())
            settings.append(s)
            mechs.append((k, m, s))
        return descriptions, settings, errors, mechs

    def evaluate(self, points: Mapping[str, Any], *, keep_traces: int = 0, what: str = "runs") -> Tuple[Evaluation, List[Any]]:
        """Run the model at ``points`` (``{input name: (N,) array}``; missing inputs at their
        mean) in chunks of :data:`CHUNK`, keeping only each run's peak and first-passage time
        (and the full result of the first ``keep_traces`` runs)."""
        from ..montecarlo import _progress, _run_all

        full = {name: np.atleast_1d(np.asarray(points[name], dtype=float)) if name in points else None for name in self.inputs}
        n = max((v.size for v in full.values() if v is not None), default=1)
        cols = {name: (v if v is not None else np.full(n, self.inputs[name].nominal)) for name, v in full.items()}
        for name, v in cols.items():
            if v.size != n:
                raise InputError(f"invalid points[{name!r}]: {v.size} values, others have {n}", field=f"points.{name}", value=v.size)
        peaks = np.full(n, np.nan)
        first = np.full(n, np.nan)
        failures: List[Tuple[int, str]] = []
        traces: List[Any] = []
        bar = _progress(n, self.progress and n >= 256, what)  # big batches only (not FORM's gradients)
        try:
            for start in range(0, n, CHUNK):
                stop = min(n, start + CHUNK)
                descriptions, settings, errors, mechs = self._jobs(cols, start, stop, keep_traces)
                raws = _run_all(descriptions, settings, self.executor, self.chunk_size, False, what) if descriptions else []
                for (k, m, s), raw in zip(mechs, raws):
                    if isinstance(raw, BaseException) or raw.get("error") is not None:
                        errors[k] = str(raw if isinstance(raw, BaseException) else raw["error"])
                        continue
                    mon = raw["monitors"][0]
                    peaks[k] = mon["peak"]
                    first[k] = mon["first_passage"]
                    if k < keep_traces:
                        traces.append(m._finish(raw, s))
                failures += sorted(errors.items())
                self.n_runs += stop - start
                bar.update(stop - start)
        finally:
            bar.close()
        return Evaluation(peaks, first, failures), traces

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        """``g(u) = 1 − peak / limit`` at standard normal points ``u`` (N × d); failure when
        ``g ≤ 0``. A run that fails gives ``g = −1`` (an exceedance) or raises
        (``on_failure="raise"``)."""
        ev, _ = self.evaluate(self.values(u), what="limit state")
        _check_failures(ev, on_failure, self)
        g = 1.0 - ev.peaks / self.limit
        g[ev.failed] = -1.0
        return g

    # ------------------------------------------------------------------ methods
    def monte_carlo(self, n: int, seed: Optional[int] = 0, executor: Any = None, on_failure: str = "fail", *, keep_traces: int = 0, confidence: float = 0.95) -> MonteCarloEstimate:
        """Crude Monte Carlo with ``n`` samples (memory: a few numbers per sample; the full
        results of the first ``keep_traces`` samples on request). Each input has its own random
        stream seeded by ``(seed, name)``. ``on_failure``: ``"fail"`` (default: a failed run
        counts as an exceedance), ``"exclude"`` (left out; ``bounds`` brackets p_f) or
        ``"raise"``."""
        check_on_failure(on_failure)
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
        start = time.perf_counter()
        saved, self.executor = self.executor, executor if executor is not None else self.executor
        try:
            u = np.column_stack([input_stream(seed, name).standard_normal(int(n)) for name in self.random_names]) if self.random_names else np.zeros((int(n), 0))
            inputs = self.values(u)
            runs0 = self.n_runs
            ev, traces = self.evaluate(inputs, keep_traces=keep_traces, what="Monte Carlo samples")
        finally:
            self.executor = saved
        _check_failures(ev, on_failure, self)
        exceed = (ev.peaks > self.limit) & ~ev.failed
        k_out, n_fail = int(exceed.sum()), len(ev.failures)
        if on_failure == "fail":
            k, n_eff = k_out + n_fail, int(n)
        else:
            k, n_eff = k_out, int(n) - n_fail
        if n_eff < 1:
            raise SimulationError(f"no Monte Carlo sample completed ({n_fail} failed); first failure: {ev.failures[0][1]}", reason=ev.failures[0][1])
        pf = k / n_eff
        lo, hi = wilson_interval(k, n_eff, confidence)
        cov = math.sqrt((1.0 - pf) / (pf * n_eff)) if pf > 0 else math.inf
        return MonteCarloEstimate(
            pf=pf, interval=(float(lo), float(hi)), cov=cov, n_runs=self.n_runs - runs0, failures=ev.failures,
            peaks=ev.peaks, first_passage_times=ev.first_passage_times, inputs=inputs, on_failure=on_failure,
            bounds=(k_out / int(n), (k_out + n_fail) / int(n)), wall_time=time.perf_counter() - start, traces=traces,
        )  # fmt: skip

    def fosm(self, bin_width: Optional[float] = None) -> FosmResult:
        """The paper's per-bin FOSM (Eqs. P27–P32) of the nominal mechanism (every input at its
        mean): per crank-angle bin, the time-averaged mean and standard deviation of |error|
        over the analysed cycles, integrated at every step (not from stored samples), against
        the allowable range ``[0, limit]`` (μ_S = limit/2, σ_S = limit/6)."""
        width = check_positive("bin_width", bin_width) if bin_width is not None else self.bin_width
        saved, self.bin_width = self.bin_width, width
        try:
            params = self.nominal()
            m = self.build(**params)
            t0, t1, period = self._window(params)
            self._check_first_assembly(m, t0)
            col = self._target(m)
            reference = self._reference(m, t0, t1, period) if self.output.body is not None else None
            if isinstance(reference, str):
                raise SimulationError(f"FOSM: {reference}", reason=reference)
            s = m.run_settings(t1, t_out=np.array([t0, t1]), outputs=["states"], **self.run_options)
            s["monitors"] = [self._monitor(col, t0, period, reference)]
        finally:
            self.bin_width = saved
        from .. import _core

        raw = _core.run_batch([m.description()], [s], 1)[0]
        self.n_runs += 1
        if isinstance(raw, BaseException) or raw.get("error") is not None:
            err = raw if isinstance(raw, BaseException) else raw["error"]
            raise SimulationError(f"FOSM: the nominal mechanism failed: {err}", reason=str(err))
        mon = raw["monitors"][0]
        per_cycle = int(math.ceil(360.0 / width - 1e-9))
        n_time = len(mon["bin_time"])
        fold = np.arange(n_time) % per_cycle
        integ = np.zeros((3, per_cycle))
        for row, key in enumerate(("bin_abs", "bin_sq", "bin_time")):
            np.add.at(integ[row], fold, np.asarray(mon[key], dtype=float))
        count = np.bincount(fold[np.asarray(mon["bin_time"]) > 0], minlength=per_cycle)
        with np.errstate(invalid="ignore", divide="ignore"):
            mu_s = integ[0] / integ[2]
            sigma_s = np.sqrt(np.maximum(integ[1] / integ[2] - mu_s**2, 0.0))
        mu_S, sigma_S = allowable_statistics(0.0, self.limit)
        beta = np.asarray(reliability_index(mu_S, sigma_S, mu_s, sigma_s), dtype=float)
        starts = np.arange(per_cycle) * width
        centres = np.minimum(starts + 0.5 * width, 0.5 * (starts + np.minimum(starts + width, 360.0)))
        return FosmResult(starts, centres, np.zeros(per_cycle, dtype=int), count, mu_s, sigma_s, beta, np.asarray(normal_cdf(beta)), mu_S, sigma_S, width)


    def importance_sampling(self, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0, *, design_point: Any = None, block: int = 64, on_failure: str = "fail") -> Any:
        """Importance sampling around the FORM design point until the estimate's coefficient of
        variation reaches ``cov`` (or ``max_runs``). See :func:`clearsim.reliability.uq.importance_sampling`."""
        from . import uq

        return uq.importance_sampling(self, cov=cov, max_runs=max_runs, seed=seed, design_point=design_point, block=block, on_failure=on_failure)

    def subset(self, seed: Optional[int] = 0, *, n_per_level: int = 1000, conditional_probability: float = 0.1, on_failure: str = "fail") -> Any:
        """Subset simulation (OpenTURNS). See :func:`clearsim.reliability.uq.subset`."""
        from . import uq

        return uq.subset(self, seed=seed, n_per_level=n_per_level, conditional_probability=conditional_probability, on_failure=on_failure)

    def sobol(self, n: int, seed: Optional[int] = 0, *, on_failure: str = "fail") -> Any:
        """First-order and total Sobol indices of the peak output (OpenTURNS, Martinez):
        ``n × (d + 2)`` runs. See :func:`clearsim.reliability.uq.sobol`."""
        from . import uq

        return uq.sobol(self, n, seed=seed, on_failure=on_failure)

    def tolerance(self, name: str, reliability: float, *, bracket: Optional[Tuple[float, float]] = None, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0) -> Any:
        """The largest mean of input ``name`` (its spread kept) for which the reliability is
        still ``reliability``. See :func:`clearsim.reliability.uq.tolerance`."""
        from . import uq

        return uq.tolerance(self, name, reliability, bracket=bracket, cov=cov, max_runs=max_runs, seed=seed)


def _check_failures(ev: Evaluation, on_failure: str, study: Study) -> None:
    check_on_failure(on_failure)
    if ev.failures and on_failure == "raise":
        k, reason = ev.failures[0]
        raise SimulationError(f"run {k} of {ev.peaks.size} failed: {reason}; {len(ev.failures)} failed in all", reason=reason)


