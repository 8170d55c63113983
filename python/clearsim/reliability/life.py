"""Reliability over operating life: p_f against the number of operating cycles, each sample's
Archard wear fed back and accumulated by cycle jumping (docs/reliability.md, "Reliability over life").

A life is simulated in **blocks**: at cycle N_k a sample runs ``settle + cycles`` crank turns
from its worn state W_k (the depths around every worn bearing and journal); the peak of the
output over the last ``cycles`` turns is the peak at N_k, and the wear of those turns gives the
per-cycle rate r_k (the settling turns' wear is a restart artefact and is left out, but for the
first block, whose start-up is the mechanism's real one). Between blocks the worn state is
extrapolated along the rate (*cycle jumping*, explicit Euler in cycles):

* first block (N_0 = 0): W_1 = W_0 + min(1, h_0/n_b) (W_end,0 − W_0) + max(0, h_0 − n_b) r_0,
  with n_b = settle + cycles the block's turns;
* then W_{k+1} = W_k + h_k r_k.

Each sample chooses its own jumps h_k: at most ``max_growth`` × the runner's depth scale (the
smallest clearance of a worn joint) of growth in its deepest-wearing bin, at most ``max_jump``
cycles, at least the analysed turns, shortened to equal jumps that land on the next requested
cycle count. All samples'
blocks of a round run as one batch.

The number of blocks is about the life's wear over ``max_growth`` × the depth scale: after the
first round :func:`life` estimates it from each sample's rate, warns (:class:`ReliabilityWarning`)
above :data:`WARN_BLOCKS` a sample and stops with an :class:`InputError` above ``max_blocks``,
both saying what sets the jumps and what to change; a sample whose wear speeds up past the
budget later is stopped there and counted as failed, with its reason (``on_failure="raise"``:
:class:`SimulationError`). A progress bar (:func:`clearsim.progress.bar`) advances per round. The algorithm only needs a :class:`BlockRunner`: tests drive
it with mocks whose life has a closed form; :class:`StudyBlocks` runs the blocks of a
:class:`~clearsim.reliability.Study` with wear fed back into the simulations.
"""

from __future__ import annotations

import copy
import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Protocol, Sequence, Tuple

import numpy as np

from ..errors import InputError, ReliabilityWarning, SimulationError, check_positive
from ..progress import bar
from .distributions import input_stream
from .estimates import wilson_interval
from .bridge import check_on_failure
from .model import ReliabilityModel
from ..lazy import lazy

stats = lazy("scipy.stats")

__all__ = ["BlockOutcome", "BlockRunner", "LifeResult", "LifeModel", "StudyBlocks", "life", "study_life", "MAX_BLOCKS", "MAX_GROWTH", "WARN_BLOCKS", "WEAR_BINS"]

#: Bins around each worn surface (rust/clearance/wear.rs WEAR_BINS).
WEAR_BINS = 360
#: Default growth of the deepest-wearing bin per jump, as a fraction of the clearance: on the
#: 200-cycle check (docs/reliability.md, "Reliability over life") 2 % keeps the peak and the worn volume within 3 %.
MAX_GROWTH = 0.02
#: Default most blocks a sample may run (``max_blocks``): a life estimated to need more stops
#: after its first round with an :class:`InputError` that says why and what to change.
MAX_BLOCKS = 1000
#: A life estimated to need more blocks a sample than this warns, with the same explanation.
WARN_BLOCKS = 200


@dataclass
class BlockOutcome:
    """What one block of N samples gives: the limit-state value ``g`` (failure when g ≤ 0) of
    the analysed turns, the ``values`` reported with it (N × k: each output's peak or minimum),
    the worn state (N × m) at the start of the analysed turns and at the block's end, and the
    runs that failed ``(sample, reason)`` (their other entries are ignored)."""

    g: np.ndarray
    values: np.ndarray
    at_window: np.ndarray
    at_end: np.ndarray
    failures: List[Tuple[int, str]] = field(default_factory=list)


