"""What the reliability methods add to each run: the monitor it carries (its spec, once) and the
grids of the ideal reference and of stored outputs. The batches themselves run through
:mod:`clearsim.batch` (re-exported here under their old names).

The monitor (``rust/monitor.rs``) tracks one output at every accepted step of the integrator —
its peak, the first time it passes a limit and per-time-bin extremes and moments — so no answer
of a study depends on an output grid (docs/physics.md §6).
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ..batch import error_of, failed, progress, run_all, run_descriptions

__all__ = ["REFERENCE_POINTS_PER_CYCLE", "MONITOR_SAMPLES_PER_STEP", "run_descriptions", "run_all", "progress", "monitor_spec", "failed", "error_of", "reference_grid", "output_grid"]

#: Points per crank cycle of the ideal reference trajectory that body errors are measured
#: against (cubic Hermite in between).
REFERENCE_POINTS_PER_CYCLE = 7200
#: Points a step at which the monitor reads the dense output (accelerations from its time
#: derivative, with one KKT solve at the worst interior point and one at the step's end): 4 a
#: step missed impact peaks by 1e-4 relative to a 3 600-point grid on the dry slider-crank, 8 do not.
MONITOR_SAMPLES_PER_STEP = 8


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
