"""What every ``clearsim`` subcommand shares (:mod:`clearsim.cli` and the commands in their own
modules, :mod:`clearsim.sweep_command`): the exit codes, how a failure is named on one line, the
summary a command that stops early leaves behind, and the argument types."""

from __future__ import annotations

import argparse
import contextlib
import math
import time
from pathlib import Path
from typing import Iterator, Sequence, Tuple

from .errors import ClearsimError

#: Exit code of every clearsim error (input, simulation) — the code argparse uses for usage errors.
EXIT_ERROR = 2
#: Exit code of any other failure (a bug in clearsim or a library: ``--debug`` shows where).
EXIT_FAILURE = 1


class OutputsFailed(RuntimeError):
    """A command stopped, or some of its outputs could not be written; what was written and the
    summary naming the failure are on disk.

    ``failed`` lists (output or command, exception); ``files`` the paths written; the first
    exception is the ``__cause__``."""

    def __init__(self, message: str, failed: Sequence[Tuple[str, BaseException]], files: Sequence[Path]) -> None:
        super().__init__(message)
        self.failed = list(failed)
        self.files = list(files)
        self.__cause__ = failed[0][1]


def _describe(err: BaseException) -> str:
    """``Type: message`` on one line (a ClearsimError: its message). An error passed through
    another library with the original traceback in its text (OpenTURNS does that) is named by
    the traceback's last line."""
    text = str(err)
    if "Traceback (most recent call last)" in text:
        last = text.strip().splitlines()[-1]
        return last.split("clearsim.errors.", 1)[-1] if "clearsim.errors." in last else last
    text = " ".join(text.split())
    return text if isinstance(err, ClearsimError) else f"{type(err).__name__}: {text}" if text else type(err).__name__


@contextlib.contextmanager
def _summary_on_failure(out_dir: Path, command: str, summary: str) -> Iterator[None]:
    """If the body fails, write what it had written (files changed since it began) and the
    cause into ``out_dir/summary`` (appended if the command wrote it already), then re-raise
    the failure as :class:`OutputsFailed` (or a ClearsimError as itself, named there too)."""
    began = time.time() - 1.0  # file times are coarse on some file systems
    try:
        yield
    except (Exception, KeyboardInterrupt) as err:
        if not out_dir.is_dir():
            raise
        path = out_dir / summary
        written = sorted(p for p in out_dir.rglob("*") if p.is_file() and p.stat().st_mtime >= began and p != path)
        fresh = not path.exists() or path.stat().st_mtime < began
        lines = [f"# {command} stopped early", ""] if fresh else ["", "## Stopped early", ""]
        lines += [f"Cause: {_describe(err)}", "", "Written before it stopped: " + (", ".join(f"`{p.relative_to(out_dir)}`" for p in written) or "nothing"), ""]
        with path.open("w" if fresh else "a", encoding="utf-8") as fh:
            fh.write("\n".join(lines) + "\n")
        if isinstance(err, (ClearsimError, KeyboardInterrupt)):
            raise
        raise OutputsFailed(f"{command} stopped: {_describe(err)}; {summary} in {out_dir} lists what was written", [(command, err)], written) from err


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive number")
    return value


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive integer")
    return value


__all__ = ["EXIT_ERROR", "EXIT_FAILURE", "OutputsFailed", "_describe", "_positive_float", "_positive_int", "_summary_on_failure"]
