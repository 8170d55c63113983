"""The oil temperature of a lubricated joint (docs/physics.md §4, *Heat*): Vogel's law against its
formula, the heat balance against its closed form at a constant viscosity, a steadily running
journal settling at the fixed point T = T_amb + P_loss(μ(T))/hA (solved here independently with
Petroff's loss of a centred journal), its warm-up against the balance's own ODE integrated here
by SciPy, and the temperature as a state of the run (``m.rhs``, ``m.jacobian``, ``state_dim``)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from heat_reference import C, L, OIL, OMEGA, R, T_AMB, fixed_point, petroff_loss, rotor, rotor_scene

import clearsim

def in_a_joint(model: object) -> None:
    """Compile ``model`` in a pinned body: its values are checked by the core (issue 29, validation once)."""
    m = clearsim.Mechanism()
    m.add_body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0, 0), "b", (0, 0), journal_radius=0.01, clearance=1e-4, model=model)  # type: ignore[arg-type]
    m.compile()

def test_vogels_law_against_its_formula() -> None:
    for t in (280.0, 313.15, 373.15, 450.0):
        assert OIL.viscosity(t) == pytest.approx(6.4e-5 * math.exp(900.0 / (t - 164.0)), rel=1e-15)
    assert OIL.viscosity(313.15) == pytest.approx(0.02672, abs=1e-5)
    with pytest.raises(clearsim.InputError, match="temperature"):
        OIL.viscosity(160.0)
    with pytest.raises(clearsim.InputError, match="vogel.a"):
        in_a_joint(clearsim.Lubricated(viscosity=clearsim.Vogel(-1.0, 900.0, 164.0), thermal=clearsim.Thermal(300.0, 1.0, 1.0)))


def test_a_steady_journal_settles_at_the_heat_balances_fixed_point() -> None:
    """Time constant C/hA = 0.1 s, run 2 s: the oil settles where Petroff's loss at μ(T) equals
    what the ambient takes away."""
    thermal = clearsim.Thermal(ambient=T_AMB, heat_capacity=0.01, heat_transfer=0.1)
    res = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=thermal)).simulate(2.0, dt_out=0.05, progress=False)
    assert res.completed
    lo = fixed_point(0.1)
    temp = res.temperature("pin")
    assert temp[0] == T_AMB
    rise = temp[-1] - T_AMB
    # The issue asks 0.5 %: the balance integrated with the mechanism settles on it.
    assert rise == pytest.approx(lo - T_AMB, rel=1e-5), (temp[-1], lo)
    assert lo - T_AMB > 10.0  # the coupling matters: 40 °C oil alone would rise by 34 K
    # The film runs at μ(T): its loss is Petroff's at the recorded temperature.
    assert res.power_loss("pin")[-1] == pytest.approx(petroff_loss(OIL.viscosity(temp[-1])), rel=1e-3)


def test_a_constant_viscosity_keeps_the_film_and_heats_as_the_closed_form() -> None:
    """With a constant viscosity the film's numbers are those without heat (the temperature, a
    state of the run that acts on nothing, moves only the integrator's steps: within the
    tolerance), and the temperature is T_amb + P/hA (1 − e^{−t hA/C}) at Petroff's constant loss P."""
    mu = 0.03
    plain = rotor(clearsim.Lubricated(viscosity=mu, length=L, film="short")).simulate(0.5, dt_out=0.05, progress=False)
    thermal = clearsim.Thermal(ambient=T_AMB, heat_capacity=0.05, heat_transfer=0.2)
    heated = rotor(clearsim.Lubricated(viscosity=mu, length=L, film="short", thermal=thermal)).simulate(0.5, dt_out=0.05, progress=False)
    assert np.allclose(plain._raw["q"], heated._raw["q"], rtol=1e-5, atol=1e-8)  # the run's rtol = 1e-6
    assert np.allclose(plain.power_loss("pin"), heated.power_loss("pin"), rtol=1e-6)
    p = petroff_loss(mu)
    want = T_AMB + p / 0.2 * (1 - np.exp(-heated.t * 0.2 / 0.05))
    assert np.allclose(heated.temperature("pin"), want, rtol=0, atol=1e-3 * p / 0.2)
    with pytest.raises(clearsim.InputError, match="no oil temperature"):
        plain.temperature("pin")


