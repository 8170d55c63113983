"""Scene files (clearsim.scene): the shipped scenes against clearsim.models, and errors that
name the key, the file and the line."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.scene import Scene, load_scene, load_scene_file
from walks import PUMP

SCENES = Path(__file__).resolve().parents[2] / "scenes"
NINE_BAR = SCENES / "nine_bar.toml"


def _same_run(a: clearsim.Mechanism, b: clearsim.Mechanism, t_end: float, dt_out: float) -> bool:
    ra, rb = a.simulate(t_end, dt_out=dt_out), b.simulate(t_end, dt_out=dt_out)
    return all(np.array_equal(ra._raw[k], rb._raw[k]) for k in ("t", "q", "qd", "qdd", "joints", "violation"))


@pytest.mark.parametrize(
    "file, reference, t_end",
    [
        ("nine_bar.toml", lambda: models.nine_bar("dry", clearance=0.5e-3), 0.02),
        ("nine_bar_lubricated.toml", lambda: models.nine_bar("lubricated", clearance=0.5e-3), 0.005),
        ("slider_crank.toml", lambda: models.slider_crank("dry"), 0.003),
    ],
)
def test_shipped_scene_is_the_model(file, reference, t_end):
    ref = reference()
    m = load_scene(SCENES / file)
    assert m.description() == ref.description()
    assert _same_run(m, ref, t_end, t_end / 100)


def test_scene_settings():
    scene = load_scene_file(NINE_BAR)
    assert isinstance(scene, Scene) and scene.path == NINE_BAR
    sim = scene.simulation
    assert sim.t_end == pytest.approx(3 * 0.4) and sim.cycles == 3 and sim.period == pytest.approx(0.4)
    assert sim.integrator == "auto" and sim.dt_out == 2e-4
    assert set(sim.outputs) >= {"states", "accelerations", "joints", "violation"}
    assert scene.outputs.bodies == ["slider9"] and scene.outputs.components == ["y"] and scene.outputs.ideal
    rel = scene.reliability
    assert rel is not None and rel.body == "slider9" and rel.component == "y" and rel.bin_width == 18.0
    assert rel.omega == pytest.approx(-5 * math.pi)
    assert rel.allowable == {"displacement": (0.0, 0.004), "velocity": (0.0, 0.6), "acceleration": (0.0, 200.0)}
    sc = load_scene_file(SCENES / "slider_crank.toml")
    assert sc.reliability is None and sc.simulation.t_end == pytest.approx(2 * 60 / 5000)


def test_scene_run_errors_and_reliability():
    scene = load_scene_file(NINE_BAR).with_overrides(t_end=0.4)  # [reliability] needs a crank turn
    run = scene.run()
    assert run.ideal is not None and run.failure is None
    for quantity in ("displacement", "velocity", "acceleration"):
        assert np.array_equal(run.errors[("slider9", quantity)], run.result.error(run.ideal, "slider9", quantity))
        fosm = run.reliability[quantity]
        assert 0.0 < fosm.min_reliability <= 1.0
    run_again = scene.run()  # the mechanism is compiled now: the ideal run must still work
    assert np.array_equal(run_again.errors[("slider9", "velocity")], run.errors[("slider9", "velocity")])


# ---------------------------------------------------------------------- errors
def _edit(tmp_path: Path, old: str, new: str, source: Path = NINE_BAR, count: int = 1) -> tuple:
    """Write a copy of ``source`` with the ``count``-th occurrence of ``old`` replaced by
    ``new``; returns (path, 1-based line of the replacement)."""
    text = source.read_text(encoding="utf-8")
    pos = -1
    for _ in range(count):
        pos = text.index(old, pos + 1)
    text = text[:pos] + new + text[pos + len(old) :]
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    return path, text[:pos].count("\n") + 1


def _error(path: Path) -> clearsim.InputError:
    with pytest.raises(clearsim.InputError) as info:
        load_scene_file(path)
    return info.value


def _assert_located(err: clearsim.InputError, path: Path, line: int, *words: str) -> None:
    msg = str(err)
    assert msg.startswith(f"{path}:{line}: "), msg
    assert err.file == str(path) and err.line == line
    for w in words:
        assert w in msg, msg


def test_unknown_key(tmp_path):
    path, line = _edit(tmp_path, "mass = 0.50", "mas = 0.50", count=2)  # rod3, the 3rd body
    err = _error(path)
    _assert_located(err, path, line, "unknown key 'mas'", "[[body]] #3", "mass")
    assert err.field == "body[2].mas"


def test_unknown_key_in_sub_table_of_second_clearance_joint(tmp_path):
    path, line = _edit(tmp_path, "restitution = 0.9", "restitutoin = 0.9", count=2)
    _assert_located(_error(path), path, line, "restitutoin", "[[clearance_joint]] #2 [dry]")


def test_wrong_type(tmp_path):
    path, line = _edit(tmp_path, "inertia = 1.000e-3", 'inertia = "small"')
    _assert_located(_error(path), path, line, "body[7].inertia", "'small'", "must be a number")


def test_boolean_is_not_a_number(tmp_path):
    path, line = _edit(tmp_path, "clearance = 0.5e-3", "clearance = true")
    _assert_located(_error(path), path, line, "clearance", "must be a number")


def test_missing_required_key(tmp_path):
    path, line = _edit(tmp_path, "inertia = 1.667e-4\n", "", count=2)  # crank4
    header = path.read_text().splitlines().index('name = "crank4"                       # O4 → A, L = 0.10 m')
    _assert_located(_error(path), path, header, "missing key 'inertia'", "[[body]] #4")


def test_builder_value_error_is_located(tmp_path):
    path, line = _edit(tmp_path, "mass = 0.65", "mass = -0.65")
    _assert_located(_error(path), path, line, "rod7", "mass", "must be positive")


def test_model_value_error_is_located(tmp_path):
    path, line = _edit(tmp_path, 'normal_law = "lankarani_nikravesh"', 'normal_law = "hooke"', count=2)
    _assert_located(_error(path), path, line, "normal_law", "'hooke'")


def test_unknown_body_in_joint(tmp_path):
    path, line = _edit(tmp_path, 'bodies = ["rod3", "rod7"]', 'bodies = ["rod33", "rod7"]')
    _assert_located(_error(path), path, line, "rod33", "no such body")


def test_rust_side_error_carries_the_file(tmp_path):
    path = tmp_path / "empty.toml"
    path.write_text("[simulation]\nt_end = 0.1\n")
    err = _error(path)
    assert str(err).startswith(f"{path}") and "body" in str(err)


def test_invalid_toml(tmp_path):
    path, line = _edit(tmp_path, "mass = 0.65", "mass = = 0.65")
    _assert_located(_error(path), path, line, "invalid TOML")


def test_unknown_table(tmp_path):
    path, line = _edit(tmp_path, "[simulation]", "[simulations]")
    _assert_located(_error(path), path, line, "unknown key 'simulations'")


def test_model_table_must_match_model(tmp_path):
    path, line = _edit(tmp_path, "[clearance_joint.dry]", "[clearance_joint.lubricated]")
    _assert_located(_error(path), path, line, "lubricated", "model = 'dry'")


def test_ends_and_position_exclusive(tmp_path):
    path, line = _edit(tmp_path, "ends = [[0.0, -0.40], [0.0, -0.30]]", "ends = [[0.0, -0.40], [0.0, -0.30]]\nangle = 1.0")
    _assert_located(_error(path), path, line + 1, "ends", "not both")


def test_simulation_value_error_is_located(tmp_path):
    path, line = _edit(tmp_path, 'integrator = "auto"', 'integrator = "euler"')
    _assert_located(_error(path), path, line, "integrator", "'euler'")


def test_rpm_and_omega_exclusive(tmp_path):
    path, line = _edit(tmp_path, "rpm = 5000.0", "rpm = 5000.0\nomega = 1.0", source=SCENES / "slider_crank.toml")
    _assert_located(_error(path), path, line, "rpm", "not both")


def test_missing_file(tmp_path):
    err = _error(tmp_path / "nope.toml")
    assert "nope.toml" in str(err) and "cannot read" in str(err)


def test_reliability_limits_are_required(tmp_path):
    """No silent paper defaults: a [reliability] block without [reliability.allowable] is an
    error at the [reliability] table naming the missing limits."""
    text = NINE_BAR.read_text()
    start = text.index("[reliability.allowable]")
    path = tmp_path / "scene.toml"
    path.write_text(text[:start])
    err = _error(path)
    assert "missing table [reliability.allowable]" in str(err) and "rad" in str(err)
    assert err.field == "reliability"


LOADS = """
[[force]]
type = "spring"
name = "return-spring"
body_a = "ground"
point_a = [0.3, 0.0]
body_b = "slider"
point_b = [0.0, 0.0]
stiffness = 2000.0
damping = 5.0

