"""Film thickness, friction torque and power loss of a clearance joint (docs/physics.md §4, "Film
thickness, friction and power") against Petroff's law, the long- and short-bearing closed forms and
the recorded eccentricity; their run summary against the output grid."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import numpy as np
import pytest

import clearsim
from walks import PUMP

R, C, MU, OMEGA = 0.02, 4e-5, 0.05, 100.0


def rotor(film: str, length: float, load: float = 0.0, supply: str = "widest_gap", dry: Optional[clearsim.Dry] = None) -> clearsim.Mechanism:
    """A 1 kg rotor driven at OMEGA in a ground bearing (journal at its centroid, no gravity),
    loaded by ``load`` [N] along −y."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", omega=OMEGA, angle0=0.0)
    model = dry if dry is not None else clearsim.Lubricated(viscosity=MU, length=length, film=film, supply=supply)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=model)
    if load:
        m.force("rotor", (0, 0), (0.0, -load))
    return m


def petroff(length: float) -> float:
    return 2 * math.pi * MU * R**3 * length * OMEGA / C


def in_a_joint(model: object) -> None:
    """Compile ``model`` in a pinned body: its values are checked by the core (issue 29, validation once)."""
    m = clearsim.Mechanism()
    m.add_body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0, 0), "b", (0, 0), journal_radius=0.01, clearance=1e-4, model=model)  # type: ignore[arg-type]
    m.compile()


@pytest.mark.parametrize(("film", "length", "supply"), [("long", 0.1, "widest_gap"), ("short", 0.01, "widest_gap"), ("finite", 0.04, "widest_gap"), ("finite", 0.04, "none")])
def test_a_centred_unloaded_journal_gives_petroffs_torque(film: str, length: float, supply: str) -> None:
    res = rotor(film, length, supply=supply).simulate(0.02, dt_out=1e-3, bearings=True, progress=False)
    torque = res.friction_torque("pin")
    assert np.all(np.abs(torque / -petroff(length) - 1) < 0.01)
    # Couette only; the bearing takes the opposite; the loss is Petroff's torque times ω.
    assert np.allclose(res.friction_torque("pin", "couette"), torque, rtol=1e-6)
    assert np.allclose(res.friction_torque("pin", body="bearing"), -torque, rtol=1e-6)
    assert np.all(np.abs(res.power_loss("pin") / (petroff(length) * OMEGA) - 1) < 0.01)
    b = res.summary()["bearings"]["pin"]
    assert b["mean_power_loss"] == pytest.approx(petroff(length) * OMEGA, rel=0.01)
    assert b["min_film_thickness"] == pytest.approx(C, rel=0.01)


def test_a_loaded_journal_gives_the_long_and_short_closed_forms() -> None:
    """Steadily loaded, the journal turns at ω about a fixed eccentricity ε: the long film
    (half Sommerfeld) gives πμR³Lω(4 + 5ε²)/(c(2 + ε²)√(1 − ε²)), Ocvirk's short film
    2πμR³Lω/(c√(1 − ε²)) + πμRL³ωε²/(8c(1 − ε²)^{3/2}) at the recorded ε."""
    for film, length, load in (("long", 0.1, 3000.0), ("short", 0.01, 100.0)):
        res = rotor(film, length, load).simulate(0.4, dt_out=0.01, rtol=1e-9, atol=1e-12, progress=False)
        eps = float(np.hypot(*res.eccentricity("pin")[-1])) / C
        k, root = math.pi * MU * R**3 * length * OMEGA / C, math.sqrt(1 - eps * eps)
        if film == "long":
            want = k * (4 + 5 * eps**2) / ((2 + eps**2) * root)
        else:
            want = 2 * k / root + math.pi * MU * R * length**3 * OMEGA * eps**2 / (8 * C * (1 - eps**2) ** 1.5)
        assert 0.1 < eps < 0.9
        assert -res.friction_torque("pin")[-1] == pytest.approx(want, rel=1e-4), film
        # The film carries the load: its Poiseuille part −e F_η/2 is the load's moment share.
        assert res.friction_torque("pin", "poiseuille")[-1] < 0


