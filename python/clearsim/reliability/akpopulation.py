"""The candidates of active-learning Kriging (:mod:`.akmcs`) and one pass of the surrogate over
them.

A rare event needs a large population: p_f = 1e-5 at a CoV of 0.05 needs 4·10⁷ Monte Carlo
candidates (N = (1 − p)/(p CoV²)). The population is therefore drawn block by block and never
kept whole: block k is drawn again, the same, from the generator seeded (entropy, k) each time
the surrogate passes over it. A pass (:func:`scan`) keeps what the learning needs: the sums of
the estimate (Σ w, Σ w² over the candidates classified failed) and the few candidates whose
class the surrogate is unsure of (a lower bound of U = |μ|/σ below 2: a fraction of a per cent
on a rare event), with their mean, mode and weight. Memory is a block's, whatever N.

Candidates are points of N(0, I) (AK-MCS: weight 1) or of a mixture Σ_j w_j N(c_j, I) around
design points (AK-IS: weight φ(u)/h(u)).
"""

from __future__ import annotations

import math
import os
from collections import deque
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Callable, Deque, List, Optional, Tuple

import numpy as np

__all__ = ["Population", "Scan", "scan", "draw", "BLOCK", "KEEP", "STOP_U"]

#: Candidates drawn and predicted together.
BLOCK = 65536
#: A population of at most this many candidates is also kept whole, for inspection
#: (``extra["candidates"]``, ``"weights"``, ``"classified_failed"`` of a result).
KEEP = 1_000_000
#: Learning stops when every candidate has U = |μ|/σ ≥ STOP_U (Echard et al. 2011).
STOP_U = 2.0


def draw(centres: np.ndarray, mixture: np.ndarray, n: int, rng: np.random.Generator) -> Tuple[np.ndarray, Optional[np.ndarray]]:
    """``n`` points of the mixture Σ_j w_j N(c_j, I) and their weights φ(u)/h(u) (``None``, 1
    each, when the only centre is the origin: Monte Carlo)."""
    d = centres.shape[1]
    pick = rng.choice(len(mixture), size=n, p=mixture)
    u = rng.standard_normal((n, d))
    if len(mixture) == 1 and not np.any(centres):
        return u, None
    u += centres[pick]
    # log φ(u) − log h(u) = −log Σ_j w_j exp(c_j·u − |c_j|²/2)
    expo = u @ centres.T - 0.5 * np.sum(centres**2, axis=1)[None, :]
    top = expo.max(axis=1, keepdims=True)
    log_h_over_phi = top[:, 0] + np.log(np.exp(expo - top) @ mixture)
    return u, np.exp(-log_h_over_phi)


class Population:
    """Candidates of the mixture (``centres``, ``mixture`` weights) in blocks of at most
    :data:`BLOCK`, each drawn from its own generator seeded (``seed``'s entropy, block index)."""

    def __init__(self, centres: np.ndarray, mixture: np.ndarray, size: int, seed: Optional[int]) -> None:
        self.centres = np.atleast_2d(np.asarray(centres, dtype=float))
        self.mixture = np.asarray(mixture, dtype=float)
        self.entropy = int(np.random.SeedSequence(seed).entropy)  # type: ignore[arg-type]
        self.sizes: List[int] = []
        self.grow(size)

    @property
    def size(self) -> int:
        return int(sum(self.sizes))

    @property
    def monte_carlo(self) -> bool:
        return len(self.mixture) == 1 and not np.any(self.centres)

    def grow(self, n: int) -> None:
        """Add ``n`` candidates (new blocks: the ones drawn so far stay as they are)."""
        while n > 0:
            k = min(int(n), BLOCK)
            self.sizes.append(k)
            n -= k

    def block(self, k: int) -> Tuple[np.ndarray, Optional[np.ndarray]]:
        """Block ``k``'s candidates and their weights (``None``: 1 each)."""
        return draw(self.centres, self.mixture, self.sizes[k], np.random.default_rng([self.entropy, k]))

    def head(self, n: int) -> np.ndarray:
        """The first ``n`` candidates (at most the population)."""
        out: List[np.ndarray] = []
        k = 0
        while sum(len(b) for b in out) < n and k < len(self.sizes):
            out.append(self.block(k)[0])
            k += 1
        return np.vstack(out)[:n]


