"""A reliability study of a mechanism: the simulation model (one Monte Carlo sample loop for
every method) and the methods that need the mechanism itself (crude Monte Carlo, per-bin FOSM).

:class:`Study` turns ``build(**inputs) -> Mechanism``, the random inputs, one or several
:class:`Output` and their :class:`Limit` into a function of the inputs: each output's **peak**
(or minimum, for a lower limit) over the analysed window, computed by the integrator at every
accepted step (``docs/physics.md`` §6: not from stored output samples, so no answer depends on an
output grid). One output fails when it passes its limit; the limit-state function is
``g = 1 − peak / limit`` (``minimum / limit − 1`` for a lower limit), failure when ``g ≤ 0``.
Several outputs make a series system: ``g = min_i g_i`` (docs/reliability.md).

Every method inherited from :class:`~clearsim.reliability.model.ReliabilityModel` (FORM, importance
sampling, subset simulation, Sobol indices, tolerance design) runs the model through
:meth:`Study.limit_states`; :meth:`Study.monte_carlo` and ``clearsim.monte_carlo`` run it through
:meth:`Study.run_samples`, the one sample loop.
"""

from __future__ import annotations

import inspect
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..errors import InputError, SimulationError, check_choice, check_finite, check_positive
from ..schema import ATOL, REFERENCES, RTOL
from .bridge import check_on_failure
from .distributions import input_stream
from .estimates import failure_reasons, wilson_interval
from .fosm import BIN_WIDTH, FosmResult, allowable_statistics, bin_fold, fosm_from_monitors, window_start_turns
from .model import ReliabilityModel
from .outputs import BODY_QUANTITIES, JOINT_QUANTITIES, Limit, Modes, Output, limits_and_outputs
from ..batch import error_of, failed, progress, run_all, task_threads
from .runs import REFERENCE_POINTS_PER_CYCLE, monitor_spec, output_grid, reference_grid
from .checkpoint import Checkpoint, run_jobs
from .window import at_window_start, warn_at_start
from .. import display

__all__ = ["Output", "Limit", "Study", "Evaluation", "MonteCarloEstimate", "ModeEstimate", "FosmResult", "BODY_QUANTITIES", "JOINT_QUANTITIES", "REFERENCE_POINTS_PER_CYCLE"]

#: Samples built and run together: bounds the memory of a study whatever its size.
CHUNK = 1024


@dataclass
class Evaluation:
    """The model at N input points: each output's extreme over the analysed window
    (``values``, (N, outputs): the peak for an upper limit, the minimum for a lower one; NaN for
    failed runs), the first time [s] each passed its limit (``first_passage``, NaN: never or not
    tracked), the runs that failed and, on request, each run's raw monitor results.

    ``peaks`` and ``first_passage_times`` are ``values`` and ``first_passage`` as (N,) arrays for
    a study of one output."""

    values: np.ndarray
    first_passage: np.ndarray
    failures: List[Tuple[int, str]]
    monitors: Optional[List[Any]] = None

    @property
    def peaks(self) -> np.ndarray:
        return self.values[:, 0] if self.values.shape[1] == 1 else self.values

    @property
    def first_passage_times(self) -> np.ndarray:
        return self.first_passage[:, 0] if self.first_passage.shape[1] == 1 else self.first_passage

    def __repr__(self) -> str:
        return display.text(self, "peaks", "first_passage_times", "failures")

    def _repr_html_(self) -> str:
        return display.html(self, "peaks", "first_passage_times", "failures")

    @property
    def failed(self) -> np.ndarray:
        mask = np.zeros(self.values.shape[0], dtype=bool)
        for k, _ in self.failures:
            mask[k] = True
        return mask


@dataclass
class ModeEstimate:
    """One failure mode's crude Monte Carlo estimate, from the same runs as the system's."""

    name: str
    pf: float
    interval: Tuple[float, float]
    exceedances: int


