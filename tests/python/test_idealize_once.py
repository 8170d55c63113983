"""Idealisation is done once, in the Rust core (``_core.idealize``, ``MechanismDesc::idealized``):
``Mechanism.idealized`` must give the same ideal description as the Python implementation it
replaced (kept here as the second method), on the shipped models and scenes and on mechanisms
with prismatic clearance, lubricated joints, wear, springs, motors and crank-angle load tables.
"""

from __future__ import annotations

import bisect
import copy
import math
from pathlib import Path
from typing import Any, Dict, List

import pytest

import clearsim as cs
from clearsim import Archard, Dry, Lubricated, _core, models

ROOT = Path(__file__).resolve().parents[2]


def python_idealized(m: cs.Mechanism) -> cs.Mechanism:
    """The Python idealisation that ``Mechanism.idealized`` did before (issue 29), verbatim in effect."""
    ideal = m.copy()

    def insert(entries: List[Dict[str, Any]], entry: Dict[str, Any]) -> None:
        entries.insert(bisect.bisect_right([e["name"] for e in entries], entry["name"]), entry)

    for c in ideal._clearance:
        insert(ideal._joints, {"kind": "revolute", "name": c["name"], "body_a": c["bearing_body"], "point_a": c["bearing_point"],
                               "body_b": c["journal_body"], "point_b": c["journal_point"]})  # fmt: skip
    for p in ideal._prismatic_clearance:
        insert(ideal._joints, {"kind": "prismatic", "name": p["name"], "body_a": p["guide_body"], "point_a": p["guide_point"],
                               "axis": p["axis"], "body_b": p["slider_body"], "point_b": [0.0, 0.0]})  # fmt: skip
    ideal._clearance, ideal._prismatic_clearance = [], []
    ideal._changed()
    return ideal


def _contains(small: Any, big: Any, path: str = "") -> None:
    """Every value of ``small`` is in ``big`` at the same place, equal (floats bit for bit)."""
    if isinstance(small, dict):
        for k, v in small.items():
            assert k in big, f"{path}.{k} missing"
            _contains(v, big[k], f"{path}.{k}")
    elif isinstance(small, (list, tuple)):
        assert len(small) == len(big), path
        for k, (a, b) in enumerate(zip(small, big)):
            _contains(a, b, f"{path}[{k}]")
    elif isinstance(small, float) or isinstance(big, float):
        assert float(small) == float(big) and math.copysign(1, small) == math.copysign(1, big), f"{path}: {small!r} != {big!r}"
    else:
        assert small == big, f"{path}: {small!r} != {big!r}"


def _rich() -> cs.Mechanism:
    """A slider-crank with a worn dry pin, a lubricated pin, a guide with clearance, springs, a
    motor-free driver and loads in time and in the crank angle, defined out of name order."""
    m = cs.Mechanism(gravity=(0.0, -9.81))
    m.add_body("slider", mass=0.2, inertia=1e-4, position=(0.145, 0.0), velocity=(0.1, 0.0, 0.0))
    m.add_body("crank", mass=0.3, inertia=1e-4, position=(0.025, 0.0))
    m.add_body("rod", mass=0.2, inertia=2e-4, position=(0.085, 0.0), angle=0.0)
    m.revolute("ground", (0, 0), "crank", (-0.025, 0), name="z-pivot")
    m.driver("crank", omega=20.0, name="drive1")
    m.clearance_joint("b-pin", "crank", (0.025, 0), "rod", (-0.06, 0), journal_radius=0.01, clearance=2e-4,
                      model=Dry(friction=0.05, wear=Archard(coefficient=1e-4, hardness=2e9, length=0.02)))  # fmt: skip
    m.clearance_joint("a-pin", "slider", (0, 0), "rod", (0.06, 0), journal_radius=0.01, clearance=5e-5,
                      model=Lubricated(viscosity=0.04, length=0.04), initial_eccentricity=(1e-5, 0.0))  # fmt: skip
    m.prismatic_clearance("ground", (0.0, 0.0), "slider", (1.0, 0.0), 1e-4, 0.04, name="guide")
    m.spring("ground", (0.3, 0.0), "slider", (0.0, 0.0), stiffness=100.0, damping=0.5, name="return")
    m.rotational_spring("ground", "crank", stiffness=0.1, name="twist")
    m.force("slider", (0.0, 0.0), {"driver": "drive1", "angle": [0.0, math.pi, 2 * math.pi], "fx": [0.0, -50.0, 0.0], "period": 2 * math.pi}, name="gas")
    m.torque("rod", {"t": [0.0, 1.0], "torque": [0.0, 0.1]}, name="drag", reaction="crank")
    return m


def _motorised() -> cs.Mechanism:
    m = cs.Mechanism()
    m.add_body("crank", mass=0.3, inertia=1e-4, position=(0.025, 0.0))
    m.add_body("rod", mass=0.2, inertia=2e-4, position=(0.085, 0.0))
    m.revolute("ground", (0, 0), "crank", (-0.025, 0))
    m.clearance_joint("pin", "crank", (0.025, 0), "rod", (-0.06, 0), journal_radius=0.01, clearance=1e-4)
    m.motor("crank", stall_torque=1.0, no_load_speed=30.0, angle0=0.3, name="m1")
    m.torque("rod", {"driver": "m1", "angle": [0.0, 1.0], "torque": [0.0, 0.2]})
    return m


MECHANISMS = {
    "slider_crank_dry": lambda: models.slider_crank("dry"),
    "slider_crank_lubricated": lambda: models.slider_crank("lubricated"),
    "nine_bar_dry": lambda: models.nine_bar("dry"),
    "nine_bar_lubricated": lambda: models.nine_bar("lubricated"),
    "rich": _rich,
    "motorised": _motorised,
    **{f"scene {p.stem}": (lambda p=p: cs.load_scene(p)) for p in sorted((ROOT / "scenes").glob("*.toml"))},
}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_idealized_same_as_python(name: str) -> None:
    m = MECHANISMS[name]()
    old = python_idealized(m).description()
    new = m.idealized().description()
    # The same joints in the same order, every value the old description gave kept bit for bit ...
    assert [j["name"] for j in new["joints"]] == [j["name"] for j in old["joints"]]
    assert new["clearance_joints"] == [] and new["prismatic_clearance_joints"] == []
    # (as the core reads them: names resolved, defaults filled in)
    _contains(_core.resolve(old), _core.resolve(new))
    # ... and what the core reads from both is the same (idealising an ideal mechanism changes nothing).
    assert _core.idealize(old) == new
    assert _core.idealize(new) == new
    # The original is untouched, and the ideal one runs like any mechanism.
    assert m.description()["clearance_joints"] or m.description()["prismatic_clearance_joints"]
    # (The original's state has an oil temperature per joint with a heat model; the ideal has none.)
    heated = sum(1 for c in m.description()["clearance_joints"] if c["model"].get("thermal"))
    assert m.idealized().compile().state_dim + heated == m.compile().state_dim


def test_idealized_keeps_settings_and_names() -> None:
    """The ideal copy keeps what is not in the description (assembly tolerance, names taken)."""
    m = _rich()
    m.assembly_tolerance = None
    ideal = m.idealized()
    assert ideal.assembly_tolerance is None
    with pytest.raises(cs.InputError):
        ideal.revolute("ground", (0, 0), "rod", (0, 0), name="b-pin")  # the clearance joint's name stays taken
    assert ideal.body_names == m.body_names
    assert ideal.default_integrator == "rk45"
    assert copy.deepcopy(ideal).description() == ideal.description()