def test_film_thickness_is_the_clearance_less_the_recorded_eccentricity() -> None:
    res = rotor("finite", 0.04, 1000.0).simulate(0.05, dt_out=1e-3, progress=False)
    h = res.film_thickness("pin")
    e = res.eccentricity("pin")
    assert np.allclose(h, C - np.hypot(e[:, 0], e[:, 1]), rtol=0, atol=1e-20)
    assert h.min() < 0.8 * C


def test_the_minimum_film_does_not_depend_on_the_output_grid() -> None:
    m = rotor("finite", 0.04, 1000.0)
    runs = [m.simulate(0.1, dt_out=dt, bearings=True, extremes=["pin"], progress=False) for dt in (1e-2, 1e-3, 3.7e-5)]
    summaries = [r.summary()["bearings"]["pin"] for r in runs]
    for s in summaries[1:]:
        assert s["min_film_thickness"] == pytest.approx(summaries[0]["min_film_thickness"], rel=1e-9)
        assert s["t_min_film"] == pytest.approx(summaries[0]["t_min_film"], abs=1e-9)
        assert s["peak_power_loss"] == pytest.approx(summaries[0]["peak_power_loss"], rel=1e-9)
        assert s["mean_power_loss"] == pytest.approx(summaries[0]["mean_power_loss"], rel=1e-9)
    for r, s in zip(runs, summaries):
        # At least every stored value, and the tracked minimum sits between the samples; the
        # exact monitors of Result.extremes (a search written separately, on the film
        # thickness with the force evaluated) find the same minimum.
        assert s["min_film_thickness"] <= r.film_thickness("pin").min()
        assert s["min_film_thickness"] == pytest.approx(r.extremes("pin", "film_thickness").min, rel=1e-9)
        # The peak power loss is read at the steps' ends: within 0.5 % of the largest stored one.
        assert s["peak_power_loss"] == pytest.approx(r.power_loss("pin").max(), rel=5e-3)
    assert summaries[0]["min_film_thickness"] < runs[0].film_thickness("pin").min()
    # The mean power loss against the stored loss on the finest grid, by trapezoids.
    fine = runs[-1]
    mean = np.sum(0.5 * (fine.power_loss("pin")[1:] + fine.power_loss("pin")[:-1]) * np.diff(fine.t)) / (fine.t[-1] - fine.t[0])
    assert summaries[-1]["mean_power_loss"] == pytest.approx(mean, rel=1e-4)
    # The crank angle at the minimum: the driver's θ = ωt.
    s = summaries[-1]
    assert s["min_film_crank_angle_deg"] == pytest.approx(math.degrees(OMEGA * s["t_min_film"]) % 360, abs=1e-6)
    assert "pin: h_min" in repr(runs[0])


def test_a_run_tracks_the_bearing_summary_only_when_asked_and_says_how_to_ask() -> None:
    """A default run pays for no reading it did not ask for (issue 37: the film monitors made
    every lubricated RK45 step 2.3–3.2× dearer): it tracks no summary, and asking for one names
    the option; with ``bearings=True`` the summary is there and its minimum is the stored
    films' or below, located between them."""
    m = rotor("finite", 0.04, 1000.0)
    plain = m.simulate(0.05, dt_out=1e-3, progress=False)
    assert "monitors" not in plain._raw and not plain.bearings_tracked
    with pytest.raises(clearsim.InputError, match=r"did not track the bearing summary of 'pin' \(pass bearings=True to simulate"):
        plain.bearing_summary()
    assert "bearings" not in plain.summary() and "h_min" not in repr(plain)
    tracked = m.simulate(0.05, dt_out=1e-3, bearings=True, progress=False)
    assert tracked.stats["steps"] == plain.stats["steps"] and tracked.stats["rhs_evaluations"] == plain.stats["rhs_evaluations"]
    b = tracked.bearing_summary()["pin"]
    assert b["min_film_thickness"] <= tracked.film_thickness("pin").min() and b["min_film_thickness"] > 0.0
    assert 0.0 <= b["t_min_film"] <= 0.05 and 0.0 <= b["t_peak_power_loss"] <= 0.05
    assert "pin: h_min" in repr(tracked) and tracked.summary()["bearings"]["pin"] == b
    assert np.array_equal(tracked.film_thickness("pin"), plain.film_thickness("pin"))


