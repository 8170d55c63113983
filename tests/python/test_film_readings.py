"""Oil flow and film pressure of a lubricated joint (docs/physics.md §4, "Oil flow and pressure"):
the side leakage against the short bearing's closed form and Butenschön's flow column (the finite
film's own table test is in Rust: `cargo test finite_side_leakage`), the peak pressure against the
long and short closed forms and against a finite-difference Reynolds solve written here, separately
from the core's, and what a run that does not ask for them stores (nothing)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Tuple

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import clearsim

R, C, MU, OMEGA = 0.02, 4e-5, 0.05, 100.0
DATA = Path(__file__).resolve().parents[1] / "data"


def rotor(film: str, length: float, load: float = 0.0, supply: str = "widest_gap") -> clearsim.Mechanism:
    """A 1 kg rotor driven at OMEGA in a ground bearing (journal at its centroid, no gravity),
    loaded by ``load`` [N] along −y."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", omega=OMEGA, angle0=0.0)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=clearsim.Lubricated(viscosity=MU, length=length, film=film, supply=supply))
    if load:
        m.force("rotor", (0, 0), (0.0, -load))
    return m


def film_at(m: clearsim.Mechanism, eps: float, eps_dot: float = 0.0, omega: float = OMEGA) -> dict:
    """The core's film readings of the rotor's joint with the journal at ε along +x, moving
    radially at ε̇ [1/s] and turning at ω [rad/s]."""
    y = np.array([eps * C, 0.0, 0.0, eps_dot * C, 0.0, omega])
    field = m.compile().film_field(0, y)
    assert field is not None
    return field


