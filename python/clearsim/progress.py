"""Progress bars: one place, one switch.

Every long run and batch of clearsim (``Mechanism.simulate``, Monte Carlo, ``reliability.Study``,
scenes, ``clearsim paper``) shows its progress through :func:`bar`: a ``tqdm.auto`` bar, which is a
text bar with elapsed time, rate and an estimate of the time left in a terminal and a widget in
Jupyter. Bars appear only after a second, so short runs print nothing.

Silence them all with :func:`set_progress` (``clearsim.set_progress(False)``) or the environment
variable ``CLEARSIM_PROGRESS=0``; the ``progress=`` argument of each call silences one call.
"""

from __future__ import annotations

import os
from typing import Any, Optional

_enabled: Optional[bool] = None  # None: follow CLEARSIM_PROGRESS
#: Seconds of wall time before a bar appears (``bar(delay=None)``): shorter runs print nothing.
DELAY = 1.0


def set_progress(enabled: bool) -> None:
    """Show (``True``) or hide (``False``) every clearsim progress bar from now on, overriding
    the ``CLEARSIM_PROGRESS`` environment variable."""
    global _enabled
    _enabled = bool(enabled)


def progress_enabled() -> bool:
    """Whether progress bars are shown: :func:`set_progress` if called, else
    ``CLEARSIM_PROGRESS`` (``0``, ``false``, ``no`` or ``off`` hide them), else ``True``."""
    if _enabled is not None:
        return _enabled
    return os.environ.get("CLEARSIM_PROGRESS", "1").strip().lower() not in ("0", "false", "no", "off")


def bar(total: Optional[float], desc: str, unit: str = "run", *, enabled: bool = True, delay: Optional[float] = None, leave: bool = False, unit_scale: bool = False) -> Any:
    """A progress bar over ``total`` units (runs, or simulated seconds with ``unit="s"``) with
    an estimate of the time left (``None``: a count with its rate, no end known), shown after ``delay`` seconds (``None``: :data:`DELAY`); a
    disabled bar when ``enabled`` is false or bars are switched off. Use it as a context
    manager; ``update(n)`` advances it."""
    from tqdm.auto import tqdm

    wait = DELAY if delay is None else delay
    return tqdm(total=total, desc=desc, unit=unit, unit_scale=unit_scale, delay=wait, leave=leave, disable=not (enabled and progress_enabled()))


__all__ = ["bar", "progress_enabled", "set_progress"]
