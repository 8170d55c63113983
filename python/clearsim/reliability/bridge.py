"""OpenTURNS' view of a reliability model: what every method on OpenTURNS shares (the import
with its install hint, the seed, the function u ↦ g(u) and the event g ≤ 0), and the protocol a
model meets (:class:`ModelLike`: named inputs, standard normal space, vectorised limit state).

Everything happens in the standard normal space ``u`` of the independent inputs
(``x = F⁻¹(Φ(u))``, docs/physics.md §6): OpenTURNS sees a standard normal vector and a function
that it evaluates a sample at a time, so every batch of points becomes one parallel batch of runs.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Protocol, Tuple

import numpy as np

from ..errors import InputError, check_choice

__all__ = ["ON_FAILURE", "ModelLike", "check_on_failure", "ot", "seed_ot", "event", "normal_interval"]

#: What a run that fails does to a method: counts as a failure of the mechanism, is left out
#: (crude Monte Carlo only) or raises.
ON_FAILURE = ("fail", "exclude", "raise")


def check_on_failure(on_failure: Any) -> str:
    return str(check_choice("on_failure", on_failure, ON_FAILURE))


class ModelLike(Protocol):
    """What the methods need of a model (:class:`clearsim.reliability.ReliabilityModel` provides it)."""

    inputs: Dict[str, Any]
    random_names: List[str]
    n_runs: int

    @property
    def dimension(self) -> int: ...

    @property
    def mode_names(self) -> List[str]: ...

    def values(self, u: Any) -> Dict[str, np.ndarray]: ...

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray: ...

    def limit_states(self, u: Any, on_failure: str = "fail") -> np.ndarray: ...

    def mode(self, index: Any) -> "ModelLike": ...

    def with_input(self, name: str, value: Any) -> "ModelLike": ...


def ot() -> Any:
    """The ``openturns`` module, or an ImportError that says how to install it."""
    try:
        import openturns
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("FORM, importance sampling, subset simulation, Sobol indices and tolerance design need OpenTURNS: pip install clearsim[uq]") from exc
    return openturns


def seed_ot(seed: Optional[int]) -> None:
    """Seed OpenTURNS' generator (``None``: leave it as it is)."""
    if seed is not None:
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise InputError(f"invalid seed = {seed!r}: must be a non-negative integer", field="seed", value=seed)
        ot().RandomGenerator.SetSeed(int(seed))


def check_model(model: ModelLike, on_failure: str) -> None:
    check_on_failure(on_failure)
    if on_failure == "exclude":
        raise InputError("invalid on_failure = 'exclude': only crude Monte Carlo can leave failed runs out; use 'fail' or 'raise'", field="on_failure", value=on_failure)
    if model.dimension < 1:
        raise InputError("the study has no random input: give at least one distribution", field="inputs", value=list(model.inputs))


def event(model: ModelLike, on_failure: str, step: float = 0.05) -> Tuple[Any, Any]:
    """The function u ↦ g(u) (evaluated a sample at a time, with centred finite-difference
    gradients of step ``step`` in u) and the event g ≤ 0."""
    t = ot()
    check_model(model, on_failure)
    d = model.dimension

    def g_sample(u: Any) -> Any:
        return np.asarray(model.limit_state(np.asarray(u, dtype=float), on_failure), dtype=float).reshape(-1, 1)

    f = t.PythonFunction(d, 1, func_sample=g_sample)
    f.setGradient(t.CenteredFiniteDifferenceGradient(t.Point(d, float(step)), f.getEvaluation()))
    y = t.CompositeRandomVector(f, t.RandomVector(t.Normal(d)))
    return f, t.ThresholdEvent(y, t.LessOrEqual(), 0.0)


def normal_interval(pf: float, cov: float) -> Tuple[float, float]:
    """95 % interval of a simulation estimate from its coefficient of variation (normal
    approximation, clipped to [0, 1])."""
    half = 1.959963984540054 * pf * cov if math.isfinite(cov) else math.inf
    return max(0.0, pf - half), min(1.0, pf + half)
