"""Force elements, loads, motors and the energy balance, against closed forms."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

import clearsim
from clearsim import InputError, _core, models


def slider_on_spring(k: float = 800.0, c: float = 0.0, m: float = 2.0) -> clearsim.Mechanism:
    """A mass on a horizontal guide, tied to the origin by a spring-damper of free length 0.2 m,
    released from x = 0.3 m."""
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("mass", mass=m, inertia=0.1, position=(0.3, 0.0))
    mech.prismatic("ground", (0, 0), "mass", (0, 0), axis=(1, 0))
    mech.spring("ground", (0, 0), "mass", (0, 0), k, damping=c, free_length=0.2)
    return mech


def test_spring_mass_oscillates_at_its_natural_frequency():
    res = slider_on_spring().simulate(0.5, dt_out=1e-3, rtol=1e-9, atol=1e-12, progress=False)
    w = math.sqrt(800.0 / 2.0)
    x = res.position("mass")[:, 0]
    assert np.max(np.abs(x - (0.2 + 0.1 * np.cos(w * res.t)))) < 1e-8


def test_damped_spring_mass_decays_as_the_closed_form():
    k, c, m = 800.0, 8.0, 2.0
    res = slider_on_spring(k, c, m).simulate(0.5, dt_out=1e-3, rtol=1e-9, atol=1e-12, progress=False)
    wn, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - zeta**2)
    t = res.t
    exact = 0.2 + 0.1 * np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t))
    assert np.max(np.abs(res.position("mass")[:, 0] - exact)) < 1e-8


def test_free_length_defaults_to_the_assembled_distance():
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("mass", mass=1.0, inertia=0.1, position=(0.3, 0.0))
    mech.prismatic("ground", (0, 0), "mass", (0, 0), axis=(1, 0))
    mech.spring("ground", (0, 0), "mass", (0, 0), 1e4)
    res = mech.simulate(0.1, dt_out=1e-3, progress=False)
    assert np.max(np.abs(res.position("mass")[:, 0] - 0.3)) < 1e-12  # no preload: stays put


def test_tabulated_spring_matches_the_linear_one():
    lin = slider_on_spring().simulate(0.2, dt_out=1e-3, rtol=1e-9, atol=1e-12, progress=False)
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("mass", mass=2.0, inertia=0.1, position=(0.3, 0.0))
    mech.prismatic("ground", (0, 0), "mass", (0, 0), axis=(1, 0))
    mech.spring("ground", (0, 0), "mass", (0, 0), free_length=0.2, force_table={"deflection": [-1.0, 1.0], "force": [-800.0, 800.0]})
    tab = mech.simulate(0.2, dt_out=1e-3, rtol=1e-9, atol=1e-12, progress=False)
    assert np.max(np.abs(lin.position("mass") - tab.position("mass"))) < 1e-10


def test_rotational_spring_rotor_oscillates():
    k, inertia = 5.0, 0.02
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("rotor", mass=1.0, inertia=inertia, position=(0.0, 0.0), angle=0.3)
    mech.revolute("ground", (0, 0), "rotor", (0, 0))
    mech.rotational_spring("ground", "rotor", k, angle0=0.0)
    res = mech.simulate(1.0, dt_out=1e-3, rtol=1e-9, atol=1e-12, progress=False)
    theta = res.position("rotor")[:, 2]
    assert np.max(np.abs(theta - 0.3 * np.cos(math.sqrt(k / inertia) * res.t))) < 1e-8


def test_time_table_force_on_a_free_body_gives_the_impulse():
    # F_x = 10 t N on [0, 1] s (a ramp), held at 10 N afterwards; v = ∫F/m dt.
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("puck", mass=2.0, inertia=0.01, position=(0.0, 0.0))
    mech.force("puck", (0, 0), {"t": [0.0, 1.0], "fx": [0.0, 10.0]})
    res = mech.simulate(1.5, dt_out=0.01, rtol=1e-10, atol=1e-12, progress=False)
    t = res.t
    v_exact = np.where(t <= 1.0, 2.5 * t**2, 2.5 + 5.0 * (t - 1.0))
    assert np.max(np.abs(res.velocity("puck")[:, 0] - v_exact)) < 1e-8


def test_follower_force_gives_a_constant_torque():
    # A body pinned at its centroid; a 4 N force at (0.1, 0) along the body's y axis.
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("wheel", mass=1.0, inertia=0.02, position=(0.0, 0.0))
    mech.revolute("ground", (0, 0), "wheel", (0, 0))
    mech.force("wheel", (0.1, 0.0), (0.0, 4.0), frame="body")
    res = mech.simulate(0.5, dt_out=0.01, rtol=1e-10, atol=1e-12, progress=False)
    alpha = 4.0 * 0.1 / 0.02
    assert np.max(np.abs(res.position("wheel")[:, 2] - 0.5 * alpha * res.t**2)) < 1e-8


def test_angle_table_torque_does_the_work_of_its_integral():
    # A rotor spinning at 20 rad/s gets +T on θ ∈ [0, π) and −T on [π, 2π): after each full
    # turn the speed is back, in between ½Jω² − ½Jω0² = ∫T dθ.
    inertia, w0, tq = 0.01, 20.0, 0.05
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("rotor", mass=1.0, inertia=inertia, position=(0, 0), velocity=(0, 0, w0))
    mech.revolute("ground", (0, 0), "rotor", (0, 0))
    eps = 1e-9
    mech.motor("rotor", stall_torque=1e-12, no_load_speed=1e12, name="spin")  # only to name the rotor's angle
    mech.torque("rotor", {"driver": "spin", "angle": [0, math.pi - eps, math.pi, 2 * math.pi - eps], "torque": [tq, tq, -tq, -tq], "period": 2 * math.pi})
    res = mech.simulate(0.6, dt_out=1e-3, rtol=1e-10, atol=1e-12, progress=False)
    theta = res.position("rotor")[:, 2]
    w = res.velocity("rotor")[:, 2]
    phase = np.mod(theta, 2 * math.pi)
    work = np.where(phase < math.pi, tq * phase, tq * (2 * math.pi - phase))
    assert np.max(np.abs(0.5 * inertia * (w**2 - w0**2) - work)) < 1e-6


def test_motor_spins_up_to_the_speed_where_its_torque_meets_the_damper():
    inertia, ts, w0, c = 0.01, 2.0, 100.0, 0.01
    mech = clearsim.Mechanism(gravity=(0, 0))
    mech.add_body("rotor", mass=1.0, inertia=inertia, position=(0, 0))
    mech.revolute("ground", (0, 0), "rotor", (0, 0))
    mech.rotational_spring("ground", "rotor", 0.0, damping=c)
    mech.motor("rotor", ts, w0)
    res = mech.simulate(0.2, dt_out=1e-3, rtol=1e-10, atol=1e-12, progress=False)
    a = ts / w0 + c
    w_exact = ts / a * (1 - np.exp(-a / inertia * res.t))
    assert np.max(np.abs(res.velocity("rotor")[:, 2] - w_exact)) < 1e-7


def test_energy_balance_of_a_damped_spring_pendulum():
    mech = clearsim.Mechanism(gravity=(0, -9.81))
    mech.add_body("bob", mass=2.0, inertia=0.1, position=(0.3, 0))
    mech.revolute("ground", (0, 0), "bob", (-0.3, 0))
    mech.rotational_spring("ground", "bob", 5.0, damping=0.3)
    mech.spring("ground", (0.5, 0.2), "bob", (0, 0), 300.0, damping=1.0, free_length=0.1)
    mech.torque("bob", {"t": [0.0, 1.0], "torque": [0.0, 2.0]})
    res = mech.simulate(2.0, dt_out=0.05, rtol=1e-9, atol=1e-12, progress=False, outputs=["states", "energy"])
    e = res.energy()
    assert e["damper"][-1] < -0.1 and e["dissipated"][-1] == pytest.approx(-e["damper"][-1])  # the dampers took energy out
    assert e["load"][-1] != 0.0
    assert np.ptp(e["balance"]) < 1e-6 * (np.max(np.abs(e["spring"])) + np.max(e["kinetic"]))


def test_work_does_not_depend_on_the_output_grid():
    build = lambda: models.slider_crank("dry")  # noqa: E731
    coarse = build().simulate(0.012, dt_out=0.012 / 4, outputs=["energy"], progress=False).energy()
    fine = build().simulate(0.012, dt_out=0.012 / 400, outputs=["energy"], progress=False).energy()
    for key in ("driver", "contact", "friction", "kinetic"):
        assert coarse[key][-1] == pytest.approx(fine[key][-1], rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("kind", ["dry", "lubricated"])
def test_energy_balance_of_the_clearance_slider_crank(kind):
    """Driver work in, joint work (impacts, friction, film) out: what is left over is the
    Baumgarte stabilisation's work, small against both."""
    res = models.slider_crank(kind).simulate(0.024, outputs=["states", "energy"], rtol=1e-9, atol=1e-12, progress=False)
    e = res.energy()
    assert e["contact"][-1] + e["friction"][-1] < 0.0 and e["friction"][-1] <= 0.0
    assert np.ptp(e["balance"]) < 2e-3 * abs(e["driver"][-1]) + 1e-3 * np.max(e["kinetic"])


