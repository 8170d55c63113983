"""Clearance joints in whole mechanisms (docs/physics.md §2–§4; issue: revolute clearance joints)."""

import math
import os
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models

OMEGA = 5000 * 2 * math.pi / 60
TURN = 2 * math.pi / OMEGA
DOCS = Path(__file__).resolve().parents[2] / "docs"


def clearance_pendulum(restitution, friction=0.0, law="lankarani_nikravesh"):
    """A link hanging from the ground through a dry clearance joint, no driver."""
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("link", mass=2.0, inertia=0.02, position=(0.15, 0.0), velocity=(0.0, 1.5, 10.0))
    m.clearance_joint(
        "pivot",
        "ground",
        (0.0, 0.0),
        "link",
        (-0.15, 0.0),
        journal_radius=0.01,
        clearance=0.5e-3,
        model=clearsim.Dry(normal_law=law, restitution=restitution, friction=friction),
    )
    return m


def total_energy(m, res, joint="pivot"):
    """Kinetic + gravitational + elastic contact energy K δ^(n+1)/(n+1) (Hertz part of P3)."""
    b = m._bodies[0]
    q, v = res.position("link"), res.velocity("link")
    e = 0.5 * b["mass"] * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * b["inertia"] * v[:, 2] ** 2 + b["mass"] * 9.81 * q[:, 1]
    k = m.compile().contact_stiffness[0]
    delta = np.maximum(np.linalg.norm(res.eccentricity(joint), axis=1) - 0.5e-3, 0.0)
    return e + k * delta**2.5 / 2.5


def test_frictionless_elastic_contact_conserves_energy():
    m = clearance_pendulum(restitution=1.0)
    res = m.simulate(0.5, rtol=1e-10, atol=1e-13, dt_out=1e-4)
    assert sum(res.impacts.values()) > 5
    e = total_energy(m, res)
    assert np.ptp(e) < 1e-6 * np.max(np.abs(e))


@pytest.mark.parametrize("law", ["lankarani_nikravesh", "hunt_crossley", "flores"])
def test_dissipative_contact_loses_energy_monotonically(law):
    m = clearance_pendulum(restitution=0.7, law=law)
    res = m.simulate(0.5, rtol=1e-10, atol=1e-13, dt_out=1e-4)
    e = total_energy(m, res)
    assert sum(res.impacts.values()) > 3
    assert np.all(np.diff(e) < 1e-9 * np.max(np.abs(e)))
    assert e[-1] < e[0] - 1e-3


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))


def test_vanishing_clearance_reproduces_the_ideal_slider_acceleration():
    """1 µm clearance with a stiff, well-damped contact: over the second turn (after the
    start-up impact has decayed) the slider acceleration is the ideal one within 1 % RMS.
    (With the lightly damped steel contact, the journal rings on the contact spring after
    every load reversal: amplitude ≈ sqrt(2 a c)·ω_contact ≈ 10 % of the peak at 1 µm.)"""
    ideal = models.slider_crank("ideal").simulate(2 * TURN, rtol=1e-9, atol=1e-12, dt_out=TURN / 720)
    a0 = ideal.acceleration("slider")[720:, 0]
    errors = {}
    for c in (1e-5, 1e-6):
        dry = clearsim.Dry(normal_law="flores", restitution=0.3, stiffness=1e12)
        m = models.slider_crank("dry", clearance=c, journal_radius=10e-3 - c, dry=dry)
        res = m.simulate(2 * TURN, rtol=1e-8, atol=1e-11, dt_out=TURN / 720)
        errors[c] = rms(res.acceleration("slider")[720:, 0] - a0) / rms(a0)
    assert errors[1e-6] < 0.01
    assert errors[1e-6] < errors[1e-5]


