"""Random inputs of a reliability study, backed by ``scipy.stats``.

Each input is a :class:`Distribution`: the named shortcuts (:class:`Normal`, :class:`Uniform`,
:class:`LogNormal`, :class:`TruncatedNormal`, :class:`Fixed`) check their parameters and name the
field at fault; any frozen ``scipy.stats`` distribution (``scipy.stats.weibull_min(2, scale=…)``)
is accepted as it is. The studies work with the inverse CDF (``ppf``): an input is the image of
a standard normal variable ``u`` under ``x = F⁻¹(Φ(u))`` (independent inputs), which is how FORM,
importance sampling and subset simulation see them.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np

from ..errors import InputError, check_finite
from ..lazy import lazy

special = lazy("scipy.special")
stats = lazy("scipy.stats")

__all__ = [
    "Distribution",
    "Fixed",
    "LogNormal",
    "Normal",
    "Scipy",
    "Shifted",
    "TruncatedNormal",
    "Uniform",
    "as_distribution",
    "sample_inputs",
]


class Distribution:
    """A random input. Subclasses give :attr:`dist`, a frozen ``scipy.stats`` distribution
    (``None`` for a deterministic value)."""

    @property
    def dist(self) -> Any:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def random(self) -> bool:
        """Whether the input varies (a :class:`Fixed` value or a zero spread does not)."""
        d = self.dist
        return d is not None and float(d.std()) > 0.0

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        """``n`` independent draws."""
        n = _check_n(n)
        return self.ppf(rng.random(n)) if self.random else np.full(n, self.nominal)

    def ppf(self, p: Any) -> np.ndarray:
        """Inverse CDF at probabilities ``p``."""
        d = self.dist
        return np.full(np.shape(p), self.nominal) if d is None else np.asarray(d.ppf(p), dtype=float)

    def from_standard_normal(self, u: Any) -> np.ndarray:
        """``F⁻¹(Φ(u))``: the input value for the standard normal variable ``u`` (tails kept
        accurate by working on the side of the smaller probability)."""
        u = np.asarray(u, dtype=float)
        d = self.dist
        if d is None or not self.random:
            return np.full(u.shape, self.nominal)
        lower = np.asarray(d.ppf(special.ndtr(np.minimum(u, 0.0))), dtype=float)
        upper = np.asarray(d.isf(special.ndtr(-np.maximum(u, 0.0))), dtype=float)
        return np.where(u <= 0.0, lower, upper)

    def to_standard_normal(self, x: Any) -> np.ndarray:
        """``Φ⁻¹(F(x))``, the inverse of :meth:`from_standard_normal`."""
        x = np.asarray(x, dtype=float)
        d = self.dist
        if d is None or not self.random:
            return np.zeros(x.shape)
        return np.where(x <= d.median(), special.ndtri(d.cdf(x)), -special.ndtri(d.sf(x)))

    @property
    def nominal(self) -> float:
        """The mean value [input's unit]."""
        return float(self.dist.mean())

    @property
    def spread(self) -> float:
        """The standard deviation [input's unit] (0 for a fixed value)."""
        d = self.dist
        return 0.0 if d is None else float(d.std())

    def with_mean(self, value: float) -> "Distribution":
        """The same distribution moved so that its mean is ``value`` (tolerance design keeps the
        spread and moves the nominal value)."""
        return Shifted(self, float(value) - self.nominal)


def _nonneg(field_name: str, value: Any) -> float:
    v = check_finite(field_name, value)
    if v < 0.0:
        raise InputError(f"invalid {field_name} = {value!r}: must not be negative", field=field_name, value=value)
    return v


def _check_n(n: Any) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"invalid n = {n!r}: must be a positive integer", field="n", value=n)
    return int(n)


@dataclass(frozen=True)
class Fixed(Distribution):
    """A deterministic value (every draw equals ``value``)."""

    value: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", check_finite("Fixed.value", self.value))

    @property
    def dist(self) -> Any:
        return None

    @property
    def nominal(self) -> float:
        return self.value

    def with_mean(self, value: float) -> "Distribution":
        return Fixed(value)


@dataclass(frozen=True)
class Normal(Distribution):
    """Normal distribution with mean ``mean`` and standard deviation ``std`` (≥ 0), in the
    input's unit."""

    mean: float
    std: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mean", check_finite("Normal.mean", self.mean))
        object.__setattr__(self, "std", _nonneg("Normal.std", self.std))

    @property
    def dist(self) -> Any:
        return stats.norm(self.mean, self.std) if self.std > 0 else None

    @property
    def nominal(self) -> float:
        return self.mean

    def with_mean(self, value: float) -> "Distribution":
        return Normal(value, self.std)

    def from_standard_normal(self, u: Any) -> np.ndarray:
        """``mean + std u``: exact at any ``u`` (Φ(u) rounds to 0 or 1 beyond |u| ≈ 38)."""
        u = np.asarray(u, dtype=float)
        return self.mean + self.std * u if self.std > 0 else np.full(u.shape, self.mean)


