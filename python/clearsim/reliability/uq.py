"""Rare events, sensitivity and tolerance design (``pip install clearsim[uq]`` for the methods on
OpenTURNS): one import for every method on a :class:`~clearsim.reliability.model.ReliabilityModel`.

clearsim supplies the model — a vectorised limit-state function ``g(u)`` that runs a batch of
simulations in parallel — and the methods work in the standard normal space ``u`` of the
independent inputs (``x = F⁻¹(Φ(u))``, docs/physics.md §6). Rooms: :mod:`.form` (FORM on noisy
limit states, series systems), :mod:`.sampling` (importance sampling, subset simulation),
:mod:`.sobol` (Sobol indices by sampling or polynomial chaos), :mod:`.tolerance` (tolerance
design), :mod:`.akmcs` (AK-MCS, AK-IS: few runs), :mod:`.bridge` (OpenTURNS' view of a model).
"""

from __future__ import annotations

from .akmcs import ak_is, ak_mcs
from .bridge import event as _event
from .bridge import normal_interval as _interval
from .bridge import ot as _ot
from .bridge import seed_ot as _seed
from .form import FormResult, SystemFormResult, ditlevsen_bounds, form, series_probability, system_form
from .sampling import SamplingResult, importance_sampling, subset
from .sobol import SobolResult, sobol
from .tolerance import ToleranceResult, tolerance

__all__ = [
    "FormResult", "SystemFormResult", "SamplingResult", "SobolResult", "ToleranceResult",
    "form", "system_form", "series_probability", "ditlevsen_bounds", "importance_sampling", "subset", "sobol", "tolerance",
    "ak_mcs", "ak_is", "_ot", "_seed", "_event", "_interval",
]  # fmt: skip
