"""Batches of runs in the Rust core, the only caller of ``_core.run_batch``: run descriptions
with their settings (on all local cores with the GIL released, or in chunks through any
``concurrent.futures``-style executor), with a progress bar, and tell a failed run (an exception,
or a result carrying its error and what it computed) from a completed one.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional

from . import _core

__all__ = ["run_descriptions", "run_all", "progress", "failed", "error_of"]


def run_descriptions(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]]) -> List[Any]:
    """Run descriptions with their settings in the Rust core (all local cores). A pure,
    picklable function: this is what a remote executor runs for a chunk of samples."""
    return _core.run_batch(descriptions, settings, 0)


def failed(raw: Any) -> bool:
    """Whether a raw run result is a failure (an exception or a result carrying an error)."""
    return isinstance(raw, BaseException) or raw.get("error") is not None


def error_of(raw: Any) -> Any:
    """The error of a failed raw run result."""
    return raw if isinstance(raw, BaseException) else raw["error"]


def progress(total: int, enabled: bool, what: str) -> Any:
    """A progress bar over ``total`` runs (:func:`clearsim.progress.bar`)."""
    from .progress import bar

    return bar(total, what, "run", enabled=enabled)


def run_all(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], executor: Any, chunk_size: Optional[int], show: bool, what: str) -> List[Any]:
    """Run in chunks (so a progress bar can move), locally in Rust or through ``executor``."""
    total = len(descriptions)
    if total == 0:
        return []
    if chunk_size is None:
        if executor is None:
            # In-core batches: large enough that the threads stay busy to the batch's end (run
            # times vary ±30 % between samples; with 3–6 runs a batch on 2 threads a quarter of
            # the time was spent waiting for the slowest), small enough for the bar to move.
            chunk_size = max(1, min(total, max(16 * (os.cpu_count() or 1), total // 20)))
        else:
            chunk_size = max(1, min(32, total // 20 or 1))  # spread over the executor's workers
    chunks = [(descriptions[i : i + chunk_size], settings[i : i + chunk_size]) for i in range(0, total, chunk_size)]
    bar = progress(total, show, what)
    out: List[Any] = []
    try:
        if executor is None:
            for d, s in chunks:
                out += run_descriptions(d, s)
                bar.update(len(d))
        else:
            for res in executor.map(run_descriptions, [c[0] for c in chunks], [c[1] for c in chunks]):
                out += list(res)
                bar.update(len(res))
    finally:
        bar.close()
    return out
