"""Result.extremes: peaks tracked at every integration step, so they do not depend on the output
grid (issue 28 item 10). Checked against the ideal slider-crank's closed form, against every
stored sample, and between runs that differ only in dt_out."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim
from clearsim import models
from walks import TOGGLE

RPM = 5000.0
OMEGA = RPM * 2 * math.pi / 60  # [rad/s]
R, L = 0.05, 0.12  # [m] crank and rod of models.slider_crank
PERIOD = 2 * math.pi / OMEGA


def _run(joints: str, dt_out: float, t_end: float = 2 * PERIOD, **kw):
    m = models.slider_crank(joints)
    return m.simulate(t_end, dt_out=dt_out, progress=False, extremes=["slider"] + m.clearance_joint_names, **kw)


def test_ideal_slider_crank_peak_acceleration_is_the_closed_form():
    """At top dead centre (θ = 0, every period) the slider's acceleration is −rω²(1 + r/l) and its
    position r + l; the run starts there, so the extremes must find these values on any grid."""
    res = _run("ideal", dt_out=2 * PERIOD / 13, rtol=1e-10, atol=1e-13)  # 6.5 samples a turn: θ = 0 only at t = 0, 2T
    acc = res.extremes("slider", "acceleration", component="x")
    assert acc.min == pytest.approx(-R * OMEGA**2 * (1 + R / L), rel=1e-7)
    phase = (acc.t_min / PERIOD) % 1.0
    assert min(phase, 1 - phase) < 1e-6
    pos = res.extremes("slider", "displacement", component="x")
    assert pos.max == pytest.approx(R + L, rel=1e-9) and pos.min == pytest.approx(L - R, rel=1e-9)
    # Bottom dead centre at θ = π: t = T/2 and 3T/2, between the samples.
    phase = (pos.t_min / PERIOD) % 1.0
    assert abs(phase - 0.5) < 1e-4
    # The stored samples miss both: the grid's largest |acceleration| is well below the peak.
    stored = res.acceleration("slider")[1:-1, 0]  # t = 0 and 2T are at θ = 0
    assert np.min(stored) > acc.min + 0.05 * abs(acc.min)


@pytest.mark.parametrize("joints, integrator", [("ideal", "rk45"), ("dry", "rk45"), ("dry", "dop853"), ("lubricated", "radau")])
def test_extremes_do_not_depend_on_dt_out_and_bound_every_sample(joints, integrator):
    t_end = 0.012 if joints != "ideal" else 2 * PERIOD
    runs = [_run(joints, dt_out=dt, t_end=t_end, integrator=integrator) for dt in (1e-3, 1e-5)]
    m = models.slider_crank(joints)
    names = [("slider", q, c) for q in ("displacement", "velocity", "acceleration") for c in ("x", "y")]
    names += [(j, q, None) for j in m.clearance_joint_names for q in ("eccentricity", "force", "contact_force", "film_force")]
    assert runs[0].stats["steps"] == runs[1].stats["steps"]
    for name, q, c in names:
        coarse, fine = (r.extremes(name, q, c) for r in runs)
        scale = max(abs(fine.max), abs(fine.min), 1e-300)
        assert abs(coarse.max - fine.max) <= 1e-12 * scale and abs(coarse.min - fine.min) <= 1e-12 * scale, (name, q, c, coarse, fine)
        assert coarse.t_max == pytest.approx(fine.t_max, abs=1e-12) and coarse.t_min == pytest.approx(fine.t_min, abs=1e-12)
    # ≥ every stored sample of the fine grid (to round-off), for the quantities the run stores.
    res = runs[1]
    stored = {
        "displacement": res.position("slider"),
        "velocity": res.velocity("slider"),
        "acceleration": res.acceleration("slider"),
    }
    for q, arr in stored.items():
        for k, c in enumerate(("x", "y")):
            e = res.extremes("slider", q, c)
            scale = max(abs(e.max), abs(e.min))
            assert np.max(arr[:, k]) <= e.max + 1e-12 * scale, (q, c)
            assert np.min(arr[:, k]) >= e.min - 1e-12 * scale, (q, c)
    for j in m.clearance_joint_names:
        ecc = np.hypot(*res.eccentricity(j).T) / 0.5e-3
        e = res.extremes(j, "eccentricity")
        assert np.max(ecc) <= e.max + 1e-9 and np.min(ecc) >= e.min - 1e-9
        force = np.hypot(*res.joint_force(j).T)
        f = res.extremes(j, "force")
        assert np.max(force) <= f.max * (1 + 1e-12) + 1e-9


def test_extremes_must_be_asked_for_and_named():
    m = models.slider_crank("dry")
    res = m.simulate(0.002, progress=False)
    with pytest.raises(clearsim.InputError, match="did not track its extremes"):
        res.extremes("slider", "acceleration", "x")
    with pytest.raises(clearsim.InputError, match="no such body, joint or driver"):
        m.simulate(0.002, progress=False, extremes=["slidr"])
    res = m.simulate(0.002, progress=False, extremes=True)
    with pytest.raises(clearsim.InputError, match="component"):
        res.extremes("slider", "acceleration")
    with pytest.raises(clearsim.InputError, match="quantity"):
        res.extremes("rod-slider", "acceleration")
    assert "m/s²" in str(res.extremes("slider", "acceleration", "x"))


def test_simulate_with_ideal_tracks_the_bodies_of_both():
    m = models.slider_crank("dry")
    res, ideal = m.simulate_with_ideal(0.004, extremes=["slider", "rod-slider"])
    assert res.extremes("rod-slider", "eccentricity").max > 0
    assert ideal.extremes("slider", "acceleration", "x").min < 0


def test_extremes_of_the_bearing_readings_are_tracked_when_asked():
    """``simulate(extremes=[joint])`` tracks a clearance joint's film thickness, friction torque
    and power loss too (lubricated or dry), and each extreme bounds the stored samples and
    agrees with them on a fine output grid; the dry line-contact pin's peak torque is μ R_j F_N
    at its peak contact force. Before: ``extremes("A", "friction_torque")`` said the run did
    not track its extremes, and so did every reading of the dry pin, though both were asked for."""
    m = clearsim.load_scene(TOGGLE)
    res = m.simulate(0.1, dt_out=2e-5, extremes=["A", "P"], progress=False)
    for joint in ("A", "P"):
        for quantity, values in (("film_thickness", res.film_thickness(joint)), ("friction_torque", res.friction_torque(joint)),
                                 ("power_loss", res.power_loss(joint))):  # fmt: skip
            x = res.extremes(joint, quantity)
            span = values.max() - values.min()
            assert x.max >= values.max() - 1e-12 * abs(values.max()) and x.min <= values.min() + 1e-12 * abs(values.min())
            assert x.max - values.max() < 0.1 * span and values.min() - x.min < 0.1 * span, (joint, quantity)
    torque, contact = res.extremes("P", "friction_torque"), res.extremes("P", "contact_force")
    assert torque.max == pytest.approx(0.1 * 8e-3 * contact.max, rel=1e-6) and torque.t_max == pytest.approx(contact.t_max)
