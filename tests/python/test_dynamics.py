"""Periodic or chaotic (issue 40): harmonic loads and motions, Poincaré sections at exact times,
bifurcation diagrams, the largest Lyapunov exponent through impacts, spectra — each against an
independent result: Baker & Gollub's pendulum integrated by SciPy as a plain ODE with its own
variational exponent, the bouncing ball's published period doubling and its exact contraction
ln(e)/T, the slider-crank's exact kinematics, closed forms (tests/python/dynamics_reference.py).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from dynamics_reference import PERIOD, ball_impacts, ball_period_doubling, pendulum_exponent, pendulum_sections, repeat_period
from heat_reference import L, OIL, OMEGA, T_AMB, rotor
from scipy.integrate import solve_ivp

import clearsim
from clearsim import dynamics, models
from clearsim.cli import main
from clearsim.dynamics.classify import classify

TIGHT = dict(integrator="dop853", rtol=1e-9, atol=1e-11)
SCENE = Path(__file__).resolve().parents[1] / "data" / "scenes" / "driven_pendulum.toml"


# ---------------------------------------------------------------------------- Harmonic
def test_a_harmonic_torque_drives_the_pendulum_as_its_equation():
    """The mechanism with clearsim.Harmonic(g, 2/3) as its torque follows θ'' + θ'/2 + sin θ =
    g cos(2t/3) as SciPy integrates it."""
    g = 1.15
    res = models.driven_pendulum(g).simulate(2 * PERIOD, dt_out=PERIOD / 16, progress=False, **TIGHT)
    ode = lambda t, y: [y[1], -y[1] / 2 - math.sin(y[0]) + g * math.cos(2 * t / 3)]  # noqa: E731
    ref = solve_ivp(ode, (0, 2 * PERIOD), [0.2, 0.0], method="DOP853", rtol=1e-11, atol=1e-13, t_eval=res.t)
    np.testing.assert_allclose(res.position("bob")[:, 2], ref.y[0], atol=2e-7)
    np.testing.assert_allclose(res.velocity("bob")[:, 2], ref.y[1], atol=2e-7)


def test_a_harmonic_driver_moves_the_body_by_its_law_and_a_force_component_is_one():
    h = clearsim.Harmonic(0.3, 40.0, phase=0.7, offset=-0.2)
    assert h.period == pytest.approx(2 * math.pi / 40.0) and h(0.0) == pytest.approx(-0.2 + 0.3 * math.cos(0.7))
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("arm", mass=1.0, inertia=0.01, ends=((0.0, 0.0), (0.1, 0.0)))
    m.revolute("ground", (0.0, 0.0), "arm", (-0.05, 0.0))
    m.driver("arm", law=h, name="wave")
    m.add_body("puck", mass=2.0, inertia=0.01, position=(1.0, 0.0))
    m.force("puck", (0.0, 0.0), (clearsim.Harmonic(4.0, 10.0), 0.0), name="push")
    res = m.simulate(0.5, dt_out=0.5 / 200, rtol=1e-10, atol=1e-12, progress=False)
    t = res.t
    np.testing.assert_allclose(res.position("arm")[:, 2], h(t), atol=1e-9)
    np.testing.assert_allclose(res.acceleration("arm")[:, 2], -0.3 * 1600 * np.cos(40 * t + 0.7), rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(res.acceleration("puck")[:, 0], 2.0 * np.cos(10 * t), atol=1e-9)  # F/m


@pytest.mark.parametrize(
    "build, field",
    [
        (lambda m: m.torque("bob", clearsim.Harmonic(1.0, -2.0), name="bad"), "force 'bad'.magnitude.omega"),
        (lambda m: m.torque("bob", clearsim.Harmonic(float("nan"), 2.0), name="bad"), "force 'bad'.magnitude.amplitude"),
        (lambda m: m.driver("bob", law=clearsim.Harmonic(0.1, 0.0), name="bad"), "driver 'bad'.omega"),
    ],
)
def test_a_bad_harmonic_is_an_input_error_naming_element_field_and_value(build, field):
    m = models.driven_pendulum(1.0)
    with pytest.raises(clearsim.InputError) as err:
        build(m)  # named where it is made: the core checks each element as it is added
    assert err.value.field == field, err.value


def test_a_harmonic_needs_numbers_and_a_driver_one_law():
    with pytest.raises(clearsim.InputError, match="invalid amplitude = 'big'"):
        clearsim.Harmonic("big", 1.0)  # type: ignore[arg-type]
    with pytest.raises(clearsim.InputError, match="exactly one of omega"):
        models.driven_pendulum(1.0).driver("bob", omega=1.0, law=clearsim.Harmonic(0.1, 1.0))


def test_harmonic_loads_and_laws_in_a_scene(tmp_path):
    scene = clearsim.scene.load_scene_file(SCENE)
    drive = next(f for f in scene.mechanism.description()["forces"] if f["name"] == "drive")
    assert drive["magnitude"] == {"kind": "harmonic", "amplitude": 0.9, "omega": 2 / 3, "phase": 0.0, "offset": 0.0}
    text = SCENE.read_text().replace(
        "[simulation]",
        '[[force]]\ntype = "force"\nname = "shake"\nbody = "bob"\nvalue = [{ amplitude = 2.0, omega = 3.0, phase = 0.5 }, 1.0]\n\n'
        '[[body]]\nname = "wheel"\nmass = 1.0\ninertia = 0.1\nposition = [2.0, 0.0]\nangle = 0.3\n\n'
        '[[joint]]\ntype = "revolute"\nbodies = ["ground", "wheel"]\npoints = [[2.0, 0.0], [0.0, 0.0]]\n\n'
        '[[driver]]\nname = "rock"\nbody = "wheel"\nharmonic = { amplitude = 0.2, omega = 5.0, offset = 0.1 }\n\n[simulation]',
    )  # fmt: skip
    path = tmp_path / "s.toml"
    path.write_text(text)
    desc = clearsim.load_scene(path).description()
    shake = next(f for f in desc["forces"] if f["name"] == "shake")
    assert shake["fx"]["kind"] == "harmonic" and shake["fx"]["phase"] == 0.5 and shake["fy"] == {"kind": "constant", "value": 1.0}
    assert desc["drivers"][0]["law"] == {"kind": "harmonic", "amplitude": 0.2, "omega": 5.0, "phase": 0.0, "offset": 0.1}
    path.write_text(text.replace("omega = 5.0, offset", "omega = -5.0, offset"))
    with pytest.raises(clearsim.InputError, match=r"s\.toml:\d+: .*driver 'rock'\.omega = -5\.0"):
        clearsim.load_scene(path)


# ---------------------------------------------------------------------------- Poincaré sections
def test_poincare_sections_are_exact_times_whatever_the_output_grid():
    """Sections at t = kT from the dense output: the same bits for two output grids, the ODE's
    state there, every other one for period 2T, and none asked for is an InputError."""
    m = models.driven_pendulum(1.07)
    runs = [m.simulate(20 * PERIOD, sections=(PERIOD, 0.0), progress=False, dt_out=dt, **TIGHT) for dt in (0.37, PERIOD / 64)]
    a, b = (r.poincare() for r in runs)
    assert np.array_equal(a.t, PERIOD * np.arange(21)) and np.array_equal(a.position("bob"), b.position("bob"))
    assert np.array_equal(a.velocity("bob"), b.velocity("bob"))
    ref = solve_ivp(lambda t, y: [y[1], -y[1] / 2 - math.sin(y[0]) + 1.07 * math.cos(2 * t / 3)], (0, 20 * PERIOD), [0.2, 0.0],
                    method="DOP853", rtol=1e-11, atol=1e-13, t_eval=a.t)  # fmt: skip
    np.testing.assert_allclose(a.position("bob")[:, 2], ref.y[0], atol=1e-6)
    np.testing.assert_allclose(a.velocity("bob")[:, 2], ref.y[1], atol=1e-6)
    two = runs[0].poincare(2 * PERIOD, math.pi)  # phase π of 2T: the odd multiples of T
    assert np.allclose(two.t, PERIOD * np.arange(1, 21, 2)) and two.section_period == 2 * PERIOD
    assert np.array_equal(runs[0].poincare(after=10 * PERIOD).t, a.t[10:])
    with pytest.raises(clearsim.InputError, match="whole multiple"):
        runs[0].poincare(1.5 * PERIOD)
    fig = runs[1].phase_portrait("bob", "theta")  # the trajectory and its section points on top
    line, dots = fig.axes[0].get_lines()
    assert len(line.get_xdata()) == len(runs[1].t) and np.array_equal(dots.get_ydata(), a.velocity("bob")[:, 2])
    with pytest.raises(clearsim.InputError, match="recorded no Poincaré sections"):
        m.simulate(1.0, progress=False).poincare(PERIOD)
    with pytest.raises(clearsim.InputError, match="sections.period = 0.0"):
        m.simulate(1.0, sections=0.0, progress=False)


# ---------------------------------------------------------------------------- pendulum table
def test_pendulum_periods_and_chaos_match_an_independent_integration():
    """Baker & Gollub (q = 2, ω_D = 2/3, from θ = 0.2): period 2 at g = 1.07, period 4 at 1.47,
    chaos at 1.5 — clearsim's diagram against SciPy's sections of the plain ODE."""
    gs = [1.07, 1.47, 1.5]
    b = dynamics.bifurcation(models.driven_pendulum, gs, "g", transient_cycles=150, cycles=32, output=("bob", "velocity", "theta"), progress=False, **TIGHT)
    assert b.kind == ["period-2", "period-4", "chaotic"], b.how
    assert np.isnan(b.exponent[0]) and b.exponent[2] > 0 and b.exponent_interval[2][0] > 0
    for g, k, pts in zip(gs[:2], (2, 4), b.points):
        ref = pendulum_sections(g, 150, 33, rtol=1e-10)
        assert repeat_period(ref) == k
        np.testing.assert_allclose(np.sort(np.unique(np.round(pts, 5))), np.sort(np.unique(np.round(ref[:, 1], 5))), atol=2e-5)


def test_the_chaotic_pendulum_exponent_matches_the_variational_equation():
    """λ at g = 1.5 by two renormalised runs of the mechanism against SciPy's variational
    equation of the ODE: two finite-time samples of one number, within their intervals."""
    ly = dynamics.lyapunov(models.driven_pendulum(1.5), 450 * PERIOD, 50 * PERIOD, **TIGHT)
    ref, ref_half = pendulum_exponent(1.5, 50, 200, rtol=1e-9)
    assert ly.failure is None and len(ly.log_growth) == 400 and ly.renormalize_every == pytest.approx(PERIOD)
    assert ly.exponent > 0.05 and ref > 0.05
    assert abs(ly.exponent - ref) < 2 * math.hypot(ly.half_width, ref_half), (ly.exponent, ly.interval, ref, ref_half)
    t, running = ly.convergence
    assert len(t) == 400 and running[-1] == pytest.approx(ly.exponent)


def test_a_heated_bearings_exponent_is_the_mechanical_one_at_its_oil_temperature():
    """Oil temperatures in the state (a heated joint): the shadow measures (q, q̇) and takes the
    run's temperatures at each renormalisation. A gravity-loaded rotor settled in its film, its
    exponent over two turns (renormalised every 1/8 turn, the contraction then stays well above
    the integration error) against the same rotor at a constant viscosity: with a heat capacity
    so large that the oil warms by µK, at μ(T_amb), within 1 %; heated by 19 K (C/hA = 20 ms,
    settled after 0.5 s) at μ of the temperature reached, within 2 % (the temperature's own
    response to the shadow's motion is the difference), where μ(T_amb) gives 35 % less."""
    turn = 2 * math.pi / OMEGA
    tight = dict(renormalize_every=turn / 8, rtol=1e-8, atol=1e-11)

    def exponent(model: clearsim.Lubricated) -> "dynamics.LyapunovExponent":
        ly = dynamics.lyapunov(rotor(model, gravity=9.81), 0.5 + 2 * turn, 0.5, **tight)
        assert ly.failure is None and len(ly.log_growth) == 16
        return ly

    cold = exponent(clearsim.Lubricated(viscosity=OIL.viscosity(T_AMB), length=L, film="short")).exponent
    for capacity, rel in ((1e6, 0.01), (2e-3, 0.02)):
        heated = exponent(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=clearsim.Thermal(T_AMB, capacity, 0.1)))
        temp = heated.result.temperature("pin")[-1]
        plain = cold if capacity > 1 else exponent(clearsim.Lubricated(viscosity=OIL.viscosity(temp), length=L, film="short")).exponent
        assert heated.exponent < 0 and heated.exponent == pytest.approx(plain, rel=rel), (capacity, temp, heated.exponent, plain)
    assert temp - T_AMB > 15 and abs(plain - cold) > 0.3 * abs(cold), (temp, plain, cold)


