"""Periodic, quasi-periodic or chaotic? Tools for the long-run dynamics of mechanisms with
clearance (docs/physics.md §13), one concept a module:

- :mod:`.readings`: ``Result.poincare`` (sections at exact times) and ``Result.spectrum``;
- :mod:`.spectrum`: amplitude spectra over whole periods;
- :mod:`.period`: a mechanism's forcing period;
- :mod:`.lyapunov`: the largest Lyapunov exponent (two trajectories, renormalised);
- :mod:`.classify`: period-k, quasi-periodic or chaotic from the sections;
- :mod:`.bifurcation`: diagrams over a parameter, in the core's batch.

Their plots are in :mod:`clearsim.plots.dynamics`; ``clearsim sweep scene.toml`` runs a
bifurcation diagram from a scene's ``[sweep]`` table.
"""

from .bifurcation import Bifurcation, bifurcation
from .classify import Classification, classify
from .lyapunov import LyapunovExponent, lyapunov
from .period import forcing_period
from .spectrum import Spectrum, spectrum

__all__ = ["Bifurcation", "Classification", "LyapunovExponent", "Spectrum", "bifurcation", "classify", "forcing_period", "lyapunov", "spectrum"]