def test_the_summary_says_its_window_and_follows_extremes_from() -> None:
    """bearing_summary's means run over one window, which it names (window_start, window_end
    [s], and the printed table's caption): the run, or from extremes_from on — whether or not the
    extremes track the joint (its mean power changed with extremes=True before). Its mean power
    is the stored power's time average over that window (trapezoids on a fine grid); its minimum
    film and peak power are found in that window."""
    from clearsim.joint_readings import summary_markdown

    m = rotor("finite", 0.04, 1000.0)  # the journal sinks from the centre: the loss changes in time
    whole = m.simulate(0.1, dt_out=1e-3, bearings=True, progress=False).bearing_summary()["pin"]
    assert (whole["window_start"], whole["window_end"]) == (0.0, pytest.approx(0.1, abs=1e-15))
    late = [m.simulate(0.1, dt_out=2e-5, extremes=e, extremes_from=0.05, bearings=True, progress=False) for e in (False, True)]
    a, b = (r.bearing_summary()["pin"] for r in late)
    assert a == b and (a["window_start"], a["window_end"]) == (0.05, pytest.approx(0.1, abs=1e-15))
    t, p = late[0].t, late[0].power_loss("pin")
    keep = t >= 0.05
    average = float(np.sum(0.5 * (p[keep][1:] + p[keep][:-1]) * np.diff(t[keep]))) / 0.05
    assert a["mean_power_loss"] == pytest.approx(average, rel=1e-3)
    h = late[0].film_thickness("pin")
    assert a["min_film_thickness"] <= h[keep].min() and a["peak_power_loss"] >= p[keep].max() * (1 - 3e-3)  # the peak at step ends
    assert 0.05 <= a["t_min_film"] <= 0.1 and 0.05 <= a["t_peak_power_loss"] <= 0.1
    assert abs(whole["mean_power_loss"] / a["mean_power_loss"] - 1) > 1e-3  # the window matters here
    assert "t = 0.05 to 0.1 s" in "\n".join(summary_markdown(late[0].summary()["bearings"]))


def test_dry_friction_moment_and_power_in_contact() -> None:
    """A dry pin pressed against its bearing by the load while turning: R_j F_t on the journal,
    −R_b F_t on the bearing, and the friction power −F_t · slip ≈ c_f F_N R_j ω."""
    res = rotor("", 0.0, 50.0, dry=clearsim.Dry(friction=0.1)).simulate(0.05, dt_out=1e-4, progress=False)
    normal, tangential = res.contact_force("pin").T
    touching = res.contact_state("pin") == 2
    assert touching.sum() > 100 and np.all(np.abs(tangential[touching]) == pytest.approx(0.1 * normal[touching], rel=1e-9))
    assert np.allclose(res.friction_torque("pin"), R * tangential * touching, rtol=1e-12, atol=0)
    assert np.allclose(res.friction_torque("pin", body="bearing"), -(R + C) * tangential * touching, rtol=1e-12, atol=0)
    # The slip of the contact points along t = n turned +90°: t·ė + R_j ω (the bearing is fixed).
    e, e_dot = res.eccentricity("pin"), res.eccentricity_rate("pin")
    n = e / np.maximum(np.hypot(e[:, 0], e[:, 1]), 1e-300)[:, None]
    slip = -n[:, 1] * e_dot[:, 0] + n[:, 0] * e_dot[:, 1] + R * OMEGA
    assert np.allclose(res.power_loss("pin")[touching], -(tangential * slip)[touching], rtol=1e-9)
    assert np.all(res.power_loss("pin")[touching] > 0)
    assert np.all(res.power_loss("pin")[~touching] == 0)
    assert "bearings" not in res.summary()  # the summary's film rows are for lubricated joints


def test_a_prismatic_clearance_reads_its_two_ends() -> None:
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("slider", mass=1.0, inertia=1e-3)
    m.prismatic_clearance("ground", (0, 0), "slider", (1, 0), 1e-3, 0.08, clearsim.Dry(), name="G")
    res = m.simulate(0.01, dt_out=1e-3, progress=False)
    h = res.film_thickness("G")
    assert h.shape == (len(res.t), 2)
    assert np.array_equal(h[:, 0], res.film_thickness("G front"))
    assert h[0, 0] == pytest.approx(0.5e-3)


