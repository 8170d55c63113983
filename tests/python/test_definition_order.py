"""Definitions in any order (issue 28 item 7): references between elements (a joint's bodies, a
load table's driver, a spring's bodies) are resolved when the mechanism compiles, and the
elements are kept in a canonical order, so every answer is bit-identical whatever order the
elements were defined in. A reference to nothing names the element and its field."""

from __future__ import annotations

import math
import random
from pathlib import Path
from typing import Any, Callable, List, Tuple

import numpy as np
import pytest

import clearsim
from clearsim import Dry, InputError, Lubricated, Mechanism, models

SCENES = Path(__file__).resolve().parents[2] / "scenes"
Call = Tuple[str, tuple, dict]


class _Recording:
    """Stands in for Mechanism inside clearsim.models: records the calls of a model builder."""

    def __init__(self, **kwargs: Any) -> None:
        self.init = kwargs
        self.calls: List[Call] = []

    def __getattr__(self, name: str) -> Callable[..., "_Recording"]:
        def record(*args: Any, **kwargs: Any) -> "_Recording":
            self.calls.append((name, args, kwargs))
            return self

        return record


def _recorded(monkeypatch: pytest.MonkeyPatch, build: Callable[[], Any]) -> _Recording:
    with monkeypatch.context() as mp:
        mp.setattr(models, "Mechanism", _Recording)
        return build()


def _replay(init: dict, calls: List[Call], order: List[int]) -> Mechanism:
    m = Mechanism(**init)
    for k in order:
        name, args, kwargs = calls[k]
        getattr(m, name)(*args, **kwargs)
    return m


def _orders(n: int) -> List[List[int]]:
    return [list(reversed(range(n)))] + [random.Random(seed).sample(range(n), n) for seed in (1, 2)]


def _same(a: clearsim.Result, b: clearsim.Result) -> None:
    assert a.body_names == b.body_names and a.joint_names == b.joint_names
    assert np.array_equal(a.t, b.t)
    for body in a.body_names:
        assert np.array_equal(a.position(body), b.position(body)), body
        assert np.array_equal(a.velocity(body), b.velocity(body)), body
    for joint in a.joint_names:
        assert np.array_equal(a.eccentricity(joint), b.eccentricity(joint)), joint
    assert a.stats["steps"] == b.stats["steps"] and a.impacts == b.impacts


# A dry slider-crank run amplifies round-off: on the old code, its bodies defined in reversed
# order moved the slider by 2.3e-5 m within one crank turn.
MODELS = {
    "slider-crank dry": (lambda: models.slider_crank("dry"), 0.012),
    "slider-crank lubricated": (lambda: models.slider_crank("lubricated", lubricated=Lubricated(film="short", length=0.01)), 0.004),
    "nine-bar dry": (lambda: models.nine_bar("dry"), 0.05),
}


@pytest.mark.parametrize("case", sorted(MODELS))
def test_models_defined_in_any_order_run_bit_identically(monkeypatch, case):
    build, t_end = MODELS[case]
    rec = _recorded(monkeypatch, build)
    n = len(rec.calls)
    ref = _replay(rec.init, rec.calls, list(range(n)))
    base, base_ideal = ref.simulate_with_ideal(t_end, dt_out=t_end / 200)
    for order in _orders(n):
        m = _replay(rec.init, rec.calls, order)
        assert m.description() == ref.description()
        res, ideal = m.simulate_with_ideal(t_end, dt_out=t_end / 200)
        _same(res, base)
        _same(ideal, base_ideal)


def _compressor_calls() -> List[Call]:
    """Every kind of element and reference: a load table over a driver's angle, a motor-less
    driver, springs between bodies and the ground, a torque with a reaction body, a dry and a
    lubricated clearance joint, a prismatic guide."""
    r, l, e = 0.04, 0.14, 0.01
    xs = r + math.sqrt(l * l - e * e)
    gas = {"driver": "motor", "angle": [0.0, 0.7, 3.1416, 5.24, 6.28], "fx": [-1500.0, 0.0, 0.0, -700.0, -1500.0], "period": 2 * math.pi}
    return [
        ("add_body", ("crank",), dict(mass=0.5, inertia=2e-4, ends=((0.0, 0.0), (r, 0.0)))),
        ("add_body", ("rod",), dict(mass=0.3, inertia=5e-4, ends=((r, 0.0), (xs, e)))),
        ("add_body", ("piston",), dict(mass=0.25, inertia=1e-4, position=(xs, e))),
        ("revolute", ("ground", (0.0, 0.0), "crank", (-r / 2, 0.0)), dict(name="main")),
        ("prismatic", ("ground", (0.0, e), "piston", (0.0, 0.0)), dict(axis=(1.0, 0.0), name="cylinder")),
        ("driver", ("crank",), dict(omega=157.08, name="motor")),
        ("clearance_joint", ("crank-pin", "rod", (-l / 2, 0.0), "crank", (r / 2, 0.0)),
         dict(journal_radius=0.01, clearance=5e-5, model=Lubricated(viscosity=0.02, length=0.012, film="short"))),
        ("clearance_joint", ("wrist-pin", "rod", (l / 2, 0.0), "piston", (0.0, 0.0)), dict(journal_radius=0.006, clearance=2e-5, model=Dry())),
        ("force", ("piston", (0.0, 0.0), gas), dict(name="gas")),
        ("spring", ("ground", (0.3, e), "piston", (0.0, 0.0)), dict(stiffness=2000.0, damping=5.0, name="return")),
        ("rotational_spring", ("rod", "crank"), dict(stiffness=0.5, damping=0.01, name="seal")),
        ("torque", ("rod", 0.2), dict(reaction="crank", name="friction")),
    ]  # fmt: skip


