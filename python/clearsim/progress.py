"""Progress bars: one place, one switch.

Every long run and batch of clearsim (``Mechanism.simulate``, Monte Carlo, ``reliability.Study``,
scenes, ``clearsim paper``) shows its progress through :func:`bar`: a text bar with elapsed time,
rate and an estimate of the time left in a terminal, a widget in Jupyter when ipywidgets is
installed (the text bar, without a warning, when it is not). A bar comes into being only once
its run has lasted :data:`DELAY` (a second): a shorter run creates nothing, prints nothing and
leaves no widget in a notebook; a bar that goes away when done (``leave=False``, the default)
closes every widget it opened.

Silence them all with :func:`set_progress` (``clearsim.set_progress(False)``) or the environment
variable ``CLEARSIM_PROGRESS=0``; the ``progress=`` argument of each call silences one call.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any, Optional

_enabled: Optional[bool] = None  # None: follow CLEARSIM_PROGRESS
#: Seconds of wall time before a bar appears (``bar(delay=None)``): shorter runs print nothing.
DELAY = 1.0


#: Seconds between redraws of a text bar written into a file or a pipe.
NON_TTY_INTERVAL = 15.0


def _is_terminal() -> bool:
    """Whether stderr (where the text bars go) is a terminal."""
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):  # closed or replaced stream
        return False


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


def bar_class() -> Any:
    """The tqdm class a bar is drawn with: the notebook widget in a Jupyter kernel (not a Qt
    console or Spyder) when ipywidgets is importable, else the text bar. Unlike ``tqdm.auto``
    it says nothing when ipywidgets is missing."""
    from tqdm.std import tqdm as text

    if "ipykernel.zmqshell" not in sys.modules or any(k == "QT_API" or k.startswith("SPYDER") for k in os.environ):
        return text
    try:
        from tqdm import notebook
    except Exception:  # noqa: BLE001 — any trouble with the widgets: the text bar
        return text
    return notebook.tqdm if getattr(notebook, "IProgress", None) is not None else text


def _close_widgets(widget: Any) -> None:
    """Close a widget, its children and their layout and style models (``Widget.close`` closes
    one model: a tqdm notebook bar is eleven)."""
    for child in getattr(widget, "children", ()) or ():
        _close_widgets(child)
    for part in ("layout", "style"):
        sub = getattr(widget, part, None)
        if sub is not None and hasattr(sub, "close"):
            sub.close()
    if hasattr(widget, "close"):
        widget.close()


class Bar:
    """A progress bar over ``total`` units (``None``: a count, no end known) that exists only once shown: it counts (``n``,
    ``update``) from its creation and opens the tqdm bar (with the elapsed time, rate and time
    left counted from its creation) at the first update after ``delay`` seconds. Use it as a
    context manager or call :meth:`close`."""

    def __init__(self, total: Optional[float], desc: str, unit: str, *, enabled: bool, delay: float, leave: bool, unit_scale: bool) -> None:
        self.total = total
        self.n: float = 0
        self.delay = delay
        self.desc, self.unit, self.leave, self.unit_scale = desc, unit, leave, unit_scale
        self.disable = not enabled
        self._postfix: Optional[str] = None
        self._born = time.time()
        self._shown: Any = None
        if self.disable is False and delay <= 0:
            self._open()

    def _open(self) -> Any:
        cls = bar_class()
        # A delay > 0 draws nothing before the first update (no empty bar first); counted from
        # the bar's creation, as the rate and the time left are, it has passed already.
        # Into a log or a pipe (stderr not a terminal) a text bar redraws every NON_TTY_INTERVAL
        # seconds, not ten times a second: a 15 s run leaves a line or two, not 150 redraws.
        every = {} if _is_terminal() or cls.__module__ != "tqdm.std" else {"mininterval": NON_TTY_INTERVAL}
        shown = cls(total=self.total, desc=self.desc, unit=self.unit, unit_scale=self.unit_scale, leave=self.leave, delay=max(self.delay, 1e-9), **every)
        shown.start_t = shown.last_print_t = self._born
        if self._postfix is not None:
            shown.set_postfix_str(self._postfix, refresh=False)
        if self.n:
            shown.update(self.n)
        if self.delay <= 0:
            shown.refresh()  # at once, as asked
        self._shown = shown
        return shown

    @property
    def shown(self) -> bool:
        """Whether the bar has been drawn (a run longer than ``delay``)."""
        return self._shown is not None

    def update(self, n: float = 1) -> None:
        """Advance by ``n`` units (drawn once ``delay`` seconds have passed)."""
        self.n += n
        if self.disable:
            return
        if self._shown is None:
            if time.time() - self._born >= self.delay:
                self._open()
            return
        if self._shown.total != self.total:
            self._shown.total = self.total
        self._shown.update(n)

    def set_postfix_str(self, text: str = "", refresh: bool = True) -> None:
        """Text after the bar (e.g. the run that finished last)."""
        self._postfix = str(text)
        if self._shown is not None:
            self._shown.set_postfix_str(self._postfix, refresh=refresh)

    def refresh(self) -> None:
        """Redraw (after a change of ``total``)."""
        if self._shown is not None:
            self._shown.total = self.total
            self._shown.refresh()

    def close(self) -> None:
        """Close the bar: a notebook bar that goes away when done closes every widget model
        it opened; one that stays (``leave=True``) keeps them, so it still shows."""
        shown, self._shown = self._shown, None
        if shown is None:
            return
        shown.close()
        container = getattr(shown, "container", None)
        if container is not None and not self.leave:
            _close_widgets(container)

    def __enter__(self) -> "Bar":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def bar(total: Optional[float], desc: str, unit: str = "run", *, enabled: bool = True, delay: Optional[float] = None, leave: bool = False, unit_scale: bool = False) -> Bar:
    """A progress bar over ``total`` units (runs, or simulated seconds with ``unit="s"``) with
    an estimate of the time left (``None``: a count with its rate, no end known), shown after ``delay`` seconds (``None``: :data:`DELAY`); a
    disabled bar when ``enabled`` is false or bars are switched off. Use it as a context
    manager; ``update(n)`` advances it. Nothing is created (no widget in a notebook) for a run
    shorter than the delay."""
    wait = DELAY if delay is None else delay
    return Bar(total, desc, unit, enabled=enabled and progress_enabled(), delay=wait, leave=leave, unit_scale=unit_scale)


__all__ = ["Bar", "bar", "bar_class", "progress_enabled", "set_progress"]