# ---------------------------------------------------------------------------- an impact oscillator
def _restitution_of_the_law(restitution: float) -> float:
    """The restitution the ball's contact law gives: dropped 1 mm on a still table."""
    r = models.bouncing_ball(1e-9, restitution=restitution, height=1e-3).simulate(0.03, rtol=1e-10, atol=1e-13, dt_out=1e-6, progress=False)
    return float(r.velocity("ball")[:, 1].max() / math.sqrt(2 * 9.81 * 1e-3))


def test_the_bouncing_ball_doubles_its_period_where_holmes_says_and_contracts_by_e():
    """Holmes (1982): one bounce a period is stable up to Γ₂(e) = √((π(1−e)/(1+e))² +
    (2(1+e²)/(1+e)²)²), then two; while its multipliers are a complex pair of modulus e, the
    largest Lyapunov exponent is ln(e)/T — through an impact each period."""
    e = _restitution_of_the_law(0.5)
    assert 0.4 < e < 0.55
    g2 = ball_period_doubling(e)
    gammas = [0.92 * g2, 1.05 * g2]
    b = dynamics.bifurcation(lambda gamma: models.bouncing_ball(gamma), gammas, "Γ", transient_cycles=100, cycles=16,
                             output=("ball", "velocity", "y"), lyapunov=False, rtol=1e-8, atol=1e-11, progress=False)  # fmt: skip
    assert b.kind == ["period-1", "period-2"], b.how
    for gamma, k in zip(gammas, (1, 2)):  # the exact impact map agrees
        speeds = ball_impacts(gamma, e, 50.0, 400)[-8:, 1]
        assert len(np.unique(np.round(speeds, 6))) == k
    period = 0.02
    ly = dynamics.lyapunov(models.bouncing_ball(1.3), 200 * period, 40 * period, rtol=1e-9, atol=1e-12)
    assert ly.exponent * period == pytest.approx(math.log(e), rel=0.005)
    assert ly.interval[0] < math.log(e) / period < ly.interval[1]


