"""The analysed window's start-up check: a study whose peaks sit at the window's opening (the
start-up jolt of a run from rest at t = 0 when ``skip_cycles = 0``) reports that jolt for every
sample, whatever its inputs; it warns, naming ``skip_cycles`` (docs/reliability.md, "The start-up
transient")."""

from __future__ import annotations

import warnings
from typing import Any, Sequence

import numpy as np

from ..errors import ReliabilityWarning

__all__ = ["EDGE_SHARE", "STANDS_OUT", "MOST", "at_window_start", "warn_at_start"]

#: A peak this close to the window's start (a share of the window's length: 3.6° of crank a
#: cycle) sits at its start.
EDGE_SHARE = 0.01
#: ... and is a jolt when the window's first time bin's extreme is this many times every later
#: bin's (an error that merely falls through a short window is not one).
STANDS_OUT = 2.0
#: The share of the completed samples with their peak at the start above which a study warns.
MOST = 0.5


def at_window_start(t_peak: float, t_start: float, span: float, bin_max: Any, bin_min: Any) -> bool:
    """Whether a peak at ``t_peak`` [s] is a jolt at the start of a window ``[t_start, t_start +
    span]`` [s]: within :data:`EDGE_SHARE` of its start, and its first time bin's extreme (from the
    monitor's per-bin ``bin_max``, ``bin_min``) :data:`STANDS_OUT` times every later bin's. A
    window of one bin cannot tell: no."""
    if not t_peak - t_start <= EDGE_SHARE * span:  # the common case, decided without the bins
        return False
    extremes = np.maximum(np.abs(np.asarray(bin_max, dtype=float)), np.abs(np.asarray(bin_min, dtype=float)))
    if extremes.size < 2:
        return False
    return bool(extremes[0] > STANDS_OUT * np.max(extremes[1:]))


def warn_at_start(at_start: np.ndarray, completed: np.ndarray, values: np.ndarray, labels: Sequence[str], units: Sequence[str], skip_cycles: float, t_start: float) -> bool:
    """Warn (:class:`clearsim.errors.ReliabilityWarning`) when most ``completed`` samples' peak of
    an output sits at the window's start (``at_start``, (N, outputs)); ``values`` their peaks.
    Returns whether it warned."""
    n_ok = int(np.count_nonzero(completed))
    if n_ok == 0:
        return False
    for i, (label, unit) in enumerate(zip(labels, units)):
        hits = at_start[:, i] & completed
        share = int(np.count_nonzero(hits)) / n_ok
        if share > MOST:
            peak = float(np.nanmedian(values[hits, i]))
            warnings.warn(
                f"the peak {label} sits at the analysed window's start (t = {t_start:.4g} s, skip_cycles = {skip_cycles:g}) in {share:.0%} of {n_ok} "
                f"completed samples (median {peak:.5g} {unit}): that is the start-up transient, not the mechanism's running, and it hides the "
                f"inputs' effect; analyse later turns with a larger skip_cycles (docs/reliability.md, 'The start-up transient')",
                ReliabilityWarning, stacklevel=4,
            )  # fmt: skip
            return True
    return False