def orbit_figure(results, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), constrained_layout=True)
    colours = {"ideal": "0.3", "dry": "#d55e00", "lubricated": "#0072b2"}
    for kind, res in results.items():
        deg = np.degrees(OMEGA * res.t)
        axes[0].plot(deg, res.acceleration("slider")[:, 0] / 1e3, color=colours[kind], lw=1, label=kind)
        if kind != "ideal":
            e = res.eccentricity("rod-slider") / 0.5e-3
            ax = axes[1] if kind == "dry" else axes[2]
            ax.plot(e[:, 0], e[:, 1], color=colours[kind], lw=0.8)
            circle = np.linspace(0, 2 * np.pi, 200)
            ax.plot(np.cos(circle), np.sin(circle), "k--", lw=0.8)
            ax.set_aspect("equal")
            ax.set_xlabel("e_x / c [-]")
            ax.set_ylabel("e_y / c [-]")
            ax.set_title(f"journal orbit, {kind}")
    axes[0].set_xlabel("crank angle [deg]")
    axes[0].set_ylabel("slider acceleration [km/s²]")
    axes[0].set_yscale("symlog", linthresh=20)
    axes[0].legend()
    axes[0].set_title("slider-crank at 5000 rpm, c = 0.5 mm")
    fig.savefig(path, dpi=130)
    plt.close(fig)


def test_slider_crank_dry_and_lubricated_show_the_known_phenomena():
    results = {kind: models.slider_crank(kind).simulate(2 * TURN, rtol=1e-7, atol=1e-10, dt_out=TURN / 1440) for kind in ("ideal", "dry", "lubricated")}
    a_ideal = results["ideal"].acceleration("slider")[:, 0]
    peak = np.max(np.abs(a_ideal))
    dry, lub = results["dry"], results["lubricated"]
    state = dry.contact_state("rod-slider")
    # Dry: free flight, impacts and contact phases; spikes many times the ideal peak.
    assert np.mean(state == 0) > 0.05 and np.mean(state == 2) > 0.05
    assert dry.impacts["rod-slider"] >= 5
    assert np.max(np.abs(dry.acceleration("slider")[:, 0])) > 3 * peak
    # Lubricated: the orbit stays inside the clearance, no dry contact, spikes reduced ≥ 10×.
    eps = np.linalg.norm(lub.eccentricity("rod-slider"), axis=1) / 0.5e-3
    assert np.max(eps) < 1.0
    assert np.all(lub.contact_state("rod-slider") == 0)
    dry_err = np.max(np.abs(dry.acceleration("slider")[:, 0] - a_ideal))
    lub_err = np.max(np.abs(lub.acceleration("slider")[:, 0] - a_ideal))
    assert lub_err * 10 < dry_err
    if os.environ.get("CLEARSIM_WRITE_DOCS"):
        orbit_figure(results, DOCS / "slider_crank_dry_vs_lubricated.png")


def test_dry_scene_runs_no_film_code_and_forces_balance():
    """A dry joint has no film part; the film-force channels stay exactly zero, and the joint
    force equals −F_N n + F_t t from the recorded components."""
    res = models.slider_crank("dry").simulate(TURN / 2, dt_out=TURN / 720)
    assert np.all(res.film_force("rod-slider") == 0.0)
    e = res.eccentricity("rod-slider")
    norm = np.linalg.norm(e, axis=1)
    n = np.where(norm[:, None] > 0, e / np.where(norm > 0, norm, 1.0)[:, None], [1.0, 0.0])
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    fn, ft = res.contact_force("rod-slider").T
    w = res.dry_weight("rod-slider")
    expected = (-fn * w)[:, None] * n + (ft * w)[:, None] * t
    assert np.allclose(res.joint_force("rod-slider"), expected, atol=1e-9 * (1 + np.max(np.abs(fn))))


def test_lubricated_nine_bar_holds_the_journals_in_the_film():
    """Spec §7: with μ = 0.4 Pa s the long-bearing film holds both journals near ε ≈ 0.9, in the
    film (no contact) but well off the centre: measured max ε over the first quarter cycle
    A 0.92, B 0.79. A film several times too stiff or too soft moves these out of the band."""
    period = 0.4
    res = models.nine_bar("lubricated", clearance=0.5e-3).simulate(period / 4, dt_out=1e-4)
    for j in ("A", "B"):
        eps = np.linalg.norm(res.eccentricity(j), axis=1) / 0.5e-3
        assert 0.7 < np.max(eps) < 0.97, (j, np.max(eps))
        assert np.all(res.contact_state(j) == 0)


