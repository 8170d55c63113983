"""A scene's [parameters]: named numbers any numeric field may use (a name or a small expression,
evaluated without eval), a [[study.input]] that randomises one (a link length is then two joint
points that follow it), and every mistake named at its file and line."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import reliability as rel
from clearsim.errors import InputError
from clearsim.scene import load_scene_file
from clearsim.scene.parameters import ExpressionError, evaluate, resolve

# The slider-crank of clearsim.models with its crank and rod lengths as parameters: every point
# that depends on them is written with them.
SCENE = """
[parameters]
crank = 0.05                     # m
rod = 0.12                       # m
half_rod = "rod / 2"             # a parameter may use another

[[body]]
name = "crank"
mass = 0.30
inertia = 1.0e-4
ends = [[0.0, 0.0], ["crank", 0.0]]

[[body]]
name = "rod"
mass = 0.21
inertia = 2.5e-4
ends = [["crank", 0.0], ["crank + rod", 0.0]]

[[body]]
name = "slider"
mass = 0.14
inertia = 1.0e-4
position = ["crank + rod", 0]

[[joint]]
type = "revolute"
name = "crank-ground"
bodies = ["ground", "crank"]
points = [[0.0, 0.0], ["-crank/2", 0.0]]

[[joint]]
type = "revolute"
name = "crank-rod"
bodies = ["crank", "rod"]
points = [["crank / 2", 0.0], ["-half_rod", 0.0]]

[[joint]]
type = "prismatic"
name = "slider-guide"
bodies = ["ground", "slider"]
points = [[0.0, 0.0], [0.0, 0.0]]
axis = [1.0, 0.0]

[[driver]]
name = "crank-drive"
body = "crank"
rpm = 5000.0
angle0 = 0.0

[[clearance_joint]]
name = "rod-slider"
bearing_body = "slider"
bearing_point = [0.0, 0.0]
journal_body = "rod"
journal_point = ["half_rod", 0.0]
journal_radius = 9.5e-3
clearance = 0.5e-3
model = "dry"

[simulation]
cycles = 1

[study]
body = "slider"
component = "x"
quantity = "displacement"
limit = 0.6e-3
cycles = 1.0
methods = ["monte_carlo"]
samples = 6

[[study.input]]
parameter = "rod"                # the rod's length: both its ends and the pin follow it
distribution = "normal"
mean = "rod"
std = 1e-3

