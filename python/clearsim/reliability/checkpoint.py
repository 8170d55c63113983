"""The sample loop's runs as chunks finish: through any executor (the progress bar moves per
finished chunk, not per 1 024 samples), saved to a checkpoint directory that the same call
resumes from (only the missing samples run again), and runs lost to the machinery — a dead
worker, a broken pool, a cluster that finishes nothing for ``timeout`` seconds — told apart from
samples whose own run fails: a :class:`clearsim.ClusterError` naming the chunks lost, what
finished and how to resume.

A checkpoint directory holds one small file a finished chunk (``chunk_<first>_<end>.pkl``: each
sample's number, a digest of its description and run settings, and its raw result, failures with
their reasons included), written to a temporary name and renamed, so a file is whole or absent.
A stored sample is used only where its digest matches the sample asked for: a changed study
reruns what changed, and a resumed run equals an uninterrupted one bit for bit (the samples are
reproducible by position).
"""

from __future__ import annotations

import hashlib
import os
import pickle
import re
import tempfile
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from ..batch import chunk_size_for, run_chunks
from ..errors import ClusterError, InputError

__all__ = ["Checkpoint", "run_jobs"]

_NAME = re.compile(r"^chunk_(\d+)_(\d+)\.pkl$")


class Checkpoint:
    """Finished chunks of samples in directory ``path`` (made if missing)."""

    def __init__(self, path: Any) -> None:
        self.path = os.fspath(path)
        try:
            os.makedirs(self.path, exist_ok=True)
        except OSError as err:
            raise InputError(f"invalid checkpoint = {self.path!r}: cannot make the directory ({err})", field="checkpoint", value=self.path) from None

    @staticmethod
    def digest(description: Dict[str, Any], settings: Dict[str, Any]) -> bytes:
        """What a sample's run depends on: its description and run settings."""
        return hashlib.sha256(pickle.dumps((description, settings), protocol=4)).digest()

    def load(self, first: int, end: int) -> Dict[int, Tuple[bytes, Any]]:
        """``{sample: (digest, raw result)}`` stored for samples ``first`` … ``end − 1``."""
        found: Dict[int, Tuple[bytes, Any]] = {}
        for name in sorted(os.listdir(self.path)):
            m = _NAME.match(name)
            if m is None or int(m.group(2)) <= first or int(m.group(1)) >= end:
                continue
            try:
                with open(os.path.join(self.path, name), "rb") as f:
                    stored = pickle.load(f)
            except (OSError, pickle.UnpicklingError, EOFError):
                continue  # unreadable: its samples run again
            for k, key, raw in zip(stored["samples"], stored["digests"], stored["raws"]):
                if first <= k < end:
                    found[k] = (key, raw)
        return found

    def save(self, samples: Sequence[int], digests: Sequence[bytes], raws: Sequence[Any]) -> None:
        """Store a finished chunk (atomically: a temporary file renamed)."""
        name = f"chunk_{min(samples):09d}_{max(samples) + 1:09d}.pkl"
        fd, tmp = tempfile.mkstemp(dir=self.path, prefix=".chunk_", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                pickle.dump({"samples": list(samples), "digests": list(digests), "raws": list(raws)}, f, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, os.path.join(self.path, name))
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise


def run_jobs(
    samples: Sequence[int], descriptions: List[Dict[str, Any]], settings: List[Dict[str, Any]], *, executor: Any, chunk_size: Optional[int],
    nominal: Optional[Dict[str, Any]], threads: Optional[int], show: bool, on_done: Callable[[int], None], store: Optional[Checkpoint] = None,
    timeout: Optional[float] = None, finished_before: int = 0,
) -> List[Any]:  # fmt: skip
    """The raw results of samples ``samples`` (their ``descriptions`` and ``settings``): those in
    ``store`` read back, the others run in chunks (:func:`clearsim.batch.run_chunks`), each saved
    as it finishes; ``on_done(count)`` as samples finish. Chunks lost to the machinery raise a
    :class:`ClusterError` once every other chunk has finished (and been saved)."""
    n = len(samples)
    raws: List[Any] = [None] * n
    done = [False] * n
    digests: List[bytes] = []
    if store is not None:
        digests = [store.digest(d, s) for d, s in zip(descriptions, settings)]
        found = store.load(min(samples), max(samples) + 1) if n else {}
        for i, k in enumerate(samples):
            if k in found and found[k][0] == digests[i]:
                raws[i], done[i] = found[k][1], True
        if any(done):
            on_done(sum(done))
    todo = [i for i in range(n) if not done[i]]
    size = chunk_size if chunk_size is not None else chunk_size_for(len(todo), executor, show)
    lost: List[Tuple[int, int, str]] = []
    for a, b, result in run_chunks([descriptions[i] for i in todo], [settings[i] for i in todo], executor, size, nominal, threads, timeout):
        index = todo[a:b]
        if isinstance(result, BaseException):
            lost.append((samples[index[0]], samples[index[-1]] + 1, f"{type(result).__name__}: {result}".rstrip(": ")))
            continue
        for i, raw in zip(index, result):
            raws[i], done[i] = raw, True
        if store is not None:
            store.save([samples[i] for i in index], [digests[i] for i in index], result)
        on_done(len(index))
    if lost:
        raise _lost(lost, finished_before + sum(done), finished_before + n, store)
    return raws


def _lost(lost: List[Tuple[int, int, str]], finished: int, asked: int, store: Optional[Checkpoint]) -> ClusterError:
    """The error for chunks lost to the machinery: which, why, what finished, how to resume."""
    shown = "; ".join(f"samples {a}–{b - 1}: {why}" for a, b, why in lost[:5]) + ("; …" if len(lost) > 5 else "")
    n_lost = sum(b - a for a, b, _ in lost)
    if store is not None:
        after = f"the finished ones are saved in checkpoint {store.path!r}: the same call resumes, running the lost samples only"
    else:
        after = "they are not kept: give checkpoint='a directory' to save finished samples and resume after a failure"
    message = (
        f"{len(lost)} chunk(s) of samples ({n_lost} samples) lost to the executor, not to the mechanism ({shown}); "
        f"{finished} of the {asked} samples so far finished: {after}"
    )  # fmt: skip
    return ClusterError(message, lost=lost, finished=finished, checkpoint=None if store is None else store.path)