class BlockRunner(Protocol):
    """Runs one block for N samples at standard normal points ``u`` (N × d) from worn states
    ``wear`` (N × :attr:`state_size`)."""

    #: Turns before the analysed ones in a block, and the analysed turns.
    settle_cycles: float
    window_cycles: float
    #: Length m of a sample's worn state.
    state_size: int
    #: The depth [m] jumps are limited against (``max_growth`` × this per jump).
    depth_scale: float

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome: ...


@dataclass
class LifeResult:
    """p_f against operating cycles.

    ``cycles`` the requested cycle counts; ``pf`` at each (the probability that the limit state
    has been passed in some block up to that count: failure is not undone by later blocks) with
    its Wilson ``interval`` (lower and upper arrays); ``g`` (samples × cycles) the limit-state
    value at each count and ``peaks`` (samples × cycles × outputs) each output's peak (its
    minimum for a lower limit), NaN once a run failed; ``depth`` (samples × cycles × worn
    surfaces) the largest worn depth [m] of each bearing and journal, named in ``surfaces``;
    ``failure_cycles`` each sample's first-passage cycle count, interpolated linearly in g
    between blocks (inf: none up to the last count); ``blocks`` the blocks each sample ran;
    ``n_runs`` simulations; ``failures`` ``(sample, cycle, reason)`` of failed runs (counted as
    failures from that block on); ``worn`` each sample's worn state at the last count."""

    cycles: np.ndarray
    pf: np.ndarray
    interval: Tuple[np.ndarray, np.ndarray]
    g: np.ndarray
    peaks: np.ndarray
    depth: np.ndarray
    #: (samples × cycles) the smallest g over the blocks up to each count (−1 after a failed
    #: run): failure by then when ≤ 0.
    g_min: np.ndarray
    surfaces: List[str]
    failure_cycles: np.ndarray
    blocks: np.ndarray
    n_runs: int
    wall_time: float
    failures: List[Tuple[int, float, str]] = field(default_factory=list)
    worn: Optional[np.ndarray] = None
    outputs: List[str] = field(default_factory=list)

    @property
    def reliability(self) -> np.ndarray:
        return 1.0 - self.pf

    def life_at(self, reliability: float, confidence: float = 0.95) -> Tuple[float, Tuple[float, float]]:
        """The cycle count at which the reliability falls to ``reliability``, with a
        ``confidence`` interval: the (1 − R)-quantile of the samples' first-passage cycles and
        its distribution-free order-statistic interval (binomial ranks). An end of the interval
        beyond the last count is ``inf``; an :class:`InputError` if the estimate itself lies
        beyond it (run a longer life or more samples)."""
        r = float(reliability)
        if not 0.0 < r < 1.0:
            raise InputError(f"invalid reliability = {reliability!r}: must lie in (0, 1)", field="reliability", value=reliability)
        n = self.failure_cycles.size
        q = 1.0 - r
        life = np.sort(self.failure_cycles)
        k = max(1, int(math.ceil(q * n)))  # the estimate: the k-th smallest (1-based)
        if not math.isfinite(life[k - 1]):
            failed = int(np.isfinite(life).sum())
            raise InputError(
                f"invalid reliability = {reliability!r}: only {failed} of {n} samples failed by {self.cycles[-1]:g} cycles, "
                f"so R stays above {1.0 - failed / n:.4g} there; run a longer life or more samples", field="reliability", value=reliability,
            )  # fmt: skip
        alpha = 1.0 - float(confidence)
        lo = int(stats.binom.ppf(0.5 * alpha, n, q))  # ranks with P(x_(lo) ≤ ξ_q ≤ x_(hi)) ≥ confidence
        hi = int(stats.binom.ppf(1.0 - 0.5 * alpha, n, q)) + 1

        def at(i: int) -> float:
            return float(life[i - 1]) if 1 <= i <= n else (0.0 if i < 1 else math.inf)

        return float(life[k - 1]), (at(lo), at(hi))


