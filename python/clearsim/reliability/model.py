"""What the reliability methods need of a model: named random inputs and a vectorised
limit-state function ``g`` (failure when ``g ≤ 0``), seen in the standard normal space of the
inputs. :class:`clearsim.reliability.Study` is such a model built on simulations;
:class:`LimitState` wraps any vectorised Python function of the inputs (used by the tests to
check the methods against closed forms)."""

from __future__ import annotations

import copy
from typing import Any, Callable, Dict, Mapping, Optional, Sequence

import numpy as np

from ..errors import InputError, check_choice
from .distributions import Distribution, as_distribution

ON_FAILURE = ("fail", "exclude", "raise")


def check_on_failure(on_failure: Any) -> str:
    return str(check_choice("on_failure", on_failure, ON_FAILURE))


class Model:
    """Named inputs (:class:`Distribution` each) and the map from standard normal points to them.

    Subclasses provide ``limit_state(u, on_failure) -> (N,) array`` and count their runs in
    ``n_runs``."""

    inputs: Dict[str, Distribution]
    random_names: list
    _counter: list  # [runs so far], shared by the copies of :meth:`with_input`

    @property
    def n_runs(self) -> int:
        """Model evaluations (simulations) so far, copies made by :meth:`with_input` included."""
        return self._counter[0]

    @n_runs.setter
    def n_runs(self, value: int) -> None:
        self._counter[0] = value

    def _set_inputs(self, inputs: Mapping[str, Any]) -> None:
        self.inputs = {str(k): as_distribution(str(k), v) for k, v in inputs.items()}
        self.random_names = [k for k, d in self.inputs.items() if d.random]

    @property
    def dimension(self) -> int:
        """Number of random inputs (the dimension of the standard normal space)."""
        return len(self.random_names)

    def values(self, u: Any) -> Dict[str, np.ndarray]:
        """The inputs at standard normal points ``u`` (N × :attr:`dimension`): each random input
        ``x = F⁻¹(Φ(u))`` (independent inputs), fixed inputs broadcast."""
        u = np.atleast_2d(np.asarray(u, dtype=float))
        if u.shape[1] != self.dimension:
            raise InputError(f"invalid u: {u.shape[1]} columns for {self.dimension} random inputs ({', '.join(self.random_names)})", field="u", value=u.shape)
        out = {}
        for name, d in self.inputs.items():
            out[name] = d.from_standard_normal(u[:, self.random_names.index(name)]) if name in self.random_names else np.full(u.shape[0], d.nominal)
        return out

    def nominal(self) -> Dict[str, float]:
        """Every input at its mean."""
        return {name: d.nominal for name, d in self.inputs.items()}

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def form(self, *, start: Optional[Sequence[float]] = None, step: float = 0.05, max_iterations: int = 50, on_failure: str = "fail") -> Any:
        """FORM (OpenTURNS): design point, Hasofer–Lind β, p_f ≈ Φ(−β) and importance factors.
        See :func:`clearsim.reliability.uq.form`."""
        from . import uq

        return uq.form(self, start=start, step=step, max_iterations=max_iterations, on_failure=on_failure)

    def with_input(self, name: str, value: Any) -> "Model":
        """A copy with input ``name`` replaced (caches shared, run count kept)."""
        if name not in self.inputs:
            raise InputError(f"invalid input {name!r}: not an input (known: {', '.join(self.inputs)})", field="name", value=name)
        other = copy.copy(self)
        other._set_inputs({**self.inputs, name: value})
        return other


class LimitState(Model):
    """Any vectorised limit-state function of named inputs.

    ``LimitState(lambda x: 3.0 - x["a"] - x["b"], {"a": Normal(0, 1), "b": Normal(0, 1)})``:
    ``function`` takes ``{name: (N,) array}`` and returns ``(N,)`` values of ``g``; failure when
    ``g ≤ 0``."""

    def __init__(self, function: Callable[[Dict[str, np.ndarray]], Any], inputs: Mapping[str, Any]) -> None:
        if not callable(function):
            raise InputError(f"invalid function = {function!r}: must be callable", field="function", value=function)
        self.function = function
        self._set_inputs(inputs)
        self._counter = [0]

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        check_on_failure(on_failure)
        x = self.values(u)
        g = np.asarray(self.function(x), dtype=float).reshape(-1)
        self.n_runs += g.size
        return g
