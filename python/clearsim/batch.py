"""Batches of runs in the Rust core, the only caller of ``_core.run_batch``: run descriptions
with their settings (on all local cores with the GIL released, in chunks through any
``concurrent.futures``-style executor, or one run a task on Python threads beside other work),
with a progress bar, and tell a failed run (an exception, or a result carrying its error and what
it computed) from a completed one, or turn it into a :class:`clearsim.Result` and its failure.
A run's wall-time budget is its settings' ``max_seconds`` (the core stops it there and keeps
what it computed).

Monitors measured against a reference name it in their settings; the core makes the reference
runs (each distinct one once per batch, ``rust/batch.rs``) from the descriptions and the batch's
one ``nominal`` description, so a task sent to an executor carries only descriptions and settings:
its worker runs the references itself.
"""

from __future__ import annotations

import os
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, as_completed, wait
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

from . import _core
from .errors import InputError, SimulationError

__all__ = ["run_descriptions", "task_threads", "chunk_size_for", "run_chunks", "TIMEOUT", "run_all", "start", "Started", "finish", "progress", "failed", "error_of"]


def run_descriptions(descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], threads: int = 0, nominal: Optional[Dict[str, Any]] = None) -> List[Any]:
    """Run descriptions with their settings in the Rust core on ``threads`` threads (0: all
    local cores), monitors measured against the reference runs they name (``nominal``: the
    nominal design's description, for those measured against its ideal). A pure, picklable
    function: this is what a remote executor runs for a chunk of samples."""
    return _core.run_batch(descriptions, settings, threads, nominal)


def task_threads(threads: Optional[int], executor: Any) -> int:
    """The core's threads for one batch: ``threads`` if given (0: all the machine's cores),
    else all local cores in this process and one per task under an executor (whose workers
    decide the parallelism: a Dask worker of one thread runs one task at a time)."""
    if threads is None:
        return 0 if executor is None else 1
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 0:
        raise InputError(f"invalid threads = {threads!r}: a number of threads ≥ 1 (0: all cores)", field="threads", value=threads)
    return threads


def failed(raw: Any) -> bool:
    """Whether a raw run result is a failure (an exception or a result carrying an error)."""
    return isinstance(raw, BaseException) or raw.get("error") is not None


def error_of(raw: Any) -> Any:
    """The error of a failed raw run result."""
    return raw if isinstance(raw, BaseException) else raw["error"]


def progress(total: int, enabled: bool, what: str, **options: Any) -> Any:
    """A progress bar over ``total`` runs (:func:`clearsim.progress.bar`, with its ``options``)."""
    from .progress import bar

    return bar(total, what, "run", enabled=enabled, **options)


def finish(mechanism: Any, raw: Any, settings: Dict[str, Any]) -> Tuple[Any, Optional[SimulationError]]:
    """A raw run result of ``mechanism`` (a :class:`clearsim.Mechanism`) run with ``settings``
    as ``(result, failure)``: its :class:`clearsim.Result` and ``None`` for a completed run; for
    a run that stopped, the partial result and the :class:`clearsim.SimulationError` saying where
    and why (the same as :meth:`clearsim.Mechanism.simulate` raises). A run that failed before it
    computed anything raises its error."""
    if isinstance(raw, BaseException):
        raise raw
    try:
        return mechanism._finish(raw, settings), None
    except SimulationError as err:
        if getattr(err, "result", None) is None:
            raise
        return err.result, err


#: Seconds a cluster may go without finishing a chunk before a run through an executor stops
#: (:func:`run_chunks`): generous, as one chunk of slow samples can take minutes.
TIMEOUT = 1800.0


