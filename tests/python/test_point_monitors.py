"""Points on bodies tracked at every step (issue 36 item 2, the part in the core's monitors,
rust/monitor/target.rs): ``simulate(extremes=[(body, (x, y))])`` with
``res.extremes(body, quantity, component, point=(x, y))``, and ``rel.Output(body=, point=,
component=)`` through a Study. Checked against closed forms (a crank's tip at constant speed;
the slider-crank's coupler point) and against the point computed here from stored states on a
dense grid (a second method)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError

OMEGA, LENGTH = 30.0, 0.2


def _crank() -> clearsim.Mechanism:
    m = clearsim.Mechanism()
    m.add_body("crank", mass=0.5, inertia=2e-3, position=(LENGTH / 2, 0.0))
    m.revolute("ground", (0.0, 0.0), "crank", (-LENGTH / 2, 0.0), name="pivot")
    m.driver("crank", omega=OMEGA, angle0=0.0, name="drive")
    return m


def test_the_tip_of_a_constant_speed_crank():
    tip = (LENGTH / 2, 0.0)  # body frame: the tip is LENGTH from the pivot
    res = _crank().simulate(0.3, extremes=[("crank", tip)], progress=False)
    speed = res.extremes("crank", "velocity", "magnitude", point=tip)
    accel = res.extremes("crank", "acceleration", "magnitude", point=tip)
    assert speed.max == pytest.approx(OMEGA * LENGTH, rel=1e-6) and speed.min == pytest.approx(OMEGA * LENGTH, rel=1e-6)
    # Accelerations come from the KKT solve on the integrated state, whose constraint drift the
    # Baumgarte terms turn into a few 1e-6 of the value.
    assert accel.max == pytest.approx(OMEGA**2 * LENGTH, rel=5e-5) and accel.min == pytest.approx(OMEGA**2 * LENGTH, rel=5e-5)
    x = res.extremes("crank", "displacement", "x", point=tip)
    assert x.max == pytest.approx(LENGTH, rel=1e-7) and x.min == pytest.approx(-LENGTH, rel=1e-7)
    assert x.t_min == pytest.approx(math.pi / OMEGA, rel=1e-5)  # half a turn
    assert res.extremes("crank", "displacement", "magnitude", point=tip).max == pytest.approx(LENGTH, rel=1e-7)
    assert "m/s²" == accel.unit and "crank (0.1, 0).magnitude acceleration" == accel.quantity


def _coupler_path(phi: np.ndarray, p: tuple) -> np.ndarray:
    """The slider-crank's point p (rod frame, from the rod's centroid) at crank angles phi: pin
    B = r(cos φ, sin φ), slider C = (r cos φ + sqrt(l² − r² sin² φ), 0), rod centroid (B + C)/2,
    rod angle atan2(C − B)."""
    r, l = 0.05, 0.12
    b = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=1)
    c = np.stack([r * np.cos(phi) + np.sqrt(l**2 - (r * np.sin(phi)) ** 2), np.zeros_like(phi)], axis=1)
    beta = np.arctan2(c[:, 1] - b[:, 1], c[:, 0] - b[:, 0])
    mid = 0.5 * (b + c)
    return mid + np.stack([np.cos(beta) * p[0] - np.sin(beta) * p[1], np.sin(beta) * p[0] + np.cos(beta) * p[1]], axis=1)


def test_the_coupler_point_of_a_slider_crank():
    m = clearsim.models.slider_crank(joints="ideal")
    omega = 5000 * 2 * math.pi / 60
    p = (0.02, 0.03)
    period = 2 * math.pi / omega
    res = m.simulate(period, extremes=[("rod", p)], dt_out=period / 4000, progress=False)
    path = _coupler_path(np.linspace(0.0, 2 * math.pi, 200_001), p)
    for k, comp in enumerate("xy"):
        e = res.extremes("rod", "displacement", comp, point=p)
        assert e.max == pytest.approx(path[:, k].max(), abs=1e-8) and e.min == pytest.approx(path[:, k].min(), abs=1e-8)
    # Second method: the point from the stored states (r + A p, ṙ + θ̇ B p) on the dense grid
    # never passes the tracked extremes, and comes within the grid's resolution of them.
    q, qd = res.position("rod"), res.velocity("rod")
    c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
    v = np.stack([qd[:, 0] + qd[:, 2] * (-s * p[0] - c * p[1]), qd[:, 1] + qd[:, 2] * (c * p[0] - s * p[1])], axis=1)
    speed = res.extremes("rod", "velocity", "magnitude", point=p)
    stored = np.hypot(v[:, 0], v[:, 1])
    assert stored.max() <= speed.max * (1 + 1e-12) and stored.max() == pytest.approx(speed.max, rel=1e-5)
    assert stored.min() >= speed.min * (1 - 1e-12) - 1e-12 and stored.min() == pytest.approx(speed.min, rel=1e-3, abs=1e-3)


def test_bad_points_are_named():
    m = _crank()
    with pytest.raises(InputError, match="extremes"):
        m.simulate(0.01, extremes=[("nobody", (0.0, 0.0))], progress=False)
    with pytest.raises(InputError, match="extremes"):
        m.simulate(0.01, extremes=[("crank", (0.0, math.nan))], progress=False)
    res = m.simulate(0.01, extremes=[("crank", (0.1, 0.0))], progress=False)
    with pytest.raises(InputError, match="did not track"):
        res.extremes("crank", "velocity", "x", point=(0.2, 0.0))
    with pytest.raises(InputError, match="component"):
        res.extremes("crank", "velocity", "theta", point=(0.1, 0.0))
    with pytest.raises(InputError, match="point"):
        rel.Output(joint="B", point=(0.0, 0.0), quantity="force")
    with pytest.raises(InputError, match="component"):
        rel.Output(body="rod", point=(0.0, 0.0), component="theta")
    with pytest.raises(InputError, match="Output.point"):
        rel.Output(body="rod", point=(0.0,), component="x")


def test_a_study_of_a_coupler_point_against_its_stored_trace():
    point = (0.02, 0.03)
    out = rel.Output(body="rod", point=point, component="magnitude", quantity="displacement")
    assert out.unit == "m" and out.name == "rod(0.02,0.03).magnitude.displacement"
    study = rel.Study(lambda clearance: clearsim.models.slider_crank(joints="dry", clearance=clearance), {"clearance": rel.Normal(0.5e-3, 0.02e-3)},
                      out, rel.Limit(1e-3), cycles=0.5, progress=False)  # fmt: skip
    ev, traces = study.run_samples({"clearance": [0.5e-3]}, keep_traces=1, points_per_cycle=3600, raw_traces=True)
    peak = float(ev.peaks[0])
    sample, ideal = traces[0]["sample"], traces[0]["ideal"]
    b = 3 * 1  # the rod: bodies crank, rod, slider

    def at(q: np.ndarray) -> np.ndarray:
        c, s = np.cos(q[:, b + 2]), np.sin(q[:, b + 2])
        return np.stack([q[:, b] + c * point[0] - s * point[1], q[:, b + 1] + s * point[0] + c * point[1]], axis=1)

    stored = np.hypot(*(at(sample["q"]) - at(ideal["q"])).T)
    # The peak tracked at 8 points a step agrees with the stored values' largest (3 600 a cycle).
    assert stored.max() == pytest.approx(peak, rel=2e-3)
    assert 1e-6 < peak < 2e-3
