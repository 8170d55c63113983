"""Monte Carlo dynamic-accuracy reliability (docs/physics.md §6, beyond the paper).

Random inputs (clearance sizes, lengths, drive speed, friction, viscosity …) are sampled, each
sample's mechanism and its ideal counterpart are simulated — in parallel inside the Rust core
with the GIL released, or through any ``concurrent.futures``-style executor (for example a Dask
cluster's ``client.get_executor()``) when the sweep outgrows one machine — and the errors of one
output are turned into per-bin reliability and the first-passage probability, with confidence
intervals, next to FOSM.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core, display
from .errors import InputError, SimulationError, check_choice, check_positive, renamed
from .mechanism import Mechanism
from .running import COMPONENTS
from .reliability import (
    Distribution,
    Estimate,
    FosmResult,
    MonteCarloBins,
    compare_fosm_mc,
    failure_reasons,
    normal_cdf,
    reliability_index,
    wilson_interval,
    mc_bin_reliability,
    sample_inputs,
)
from .reliability.model import check_on_failure

QUANTITIES = {"displacement": "q", "velocity": "qd", "acceleration": "qdd"}
#: Points per crank cycle of the ideal reference trajectory the errors are measured against.
REFERENCE_POINTS_PER_CYCLE = 7200
#: Units of an error, per quantity and component (x, y: translation; theta: rotation).
UNITS = {
    ("displacement", False): "m", ("velocity", False): "m/s", ("acceleration", False): "m/s²",
    ("displacement", True): "rad", ("velocity", True): "rad/s", ("acceleration", True): "rad/s²",
}


def run_descriptions(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]]) -> List[Any]:
    """Run descriptions with their settings in the Rust core (all local cores). A pure,
    picklable function: this is what a remote executor runs for a chunk of samples."""
    return _core.run_batch(descriptions, settings, 0)


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
        (n_ok, n_times) crank angle [deg] of each analysed output sample.
    errors:
        ``{quantity: (n_ok, n_times) array}`` of signed errors (clearance − ideal response).
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
    omega: Union[str, float] = "omega",
    cycles: float = 1.0,
    skip_cycles: float = 0.0,
    body: Optional[str] = None,
    component: Optional[str] = None,
    allowable: Optional[Mapping[str, Tuple[float, float]]] = None,
    quantities: Optional[Sequence[str]] = None,
    on_failure: str = "fail",
    max_steps: Optional[int] = None,
    max_seconds: Optional[float] = None,
    bin_width: float = 18.0,
    points_per_cycle: int = 360,
    seed: Optional[int] = 0,
    confidence: float = 0.95,
    executor: Any = None,
    chunk_size: Optional[int] = None,
    progress: bool = True,
    integrator: str = "auto",
    rtol: float = 1e-6,
    atol: float = 1e-9,
    axis: Optional[str] = None,
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
        number. Each sample runs ``skip_cycles + cycles`` crank turns; the first ``skip_cycles``
        (start-up transient) are not analysed.
    body, component:
        The output analysed (required, no default): a body's ``x``, ``y`` or ``theta``
        error against the ideal mechanism. (``axis=`` is the old name of ``component=``.)
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
        ``client.get_executor()``): chunks of samples are sent to :func:`run_descriptions`.
    integrator, rtol, atol:
        As in :meth:`Mechanism.simulate`; ``"auto"`` (default) runs lubricated samples with
        RADAU5 and their ideal counterparts and dry samples with RK45.
    """
    import time

    start = time.perf_counter()
    n = int(n)
    if n < 1:
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    if body is None:
        raise InputError("missing body: name the body whose error is analysed (there is no default)", field="body", value=None)
    component = renamed("axis", "component", axis, component)
    check_choice("component", component, COMPONENTS, "(there is no default)")
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
    if isinstance(omega, str):
        if omega not in inputs:
            raise InputError(f"invalid omega = {omega!r}: not a sampled input; give the drive speed [rad/s]", field="omega", value=omega)
        omegas = np.asarray(inputs[omega], dtype=float)
    else:
        omegas = np.full(n, float(omega))
    if np.any(omegas == 0) or not np.all(np.isfinite(omegas)):
        raise InputError("invalid omega: the drive speed must be finite and non-zero", field="omega", value=omega)

    n_out = int(round(points_per_cycle * cycles))
    # The ideal twin is smooth: it runs once per distinct ideal mechanism and window (random
    # inputs such as a clearance do not change it), on a grid fine enough to interpolate it
    # anywhere (cubic Hermite, REFERENCE_POINTS_PER_CYCLE) and containing the output grid.
    refine = max(1, math.ceil(REFERENCE_POINTS_PER_CYCLE / points_per_cycle))
    outputs = ["states", "accelerations"] if "acceleration" in quantities else ["states"]
    budget: Dict[str, Any] = {}
    if max_steps is not None:
        budget["max_steps"] = max_steps
    if max_seconds is not None:
        budget["max_seconds"] = max_seconds
    samples: List[Tuple[Mechanism, Dict[str, Any], str]] = []
    ideal_jobs: Dict[str, Tuple[Dict[str, Any], Dict[str, Any]]] = {}
    for k in range(n):
        params = {name: float(v[k]) for name, v in inputs.items()}
        m = build(**params)
        period = 2 * math.pi / abs(omegas[k])
        t0 = skip_cycles * period
        t_out = t0 + period * cycles * np.arange(n_out + 1) / n_out
        t_ref = t0 + period * cycles * np.arange(n_out * refine + 1) / (n_out * refine)
        t_ref[::refine] = t_out  # the output grid exactly, its end included
        run = dict(t_out=t_out, integrator=integrator, rtol=rtol, atol=atol, outputs=outputs, **budget)
        key, ideal_desc, ideal_settings = m.reference_job(t_ref, integrator=integrator, rtol=rtol, atol=atol, **budget)
        ideal_jobs.setdefault(key, (ideal_desc, ideal_settings))
        samples.append((m, m.run_settings(float(t_out[-1]), **run), key))
        names = m.body_names
    if body not in names:
        raise InputError(f"invalid body = {body!r}: no such body (known: {', '.join(names)})", field="body", value=body)
    b = names.index(body)
    col = 3 * b + COMPONENTS.index(component)
    keys = list(ideal_jobs)
    ideal_raws = dict(zip(keys, _run_all([ideal_jobs[k][0] for k in keys], [ideal_jobs[k][1] for k in keys], executor, chunk_size, progress, "ideal mechanisms")))

    descriptions: List[Dict[str, Any]] = []
    settings: List[Dict[str, Any]] = []
    for k, (m, s, key) in enumerate(samples):
        ideal_raw = ideal_raws[key]
        if not _failed(ideal_raw):
            period = 2 * math.pi / abs(omegas[k])
            s["monitors"] = [
                _monitor_spec(ideal_raw, col, q, limits[q], float(s["t_out"][0]), period, cycles, bin_width) for q in quantities
            ]
        descriptions.append(m.description())
        settings.append(s)
    sample_raws = _run_all(descriptions, settings, executor, chunk_size, progress, "Monte Carlo samples")
    raws: List[Any] = []
    for k, (_, _, key) in enumerate(samples):
        ideal_raw = ideal_raws[key]
        raws += [sample_raws[k], _on_grid(ideal_raw, refine) if not _failed(ideal_raw) else ideal_raw]

    ok = np.zeros(n, dtype=bool)
    failures: List[Tuple[int, str]] = []
    errs: Dict[str, List[np.ndarray]] = {q: [] for q in quantities}
    angles: List[np.ndarray] = []
    monitored: Dict[str, List[Dict[str, Any]]] = {q: [] for q in quantities}
    for k in range(n):
        actual, ideal = raws[2 * k], raws[2 * k + 1]
        bad = next((r for r in (actual, ideal) if isinstance(r, BaseException) or r.get("error") is not None), None)
        if bad is not None:
            err = bad if isinstance(bad, BaseException) else bad["error"]
            which = "sample" if bad is actual else "ideal twin of the sample"
            failures.append((k, f"{err} ({which})"))
            continue
        ok[k] = True
        for i, q in enumerate(quantities):
            channel = QUANTITIES[q]
            errs[q].append(actual[channel][:, col] - ideal[channel][:, col])
            monitored[q].append(actual["monitors"][i])
        angles.append(np.degrees(abs(omegas[k]) * (actual["t"] - actual["t"][0])))
    if failures and on_failure == "raise":
        k, reason = failures[0]
        sample_text = ", ".join(f"{name}={float(v[k]):.6g}" for name, v in inputs.items())
        raise SimulationError(f"Monte Carlo sample {k} ({sample_text}) failed: {reason}; {len(failures)} of {n} samples failed", reason=reason)
    if not ok.any():
        raise SimulationError(f"no Monte Carlo sample completed ({n} failed); first failure: {failures[0][1]}", reason=failures[0][1])
    n_failed = len(failures) if on_failure == "fail" else 0
    crank = np.array(angles)
    errors = {q: np.array(v) for q, v in errs.items()}
    bins = {}
    passage = {}
    bounds: Dict[str, Tuple[float, float]] = {}
    peaks: Dict[str, np.ndarray] = {}
    first_times: Dict[str, np.ndarray] = {}
    for q in quantities:
        lo, hi = limits[q]
        bins[q] = mc_bin_reliability(np.abs(errors[q]), crank, hi, lo, bin_width=bin_width, confidence=confidence, failed=n_failed)
        # Exceedances from the integrator's every step (the monitor), not from the stored grid.
        exceed_bins = np.array([(mon["bin_max"] > hi) | (mon["bin_min"] < lo) for mon in monitored[q]])
        _fold_into_bins(bins[q], exceed_bins, monitored[q], bin_width, n_failed, confidence)
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
    )


