"""What the reliability methods add to each run: the monitors it carries (what each watches and
what it is measured against, named, never shipped: the core makes the reference runs) and the
grids of the reference runs and of stored outputs. The batches themselves run through
:mod:`clearsim.batch` (re-exported here under their old names).

The monitor (``rust/monitor/``) tracks one output at every accepted step of the integrator —
its peak, the first time it passes a limit and per-time-bin extremes and moments — so no answer
of a study depends on an output grid (docs/physics.md §6). Its error is measured against a
reference run that the core's batch makes from the sample's own description (its ideal twin) or
from the batch's nominal description (``rust/batch.rs``): one run per distinct ideal mechanism,
shared by the samples measured against it.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional

import numpy as np

from ..batch import error_of, failed, progress, run_all, run_descriptions

__all__ = ["REFERENCE_POINTS_PER_CYCLE", "MONITOR_SAMPLES_PER_STEP", "run_descriptions", "run_all", "progress", "monitor_spec", "failed", "error_of", "reference_grid", "output_grid"]

#: Points per crank cycle of the reference runs that body errors are measured against (cubic
#: Hermite in between).
REFERENCE_POINTS_PER_CYCLE = 7200
#: Points a step at which the monitor reads the dense output (accelerations from its time
#: derivative, with one KKT solve at the worst interior point and one at the step's end): 4 a
#: step missed impact peaks by 1e-4 relative to a 3 600-point grid on the dry slider-crank, 8 do not.
MONITOR_SAMPLES_PER_STEP = 8


def monitor_spec(
    target: Dict[str, Any], quantity: str, reference: Optional[str], limit: Optional[float], t_start: float, period: float, cycles: float, bin_width: float
) -> Dict[str, Any]:  # fmt: skip
    """The monitor of one quantity of ``target`` (:meth:`Output.target`: a body coordinate, a
    point on a body, or a clearance joint) in time bins of ``bin_width`` degrees of crank angle
    over ``cycles`` turns from ``t_start`` [s]: a body target's error against the ``reference``
    run (``"own_ideal"`` or ``"nominal"``, made by the core; ``None``: the quantity itself, as
    for a joint). ``limit``: the first passage above it is timed (``None``: not tracked)."""
    spec: Dict[str, Any] = {
        **target,
        "quantity": quantity,
        "t_start": float(t_start),
        "bin_width": period * bin_width / 360.0,
        "bins": int(math.ceil(cycles * 360.0 / bin_width - 1e-9)),
        "samples_per_step": MONITOR_SAMPLES_PER_STEP,
    }
    if limit is not None and math.isfinite(limit):
        spec["limit"] = float(limit)
    if reference is not None:
        spec["reference"] = reference
    return spec


def reference_grid(t0: float, t1: float, period: float, points_per_cycle: Optional[int] = None, record: bool = False) -> Dict[str, Any]:
    """The grid the reference runs record on over ``[t0, t1]`` [s] (``t1 − t0`` a whole number
    of ``period`` [s] or not), as run settings give it (``rust/monitor/reference.rs``,
    ``ReferenceGrid``: equal intervals, numpy's ``linspace``): at least
    :data:`REFERENCE_POINTS_PER_CYCLE` points a cycle; with an output grid of
    ``points_per_cycle`` points a cycle (:func:`output_grid`), a whole multiple of it over the
    same span, so that every output time is a grid point (to round-off). ``record``: the run's
    output also gives the reference at its output times (for error traces)."""
    if points_per_cycle is None:
        n = max(2, int(math.ceil(REFERENCE_POINTS_PER_CYCLE * (t1 - t0) / period)))
        return {"t_start": float(t0), "t_end": float(t1), "intervals": n, "record": bool(record)}
    t_out = output_grid(t0, t1, period, points_per_cycle)
    refine = max(1, math.ceil(REFERENCE_POINTS_PER_CYCLE / points_per_cycle))
    return {"t_start": float(t0), "t_end": float(t_out[-1]), "intervals": (t_out.size - 1) * refine, "record": bool(record)}


def output_grid(t0: float, t1: float, period: float, points_per_cycle: int) -> np.ndarray:
    """The stored output grid [s]: ``points_per_cycle`` intervals a crank cycle over ``[t0, t1]``."""
    n_out = max(1, int(round(points_per_cycle * (t1 - t0) / period)))
    return t0 + (t1 - t0) * np.arange(n_out + 1) / n_out