def test_parts_and_bodies_are_checked() -> None:
    res = rotor("short", 0.01).simulate(0.001, dt_out=1e-4, progress=False)
    with pytest.raises(clearsim.InputError, match="part"):
        res.friction_torque("pin", part="viscous")
    with pytest.raises(clearsim.InputError, match="body"):
        res.friction_torque("pin", body="crank")
    with pytest.raises(clearsim.InputError, match="no such clearance joint"):
        res.power_loss("nope")


def test_clearsim_run_writes_the_readings_and_their_summary(tmp_path: Path) -> None:
    """``clearsim run``: the joints CSV columns and the summary's table of the lubricated joints."""
    from clearsim import cli

    text = (Path(__file__).resolve().parents[2] / "scenes" / "nine_bar_lubricated.toml").read_text(encoding="utf-8")
    text = text.replace("cycles = 3 ", "cycles = 0.25 ").replace('joint_quantities = ["eccentricity", "force"]', 'joint_quantities = ["film_thickness", "friction_torque", "power_loss"]')
    text = text[: text.index("[reliability]")]
    scene = tmp_path / "scene.toml"
    scene.write_text(text, encoding="utf-8")
    assert cli.main(["run", str(scene), "-o", str(tmp_path / "out"), "--no-plots", "-q"]) == 0
    header = (tmp_path / "out" / "joints.csv").read_text(encoding="utf-8").splitlines()[0]
    assert "A.film_thickness [m]" in header and "B.friction_torque_bearing [N m]" in header and "A.power_loss [W]" in header
    md = (tmp_path / "out" / "summary.md").read_text(encoding="utf-8")
    assert "| lubricated joint | min film [µm]" in md and "| A |" in md
    import json

    bearings = json.loads((tmp_path / "out" / "summary.json").read_text(encoding="utf-8"))["run"]["bearings"]
    assert set(bearings) == {"A", "B"} and 0 < bearings["A"]["min_film_thickness"] < 5e-4


# ---------------------------------------------------------------- roughness (mixed lubrication)
SIGMA, LOAD = 1e-6, 2000.0


