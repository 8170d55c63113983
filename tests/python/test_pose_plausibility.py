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
