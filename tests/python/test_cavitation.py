"""Mass-conserving cavitation, ``Lubricated(film="finite", cavitation="jfo")`` (docs/physics.md §4,
*Mass-conserving cavitation*): against the Reynolds-condition film it must reproduce at a steady
state (a full film's complementarity problem is the same; its own table test against Butenschön is
in Rust: `cargo test bearing_jfo`), against the conservation of the oil (what the supply feeds less
what leaks is what the gap gains, recounted here from the recorded fill), and its input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim

R, C, MU, OMEGA, LOAD = 0.02, 4e-5, 0.05, 100.0, 400.0
LENGTH = 0.02  # L/D = 1/2
#: The content grid of rust/laws/bearing_jfo.rs (90 cells of 4°, 8 nodes over the half width).
N_THETA, N_ZETA = 90, 8


def rotor(cavitation: str, load: object = (0.0, -LOAD), eccentricity: tuple = (0.0, 0.0)) -> clearsim.Mechanism:
    """A 1 kg rotor driven at OMEGA in a ground bearing (L/D = 1/2, no gravity) under ``load``."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", omega=OMEGA, angle0=0.0)
    model = clearsim.Lubricated(viscosity=MU, length=LENGTH, film="finite", cavitation=cavitation)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=model, initial_eccentricity=eccentricity)
    m.force("rotor", (0, 0), load)
    return m


def oil_in_gap(res: clearsim.Result) -> np.ndarray:
    """(N,) oil in the gap [m³] from the recorded fill θ_f: Σ θ_f h dA over the content grid, h the
    cell mean of c (1 + ε cos θ), control volumes of 4° × L/16 (half a node's at the mid-plane,
    both halves of the width), the supply groove (cell 0) full."""
    fill = res._raw["film_content"][:, 0, :].reshape(len(res.t), N_THETA, N_ZETA)
    eps = np.hypot(*res.eccentricity("pin").T) / C
    dth, dz = 2 * np.pi / N_THETA, 1.0 / N_ZETA
    faces = dth * (np.arange(N_THETA) + 0.5)
    cos_mean = (np.sin(faces) - np.sin(np.roll(faces, 1) - np.where(np.arange(N_THETA) == 0, 2 * np.pi, 0))) / dth
    h = 1 + eps[:, None] * cos_mean[None, :]
    weight = np.full(N_ZETA, dz)
    weight[0] = dz / 2
    f = fill.copy()
    f[:, 0, :] = 1.0
    return C * R * LENGTH * dth * np.einsum("tij,ti,j->t", f, h, weight)


def test_a_steady_journal_has_the_reynolds_films_position_and_feeds_what_it_leaks() -> None:
    """Started at the Reynolds film's equilibrium, the mass-conserving film settles within 0.5 %
    of its ε and 1° of its attitude, with the peak pressure within 2 %, and its supply groove
    then feeds what leaks out of the ends within 1 % (the mass balance of a steady state)."""
    steady = rotor("reynolds").simulate(0.2, dt_out=0.01, progress=False)
    e = steady.eccentricity("pin")[-1]
    res = rotor("jfo", eccentricity=(float(e[0]), float(e[1]))).simulate(0.12, dt_out=0.01, outputs=["states", "joints", "film"], progress=False)
    f = res.eccentricity("pin")[-1]
    assert math.hypot(*f) == pytest.approx(math.hypot(*e), rel=0.005)
    assert abs(math.degrees(math.atan2(f[1], f[0]) - math.atan2(e[1], e[0]))) < 1.0
    side, supply = res.flow("pin")[-1]
    assert supply == pytest.approx(side, rel=0.01) and side > 0
    ref = rotor("reynolds", eccentricity=(float(e[0]), float(e[1]))).simulate(0.01, dt_out=0.005, outputs=["states", "joints", "film"], progress=False)
    assert res.peak_pressure("pin")[-1] == pytest.approx(ref.peak_pressure("pin")[-1], rel=0.02)


def test_the_oil_in_the_gap_changes_by_what_is_fed_less_what_leaks() -> None:
    """Under a load turning at half the shaft speed the film ruptures and reforms every turn: over
    the run the oil in the gap (recounted from the recorded fill) changes by ∫ (supply − leakage) dt
    within 1 % of the oil that leaked."""
    turning = {"t": np.linspace(0.0, 0.08, 161).tolist(), "fx": (LOAD * np.sin(0.5 * OMEGA * np.linspace(0.0, 0.08, 161))).tolist(),
               "fy": (-LOAD * np.cos(0.5 * OMEGA * np.linspace(0.0, 0.08, 161))).tolist()}  # fmt: skip
    res = rotor("jfo", load=turning, eccentricity=(0.0, -0.5 * C)).simulate(0.08, dt_out=2e-4, outputs=["states", "joints", "film"], progress=False)
    assert res.completed
    oil = oil_in_gap(res)
    q = res.flow("pin")
    dt = np.diff(res.t)
    fed = float(np.sum(0.5 * (q[1:, 1] + q[:-1, 1]) * dt))
    leaked = float(np.sum(0.5 * (q[1:, 0] + q[:-1, 0]) * dt))
    assert leaked > 0 and abs((oil[-1] - oil[0]) - (fed - leaked)) < 0.01 * leaked, (oil[-1] - oil[0], fed - leaked, leaked)
    fill = res._raw["film_content"][-1, 0]
    assert fill.min() < 0.9  # it did rupture


def test_its_inputs_are_checked() -> None:
    """Mass-conserving cavitation needs the finite film and its supply groove: named as the
    model is made (the core checks a model alone)."""
    for options, field in [
        (dict(film="short", cavitation="jfo"), "cavitation"),
        (dict(film="finite", supply="none", cavitation="jfo"), "supply"),
        (dict(film="finite", cavitation="mass"), "cavitation"),
    ]:
        with pytest.raises(clearsim.InputError, match=field) as err:
            clearsim.Lubricated(**options)
        assert err.value.field == field
