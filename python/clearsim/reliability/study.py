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
:meth:`Study.run_samples`, the one sample loop (reliability/samples.py).
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
from ..batch import task_threads
from .runs import REFERENCE_POINTS_PER_CYCLE
from .samples import Evaluation, SampleLoop, _check_failures
from .. import display

__all__ = ["Output", "Limit", "Study", "Evaluation", "MonteCarloEstimate", "ModeEstimate", "FosmResult", "BODY_QUANTITIES", "JOINT_QUANTITIES", "REFERENCE_POINTS_PER_CYCLE"]


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


class Study(SampleLoop, ReliabilityModel, Modes):
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
