"""Reactions by name (issue 36 item 5): ``Result.joint_force`` for revolute, prismatic and
clearance joints, ``joint_torque`` and ``driver_torque``, in the global frame on each joint's
second body, checked by a second method — Newton–Euler on every body at every output time (the
joint forces, torques, clearance-joint forces and gravity on a body equal m a and J α) — and
against closed forms: a pendulum's pivot force m(g cos φ + ω² L) along the rod, and a constant-
speed slider-crank's driver torque from its closed-form kinetic energy (τ ω = dT/dt)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.cli import main

SCENES = Path(__file__).resolve().parents[2] / "scenes"
TIGHT = dict(rtol=1e-10, atol=1e-13)


def _rot(th: np.ndarray, p) -> np.ndarray:
    c, s = np.cos(th), np.sin(th)
    return np.column_stack([c * p[0] - s * p[1], s * p[0] + c * p[1]])


def newton_euler_residual(res: clearsim.Result) -> np.ndarray:
    """(N, bodies, 3) of m a − ΣF and J α − ΣM (about the centroid), from the joints' reactions
    read by name, the clearance joints' forces and friction torques, and gravity."""
    desc = res.description
    names = res.body_names
    n = len(res.t)
    q = np.stack([res.position(b) for b in names], axis=1)
    acc = np.stack([res.acceleration(b) for b in names], axis=1)
    mass = np.array([[b["mass"], b["mass"], b["inertia"]] for b in desc["bodies"]])
    load = np.zeros((n, len(names), 3))
    load[:, :, :2] += mass[None, :, :2] * np.asarray(desc["gravity"])[None, None, :]

    def add(body, force, moment):
        if body is not None:
            load[:, body, :2] += force
            load[:, body, 2] += moment

    def cross(r, f):
        return r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0]

    for j in desc["joints"]:
        f = res.joint_force(j["name"])
        tq = res.joint_torque(j["name"])
        b, a = j["body_b"], j["body_a"]
        arm_b = _rot(q[:, b, 2], j["point_b"])
        add(b, f, cross(arm_b, f) + tq)
        if a is not None:
            if j["kind"] == "revolute":
                arm_a = _rot(q[:, a, 2], j["point_a"])
            else:  # the guide takes the opposite force where the slider's point is
                arm_a = q[:, b, :2] + arm_b - q[:, a, :2]
            add(a, -f, cross(arm_a, -f) - tq)
    for d in desc["drivers"]:
        add(d["body"], 0.0, res.driver_torque(d["name"]))
    for c in desc["clearance_joints"]:
        f = res.joint_force(c["name"])
        jb, bb = c["journal_body"], c["bearing_body"]
        add(jb, f, cross(_rot(q[:, jb, 2], c["journal_point"]), f) + res.friction_torque(c["name"]))
        if bb is not None:
            add(bb, -f, cross(_rot(q[:, bb, 2], c["bearing_point"]), -f) + res.friction_torque(c["name"], body="bearing"))
    return mass[None, :, :] * acc - load


@pytest.mark.parametrize(
    "build, t_end",
    [
        (lambda: models.slider_crank("ideal", gravity=(0.0, -9.81)), 0.012),
        (lambda: models.slider_crank("dry", gravity=(3.0, -9.81)), 0.003),
        (lambda: models.nine_bar("ideal"), 0.1),
    ],
    ids=["slider-crank", "slider-crank-dry", "nine-bar"],
)
def test_newton_euler_holds_on_every_body(build, t_end):
    m = build()
    res = m.simulate(t_end, dt_out=t_end / 200, outputs=["states", "accelerations", "reactions", "joints"], progress=False)
    residual = newton_euler_residual(res)
    scale = max(float(np.max(np.abs(np.stack([res.joint_force(j["name"]) for j in res.description["joints"]])))), 1.0)
    arm = 0.1  # m: the moments' scale is a force times a link's length
    assert np.max(np.abs(residual[:, :, :2])) < 1e-8 * scale
    assert np.max(np.abs(residual[:, :, 2])) < 1e-8 * scale * arm


