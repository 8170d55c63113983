"""Lock-ups and over-constraint named (issue 28, item 5; docs/physics.md §1, "Lock-ups and
over-constraint"): a constraint Jacobian that loses rank — in assembly, following the drivers to
t0, or during a run — names the joints and drivers whose rows are dependent, the time and what
it means, instead of a bare "step size underflow"."""

import math
import re

import pytest

import clearsim
from clearsim import models

OMEGA = 10.0  # [rad/s]


def four_bar(drive: str) -> clearsim.Mechanism:
    """A Grashof crank-rocker: ground pivots 0.3 m apart, crank 0.1 m, coupler 0.3 m, rocker
    0.2 m; ``drive`` is ``"crank"``, ``"rocker"`` or ``"both"``."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    a, o4, l_coupler, l_rocker = (0.0, 0.1), (0.3, 0.0), 0.3, 0.2
    d = math.dist(a, o4)
    along = (l_coupler**2 - l_rocker**2 + d**2) / (2 * d)
    h = math.sqrt(l_coupler**2 - along**2)
    ux, uy = (o4[0] - a[0]) / d, (o4[1] - a[1]) / d
    b = (a[0] + along * ux - h * uy, a[1] + along * uy + h * ux)

    def link(name, p, q):
        m.add_body(name, mass=1.0, inertia=0.01, position=((p[0] + q[0]) / 2, (p[1] + q[1]) / 2), angle=math.atan2(q[1] - p[1], q[0] - p[0]))
        return math.dist(p, q) / 2

    hc, hr, hk = link("crank", (0.0, 0.0), a), link("coupler", a, b), link("rocker", o4, b)
    m.revolute("ground", (0.0, 0.0), "crank", (-hc, 0.0), name="O2")
    m.revolute("crank", (hc, 0.0), "coupler", (-hr, 0.0), name="A")
    m.revolute("coupler", (hr, 0.0), "rocker", (hk, 0.0), name="B")
    m.revolute("ground", o4, "rocker", (-hk, 0.0), name="O4")
    if drive in ("crank", "both"):
        m.driver("crank", omega=OMEGA, angle0=math.pi / 2, name="crank-drive")
    if drive in ("rocker", "both"):
        m.driver("rocker", omega=OMEGA, angle0=math.atan2(b[1] - o4[1], b[0] - o4[0]), name="rocker-drive")
    return m


def rocker_limit_time() -> float:
    """When the rocker, turning at OMEGA from its starting angle, reaches an extreme: crank and
    coupler aligned, so that the distance from the crank's pivot O2 to the rocker's tip B is
    coupler ± crank (0.4 or 0.2 m). First crossing by a scan, then bisection."""
    th0 = four_bar("rocker")._drivers[0]["law"]["angle0"]

    def slack(t: float) -> float:  # > 0 while the loop closes
        th = th0 + OMEGA * t
        r = math.hypot(0.3 + 0.2 * math.cos(th), 0.2 * math.sin(th))
        return (0.4 - r) * (r - 0.2)

    lo = 0.0
    hi = next(k * 1e-3 for k in range(1, 1000) if slack(k * 1e-3) < 0)
    lo = hi - 1e-3
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if slack(mid) > 0 else (lo, mid)
    return lo


def test_a_four_bar_driven_past_its_rockers_limit_names_the_dead_centre():
    """Driving the rocker at constant speed takes it to its extreme, where crank and coupler
    align: the run stops there with the lock-up named (before: "step size underflow at t = …"
    and nothing else)."""
    with pytest.raises(clearsim.SimulationError) as info:
        four_bar("rocker").simulate(0.7, progress=False)
    msg = str(info.value)
    assert not msg.startswith("step size underflow")
    assert "'crank' and 'coupler' aligned: dead centre" in msg
    assert "driver 'rocker-drive' cannot drive the mechanism past it" in msg
    for joint in ("A", "B", "O2", "O4"):
        assert f"revolute joint '{joint}'" in msg
    t_limit = rocker_limit_time()
    assert info.value.t == pytest.approx(t_limit, abs=1e-6)
    assert f"t = {info.value.t:.9f} s" in msg
    assert info.value.result is not None and info.value.result.t[-1] <= info.value.t


def test_the_same_dead_centre_before_t0_is_an_assembly_error():
    with pytest.raises(clearsim.AssemblyError) as info:
        four_bar("rocker").simulate(0.6, t0=0.5, progress=False)
    msg = str(info.value)
    assert "following the drivers from the pose given (t = 0) to t0 = 0.5 s" in msg
    assert "'crank' and 'coupler' aligned: dead centre" in msg and "driver 'rocker-drive'" in msg
    assert info.value.t == pytest.approx(rocker_limit_time(), abs=1e-6)


def test_a_slider_crank_whose_crank_is_longer_than_its_rod_names_the_dead_centre():
    """Crank 50 mm, rod 40 mm: the loop cannot close beyond θ = asin(0.04/0.05) = 53.13°, where
    the rod stands perpendicular to the slider's guide (before: a bare step size underflow)."""
    m = models.slider_crank("ideal", crank_length=0.05, rod_length=0.04)
    with pytest.raises(clearsim.SimulationError) as info:
        m.simulate(0.012, progress=False)
    msg = str(info.value)
    assert "'rod' perpendicular to the guide of prismatic joint 'slider-guide': dead centre" in msg
    assert "driver 'crank-drive' cannot drive the mechanism past it" in msg
    for joint in ("crank-rod", "rod-slider", "crank-ground"):
        assert f"revolute joint '{joint}'" in msg
    t_dead = math.asin(0.04 / 0.05) / (5000 * 2 * math.pi / 60)
    assert info.value.t == pytest.approx(t_dead, rel=1e-6)