def test_a_press_load_over_part_of_the_stroke_runs_and_pickles():
    m = models.nine_bar("dry")
    m.force("slider9", (0, 0), {"driver": "drive1", "angle": np.radians([0, 200, 220, 300, 320, 360]), "fy": [0, 0, 300, 300, 0, 0], "period": 2 * math.pi})
    res = m.simulate(0.4, progress=False)
    assert res.completed
    again = pickle.loads(pickle.dumps(m))
    assert again.description() == m.description()


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda m: m.spring("ground", (0, 0), "mass", (0, 0), -1.0), "stiffness"),
        (lambda m: m.spring("ground", (0, 0), "mass", (0, 0)), "stiffness"),
        (lambda m: m.spring("ground", (0, 0), "mass", (0, 0), 1.0, force_table={"deflection": [0, 1], "force": [0, 1]}), "stiffness"),
        (lambda m: m.spring("ground", (0, 0), "mass", (0, 0), force_table={"deflection": [0, 0], "force": [0, 1]}), "force_table.x[1]"),
        (lambda m: m.spring("mass", (0, 0), "mass", (0, 0), 1.0), "body_b"),
        (lambda m: m.force("mass", (0, 0), 5.0), "value"),
        (lambda m: m.force("mass", (0, 0), (1.0, float("nan"))), "value[1]"),
        (lambda m: m.force("mass", (0, 0), (1.0, 0.0), frame="local"), "frame"),
        # An unknown driver is found when the mechanism compiles (it may be added later).
        (lambda m: m.force("mass", (0, 0), {"driver": "crank", "angle": [0, 1], "fx": [0, 1]}).description(), "force 'force1'.value.driver"),
        (lambda m: m.force("mass", (0, 0), {"driver": 3, "angle": [0, 1], "fx": [0, 1]}), "value.driver"),
        (lambda m: m.force("mass", (0, 0), {"t": [0, 1], "fx": [0, 1], "period": 0.5}), "fx.period"),
        (lambda m: m.force("mass", (0, 0), {"t": [0, 1], "fz": [0, 1]}), "value.fz"),
        (lambda m: m.force("mass", (0, 0), {"t": [0, 1, 2], "fx": [0, 1]}), "fx.x"),
        (lambda m: m.force("mass", (0, 0), {"fx": [0, 1]}), "value"),
        (lambda m: m.motor("mass", 1.0, 0.0), "no_load_speed"),
        (lambda m: m.motor("mass", -1.0, 10.0), "stall_torque"),
        (lambda m: m.torque("mass", 1.0, reaction="mass"), "reaction"),
        (lambda m: m.torque("mass", {"t": [0, 1], "torque": [0, "x"]}), "value.torque"),
        (lambda m: m.rotational_spring("ground", "mass", 1.0, damping=-2.0), "damping"),
    ],
)
def test_bad_force_elements_name_the_field(call, field):
    mech = clearsim.Mechanism()
    mech.add_body("mass", mass=1.0, inertia=0.1, position=(0.3, 0.0))
    with pytest.raises(InputError) as err:
        call(mech)
        mech.compile()  # the values' ranges are the core's checks (issue 29, validation once)
    assert err.value.field == field or err.value.field.endswith(f"'.{field}"), err.value.field