def test_pendulum_pivot_force():
    mass, length, inertia, g = 2.0, 0.4, 0.01, 9.81
    m = clearsim.Mechanism(gravity=(0.0, -g))
    m.add_body("bob", mass=mass, inertia=inertia, position=(length, 0.0), angle=0.0)
    m.revolute("ground", (0.0, 0.0), "bob", (-length, 0.0), name="pivot")
    res = m.simulate(1.0, dt_out=1e-3, outputs=["states", "accelerations", "reactions"], progress=False, **TIGHT)
    x, y, th = res.position("bob").T
    w = res.velocity("bob")[:, 2]
    f = res.joint_force("pivot")  # on the bob (body_b), from the pivot
    u = np.column_stack([x, y]) / length  # unit vector pivot → bob
    phi = np.arctan2(x, -y)  # angle from hanging straight down
    tension = mass * (g * np.cos(phi) + w**2 * length)
    np.testing.assert_allclose(-(f * u).sum(axis=1), tension, rtol=0, atol=1e-8 * mass * g)
    # across the rod: m L α + m g sin φ with α = −m g L sin φ / (J + m L²)
    t_dir = np.column_stack([-u[:, 1], u[:, 0]])
    alpha = -mass * g * length * np.sin(phi) / (inertia + mass * length**2)
    np.testing.assert_allclose((f * t_dir).sum(axis=1), mass * length * alpha + mass * g * np.sin(phi), rtol=0, atol=1e-7 * mass * g)
    np.testing.assert_array_equal(res.joint_torque("pivot"), 0.0)
    assert float(np.max(tension)) > 2 * mass * g  # released horizontal: the swing's bottom carries 3 m g


def test_driver_torque_of_a_constant_speed_slider_crank():
    r, l, rpm = 0.05, 0.12, 5000.0
    w = rpm * 2 * math.pi / 60
    m = models.slider_crank("ideal", rpm=rpm)
    res = m.simulate(60 / rpm, dt_out=60 / rpm / 400, outputs=["states", "accelerations", "reactions"], progress=False, **TIGHT)
    mc, jc, mr, jr, ms = 0.30, 1e-4, 0.21, 2.5e-4, 0.14

    def kinetic(t):
        th = w * t
        s, c = np.sin(th), np.cos(th)
        root = np.sqrt(l**2 - (r * s) ** 2)
        xs_dot = -r * s * w - r**2 * s * c * w / root
        phi_dot = -(r * c * w / l) / np.sqrt(1 - (r * s / l) ** 2)
        vrx, vry = 0.5 * (-r * s * w + xs_dot), 0.5 * r * c * w
        return 0.5 * (jc + mc * (r / 2) ** 2) * w**2 + 0.5 * mr * (vrx**2 + vry**2) + 0.5 * jr * phi_dot**2 + 0.5 * ms * xs_dot**2

    h = 1e-8
    torque = (kinetic(res.t + h) - kinetic(res.t - h)) / (2 * h) / w  # τ ω = dT/dt (no gravity, no friction)
    got = res.driver_torque("crank-drive")
    assert got.shape == (len(res.t),)
    np.testing.assert_allclose(got, torque, rtol=0, atol=1e-6 * np.max(np.abs(torque)))
    assert np.max(np.abs(torque)) > 1.0  # N m: a real load