[[force]]
type = "force"
name = "stamp"
body = "slider"
value = { driver = "crank-drive", angle = [0.0, 2.6, 2.8, 3.1], fx = [0.0, 0.0, 400.0, 0.0], period = 6.283185307179586 }

[[force]]
type = "torque"
body = "rod"
value = 0.5
"""


def test_scene_force_elements_are_the_python_ones(tmp_path):
    path = tmp_path / "loaded.toml"
    path.write_text((SCENES / "slider_crank.toml").read_text(encoding="utf-8") + LOADS, encoding="utf-8")
    ref = models.slider_crank("dry")
    ref.spring("ground", (0.3, 0.0), "slider", (0.0, 0.0), 2000.0, damping=5.0, name="return-spring")
    ref.force("slider", (0, 0), {"driver": "crank-drive", "angle": [0.0, 2.6, 2.8, 3.1], "fx": [0.0, 0.0, 400.0, 0.0], "period": 2 * math.pi}, name="stamp")
    ref.torque("rod", 0.5, name="torque1")
    m = load_scene(path)
    assert m.description() == ref.description()
    assert _same_run(m, ref, 0.003, 0.003 / 100)


def test_scene_force_element_error_is_located(tmp_path):
    path, line = _edit(tmp_path, "stiffness = 2000.0", "stiffness = -2000.0", source=_with_loads(tmp_path))
    _assert_located(_error(path), path, line, "stiffness", "-2000")
    path, line = _edit(tmp_path, 'driver = "crank-drive"', 'driver = "crank-drve"', source=_with_loads(tmp_path))
    _assert_located(_error(path), path, line, "crank-drve", "no such driver")
    path, line = _edit(tmp_path, 'type = "torque"', 'type = "torsion"', source=_with_loads(tmp_path))
    _assert_located(_error(path), path, line, "torsion", "spring")


def _with_loads(tmp_path: Path) -> Path:
    src = tmp_path / "with_loads.toml"
    src.write_text((SCENES / "slider_crank.toml").read_text(encoding="utf-8") + LOADS, encoding="utf-8")
    return src


def test_scene_prismatic_clearance_joint_is_the_python_one(tmp_path):
    text = (SCENES / "slider_crank.toml").read_text(encoding="utf-8")
    start = text.index('[[joint]]\ntype = "prismatic"')  # the ideal slider guide
    end = text.index("\n[[", start + 5) + 1
    text = text[:start] + text[end:] + """
