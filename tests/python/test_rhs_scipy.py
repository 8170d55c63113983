"""``Mechanism.rhs`` lets any SciPy integrator drive clearsim's model: solve_ivp(m.rhs) on the
ideal slider-crank and nine-bar matches clearsim's own RK45 to the tolerance."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from clearsim.errors import InputError
from clearsim.models import nine_bar, slider_crank

CASES = {
    # name: (model, slider body, one crank cycle [s], stroke [m])
    "slider_crank": (lambda: slider_crank("ideal"), "slider", 60.0 / 5000.0, 0.100),
    "nine_bar": (lambda: nine_bar("ideal"), "slider9", 2 * math.pi / (5 * math.pi), 0.141),
}


def test_state_layout():
    m = nine_bar("ideal")
    y0 = m.initial_state()
    n = 3 * len(m.body_names)
    assert y0.shape == (m.state_dim,) == (2 * n,)
    dy = m.rhs(0.0, y0)
    assert dy.shape == y0.shape
    np.testing.assert_array_equal(dy[:n], y0[n:])  # q̇ first, then q̈
    # Cranks 1 and 4 turn at the drive speed; the slider starts where the assembly puts it.
    k = m.body_names.index("crank1")
    assert y0[n + 3 * k + 2] == pytest.approx(-5 * math.pi, rel=1e-12)
    assert y0[3 * m.body_names.index("slider9") + 1] == pytest.approx(-0.4570, abs=2e-3)


def test_state_index_names_the_entries_a_run_records():
    m = nine_bar("ideal")
    y0 = m.initial_state()
    res = m.simulate(0.01, t_out=[0.0, 0.01], progress=False)
    for body in ("crank1", "slider9"):
        for c, coord in enumerate(("x", "y", "theta")):
            assert y0[m.state_index(body, coord)] == pytest.approx(res.position(body)[0, c], abs=1e-12)
            assert y0[m.state_index(body, coord, velocity=True)] == pytest.approx(res.velocity(body)[0, c], abs=1e-9)
    dy = m.rhs(0.0, y0)
    assert dy[m.state_index("slider9", "y", velocity=True)] == pytest.approx(res.acceleration("slider9")[0, 1], rel=1e-9)
    with pytest.raises(InputError, match="component = 'z'"):
        m.state_index("slider9", "z")
    with pytest.raises(InputError, match="no such body"):
        m.state_index("ground", "x")


@pytest.mark.parametrize("name", sorted(CASES))
def test_solve_ivp_on_rhs_matches_clearsim_rk45(name):
    build, slider, cycle, stroke = CASES[name]
    m = build()
    rtol, atol = 1e-8, 1e-11
    t = np.linspace(0.0, cycle, 201)
    own = m.simulate(cycle, integrator="rk45", rtol=rtol, atol=atol, t_out=t)
    sol = solve_ivp(m.rhs, (0.0, cycle), m.initial_state(), method="RK45", rtol=rtol, atol=atol, t_eval=t)
    assert sol.success, sol.message
    k = m.body_names.index(slider)
    axis = 0 if name == "slider_crank" else 1  # slider moves along x (slider-crank) or y (nine-bar)
    x_own = own.position(slider)[:, axis]
    x_scipy = sol.y[3 * k + axis]
    # Both are within a few tolerances of the true motion: they agree to ~1e-6 of the stroke.
    assert np.max(np.abs(x_own - x_scipy)) < 1e-6 * stroke
    assert np.ptp(x_own) == pytest.approx(stroke, rel=0.02)
    # Velocities agree as well (the whole state, not just one channel, is the same).
    v_own = own.velocity(slider)[:, axis]
    v_scipy = sol.y[3 * len(m.body_names) + 3 * k + axis]
    assert np.max(np.abs(v_own - v_scipy)) < 1e-5 * np.max(np.abs(v_own))


def test_rhs_with_clearance_joints_is_finite_and_matches_simulate_start():
    """Dry and lubricated models expose the same rhs. A short SciPy run on the lubricated model
    agrees with clearsim; the dry one differs once impacts start, because ``m.rhs`` has no impact
    memory (δ̇⁽⁻⁾ is the current approach speed, not the one recorded at the impact's onset)."""
    for joints in ("dry", "lubricated"):
        m = slider_crank(joints)
        y0 = m.initial_state()
        assert np.all(np.isfinite(m.rhs(0.0, y0)))
    m = slider_crank("lubricated")
    t_end = 1e-3
    own = m.simulate(t_end, rtol=1e-9, atol=1e-12, t_out=[0.0, t_end])
    sol = solve_ivp(m.rhs, (0.0, t_end), m.initial_state(), method="DOP853", rtol=1e-9, atol=1e-12)
    assert sol.success
    k = m.body_names.index("slider")
    assert sol.y[3 * k, -1] == pytest.approx(own.position("slider")[-1, 0], abs=1e-8)


def test_jacobian_is_the_stiff_part_of_the_rhs_derivative():
    """``m.jacobian`` against central differences of ``m.rhs`` (an independent path through
    Python) at a state in the film near ε → 1: the identity block exactly, the acceleration block
    to a few per cent (only the non-stiff pose terms are left out); and SciPy's Radau with
    ``jac=m.jacobian`` reproduces clearsim's RADAU5."""
    from clearsim.joints import Lubricated

    m = nine_bar("lubricated", clearance=0.5e-3, lubricated=Lubricated(viscosity=0.04, length=0.05))
    t = 0.02
    r = m.simulate(t, integrator="dop853", rtol=1e-10, atol=1e-13, t_out=[0.0, t], progress=False)
    y = np.concatenate([np.concatenate([r.position(b)[-1] for b in m.body_names]), np.concatenate([r.velocity(b)[-1] for b in m.body_names])])
    jac = m.jacobian(t, y)
    n = m.state_dim // 2
    fd = np.empty_like(jac)
    for j in range(2 * n):
        d = 1.5e-8 * max(abs(y[j]), 1.0)
        yp, ym = y.copy(), y.copy()
        yp[j] += d
        ym[j] -= d
        fd[:, j] = (m.rhs(t, yp) - m.rhs(t, ym)) / (2 * d)
    np.testing.assert_array_equal(jac[:n, :n], 0.0)
    np.testing.assert_array_equal(jac[:n, n:], np.eye(n))
    rel = np.linalg.norm(jac[n:] - fd[n:]) / np.linalg.norm(fd[n:])
    assert rel < 0.05, rel
    assert np.abs(fd[n:]).max() > 1e4  # the film is stiff here: the check has something to see
    with pytest.raises(InputError, match="y"):
        m.jacobian(t, y[:5])

    t_end = 0.05
    ts = np.linspace(0.0, t_end, 11)
    ours = m.simulate(t_end, integrator="radau", rtol=1e-7, atol=1e-10, t_out=ts, progress=False)
    sol = solve_ivp(m.rhs, (0.0, t_end), m.initial_state(), method="Radau", jac=m.jacobian, rtol=1e-7, atol=1e-10, t_eval=ts)
    assert sol.success
    k = m.body_names.index("slider9")
    np.testing.assert_allclose(sol.y[3 * k + 1], ours.position("slider9")[:, 1], atol=1e-7)
