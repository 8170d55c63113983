"""Independent results the dynamics tools are checked against, written without clearsim:

- Baker & Gollub's damped driven pendulum θ'' + θ'/q + sin θ = g cos(ω_D t) integrated with
  SciPy's DOP853 as the plain ODE: its stroboscopic sections, the period they repeat with, and
  its largest Lyapunov exponent from the variational equation (δθ'' + δθ'/q + cos θ δθ = 0,
  renormalised every drive period);
- the bouncing ball on a sinusoidally vibrating table (Holmes 1982; Tufillaro, Abbott & Reilly,
  *An Experimental Approach to Nonlinear Dynamics and Chaos*, 1992, ch. 3): the one-bounce-a-
  period orbit takes off at cos φ = π(1 − e)/((1 + e) Γ) with v = gT/2 and doubles its period at
  Γ₂ = √((π(1 − e)/(1 + e))² + (2(1 + e²)/(1 + e)²)²); below the point where its two
  multipliers turn real they are a complex pair of modulus e (the map contracts areas by e²), so
  its largest Lyapunov exponent is ln(e)/T.

Used by tests/python/test_dynamics.py and benches/pendulum_table.py.
"""

from __future__ import annotations

import math
from typing import List, Tuple

import numpy as np
from scipy.integrate import solve_ivp

DRIVE_OMEGA = 2.0 / 3.0
PERIOD = 2 * math.pi / DRIVE_OMEGA


def _pendulum(g: float, q: float):
    def f(t: float, y: np.ndarray) -> np.ndarray:
        th, w = y[0], y[1]
        out = [w, -w / q - math.sin(th) + g * math.cos(DRIVE_OMEGA * t)]
        if len(y) > 2:
            out += [y[3], -y[3] / q - math.cos(th) * y[2]]
        return np.array(out)

    return f


def pendulum_sections(g: float, transient: int, cycles: int, *, q: float = 2.0, theta0: float = 0.2, rtol: float = 1e-10) -> np.ndarray:
    """(θ wrapped to (−π, π], θ') at t = n T for n = transient … transient + cycles − 1."""
    t = PERIOD * np.arange(transient, transient + cycles)
    sol = solve_ivp(_pendulum(g, q), (0.0, t[-1]), [theta0, 0.0], method="DOP853", rtol=rtol, atol=rtol * 1e-2, t_eval=t)
    th = (sol.y[0] + math.pi) % (2 * math.pi) - math.pi
    return np.stack([th, sol.y[1]], axis=1)


def repeat_period(points: np.ndarray, tol: float = 1e-4, max_period: int = 16) -> int:
    """The smallest k ≤ max_period with every section point repeating k periods later within
    ``tol`` (θ on the circle, θ' as is); 0 if none."""
    for k in range(1, max_period + 1):
        d_th = np.abs((points[k:, 0] - points[:-k, 0] + math.pi) % (2 * math.pi) - math.pi)
        d_w = np.abs(points[k:, 1] - points[:-k, 1])
        if max(d_th.max(), d_w.max()) <= tol:
            return k
    return 0


def pendulum_exponent(g: float, transient: int, cycles: int, *, q: float = 2.0, theta0: float = 0.2, rtol: float = 1e-10) -> Tuple[float, float]:
    """The largest Lyapunov exponent [1/s] from the variational equation renormalised every
    period over ``cycles`` periods after ``transient``, and the half-width of its 95 % interval
    from 10 batch means (t quantile 2.262)."""
    f = _pendulum(g, q)
    y = solve_ivp(f, (0.0, transient * PERIOD), [theta0, 0.0], method="DOP853", rtol=rtol, atol=rtol * 1e-2).y[:, -1]
    state = np.array([y[0], y[1], 1.0, 0.0])
    logs: List[float] = []
    for n in range(cycles):
        t0 = (transient + n) * PERIOD
        sol = solve_ivp(f, (t0, t0 + PERIOD), state, method="DOP853", rtol=rtol, atol=rtol * 1e-2)
        state = sol.y[:, -1].copy()
        d = math.hypot(state[2], state[3] / DRIVE_OMEGA)
        logs.append(math.log(d))
        state[2:] /= d
    g_arr = np.asarray(logs)
    b = 10
    size = len(g_arr) // b
    means = g_arr[len(g_arr) - b * size :].reshape(b, size).sum(axis=1) / (size * PERIOD)
    return float(g_arr.sum() / (len(g_arr) * PERIOD)), float(2.262 * means.std(ddof=1) / math.sqrt(b))


def ball_period_doubling(e: float) -> float:
    """Γ₂ at which the one-bounce-a-period orbit of the bouncing ball doubles its period."""
    g1 = math.pi * (1 - e) / (1 + e)
    return math.hypot(g1, 2 * (1 + e * e) / (1 + e) ** 2)


def ball_takeoff(gamma: float, e: float, g: float, frequency: float) -> Tuple[float, float]:
    """(take-off speed [m/s] relative to the ground, cos of the take-off phase) of the period-1
    orbit of z_table = A sin(ω t), Γ = A ω²/g."""
    period = 1.0 / frequency
    return g * period / 2, math.pi * (1 - e) / ((1 + e) * gamma)


def ball_impacts(gamma: float, e: float, frequency: float, impacts: int, g: float = 9.81) -> np.ndarray:
    """The exact impact map of the bouncing ball (instant impacts, restitution ``e``, table
    z = A sin ω t): (phase ω t mod 2π, take-off speed) of ``impacts`` impacts, from the take-off of
    the one-bounce-a-period orbit slightly disturbed. Each next impact is the first root of
    z_ball − z_table after the last, bracketed on a grid of T/400 and found by Brent's method."""
    from scipy.optimize import brentq

    w = 2 * math.pi * frequency
    amp = gamma * g / w**2
    period = 1.0 / frequency
    phi = math.acos(math.pi * (1 - e) / ((1 + e) * gamma))
    t, v = phi / w, g * period / 2 * 1.01
    out = []
    for _ in range(impacts):
        z0 = amp * math.sin(w * t)
        gap = lambda s: z0 + v * (s - t) - g * (s - t) ** 2 / 2 - amp * math.sin(w * s)  # noqa: E731
        h = period / 400
        s = t + h
        while gap(s) > 0:
            s += h
        s = brentq(gap, s - h, s, xtol=1e-15)
        u = amp * w * math.cos(w * s)
        v = -e * (v - g * (s - t) - u) + u
        t = s
        out.append((w * t % (2 * math.pi), v))
    return np.asarray(out)