def test_lubricated_joint_uses_the_dry_law_only_beyond_the_clearance():
    """μ = 0.04 Pa s lets the journals sink into the transition band (docs/physics.md §7): the dry weight
    is 0 for e ≤ c, the linear blend (e − c)/e0 inside the band and 1 beyond (P18)."""
    c = 0.5e-3
    lub = clearsim.Lubricated(viscosity=0.04, length=0.05)
    res = models.nine_bar("lubricated", clearance=c, lubricated=lub).simulate(0.2, dt_out=1e-4)
    seen_band = False
    for j in ("A", "B"):
        e = np.linalg.norm(res.eccentricity(j), axis=1)
        w = res.dry_weight(j)
        expected = np.clip((e - c) / (0.05 * c), 0.0, 1.0)
        np.testing.assert_allclose(w, expected, atol=1e-12)
        assert np.all(res.film_force(j)[e >= 1.05 * c] == 0.0)
        seen_band |= bool(np.any((e > c) & (e < 1.05 * c)))
    assert seen_band


@pytest.mark.parametrize("integrator", ["rk45", "dop853"])
def test_adaptive_methods_survive_trial_steps_deep_into_contact(integrator):
    """A trial step of a high-order method can drive a journal far into its bearing, where f is
    not finite; the step must be rejected and retried, not end the run."""
    res = models.nine_bar("dry", clearance=0.5e-3).simulate(0.4, integrator=integrator, rtol=1e-6, atol=1e-9)
    assert res.completed
    assert np.all(np.isfinite(res.acceleration("slider9")))


def test_progress_callback_sees_the_simulated_time():
    m = models.nine_bar("lubricated")
    seen = []
    # The callback is called at most every 50 ms of wall time: ~0.5 s of work with RK45.
    raw = m.compile().simulate(m.run_settings(1.2, dt_out=1e-3, integrator="rk45"), seen.append)
    assert raw["error"] is None
    assert seen and all(0.0 < t <= 1.2 for t in seen) and seen == sorted(seen)


def test_a_short_run_shows_no_progress_bar(capfd):
    """The bar appears only for runs longer than a second of wall time; a run of a few
    milliseconds writes nothing (0.02 s simulated: far from a second even on a loaded machine)."""
    res = models.nine_bar("lubricated").simulate(0.02, integrator="rk45", rtol=1e-6, atol=1e-9)
    assert res.completed
    assert capfd.readouterr().err == ""


def test_an_exception_in_the_progress_callback_interrupts_and_keeps_the_partial_result():
    m = models.nine_bar("lubricated")

    def stop(t):
        raise KeyboardInterrupt

    raw = m.compile().simulate(m.run_settings(1.2, dt_out=1e-3, integrator="rk45"), stop)  # ~0.5 s of work
    assert isinstance(raw["error"], clearsim.InterruptedRun)
    assert 0 < len(raw["t"]) < 1201


def single_impact_restitution(k, mass, g, v_in, ce, dt=2e-8):
    """Independent 1-D reference: a mass entering a Lankarani–Nikravesh wall at v_in under a
    body force m g (P3, δ̇⁽⁻⁾ = v_in), integrated by RK4 until it leaves; returns v_out / v_in."""
    d = 3 * (1 - ce * ce) / 4

    def acc(x, v):
        return g - (k * x**1.5 * (1 + d * v / v_in) if x > 0 else 0.0) / mass

    x, v = 0.0, v_in
    while True:
        k1x, k1v = v, max(acc(x, v), -1e300)
        k2x, k2v = v + 0.5 * dt * k1v, acc(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v)
        k3x, k3v = v + 0.5 * dt * k2v, acc(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v)
        k4x, k4v = v + dt * k3v, acc(x + dt * k3x, v + dt * k3v)
        x += dt * (k1x + 2 * k2x + 2 * k3x + k4x) / 6
        v += dt * (k1v + 2 * k2v + 2 * k3v + k4v) / 6
        if x < 0:
            return -v / v_in