[[clearance_joint]]
type = "prismatic"
name = "guide"
guide_body = "ground"
guide_point = [0.0, 0.0]
slider_body = "slider"
axis = [1.0, 0.0]
clearance = 0.2e-3
slider_length = 0.05
corner_radius = 0.01
[clearance_joint.dry]
friction = 0.05
"""
    path = tmp_path / "guide.toml"
    path.write_text(text, encoding="utf-8")
    m = load_scene(path)
    assert m.clearance_joint_names == ["rod-slider", "guide front", "guide rear"]
    d = m.description()["prismatic_clearance_joints"][0]
    assert d["clearance"] == 0.2e-3 and d["model"]["friction"] == 0.05 and d["slider_length"] == 0.05 and d["corner_radius"] == 0.01
    assert m.simulate(0.002, progress=False).completed


def test_a_bad_lubricated_field_in_a_scene_names_its_joint(tmp_path):
    """A negative viscosity (or a restitution above 1) in ``[clearance_joint.lubricated]`` /
    ``[clearance_joint.dry]`` names the joint, the field and the value, as ``with_values`` does.
    Before: ``invalid viscosity = -0.2: must be positive`` (which of the joints?)."""
    text = PUMP.read_text(encoding="utf-8")
    for old, new, said in (("viscosity = 0.2 ", "viscosity = -0.2 ", "invalid clearance joint 'A'.viscosity = -0.2: must be positive"),
                           ("restitution = 0.8", "restitution = 1.8", "invalid clearance joint 'O4'.restitution = 1.8")):  # fmt: skip
        path = tmp_path / "bad.toml"
        path.write_text(text.replace(old, new, 1), encoding="utf-8")
        with pytest.raises(clearsim.InputError) as info:
            clearsim.load_scene(path)
        assert said in str(info.value) and str(info.value).startswith(f"{path}:")


def test_a_lubricated_joint_needs_its_viscosity_and_length(tmp_path):
    """A bearing's length and its oil's viscosity define its film: left out of a scene, they are a
    missing key named with the file and the line, not Lubricated()'s defaults (0.4 Pa s, 50 mm:
    the paper's bearing), which ran a 20 mm big end as a 50 mm one without a word."""
    for old, new, key in (("length = 25e-3                        # m (L/D = 0.83)\n", "", "length"),
                          ("viscosity = 0.2                       # Pa s (SAE 40 near 30 °C)\n", "", "viscosity")):  # fmt: skip
        path, line = _edit(tmp_path, old, new, source=PUMP)
        err = _error(path)
        assert f"missing key '{key}'" in str(err) and "[[clearance_joint]] #1 [lubricated]" in str(err), str(err)
        assert str(err).startswith(f"{path}:")
    path, line = _edit(tmp_path, '[clearance_joint.lubricated]\nviscosity = 0.2                       # Pa s (SAE 40 near 30 °C)\n'
                       'length = 25e-3                        # m (L/D = 0.83)\nfilm = "short"\n', "", source=PUMP)  # fmt: skip
    err = _error(path)
    assert "[clearance_joint.lubricated]" in str(err) and "viscosity" in str(err) and "length" in str(err), str(err)
