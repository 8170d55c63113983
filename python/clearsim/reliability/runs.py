"""Batches of runs for the reliability methods: the monitor each run carries (its spec, once) and
the batch runner (in the Rust core on all local cores, or through any ``concurrent.futures``-style
executor), with progress bars.

The monitor (``rust/monitor.rs``) tracks one output at every accepted step of the integrator —
its peak, the first time it passes a limit and per-time-bin extremes and moments — so no answer
of a study depends on an output grid (docs/physics.md §6).
"""

from __future__ import annotations

import math
import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .. import _core

__all__ = ["REFERENCE_POINTS_PER_CYCLE", "MONITOR_SAMPLES_PER_STEP", "run_descriptions", "run_all", "progress", "monitor_spec", "failed", "error_of", "reference_grid", "output_grid"]

#: Points per crank cycle of the ideal reference trajectory that body errors are measured
#: against (cubic Hermite in between).
REFERENCE_POINTS_PER_CYCLE = 7200
#: Points a step at which the monitor reads the dense output (accelerations from its time
#: derivative, with one KKT solve at the worst interior point and one at the step's end): 4 a
#: step missed impact peaks by 1e-4 relative to a 3 600-point grid on the dry slider-crank, 8 do not.
MONITOR_SAMPLES_PER_STEP = 8


def run_descriptions(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]]) -> List[Any]:
    """Run descriptions with their settings in the Rust core (all local cores). A pure,
    picklable function: this is what a remote executor runs for a chunk of samples."""
    return _core.run_batch(descriptions, settings, 0)


def failed(raw: Any) -> bool:
    """Whether a raw run result is a failure (an exception or a result carrying an error)."""
    return isinstance(raw, BaseException) or raw.get("error") is not None


def error_of(raw: Any) -> Any:
    """The error of a failed raw run result."""
    return raw if isinstance(raw, BaseException) else raw["error"]


def progress(total: int, enabled: bool, what: str) -> Any:
    """A progress bar over ``total`` runs (:func:`clearsim.progress.bar`)."""
    from ..progress import bar

    return bar(total, what, "run", enabled=enabled)


def run_all(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], executor: Any, chunk_size: Optional[int], show: bool, what: str) -> List[Any]:
    """Run in chunks (so a progress bar can move), locally in Rust or through ``executor``."""
    total = len(descriptions)
    if total == 0:
        return []
    if chunk_size is None:
        if executor is None:
            # In-core batches: large enough that the threads stay busy to the batch's end (run
            # times vary ±30 % between samples; with 3–6 runs a batch on 2 threads a quarter of
            # the time was spent waiting for the slowest), small enough for the bar to move.
            chunk_size = max(1, min(total, max(16 * (os.cpu_count() or 1), total // 20)))
        else:
            chunk_size = max(1, min(32, total // 20 or 1))  # spread over the executor's workers
    chunks = [(descriptions[i : i + chunk_size], settings[i : i + chunk_size]) for i in range(0, total, chunk_size)]
    bar = progress(total, show, what)
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


def monitor_spec(ideal: Optional[Dict[str, Any]], col: int, quantity: str, limit: Optional[float], t_start: float, period: float, cycles: float, bin_width: float) -> Dict[str, Any]:
    """The monitor of one quantity in time bins of ``bin_width`` degrees of crank angle over
    ``cycles`` turns from ``t_start`` [s]: a body coordinate's error against the ideal run (cubic
    Hermite through the ideal's values and rates on the reference grid), or, without ``ideal``,
    the quantity itself (a joint's, ``col`` its index). ``limit``: the first passage above it is
    timed (``None``: not tracked)."""
    spec: Dict[str, Any] = {
        "coordinate": int(col),
        "quantity": quantity,
        "t_start": float(t_start),
        "bin_width": period * bin_width / 360.0,
        "bins": int(math.ceil(cycles * 360.0 / bin_width - 1e-9)),
        "samples_per_step": MONITOR_SAMPLES_PER_STEP,
    }
    if limit is not None and math.isfinite(limit):
        spec["limit"] = float(limit)
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


def reference_grid(t0: float, t1: float, period: float, points_per_cycle: Optional[int] = None) -> Tuple[np.ndarray, int]:
    """The grid [s] the ideal reference is computed on over ``[t0, t1]`` (``t1 − t0`` a whole
    number of ``period`` [s] or not) and its refinement ``refine``: at least
    :data:`REFERENCE_POINTS_PER_CYCLE` points a cycle; with an output grid of
    ``points_per_cycle`` points a cycle, a multiple of it whose every ``refine``-th point is
    exactly the output grid's (:func:`output_grid`)."""
    if points_per_cycle is None:
        n = max(2, int(math.ceil(REFERENCE_POINTS_PER_CYCLE * (t1 - t0) / period)))
        return np.linspace(t0, t1, n + 1), 1
    t_out = output_grid(t0, t1, period, points_per_cycle)
    refine = max(1, math.ceil(REFERENCE_POINTS_PER_CYCLE / points_per_cycle))
    n = (t_out.size - 1) * refine
    t_ref = t0 + (t_out[-1] - t0) * np.arange(n + 1) / n
    t_ref[::refine] = t_out  # the output grid exactly, its end included
    return t_ref, refine


def output_grid(t0: float, t1: float, period: float, points_per_cycle: int) -> np.ndarray:
    """The stored output grid [s]: ``points_per_cycle`` intervals a crank cycle over ``[t0, t1]``."""
    n_out = max(1, int(round(points_per_cycle * (t1 - t0) / period)))
    return t0 + (t1 - t0) * np.arange(n_out + 1) / n_out