# ---------------------------------------------------------------------------- classification
def test_a_torus_is_quasi_periodic_and_a_strange_attractor_chaotic():
    """Sections from maps with known answers: a rotation by the golden angle on a circle
    (quasi-periodic), the Hénon map (chaotic, λ = 0.42 a step), a 3-cycle."""
    n = 120
    golden = 2 * math.pi * (math.sqrt(5) - 1) / 2
    circle = np.stack([np.cos(golden * np.arange(n)), np.sin(golden * np.arange(n))], axis=1)
    x, y, henon = 0.1, 0.1, []
    for k in range(n + 200):
        x, y = 1 - 1.4 * x * x + y, 0.3 * x
        if k >= 200:
            henon.append((x, y))
    cycle = np.tile([[0.0, 1.0], [1.0, 0.0], [0.5, 0.5]], (n // 3, 1))
    as_cycles = lambda pts: np.asarray(pts)[:, None, :]  # noqa: E731  (one sample a period)
    assert classify(as_cycles(circle)).kind == "quasi-periodic"
    assert classify(as_cycles(henon)).kind == "chaotic"
    assert classify(as_cycles(cycle)).kind == "period-3"
    assert classify(as_cycles(circle), exponent=0.01, interval=(-0.02, 0.04), period=1.0).kind == "quasi-periodic"
    assert classify(as_cycles(henon), exponent=0.42, interval=(0.38, 0.46), period=1.0).kind == "chaotic"


def test_loose_tolerances_are_refused_for_an_exponent_before_anything_runs():
    """The two runs must stay further apart than the integrator's error in a position."""
    with pytest.raises(clearsim.InputError, match=r"invalid rtol = 1e-06: .* use rtol ≤ "):
        dynamics.lyapunov(models.slider_crank("dry"), 0.1, 0.05)
    with pytest.raises(clearsim.InputError, match="invalid transient"):
        dynamics.lyapunov(models.driven_pendulum(1.0), 10.0, 20.0)


def test_failed_runs_are_counted_with_their_reasons():
    b = dynamics.bifurcation(models.driven_pendulum, [0.9, 1.07], transient_cycles=10, cycles=8, output=("bob", "velocity", "theta"),
                             max_steps=200, progress=False)  # fmt: skip
    assert b.kind == ["failed", "failed"] and len(b.failures) == 2
    assert all("maximum number of steps" in why for _, why in b.failures), b.failures
    with pytest.raises(clearsim.InputError, match="no body 'rod'"):
        dynamics.bifurcation(models.driven_pendulum, [1.0], output=("rod", "velocity", "x"), progress=False)


# ---------------------------------------------------------------------------- spectra
def test_the_slider_acceleration_spectrum_is_that_of_the_exact_kinematics():
    """Ideal slider-crank at constant ω: ẍ(θ) of x = r cos θ + √(l² − r² sin² θ) has harmonic 1
    exactly r ω² and even harmonics r ω²(r/l)(1 + …), 4 …: their amplitudes from a fine DFT
    of the closed form."""
    rpm, r, l = 5000.0, 0.05, 0.12
    w = rpm * 2 * math.pi / 60
    period = 2 * math.pi / w
    res = models.slider_crank("ideal", rpm=rpm).simulate(2 * period, dt_out=period / 128, rtol=1e-10, atol=1e-13, progress=False)
    sp = res.spectrum("slider", "acceleration", "x")
    assert sp.period == pytest.approx(period) and sp.cycles == 2 and sp.unit == "m/s²"
    th = 2 * math.pi * np.arange(4096) / 4096
    s, c = np.sin(th), np.cos(th)
    d = np.sqrt(l * l - r * r * s * s)
    acc = w * w * (-r * c - r * r * (c * c - s * s) / d - r**4 * s * s * c * c / d**3)
    exact = 2 * np.abs(np.fft.rfft(acc)) / len(acc)
    assert sp.harmonic(1) == pytest.approx(r * w * w, rel=1e-7)
    for k in range(2, 9):
        assert sp.harmonic(k) == pytest.approx(exact[k], rel=1e-5, abs=1e-6 * r * w * w), k
    assert sp.harmonic(2) == pytest.approx(r * w * w * (r / l) * (1 + (r / l) ** 2 / 4), rel=0.01)
    pin = res.spectrum("crank", "acceleration", "y", point=(r / 2, 0.0))  # the crank pin: r ω² sin θ, one line
    assert pin.harmonic(1) == pytest.approx(r * w * w, rel=1e-7) and max(pin.harmonic(k) for k in (0, 2, 3, 4)) < 1e-6 * r * w * w
    with pytest.raises(clearsim.InputError, match="whole number of samples a period"):
        models.slider_crank("ideal").simulate(2 * period, dt_out=period / 100.5, progress=False).spectrum("slider", "acceleration", "x")


# ---------------------------------------------------------------------------- clearsim sweep
def test_clearsim_sweep_writes_its_tables_figures_and_report(tmp_path):
    out = tmp_path / "sweep"
    assert main(["sweep", str(SCENE), "-o", str(out), "--cycles", "8", "-q"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"bifurcation_points.csv", "bifurcation_kinds.csv", "bifurcation.png", "poincare.png", "report.md"} <= names
    kinds = (out / "bifurcation_kinds.csv").read_text().splitlines()
    assert kinds[0].startswith("drive.amplitude,kind,period,exponent [1/s]")
    assert [row.split(",")[1] for row in kinds[1:]] == ["period-1", "period-2"]
    assert "0.9: period-1" in (out / "report.md").read_text()
    assert main(["sweep", str(Path(__file__).resolve().parents[2] / "scenes" / "nine_bar.toml"), "-o", str(tmp_path / "x"), "-q"]) == 2


# ---------------------------------------------------------------------------- points as outputs
def test_a_bifurcation_of_a_point_is_its_rigid_body_motion():
    """The bob's point (0, −0.5), twice as far from the fixed pivot as its centroid, moves at twice
    the centroid's velocity (v = θ̇ × r), and the pivot's own point (0, 0.5) stays at the origin."""
    m = models.driven_pendulum(0.9)
    kw = dict(transient_cycles=2, cycles=4, lyapunov=False, progress=False, **TIGHT)
    body = dynamics.bifurcation(m, [0.9, 1.07], "drive.amplitude", output=("bob", "velocity", "x"), **kw)
    tip = dynamics.bifurcation(m, [0.9, 1.07], "drive.amplitude", output=("bob", "velocity", "x"), point=(0.0, -0.5), **kw)
    pivot = dynamics.bifurcation(m, [0.9, 1.07], "drive.amplitude", output=("bob", "displacement", "magnitude"), point=(0.0, 0.5), **kw)
    assert tip.output == "bob(0,-0.5).x.velocity" and tip.unit == "m/s" and tip.point == (0.0, -0.5)
    for i in range(2):
        assert len(tip.points[i]) == 5 and np.max(np.abs(body.points[i])) > 0.1
        np.testing.assert_allclose(tip.points[i], 2 * body.points[i], rtol=1e-9, atol=1e-12)
        assert np.max(np.abs(pivot.points[i])) < 1e-7
    with pytest.raises(clearsim.InputError, match=r"output.component.*magnitude"):
        dynamics.bifurcation(m, [0.9], "drive.amplitude", output=("bob", "velocity", "theta"), point=(0.0, 0.1), **kw)
    with pytest.raises(clearsim.InputError, match="a point lies on a body"):
        dynamics.bifurcation(m, [0.9], "drive.amplitude", output=("pivot", "force"), point=(0.0, 0.1), **kw)


def test_a_scene_sweep_takes_a_point_output(tmp_path):
    """[sweep] output = { body, point, quantity, component }: clearsim sweep writes the point's
    sections, twice the centroid's velocity (as the bifurcation above); a point off a body is an
    error at its line."""
    text = SCENE.read_text().replace(
        'output = { body = "bob", quantity = "velocity", component = "theta" }', 'output = { body = "bob", point = [0.0, -0.5], quantity = "velocity", component = "x" }'
    )
    path = tmp_path / "pendulum.toml"
    path.write_text(text)
    scene = clearsim.scene.load_scene_file(path)
    assert scene.sweep is not None and scene.sweep.point == (0.0, -0.5)
    out = tmp_path / "sweep"
    assert main(["sweep", str(path), "-o", str(out), "--cycles", "4", "--transient-cycles", "2", "-q"]) == 0
    rows = np.loadtxt(out / "bifurcation_points.csv", delimiter=",", skiprows=1)
    assert "bob(0,-0.5).x.velocity [m/s]" in (out / "bifurcation_points.csv").read_text().splitlines()[0]
    kw = dict(transient_cycles=2, cycles=4, lyapunov=False, progress=False, **TIGHT)
    body = dynamics.bifurcation(models.driven_pendulum(0.9), [0.9, 1.07], "drive.amplitude", output=("bob", "velocity", "x"), **kw)
    np.testing.assert_allclose(np.sort(rows[:, -1]), np.sort(2 * np.concatenate(body.points)), rtol=1e-7, atol=1e-10)
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('body = "bob", point', 'body = "bobb", point'))
    with pytest.raises(clearsim.InputError, match=r"bad.toml:\d+: invalid sweep.output.body = 'bobb'"):
        clearsim.scene.load_scene_file(bad)
