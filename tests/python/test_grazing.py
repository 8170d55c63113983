"""Grazing contacts (docs/physics.md §3, "Grazing contacts"): a contact whose onset comes at
δ̇ ≈ 0 is not located as a switching point, so it neither toggles on and off nor stalls the run,
while real impacts keep their located onsets (issue 28, item 4)."""

import math

import pytest

import clearsim

C = 0.5e-3  # radial clearance [m]
ARM = 0.1  # journal to centroid [m]


def hanging_link(inside: float) -> clearsim.Mechanism:
    """A link hanging from a ground bearing by a dry, frictionless clearance joint, its journal
    released at rest against the bearing's side wall (e = (c − inside, 0)) with gravity along
    the wall and along the link: the wall curves into the journal's path, so contact starts at
    δ = 0 with δ̇ = 0 and then carries the link's weight."""
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("link", mass=1.0, inertia=1e-4, position=(C - inside, -ARM))
    m.clearance_joint("pin", "ground", (0.0, 0.0), "link", (0.0, ARM), journal_radius=0.01, clearance=C,
                      initial_eccentricity=(C - inside, 0.0), model=clearsim.Dry(friction=0.0))  # fmt: skip
    return m


@pytest.mark.parametrize("integrator", ["rk45", "radau"])
def test_a_journal_released_against_the_wall_runs_as_one_released_inside(integrator):
    """Before: the onset at δ̇ = 0 was located again and again as δ changed sign on round-off
    (δ ≈ 1e-19 m), the steps shrank to ~2e-13 s and the run used up its step budget at
    t ≈ 1.4 µs (rk45 and radau). Now the release at the wall takes at most 10× the steps of the
    same release 1 µm inside it (measured: about 1×)."""
    wall = hanging_link(0.0).simulate(0.1, integrator=integrator, max_steps=200_000, progress=False)
    inside = hanging_link(1e-6).simulate(0.1, integrator=integrator, max_steps=200_000, progress=False)
    assert wall.completed and inside.completed
    assert wall.stats["steps"] <= 10 * inside.stats["steps"], (wall.stats, inside.stats)


@pytest.mark.parametrize("integrator", ["rk45", "radau"])
def test_a_contact_starting_at_rest_does_not_toggle(integrator):
    """The link slides down the wall pressed into it by its weight: one contact, from the
    release on, over the first 10 ms (the journal then travels ~0.5 mm along the wall)."""
    res = hanging_link(0.0).simulate(0.01, integrator=integrator, progress=False)
    assert res.impacts["pin"] == 1
    e = res.eccentricity("pin")
    assert (e[:, 0] ** 2 + e[:, 1] ** 2).min() >= (C * (1 - 1e-9)) ** 2  # never left the wall
    assert abs(e[-1, 1]) > 0.2 * C  # and moved along it


def test_an_impact_at_speed_is_still_located():
    """The same link, its journal centred, under a sideways body force of 50 m/s² hits the wall
    at δ̇ = √(2 g c) ≈ 0.22 m/s ≫ the 1 mm/s floor: a real impact, located as before (a step
    ends on the onset), at the time free flight predicts. Its rebound against an independent
    reference is test_clearance.py's restitution test."""
    g = 50.0
    m = clearsim.Mechanism(gravity=(g, 0.0))
    m.add_body("link", mass=1.0, inertia=1e-4, position=(0.0, -ARM))
    m.clearance_joint("pin", "ground", (0.0, 0.0), "link", (0.0, ARM), journal_radius=0.01, clearance=C,
                      model=clearsim.Dry(friction=0.0))  # fmt: skip
    t_hit = math.sqrt(2 * C / g)
    res = m.simulate(1.02 * t_hit, dt_out=t_hit / 5000, progress=False)
    assert res.impacts["pin"] == 1
    assert res.stats["steps_to_switch"] >= 1
    onset = res.t[int(res.contact_state("pin").argmax())]
    assert onset == pytest.approx(t_hit, abs=2 * t_hit / 5000)