def _run_all(
    descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], executor: Any, chunk_size: Optional[int], progress: bool, what: str
) -> List[Any]:
    """Run in chunks (so a progress bar can move), locally in Rust or through ``executor``."""
    total = len(descriptions)
    if chunk_size is None:
        if executor is None:
            # In-core batches: large enough that the threads stay busy to the batch's end (run
            # times vary ±30 % between samples; with 3–6 runs a batch on 2 threads a quarter of
            # the time was spent waiting for the slowest), small enough for the bar to move.
            chunk_size = max(1, min(total, max(16 * (os.cpu_count() or 1), total // 20)))
        else:
            chunk_size = max(1, min(32, total // 20 or 1))  # spread over the executor's workers
    chunks = [(descriptions[i : i + chunk_size], settings[i : i + chunk_size]) for i in range(0, total, chunk_size)]
    bar = _progress(total, progress, what)
    out: List[Any] = []
    try:
        if executor is None:
            for d, s in chunks:
                out += run_descriptions(d, s)
                bar.update(len(d))
        else:
            for res in executor.map(run_descriptions, [c[0] for c in chunks], [c[1] for c in chunks]):
                out += list(res)
                bar.update(len(res))
    finally:
        bar.close()
    return out


def _failed(raw: Any) -> bool:
    return isinstance(raw, BaseException) or raw.get("error") is not None


def _on_grid(raw: Dict[str, Any], refine: int) -> Dict[str, Any]:
    """The ideal run's outputs at every ``refine``-th reference point: the samples' output grid."""
    return {key: (value[::refine] if key in ("t", "q", "qd", "qdd") else value) for key, value in raw.items()}


def _monitor_spec(ideal: Optional[Dict[str, Any]], col: int, quantity: str, limit: Tuple[float, float], t_start: float, period: float, cycles: float, bin_width: float) -> Dict[str, Any]:
    """The monitor of one quantity in time bins of ``bin_width`` degrees of crank angle: a body
    coordinate's error against the ideal run (cubic Hermite through the ideal's values and rates
    on the reference grid), or, without ``ideal``, the quantity itself (a joint's)."""
    spec: Dict[str, Any] = {
        "coordinate": col,
        "quantity": quantity,
        "t_start": t_start,
        "bin_width": period * bin_width / 360.0,
        "bins": int(math.ceil(cycles * 360.0 / bin_width - 1e-9)),
        "limit": float(limit[1]),
        # Points a step, read off the dense output (accelerations from its time derivative,
        # with one KKT solve at the worst interior point and one at the step's end): 4 a step
        # missed impact peaks by 1e-4 relative to a 3 600-point grid on the dry slider-crank, 8 do not.
        "samples_per_step": 8,
    }
    if ideal is not None:
        t = ideal["t"]
        if quantity == "displacement":
            value, rate = ideal["q"][:, col], ideal["qd"][:, col]
        elif quantity == "velocity":
            value, rate = ideal["qd"][:, col], ideal["qdd"][:, col]
        else:
            value = ideal["qdd"][:, col]
            rate = np.gradient(value, t)
        spec["reference"] = {"t": np.ascontiguousarray(t), "value": np.ascontiguousarray(value), "rate": np.ascontiguousarray(rate)}
    return spec


def _fold_into_bins(b: Any, exceed_bins: np.ndarray, monitored: List[Dict[str, Any]], bin_width: float, failed: int, confidence: float) -> None:
    """Per crank-angle bin (cycles folded modulo 360°, as ``b`` numbers its bins), from the
    monitor's time bins: the fraction of samples whose |error| stays in range over the whole
    bin, and FOSM (P27–P32) from the time-averaged mean and standard deviation of |error| over
    the completed samples and the analysed cycles (μ_s = Σ∫|e|dt / Σ∫dt, σ_s² = Σ∫e²dt / Σ∫dt −
    μ_s²), so neither depends on the stored output grid."""
    n_s, n_time_bins = exceed_bins.shape
    per_cycle = max(1, int(math.ceil(360.0 / bin_width - 1e-9)))
    starts = np.asarray(b.bin_starts, dtype=float)
    n_bins = len(starts)
    fold = np.array([k % per_cycle if n_bins == per_cycle else int(np.argmin(np.abs(starts - (k * bin_width) % 360.0))) for k in range(n_time_bins)])
    left = np.zeros((n_s, n_bins), dtype=bool)
    integral = np.zeros((3, n_bins))
    count = np.zeros(n_bins, dtype=int)
    for k in range(n_time_bins):
        left[:, fold[k]] |= exceed_bins[:, k]
    for mon in monitored:
        np.add.at(integral[0], fold, mon["bin_abs"][:n_time_bins])
        np.add.at(integral[1], fold, mon["bin_sq"][:n_time_bins])
        np.add.at(integral[2], fold, mon["bin_time"][:n_time_bins])
        np.add.at(count, fold, (mon["bin_time"][:n_time_bins] > 0).astype(int))
    n_in = np.full(n_bins, n_s + failed)
    k_ok = (~left).sum(axis=0)
    b.n_samples = n_in
    b.reliability = k_ok / n_in
    lo, hi = wilson_interval(k_ok, n_in, confidence)
    b.lo, b.hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu_s = integral[0] / integral[2]
        sigma_s = np.sqrt(np.maximum(integral[1] / integral[2] - mu_s**2, 0.0))
    old = b.fosm
    beta = reliability_index(old.mu_S, old.sigma_S, mu_s, sigma_s)
    beta = np.asarray(beta, dtype=float)
    b.fosm = FosmResult(old.bin_starts, old.bin_centres, old.cycle, count, mu_s, sigma_s, beta, np.asarray(normal_cdf(beta), dtype=float), old.mu_S, old.sigma_S, old.bin_width)


def _progress(total: int, enabled: bool, what: str) -> Any:
    from .progress import bar

    return bar(total, what, "run", enabled=enabled)


__all__ = ["monte_carlo", "MonteCarloResult", "run_descriptions"]
