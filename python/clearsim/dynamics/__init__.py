"""Periodic, quasi-periodic or chaotic? Tools for the long-run dynamics of mechanisms with
clearance (docs/physics.md §13), one concept a module:

- :mod:`.readings`: ``Result.poincare`` (sections at exact times) and ``Result.spectrum``;
- :mod:`.spectrum`: amplitude spectra over whole periods;
- :mod:`.period`: a mechanism's forcing period;
- :mod:`.lyapunov`: the largest Lyapunov exponent (two trajectories, renormalised);
- :mod:`.classify`: period-k, quasi-periodic or chaotic from the sections;
- :mod:`.bifurcation`: diagrams over a parameter, in the core's batch.

Their plots are in :mod:`clearsim.plots.dynamics`; ``clearsim sweep scene.toml`` runs a
bifurcation diagram from a scene's ``[sweep]`` table. The names below are imported on first use
(``import clearsim`` loads only what :class:`clearsim.Result` needs).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .bifurcation import Bifurcation, bifurcation
    from .classify import Classification, classify
    from .lyapunov import LyapunovExponent, lyapunov
    from .period import forcing_period
    from .spectrum import Spectrum, spectrum

#: Each public name and the module that defines it.
_WHERE = {
    "Bifurcation": "bifurcation", "bifurcation": "bifurcation", "Classification": "classify", "classify": "classify",
    "LyapunovExponent": "lyapunov", "lyapunov": "lyapunov", "forcing_period": "period", "Spectrum": "spectrum", "spectrum": "spectrum",
}  # fmt: skip


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module 'clearsim.dynamics' has no attribute {name!r}")


__all__ = ["Bifurcation", "Classification", "LyapunovExponent", "Spectrum", "bifurcation", "classify", "forcing_period", "lyapunov", "spectrum"]
