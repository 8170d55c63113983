"""Exceptions raised by clearsim.

Every error of the Rust core is mapped to one of these classes in one place
(``rust/python.rs``); the Python layer raises the same classes for its own checks.
"""

from __future__ import annotations

from typing import Any, Dict, Optional


class ClearsimError(Exception):
    """Base class of every clearsim error."""

    def __init__(self, message: str, **info: Any) -> None:
        super().__init__(message)
        self.reason: str = info.pop("reason", message)
        for key, value in info.items():
            setattr(self, key, value)

    def __reduce__(self) -> Any:
        # Pickle with the keyword details (field, value, t, result, ...), which the default
        # exception pickling would drop.
        return (_rebuild_error, (self.__class__, self.args[0] if self.args else "", dict(self.__dict__)))


def _rebuild_error(cls: type, message: str, info: Dict[str, Any]) -> "ClearsimError":
    err = cls.__new__(cls)
    Exception.__init__(err, message)
    err.__dict__.update(info)
    return err


class InputError(ClearsimError, ValueError):
    """A field of a mechanism, scene or run has a value it cannot take.

    Attributes: ``field`` (dotted name of the field) and ``value`` (as given).
    """

    field: str
    value: Any

    def __init__(self, message: str, field: str = "", value: Any = None, **info: Any) -> None:
        super().__init__(message, field=field, value=value, **info)


class SimulationError(ClearsimError, RuntimeError):
    """A run that could not go on (step-size underflow, non-finite state, singular Jacobian).

    Attributes: ``t`` (time of the failure [s]), ``reason`` (the full diagnosis), ``joint`` and
    ``eccentricity`` (the clearance joint nearest contact and its ε = e/c, when there is one),
    and ``result`` (a :class:`clearsim.Result` with everything computed before the failure).
    """

    t: Optional[float] = None
    joint: Optional[str] = None
    eccentricity: Optional[float] = None
    result: Any = None


class AssemblyError(SimulationError):
    """Newton's method could not assemble the mechanism from the given poses at t0."""


class InterruptedRun(SimulationError):
    """The run was interrupted (Ctrl-C). ``Mechanism.simulate`` returns the partial result with
    a warning instead of raising this."""


def check_finite(field: str, value: Any) -> float:
    """``float(value)``, or :class:`InputError` naming ``field`` if it is not a finite number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"invalid {field} = {value!r}: must be a number", field=field, value=value) from None
    if v != v or v in (float("inf"), float("-inf")):
        raise InputError(f"invalid {field} = {value!r}: must be a finite number", field=field, value=value)
    return v


def check_positive(field: str, value: Any) -> float:
    v = check_finite(field, value)
    if v <= 0.0:
        raise InputError(f"invalid {field} = {value!r}: must be positive", field=field, value=value)
    return v