def chunk_size_for(total: int, executor: Any, show: bool) -> int:
    """Runs a batch: under an executor a few dozen (spread over its workers; the bar moves as each
    finishes); locally one in-core batch, or, with a bar, large enough that the core's threads
    stay busy to the batch's end (run times vary ±30 % between samples: with 3–6 runs a batch on 2
    threads a quarter of the time was spent waiting for the slowest), small enough for the bar to move."""
    if executor is not None:
        return max(1, min(32, total // 20 or 1))
    if not show:
        return max(1, total)  # one batch: each distinct reference runs once (the core makes them per batch)
    return max(1, min(total, max(16 * (os.cpu_count() or 1), total // 20)))


def run_chunks(
    descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], executor: Any, size: int, nominal: Optional[Dict[str, Any]] = None,
    threads: Optional[int] = None, timeout: Optional[float] = None,
) -> Iterator[Tuple[int, int, Union[List[Any], BaseException]]]:  # fmt: skip
    """Run in chunks of ``size`` and yield ``(start, stop, raws)`` as each chunk finishes:
    locally in order, through an executor with ``submit`` as they complete (one with ``map``
    only: in order). A chunk the machinery lost (a dead worker, a broken pool) yields its
    exception instead of its runs, and the others go on; when no chunk finishes for ``timeout``
    seconds (default :data:`TIMEOUT`) every chunk still out yields a ``TimeoutError``."""
    cores = task_threads(threads, executor)
    bounds = [(i, min(len(descriptions), i + size)) for i in range(0, len(descriptions), max(1, size))]
    if executor is None:
        for a, b in bounds:
            yield a, b, run_descriptions(descriptions[a:b], settings[a:b], cores, nominal)
        return
    if not hasattr(executor, "submit"):
        results = executor.map(run_descriptions, [descriptions[a:b] for a, b in bounds], [settings[a:b] for a, b in bounds], *[len(bounds) * [x] for x in (cores, nominal)])
        for k, (a, b) in enumerate(bounds):
            try:
                yield a, b, list(next(results))
            except Exception as err:  # noqa: BLE001 — the machinery failed: every chunk from here is lost
                for a2, b2 in bounds[k:]:
                    yield a2, b2, err
                return
        return
    limit = TIMEOUT if timeout is None else float(timeout)
    pending = {executor.submit(run_descriptions, descriptions[a:b], settings[a:b], cores, nominal): (a, b) for a, b in bounds}
    while pending:
        done, _ = wait(list(pending), timeout=limit, return_when=FIRST_COMPLETED)
        if not done:
            for fut, (a, b) in sorted(pending.items(), key=lambda item: item[1]):
                fut.cancel()
                yield a, b, TimeoutError(f"no chunk finished in {limit:g} s (timeout)")
            return
        for fut in sorted(done, key=lambda f: pending[f]):
            a, b = pending.pop(fut)
            try:
                raws: Union[List[Any], BaseException] = list(fut.result())
            except BaseException as err:  # noqa: BLE001 — KilledWorker, BrokenProcessPool, CancelledError: the machinery's
                raws = err
            yield a, b, raws


def run_all(
    descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], executor: Any, chunk_size: Optional[int], show: bool, what: str,
    nominal: Optional[Dict[str, Any]] = None, threads: Optional[int] = None,
) -> List[Any]:  # fmt: skip
    """Run in chunks (so a progress bar can move), locally in Rust or through ``executor``, each
    chunk on :func:`task_threads` threads of the core; ``nominal`` as :func:`run_descriptions`."""
    cores = task_threads(threads, executor)
    total = len(descriptions)
    if total == 0:
        return []
    if chunk_size is None:
        chunk_size = chunk_size_for(total, executor, show)
    chunks = [(descriptions[i : i + chunk_size], settings[i : i + chunk_size]) for i in range(0, total, chunk_size)]
    bar = progress(total, show, what)
    out: List[Any] = []
    try:
        if executor is None:
            for d, s in chunks:
                out += run_descriptions(d, s, cores, nominal)
                bar.update(len(d))
        else:
            each = [len(chunks) * [x] for x in (cores, nominal)]
            for res in executor.map(run_descriptions, [c[0] for c in chunks], [c[1] for c in chunks], *each):
                out += list(res)
                bar.update(len(res))
    finally:
        bar.close()
    return out


class Started:
    """Runs started by :func:`start`: one run a task on Python threads (the core releases the
    GIL, so they run in parallel with each other and with Python work in the caller's thread).
    Use it as a context manager: leaving it cancels the runs not yet started and waits for the
    others."""

    def __init__(self, descriptions: Sequence[Dict[str, Any]], settings: Sequence[Dict[str, Any]], threads: Optional[int] = None) -> None:
        workers = max(1, min(len(descriptions), threads or os.cpu_count() or 1))
        self._pool = ThreadPoolExecutor(max_workers=workers)
        # One description a batch: the core runs it in this worker's thread (no pool of its own).
        self._futures: List["Future[List[Any]]"] = [self._pool.submit(run_descriptions, [d], [s], 1) for d, s in zip(descriptions, settings)]

    def results(self, show: bool, what: str, labels: Optional[Sequence[str]] = None) -> List[Any]:
        """Wait for every run, a progress bar moving as each finishes (named by its ``labels``
        entry); the raw results (:func:`failed`, :func:`finish`) in the order of the descriptions."""
        index = {fut: k for k, fut in enumerate(self._futures)}
        out: List[Any] = [None] * len(self._futures)
        bar = progress(len(self._futures), show, what, delay=0.0, leave=True)
        try:
            for fut in as_completed(self._futures):
                k = index[fut]
                out[k] = fut.result()[0]
                if labels is not None:
                    bar.set_postfix_str(labels[k])
                bar.update(1)
        finally:
            bar.close()
        return out

    def close(self) -> None:
        """Cancel the runs not yet started; wait for those running."""
        self._pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self) -> "Started":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def start(descriptions: Sequence[Dict[str, Any]], settings: Sequence[Dict[str, Any]], threads: Optional[int] = None) -> Started:
    """Start ``descriptions`` with their ``settings``, one run a task on ``threads`` Python
    threads (default: the local cores) in the order given (put the longest first), and return
    at once; :meth:`Started.results` collects them. For a few long runs whose progress should
    show run by run, or a batch that goes on in the background while the caller works."""
    if len(descriptions) != len(settings):
        raise InputError(f"invalid settings: {len(settings)} entries for {len(descriptions)} descriptions", field="settings", value=len(settings))
    return Started(descriptions, settings, threads)