def warm_up_reference(cap: float, h_a: float, t: np.ndarray) -> np.ndarray:
    """T(t) of C dT/dt = P(μ(T)) − hA (T − T_amb) with Petroff's loss of the centred journal,
    from T_amb, by SciPy's Radau at rtol 1e-11 (a second integration of the balance alone)."""
    from scipy.integrate import solve_ivp

    sol = solve_ivp(lambda _t, y: [(petroff_loss(OIL.viscosity(y[0])) - h_a * (y[0] - T_AMB)) / cap], (0.0, float(t[-1])), [T_AMB], method="Radau", t_eval=t, rtol=1e-11, atol=1e-9)
    return np.asarray(sol.y[0])


@pytest.mark.parametrize("integrator, h_max", [("radau", None), ("radau", 0.5), ("rodas4", None), ("rk45", None)])
def test_a_warm_up_follows_the_heat_balance_and_prints_the_loss_at_the_printed_temperature(integrator: str, h_max: "float | None") -> None:
    """C/hA = 20 s, run 200 s (10 time constants) with the integrator's own steps and with steps
    of at most 0.5 s, by the implicit methods (the temperature in their Newton matrices) and an
    explicit one: the recorded temperature follows the balance's ODE (to 1e-4 of the rise),
    ends within 0.5 % of the rise at the fixed point, and the power loss at every output is
    Petroff's at the temperature printed beside it. On main (the temperature advanced once per
    step outside the integrator, each step integrated at its start's viscosity) the run took 17
    steps and its temperature missed the ODE's by up to 0.70 K (3.9 % of the rise) mid-way; with
    h_max = 0.5 s it printed 2.953 W where the printed temperature gives 2.906 W."""
    cap, h_a = 2.0, 0.1
    thermal = clearsim.Thermal(ambient=T_AMB, heat_capacity=cap, heat_transfer=h_a)
    m = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=thermal))
    kw = {} if h_max is None else {"h_max": h_max}
    res = m.simulate(200.0, dt_out=2.5, progress=False, integrator=integrator, **kw)
    assert res.completed
    temp = res.temperature("pin")
    rise = fixed_point(h_a) - T_AMB
    assert np.abs(temp - warm_up_reference(cap, h_a, res.t)).max() < 1e-4 * rise
    assert abs(temp[-1] - fixed_point(h_a)) < 5e-3 * rise
    want = np.array([petroff_loss(OIL.viscosity(x)) for x in temp])
    assert np.allclose(res.power_loss("pin"), want, rtol=1e-4)