@dataclass
class MonteCarloEstimate:
    """Crude Monte Carlo estimate of the probability that the output exceeds its limit (any
    output its limit, for a series system).

    ``pf`` with its Wilson ``interval``; ``cov`` its coefficient of variation; ``n_runs``
    simulations; ``failures`` ``(sample, reason)`` of every run that failed, counted as exceedances
    (``on_failure="fail"``) or left out (``"exclude"``: ``bounds`` is then the range of p_f if
    every failed sample had stayed within / exceeded the limit). ``peaks`` and
    ``first_passage_times`` per sample (NaN for failed samples; (n, outputs) for a system),
    ``inputs`` the sampled values, ``traces`` the full :class:`clearsim.Result` of the first
    ``keep_traces`` samples; ``modes`` each output's own estimate from the same runs."""

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
    modes: List[ModeEstimate] = field(default_factory=list)

    def __repr__(self) -> str:
        return display.text(self, "pf", "interval", "cov", "n_runs", "failures", "on_failure", "bounds", "wall_time", "peaks", "inputs")

    def _repr_html_(self) -> str:
        return display.html(self, "pf", "interval", "cov", "n_runs", "failures", "on_failure", "bounds", "wall_time", "peaks", "inputs")

    @property
    def reliability(self) -> float:
        return 1.0 - self.pf

    def failure_reasons(self) -> Dict[str, int]:
        """How many runs failed for each kind of reason (the message up to ' at t =')."""
        return failure_reasons(self.failures)


@dataclass
class _Job:
    """One sample's run as the loop builds it: its mechanism and run settings (the monitors
    name the reference they are measured against; the core makes it)."""

    k: int
    mechanism: Any
    settings: Dict[str, Any]
    #: Each output's clearance [m] (a film thickness's; 0 for the others).
    clearances: List[float]


def _driver_speed(m: Any) -> float:
    """ω [rad/s] of the constant-speed driver of mechanism ``m``: the default of ``Study(omega=)``
    (a scene's ``[study]`` takes the first such driver of the file the same way)."""
    speeds = {d["name"]: float(d["law"]["omega"]) for d in m.description()["drivers"] if d["law"]["kind"] == "constant_speed"}
    if not speeds:
        raise InputError(
            "missing omega: the nominal mechanism has no constant-speed driver to take the crank cycle from; "
            "give omega, the drive speed [rad/s], or the name of the input that holds it", field="omega", value=None,
        )  # fmt: skip
    if len(set(speeds.values())) > 1:
        listed = ", ".join(f"{name!r} {w:g} rad/s" for name, w in speeds.items())
        raise InputError(f"missing omega: the nominal mechanism has several constant-speed drivers ({listed}); give omega, the drive speed [rad/s] of the crank cycle", field="omega", value=None)
    return next(iter(speeds.values()))


def _check_takes(build: Callable[..., Any], names: Sequence[str]) -> None:
    """``build(**inputs)`` must take every input by name: a mismatch (an input renamed in one
    place) is an InputError here, not a TypeError from the first run."""
    try:
        signature = inspect.signature(build)
    except (TypeError, ValueError):  # no signature to read (a builtin): the first call will say
        return
    try:
        signature.bind(**{n: None for n in names})
    except TypeError as err:
        raise InputError(f"invalid inputs = {list(names)!r}: build{signature} does not take them by name ({err})", field="inputs", value=list(names)) from None