def test_descriptions_enter_the_core_through_one_checked_path():
    """The core reads a description (dict or JSON) with serde and names the element at fault."""
    desc = slider_on_spring().description()
    _core.compile(desc)
    bad = slider_on_spring().description()
    del bad["bodies"][0]["mass"]
    with pytest.raises(InputError, match=r"body 'mass'.*missing field `mass`"):
        _core.compile(bad)
    bad = slider_on_spring().description()
    bad["forces"][0]["stiffness"] = -5.0
    with pytest.raises(InputError) as err:
        _core.compile(bad)
    assert err.value.field == "force 'spring1'.stiffness"
    bad = slider_on_spring().description()
    bad["forces"][0]["kind"] = "bungee"
    with pytest.raises(InputError, match="unknown variant `bungee`"):
        _core.compile(bad)


def test_undriven_spring_and_gravity_four_bar_conserves_energy():
    """An undriven crank-rocker (Grashof: 0.06 + 0.22 < 0.2 + 0.15, no singular pose) with
    ideal joints under gravity and a spring: kinetic + gravity + spring energy stays constant,
    and the drift falls with the tolerance (no load, damper or driver)."""
    a, d, r1, r2 = np.array([0.0, 0.06]), np.array([0.22, 0.0]), 0.2, 0.15
    dist = np.linalg.norm(d - a)
    along = (r1**2 - r2**2 + dist**2) / (2 * dist)
    b = a + along * (d - a) / dist + math.sqrt(r1**2 - along**2) * np.array([a[1] - d[1], d[0] - a[0]]) / dist
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("crank", mass=0.5, inertia=2e-3, position=(0.0, 0.03), angle=math.pi / 2)
    m.add_body("coupler", mass=0.8, inertia=6e-3, position=tuple((a + b) / 2), angle=math.atan2(*(b - a)[::-1]))
    m.add_body("rocker", mass=0.6, inertia=4e-3, position=tuple((b + d) / 2), angle=math.atan2(*(b - d)[::-1]))
    m.revolute("ground", (0.0, 0.0), "crank", (-0.03, 0.0))
    m.revolute("crank", (0.03, 0.0), "coupler", (-0.1, 0.0))
    m.revolute("coupler", (0.1, 0.0), "rocker", (0.075, 0.0))
    m.revolute("rocker", (-0.075, 0.0), "ground", (0.22, 0.0))
    m.spring("ground", (0.1, -0.1), "coupler", (0.0, 0.0), 400.0, free_length=0.15)
    for rtol, bound in ((1e-6, 1e-5), (1e-8, 1e-7), (1e-10, 1e-9)):  # measured: 6e-7, 3e-9, 3e-11
        res = m.simulate(1.0, dt_out=1e-2, rtol=rtol, atol=rtol * 1e-3, outputs=["states", "energy"], progress=False)
        e = res.energy()
        scale = np.max(e["kinetic"]) + np.ptp(e["gravity"]) + np.max(e["spring"])
        assert np.max(e["kinetic"]) > 1.0
        assert np.ptp(e["balance"]) < bound * scale, (rtol, np.ptp(e["balance"]) / scale)