def life(
    runner: BlockRunner,
    u: np.ndarray,
    cycles: Sequence[float],
    *,
    max_growth: Optional[float] = MAX_GROWTH,
    max_jump: Optional[float] = None,
    surfaces: Optional[List[str]] = None,
    confidence: float = 0.95,
    on_failure: str = "fail",
    max_blocks: int = MAX_BLOCKS,
    progress: bool = True,
) -> LifeResult:
    """Simulate the life of the samples at standard normal points ``u`` (N × d) in blocks (see
    the module's docstring) and estimate p_f at each of ``cycles``.
    ``max_growth``: the deepest bin's growth per jump as a fraction of ``runner.depth_scale``
    (``None``: no limit); ``max_jump``: most cycles per jump (``None``: no limit);
    ``surfaces``: names of the worn surfaces, each :data:`WEAR_BINS` entries of the state;
    ``max_blocks``: most blocks a sample may run (an estimate above it after the first round is
    an :class:`InputError`; a sample reaching it later is stopped and counted as failed);
    ``progress``: a bar over the rounds of blocks."""
    t_start = time.perf_counter()
    check_on_failure(on_failure)
    if isinstance(max_blocks, bool) or not isinstance(max_blocks, (int, np.integer)) or max_blocks < 1:
        raise InputError(f"invalid max_blocks = {max_blocks!r}: must be a positive integer", field="max_blocks", value=max_blocks)
    if on_failure == "exclude":
        raise InputError("invalid on_failure = 'exclude': a life cannot leave a failed sample out; use 'fail' or 'raise'", field="on_failure", value=on_failure)
    req = np.asarray(cycles, dtype=float).reshape(-1)
    if req.size == 0 or not np.all(np.isfinite(req)) or np.any(req < 0):
        raise InputError(f"invalid cycles = {cycles!r}: give one or more finite cycle counts ≥ 0", field="cycles", value=cycles)
    req = np.unique(req)
    cap = math.inf if max_jump is None else check_positive("max_jump", max_jump)
    growth = math.inf if max_growth is None else check_positive("max_growth", max_growth) * float(runner.depth_scale)
    u = np.atleast_2d(np.asarray(u, dtype=float))
    n, m = u.shape[0], int(runner.state_size)
    names = surfaces if surfaces is not None else [f"surface {k}" for k in range(m // WEAR_BINS)]
    window, n_block = float(runner.window_cycles), float(runner.settle_cycles) + float(runner.window_cycles)
    wear = np.zeros((n, m))
    at_n = np.zeros(n)  # each sample's cycle count
    nxt = np.zeros(n, dtype=int)  # its next requested count to record
    blocks = np.zeros(n, dtype=int)
    active = np.ones(n, dtype=bool)
    failures: List[Tuple[int, float, str]] = []
    g_req = np.full((n, req.size), np.nan)
    gmin_req = np.full((n, req.size), np.nan)
    g_run = np.full(n, math.inf)
    values_req: Optional[np.ndarray] = None
    depth_req = np.full((n, req.size, len(names)), np.nan)
    worn = np.zeros((n, m))
    first = np.full(n, math.inf)
    prev_n = np.full(n, np.nan)
    prev_g = np.full(n, np.nan)
    n_runs = 0
    rounds = 0
    budget = _Budget(int(max_blocks), growth, cap, window, float(runner.depth_scale), max_growth, max_jump)
    progress_bar = bar(req.size, "life: rounds of blocks", unit="round", enabled=progress)  # total: the estimate, from round 2
    try:
        while active.any():
            idx = np.flatnonzero(active)
            t_round = time.perf_counter()
            out = runner(u[idx], wear[idx])
            n_runs += idx.size
            rounds += 1
            blocks[idx] += 1
            values = np.asarray(out.values, dtype=float).reshape(idx.size, -1)
            if values_req is None:
                values_req = np.full((n, req.size, values.shape[1]), np.nan)
            if out.failures and on_failure == "raise":
                i, reason = out.failures[0]
                raise SimulationError(f"life: sample {idx[i]} failed at {at_n[idx[i]]:g} cycles: {reason}", reason=reason)
            ok = np.ones(idx.size, dtype=bool)
            for i, reason in out.failures:
                s = int(idx[i])
                ok[i] = False
                active[s] = False
                failures.append((s, float(at_n[s]), reason))
                first[s] = min(first[s], float(at_n[s]))
                worn[s] = wear[s]
                gmin_req[s, nxt[s] :] = -1.0
            sel, i_ok = idx[ok], np.flatnonzero(ok)
            g = np.asarray(out.g, dtype=float)[i_ok]
            g_run[sel] = np.minimum(g_run[sel], g)
            # First passage, interpolated linearly in g between this block and the last.
            newly = (g <= 0.0) & ~np.isfinite(first[sel])
            a, ga = prev_n[sel], prev_g[sel]
            crossed = newly & np.isfinite(ga) & (ga > 0.0)
            with np.errstate(invalid="ignore", divide="ignore"):
                interp = a + (at_n[sel] - a) * ga / (ga - g)
            first[sel] = np.where(crossed, interp, np.where(newly, at_n[sel], first[sel]))
            prev_n[sel], prev_g[sel] = at_n[sel], g
            # Record the requested counts reached.
            here = at_n[sel] == req[nxt[sel]]
            for s, i in zip(sel[here], i_ok[here]):
                g_req[s, nxt[s]] = out.g[i]
                gmin_req[s, nxt[s]] = g_run[s]
                values_req[s, nxt[s]] = values[i]
                depth_req[s, nxt[s]] = _surface_depths(wear[s : s + 1], len(names))[0]
                nxt[s] += 1
            done = nxt[sel] == req.size
            worn[sel[done]] = wear[sel[done]]
            active[sel[done]] = False
            go, i_go = sel[~done], i_ok[~done]
            # A sample that spent its block budget is stopped, counted as failed from here.
            spent = blocks[go] >= max_blocks
            for s in go[spent]:
                reason = f"stopped after max_blocks = {max_blocks} blocks at {at_n[s]:g} of {req[-1]:g} cycles: its wear sped up past the first round's estimate"
                if on_failure == "raise":
                    raise SimulationError(f"life: sample {s} {reason}", reason=reason)
                failures.append((int(s), float(at_n[s]), reason))
                first[s] = min(first[s], float(at_n[s]))
                worn[s] = wear[s]
                gmin_req[s, nxt[s] :] = -1.0
                active[s] = False
            go, i_go = go[~spent], i_go[~spent]
            progress_bar.update(1)
            if go.size == 0:
                continue
            at_window, at_end = out.at_window[i_go], out.at_end[i_go]
            rate = np.maximum(at_end - at_window, 0.0) / window
            fastest = rate.max(axis=1) if m else np.zeros(go.size)
            with np.errstate(divide="ignore"):
                h_growth = np.where(fastest > 0, growth / fastest, math.inf)
            # The allowed jump, shortened so that equal jumps land on the next requested count.
            target = req[nxt[go]]
            remaining = target - at_n[go]
            allowed = np.minimum(cap, np.maximum(h_growth, window))
            # Relative tolerance: a rate carries rounding ~1e-12 relative, which over thousands of jumps an absolute one did not absorb.
            h = remaining / np.maximum(1.0, np.ceil(remaining / allowed * (1.0 - 1e-9)))
            left = _blocks_left(at_n[go], nxt[go], req, allowed)
            if rounds == 1:
                budget.check(left + blocks[go], fastest, allowed, wear[go], req[-1] - at_n[go], req[-1], req.size, time.perf_counter() - t_round)
            progress_bar.total = rounds + int(left.max())
            progress_bar.refresh()
            start = blocks[go] == 1  # the life's real start-up: the first block's whole wear
            inc = h[:, None] * rate
            frac = np.minimum(1.0, h / n_block)[:, None]
            inc[start] = (frac * (at_end - wear[go]) + np.maximum(0.0, h - n_block)[:, None] * rate)[start]
            wear[go] += np.maximum(inc, 0.0)
            at_n[go] = np.where(h == remaining, target, at_n[go] + h)
    finally:
        progress_bar.close()
    kk = (first[:, None] <= req[None, :]).sum(axis=0)
    lo, hi = wilson_interval(kk, np.full(req.size, n), confidence)
    return LifeResult(
        cycles=req, pf=kk / n, interval=(np.atleast_1d(lo), np.atleast_1d(hi)), g=g_req, g_min=gmin_req,
        peaks=values_req if values_req is not None else np.full((n, req.size, 0), np.nan), depth=depth_req, surfaces=list(names),
        failure_cycles=first, blocks=blocks, n_runs=n_runs, wall_time=time.perf_counter() - t_start, failures=failures, worn=worn,
    )  # fmt: skip


def _blocks_left(at_n: np.ndarray, nxt: np.ndarray, req: np.ndarray, allowed: np.ndarray) -> np.ndarray:
    """Blocks each sample still runs to the last requested count if its jumps stay ``allowed``
    (one a jump: equal jumps landing on each count from ``at_n`` on)."""
    lower = np.maximum(np.concatenate([[-math.inf], req[:-1]])[None, :], at_n[:, None])
    seg = req[None, :] - lower
    mine = (np.arange(req.size)[None, :] >= nxt[:, None]) & (seg > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        jumps = np.maximum(1.0, np.ceil(seg / allowed[:, None] * (1.0 - 1e-9)))
    return np.where(mine, jumps, 0.0).sum(axis=1).astype(int)


@dataclass
class _Budget:
    """The first round's estimate of a life's blocks against ``max_blocks``, and why the jumps
    are as long as they are (the growth limit, ``max_jump`` or the analysed turns)."""

    max_blocks: int
    growth: float
    cap: float
    window: float
    depth_scale: float
    max_growth: Optional[float]
    max_jump: Optional[float]

    def check(self, total: np.ndarray, fastest: np.ndarray, allowed: np.ndarray, wear: np.ndarray, remaining: np.ndarray, last: float, counts: int, t_round: float) -> None:
        worst = int(np.argmax(total))
        est = int(total[worst])
        if est <= WARN_BLOCKS and est <= self.max_blocks:
            return
        rate, h = float(fastest[worst]), float(allowed[worst])
        c = self.depth_scale
        if est <= counts + 1:
            why = f"{counts} requested cycle counts each take a block (ask for fewer)"
        elif h >= self.cap:
            why = f"max_jump = {self.max_jump:g} caps each jump (raise it or leave it out)"
        elif h <= self.window and rate * self.window > self.growth:
            why = (
                f"its deepest bin wears {rate:.3g} m a cycle, more than max_growth × c = {self.growth:.3g} m in one analysed "
                f"window, so each block advances only the window's {self.window:g} cycles (cycle jumping saves nothing here; "
                "check the wear coefficient)"
            )  # fmt: skip
        else:
            why = f"its deepest bin wears {rate:.3g} m a cycle and max_growth = {self.max_growth:g} allows {self.growth:.3g} m a jump, so each jump is {h:.3g} cycles"
        depth = float(wear[worst].max(initial=0.0)) + rate * float(remaining[worst])
        msg = (
            f"life to {last:g} cycles needs about {est} blocks a sample (at the first round's wear rates; {t_round:.3g} s a round, "
            f"so at least {est * t_round:.3g} s): in the fastest-wearing sample {why}; at that rate it is worn {depth:.3g} m deep "
            f"by {last:g} cycles, {depth / c:.3g} × the depth scale c = {c:.3g} m (the smallest worn clearance). To shorten it ask "
            "for fewer cycles, or raise max_growth (the extrapolation error grows with it: docs/reliability.md, 'Reliability over life')"
        )  # fmt: skip
        if est > self.max_blocks:
            raise InputError(f"invalid life: {msg}; or raise max_blocks = {self.max_blocks} to run it anyway", field="max_blocks", value=self.max_blocks)
        warnings.warn(msg, ReliabilityWarning, stacklevel=4)


def _surface_depths(wear: np.ndarray, surfaces: int) -> np.ndarray:
    """Largest depth of each worn surface (N × surfaces) from states of WEAR_BINS per surface."""
    if surfaces == 0:
        return np.zeros((wear.shape[0], 0))
    return wear[:, : surfaces * WEAR_BINS].reshape(wear.shape[0], surfaces, WEAR_BINS).max(axis=2)


# ---------------------------------------------------------------------------- the Study's blocks
def _wear_entries(description: Dict[str, Any]) -> List[Tuple[str, Dict[str, Any]]]:
    """(joint name, its wear dict) of every clearance joint of a description that models wear."""
    out = []
    for c in description.get("clearance_joints", []):
        model = c["model"]
        law = model.get("wear") if model.get("kind") == "dry" else model.get("dry", {}).get("wear")
        if law is not None:
            out.append((str(c["name"]), law))
    return out


class StudyBlocks:
    """The blocks of a :class:`~clearsim.reliability.Study`: each sample's mechanism, with the
    worn state written into its Archard laws (``initial_bearing``, ``initial_journal``) and wear
    fed back, runs ``settle + cycles`` turns; the study's monitor reads the peak over the last
    ``cycles`` (the study's window moved to start after ``settle`` turns) and the run's
    ``wear_mark`` the books at the window's start.

    Every worn joint's law must have ``feedback=True`` (else wear would not change the output)."""

    def __init__(self, study: Any, settle: Optional[float] = None) -> None:
        self.study = copy.copy(study)  # run count shared
        skip = float(study.skip_cycles)
        self.settle_cycles = max(skip, 1.0) if settle is None else float(settle)
        if not (math.isfinite(self.settle_cycles) and self.settle_cycles >= 0):
            raise InputError(f"invalid settle = {settle!r}: must be a finite number of turns ≥ 0", field="settle", value=settle)
        self.study.skip_cycles = self.settle_cycles
        self.window_cycles = float(study.cycles)
        m = study.built(study.nominal())
        entries = _wear_entries(m.description())
        if not entries:
            raise InputError(
                "invalid study for life: its mechanism models no wear; give a dry law Dry(wear=clearsim.Archard(..., feedback=True))",
                field="build", value=None,
            )  # fmt: skip
        for name, law in entries:
            if not law.get("feedback", False):
                raise InputError(
                    f"invalid clearance joint {name!r}.wear.feedback = False: life needs the worn depth fed back "
                    "(Archard(..., feedback=True)), or wear would not change the output", field=f"clearance joint '{name}'.wear.feedback", value=False,
                )  # fmt: skip
        self.joints = [name for name, _ in entries]
        scale = [float(c["clearance"]) for c in m.description()["clearance_joints"] if c["name"] in self.joints]
        self.depth_scale = min(scale)
        self.surfaces = [f"{j} {s}" for j in self.joints for s in ("bearing", "journal")]
        self.state_size = len(self.surfaces) * WEAR_BINS

    def __call__(self, u: np.ndarray, wear: np.ndarray) -> BlockOutcome:
        st = self.study
        n = u.shape[0]
        at_window = np.zeros((n, self.state_size))
        at_end = np.zeros((n, self.state_size))
        mismatch: Dict[int, str] = {}

        def on_job(k: int, description: Dict[str, Any], settings: Dict[str, Any]) -> None:
            entries = _wear_entries(description)
            if [name for name, _ in entries] != self.joints:
                mismatch[k] = f"the worn joints {[e[0] for e in entries]} differ from the nominal mechanism's {self.joints}"
            for j, (_, law) in enumerate(entries[: len(self.joints)]):
                base = 2 * j * WEAR_BINS
                law["initial_bearing"] = wear[k, base : base + WEAR_BINS].tolist()
                law["initial_journal"] = wear[k, base + WEAR_BINS : base + 2 * WEAR_BINS].tolist()
            settings["wear_mark"] = float(settings["monitors"][0]["t_start"])

        def on_raw(k: int, raw: Dict[str, Any]) -> None:
            books = [b for b in raw.get("wear") or [] if b is not None]
            for j, b in enumerate(books[: len(self.joints)]):
                base = 2 * j * WEAR_BINS
                at_end[k, base : base + WEAR_BINS] = b["bearing"]
                at_end[k, base + WEAR_BINS : base + 2 * WEAR_BINS] = b["journal"]
                at_window[k, base : base + WEAR_BINS] = b["bearing_at_mark"]
                at_window[k, base + WEAR_BINS : base + 2 * WEAR_BINS] = b["journal_at_mark"]

        ev, _ = st.run_samples(st.values(u), what="life blocks", show=False, on_job=on_job, on_raw=on_raw)
        g = np.min(np.column_stack([lim.g(ev.values[:, i]) for i, lim in enumerate(st.limits)]), axis=1)
        failures = dict(ev.failures)
        failures.update(mismatch)
        return BlockOutcome(g, ev.values, at_window, at_end, sorted(failures.items()))


def study_life(
    study: Any,
    cycles: Sequence[float],
    n: int,
    seed: Optional[int] = 0,
    *,
    max_growth: Optional[float] = MAX_GROWTH,
    max_jump: Optional[float] = None,
    settle: Optional[float] = None,
    on_failure: str = "fail",
    confidence: float = 0.95,
    max_blocks: int = MAX_BLOCKS,
) -> LifeResult:
    """:meth:`Study.life`: ``n`` Monte Carlo samples (the streams of :meth:`Study.monte_carlo`
    with the same ``seed``), each run through its life in blocks (a progress bar when the
    study's ``progress`` is on)."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    runner = StudyBlocks(study, settle)
    u = np.column_stack([input_stream(seed, name).standard_normal(int(n)) for name in study.random_names]) if study.random_names else np.zeros((int(n), 0))
    res = life(runner, u, cycles, max_growth=max_growth, max_jump=max_jump, surfaces=runner.surfaces, confidence=confidence, on_failure=on_failure,
               max_blocks=max_blocks, progress=bool(study.progress))  # fmt: skip
    res.outputs = list(study.mode_names)
    return res


class LifeModel(ReliabilityModel):
    """The limit state of a whole life as a reliability model: ``g(u)`` is the smallest g over
    the blocks of the life of the sample at u up to ``cycles`` operating cycles (failure by then
    when ≤ 0; a failed run gives −1), so AK-MCS, FORM or importance sampling answer
    "p_f after N cycles" with each evaluation one life (``Study.life_model``). One mode (the
    study's modes combined, min g)."""

    def __init__(self, study: Any, cycles: float, *, max_growth: Optional[float] = MAX_GROWTH, max_jump: Optional[float] = None, settle: Optional[float] = None) -> None:
        n = float(cycles)
        if not (math.isfinite(n) and n >= 0):
            raise InputError(f"invalid cycles = {cycles!r}: a cycle count ≥ 0", field="cycles", value=cycles)
        self.cycles = n
        self.runner = StudyBlocks(study, settle)
        self.options: Dict[str, Any] = {"max_growth": max_growth, "max_jump": max_jump, "progress": bool(study.progress)}
        self.inputs = study.inputs
        self.random_names = study.random_names
        self._counter = study._counter

    @property
    def mode_names(self) -> List[str]:
        return [f"failure by {self.cycles:g} cycles"]

    def limit_states(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        pts = np.atleast_2d(np.asarray(u, dtype=float))
        res = life(self.runner, pts, [self.cycles], on_failure=on_failure, **self.options)
        return np.asarray(res.g_min[:, -1:], dtype=float)

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        return np.asarray(self.limit_states(u, on_failure)[:, 0])