def test_the_temperature_is_a_state_of_the_run() -> None:
    """y = (q, q̇, T): ``state_dim`` counts it, ``initial_state`` starts it at ``initial``,
    ``m.rhs`` gives dT/dt = (P(μ(T)) − hA (T − T_amb))/C with Petroff's loss, and
    ``m.jacobian`` its derivative in T against a difference of that closed form (and the film's
    change with T in the journal's rows: the film force ∝ μ). The (q, q̇) part keeps 6 per body."""
    cap, h_a = 0.5, 0.1
    thermal = clearsim.Thermal(ambient=T_AMB, heat_capacity=cap, heat_transfer=h_a, initial=320.0)
    m = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=thermal))
    assert m.state_dim == 7
    assert m.state_index("rotor", "theta", velocity=True) == 5
    y = m.initial_state()
    assert y.shape == (7,) and y[6] == 320.0
    y[0] += 0.3 * C  # off the centre, at rest: a film force that follows μ(T)
    dy = m.rhs(0.0, y)

    def balance(temp: float, eps: float) -> float:
        """dT/dt with Ocvirk's short-bearing loss at rest, ω T_j (docs/physics.md §4, *Film friction*)."""
        mu = OIL.viscosity(temp)
        torque = 2 * math.pi * mu * R**3 * L * OMEGA / (C * math.sqrt(1 - eps**2)) + math.pi * mu * R * L**3 * OMEGA * eps**2 / (8 * C * (1 - eps**2) ** 1.5)
        return (OMEGA * torque - h_a * (temp - T_AMB)) / cap

    assert dy[6] == pytest.approx(balance(320.0, 0.3), rel=1e-6)
    jac = m.jacobian(0.0, y)
    assert jac.shape == (7, 7)
    d_t = (balance(320.0 + 1e-3, 0.3) - balance(320.0 - 1e-3, 0.3)) / 2e-3
    assert jac[6, 6] == pytest.approx(d_t, rel=1e-4)
    # The film force is ∝ μ: ∂ẍ/∂T = ẍ_film μ'(T)/μ(T), ẍ_film = the acceleration at rest.
    mu, dmu = OIL.viscosity(320.0), (OIL.viscosity(320.0 + 1e-3) - OIL.viscosity(320.0 - 1e-3)) / 2e-3
    assert jac[3, 6] == pytest.approx(dy[3] * dmu / mu, rel=1e-3)
    y_hot = y.copy()
    y_hot[6] = 330.0
    assert m.rhs(0.0, y_hot)[3] == pytest.approx(dy[3] * OIL.viscosity(330.0) / mu, rel=1e-9)


def test_the_temperature_does_not_depend_on_the_output_grid() -> None:
    thermal = clearsim.Thermal(ambient=T_AMB, heat_capacity=0.01, heat_transfer=0.1, initial=320.0)
    m = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=thermal))
    fine, coarse = (m.simulate(0.4, dt_out=dt, progress=False) for dt in (0.01, 0.1))
    assert fine.temperature("pin")[0] == 320.0
    assert np.array_equal(fine.temperature("pin")[::10], coarse.temperature("pin"))


def test_bad_heat_input_names_its_field() -> None:
    with pytest.raises(clearsim.InputError, match="thermal"):
        in_a_joint(clearsim.Lubricated(viscosity=OIL, length=L))  # a Vogel law needs the temperature
    with pytest.raises(clearsim.InputError, match="heat_capacity"):
        in_a_joint(clearsim.Lubricated(thermal=clearsim.Thermal(T_AMB, -1.0, 0.1)))
    cold = clearsim.Thermal(ambient=150.0, heat_capacity=0.01, heat_transfer=0.1)
    with pytest.raises(clearsim.InputError, match="ambient"):
        rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=cold)).simulate(0.01, progress=False)
    frozen = clearsim.Thermal(ambient=T_AMB, heat_capacity=0.01, heat_transfer=0.1, initial=164.0)
    with pytest.raises(clearsim.InputError, match=r"^invalid thermal\.initial = 164\.0"):  # where the model is made
        rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=frozen)).simulate(0.01, progress=False)
    with pytest.raises(clearsim.InputError, match="vogel"):
        in_a_joint(clearsim.Lubricated(viscosity=clearsim.Vogel(1e-4, -5.0, 164.0), length=L, thermal=frozen))


def test_the_scene_keys(tmp_path: "object") -> None:
    from pathlib import Path

    scene = Path(str(tmp_path)) / "heat.toml"
    scene.write_text(rotor_scene("{vogel = [6.4e-5, 900.0, 164.0]}", 0.01, 0.1, 0.01))
    m = clearsim.load_scene(scene)
    lub = m.description()["clearance_joints"][0]["model"]
    assert lub["viscosity"] == {"vogel": [6.4e-5, 900.0, 164.0]}
    assert lub["thermal"]["heat_capacity"] == 0.01