def test_reactions_of_every_joint_kind_by_name():
    m = models.slider_crank("dry")
    res, ideal = m.simulate_with_ideal(0.002, dt_out=1e-4, outputs=["states", "accelerations", "reactions", "joints"], progress=False)
    # the ideal twin's joint made from the clearance joint is reached by the same name: on the journal (rod)
    assert ideal.joint_force("rod-slider").shape == (len(ideal.t), 2)
    assert res.joint_force("rod-slider").shape == (len(res.t), 2)  # the clearance joint: its own reading
    f = res.joint_force("slider-guide")  # prismatic on the x axis: a force along y only
    np.testing.assert_array_equal(f[:, 0], 0.0)
    assert res.joint_torque("slider-guide").shape == (len(res.t),)
    with pytest.raises(clearsim.InputError, match="driver_torque"):
        res.joint_force("crank-drive")
    with pytest.raises(clearsim.InputError, match="friction_torque"):
        res.joint_torque("rod-slider")
    with pytest.raises(clearsim.InputError, match=r"known: rod-slider, crank-ground, crank-rod, slider-guide"):
        res.joint_force("nope")
    with pytest.raises(clearsim.InputError, match="joint_force"):
        res.driver_torque("crank-rod")
    plain = m.simulate(0.001, progress=False)
    with pytest.raises(clearsim.InputError, match=r"outputs=\[\.\.\., 'reactions'\]"):
        plain.joint_force("crank-rod")
    peaks = res.reaction_summary()
    assert set(peaks) == {"rod-slider", "crank-ground", "crank-rod", "slider-guide", "crank-drive"}
    assert peaks["crank-rod"]["peak_force"] == pytest.approx(float(np.max(np.hypot(*res.joint_force("crank-rod").T))))
    k = int(np.argmax(np.abs(res.driver_torque("crank-drive"))))
    assert peaks["crank-drive"] == {"kind": "driver", "tracked": False, "peak_torque": res.driver_torque("crank-drive")[k], "t_peak_torque": res.t[k]}
    assert [peaks[n]["kind"] for n in ("rod-slider", "crank-rod", "slider-guide")] == ["clearance", "revolute", "prismatic"]


def _spun_crank(mass: float, r: float, w: float, g: float) -> clearsim.Mechanism:
    """A crank turned at constant ω about the origin under gravity, its centroid r from the pivot
    (body_b of the pivot: the force on the crank is m (a − g) with a = −ω² r (cos θ, sin θ))."""
    m = clearsim.Mechanism(gravity=(0.0, -g))
    m.add_body("crank", mass=mass, inertia=1e-3, position=(r * math.cos(0.3), r * math.sin(0.3)), angle=0.3)
    m.revolute("ground", (0.0, 0.0), "crank", (-r, 0.0), name="pivot")
    m.driver("crank", omega=w, name="motor")
    return m


@pytest.mark.parametrize("integrator", ["rk45", "radau"])
def test_tracked_reaction_peaks_are_the_closed_form_at_any_dt_out(integrator):
    """The pivot's |F| peaks at m (ω² r + g) (θ = 3π/2), its components at ±m ω² r and
    m (g ± ω² r), the driver's torque m g r cos θ at ±m g r: tracked at every step, the same at
    dt_out T/50 and T/5000, where the stored outputs miss the peaks (the grid starts at θ = 0.3)."""
    mass, r, w, g = 0.5, 0.08, 9.0, 9.81
    period = 2 * math.pi / w
    m = _spun_crank(mass, r, w, g)
    runs = [m.simulate(period, dt_out=period / n, outputs=["states", "reactions"], extremes=["pivot", "motor"], integrator=integrator, progress=False, **TIGHT) for n in (50, 5000)]
    for res in runs:
        s = res.reaction_summary()
        pivot, motor = s["pivot"], s["motor"]
        assert pivot["tracked"] and motor["tracked"]
        assert pivot["peak_force"] == pytest.approx(mass * (w * w * r + g), rel=1e-9)
        assert (pivot["t_peak_force"] * w + 0.3) % (2 * math.pi) == pytest.approx(1.5 * math.pi, abs=1e-4)
        assert (pivot["max_fx"], pivot["min_fx"]) == pytest.approx((mass * w * w * r, -mass * w * w * r), rel=1e-9)
        assert (pivot["max_fy"], pivot["min_fy"]) == pytest.approx((mass * (g + w * w * r), mass * (g - w * w * r)), rel=1e-9)
        assert (motor["max_torque"], motor["min_torque"]) == pytest.approx((mass * g * r, -mass * g * r), rel=1e-9)
        assert abs(motor["peak_torque"]) == pytest.approx(mass * g * r, rel=1e-9)
        assert res.extremes("pivot", "force", "y").max == pivot["max_fy"] and res.extremes("motor", "torque").min == motor["min_torque"]
    coarse, fine = (r.reaction_summary() for r in runs)
    assert coarse["pivot"]["peak_force"] == pytest.approx(fine["pivot"]["peak_force"], rel=1e-12)
    # the stored outputs of the coarse grid miss the peak (what reaction_summary reported before)
    stored = float(np.max(np.hypot(*runs[0].joint_force("pivot").T)))
    assert stored < coarse["pivot"]["peak_force"] * (1 - 1e-5)


