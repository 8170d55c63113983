"""``reliability.Study``'s default drive speed: the constant-speed driver of the nominal
mechanism, the same ω a scene's ``[study]`` takes; a clear InputError without one."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError
from clearsim.scene.study import scene_study
from clearsim.scene import load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"


@pytest.mark.parametrize("name, omega", [("compressor.toml", 1500 * 2 * math.pi / 60), ("nine_bar_reliability.toml", -5 * math.pi)])
def test_a_python_study_takes_the_drive_speed_a_scene_study_takes(name: str, omega: float) -> None:
    scene = load_scene_file(SCENES / name)
    from_scene = scene_study(scene, progress=False)
    mech = scene.mechanism

    def build(**values: float) -> clearsim.Mechanism:
        return mech.with_values(values)

    study = rel.Study(build, from_scene.inputs, from_scene.outputs, from_scene.limits, progress=False)
    assert study.omega == from_scene.omega == pytest.approx(omega, rel=1e-12)
    assert study._window(study.nominal())[2] == from_scene._window(from_scene.nominal())[2]  # the crank period [s]


def test_without_a_constant_speed_driver_omega_must_be_given() -> None:
    scene = load_scene_file(SCENES / "engine.toml")  # a motor turns the crank: no driver
    mech = scene.mechanism
    with pytest.raises(InputError, match="no constant-speed driver") as err:
        rel.Study(lambda scale: mech, {"scale": 1.0}, rel.Output(body="piston", component="x"), limit=1e-3, progress=False)
    assert err.value.field == "omega"


def test_several_drive_speeds_are_named_and_omega_asked_for() -> None:
    def build(clearance: float) -> clearsim.Mechanism:
        m = clearsim.models.slider_crank("dry", clearance=clearance)
        return m.driver("rod", omega=10.0, name="second")

    with pytest.raises(InputError, match=r"several constant-speed drivers \('crank-drive' 523\.599 rad/s, 'second' 10 rad/s\)") as err:
        rel.Study(build, {"clearance": 0.5e-3}, rel.Output(body="slider", component="x"), limit=1e-3, progress=False)
    assert err.value.field == "omega"
    given = rel.Study(build, {"clearance": 0.5e-3}, rel.Output(body="slider", component="x"), limit=1e-3, omega=10.0, progress=False)
    assert given.omega == 10.0