@dataclass(frozen=True)
class Uniform(Distribution):
    """Uniform distribution on ``[low, high)`` (low < high)."""

    low: float
    high: float

    def __post_init__(self) -> None:
        lo = check_finite("Uniform.low", self.low)
        hi = check_finite("Uniform.high", self.high)
        if not lo < hi:
            raise InputError(f"invalid Uniform.low = {self.low!r}: must be below Uniform.high = {self.high!r}", field="Uniform.low", value=self.low)
        object.__setattr__(self, "low", lo)
        object.__setattr__(self, "high", hi)

    @property
    def dist(self) -> Any:
        return stats.uniform(self.low, self.high - self.low)

    def with_mean(self, value: float) -> "Distribution":
        half = 0.5 * (self.high - self.low)
        return Uniform(value - half, value + half)


@dataclass(frozen=True)
class LogNormal(Distribution):
    """Log-normal distribution given by the mean (> 0) and standard deviation of the variable
    itself (not of its logarithm): ``σ_ln² = ln(1 + (std/mean)²)``, ``μ_ln = ln(mean) − σ_ln²/2``.
    Suits strictly positive inputs such as clearances and viscosities."""

    mean: float
    std: float

    def __post_init__(self) -> None:
        m = check_finite("LogNormal.mean", self.mean)
        if m <= 0.0:
            raise InputError(f"invalid LogNormal.mean = {self.mean!r}: must be positive", field="LogNormal.mean", value=self.mean)
        object.__setattr__(self, "mean", m)
        object.__setattr__(self, "std", _nonneg("LogNormal.std", self.std))

    @property
    def log_params(self) -> Tuple[float, float]:
        """``(μ_ln, σ_ln)`` of ln X."""
        s2 = math.log1p((self.std / self.mean) ** 2)
        return math.log(self.mean) - 0.5 * s2, math.sqrt(s2)

    @property
    def dist(self) -> Any:
        mu, s = self.log_params
        return stats.lognorm(s, scale=math.exp(mu)) if s > 0 else None

    @property
    def nominal(self) -> float:
        return self.mean

    def with_mean(self, value: float) -> "Distribution":
        return LogNormal(value, self.std)

    def from_standard_normal(self, u: Any) -> np.ndarray:
        """``exp(μ_ln + σ_ln u)``: exact at any ``u`` (Φ(u) rounds to 0 or 1 beyond |u| ≈ 38)."""
        u = np.asarray(u, dtype=float)
        mu, s = self.log_params
        return np.exp(mu + s * u) if s > 0 else np.full(u.shape, self.mean)


@dataclass(frozen=True)
class TruncatedNormal(Distribution):
    """Normal distribution ``N(mean, std²)`` restricted to ``[low, high]``.

    ``mean`` and ``std`` are those of the parent (untruncated) normal, as in
    ``scipy.stats.truncnorm``; the truncated variable's own mean and std differ unless the bounds
    are far away (:attr:`dist` gives them).
    """

    mean: float
    std: float
    low: float
    high: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mean", check_finite("TruncatedNormal.mean", self.mean))
        s = check_finite("TruncatedNormal.std", self.std)
        if s <= 0.0:
            raise InputError(f"invalid TruncatedNormal.std = {self.std!r}: must be positive", field="TruncatedNormal.std", value=self.std)
        object.__setattr__(self, "std", s)
        lo, hi = float(self.low), float(self.high)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise InputError(
                f"invalid TruncatedNormal.low = {self.low!r}: must be below TruncatedNormal.high = {self.high!r}",
                field="TruncatedNormal.low", value=self.low,
            )  # fmt: skip
        a, b = (lo - self.mean) / s, (hi - self.mean) / s
        if not (special.ndtr(b) - special.ndtr(a) > 0.0 or special.ndtr(-a) - special.ndtr(-b) > 0.0):
            raise InputError(
                f"invalid TruncatedNormal.low = {self.low!r}: the interval [{self.low!r}, {self.high!r}] has no probability under N({self.mean!r}, {self.std!r}²)",
                field="TruncatedNormal.low", value=self.low,
            )  # fmt: skip
        object.__setattr__(self, "low", lo)
        object.__setattr__(self, "high", hi)

    @property
    def dist(self) -> Any:
        return stats.truncnorm((self.low - self.mean) / self.std, (self.high - self.mean) / self.std, loc=self.mean, scale=self.std)

    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        # Inverse CDF on the side of the smaller tail, so that far tails keep their precision.
        return self.from_standard_normal(rng.standard_normal(_check_n(n)))

    def with_mean(self, value: float) -> "Distribution":
        shift = float(value) - float(self.dist.mean())
        return TruncatedNormal(self.mean + shift, self.std, self.low + shift, self.high + shift)