def test_every_element_kind_in_any_order():
    calls = _compressor_calls()
    n = len(calls)
    ref = _replay({"gravity": (0.0, -9.81)}, calls, list(range(n)))
    base = ref.simulate(0.01, dt_out=5e-5, progress=False)
    assert base.completed
    for order in _orders(n):
        m = _replay({"gravity": (0.0, -9.81)}, calls, order)
        _same(m.simulate(0.01, dt_out=5e-5, progress=False), base)


def test_a_load_table_over_a_driver_defined_before_the_driver():
    # On the old code: InputError "invalid value.driver = 'motor': no such driver or motor (known: none yet)".
    calls = _compressor_calls()
    first = [k for k, c in enumerate(calls) if c[0] == "force"] + [k for k, c in enumerate(calls) if c[0] != "force"]
    m = _replay({}, calls, first)
    assert m.simulate(0.002, progress=False).completed


@pytest.mark.parametrize(
    "call, field, known",
    [
        (("force", ("piston", (0.0, 0.0), {"driver": "motr", "angle": [0.0, 1.0], "fx": [0.0, 1.0]}), {"name": "gas2"}), "force 'gas2'.value.driver", "motor"),
        (("torque", ("piston", {"driver": "crank", "angle": [0.0, 1.0], "torque": [0.0, 1.0]}), {}), "torque 'torque1'.value.driver", "motor"),
        (("spring", ("ground", (0.0, 0.0), "pistn", (0.0, 0.0)), {"stiffness": 1.0, "name": "s"}), "spring 's'.body_b", "piston"),
        (("rotational_spring", ("rd", "crank", 1.0), {}), "rotational spring 'rotational_spring1'.body_a", "rod"),
        (("torque", ("rod", 1.0), {"reaction": "crank2", "name": "t"}), "torque 't'.reaction", "crank"),
        (("motor", ("crank", 1.0, 10.0), {"reaction": "frame", "name": "m"}), "motor 'm'.reaction", "ground"),
        (("revolute", ("crnk", (0.0, 0.0), "rod", (0.0, 0.0)), {"name": "j"}), "joint 'j'.body_a", "crank"),
        (("prismatic", ("ground", (0.0, 0.0), "slider", (0.0, 0.0)), {"name": "guide"}), "joint 'guide'.body_b", "piston"),
        (("driver", ("crank4",), {"omega": 1.0, "name": "d4"}), "driver 'd4'.body", "crank"),
        (("clearance_joint", ("pin", "rod", (0.0, 0.0), "journal", (0.0, 0.0)), {"journal_radius": 0.01, "clearance": 1e-4}), "clearance joint 'pin'.journal_body", "rod"),
        (("prismatic_clearance", ("ground", (0.0, 0.0), "slidr", (1.0, 0.0), 1e-4, 0.05), {"name": "pc"}), "clearance joint 'pc'.slider_body", "piston"),
    ],
)  # fmt: skip
def test_a_wrong_reference_names_the_element_and_field(call, field, known):
    m = _replay({}, _compressor_calls(), list(range(len(_compressor_calls()))))
    name, args, kwargs = call
    getattr(m, name)(*args, **kwargs)  # accepted: the element it names may come later
    with pytest.raises(InputError) as err:
        m.compile()
    assert err.value.field == field
    assert str(err.value).startswith(f"invalid {field} = ") and "known: " in str(err.value) and known in str(err.value)


def test_a_wrong_driver_in_a_scene_points_at_the_force(tmp_path):
    text = (SCENES / "engine.toml").read_text().replace('value = { driver = "dyno"', 'value = { driver = "dynamo"')
    path = tmp_path / "engine.toml"
    path.write_text(text)
    line = 1 + next(k for k, ln in enumerate(text.splitlines()) if ln.startswith('value = { driver = "dynamo"'))
    with pytest.raises(InputError) as err:
        clearsim.scene.load_scene_file(path)
    assert str(err.value).startswith(f"{path}:{line}:") and "force 'gas'.value.driver = 'dynamo'" in str(err.value) and "known: dyno" in str(err.value)


def test_a_driver_in_a_scene_may_come_after_the_force_that_follows_it(tmp_path):
    text = (SCENES / "engine.toml").read_text()
    # Move the motor (the gas table's driver) to the end of the file.
    start = text.index("[[force]]\ntype = \"motor\"")
    end = text.index("[[force]]", start + 5)
    moved = text[:start] + text[end:] + "\n" + text[start:end]
    path = tmp_path / "engine.toml"
    path.write_text(moved)
    a = clearsim.load_scene(SCENES / "engine.toml").simulate(0.005, progress=False)
    b = clearsim.load_scene(path).simulate(0.005, progress=False)
    _same(a, b)
