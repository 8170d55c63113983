"""The connecting-rod big-end example (scenes/con_rod_bearing.toml: Flores, Claro & Ambrósio 2006,
a 720° load diagram at 2 000 rpm) against a massless journal solved here, separately from the core:
the short (Ocvirk) film's force balance F_film(e, ė) + F_load = 0 solved for ė at every instant and
integrated by SciPy, and its minimum film over the load's 720° cycle (docs/examples.md)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Tuple

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import clearsim
from clearsim.scene import load_scene_file

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "con_rod_bearing.toml"
MU, L, R, C = 0.00416, 0.0254, 0.03175, 35.56e-6
OMEGA = 2000 * 2 * math.pi / 60
NODES, WEIGHTS = np.polynomial.legendre.leggauss(64)


def load_table() -> Tuple[np.ndarray, np.ndarray]:
    """The scene's load table (crank angle [rad], force along y [N])."""
    scene = load_scene_file(SCENE)
    force = next(f for f in scene.mechanism.description()["forces"] if f.get("name") == "big-end load")
    table = force["fy"]["table"]
    return np.asarray(table["x"]), np.asarray(table["y"])


def ocvirk_direction(eps: float, theta_m: float) -> np.ndarray:
    """Short-bearing film force (F_ξ, F_η) on the journal [N] per unit of ρ = hypot(Wε, 2ε̇) [1/s]:
    R ∫ (μL³/(2c²)) cos(θ − θm)/H³ (cosθ, sinθ) dθ over the half film θm ± π/2 where the pressure
    (∝ Wε sinθ − 2ε̇ cosθ = ρ cos(θ − θm)) is positive (Gauss–Legendre, 64 points)."""
    th = theta_m + 0.5 * math.pi * NODES
    integrand = np.cos(th - theta_m) / (1 + eps * np.cos(th)) ** 3
    k = R * MU * L**3 / (2 * C**2) * 0.5 * math.pi
    return k * np.array([np.sum(WEIGHTS * integrand * np.cos(th)), np.sum(WEIGHTS * integrand * np.sin(th))])


def massless_orbit(cycles: int = 2) -> Tuple[np.ndarray, np.ndarray]:
    """The massless journal's eccentricity (ex, ey) [m] over time [s]: at each instant the film
    force balances the load. The force is ρ I(ε, θm) (homogeneous in the motion), so θm is where
    I points against the load (a secant search from the last one) and ρ = |load|/|I|; then
    Wε = ρ sin θm, ε̇ = −ρ cos θm / 2, γ̇ = (ω − W)/2 and ė = c ε̇ n + e γ̇ t."""
    xs, ys = load_table()
    period = 4 * math.pi / OMEGA
    last = [math.pi / 2]

    def rate(t: float, e: np.ndarray) -> np.ndarray:
        ecc = math.hypot(*e)
        n = e / ecc
        tv = np.array([-n[1], n[0]])
        load = np.array([0.0, np.interp((OMEGA * t) % (4 * math.pi), xs, ys)])
        target = -np.array([load @ n, load @ tv])
        eps = ecc / C
        aim = math.atan2(target[1], target[0])

        def miss(tm: float) -> float:
            i = ocvirk_direction(eps, tm)
            return (math.atan2(i[1], i[0]) - aim + math.pi) % (2 * math.pi) - math.pi

        # Bracket the root near the last θm (the miss wraps at ±π: a bracket must not span it):
        # the force turns with θm at about its rate, so the root lies near θm − miss.
        f0 = miss(last[0])
        width = 1.5 * abs(f0) + 0.05
        lo, hi = last[0] - width, last[0] + width
        f_lo, f_hi = miss(lo), miss(hi)
        if not (f_lo * f_hi <= 0 and abs(f_lo - f_hi) < math.pi):
            grid = last[0] + np.linspace(-math.pi, math.pi, 145)
            vals = [miss(x) for x in grid]
            k = next(k for k in range(144) if vals[k] * vals[k + 1] <= 0 and abs(vals[k] - vals[k + 1]) < math.pi)
            lo, hi = grid[k], grid[k + 1]
        tm = float(brentq(miss, lo, hi, xtol=1e-14))
        last[0] = tm
        rho = math.hypot(*target) / math.hypot(*ocvirk_direction(eps, tm))
        wedge = rho * math.sin(tm) / eps
        eps_dot = -rho * math.cos(tm) / 2
        return C * eps_dot * n + ecc * (OMEGA - wedge) / 2 * tv

    out = solve_ivp(rate, (0.0, cycles * period), [0.0, -0.5 * C], rtol=1e-8, atol=1e-14, max_step=period / 360, dense_output=True)
    t = np.linspace((cycles - 1) * period, cycles * period, 7201)
    return t, out.sol(t).T