def test_reaction_extremes_are_named_and_asked_for():
    m = _spun_crank(0.5, 0.08, 9.0, 9.81)
    res = m.simulate(0.1, outputs=["states", "reactions"], extremes=["motor"], progress=False)
    with pytest.raises(clearsim.InputError, match=r"did not track.*extremes=\['pivot'\]"):
        res.extremes("pivot", "force")
    with pytest.raises(clearsim.InputError, match="quantity"):
        res.extremes("motor", "force")
    with pytest.raises(clearsim.InputError, match="known: crank, pivot, motor"):
        m.simulate(0.1, extremes=["pivt"], progress=False)
    s = res.reaction_summary()
    assert s["motor"]["tracked"] and not s["pivot"]["tracked"]  # the pivot: over the stored outputs


def test_reactions_in_exports(tmp_path):
    m = models.slider_crank("ideal")
    res = m.simulate(0.002, dt_out=1e-4, outputs=["states", "reactions"], progress=False)
    df = res.to_pandas()
    units = df.attrs["units"]
    assert units["crank-rod.fx"] == "N" and units["slider-guide.torque"] == "N m" and units["crank-drive.torque"] == "N m"
    assert "crank-rod.torque" not in df  # a revolute joint carries no couple
    np.testing.assert_array_equal(df["crank-rod.fy"].to_numpy(), res.joint_force("crank-rod")[:, 1])
    np.testing.assert_array_equal(df["crank-drive.torque"].to_numpy(), res.driver_torque("crank-drive"))
    res.save(tmp_path / "r.csv")
    header = (tmp_path / "r.csv").read_text().splitlines()[0].split(",")
    assert {"crank-ground.fx [N]", "slider-guide.fy [N]", "slider-guide.torque [N m]", "crank-drive.torque [N m]"} <= set(header)
    ds = res.to_xarray()
    np.testing.assert_array_equal(ds["reaction"].sel(constraint="crank-drive", reaction_component="torque").values, res.driver_torque("crank-drive"))


def test_clearsim_run_writes_reactions_and_their_peaks(tmp_path, capsys):
    out = tmp_path / "sc"
    assert main(["run", str(SCENES / "slider_crank.toml"), "-o", str(out), "--t-end", "0.002", "--no-plots"]) == 0
    printed = capsys.readouterr().out
    assert "peak joint force: rod-slider" in printed and "peak driver torque: crank-drive" in printed
    header = (out / "reactions.csv").read_text().splitlines()[0].split(",")
    assert header == ["t [s]", "crank-ground.fx [N]", "crank-ground.fy [N]", "crank-rod.fx [N]", "crank-rod.fy [N]",
                      "slider-guide.fx [N]", "slider-guide.fy [N]", "slider-guide.torque [N m]", "crank-drive.torque [N m]"]  # fmt: skip
    rows = np.loadtxt(out / "reactions.csv", delimiter=",", skiprows=1)
    summary = json.loads((out / "summary.json").read_text())
    peaks = summary["run"]["reactions"]
    # tracked at every step (at least every stored output's value)
    assert peaks["crank-drive"]["tracked"] and peaks["crank-rod"]["tracked"] and peaks["rod-slider"]["tracked"]
    assert abs(peaks["crank-drive"]["peak_torque"]) >= np.max(np.abs(rows[:, -1])) * (1 - 1e-9)
    assert peaks["crank-rod"]["peak_force"] >= np.max(np.hypot(rows[:, 3], rows[:, 4])) * (1 - 1e-9)
    assert "| crank-drive (driver) |" in (out / "summary.md").read_text()