# ------------------------------------------------------------------ an independent Reynolds solve
def reynolds_fd(eps: float, length: float, wedge: float, eps_dot: float = 0.0, n_theta: int = 240, n_z: int = 24) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The film pressure p(θ, z) [Pa] of the rotor's bearing (R, C, MU, L = ``length``) by central
    differences on a uniform node grid: (1/R²) ∂θ(h³ ∂θp) + ∂z(h³ ∂zp) = 6μ W ∂θh + 12μ ∂t h,
    h = c(1 + ε cos θ), p = 0 on the supply line θ = 0 and at both ends, and p ≥ 0 with the
    complementary condition (Swift–Stieber), found by active sets on a sparse direct solve."""
    th = 2 * np.pi * np.arange(n_theta) / n_theta
    z = np.linspace(-length / 2, length / 2, n_z + 1)
    dth, dz = th[1], z[1] - z[0]
    h3 = lambda t: (C * (1 + eps * np.cos(t))) ** 3  # noqa: E731
    # Unknowns: θ nodes 1 … n_θ − 1 (θ = 0 is the supply line), z nodes 1 … n_z − 1 (the ends are
    # ambient); index (i − 1)(n_z − 1) + (j − 1).
    ni, nj = n_theta - 1, n_z - 1
    i, j = np.meshgrid(np.arange(1, n_theta), np.arange(1, n_z), indexing="ij")
    k = (i - 1) * nj + (j - 1)
    he, hw = h3(th[i] + dth / 2) / (R * dth) ** 2, h3(th[i] - dth / 2) / (R * dth) ** 2
    hz = h3(th[i]) / dz**2
    rows, cols, vals = [k.ravel()], [k.ravel()], [(he + hw + 2 * hz).ravel()]
    for mask, other, w in ((i < n_theta - 1, k + nj, he), (i > 1, k - nj, hw), (j < n_z - 1, k + 1, hz), (j > 1, k - 1, hz)):
        rows.append(k[mask]), cols.append(other[mask]), vals.append(-w[mask])
    m = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(ni * nj, ni * nj))
    f = (6 * MU * wedge * (-C * eps * np.sin(th[i])) + 12 * MU * C * eps_dot * np.cos(th[i])).ravel()
    # −div(h³ ∇p) = −rhs: M p = −f, p ≥ 0, M p + f ≥ 0, complementary.
    free = np.ones(ni * nj, dtype=bool)
    p = np.zeros(ni * nj)
    for _ in range(200):
        p = np.zeros(ni * nj)
        idx = np.flatnonzero(free)
        p[idx] = spla.spsolve(m[idx][:, idx].tocsc(), -f[idx])
        neg = free & (p < 0)
        if neg.any():
            free &= ~neg
            continue
        add = ~free & (m @ np.maximum(p, 0) + f < -1e-9 * np.abs(f).max())
        if not add.any():
            break
        free |= add
    field = np.zeros((n_theta, n_z + 1))
    field[1:, 1:-1] = np.maximum(p, 0.0).reshape(ni, nj)
    return th, z, field


# ------------------------------------------------------------------ flow
def test_short_film_side_leakage_is_the_closed_form_and_long_film_has_none() -> None:
    """Ocvirk's pressure leaks R c L ρ out of both ends (ρ = hypot(Wε, 2ε̇): docs/physics.md §4),
    and the supply delivers what leaks; the infinitely long film has no axial flow."""
    length = 0.01
    for eps, eps_dot in [(0.3, 0.0), (0.6, 5.0), (0.8, -20.0)]:
        f = film_at(rotor("short", length), eps, eps_dot)
        expected = R * C * length * math.hypot(OMEGA * eps, 2 * eps_dot)
        assert f["side_leakage"] == pytest.approx(expected, rel=1e-12)
        assert f["supply_flow"] == f["side_leakage"]
    long = film_at(rotor("long", 0.1), 0.6)
    assert (long["side_leakage"], long["supply_flow"]) == (0.0, 0.0) and long["peak_pressure"] > 0


def butenschoen_flow() -> dict:
    rows = {}
    for line in (DATA / "butenschoen_flow_rotation.csv").read_text(encoding="utf-8").splitlines():
        if line.startswith("#") or line.startswith("B_over_D"):
            continue
        bd, eps, q = line.split(",")
        a, _, b = bd.partition("/")
        rows[(float(a) / float(b or 1), float(eps))] = float(q)
    return rows


def test_a_steadily_loaded_finite_bearing_leaks_what_butenschoen_tabulates() -> None:
    """A run with ``outputs=[..., "film"]``: at the journal's steady ε the recorded side leakage,
    normalised as Butenschön does (Q = Q_side/(R³ Ψ W)), against his flow column at B/D = 1/2
    interpolated in ε (within 3 %); a run that does not ask stores no film channel and its bearing
    summary (``bearings=True``) has no film rows."""
    length = 0.02  # B/D = 1/2
    m = rotor("finite", length, load=400.0)
    res = m.simulate(0.15, dt_out=5e-3, outputs=["states", "joints", "film"], bearings=True, progress=False)
    eps = float(np.hypot(*res.eccentricity("pin")[-1]) / C)
    table = butenschoen_flow()
    grid = sorted(e for (bd, e) in table if bd == 0.5)
    q_tab = float(np.interp(eps, grid, [table[(0.5, e)] for e in grid]))
    side, supply = res.flow("pin")[-1]
    assert side / (R**3 * (C / R) * OMEGA) == pytest.approx(q_tab, rel=0.03), eps
    assert supply == side
    summary = res.bearing_summary()["pin"]
    assert summary["mean_side_leakage"] > 0 and summary["peak_pressure"] == pytest.approx(res.peak_pressure("pin").max())
    # The summary gains the film's rows only when the run asked for the film as well.
    plain = m.simulate(0.01, dt_out=1e-3, bearings=True, progress=False)
    assert "film" not in plain._raw and "peak_pressure" not in plain.bearing_summary()["pin"]
    with pytest.raises(clearsim.InputError, match="film"):
        plain.flow("pin")


# ------------------------------------------------------------------ pressure
def test_closed_form_peaks() -> None:
    """Long film (Gümbel, pure rotation): the peak of p ∝ sinθ (2 + ε cosθ)/(1 + ε cosθ)² sits at
    cos θ = −3ε/(2 + ε²) (Pinkus & Sternlicht); its value from P12. Short film: the mid-plane peak
    at cos θ = (1 − √(1 + 24ε²))/(4ε), p = (3μ/c²)(L²/4) Wε sinθ/(1 + ε cosθ)³."""
    for eps in (0.3, 0.7):
        f = film_at(rotor("long", 0.1), eps)
        th = math.acos(-3 * eps / (2 + eps**2))
        p = 6 * MU * (R / C) ** 2 * OMEGA * eps * math.sin(th) * (2 + eps * math.cos(th)) / ((2 + eps**2) * (1 + eps * math.cos(th)) ** 2)
        assert f["peak_angle"] == pytest.approx(th, abs=1e-6) and f["peak_pressure"] == pytest.approx(p, rel=1e-9)
        f = film_at(rotor("short", 0.01), eps)
        th = math.acos((1 - math.sqrt(1 + 24 * eps**2)) / (4 * eps))
        p = 3 * MU / C**2 * 0.01**2 / 4 * OMEGA * eps * math.sin(th) / (1 + eps * math.cos(th)) ** 3
        assert f["peak_angle"] == pytest.approx(th, abs=1e-6) and f["peak_pressure"] == pytest.approx(p, rel=1e-9)


P_MAX_CASES = [(0.5, 0.6, 0.0), (0.5, 0.8, 0.0), (1.0, 0.6, 0.0), (0.5, 0.6, 20.0), (0.25, 0.9, 0.0)]


@pytest.mark.parametrize(("l_over_d", "eps", "eps_dot"), P_MAX_CASES)
def test_finite_peak_pressure_matches_an_independent_fd_solve(l_over_d: float, eps: float, eps_dot: float) -> None:
    """The finite film's peak pressure (its solver's 120 × 20 grid stretched towards the thinnest
    film, refined by a parabola) against the uniform 360 × 40 finite-difference solve above:
    within 2 %, at the same angle within 2°; the side leakage within 3 %."""
    length = 2 * R * l_over_d
    f = film_at(rotor("finite", length), eps, eps_dot)
    th, z, p = reynolds_fd(eps, length, OMEGA, eps_dot)
    k = np.unravel_index(np.argmax(p), p.shape)
    assert f["peak_pressure"] == pytest.approx(p[k], rel=0.02)
    assert abs(math.degrees(f["peak_angle"] - th[k[0]])) < 2.0
    # Side leakage of the FD field: h³/(12μ) |∂p/∂z| out of both ends (one-sided, second order).
    dz = z[1] - z[0]
    h3 = (C * (1 + eps * np.cos(th))) ** 3
    grad = (3 * p[:, 0] - 4 * p[:, 1] + p[:, 2]) / (2 * dz)
    q_fd = 2 * np.sum(h3 / (12 * MU) * -grad * R * (th[1] - th[0]))
    assert f["side_leakage"] == pytest.approx(q_fd, rel=0.03)


def test_pressure_at_an_output_time_and_its_picture(tmp_path: Path) -> None:
    """``res.pressure(joint, t)`` solves the film at a stored state: θ × z for the finite film with
    its peak where the run's ``film`` channel put it; θ for the short film; a time that is not an
    output is refused; the picture is drawn."""
    res = rotor("finite", 0.02, load=400.0).simulate(0.02, dt_out=1e-3, outputs=["states", "joints", "film"], progress=False)
    field = res.pressure("pin", 0.02)
    assert field.p.shape == (len(field.theta), len(field.z)) and field.p.min() >= 0
    assert field.peak_pressure == pytest.approx(res.peak_pressure("pin")[-1], rel=1e-6)  # the solver's tolerance: warm-started apart
    assert field.p.max() <= field.peak_pressure * (1 + 1e-12)
    with pytest.raises(clearsim.InputError, match="not an output time"):
        res.pressure("pin", 0.0125)
    short = rotor("short", 0.01, load=100.0).simulate(0.01, dt_out=1e-3, progress=False).pressure("pin", 0.01)
    assert short.z is None and short.p.ndim == 1
    from clearsim import plots

    path = plots.save(plots.plot_film_pressure(field), tmp_path / "p.png")
    assert path.stat().st_size > 10_000


def test_a_dry_joint_has_no_flow_or_pressure_to_read() -> None:
    """A dry joint beside a lubricated one (a dry wrist pin, a lubricated big end) has no film:
    its flow and peak pressure are an InputError naming it, as its pressure field is, not a
    column of zeros that reads as a bearing that leaks nothing."""
    m = rotor("short", 0.01, load=100.0)
    m.add_body("arm", mass=0.1, inertia=1e-5, position=(0.05, 0.0))
    m.clearance_joint("dry-pin", "rotor", (0.05, 0.0), "arm", (0.0, 0.0), journal_radius=5e-3, clearance=2e-5, model=clearsim.Dry())
    res = m.simulate(0.002, dt_out=1e-3, outputs=["states", "joints", "film"], progress=False)
    assert res.flow("pin")[-1, 0] > 0  # the lubricated one reads
    for read in (lambda: res.flow("dry-pin"), lambda: res.peak_pressure("dry-pin"), lambda: res.peak_pressure_angle("dry-pin"), lambda: res.pressure("dry-pin", 0.002)):
        with pytest.raises(clearsim.InputError, match="'dry-pin': it has no film"):
            read()


def test_the_film_summary_keeps_to_the_summary_window() -> None:
    """``bearing_summary`` names its window (``extremes_from`` on): its peak pressure and mean
    flows come from the outputs inside it, like its minimum film. A rotor loaded by 2 kN for the
    first 10 ms, then by 200 N: from 0.02 s on the peak pressure is the light load's and the mean
    leakage the trapezoids' over the outputs from 0.02 s. Before, both were taken over the whole
    run: the peak sat at t < window_start, in the heavy start."""
    m = rotor("finite", 0.02)
    m.force("rotor", (0, 0), {"t": [0.0, 0.01, 0.0101, 0.04], "fy": [-2000.0, -2000.0, -200.0, -200.0]})
    res = m.simulate(0.04, dt_out=5e-4, outputs=["states", "joints", "film"], bearings=True, extremes_from=0.02, progress=False)
    b = res.bearing_summary()["pin"]
    inside = res.t >= 0.02 - 1e-12
    t, p, q = res.t[inside], res.peak_pressure("pin")[inside], res.flow("pin")[inside]
    assert b["window_start"] <= b["t_peak_pressure"] <= b["window_end"]
    assert b["peak_pressure"] == p.max() < 0.5 * res.peak_pressure("pin").max()
    assert b["mean_side_leakage"] == pytest.approx(np.sum(0.5 * (q[1:, 0] + q[:-1, 0]) * np.diff(t)) / (t[-1] - t[0]), rel=1e-12)