@pytest.fixture(scope="module")
def reference() -> Tuple[float, float]:
    """h_min [m] and its crank angle [deg] over the last 720° cycle of the massless short film."""
    t, e = massless_orbit(2)
    h = C - np.hypot(e[:, 0], e[:, 1])
    k = int(np.argmin(h))
    return float(h[k]), math.degrees(OMEGA * t[k]) % 720.0


def scene_run(tmp: Path, film: str, cycles: int = 3) -> clearsim.Result:
    """The scene's mechanism with ``film``, run ``cycles`` load cycles, the joint's extremes
    tracked over the last."""
    text = SCENE.read_text(encoding="utf-8").replace('film = "finite"', f'film = "{film}"')
    path = tmp / f"con_rod_{film}.toml"
    path.write_text(text, encoding="utf-8")
    m = load_scene_file(path).mechanism
    period = 4 * math.pi / OMEGA
    return m.simulate(cycles * period, dt_out=period / 720, extremes_from=(cycles - 1) * period, extremes=["big-end"], bearings=True, progress=False)


def test_the_short_film_big_end_has_the_massless_orbits_minimum_film(reference: Tuple[float, float], tmp_path: Path) -> None:
    """The scene's journal (50 g, so almost massless) with the short film: its minimum film over
    the last cycle within 1 % of the massless journal's, at the same crank angle within 3°, and
    reported over the load's 720° cycle."""
    h_ref, angle_ref = reference
    res = scene_run(tmp_path, "short")
    ext = res.extremes("big-end", "film_thickness")
    angle = math.degrees(OMEGA * ext.t_min) % 720.0
    assert ext.min == pytest.approx(h_ref, rel=0.01), (ext.min, h_ref)
    assert abs(angle - angle_ref) < 3.0, (angle, angle_ref)
    b = res.bearing_summary()["big-end"]
    assert 0.0 <= b["min_film_crank_angle_deg"] < 720.0


def test_the_scene_runs_with_its_readings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``clearsim run`` on the scene (finite film, one cycle here): the bearing summary has the
    minimum film over 0–720°, the peak pressure, the flows and the oil temperature, and the run
    prints them with the friction power; joints.csv has the flow columns in m³/s; the pressure
    picture is written."""
    from clearsim.cli import main

    scene = tmp_path / "one_cycle.toml"
    scene.write_text(SCENE.read_text(encoding="utf-8").replace("cycles = 3 ", "cycles = 1 "), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out)]) == 0
    import json

    bearings = json.loads((out / "summary.json").read_text(encoding="utf-8"))["run"]["bearings"]["big-end"]
    assert 0 < bearings["min_film_thickness"] < C and 0 <= bearings["min_film_crank_angle_deg"] < 720
    assert bearings["peak_pressure"] > 1e6 and bearings["mean_side_leakage"] > 0 and bearings["temperature_end"] > 363.15
    header = (out / "joints.csv").read_text(encoding="utf-8").splitlines()[0]
    assert "big-end.side_leakage [m^3/s]" in header and "big-end.peak_pressure [Pa]" in header
    assert (out / "big-end_pressure.png").exists()
    line = next(t for t in capsys.readouterr().out.splitlines() if t.startswith("bearing big-end:"))
    for part in ("min film", "µm at ", "oil 363.15 →", "peak pressure", "MPa", "side leakage", "cm³/s", "mean power loss"):
        assert part in line, (part, line)