def test_motor_driven_flywheel_settles_at_the_closed_form_speed_under_a_load_torque():
    """T_s (1 − ω/ω₀) = T_L: ω* = ω₀ (1 − T_L/T_s), approached as ω* (1 − e^(−t/τ)), τ = J ω₀/T_s."""
    inertia, ts, w0, tl = 0.05, 4.0, 150.0, 1.0
    m = clearsim.Mechanism(gravity=(0, 0))
    m.add_body("flywheel", mass=3.0, inertia=inertia, position=(0, 0))
    m.revolute("ground", (0, 0), "flywheel", (0, 0))
    m.motor("flywheel", ts, w0)
    m.torque("flywheel", -tl)
    res = m.simulate(30.0, dt_out=0.1, rtol=1e-10, atol=1e-12, progress=False, outputs=["states", "energy"])  # 16 τ
    w_star, tau = w0 * (1 - tl / ts), inertia * w0 / ts
    w = res.velocity("flywheel")[:, 2]
    assert np.max(np.abs(w - w_star * (1 - np.exp(-res.t / tau)))) < 1e-7 * w_star
    assert w[-1] == pytest.approx(w_star, rel=1e-6)
    e = res.energy()
    assert e["motor"][-1] > 0 > e["load"][-1]
    assert np.ptp(e["balance"]) < 1e-6 * e["motor"][-1]


def test_stiff_spring_damper_enters_the_implicit_newton_matrix():
    """An overdamped stiff spring-damper (eigenvalues −1e3 and −1e7 1/s): RADAU5 with the
    spring's derivatives in its Newton matrix takes large steps without rejections and matches
    the closed form x(t) = A e^{r1 t} + B e^{r2 t}."""
    k, c, mass = 1e10, 1e7, 1.0
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("block", mass=mass, inertia=1.0, position=(0.101, 0.0))
    m.prismatic("ground", (0.0, 0.0), "block", (0.0, 0.0), axis=(1.0, 0.0))
    m.spring("ground", (0.0, 0.0), "block", (0.0, 0.0), stiffness=k, damping=c, free_length=0.1)
    res = m.simulate(0.02, integrator="radau", dt_out=1e-3, progress=False)
    r1, r2 = np.roots([mass, c, k])
    exact = 0.001 * (r2 * np.exp(r1 * res.t) - r1 * np.exp(r2 * res.t)) / (r2 - r1)
    assert np.max(np.abs(res.position("block")[:, 0] - 0.1 - exact)) < 1e-9
    assert res.stats["rejected_steps"] == 0 and res.stats["steps"] < 200  # without it: 38 rejected, 162 steps