def test_a_four_bar_driven_at_crank_and_rocker_names_both_drivers():
    """10 equations for 9 coordinates: before, the message said so with "(residual ‖Φ‖ = NaN)"
    and named nothing; now it names both drivers and the loop's joints and what to do."""
    with pytest.raises(clearsim.AssemblyError) as info:
        four_bar("both").simulate(0.1, progress=False)
    msg = str(info.value)
    assert "10 constraint equations for 9 coordinates" in msg and "over-constrained" in msg
    assert "driver 'rocker-drive'" in msg and "driver 'crank-drive'" in msg
    for joint in ("A", "B", "O2", "O4"):
        assert f"revolute joint '{joint}'" in msg
    assert "drive one of them" in msg and "NaN" not in msg
    assert info.value.t == 0.0


def test_a_redundant_joint_at_a_sound_pose_is_named():
    """A second revolute joint at the same pivot repeats the first one's rows: both are named."""
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("link", mass=1.0, inertia=0.01, position=(0.1, 0.0))
    m.add_body("link2", mass=1.0, inertia=0.01, position=(0.3, 0.0))
    m.revolute("ground", (0.0, 0.0), "link", (-0.1, 0.0), name="pivot")
    m.revolute("link", (0.1, 0.0), "link2", (-0.1, 0.0), name="elbow")
    m.revolute("link", (0.1, 0.0), "link2", (-0.1, 0.0), name="elbow_again")
    with pytest.raises(clearsim.AssemblyError, match=re.escape("revolute joint 'elbow")) as info:
        m.simulate(0.01, progress=False)
    assert "elbow_again" in str(info.value) and "'elbow'" in str(info.value)


def test_a_sound_crank_driven_four_bar_runs_from_any_start():
    """The same four-bar driven at its crank turns round: no lock-up, from 0 or from half a turn."""
    for t0 in (0.0, 0.35):
        res = four_bar("crank").simulate(t0 + 0.7, t0=t0, progress=False)
        assert res.completed