@dataclass(frozen=True)
class Scipy(Distribution):
    """Any frozen ``scipy.stats`` continuous distribution, e.g.
    ``Scipy(scipy.stats.weibull_min(1.5, scale=2e-4))``; plain frozen distributions passed as
    inputs are wrapped in it."""

    frozen: Any

    def __post_init__(self) -> None:
        if not (hasattr(self.frozen, "ppf") and hasattr(self.frozen, "cdf") and hasattr(self.frozen, "std")):
            raise InputError(f"invalid distribution {self.frozen!r}: expected a frozen scipy.stats distribution", field="distribution", value=self.frozen)
        if not math.isfinite(float(self.frozen.mean())) or not math.isfinite(float(self.frozen.std())):
            raise InputError(f"invalid distribution {self.frozen!r}: its mean and standard deviation must be finite", field="distribution", value=self.frozen)

    @property
    def dist(self) -> Any:
        return self.frozen


@dataclass(frozen=True)
class Shifted(Distribution):
    """``base`` moved by ``offset`` (in the input's unit)."""

    base: Distribution
    offset: float

    @property
    def dist(self) -> Any:
        d = self.base.dist
        return None if d is None else _ShiftedFrozen(d, self.offset)

    @property
    def nominal(self) -> float:
        return self.base.nominal + self.offset

    def with_mean(self, value: float) -> "Distribution":
        return Shifted(self.base, float(value) - self.base.nominal)


class _ShiftedFrozen:
    """The part of a frozen scipy distribution's interface the studies use, moved by ``offset``."""

    def __init__(self, d: Any, offset: float) -> None:
        self.d, self.o = d, offset

    def ppf(self, p: Any) -> Any:
        return self.d.ppf(p) + self.o

    def isf(self, p: Any) -> Any:
        return self.d.isf(p) + self.o

    def cdf(self, x: Any) -> Any:
        return self.d.cdf(np.asarray(x) - self.o)

    def sf(self, x: Any) -> Any:
        return self.d.sf(np.asarray(x) - self.o)

    def median(self) -> float:
        return float(self.d.median()) + self.o

    def mean(self) -> float:
        return float(self.d.mean()) + self.o

    def std(self) -> float:
        return float(self.d.std())


def as_distribution(name: str, value: Any) -> Distribution:
    """An input given as a :class:`Distribution`, a frozen ``scipy.stats`` distribution or a
    number (:class:`Fixed`)."""
    if isinstance(value, Distribution):
        return value
    if hasattr(value, "ppf") and hasattr(value, "rvs"):
        return Scipy(value)
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InputError(
            f"invalid inputs[{name!r}] = {value!r}: give a number, a clearsim.reliability distribution or a frozen scipy.stats distribution",
            field=f"inputs.{name}", value=value,
        )  # fmt: skip
    return Fixed(check_finite(f"inputs[{name!r}]", value))


def input_stream(seed: Optional[int], name: str) -> np.random.Generator:
    """The random stream of one named input: seeded by ``(seed, crc32(name))``, so the samples of
    an input do not depend on the order of the inputs or on which others are present."""
    if seed is None:
        base = int(np.random.SeedSequence().entropy)  # type: ignore[arg-type]
    else:
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise InputError(f"invalid seed = {seed!r}: must be a non-negative integer", field="seed", value=seed)
        base = int(seed)
    return np.random.default_rng([base, zlib.crc32(str(name).encode("utf-8"))])


def sample_inputs(distributions: Mapping[str, Union[Distribution, float]], n: int, seed: Optional[int] = None) -> Dict[str, np.ndarray]:
    """Draw ``n`` independent samples of each named random input.

    Each name gets its own random stream (:func:`input_stream`), so common random numbers carry
    across studies. Plain numbers are taken as :class:`Fixed`.

    Returns ``{name: array of shape (n,)}``, in the units of the distributions.
    """
    n = _check_n(n)
    if seed is None:
        entropy = np.random.SeedSequence().entropy
        assert isinstance(entropy, int)  # a fresh SeedSequence draws one int
        seed = entropy % (2**63)
    return {name: as_distribution(name, dist).sample(n, input_stream(seed, name)) for name, dist in distributions.items()}
