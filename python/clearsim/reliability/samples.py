"""A study's one sample loop: each sample's mechanism built from its inputs, its run settings with
the monitors that track each output's extreme over the analysed window against the reference the
study names (the core makes the reference runs), the samples run in chunks through the batch
runner (in-process or through an executor, with checkpoints), and each run's extremes, first
passages and failures read back into an :class:`Evaluation`. :class:`~clearsim.reliability.study.Study`
is built on it; every method reaches the mechanism through :meth:`SampleLoop.run_samples`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from .. import display
from ..batch import error_of, failed, progress
from ..errors import InputError, SimulationError
from .bridge import check_on_failure
from .checkpoint import Checkpoint, run_jobs
from .fosm import window_start_turns
from .outputs import Limit, Output
from .runs import monitor_spec, output_grid, reference_grid
from .window import at_window_start, warn_at_start

__all__ = ["CHUNK", "Evaluation", "SampleLoop"]


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
class _Job:
    """One sample's run as the loop builds it: its mechanism and run settings (the monitors
    name the reference they are measured against; the core makes it)."""

    k: int
    mechanism: Any
    settings: Dict[str, Any]
    #: Each output's clearance [m] (a film thickness's; 0 for the others).
    clearances: List[float]




class SampleLoop:
    """The sample loop of a study (:class:`~clearsim.reliability.study.Study` sets its
    attributes): ``build``, the inputs, outputs and limits, the window, the run options, the
    reference and where the runs go (executor, threads, chunk size, progress)."""

    build: Callable[..., Any]
    inputs: Dict[str, Any]
    outputs: List[Output]
    limits: List[Limit]
    omega: Any
    cycles: float
    skip_cycles: float
    bin_width: float
    run_options: Dict[str, Any]
    reference: str
    executor: Any
    threads: Optional[int]
    chunk_size: Optional[int]
    progress: bool
    n_runs: int
    _nominal: Optional[Tuple[Dict[str, Any], List[str]]]
    _assembly_checked: bool
    _warned_start: bool


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
            for o in self.outputs:  # an output point in mm or in the global frame warns, once
                if getattr(o, "point", None) is not None and o.body is not None:
                    m.warn_output_point(o.body, o.point, "Output.point")
            self._assembly_checked = True

    def _nominal_run(self) -> Tuple[Dict[str, Any], List[str]]:
        """The nominal design's description (``build`` at the inputs' means: the reference of
        ``reference="nominal"``, which the core idealises and runs) and its bodies."""
        if self._nominal is None:
            m = self.built({name: d.nominal for name, d in self.inputs.items()})  # every input at its mean
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



def _check_failures(ev: Evaluation, on_failure: str) -> None:
    check_on_failure(on_failure)
    if ev.failures and on_failure == "raise":
        k, reason = ev.failures[0]
        raise SimulationError(f"run {k} of {ev.values.shape[0]} failed: {reason}; {len(ev.failures)} failed in all", reason=reason)
