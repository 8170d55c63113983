"""``clearsim.monte_carlo``: the Monte Carlo per-bin reliability of one body coordinate's errors,
a name kept at the package's top for :func:`clearsim.reliability.binned.monte_carlo` (one sample
loop: :meth:`clearsim.reliability.Study.run_samples`)."""

from .batch import run_descriptions
from .reliability.binned import QUANTITIES, UNITS, MonteCarloResult, monte_carlo

__all__ = ["monte_carlo", "MonteCarloResult", "run_descriptions", "QUANTITIES", "UNITS"]