@pytest.mark.parametrize("rtol", [1e-5, 1e-9])
def test_impact_onset_is_located_so_restitution_does_not_depend_on_the_tolerance(rtol):
    """A centred journal falls across its clearance (a body force along +x) and hits the bearing
    head-on: the rebound height over the drop height c gives the restitution, which must match an
    independent 1-D integration of the Lankarani–Nikravesh impact at a loose and a tight
    tolerance — true only if δ̇⁽⁻⁾ is taken at the located onset of contact, not from a trial
    stage."""
    c, g = 0.5e-3, 50.0
    m = clearsim.Mechanism(gravity=(g, 0.0))
    m.add_body("puck", mass=1.0, inertia=0.01, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0.0, 0.0), "puck", (0.0, 0.0), journal_radius=0.01, clearance=c,
                      model=clearsim.Dry(restitution=0.9, friction=0.0))
    t_fall = math.sqrt(2 * c / g)
    res = m.simulate(2.3 * t_fall, rtol=rtol, atol=rtol * 1e-4, dt_out=t_fall / 5000, progress=False)
    assert res.impacts["pin"] == 1
    ex = res.eccentricity("pin")[:, 0]
    after = np.argmax(ex) + np.argmax(res.contact_state("pin")[np.argmax(ex):] == 0)
    rebound = c - np.min(ex[after:])
    expected = single_impact_restitution(m.compile().contact_stiffness[0], 1.0, g, math.sqrt(2 * g * c), 0.9)
    assert 0.85 < expected < 0.95
    assert math.sqrt(rebound / c) == pytest.approx(expected, rel=2e-3)


def test_dry_impacts_converge_with_the_tolerance():
    """Steps end where a contact starts or ends and where the friction ramp turns (stats
    ``steps_to_switch``), so no step straddles a kink of the joint force and the error follows
    the tolerance through the impacts: on
    the dry slider-crank (≈ 40 contact switches a cycle) three methods at rtol ≈ 1e-10 agree
    with a DOP853 reference at 1e-13 — itself confirmed by RADAU5 at 1e-12 — to 1e-9 m, and the
    explicit methods' errors fall ≥ 10× from rtol 1e-8 to 1e-10. (Steps straddling the switches
    left DOP853 at 1e-10 off by 3e-9 m, and at 1e-11 by 5e-9 m.) The impacts make the error at
    one tolerance erratic within a factor of ~10, so each figure is the median over rtol × (0.8,
    1, 1.25)."""
    m = models.slider_crank("dry")
    cycle = 60.0 / 5000.0
    t = np.linspace(0.0, cycle, 601)

    def slider_x(integrator, rtol):
        res = m.simulate(cycle, integrator=integrator, rtol=rtol, atol=rtol * 1e-3, t_out=t, progress=False)
        assert res.completed
        return res.position("slider")[:, 0], res.stats

    ref, stats = slider_x("dop853", 1e-13)
    assert stats["steps_to_switch"] >= 20
    assert np.max(np.abs(slider_x("radau", 1e-12)[0] - ref)) < 1e-11

    def median_error(integrator, rtol):
        return np.median([np.max(np.abs(slider_x(integrator, rtol * f)[0] - ref)) for f in (0.8, 1.0, 1.25)])

    assert median_error("radau", 1e-10) < 1e-9
    for integrator in ("dop853", "rk45"):
        fine = median_error(integrator, 1e-10)
        assert fine < 1e-9, integrator
        assert median_error(integrator, 1e-8) > 10 * fine, integrator


def test_a_locked_up_mechanism_stops_and_names_the_joint():
    """A rod shorter than the crank cannot follow it past ~37°: the dry journal is driven into
    its bearing. The run stops once the penetration exceeds max(c, 0.05 R_j) (before this check it
    ran on with the journal 14 clearances deep), names the joint and keeps the partial result."""
    m = clearsim.models.slider_crank("dry", clearance=0.5e-3, journal_radius=9.5e-3, rod_length=0.03)
    with pytest.raises(clearsim.SimulationError, match="locked up") as info:
        m.simulate(0.012, progress=False)
    err = info.value
    assert err.joint == "rod-slider" and err.penetration > 0.5e-3
    assert 0.0 < err.t < 0.012 and len(err.result.t) > 10 and err.result.t[-1] <= err.t
    # The ideal twin of a sound slider-crank never comes near the limit.
    ok = clearsim.models.slider_crank("dry", clearance=0.5e-3).simulate(0.012, progress=False)
    assert ok.completed


