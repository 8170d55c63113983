"""A dry pin in its bore as a line contact, Dry(stiffness_form="cylindrical", length=L)
(docs/physics.md §3): Johnson's law by hand, a resting pin's penetration against it and against
its length, and the option's checks."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim
from clearsim import Dry, InputError

M, R_J, C = 20.0, 0.01, 1e-4


def johnson_penetration(force: float, length: float) -> float:
    """δ = (P/(πE*)) [ln(4πE*R*/P) − 1], P = F/L, steel on steel, R* = R_b R_j/(R_b − R_j)."""
    e_star = 207e9 / (2 * (1 - 0.3**2))
    r_star = (R_J + C) * R_J / C
    x = force / length / (math.pi * e_star)
    return x * (math.log(4 * r_star / x) - 1)


def resting_penetration(length: float) -> float:
    """A pin released 1 µm above the bottom of its bearing, settled under its weight."""
    m = clearsim.Mechanism(gravity=(0, -9.81))
    m.add_body("pin", mass=M, inertia=1e-3, position=(0, 0))
    dry = Dry(friction=0.0, restitution=0.5, normal_law="flores", stiffness_form="cylindrical", length=length)
    m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=dry, initial_eccentricity=(0, -C + 1e-6))
    res = m.simulate(0.1, dt_out=1e-3, rtol=1e-8, atol=1e-11, progress=False)
    assert res.completed
    e = np.hypot(*res.eccentricity("J").T)
    return float(np.mean(e[-10:]) - C)


def in_a_joint(model: object) -> None:
    """Compile ``model`` in a pinned body: its values are checked by the core (issue 29, validation once)."""
    m = clearsim.Mechanism()
    m.add_body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0, 0), "b", (0, 0), journal_radius=0.01, clearance=1e-4, model=model)  # type: ignore[arg-type]
    m.compile()

def test_hand_value_of_johnsons_line_contact():
    # 8.5 kN on a 20 mm pin, R_j = 10 mm, c = 0.5 mm (R* = 0.21 m): δ = 14.83 µm by hand
    # (rust/laws/contact_line.rs); the point-contact form gives 12.6 µm whatever the length.
    e_star = 207e9 / (2 * (1 - 0.3**2))
    x = 8500 / 0.02 / (math.pi * e_star)
    assert x * (math.log(4 * 0.21 / x) - 1) == pytest.approx(1.48296e-5, rel=1e-5)


def test_a_resting_pin_penetrates_about_half_as_deep_when_twice_as_long():
    short, long = resting_penetration(0.02), resting_penetration(0.04)
    weight = M * 9.81
    assert short == pytest.approx(johnson_penetration(weight, 0.02), rel=0.01)
    assert long == pytest.approx(johnson_penetration(weight, 0.04), rel=0.01)
    assert 0.5 < long / short < 0.55  # ½ (ln 2K − 1)/(ln K − 1), K = 4πE*R*L/F


def test_cylindrical_form_is_checked_by_name():
    with pytest.raises(InputError) as e:
        Dry(stiffness_form="cylindrical")
    assert e.value.field == "length"
    with pytest.raises(InputError) as e:
        Dry(length=0.02)
    assert e.value.field == "length"
    with pytest.raises(InputError):
        Dry(stiffness_form="cylinder", length=0.02)
    with pytest.raises(InputError, match="length"):
        in_a_joint(Dry(stiffness_form="cylindrical", length=-1.0))

    def compile_with(dry: Dry) -> None:
        m = clearsim.Mechanism()
        m.add_body("pin", mass=1.0, inertia=1e-3, position=(0, 0))
        m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=dry)
        m.compile()

    compile_with(Dry(stiffness_form="cylindrical", length=0.02))
    with pytest.raises(InputError, match="stiffness"):
        compile_with(Dry(stiffness_form="cylindrical", length=0.02, stiffness=1e10))
    with pytest.raises(InputError, match="exponent"):
        compile_with(Dry(stiffness_form="cylindrical", length=0.02, exponent=1.1))
    m = clearsim.Mechanism()
    m.add_body("s", mass=1.0, inertia=1e-3, position=(0, 0))
    with pytest.raises(InputError, match="revolute"):
        m.prismatic_clearance("ground", (0, 0), "s", (1, 0), 1e-3, 0.05, Dry(stiffness_form="cylindrical", length=0.02))