[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3
std = 0.05e-3
"""


def python_build(rod: float, clearance: float) -> clearsim.Mechanism:
    """The same mechanism through the Python API: what the scene's [parameters] stand for."""
    crank = 0.05
    m = clearsim.Mechanism()
    m.add_body("crank", mass=0.30, inertia=1.0e-4, ends=((0.0, 0.0), (crank, 0.0)))
    m.add_body("rod", mass=0.21, inertia=2.5e-4, ends=((crank, 0.0), (crank + rod, 0.0)))
    m.add_body("slider", mass=0.14, inertia=1.0e-4, position=(crank + rod, 0.0))
    m.revolute("ground", (0.0, 0.0), "crank", (-crank / 2, 0.0), name="crank-ground")
    m.revolute("crank", (crank / 2, 0.0), "rod", (-(rod / 2), 0.0), name="crank-rod")
    m.prismatic("ground", (0.0, 0.0), "slider", (0.0, 0.0), axis=(1.0, 0.0), name="slider-guide")
    m.driver("crank", omega=5000.0 * 2 * math.pi / 60.0, angle0=0.0, name="crank-drive")
    m.clearance_joint("rod-slider", "slider", (0.0, 0.0), "rod", (rod / 2, 0.0), journal_radius=9.5e-3, clearance=clearance, model=clearsim.Dry())
    return m


def _scene(tmp_path: Path, text: str = SCENE) -> Path:
    path = tmp_path / "crank.toml"
    path.write_text(text)
    return path


def test_a_random_link_length_gives_the_python_builds_answers_bit_for_bit(tmp_path):
    scene = load_scene_file(_scene(tmp_path))
    assert scene.parameters == {"crank": 0.05, "rod": 0.12, "half_rod": 0.06}
    assert scene.mechanism.description() == python_build(0.12, 0.5e-3).description()
    from_scene = scene.study_model(progress=False)
    inputs = {"rod": rel.Normal(0.12, 1e-3), "rod-slider.clearance": rel.Normal(0.5e-3, 0.05e-3)}  # named as the scene names them: the same draws

    def build(rod: float, **paths: float) -> clearsim.Mechanism:
        return python_build(rod, paths["rod-slider.clearance"])

    from_python = rel.Study(build, inputs, rel.Output(body="slider", component="x", quantity="displacement"), limit=0.6e-3, cycles=1.0, progress=False)
    a, b = from_scene.monte_carlo(6, seed=3), from_python.monte_carlo(6, seed=3)
    assert all(np.array_equal(a.inputs[k], b.inputs[k]) for k in inputs) and np.ptp(a.inputs["rod"]) > 1e-4  # each sample its own rod
    assert np.array_equal(a.peaks, b.peaks) and np.array_equal(a.first_passage_times, b.first_passage_times, equal_nan=True)
    assert a.pf == b.pf and not a.failures
    # A rod 1 mm longer moves the slider 1 mm further out at top dead centre: the points followed.
    longer = scene._rebuild({"rod": 0.121})
    assert longer.description() == python_build(0.121, 0.5e-3).description()


def test_expressions_are_evaluated_without_eval():
    names = {"rod": 0.12, "crank": 0.05}
    assert evaluate("rod / 2", names) == 0.06
    assert evaluate("-(crank + rod) * 2 ** 2", names) == -(0.05 + 0.12) * 4
    assert evaluate("sqrt(rod**2 - crank**2) + cos(pi) + atan2(1, 1)", names) == math.sqrt(0.12**2 - 0.05**2) - 1 + math.pi / 4
    for bad, why in [("__import__('os')", "unknown function"), ("rod.real", "not allowed"), ("[rod]", "not allowed"), ("rod +", "not an arithmetic"),
                     ("1/0", "cannot be evaluated"), ("sqrt(-1)", "cannot be evaluated"), ("crnk", "unknown name 'crnk'"), ("'a' * 3", "not allowed"),
                     ("(lambda: 1)()", "not allowed"), ("10.0 ** 400", "cannot be evaluated")]:  # fmt: skip
        with pytest.raises(ExpressionError, match=why):
            evaluate(bad, names)
    assert resolve({"b": "a * 2", "a": 3, "c": "a + b"}) == {"b": 6.0, "a": 3.0, "c": 9.0}  # any order
    assert resolve({"b": "a * 2", "a": 3}, {"a": 5}) == {"b": 10.0, "a": 5.0}  # an override reaches what uses it
    with pytest.raises(ExpressionError, match="cycle"):
        resolve({"a": "b", "b": "a + 1"})


def _error(tmp_path: Path, old: str, new: str) -> InputError:
    text = SCENE.replace(old, new, 1)
    assert text != SCENE
    path = _scene(tmp_path, text)
    line = next(k for k, row in enumerate(text.splitlines(), 1) if new.splitlines()[0] in row)
    with pytest.raises(InputError) as err:
        load_scene_file(path)
    assert str(err.value).startswith(f"{path}:{line}: "), (str(err.value), line)
    assert err.value.line == line and err.value.file == str(path)
    return err.value


@pytest.mark.parametrize(
    "old, new, words",
    [
        ('ends = [["crank", 0.0], ["crank + rod", 0.0]]', 'ends = [["crank", 0.0], ["crank + rood", 0.0]]', ["body[1].ends", "unknown name 'rood'", "crank, rod, half_rod"]),
        ("mass = 0.21", 'mass = "0.21 *"', ["body[1].mass", "'0.21 *'", "not an arithmetic expression"]),
        ("mass = 0.21", "mass = \"__import__('os').getcwd()\"", ["body[1].mass", "not allowed"]),
        ('journal_point = ["half_rod", 0.0]', 'journal_point = ["half_rod(2)", 0.0]', ["clearance_joint[0].journal_point", "not allowed"]),
        ('half_rod = "rod / 2"', 'half_rod = "rod / 2 + half_rod"', ["parameters.half_rod", "cycle"]),
        ('half_rod = "rod / 2"', 'half_rod = "rod / (crank - 0.05)"', ["parameters.half_rod", "cannot be evaluated"]),
        ('half_rod = "rod / 2"', "half_rod = [1, 2]", ["parameters.half_rod", "must be a number or an expression"]),
        ('half_rod = "rod / 2"', 'sqrt = 2.0\nhalf_rod = "rod / 2"', ["parameter name 'sqrt'", "function"]),
        ('parameter = "rod"', 'parameter = "rood"', ["no such parameter", "crank, rod, half_rod"]),
        ('parameter = "rod"', 'parameter = "rod"\npath = "rod-slider.clearance"', ["give path", "not both"]),
        ("std = 1e-3", 'std = "rod / 0"', ["std", "cannot be evaluated"]),
    ],
)
def test_every_mistake_is_named_at_its_line(tmp_path, old, new, words):
    err = _error(tmp_path, old, new)
    for w in words:
        assert w in str(err), str(err)


def test_a_parameter_takes_the_unit_of_the_fields_it_is_written_in():
    """samples.csv heads a random [parameters] input with its unit: the feeder's link lengths and
    pivot coordinates, written in points (``"-l5 / 2"``, ``"l6 - arm_half"``), are lengths [m]; a
    parameter in a product of parameters or in fields of different units gets none."""
    from clearsim.reliability.report import input_column
    from clearsim.scene.parameters import parameter_units

    path = Path(__file__).resolve().parents[1] / "data" / "scenes" / "feeder_six_bar.toml"
    scene = clearsim.scene.load_scene_file(path)
    assert {k: scene.parameter_units.get(k) for k in ("l5", "l6", "o6x", "r2", "arm_half")} == dict.fromkeys(("l5", "l6", "o6x", "r2", "arm_half"), "m")
    assert input_column("l5", scene.parameter_units) == "l5 [m]" and input_column("D.clearance") == "D.clearance [m]" and input_column("k") == "k"
    data = {"parameters": {"a": 1.0, "b": 2.0, "w": 3.0, "m": 1.0},
            "body": [{"position": ["a * b", "2 * a"], "mass": "m", "inertia": "m / 12"}], "driver": [{"omega": "w", "angle0": "-w"}]}  # fmt: skip
    assert parameter_units(data, {"mass": "kg", "inertia": "kg m^2", "omega": "rad/s", "angle0": "rad"}) == {}
    data["body"][0]["position"] = ["-a / 2", "2 * b + a"]
    data["driver"][0] = {"omega": "w"}
    assert parameter_units(data, {"mass": "kg", "omega": "rad/s"}) == {"a": "m", "b": "m", "w": "rad/s", "m": "kg"}