def test_outputs_inside_a_contact_use_its_impact_speed_to_the_end():
    """Within one contact the Lankarani–Nikravesh force F_N = K δ^1.5 (1 + D δ̇/δ̇⁽⁻⁾) (P3) uses
    the impact speed δ̇⁽⁻⁾ of that contact at every instant, so the δ̇⁽⁻⁾ implied by each recorded
    output, D δ̇ / (F_N/(K δ^1.5) − 1), is the same to the last output of the contact. The
    outputs of the step that ended a contact were evaluated with the memory already cleared
    (|δ̇| instead of δ̇⁽⁻⁾): measured 77 % off before the fix, 6e-13 after."""
    m = models.slider_crank("dry", dry=clearsim.Dry(restitution=0.5, friction=0.0))
    r = m.simulate(0.024, dt_out=2e-7, rtol=1e-8, atol=1e-11)
    c, k = 0.5e-3, m.compile().contact_stiffness[0]
    e, e_dot = r.eccentricity("rod-slider"), r.eccentricity_rate("rod-slider")
    norm = np.linalg.norm(e, axis=1)
    delta, delta_dot = norm - c, np.sum(e * e_dot, axis=1) / norm
    normal = r.contact_force("rod-slider")[:, 0]
    d = 3 * (1 - 0.5**2) / 4
    usable = (r.contact_state("rod-slider") == 2) & (delta > 1e-9) & (np.abs(delta_dot) > 1e-4)
    implied = d * delta_dot / (normal / (k * np.where(delta > 0, delta, 1.0) ** 1.5) - 1)
    contact = np.flatnonzero(r.contact_state("rod-slider") == 2)
    episodes = [ep for ep in np.split(contact, np.flatnonzero(np.diff(contact) > 1) + 1) if usable[ep].sum() >= 6]
    assert len(episodes) >= 4
    for ep in episodes:
        v = implied[ep[usable[ep]]]
        median = np.median(v)
        assert np.max(np.abs(v[-3:] - median)) < 1e-6 * abs(median), (r.t[ep[0]], v[-3:], median)


@pytest.mark.parametrize("omega", [100.0, -100.0])
def test_a_loaded_journal_settles_at_the_long_bearing_attitude_angle(omega):
    """A 10 kg shaft turning at ±100 rad/s in a lubricated bearing (R = 10 mm, c = 0.1 mm,
    L = 20 mm, μ = 0.05 Pa s) under its weight settles where the film carries the load. Closed
    forms of the half-Sommerfeld long bearing (docs/physics.md §4, wedge = θ̇ since the bearing is
    fixed and the journal does not whirl): the attitude angle φ between the load line and the
    eccentricity, tan φ = π√(1 − ε²)/(2ε), turned from the load line in the direction of
    rotation (so a counter-clockwise shaft sits down and to the right), and the load
    W = 6μ|θ̇|LR(R/c)² ε√(π²(1 − ε²) + 4ε²)/((2 + ε²)(1 − ε²))."""
    mass, r_j, c, length, mu = 10.0, 0.01, 1e-4, 0.02, 0.05
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("shaft", mass=mass, inertia=1e-3)
    m.clearance_joint("bearing", "ground", (0, 0), "shaft", (0, 0), journal_radius=r_j, clearance=c,
                      model=clearsim.Lubricated(viscosity=mu, length=length))  # fmt: skip
    m.driver("shaft", omega=omega)
    r = m.simulate(0.5, dt_out=1e-3)
    ex, ey = r.eccentricity("bearing")[-1] / c
    eps = math.hypot(ex, ey)
    assert ey < 0 and (ex > 0) == (omega > 0), (ex, ey)
    phi = math.atan2(abs(ex), -ey)  # from the load line (−y) toward the eccentricity
    assert math.degrees(abs(phi - math.atan(math.pi * math.sqrt(1 - eps**2) / (2 * eps)))) < 0.2, (math.degrees(phi), eps)
    load = 6 * mu * abs(omega) * length * r_j * (r_j / c) ** 2 * eps * math.sqrt(math.pi**2 * (1 - eps**2) + 4 * eps**2)
    load /= (2 + eps**2) * (1 - eps**2)
    assert load == pytest.approx(mass * 9.81, rel=0.01)
    assert r.joint_force("bearing")[-1] == pytest.approx([0.0, mass * 9.81], abs=1e-3 * mass * 9.81)