class Study(ReliabilityModel, Modes):
    """Reliability of one or several outputs of a mechanism with random inputs.

    Parameters
    ----------
    build:
        ``build(**inputs) -> Mechanism`` for one set of input values.
    inputs:
        ``{name: distribution or number}``: :mod:`clearsim.reliability` distributions, frozen
        ``scipy.stats`` distributions or fixed numbers, in the units ``build`` expects.
    output:
        The analysed :class:`Output`, or a list of them: a series system that fails when any
        output passes its limit.
    limit:
        Required: the limit of each output in its unit (:attr:`Output.unit`): a positive number
        (the largest acceptable peak), :meth:`Limit.below` / ``("below", x)`` (the smallest
        acceptable minimum, e.g. a film thickness) or :meth:`Limit.above`; a list for a list of
        outputs.
    omega:
        Drive speed [rad/s] defining the crank cycle: a number or the name of an input. Default:
        the speed of the constant-speed driver of the nominal mechanism (``build`` at the inputs'
        means), as a scene's ``[study]`` takes it; an :class:`InputError` when it has none, or
        several at different speeds. Give the input's name when an input sets the drive speed.
    cycles, skip_cycles:
        The analysed window: ``cycles`` crank turns after ``skip_cycles`` turns of start-up,
        opening at the first bin edge of the crank angle |ω| t at or after them (t from t = 0,
        docs/physics.md §6: ``skip_cycles = 0.26`` with 18° bins opens at 0.3 turns).
    bin_width:
        Crank-angle bins [deg] of the per-bin FOSM, edges at k·bin_width of |ω| t modulo 360°.
    integrator, rtol, atol:
        As in :meth:`clearsim.Mechanism.simulate`.
    max_steps, max_seconds:
        Budget of each run (steps; wall time [s]); a run that uses it up fails with its reason.
    reference:
        What body and point errors are measured against: ``"own_ideal"`` (default) each sample's
        own mechanism with its clearance joints made ideal — the paper's question, what do the
        clearances add? (link-length and pivot tolerances move the reference with the sample and
        barely register) — or ``"nominal"``: the ideal motion of the nominal design (``build`` at
        the inputs' means), one run for all samples — a designer's question, how far from the
        nominal motion? (every tolerance counts). The core runs each reference once and shares
        it (docs/reliability.md, "What the error is measured against").
    executor:
        ``None``: in the Rust core on all local cores. Otherwise any ``concurrent.futures``-style
        executor (``ProcessPoolExecutor``, Dask's ``client.get_executor()``): a task carries only
        the chunk's descriptions and settings (and the nominal description); its worker runs the
        reference itself.
    threads:
        The core's threads per batch: default all local cores in this process, one per task
        under an ``executor`` (its workers' sizes decide); 0: all the machine's cores.
    progress:
        Progress bars on batches (``False`` silences them).
    """

    def __init__(
        self,
        build: Callable[..., Any],
        inputs: Mapping[str, Any],
        output: Any,
        limit: Any = None,
        *,
        omega: Any = None,
        cycles: float = 1.0,
        skip_cycles: float = 0.0,
        bin_width: float = BIN_WIDTH,
        integrator: str = "auto",
        rtol: float = RTOL,
        atol: float = ATOL,
        max_steps: Optional[int] = None,
        max_seconds: Optional[float] = None,
        reference: str = "own_ideal",
        executor: Any = None,
        threads: Optional[int] = None,
        chunk_size: Optional[int] = None,
        progress: bool = True,
    ) -> None:
        if not callable(build):
            raise InputError(f"invalid build = {build!r}: must be a callable returning a Mechanism", field="build", value=build)
        self.outputs, self.limits = limits_and_outputs(output, limit)
        if not inputs:
            raise InputError("missing inputs: give at least one {name: distribution or number}", field="inputs", value=inputs)
        self.build = build
        self._set_inputs(inputs)
        _check_takes(build, list(self.nominal()))
        if omega is None:
            omega = _driver_speed(self.built(self.nominal()))
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
        self.reference = check_choice("reference", reference, REFERENCES)
        self.executor = executor
        task_threads(threads, None)  # checked here, used per batch
        self.threads = threads
        self.chunk_size = chunk_size
        self.progress = progress
        self._counter = [0]  # simulations of the mechanism with clearances so far (references aside)
        self._nominal: Optional[Tuple[Dict[str, Any], List[str]]] = None
        self._assembly_checked = False
        self._warned_start = False  # warned once that the peaks sit at the window's start

    # ------------------------------------------------------------------ outputs and limits (Modes)
    @property
    def mode_names(self) -> List[str]:
        """One failure mode per output: its :attr:`Output.name`."""
        return [o.name for o in self.outputs]

    def __repr__(self) -> str:
        modes = " and ".join(f"{o.label} {lim.text(o.unit)}" for o, lim in zip(self.outputs, self.limits))
        return f"Study({modes}; random: {', '.join(self.random_names) or 'none'})"

    # ------------------------------------------------------------------ the model
    def _omega(self, params: Mapping[str, float]) -> float:
        w = float(params[self.omega]) if isinstance(self.omega, str) else float(self.omega)
        if w == 0.0 or not math.isfinite(w):
            raise InputError(f"invalid omega = {w!r}: the drive speed must be finite and non-zero", field="omega", value=w)
        return w

    def _window(self, params: Mapping[str, float]) -> Tuple[float, float, float]:
        """The analysed window [s] and the crank period [s]: ``cycles`` turns from the first bin
        edge of |ω| t at or after ``skip_cycles`` turns (docs/physics.md §6), so that each monitor
        time bin is one crank-angle bin whatever the run's start."""
        period = 2.0 * math.pi / abs(self._omega(params))
        t0 = window_start_turns(self.skip_cycles, self.bin_width) * period
        return t0, t0 + self.cycles * period, period

    def built(self, params: Mapping[str, float]) -> Any:
        """``build(**params)``, which must be a Mechanism (an InputError naming what it was)."""
        m = self.build(**params)
        if not hasattr(m, "run_settings"):  # duck-typed: reliability sits above the mechanism
            raise InputError(f"invalid build: it returned a {type(m).__name__}, not a clearsim.Mechanism (inputs {dict(params)})", field="build", value=type(m).__name__)
        return m

    def _check_first_assembly(self, m: Any, t0: float) -> None:
        """The pose check of ``Mechanism.simulate`` (a joint point in the wrong frame is an
        AssemblyError) and the assembly at the window's start ``t0`` (a dead centre before it is
        an AssemblyError naming it), on the first mechanism the study builds."""
        if not self._assembly_checked:
            m.check_assembly(t0)
            self._assembly_checked = True

    def _nominal_run(self) -> Tuple[Dict[str, Any], List[str]]:
        """The nominal design's description (``build`` at the inputs' means: the reference of
        ``reference="nominal"``, which the core idealises and runs) and its bodies."""
        if self._nominal is None:
            m = self.built(self.nominal())
            self._nominal = (m.description(), list(m.body_names))
        return self._nominal

    def _check_bodies(self, m: Any) -> None:
        """A sample measured against the nominal design must have its bodies (the errors compare
        body by body): an InputError naming those that differ."""
        bodies = self._nominal_run()[1]
        if list(m.body_names) != bodies:
            only_nominal = [b for b in bodies if b not in m.body_names]
            only_sample = [b for b in m.body_names if b not in bodies]
            raise InputError(
                f"invalid reference = 'nominal': the nominal mechanism's bodies differ from a sample's (only in the nominal: "
                f"{only_nominal or 'none'}; only in the sample: {only_sample or 'none'}); build must give every sample the same bodies",
                field="reference", value="nominal",
            )  # fmt: skip

    def _monitors(self, m: Any, t0: float, period: float, clearances: List[float]) -> List[Dict[str, Any]]:
        """The monitors of a sample of ``m``: each output's target, measured against the study's
        reference (body and point outputs) or itself (joint outputs), from ``t0`` [s]."""
        specs = []
        for o, lim, c in zip(self.outputs, self.limits, clearances):
            target = o.target(m.body_names, m.clearance_joint_names)
            if o.quantity == "film_thickness":
                track: Optional[float] = 1.0 - lim.value / c if c > 0 else None  # ε at which h = c(1 − ε) reaches the limit
            else:
                track = lim.value if lim.side == "above" else None
            reference = self.reference if o.body is not None else None
            specs.append(monitor_spec(target, o.monitored, reference, track, t0, period, self.cycles, self.bin_width))
        return specs

    def run_samples(
        self, points: Mapping[str, Any], *, keep_traces: int = 0, points_per_cycle: int = 360, trace_outputs: Optional[Sequence[str]] = None,
        raw_traces: bool = False, keep_monitors: bool = False, check_assembly: bool = True, what: str = "runs", show: Optional[bool] = None,
        on_job: Optional[Callable[[int, Dict[str, Any], Dict[str, Any]], None]] = None, on_raw: Optional[Callable[[int, Dict[str, Any]], None]] = None,
        on_trace: Optional[Callable[[int, Any], Any]] = None, checkpoint: Any = None, timeout: Optional[float] = None,
    ) -> Tuple[Evaluation, List[Any]]:  # fmt: skip
        """The sample loop: run the model at ``points`` (``{input name: (N,) array}``; missing
        inputs at their mean) in chunks of :data:`CHUNK`, keeping each run's extremes and
        first-passage times (and on request its raw monitor results).

        The first ``keep_traces`` runs also store their outputs on ``points_per_cycle`` points a
        cycle (``trace_outputs``: the run's ``outputs``): as :class:`clearsim.Result` objects, or
        with ``raw_traces`` as ``{"sample": raw run, "ideal": the reference's t, q, qd and qdd
        at the same output times, "columns": each output's monitored coordinate or joint index}``. ``on_job(k, description,
        settings)`` may change sample k's description and run settings before it runs (life.py
        writes the worn state there); ``on_raw(k, raw)`` sees each completed run's raw result;
        ``on_trace(k, trace)`` turns a kept trace into what is kept (the full run dropped as its
        chunk ends). ``checkpoint``, ``timeout``: as :meth:`monte_carlo` (reliability/checkpoint.py)."""
        full = {name: np.atleast_1d(np.asarray(points[name], dtype=float)) if name in points else None for name in self.inputs}
        n = max((v.size for v in full.values() if v is not None), default=1)
        cols = {name: (v if v is not None else np.full(n, self.inputs[name].nominal)) for name, v in full.items()}
        for name, v in cols.items():
            if v.size != n:
                raise InputError(f"invalid points[{name!r}]: {v.size} values, others have {n}", field=f"points.{name}", value=v.size)
        m_out = len(self.outputs)
        values = np.full((n, m_out), np.nan)
        first = np.full((n, m_out), np.nan)
        failures: List[Tuple[int, str]] = []
        monitors: Optional[List[Any]] = [None] * n if keep_monitors else None
        traces: List[Any] = []
        at_start = np.zeros((n, m_out), dtype=bool)  # peaks at the window's start (window.py)
        t_start = math.nan
        shown = (self.progress and n >= 256) if show is None else show  # big batches only (not FORM's gradients)
        bar = progress(n, shown, what)
        store = Checkpoint(checkpoint) if checkpoint is not None else None
        try:
            for start in range(0, n, CHUNK):
                stop = min(n, start + CHUNK)
                jobs = self._chunk_jobs(cols, start, stop, keep_traces, points_per_cycle, trace_outputs, check_assembly, raw_traces)
                errors: Dict[int, str] = {}
                # The core only reads them (no copy), unless on_job may change them.
                descriptions = [j.mechanism.description() if on_job is not None else j.mechanism._description() for j in jobs]
                if on_job is not None:
                    for job, d in zip(jobs, descriptions):
                        on_job(job.k, d, job.settings)
                nominal = self._nominal_run()[0] if self.reference == "nominal" else None
                raws = run_jobs([j.k for j in jobs], descriptions, [j.settings for j in jobs], executor=self.executor, chunk_size=self.chunk_size, nominal=nominal,
                                threads=self.threads, show=bool(shown), on_done=bar.update, store=store, timeout=timeout, finished_before=start)  # fmt: skip
                for job, raw in zip(jobs, raws):
                    k = job.k
                    if failed(raw):
                        errors[k] = str(error_of(raw))
                        continue
                    if on_raw is not None:
                        on_raw(k, raw)
                    mons = raw["monitors"]
                    for i, (o, lim, c) in enumerate(zip(self.outputs, self.limits, job.clearances)):
                        mon = mons[i]
                        if o.quantity == "film_thickness":
                            values[k, i] = c * (1.0 - float(mon["peak"]))
                        elif lim.side == "below":
                            values[k, i] = float(np.min(mon["bin_min"]))
                        else:
                            values[k, i] = float(mon["peak"])
                        first[k, i] = float(mon["first_passage"])
                        spec = job.settings["monitors"][i]
                        t_start = spec["t_start"]
                        at_start[k, i] = lim.side == "above" and at_window_start(float(mon["t_peak"]), t_start, spec["bin_width"] * spec["bins"], mon["bin_max"], mon["bin_min"])
                    if monitors is not None:
                        monitors[k] = mons
                    if k < keep_traces:
                        trace = self._trace(job, raw, raw_traces)
                        traces.append(trace if on_trace is None else on_trace(k, trace))
                failures += sorted(errors.items())
                self.n_runs += stop - start
        finally:
            bar.close()
        ev = Evaluation(values, first, sorted(failures), monitors)
        if not getattr(self, "_warned_start", False):
            self._warned_start = warn_at_start(at_start, ~ev.failed, values, [o.label for o in self.outputs], [o.unit for o in self.outputs], self.skip_cycles, t_start)
        return ev, traces

    def _trace(self, job: _Job, raw: Dict[str, Any], raw_traces: bool) -> Any:
        if not raw_traces:
            return job.mechanism._finish(raw, job.settings)
        m = job.mechanism
        columns = [o.target(m.body_names, m.clearance_joint_names).get("coordinate") for o in self.outputs]
        ideal = (raw.get("reference") or {}).get(self.reference)
        if ideal is not None:
            ideal = {"t": raw["t"], **ideal}
        return {"sample": raw, "ideal": ideal, "columns": columns}

    def _chunk_jobs(
        self, points: Mapping[str, np.ndarray], start: int, stop: int, keep: int, points_per_cycle: int, trace_outputs: Optional[Sequence[str]],
        check_assembly: bool, record: bool = False,
    ) -> List[_Job]:  # fmt: skip
        """Build the chunk's mechanisms and run settings with each run's monitors, naming the
        reference they are measured against and its grid (the core makes the reference runs;
        ``record``: the traced runs also return the reference at their output times)."""
        jobs: List[_Job] = []
        need_reference = any(o.body is not None for o in self.outputs)
        # Run settings by window and grid: they do not depend on the mechanism but for its film
        # monitors, which the study's own replace (one run_settings call a window, not a sample).
        made: Dict[Tuple[float, float, float, bool], Dict[str, Any]] = {}
        for k in range(start, stop):
            params = {name: float(v[k]) for name, v in points.items()}
            m = self.built(params)
            t0, t1, period = self._window(params)
            if check_assembly:
                self._check_first_assembly(m, t0)  # the pose at t = 0, then the drivers followed to the window's start
            if need_reference and self.reference == "nominal":
                self._check_bodies(m)
            tracing = k < keep
            key = (t0, t1, period, tracing)
            if key not in made:
                grid = output_grid(t0, t1, period, points_per_cycle) if tracing else np.array([t0, t1])
                outputs = (list(trace_outputs) if trace_outputs is not None else None) if tracing else ["states"]
                made[key] = m.run_settings(float(grid[-1]), t_out=grid, outputs=outputs, **self.run_options)
            s = dict(made[key])
            contacts = m.contacts() if any(o.quantity == "film_thickness" for o in self.outputs) else {}
            clearances = [float(contacts[o.joint]["clearance"]) if o.quantity == "film_thickness" and o.joint in contacts else 0.0 for o in self.outputs]
            if need_reference:
                s["reference"] = reference_grid(t0, t1, period, points_per_cycle if tracing else None, record=tracing and record)
            s["monitors"] = self._monitors(m, t0, period, clearances)
            jobs.append(_Job(k, m, s, clearances))
        return jobs

    def evaluate(self, points: Mapping[str, Any], *, keep_traces: int = 0, what: str = "runs") -> Tuple[Evaluation, List[Any]]:
        """Run the model at ``points`` (``{input name: (N,) array}``; missing inputs at their
        mean), keeping each run's extremes and first-passage times (and the full result of the
        first ``keep_traces`` runs). See :meth:`run_samples`."""
        return self.run_samples(points, keep_traces=keep_traces, what=what)

    def limit_states(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        """Each output's ``g_i(u)`` at standard normal points ``u`` (N × d): ``(N, outputs)``.
        A run that fails gives ``g = −1`` in every mode (a failure) or raises
        (``on_failure="raise"``)."""
        ev, _ = self.run_samples(self.values(u), what="limit state")
        _check_failures(ev, on_failure)
        g = np.column_stack([lim.g(ev.values[:, i]) for i, lim in enumerate(self.limits)])
        g[ev.failed, :] = -1.0
        return g

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        """``g(u) = min_i g_i(u)`` (one output: ``1 − peak / limit``); failure when ``g ≤ 0``."""
        return np.min(self.limit_states(u, on_failure), axis=1)

    # ------------------------------------------------------------------ methods
    def monte_carlo(
        self, n: int, seed: Optional[int] = 0, executor: Any = None, on_failure: str = "fail", *, keep_traces: int = 0, confidence: float = 0.95,
        checkpoint: Any = None, timeout: Optional[float] = None,
    ) -> MonteCarloEstimate:  # fmt: skip
        """Crude Monte Carlo with ``n`` samples (memory: a few numbers per sample; the full
        results of the first ``keep_traces`` samples on request). Each input has its own random
        stream seeded by ``(seed, name)``. ``on_failure``: ``"fail"`` (default: a failed run
        counts as an exceedance), ``"exclude"`` (left out; ``bounds`` brackets p_f) or
        ``"raise"``. A series system's p_f and each output's (``modes``) come from the same runs.

        ``checkpoint``: a directory where finished chunks of samples are saved; the same call
        resumes from it, running only the samples missing (bit for bit the uninterrupted answer).
        Runs lost to an ``executor``'s machinery (a dead worker, a broken pool) or a cluster that
        finishes no chunk for ``timeout`` seconds (default :data:`clearsim.batch.TIMEOUT`, 1 800 s)
        raise :class:`clearsim.ClusterError` naming the chunks lost and what finished, after
        every other chunk has finished; samples whose own run fails are counted as usual."""
        check_on_failure(on_failure)
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
        start = time.perf_counter()
        saved, self.executor = self.executor, executor if executor is not None else self.executor
        try:
            u = np.column_stack([input_stream(seed, name).standard_normal(int(n)) for name in self.random_names]) if self.random_names else np.zeros((int(n), 0))
            inputs = self.values(u)
            runs0 = self.n_runs
            ev, traces = self.run_samples(inputs, keep_traces=keep_traces, what="Monte Carlo samples", checkpoint=checkpoint, timeout=timeout)
        finally:
            self.executor = saved
        _check_failures(ev, on_failure)
        ok = ~ev.failed
        exceed_by_mode = np.column_stack([lim.exceeded(ev.values[:, i]) & ok for i, lim in enumerate(self.limits)])
        n_fail = len(ev.failures)
        n_eff = int(n) if on_failure == "fail" else int(n) - n_fail
        if n_eff < 1:
            raise SimulationError(f"no Monte Carlo sample completed ({n_fail} failed); first failure: {ev.failures[0][1]}", reason=ev.failures[0][1])
        add = n_fail if on_failure == "fail" else 0

        def estimate(k_out: int) -> Tuple[float, Tuple[float, float]]:
            lo, hi = wilson_interval(k_out + add, n_eff, confidence)
            return (k_out + add) / n_eff, (float(lo), float(hi))

        k_sys = int(exceed_by_mode.any(axis=1).sum())
        pf, interval = estimate(k_sys)
        modes = [ModeEstimate(name, *estimate(int(exceed_by_mode[:, i].sum())), int(exceed_by_mode[:, i].sum())) for i, name in enumerate(self.mode_names)]
        cov = math.sqrt((1.0 - pf) / (pf * n_eff)) if pf > 0 else math.inf
        return MonteCarloEstimate(
            pf=pf, interval=interval, cov=cov, n_runs=self.n_runs - runs0, failures=ev.failures,
            peaks=ev.peaks, first_passage_times=ev.first_passage_times, inputs=inputs, on_failure=on_failure,
            bounds=(k_sys / int(n), (k_sys + n_fail) / int(n)), wall_time=time.perf_counter() - start, traces=traces, modes=modes,
        )  # fmt: skip

    def fosm(self, bin_width: Optional[float] = None, output: int = 0, allowable: Optional[Tuple[float, float]] = None) -> FosmResult:
        """The paper's per-bin FOSM (Eqs. P27–P32) of the nominal mechanism (every input at its
        mean) for output number ``output``: per crank-angle bin, the time-averaged mean and
        standard deviation of |error| over the analysed cycles, integrated at every step (not
        from stored samples), against the allowable range ``allowable = (Δv, Δu)`` in the
        output's unit (default ``(0, limit)``): μ_S = (Δu + Δv)/2, σ_S = (Δu − Δv)/6 (P31–P32).
        Crank angles are |ω| t [deg] modulo 360° with t from t = 0 (the given pose's time), whatever
        the runs' start ``t0`` or ``skip_cycles`` (docs/physics.md §6).
        Several outputs from one run: :meth:`fosm_all`."""
        return self.fosm_all(bin_width, [output], [allowable])[0]

    def fosm_all(
        self, bin_width: Optional[float] = None, outputs: Optional[Sequence[int]] = None, allowable: Optional[Sequence[Optional[Tuple[float, float]]]] = None
    ) -> List[FosmResult]:  # fmt: skip
        """:meth:`fosm` of several outputs (``outputs``: their numbers, default every output FOSM
        applies to: one with an upper limit, not a film thickness) from one monitored run of the
        nominal mechanism, each output against its own allowable range (``allowable[i]`` for
        ``outputs[i]``: ``(Δv, Δu)`` in its unit, ``None`` for ``(0, limit)``). The monitors do not steer the integrator, so each result is bit for bit
        the one :meth:`fosm` gives for that output alone."""
        width = check_positive("bin_width", bin_width) if bin_width is not None else self.bin_width
        fits = [i for i, (o, lim) in enumerate(zip(self.outputs, self.limits)) if lim.side == "above" and o.quantity != "film_thickness"]
        chosen = (fits or [0]) if outputs is None else list(outputs)  # none fits: output 0's error below says why
        ranges: List[Optional[Tuple[float, float]]] = [None] * len(chosen) if allowable is None else list(allowable)
        if not chosen:
            raise InputError(f"invalid outputs = {outputs!r}: give the number of at least one output", field="outputs", value=outputs)
        if len(ranges) != len(chosen):
            raise InputError(f"invalid allowable: {len(ranges)} ranges for {len(chosen)} outputs (one each, None for (0, limit))", field="allowable", value=allowable)
        statistics = []
        for output, pair in zip(chosen, ranges):
            if not (isinstance(output, int) and 0 <= output < len(self.outputs)):
                raise InputError(f"invalid output = {output!r}: the index of one of {len(self.outputs)} outputs", field="output", value=output)
            if self.limits[output].side != "above" or self.outputs[output].quantity == "film_thickness":
                raise InputError(f"invalid output = {output}: FOSM compares an error with an allowable range [0, limit]; {self.outputs[output].label} has a lower limit", field="output", value=output)
            lower, upper = (0.0, self.limits[output].value) if pair is None else pair
            statistics.append(allowable_statistics(lower, upper))
        saved = (self.bin_width, self.outputs, self.limits)
        self.bin_width, self.outputs, self.limits = width, [self.outputs[i] for i in chosen], [self.limits[i] for i in chosen]
        try:
            ev, _ = self.run_samples({}, keep_monitors=True, what="FOSM")
        finally:
            self.bin_width, self.outputs, self.limits = saved
        if ev.failures:
            reason = ev.failures[0][1]
            raise SimulationError(f"FOSM: the nominal mechanism failed: {reason}", reason=reason)
        assert ev.monitors is not None
        per_cycle = int(math.ceil(360.0 / width - 1e-9))
        monitors = ev.monitors[0]
        # Each time bin's crank-angle bin: |ω| t from t = 0, the window opening on a bin edge (§6).
        fold = bin_fold(window_start_turns(self.skip_cycles, width), width, len(monitors[0]["bin_time"]))
        starts = np.arange(per_cycle) * width
        centres = np.minimum(starts + 0.5 * width, 0.5 * (starts + np.minimum(starts + width, 360.0)))
        return [fosm_from_monitors([mon], fold, starts, centres, np.zeros(per_cycle, dtype=int), mu_S, sigma_S, width) for mon, (mu_S, sigma_S) in zip(monitors, statistics)]

    # ------------------------------------------------------------------ methods of other rooms
    # Reliability over life (life.py) and active-learning surrogates (akmcs.py) add their
    # methods here, each a thin call into its own module (as ReliabilityModel's methods call form.py etc.).
    def life(
        self, cycles: Sequence[float], n: int, seed: Optional[int] = 0, *, max_growth: Optional[float] = 0.02, max_jump: Optional[float] = None,
        settle: Optional[float] = None, on_failure: str = "fail", confidence: float = 0.95, max_blocks: int = 1000,
    ) -> Any:  # fmt: skip
        """p_f against operating cycles with Archard wear fed back (each worn joint needs
        ``Archard(..., feedback=True)``): ``n`` samples each run through its life in blocks of
        ``settle`` + ``cycles`` turns, the worn depths extrapolated between blocks (cycle
        jumping, at most ``max_growth`` × the clearance of growth and ``max_jump`` cycles a
        jump; at most ``max_blocks`` blocks a sample, an estimate above it after the first round is
        an InputError saying why). Returns a :class:`~clearsim.reliability.life.LifeResult` (its
        ``life_at(R)``: the cycles at which the reliability falls to R). See docs/reliability.md,
        "Reliability over life"."""
        from .life import study_life

        return study_life(self, cycles, n, seed, max_growth=max_growth, max_jump=max_jump, settle=settle, on_failure=on_failure, confidence=confidence, max_blocks=max_blocks)

    def life_model(self, cycles: float, *, max_growth: Optional[float] = 0.02, max_jump: Optional[float] = None, settle: Optional[float] = None) -> Any:
        """The limit state "failure by ``cycles`` operating cycles" as a model of its own, each
        evaluation one life in blocks (:class:`~clearsim.reliability.life.LifeModel`): its
        ``ak_mcs``, ``form`` or ``importance_sampling`` answer p_f at that life in fewer lives
        than :meth:`life`'s Monte Carlo."""
        from .life import LifeModel

        return LifeModel(self, cycles, max_growth=max_growth, max_jump=max_jump, settle=settle)


def _check_failures(ev: Evaluation, on_failure: str) -> None:
    check_on_failure(on_failure)
    if ev.failures and on_failure == "raise":
        k, reason = ev.failures[0]
        raise SimulationError(f"run {k} of {ev.values.shape[0]} failed: {reason}; {len(ev.failures)} failed in all", reason=reason)
