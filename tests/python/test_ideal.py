"""Ideal mechanisms against closed forms and an independent position analysis (docs/physics.md §8, §7)."""

import math

import numpy as np
import pytest

import clearsim
from clearsim import models

def _dry(clearance: float) -> clearsim.Mechanism:
    return models.slider_crank("dry", clearance=clearance)

R, L = 0.05, 0.12
OMEGA = 5000 * 2 * math.pi / 60


def slider_crank_closed_form(theta, omega, r=R, l=L):
    """x, ẋ, ẍ of the zero-offset slider-crank at constant crank speed."""
    s, c = np.sin(theta), np.cos(theta)
    root = np.sqrt(l * l - r * r * s * s)
    x = r * c + root
    dx = -r * s - r * r * s * c / root
    ddx = -r * c - r * r * (c * c - s * s) / root - r**4 * s * s * c * c / root**3
    return x, omega * dx, omega * omega * ddx


def test_slider_crank_matches_closed_form():
    m = models.slider_crank("ideal")
    period = 2 * math.pi / OMEGA
    res = m.simulate(period, rtol=1e-11, atol=1e-13, dt_out=period / 360)
    theta = OMEGA * res.t
    x, v, a = slider_crank_closed_form(theta, OMEGA)
    pos, vel, acc = res.position("slider")[:, 0], res.velocity("slider")[:, 0], res.acceleration("slider")[:, 0]
    assert np.max(np.abs(pos - x)) / np.max(np.abs(x)) < 1e-9
    assert np.max(np.abs(vel - v)) / np.max(np.abs(v)) < 1e-9
    assert np.max(np.abs(acc - a)) / np.max(np.abs(a)) < 1e-9
    # Anchors of docs/physics.md §8.
    assert acc[0] == pytest.approx(-19419.36, abs=0.01)
    assert np.max(pos) - np.min(pos) == pytest.approx(0.100, abs=1e-6)
    assert np.max(np.abs(vel)) == pytest.approx(28.41, abs=0.01)
    assert np.min(acc) == pytest.approx(-19419.36, abs=0.05)


def circle_intersection(p, rp, q, rq, near):
    """The intersection of circles (p, rp) and (q, rq) nearest to `near`."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = np.linalg.norm(q - p)
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    h = math.sqrt(rp * rp - a * a)
    base = p + a * (q - p) / d
    perp = np.array([-(q - p)[1], (q - p)[0]]) / d
    cands = [base + h * perp, base - h * perp]
    return min(cands, key=lambda c: np.linalg.norm(c - near))


def nine_bar_slider_y(theta1, theta4):
    """Independent position analysis of the nine-bar by loop-closure geometry (docs/physics.md §7)."""
    ys = []
    C, D = np.array([0.2919, -0.2306]), np.array([0.6756, -0.1176])
    for t1, t4 in zip(theta1, theta4):
        B1 = 0.10 * np.array([math.cos(t1), math.sin(t1)])
        A = np.array([0.0, -0.40]) + 0.10 * np.array([math.cos(t4), math.sin(t4)])
        C = circle_intersection(B1, 0.30, A, 0.30, C)
        D = circle_intersection(C, 0.40, np.array([0.45, 0.15]), 0.35, D)
        ys.append(D[1] - math.sqrt(0.35**2 - (0.59 - D[0]) ** 2))
    return np.array(ys)


def test_nine_bar_kinematics_and_drift():
    omega = -5 * math.pi
    period = 2 * math.pi / abs(omega)
    m = models.nine_bar("ideal", omega=omega)
    res = m.simulate(3 * period, rtol=1e-10, atol=1e-12, dt_out=period / 720)
    y = res.position("slider9")[:, 1]
    expected = nine_bar_slider_y(omega * res.t, math.pi / 2 + omega * res.t)
    assert np.max(np.abs(y - expected)) < 1e-8
    assert np.max(y) - np.min(y) == pytest.approx(0.141, abs=1e-3)
    assert np.min(y) == pytest.approx(-0.536, abs=1e-3)
    assert np.max(y) == pytest.approx(-0.395, abs=1e-3)
    assert np.max(res.constraint_violation) < 1e-10
    # The slider stays on its guide.
    assert np.max(np.abs(res.position("slider9")[:, 0] - 0.59)) < 1e-10


def pendulum_chain(n=3):
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    for k in range(n):
        m.add_body(f"link{k}", mass=1.0 + 0.3 * k, inertia=0.01 + 0.002 * k, position=(0.1 + 0.2 * k, 0.0))
    m.revolute("ground", (0.0, 0.0), "link0", (-0.1, 0.0))
    for k in range(1, n):
        m.revolute(f"link{k-1}", (0.1, 0.0), f"link{k}", (-0.1, 0.0))
    return m


def mechanical_energy(m, res):
    e = np.zeros(len(res.t))
    for b in m._bodies:
        q, v = res.position(b["name"]), res.velocity(b["name"])
        e += 0.5 * b["mass"] * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * b["inertia"] * v[:, 2] ** 2
        e += b["mass"] * 9.81 * q[:, 1]
    return e


@pytest.mark.parametrize("integrator,kw", [("rk45", dict(rtol=1e-10, atol=1e-12)), ("dop853", dict(rtol=1e-10, atol=1e-12))])
def test_pendulum_chain_conserves_energy(integrator, kw):
    m = pendulum_chain()
    res = m.simulate(2.0, integrator=integrator, dt_out=1e-3, **kw)
    e = mechanical_energy(m, res)
    assert np.ptp(e) < 1e-7 * (1 + abs(e[0]))
    assert np.max(res.constraint_violation) < 1e-9


def test_rk4_matches_rk45_on_the_chain():
    m = pendulum_chain(2)
    a = m.simulate(0.5, integrator="rk4", step=1e-4, dt_out=1e-2)
    b = m.simulate(0.5, rtol=1e-11, atol=1e-13, dt_out=1e-2)
    assert np.max(np.abs(a.position("link1") - b.position("link1"))) < 1e-8


def test_outputs_do_not_change_steps():
    m = models.slider_crank("ideal")
    a = m.simulate(0.01, dt_out=1e-3)
    b = m.simulate(0.01, dt_out=1e-6)
    assert a.stats["steps"] == b.stats["steps"]
    assert len(b.t) == 10001


def test_only_requested_outputs_are_stored():
    m = models.slider_crank("ideal")
    res = m.simulate(0.005, outputs=["states"])
    assert res.position("slider").shape == (1001, 3)
    with pytest.raises(clearsim.InputError, match="accelerations"):
        res.acceleration("slider")


def test_simulate_with_ideal_takes_the_options_of_simulate():
    """``progress=False``, which every ``simulate`` call in a script carries, is accepted by
    ``simulate_with_ideal`` too. Before: ``TypeError: Running.run_settings() got an unexpected
    keyword argument 'progress'``."""
    m = _dry(0.5e-3)
    res, ideal = m.simulate_with_ideal(0.002, progress=False, dt_out=1e-4)
    assert res.completed and ideal.completed and len(res.t) == len(ideal.t) == 21