@dataclass
class Scan:
    """One pass of a surrogate over a population: the estimate's sums and the candidates whose
    class is unsure (``near_*``: lower bound of U below :data:`STOP_U`)."""

    size: int
    s1: float = 0.0  # Σ w over the candidates classified failed
    s2: float = 0.0  # Σ w² over them
    sure: float = 0.0  # Σ w over the failed candidates whose class is sure (bound of U ≥ 2)
    near_u: List[np.ndarray] = field(default_factory=list)
    near_mu: List[np.ndarray] = field(default_factory=list)
    near_mode: List[np.ndarray] = field(default_factory=list)
    near_lower: List[np.ndarray] = field(default_factory=list)
    near_w: List[np.ndarray] = field(default_factory=list)
    lowest: Tuple[Optional[np.ndarray], float] = (None, math.inf)  # the candidate of smallest bound, and it
    kept: Optional[Tuple[List[np.ndarray], List[Optional[np.ndarray]], List[np.ndarray]]] = None

    def estimate(self) -> Tuple[float, float]:
        """p̂_f = Σ w 1{failed} / N and its coefficient of variation (the terms' sample CoV / √N)."""
        n = self.size
        pf = self.s1 / n
        if pf <= 0:
            return 0.0, math.inf
        var = max(self.s2 - n * pf * pf, 0.0) / (n - 1)
        return pf, math.sqrt(var) / math.sqrt(n) / pf

    def near(self) -> Tuple[np.ndarray, np.ndarray, Optional[np.ndarray], np.ndarray, np.ndarray]:
        """The unsure candidates: u, μ, deciding mode (``None``: one mode), bound of U, weight."""
        d = self.lowest[0].size if self.lowest[0] is not None else 0
        u = np.vstack(self.near_u) if self.near_u else np.empty((0, d))
        mode = np.concatenate(self.near_mode) if self.near_mode else None
        cat = [np.concatenate(a) if a else np.empty(0) for a in (self.near_mu, self.near_lower, self.near_w)]
        return u, cat[0], mode, cat[1], cat[2]

    def bounds(self, sigma: np.ndarray) -> Tuple[float, float]:
        """p_f with every unsure candidate within 2σ (``sigma``: theirs) of g = 0 counted safe,
        and counted failed."""
        _, mu, _, _, w = self.near()
        return (self.sure + float(np.sum(w[mu + STOP_U * sigma <= 0.0]))) / self.size, (self.sure + float(np.sum(w[mu - STOP_U * sigma <= 0.0]))) / self.size

    def candidates(self) -> Tuple[Optional[np.ndarray], Any, Optional[np.ndarray]]:
        """Every candidate, its weight (1.0 for Monte Carlo) and class, if the population was
        kept (at most :data:`KEEP`); else ``None`` each."""
        if self.kept is None:
            return None, None, None
        us, ws, fs = self.kept
        weight: Any = 1.0 if ws[0] is None else np.concatenate([w for w in ws if w is not None])
        return np.vstack(us), weight, np.concatenate(fs)


def scan(population: Population, classify: Callable[[np.ndarray], Tuple[np.ndarray, Optional[np.ndarray], np.ndarray]]) -> Scan:
    """Pass over every block: ``classify(u)`` gives each candidate's mean μ (failed: μ ≤ 0), its
    deciding mode (``None`` for one) and a lower bound of U. Blocks are drawn and classified on
    every core (numpy releases the GIL) and summed in their order: the same answer whatever the
    number of threads."""

    def one(k: int) -> Tuple[np.ndarray, Optional[np.ndarray], np.ndarray, Optional[np.ndarray], np.ndarray, np.ndarray]:
        u, w = population.block(k)
        mu, mode, lower = classify(u)
        return u, w, mu, mode, lower, mu <= 0.0

    out = Scan(population.size, kept=([], [], []) if population.size <= KEEP else None)
    workers = min(os.cpu_count() or 1, len(population.sizes))
    with ThreadPoolExecutor(max_workers=workers) as pool:
        ahead: Deque[Any] = deque()  # at most 2 blocks a thread in flight: memory stays a few blocks'
        todo = iter(range(len(population.sizes)))
        for k in todo:
            ahead.append(pool.submit(one, k))
            if len(ahead) >= 2 * workers:
                break
        while ahead:
            u, w, mu, mode, lower, failed = ahead.popleft().result()
            nxt = next(todo, None)
            if nxt is not None:
                ahead.append(pool.submit(one, nxt))
            terms = failed.astype(float) if w is None else np.where(failed, w, 0.0)
            out.s1 += float(terms.sum())
            out.s2 += float(np.dot(terms, terms))
            near = lower < STOP_U
            out.sure += float(terms[~near].sum())
            if near.any():
                out.near_u.append(u[near])
                out.near_mu.append(mu[near])
                out.near_lower.append(lower[near])
                out.near_w.append(np.ones(int(near.sum())) if w is None else w[near])
                if mode is not None:
                    out.near_mode.append(mode[near])
            j = int(np.argmin(lower))
            if out.lowest[0] is None or lower[j] < out.lowest[1]:
                out.lowest = (u[j].copy(), float(lower[j]))
            if out.kept is not None:
                out.kept[0].append(u)
                out.kept[1].append(w)
                out.kept[2].append(failed)
    return out