def ramped_rotor(t_end: float, omega_end: float) -> clearsim.Mechanism:
    """The rotor of :func:`rotor` (finite film, L/D = 1) with σ = 1 µm, μ_b = 0.12, loaded by 2 kN,
    started where the asperities carry the load (ε = 0.9925) and driven by θ = a t⁴ from standstill
    to ``omega_end`` at ``t_end``."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", polynomial=[0, 0, 0, 0, omega_end / (4 * t_end**3)])
    model = clearsim.Lubricated(viscosity=MU, length=0.04, film="finite", roughness=SIGMA, boundary_friction=0.12)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=model, initial_eccentricity=(0.0, -0.9925 * C))
    m.force("rotor", (0, 0), (0.0, -LOAD))
    return m


def test_a_rough_journal_runs_up_from_boundary_to_full_film_through_a_stribeck_minimum() -> None:
    t_end, omega_end = 4.0, 200.0
    res = ramped_rotor(t_end, omega_end).simulate(t_end, dt_out=t_end / 400, bearings=True, progress=False)
    omega = omega_end * (res.t / t_end) ** 3
    share = res.asperity_force("pin") / LOAD
    f = np.abs(res.friction_torque("pin")) / (R * LOAD)
    # Boundary: the asperities carry the load at standstill. Once the journal turns, its boundary
    # friction (full from 0.1 mm/s of slip) rolls it a few degrees up the bore against the load:
    # that whirl is a wedge for the film, which then carries a quarter of the load at ω ≈ 0.02 rad/s.
    assert np.all(share[res.t < 0.05] > 0.9)
    assert np.all(share[omega > 20] < 0.01)  # full film
    # No jump: between outputs 0.01 s apart the share and the friction coefficient move little
    # (the most while the boundary friction rises over its 0.1 mm/s slip ramp and rolls the
    # journal up the bore, t ≈ 0.1 s: 0.037 in share, 0.018 in f).
    assert np.max(np.abs(np.diff(share))) < 0.05 and np.max(np.abs(np.diff(f))) < 0.025
    # Stribeck: boundary friction μ_b × share where the slip is past the friction ramp (R ω > v1),
    # a minimum in between, viscous friction growing with the speed beyond.
    developed = (omega * R > 0.01) & (share > 0.5)
    assert np.allclose(f[developed], 0.12 * share[developed], rtol=0.05)
    # The low-speed end: past the boundary friction's own slip ramp (0.1 mm/s) the coefficient
    # is μ_b × share, not the dry law's ramp (which made it fall to 0 below 1 cm/s of slip).
    slow = (omega * R > 5e-4) & (omega * R < 0.01) & (share > 0.5)
    assert slow.sum() > 10 and np.allclose(f[slow], 0.12 * share[slow], rtol=0.05)
    k = int(np.argmin(np.where(omega > 0.5, f, np.inf)))
    assert 2 < omega[k] < 50 and f[k] < 0.1 * f[developed].max() and f[k] < 0.5 * f[-1]
    s = res.summary()["bearings"]["pin"]
    assert s["lambda"] == pytest.approx(s["min_film_thickness"] / SIGMA) and s["lambda"] < 1
    assert set(np.unique(res.contact_state("pin"))) <= {0, 1}  # mixed (1), never the mean surfaces in contact


def test_boundary_friction_at_a_slow_slip_is_mu_b_times_the_asperity_share() -> None:
    """A rough journal (σ = 1 µm, μ_b = 0.1, 2 kN) turning at ω = 0.15 rad/s, a slip of R ω =
    3 mm/s, three quarters of its load on the asperities (the film carries the rest): f = |T_j|/(R F) = μ_b × (asperity share) within 1 % (on the
    dry law's ramp, v0 = 1e-4, v1 = 1e-2 m/s, it read 0.29 of that: f = 0.028 at 94 %). Its own
    slip ramp is checked: boundary_slip must be positive and goes with roughness."""
    omega = 3e-3 / R
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3)
    m.driver("rotor", omega=omega)
    model = clearsim.Lubricated(viscosity=MU, length=0.04, film="finite", roughness=SIGMA, boundary_friction=0.1)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=model, initial_eccentricity=(0.0, -0.9925 * C))
    m.force("rotor", (0, 0), (0.0, -LOAD))
    res = m.simulate(0.5, dt_out=0.05, progress=False)
    share = res.asperity_force("pin")[-1] / LOAD
    f = abs(res.friction_torque("pin")[-1]) / (R * LOAD)
    assert share > 0.5 and f == pytest.approx(0.1 * share, rel=0.01), (f, share)
    with pytest.raises(clearsim.InputError, match="boundary_slip"):
        in_a_joint(clearsim.Lubricated(roughness=1e-6, boundary_slip=0.0))
    with pytest.raises(clearsim.InputError, match="boundary_slip"):
        in_a_joint(clearsim.Lubricated(boundary_slip=1e-4))


def test_the_minimum_film_crank_angle_runs_over_the_loads_720_degree_cycle() -> None:
    """Under a four-stroke load (a table over the driver's angle repeating every 720°) whose
    pulse comes in the second turn (540°–600°), the minimum film comes at its end: its crank angle is
    reported over 0–720° (it was taken modulo 360°), equal to ω t_min in degrees modulo 720."""
    m = rotor("short", 0.01)
    # A steady 500 N (an unloaded short film whirls unstably) and a 3 kN pulse.
    pulse = {"driver": "driver1", "angle": np.radians([0, 540, 560, 600, 720]).tolist(), "fy": [-500.0, -500.0, -3000.0, -500.0, -500.0], "period": 4 * np.pi}
    m.force("rotor", (0, 0), pulse)
    res = m.simulate(2 * 4 * np.pi / OMEGA, dt_out=1e-3, bearings=True, progress=False)
    b = res.bearing_summary()["pin"]
    expected = math.degrees(OMEGA * b["t_min_film"]) % 720.0
    assert b["min_film_crank_angle_deg"] == pytest.approx(expected, abs=1e-6)
    assert 540.0 < b["min_film_crank_angle_deg"] < 720.0
    assert res.crank_cycle() == (0.0, 720.0)


def test_roughness_replaces_the_transition_band_and_is_checked() -> None:
    """Inside the band (c < e, a smooth joint's blend) a rough joint keeps its film in full and
    adds the asperities; without roughness nothing changes."""
    with pytest.raises(clearsim.InputError, match="roughness"):
        in_a_joint(clearsim.Lubricated(roughness=-1e-6))
    with pytest.raises(clearsim.InputError, match="boundary_friction"):
        in_a_joint(clearsim.Lubricated(boundary_friction=0.1))
    m = rotor("short", 0.01)
    with pytest.raises(clearsim.InputError, match=r"clearance joint 'pin2'.roughness.*quarter of the clearance"):  # as it is added
        m.clearance_joint("pin2", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=clearsim.Lubricated(length=0.01, film="short", roughness=C / 3))


def test_a_dry_joint_is_not_a_bearing_with_a_film():
    """The pump (lubricated crank pin A, dry saddle O4) run with ``extremes=True, bearings=True``: the bearing
    summary, the summary and the repr list A only, whose film is positive; O4's gap minimum (its
    penetration, negative) stays in ``extremes``. Before: ``bearings`` listed O4 with
    ``min_film_thickness`` −9.0 µm and the repr printed "O4: h_min -9.01 µm"."""
    m = clearsim.load_scene(PUMP)
    res = m.simulate(0.05, dt_out=1e-3, extremes=True, bearings=True, progress=False)
    assert list(res.bearing_summary()) == ["A"] and list(res.summary()["bearings"]) == ["A"]
    assert res.bearing_summary()["A"]["min_film_thickness"] > 0.0
    assert "O4: h_min" not in repr(res) and "A: h_min" in repr(res)
    assert res.extremes("O4", "film_thickness").min < 0.0  # the penetration, under its own name


def test_the_summary_comes_with_a_point_among_the_extremes() -> None:
    """bearing_summary (and summary()) of a run that also tracks a body point's extremes
    (``extremes=[("rotor", (x, y))]``) is the same as without it. Before: ``KeyError:
    'coordinate'``, from repr(res) too (walk 5: the summary looked for its film monitors among the
    extremes' monitors, and a point's monitor has no coordinate; main's core-tracked summary since)."""
    m = rotor("finite", 0.04, 1000.0)
    plain = m.simulate(0.02, dt_out=1e-3, bearings=True, progress=False).bearing_summary()
    with_point = m.simulate(0.02, dt_out=1e-3, bearings=True, extremes=[("rotor", (0.01, 0.0))], progress=False)
    assert with_point.bearing_summary() == plain and with_point.summary()["bearings"] == plain
    assert "pin: h_min" in repr(with_point)  # the Result's repr (a notebook's display) reads it too
    # the point's own extremes: a point 10 mm from the centroid of a rotor turning at OMEGA
    speed = with_point.extremes("rotor", "velocity", "magnitude", point=(0.01, 0.0))
    assert speed.max == pytest.approx(OMEGA * 0.01, rel=1e-3)


def test_a_motor_driven_crank_reports_the_minimum_film_crank_angle() -> None:
    """A crank turned by a motor (no prescribed driver: a pump on its induction motor, walk 6),
    its load table over the motor's angle: the minimum film's crank angle is the motor body's
    angle then, over the table's 720° cycle. Before, the summary left it out (it looked for a
    driver only) and crank_cycle() said (0, 360)."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=1.0, inertia=1e-3, velocity=(0.0, 0.0, OMEGA))
    m.motor("rotor", stall_torque=1e4, no_load_speed=OMEGA, angle0=0.0, name="motor")  # stiff: ω stays within 0.1 % of ω₀
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=clearsim.Lubricated(viscosity=MU, length=0.01, film="short"))
    pulse = {"driver": "motor", "angle": np.radians([0, 540, 560, 600, 720]).tolist(), "fy": [-500.0, -500.0, -3000.0, -500.0, -500.0], "period": 4 * np.pi}
    m.force("rotor", (0, 0), pulse)
    res = m.simulate(2 * 4 * np.pi / OMEGA, dt_out=1e-4, bearings=True, progress=False)
    b = res.bearing_summary()["pin"]
    theta = np.degrees(np.interp(b["t_min_film"], res.t, res.position("rotor")[:, 2]))
    assert b["min_film_crank_angle_deg"] == pytest.approx(theta % 720.0, abs=1e-6)
    assert b["min_film_crank_angle_deg"] == pytest.approx(math.degrees(OMEGA * b["t_min_film"]) % 720.0, abs=1.0)
    assert 540.0 < b["min_film_crank_angle_deg"] < 720.0
    assert res.crank_cycle() == (0.0, 720.0)
