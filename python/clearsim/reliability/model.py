"""What the reliability methods need of a model: named random inputs and a vectorised
limit-state function ``g`` (failure when ``g ≤ 0``) of one or several failure modes, seen in the
standard normal space of the inputs, and every method on it. :class:`clearsim.reliability.Study`
is such a model built on simulations; :class:`LimitState` wraps any vectorised Python function of
the inputs (used by the tests to check the methods against closed forms).

A model with several modes is a series system: it fails when any mode fails, ``g = min_i g_i``.
"""

from __future__ import annotations

import copy
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..errors import InputError
from .akmcs import ak_is, ak_mcs
from .bridge import ON_FAILURE, check_on_failure
from .distributions import Distribution, as_distribution
from .form import FormResult, SystemFormResult, form, system_form
from .sampling import SamplingResult, importance_sampling, subset
from .sobol import SobolResult, sobol
from .tolerance import ToleranceResult, tolerance

__all__ = ["ReliabilityModel", "LimitState", "ON_FAILURE", "check_on_failure"]


class ReliabilityModel:
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

    # ------------------------------------------------------------------ failure modes
    @property
    def mode_names(self) -> List[str]:
        """The failure modes' names (one for a single limit state)."""
        return ["g"]

    def limit_states(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        """Each mode's limit state at ``u``: ``(N, modes)``."""
        return np.asarray(self.limit_state(u, on_failure), dtype=float).reshape(-1, 1)

    def mode(self, index: Union[int, str]) -> "ReliabilityModel":
        """A view of one failure mode as a model (its runs counted with this one's)."""
        names = self.mode_names
        k = names.index(index) if isinstance(index, str) and index in names else index
        if not isinstance(k, (int, np.integer)) or not 0 <= int(k) < len(names):
            raise InputError(f"invalid mode = {index!r}: one of {', '.join(names)} or its index", field="mode", value=index)
        if len(names) == 1:
            return self
        return _Mode(self, int(k))

    # ------------------------------------------------------------------ methods
    def form(self, *, start: Optional[Sequence[float]] = None, step: Union[float, str] = "auto", max_iterations: int = 50, on_failure: str = "fail", mirror: bool = True) -> Any:
        """FORM: design point, Hasofer–Lind β, p_f ≈ Φ(−β) and importance factors
        (:func:`clearsim.reliability.form.form`); on a series system FORM per mode and the
        system's first-order probability with Ditlevsen's bounds (a
        :class:`~clearsim.reliability.form.SystemFormResult`). ``step``: the gradient step in u,
        ``"auto"`` (from the limit state's measured noise) or a number. ``mirror``: also look on
        the other side of the mean point (a limit state failing on both sides, as against the
        nominal design); a second design point found there makes the answer a series system of
        the two."""
        if len(self.mode_names) > 1:
            if start is not None:
                raise InputError("invalid start: a series system runs FORM per mode from the mean point", field="start", value=start)
            return system_form(self, step=step, max_iterations=max_iterations, on_failure=on_failure, mirror=mirror)
        return form(self, start=start, step=step, max_iterations=max_iterations, on_failure=on_failure, mirror=mirror)

    def importance_sampling(self, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0, *, design_point: Any = None, block: int = 64, on_failure: str = "fail", step: Union[float, str] = "auto") -> SamplingResult:
        """Importance sampling around the FORM design point(s) until the estimate's coefficient
        of variation reaches ``cov`` (or ``max_runs``). See
        :func:`clearsim.reliability.sampling.importance_sampling`."""
        return importance_sampling(self, cov=cov, max_runs=max_runs, seed=seed, design_point=design_point, block=block, on_failure=on_failure, step=step)

    def subset(self, seed: Optional[int] = 0, *, n_per_level: int = 1000, conditional_probability: float = 0.1, on_failure: str = "fail") -> SamplingResult:
        """Subset simulation (OpenTURNS). See :func:`clearsim.reliability.sampling.subset`."""
        return subset(self, seed=seed, n_per_level=n_per_level, conditional_probability=conditional_probability, on_failure=on_failure)

    def sobol(self, n: int, seed: Optional[int] = 0, *, on_failure: str = "fail", method: str = "saltelli") -> SobolResult:
        """First-order and total Sobol indices of the limit-state value: ``method="saltelli"``
        (``n × (d + 2)`` runs) or ``"pce"`` (polynomial chaos on ``n`` runs). See
        :func:`clearsim.reliability.sobol.sobol`."""
        return sobol(self, n, seed=seed, on_failure=on_failure, method=method)

    def tolerance(self, name: str, reliability: float, *, bracket: Optional[Tuple[float, float]] = None, cov: float = 0.1, max_runs: int = 20000, seed: Optional[int] = 0, step: Union[float, str] = "auto") -> ToleranceResult:
        """The largest mean of input ``name`` (its spread kept) for which the reliability is
        still ``reliability``. See :func:`clearsim.reliability.tolerance.tolerance`."""
        return tolerance(self, name, reliability, bracket=bracket, cov=cov, max_runs=max_runs, seed=seed, step=step)

    def ak_mcs(self, max_runs: int = 150, seed: Optional[int] = 0, *, cov: float = 0.05, population: int = 10_000, max_population: int = 100_000_000,
               covariance: str = "matern52", noise: Union[float, str] = "auto", on_failure: str = "fail") -> SamplingResult:  # fmt: skip
        """AK-MCS (Echard et al. 2011): p_f from a Kriging surrogate trained on at most
        ``max_runs`` runs, on a Monte Carlo population grown until its CoV is ``cov``; one
        surrogate per mode on a series system. See :func:`clearsim.reliability.akmcs.ak_mcs`."""
        return ak_mcs(self, max_runs=max_runs, seed=seed, cov=cov, population=population, max_population=max_population, covariance=covariance, noise=noise, on_failure=on_failure)

    def ak_is(self, max_runs: int = 150, seed: Optional[int] = 0, *, cov: float = 0.05, population: int = 10_000, max_population: int = 1_000_000,
              covariance: str = "matern52", design_point: Any = None, on_failure: str = "fail", step: Union[float, str] = "auto") -> SamplingResult:  # fmt: skip
        """AK-IS (Echard et al. 2013): AK-MCS on an importance-sampling population around the
        FORM design point, for rare events; FORM's runs count and start the surrogate. See
        :func:`clearsim.reliability.akmcs.ak_is`."""
        return ak_is(self, max_runs=max_runs, seed=seed, cov=cov, population=population, max_population=max_population, covariance=covariance, design_point=design_point, on_failure=on_failure, step=step)

    def with_input(self, name: str, value: Any) -> "ReliabilityModel":
        """A copy with input ``name`` replaced (caches shared, run count kept)."""
        if name not in self.inputs:
            raise InputError(f"invalid input {name!r}: not an input (known: {', '.join(self.inputs)})", field="name", value=name)
        other = copy.copy(self)
        other._set_inputs({**self.inputs, name: value})
        return other


class LimitState(ReliabilityModel):
    """Any vectorised limit-state function of named inputs.

    ``LimitState(lambda x: 3.0 - x["a"] - x["b"], {"a": Normal(0, 1), "b": Normal(0, 1)})``:
    ``function`` takes ``{name: (N,) array}`` and returns ``(N,)`` values of ``g``; failure when
    ``g ≤ 0``. With ``modes=["A", "B"]`` (or a number of modes) the function returns one array
    per mode (a sequence, or ``(N, modes)``): a series system."""

    def __init__(self, function: Callable[[Dict[str, np.ndarray]], Any], inputs: Mapping[str, Any], modes: Union[None, int, Sequence[str]] = None) -> None:
        if not callable(function):
            raise InputError(f"invalid function = {function!r}: must be callable", field="function", value=function)
        self.function = function
        self._set_inputs(inputs)
        self._counter = [0]
        if modes is None:
            self._modes = ["g"]
        elif isinstance(modes, (int, np.integer)) and not isinstance(modes, bool):
            if modes < 1:
                raise InputError(f"invalid modes = {modes!r}: at least 1", field="modes", value=modes)
            self._modes = [f"g{i + 1}" for i in range(int(modes))]
        else:
            self._modes = [str(m) for m in modes]  # type: ignore[union-attr]
            if not self._modes:
                raise InputError("invalid modes = []: at least one", field="modes", value=modes)

    @property
    def mode_names(self) -> List[str]:
        return list(self._modes)

    def limit_states(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        check_on_failure(on_failure)
        x = self.values(u)
        n = next(iter(x.values())).size if x else np.atleast_2d(u).shape[0]
        out = self.function(x)
        if len(self._modes) == 1:
            g = np.asarray(out, dtype=float).reshape(-1, 1)
        elif isinstance(out, np.ndarray) and out.ndim == 2:
            g = np.asarray(out, dtype=float).reshape(n, len(self._modes))
        else:
            g = np.column_stack([np.asarray(v, dtype=float).reshape(-1) for v in out])
        if g.shape != (n, len(self._modes)):
            raise InputError(f"invalid function: returned {g.shape} values for {n} points and {len(self._modes)} modes", field="function", value=g.shape)
        self.n_runs += n
        return g

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        return np.min(self.limit_states(u, on_failure), axis=1)


class _Mode(ReliabilityModel):
    """One failure mode of a model with several, seen as a model (runs counted on the parent)."""

    def __init__(self, parent: ReliabilityModel, index: int) -> None:
        self.parent = parent
        self.index = index
        self.inputs = parent.inputs
        self.random_names = parent.random_names
        self._counter = parent._counter

    @property
    def mode_names(self) -> List[str]:
        return [self.parent.mode_names[self.index]]

    def limit_state(self, u: Any, on_failure: str = "fail") -> np.ndarray:
        return np.asarray(self.parent.limit_states(u, on_failure)[:, self.index], dtype=float)

    def with_input(self, name: str, value: Any) -> "ReliabilityModel":
        return _Mode(self.parent.with_input(name, value), self.index)

