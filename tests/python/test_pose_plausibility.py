"""Plausibility of the pose given (issue 28, item 6; docs/physics.md §1 "Initial state"): a joint
whose two points lie more than 1 % of the mechanism's span apart at the pose given, or a body that
the assembly turns by more than 2°, draws a PlausibilityWarning naming the joint and both points
(body frame and global); a body moved by more than 20 % stays an AssemblyError."""

import glob
import math
import warnings
from pathlib import Path

import pytest

import clearsim
from clearsim import models
from clearsim.errors import PlausibilityWarning

SCENES = sorted(glob.glob(str(Path(__file__).resolve().parents[2] / "scenes" / "*.toml")))


def slider_crank(crank_pin=(0.02, 0.0), angle0=0.0) -> clearsim.Mechanism:
    """Crank 40 mm (centroid mid-length), rod 120 mm, slider on the x axis, at top dead centre."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("crank", mass=0.3, inertia=1e-4, position=(0.02, 0.0))
    m.add_body("rod", mass=0.2, inertia=2e-4, position=(0.10, 0.0))
    m.add_body("slider", mass=0.1, inertia=1e-4, position=(0.16, 0.0))
    m.revolute("ground", (0.0, 0.0), "crank", (-0.02, 0.0), name="crank-ground")
    m.revolute("crank", crank_pin, "rod", (-0.06, 0.0), name="crank-rod")
    m.revolute("rod", (0.06, 0.0), "slider", (0.0, 0.0), name="rod-slider")
    m.prismatic("ground", (0.0, 0.0), "slider", (0.0, 0.0), axis=(1.0, 0.0), name="guide")
    m.driver("crank", omega=100.0, angle0=angle0, name="crank-drive")
    return m


def stroke(m: clearsim.Mechanism) -> float:
    res = m.simulate(2 * math.pi / 100, progress=False)
    x = res.position("slider")[:, 0]
    return float(x.max() - x.min())


def test_a_joint_point_given_in_the_global_frame_warns():
    """The crank's pin given at its global position (0.04, 0) instead of the body-frame
    (0.02, 0): before, it ran silently with a 1.5× crank (stroke 0.12 m instead of 0.08 m)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert stroke(slider_crank()) == pytest.approx(0.08, rel=1e-5)
    with pytest.warns(PlausibilityWarning) as record:
        assert stroke(slider_crank(crank_pin=(0.04, 0.0))) == pytest.approx(0.12, rel=1e-5)
    msg = str(record[0].message)
    assert "joint 'crank-rod'" in msg and "0.02 m apart" in msg
    assert "point (0.04, 0) on body 'crank' lies at (0.06, 0) (global)" in msg
    assert "point (-0.06, 0) on body 'rod' lies at (0.04, 0) (global)" in msg
    assert record[0].filename == __file__  # points at the user's call


def test_a_driver_that_turns_its_body_warns():
    """The driver's angle0 (5°) disagrees with the crank's angle given (0): every joint meets at
    the pose given, but the assembly turns the crank (and the rod) to follow the driver."""
    with pytest.warns(PlausibilityWarning, match=r"turns body '(crank|rod)' by \d"):
        slider_crank(angle0=math.radians(5.0)).check_assembly()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        slider_crank(angle0=math.radians(1.0)).check_assembly()  # 1°: below the warning


def test_far_beyond_the_warning_it_stays_an_error():
    with pytest.raises(clearsim.AssemblyError, match="joint 'crank-rod'"):
        slider_crank(crank_pin=(0.08, 0.0)).check_assembly()


@pytest.mark.parametrize("kind", ["ideal", "dry", "lubricated"])
def test_shipped_models_raise_no_plausibility_warning(kind):
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        models.slider_crank(kind).check_assembly()
        models.nine_bar(kind).check_assembly()


@pytest.mark.parametrize("path", SCENES, ids=[Path(p).stem for p in SCENES])
def test_shipped_scenes_raise_no_plausibility_warning(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        scene = clearsim.load_scene(path)
        getattr(scene, "mechanism", scene).check_assembly()


def four_bar(wrong: str = "") -> clearsim.Mechanism:
    """A parallelogram four-bar at 90°: ground pivots (0, 0) and (0.3, 0), crank and rocker 0.1 m,
    coupler 0.3 m; the joint ``wrong`` has its first body's point given in global coordinates."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("crank", mass=0.2, inertia=2e-4, position=(0.0, 0.05), angle=math.pi / 2)
    m.add_body("coupler", mass=0.5, inertia=4e-3, position=(0.15, 0.1))
    m.add_body("rocker", mass=0.2, inertia=2e-4, position=(0.3, 0.05), angle=math.pi / 2)
    local = {"P1": (-0.05, 0.0), "P2": (0.05, 0.0), "P3": (0.15, 0.0), "P4": (-0.05, 0.0)}
    world = {"P1": (0.0, 0.0), "P2": (0.0, 0.1), "P3": (0.3, 0.1), "P4": (0.3, 0.0)}
    p = {k: (world[k] if k == wrong else v) for k, v in local.items()}
    m.revolute("ground", (0, 0), "crank", p["P1"], name="P1")
    m.revolute("crank", p["P2"], "coupler", (-0.15, 0.0), name="P2")
    m.revolute("coupler", p["P3"], "rocker", (0.05, 0.0), name="P3")
    m.revolute("rocker", p["P4"], "ground", (0.3, 0.0), name="P4")
    m.driver("crank", omega=10.0)
    return m


def test_the_joint_whose_point_is_wrong_is_named():
    """One joint's point given in the global frame (issue 36, item 6): whatever the assembly then
    does — fail to converge, move a body far, or assemble with a gap — the message names that
    joint. Before: "revolute joint 'P4' is furthest from closing" for a wrong P3 (the equation
    furthest from closing after 60 Newton iterations, wherever the error started), and for a
    wrong P4 the coupler that moved most with none of its joints apart, so no joint at all."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        four_bar().check_assembly()
    for wrong in ("P2", "P3"):  # the loop cannot close: Newton does not converge
        with pytest.raises(clearsim.AssemblyError, match=rf"revolute joint '{wrong}' has its two points [0-9.]+ m apart at the pose given, the most of any joint"):
            four_bar(wrong).check_assembly()
    with pytest.raises(clearsim.AssemblyError, match=r"moves body 'coupler' .*; joint 'P4' has its two points 0.35 m apart") as info:
        four_bar("P4").check_assembly()  # it closes, far from the pose given
    assert info.value.joint == "P4" and info.value.field == "joint 'P4'" and info.value.body == "coupler"
    with pytest.warns(PlausibilityWarning, match=r"joint 'P1' has its two points 0.05 m apart"):
        four_bar("P1").compile()  # it closes near the pose given: a warning when it compiles
