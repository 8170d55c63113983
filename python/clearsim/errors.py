"""Exceptions raised by clearsim.

Every error of the Rust core is mapped to one of these classes in one place
(``rust/python/mod.rs``); the Python layer raises the same classes for its own checks.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple


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


def _rebuild_error(cls: "type[ClearsimError]", message: str, info: Dict[str, Any]) -> "ClearsimError":
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
    """The mechanism could not be assembled: Newton's method did not close it from the pose
    given (the pose at t = 0), its constraints are redundant, or following the drivers to the
    start t0 met a dead centre (the message names the joints and drivers, and ``t``)."""


class InterruptedRun(SimulationError):
    """The run was interrupted (Ctrl-C). ``Mechanism.simulate`` returns the partial result with
    a warning instead of raising this."""


class ClusterError(ClearsimError, RuntimeError):
    """Runs lost to the machinery that ran them, not to the mechanism: a worker that died
    (Dask's ``KilledWorker``, a ``BrokenProcessPool``) or a cluster that finished nothing for
    ``timeout`` seconds. ``lost``: ``[(first sample, last sample + 1, reason)]`` of the chunks lost;
    ``finished``: the samples that completed; ``checkpoint``: the directory they are saved in
    (``None``: not saved). A sample whose own run fails is not this: it is counted with its reason."""

    lost: List[Tuple[int, int, str]] = []
    finished: int = 0
    checkpoint: Optional[str] = None


class ReliabilityError(ClearsimError, RuntimeError):
    """A reliability method that cannot give a trustworthy answer on this model (FORM that does
    not converge on a noisy limit state, for example). The message says why and what to use
    instead; ``method`` names the method and ``best`` holds its best point where it has one."""

    method: str = ""
    best: Any = None


class ReliabilityWarning(UserWarning):
    """A reliability answer given with a caveat the user should read (a FORM design point
    accepted at the noise level of the limit state, a Sobol interval wider than 0.2)."""


class PlausibilityWarning(UserWarning):
    """A value that is valid but looks like a mistake: a size in millimetres where clearsim takes
    metres, a viscosity in centipoise where it takes Pa·s, a joint whose two points do not meet at
    the given pose. The run goes on; the message names the element, the field, the value and the
    unit clearsim expected. Silence it with ``warnings.filterwarnings("ignore",
    category=clearsim.PlausibilityWarning)`` when the value is meant."""


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


def check_choice(field: str, value: Any, choices: Sequence[Any], note: str = "") -> Any:
    """``value`` if it is one of ``choices``, else :class:`InputError` naming ``field``, the
    value and the choices (``note`` is appended to the message, e.g. "(there is no default)")."""
    if value not in choices:
        tail = f" {note}" if note else ""
        raise InputError(f"invalid {field} = {value!r}: must be one of {', '.join(map(str, choices))}{tail}", field=field, value=value)
    return value

