"""Amplitude spectra of a periodic or nearly periodic signal: a windowed FFT over a whole number
of periods of a uniform grid with a whole number of samples a period, so every harmonic of the
period falls on a bin and its amplitude is read in the signal's own unit (:class:`Spectrum`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from ..errors import InputError, check_choice, check_finite

#: Windows: periodic Hann (default; leakage of a line between bins falls as 1/f³) and none.
WINDOWS = ("hann", "rectangular")
#: How far a grid may stray from uniform spacing, and the samples a period from a whole number,
#: relative (round-off of t0 + k dt_out).
_GRID_TOL = 1e-6


@dataclass(frozen=True)
class Spectrum:
    """One-sided amplitude spectrum.

    ``frequency`` [Hz] and ``amplitude`` (the unit ``unit``): a line A cos(2π f t + φ) at a bin
    reads A (the window's coherent gain divided out; the mean reads itself at f = 0).
    ``order`` = frequency × period (harmonic number, fractional between harmonics);
    ``cycles`` whole periods of ``period`` [s] were analysed, ``samples_per_period`` each."""

    frequency: np.ndarray
    amplitude: np.ndarray
    unit: str
    period: float
    cycles: int
    samples_per_period: int
    window: str
    label: str = ""

    @property
    def order(self) -> np.ndarray:
        return self.frequency * self.period

    def harmonic(self, k: int) -> float:
        """The amplitude of harmonic ``k`` (frequency k/period; k = 0 the mean) [unit]."""
        i = int(k) * self.cycles
        if not 0 <= i < len(self.amplitude):
            raise InputError(f"invalid k = {k!r}: harmonics 0 … {(len(self.amplitude) - 1) // self.cycles} lie below the Nyquist frequency", field="k", value=k)
        return float(self.amplitude[i])

    def plot(self, ax: Any = None, max_order: Optional[float] = None) -> Any:
        """A stem plot of the amplitudes over the harmonic order (:func:`clearsim.plots.dynamics.plot_spectrum`)."""
        from ..plots.dynamics import plot_spectrum

        return plot_spectrum(self, ax=ax, max_order=max_order)


def spectrum(
    t: np.ndarray,
    values: np.ndarray,
    period: float,
    *,
    cycles: Optional[int] = None,
    window: str = "hann",
    unit: str = "",
    label: str = "",
) -> Spectrum:
    """The :class:`Spectrum` of ``values`` sampled at ``t`` [s] over the last ``cycles`` whole
    periods ``period`` [s] (default: every whole period the samples hold). ``t`` must be uniform
    with a whole number of samples a period (``dt = period / N``)."""
    check_choice("window", window, WINDOWS)
    period = check_finite("period", period)
    if period <= 0:
        raise InputError(f"invalid period = {period!r}: must be positive [s]", field="period", value=period)
    t = np.asarray(t, dtype=float)
    x = np.asarray(values, dtype=float)
    if t.ndim != 1 or x.shape != t.shape or len(t) < 4:
        raise InputError(f"invalid values: {x.shape} values at {t.shape} times (need the same length, at least 4)", field="values", value=x.shape)
    dt = (t[-1] - t[0]) / (len(t) - 1)
    if np.max(np.abs(np.diff(t) - dt)) > _GRID_TOL * dt:
        raise InputError("invalid t: the samples are not evenly spaced (store them with dt_out)", field="t", value=None)
    n_per = period / dt
    if abs(n_per - round(n_per)) > _GRID_TOL * n_per or round(n_per) < 2:
        raise InputError(
            f"invalid dt_out = {dt:.6g} s: a spectrum needs a whole number of samples a period {period:.6g} s "
            f"(it holds {n_per:.6g}); store with dt_out = period / N, N ≥ 2",
            field="dt_out", value=dt,
        )  # fmt: skip
    n_per = int(round(n_per))
    whole = len(t) // n_per
    if cycles is None:
        cycles = whole
    if not (isinstance(cycles, (int, np.integer)) and 1 <= cycles <= whole):
        raise InputError(f"invalid cycles = {cycles!r}: the samples hold {whole} whole periods", field="cycles", value=cycles)
    n = int(cycles) * n_per
    if not np.all(np.isfinite(x[-n:])):
        raise InputError("invalid values: not finite in the analysed window", field="values", value=None)
    seg = x[-n:]
    w = np.ones(n) if window == "rectangular" else 0.5 * (1.0 - np.cos(2 * math.pi * np.arange(n) / n))
    spec = np.fft.rfft(seg * w)
    gain = float(np.sum(w))
    amp = 2.0 * np.abs(spec) / gain
    amp[0] /= 2.0
    if n % 2 == 0:
        amp[-1] /= 2.0  # the Nyquist bin is its own mirror image
    freq = np.fft.rfftfreq(n, dt)
    return Spectrum(freq, amp, unit, float(period), int(cycles), n_per, window, label)


__all__ = ["Spectrum", "WINDOWS", "spectrum"]
