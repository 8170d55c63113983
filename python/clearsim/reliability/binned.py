"""Monte Carlo dynamic-accuracy reliability of one body coordinate's errors per crank-angle bin,
with stored error traces (``clearsim.monte_carlo``; docs/physics.md §6, beyond the paper).

A thin layer over :class:`clearsim.reliability.Study`: the samples run through the study's one
sample loop (:meth:`Study.run_samples`: in parallel inside the Rust core with the GIL released,
or through any ``concurrent.futures``-style executor), each quantity an output of the study; this
module turns the runs' monitors and stored traces into per-bin reliability and the first-passage
probability with confidence intervals, next to FOSM (:func:`clearsim.reliability.fosm.fosm_from_monitors`).
For p_f alone, ``Study.monte_carlo`` is the lighter call.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from .. import display
from ..errors import InputError, SimulationError, check_choice, check_positive
from ..mechanism import Mechanism
from ..plausibility import output_point_findings, warn_new
from ..points import check_point, raw_point_error
from ..schema import ATOL, BODY_QUANTITY_UNITS, COMPONENTS, POINT_MONITOR_COMPONENTS, RTOL
from .bridge import check_on_failure
from .distributions import Distribution, sample_inputs
from .estimates import Estimate, MonteCarloBins, compare_fosm_mc, failure_reasons, wilson_interval
from .fosm import BIN_WIDTH, allowable_statistics, bin_fold, crank_angle_at, fosm_from_monitors, window_start_turns
from .runs import output_grid
from .outputs import Limit, Output
from .study import Study

QUANTITIES = {"displacement": "q", "velocity": "qd", "acceleration": "qdd"}
#: Units of an error, per quantity and component (x, y: translation; theta: rotation).
UNITS = {(q, theta): units[int(theta)] for q, units in BODY_QUANTITY_UNITS.items() for theta in (False, True)}


@dataclass
class MonteCarloResult:
    """Outcome of :func:`monte_carlo`.

    Attributes
    ----------
    inputs:
        The sampled inputs, ``{name: (n,) array}`` (failed samples included).
    ok:
        Boolean mask of the samples whose clearance and ideal runs both completed.
    failures:
        ``(sample index, reason)`` of every sample that did not complete (simulation error,
        step or wall-time budget used up); none is dropped silently.
    on_failure:
        How failed samples entered the estimates: ``"fail"`` (each counts as leaving the
        allowable range, in every bin and in the first-passage probability) or ``"exclude"``
        (estimates over the completed samples; ``pf_bounds`` bounds them both ways).
    pf_bounds:
        ``{quantity: (low, high)}`` first-passage probability if every failed sample had stayed
        within / left the range: the honest range of the answer when failures are excluded (with
        ``"fail"`` the estimate is the high end).
    crank_angle:
        (kept, n_times) crank angle [deg] of each stored output sample of the samples whose
        errors were kept (``error_samples``): |ω| t with t from t = 0, unwrapped (the bins take it
        modulo 360°; docs/physics.md §6).
    errors:
        ``{quantity: (kept, n_times) array}`` of signed errors (clearance − ideal response) on
        the stored grid, of the samples ``keep_errors`` asked for (empty by default).
    error_samples:
        The sample number of each row of ``errors`` and ``crank_angle`` (completed samples among
        those kept).
    bins:
        ``{quantity: MonteCarloBins}``: per-bin Monte Carlo reliability with Wilson intervals,
        and FOSM from the pooled samples (``bins[q].fosm``).
    first_passage:
        ``{quantity: Estimate}``: probability that |error| leaves the allowable range anywhere
        in the analysed cycles.
    allowable:
        ``{quantity: (lower, upper)}``.
    peaks, first_passage_times:
        ``{quantity: (n_ok,) array}``: each completed sample's largest |error| over the analysed
        window and the first time [s] it exceeded the upper limit (NaN: never), tracked by the
        integrator at every step (not from the stored grid).

    ``first_passage``, the per-bin Monte Carlo reliability ``bins[q].reliability`` and the
    pooled FOSM ``bins[q].fosm`` (time-averaged moments of |error| per bin) come from the same
    step-by-step tracking, so they do not depend on ``points_per_cycle``; only the ``errors``
    traces are on the stored output grid.
    """

    inputs: Dict[str, np.ndarray]
    ok: np.ndarray
    failures: List[Tuple[int, str]]
    crank_angle: np.ndarray
    errors: Dict[str, np.ndarray]
    bins: Dict[str, MonteCarloBins]
    first_passage: Dict[str, Estimate]
    allowable: Dict[str, Tuple[float, float]]
    on_failure: str = "fail"
    pf_bounds: Dict[str, Tuple[float, float]] = field(default_factory=dict)
    peaks: Dict[str, np.ndarray] = field(default_factory=dict)
    first_passage_times: Dict[str, np.ndarray] = field(default_factory=dict)
    wall_time: float = 0.0
    extra: Dict[str, Any] = field(default_factory=dict)
    error_samples: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    def _display_rows(self) -> List[Tuple[str, Any]]:
        rows: List[Tuple[str, Any]] = [("samples", int(self.ok.size)), ("completed", int(self.ok.sum())), ("failures", self.n_failed), ("on_failure", self.on_failure)]
        rows += [(f"p_f {q}", f"{est.p:.4g} [{est.lo:.4g}, {est.hi:.4g}]") for q, est in self.first_passage.items()]
        return rows + [("allowable", self.allowable), ("errors", self.errors), ("wall_time", self.wall_time)]

    def __repr__(self) -> str:
        return display.line("MonteCarloResult", self._display_rows())

    def _repr_html_(self) -> str:
        return display.table("MonteCarloResult", self._display_rows())

    @property
    def n_failed(self) -> int:
        """Number of samples that did not complete."""
        return len(self.failures)

    def failure_reasons(self) -> Dict[str, int]:
        """How many samples failed for each kind of reason (the message up to ' at t =')."""
        return failure_reasons(self.failures)

    def table(self, quantity: str) -> List[Dict[str, Any]]:
        """Per-bin rows: Monte Carlo reliability with its interval next to FOSM."""
        return compare_fosm_mc(self.bins[quantity])

    def summary(self) -> Dict[str, Any]:
        out: Dict[str, Any] = {
            "samples": int(self.ok.size), "completed": int(self.ok.sum()), "failed": self.n_failed,
            "failure_reasons": self.failure_reasons(), "on_failure": self.on_failure, "wall_time": self.wall_time,
        }  # fmt: skip
        for q, b in self.bins.items():
            k = int(np.nanargmin(b.reliability))
            fp = self.first_passage[q]
            out[q] = {
                "first_passage_probability": fp.p,
                "first_passage_interval": (fp.lo, fp.hi),
                "first_passage_bounds": self.pf_bounds.get(q),
                "min_bin_reliability_mc": float(b.reliability[k]),
                "min_bin_interval": (float(b.lo[k]), float(b.hi[k])),
                "min_bin_angle_deg": float(b.bin_starts[k]),
                "min_bin_reliability_fosm": float(np.nanmin(b.fosm.reliability)),
            }
        return out


def monte_carlo(
    build: Callable[..., Mechanism],
    distributions: Mapping[str, Union[Distribution, float]],
    n: int,
    *,
    omega: Union[str, float, None] = None,
    cycles: float = 1.0,
    skip_cycles: float = 0.0,
    body: Optional[str] = None,
    component: Optional[str] = None,
    point: Optional[Sequence[float]] = None,
    allowable: Optional[Mapping[str, Tuple[float, float]]] = None,
    quantities: Optional[Sequence[str]] = None,
    on_failure: str = "fail",
    max_steps: Optional[int] = None,
    max_seconds: Optional[float] = None,
    bin_width: float = BIN_WIDTH,
    points_per_cycle: int = 360,
    seed: Optional[int] = 0,
    confidence: float = 0.95,
    executor: Any = None,
    chunk_size: Optional[int] = None,
    progress: bool = True,
    integrator: str = "auto",
    rtol: float = RTOL,
    atol: float = ATOL,
    reference: str = "own_ideal",
    threads: Optional[int] = None,
    keep_errors: Union[bool, int] = False,
    checkpoint: Any = None,
    timeout: Optional[float] = None,
) -> MonteCarloResult:
    """Monte Carlo reliability of one output of a mechanism with random inputs.

    Parameters
    ----------
    build:
        ``build(**inputs) -> Mechanism`` for one sample, e.g.
        ``lambda clearance, omega: clearsim.models.nine_bar("dry", clearance, omega)``.
    distributions:
        ``{input name: Distribution or number}`` (see :mod:`clearsim.reliability`).
    n:
        Number of samples.
    omega:
        The drive speed [rad/s] that defines the crank angle: the name of a sampled input, or a
        number; by default the input named ``omega`` if there is one, else the nominal
        mechanism's constant-speed driver's (as :class:`~clearsim.reliability.Study`). Each sample runs ``skip_cycles + cycles`` crank turns; the first ``skip_cycles``
        (start-up transient) are not analysed; the window opens at the first bin edge of the
        crank angle |ω| t at or after them, and bins are crank angles |ω| t modulo 360° with t
        from t = 0, as :meth:`Study.fosm <clearsim.reliability.Study.fosm>`'s.
    body, component, point:
        The output analysed (required, no default): a body's ``x``, ``y`` or ``theta``
        error against the reference; with ``point=(x, y)`` (body frame [m], as
        ``Output(body=, point=, component=)``) that point's on the body, component ``x``, ``y``
        or ``magnitude`` (|P − P_ref|).
    reference:
        What the errors are measured against: ``"own_ideal"`` (default: each sample's own
        mechanism with ideal joints, what the clearances add) or ``"nominal"`` (the nominal
        design's ideal motion, every tolerance included), as :class:`~clearsim.reliability.Study`.
    allowable:
        Required: ``{quantity: (lower, upper)}`` allowable |error| range of each analysed
        quantity (``"displacement"``, ``"velocity"``, ``"acceleration"``) in that quantity's unit:
        m, m/s, m/s² for ``x``/``y``; rad, rad/s, rad/s² for ``theta``. The paper's slider
        limits are :data:`clearsim.reliability.PAPER_ALLOWABLE`, to be passed explicitly.
    quantities:
        The quantities analysed (default: those given in ``allowable``; each needs its limit).
    on_failure:
        A sample whose run fails (simulation error, ``max_steps`` or ``max_seconds`` used up) is
        kept with its reason in ``.failures`` and ``"fail"`` (default) counts it as leaving the
        allowable range; ``"exclude"`` estimates from the completed samples and reports
        ``.pf_bounds``; ``"raise"`` raises :class:`clearsim.SimulationError` naming the sample.
    max_steps, max_seconds:
        Budget of each run (steps; wall time [s]): a sample that stalls fails with its reason
        instead of holding up the batch.
    executor:
        ``None`` runs the batch in the Rust core on all local cores. Otherwise any object with a
        ``concurrent.futures``-style ``map`` (``ProcessPoolExecutor``, Dask's
        ``client.get_executor()``): chunks of samples are sent to :func:`run_descriptions`
        (descriptions and settings only: each worker runs the references itself).
    threads:
        The core's threads per batch: default all local cores in this process, one per task
        under an ``executor``; 0: all the machine's cores.
    integrator, rtol, atol:
        As in :meth:`Mechanism.simulate`; ``"auto"`` (default) runs lubricated samples with
        RADAU5 and their ideal counterparts and dry samples with RK45.
    keep_errors:
        Store the error traces (``errors``, ``crank_angle``) on ``points_per_cycle`` points a
        cycle: ``True`` for every sample, a number for the first that many samples, ``False``
        (default) for none. Every estimate comes from the integrator's monitors whatever is
        kept; a kept sample costs 8 bytes a stored point and quantity (a full run, ~213 KB on
        the nine-bar, is dropped as its chunk ends), so memory stays bounded at any ``n``.
    checkpoint, timeout:
        A directory where finished chunks are saved and the same call resumes from; seconds a
        cluster may finish nothing before a :class:`clearsim.ClusterError` (as
        :meth:`Study.monte_carlo <clearsim.reliability.Study.monte_carlo>`).
    """
    start = time.perf_counter()
    n = int(n)
    if n < 1:
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    if body is None:
        raise InputError("missing body: name the body whose error is analysed (there is no default)", field="body", value=None)
    if point is None:
        check_choice("component", component, COMPONENTS, "(there is no default)")
    else:
        check_choice("component", component, POINT_MONITOR_COMPONENTS, "(a point's: there is no default)")
        point = check_point(point, "point")
    check_on_failure(on_failure)
    if not allowable:
        raise InputError(
            "missing allowable: give {quantity: (lower, upper)} for each analysed quantity, in its unit "
            "(m, m/s, m/s² for x and y; rad, rad/s, rad/s² for theta); there is no default",
            field="allowable", value=allowable,
        )  # fmt: skip
    quantities = list(allowable) if quantities is None else list(quantities)
    for q in quantities:
        check_choice("quantities", q, list(QUANTITIES))
        if q not in allowable:
            unit = UNITS[(q, component == "theta")]
            raise InputError(f"missing allowable[{q!r}]: the limit of the {component} {q} error [{unit}] is required", field=f"allowable.{q}", value=None)
    cycles = check_positive("cycles", cycles)
    if skip_cycles < 0:
        raise InputError(f"invalid skip_cycles = {skip_cycles!r}: must not be negative", field="skip_cycles", value=skip_cycles)
    limits: Dict[str, Tuple[float, float]] = {}
    for q in quantities:
        pair = allowable[q]
        try:
            lo, hi = (float(v) for v in pair)
        except (TypeError, ValueError):
            lo = hi = math.nan
        if not lo < hi:
            unit = UNITS[(q, component == "theta")]
            raise InputError(f"invalid allowable[{q!r}] = {pair!r}: give (lower, upper) with lower < upper [{unit}]", field=f"allowable.{q}", value=pair)
        limits[q] = (lo, hi)
    inputs = sample_inputs(distributions, n, seed)
    if omega is None and "omega" in inputs:  # the old default: the input named omega
        omega = "omega"
    if isinstance(omega, str) and omega not in inputs:
        raise InputError(f"invalid omega = {omega!r}: not a sampled input; give the drive speed [rad/s]", field="omega", value=omega)
    budget: Dict[str, Any] = {}
    if max_steps is not None:
        budget["max_steps"] = max_steps
    if max_seconds is not None:
        budget["max_seconds"] = max_seconds
    study = Study(
        build, distributions, [Output(body=body, component=component, quantity=q, point=point) for q in quantities], [Limit.above(limits[q][1]) for q in quantities],
        omega=omega, cycles=cycles, skip_cycles=skip_cycles, bin_width=bin_width, integrator=integrator, rtol=rtol, atol=atol,
        reference=reference, executor=executor, threads=threads, chunk_size=chunk_size, progress=progress, **budget,
    )  # fmt: skip
    omega = study.omega if omega is None else omega  # None: the nominal constant-speed driver's
    omegas = np.asarray(inputs[omega], dtype=float) if isinstance(omega, str) else np.full(n, float(omega))
    if np.any(omegas == 0) or not np.all(np.isfinite(omegas)):
        raise InputError("invalid omega: the drive speed must be finite and non-zero", field="omega", value=omega)
    keep = _kept(keep_errors, n)
    outputs = ["states", "accelerations"] if "acceleration" in quantities else ["states"]

    # A point's body, by its index in the mechanism (for the kept error traces).
    if point is not None:  # in mm or in the global frame: a PlausibilityWarning
        warn_new(output_point_findings(study._nominal_run()[0], str(body), point, "point"), set())
    names = study._nominal_run()[1] if point is not None and keep else []
    on_body = names.index(body) if body in names else 0  # an unknown body: the study's InputError

    def errors_of(k: int, trace: Dict[str, Any]) -> Tuple[int, np.ndarray, List[np.ndarray]]:
        """A kept sample's error rows and crank angles (its full run is not kept)."""
        actual, ideal = trace["sample"], trace["ideal"]
        col = trace["columns"][0]
        if point is not None:
            return k, crank_angle_at(actual["t"], omegas[k]), [raw_point_error(actual, ideal, on_body, point, q, str(component)) for q in quantities]
        return k, crank_angle_at(actual["t"], omegas[k]), [actual[QUANTITIES[q]][:, col] - ideal[QUANTITIES[q]][:, col] for q in quantities]

    ev, traces = study.run_samples(
        inputs, keep_traces=keep, points_per_cycle=points_per_cycle, trace_outputs=outputs, raw_traces=True, keep_monitors=True,
        check_assembly=False, what="Monte Carlo samples", show=progress, on_trace=errors_of, checkpoint=checkpoint, timeout=timeout,
    )  # fmt: skip
    assert ev.monitors is not None
    failed_at = dict(ev.failures)
    failures = [(k, _failure_reason(reason)) for k, reason in ev.failures]
    ok = np.array([k not in failed_at for k in range(n)], dtype=bool)
    monitored: Dict[str, List[Dict[str, Any]]] = {q: [ev.monitors[k][i] for k in range(n) if ok[k]] for i, q in enumerate(quantities)}
    if failures and on_failure == "raise":
        k, reason = failures[0]
        sample_text = ", ".join(f"{name}={float(v[k]):.6g}" for name, v in inputs.items())
        raise SimulationError(f"Monte Carlo sample {k} ({sample_text}) failed: {reason}; {len(failures)} of {n} samples failed", reason=reason)
    if not ok.any():
        raise SimulationError(f"no Monte Carlo sample completed ({n} failed); first failure: {failures[0][1]}", reason=failures[0][1])
    n_failed = len(failures) if on_failure == "fail" else 0
    n_times = output_grid(0.0, cycles, 1.0, points_per_cycle).size
    crank = np.array([angle for _, angle, _ in traces]).reshape(-1, n_times)
    errors = {q: np.array([rows[i] for _, _, rows in traces]).reshape(-1, n_times) for i, q in enumerate(quantities)}
    bins = {}
    passage = {}
    bounds: Dict[str, Tuple[float, float]] = {}
    peaks: Dict[str, np.ndarray] = {}
    first_times: Dict[str, np.ndarray] = {}
    for q in quantities:
        lo, hi = limits[q]
        # Exceedances from the integrator's every step (the monitor), not from the stored grid.
        exceed_bins = np.array([(mon["bin_max"] > hi) | (mon["bin_min"] < lo) for mon in monitored[q]])
        bins[q] = _monitor_bins(exceed_bins, monitored[q], window_start_turns(skip_cycles, bin_width), bin_width, n_failed, confidence, lo, hi)
        exceed = exceed_bins.any(axis=1)
        k_out = int(exceed.sum())
        n_all = int(exceed.size) + n_failed
        p_lo, p_hi = wilson_interval(k_out + n_failed, n_all, confidence)
        passage[q] = Estimate((k_out + n_failed) / n_all, float(p_lo), float(p_hi))
        bins[q].overall = Estimate(1.0 - passage[q].p, 1.0 - passage[q].hi, 1.0 - passage[q].lo)
        bounds[q] = (k_out / n, (k_out + len(failures)) / n)
        peaks[q] = np.array([mon["peak"] for mon in monitored[q]])
        first_times[q] = np.array([mon["first_passage"] for mon in monitored[q]])
    return MonteCarloResult(
        inputs=inputs,
        ok=ok,
        failures=failures,
        crank_angle=crank,
        errors=errors,
        bins=bins,
        first_passage=passage,
        allowable={q: limits[q] for q in quantities},
        on_failure=on_failure,
        pf_bounds=bounds,
        peaks=peaks,
        first_passage_times=first_times,
        wall_time=time.perf_counter() - start,
        error_samples=np.array([k for k, _, _ in traces], dtype=int),
    )


def _failure_reason(reason: str) -> str:
    """A failed sample's reason, saying which run failed: the sample or its reference."""
    if reason.endswith("(nominal ideal mechanism)"):
        return reason
    if reason.endswith("(ideal mechanism)"):
        return reason[: -len("(ideal mechanism)")] + "(ideal twin of the sample)"
    return f"{reason} (sample)"


def _kept(keep_errors: Union[bool, int], n: int) -> int:
    """How many samples' error traces are kept (``keep_errors``: a bool or a count)."""
    if isinstance(keep_errors, (bool, np.bool_)):
        return n if keep_errors else 0
    if not isinstance(keep_errors, (int, np.integer)) or keep_errors < 0:
        raise InputError(f"invalid keep_errors = {keep_errors!r}: True (every sample), False (none) or a number of samples", field="keep_errors", value=keep_errors)
    return min(int(keep_errors), n)


def _monitor_bins(
    exceed_bins: np.ndarray, monitored: List[Dict[str, Any]], start_turns: float, bin_width: float, failed: int, confidence: float, lower: float, upper: float
) -> MonteCarloBins:  # fmt: skip
    """Per crank-angle bin (edges at k·bin_width, cycles folded modulo 360°), from the
    monitor's time bins of a window opening at ``start_turns`` crank turns: the fraction of samples whose |error| stays in range over the whole
    bin, and FOSM (P27–P32) from the time-averaged mean and standard deviation of |error| over
    the completed samples and the analysed cycles (μ_s = Σ∫|e|dt / Σ∫dt, σ_s² = Σ∫e²dt / Σ∫dt −
    μ_s²), so neither depends on the stored output grid."""
    n_s, n_time_bins = exceed_bins.shape
    per_cycle = int(math.ceil(360.0 / bin_width - 1e-9))
    starts = np.arange(per_cycle) * bin_width
    centres = (starts + np.minimum(starts + bin_width, 360.0)) / 2.0
    cycle = np.zeros(per_cycle, dtype=np.int64)
    b = MonteCarloBins(starts, centres, cycle, np.zeros(per_cycle, dtype=int), np.full(per_cycle, np.nan), np.full(per_cycle, np.nan), np.full(per_cycle, np.nan),
                       None, Estimate(math.nan, math.nan, math.nan), lower, upper, confidence, bin_width)  # type: ignore[arg-type]  # fmt: skip
    n_bins = per_cycle
    fold = bin_fold(start_turns, bin_width, n_time_bins)
    left = np.zeros((n_s, n_bins), dtype=bool)
    for k in range(n_time_bins):
        left[:, fold[k]] |= exceed_bins[:, k]
    # Bins the analysed window never reaches (cycles < 1) hold no sample: NaN, not R = 1.
    seen = np.zeros(n_bins, dtype=bool)
    for mon in monitored:
        seen[fold[np.asarray(mon["bin_time"], dtype=float)[:n_time_bins] > 0.0]] = True
    n_in = np.where(seen, n_s + failed, 0)
    k_ok = (~left).sum(axis=0)
    b.n_samples = n_in
    b.reliability = np.full(n_bins, np.nan)
    b.lo, b.hi = np.full(n_bins, np.nan), np.full(n_bins, np.nan)
    if np.any(seen):
        b.reliability[seen] = k_ok[seen] / n_in[seen]
        lo, hi = wilson_interval(k_ok[seen], n_in[seen], confidence)
        b.lo[seen], b.hi[seen] = lo, hi
    mu_S, sigma_S = allowable_statistics(lower, upper)
    b.fosm = fosm_from_monitors(monitored, fold, starts, centres, cycle, mu_S, sigma_S, bin_width)
    return b


__all__ = ["monte_carlo", "MonteCarloResult"]
