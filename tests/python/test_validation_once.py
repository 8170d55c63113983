"""Validation once (issue 29, criterion 3): a value's range is checked by the Rust core
(rust/compile/validate.rs) — as each element is added (issue 36, item 6: ``_core.check_element``,
the same checks), its references to other elements when the mechanism compiles — or when a run's
settings arrive (rust/settings.rs), not again in Python. The mistake must still reach the user as
a clear InputError naming the element, the field and the value, before anything runs."""

from __future__ import annotations

import math
import re
from typing import Any, Callable, List, Tuple

import pytest

import clearsim
import clearsim as cs
from clearsim import Archard, Dry, Lubricated, Thermal, Vogel, models


def pendulum(**body: Any) -> cs.Mechanism:
    args = dict(mass=1.0, inertia=0.01, position=(0.1, 0.0))
    args.update(body)
    return cs.Mechanism().add_body("arm", **args).revolute("ground", (0, 0), "arm", (-0.1, 0), name="pivot")


def pinned(model: Any = None, **kw: Any) -> cs.Mechanism:
    args = dict(journal_radius=0.01, clearance=1e-4, model=model)
    args.update(kw)
    return cs.Mechanism().add_body("arm", mass=1.0, inertia=0.01, position=(0.1, 0.0)).clearance_joint("pin", "ground", (0, 0), "arm", (-0.1, 0), **args)


def slider(**kw: Any) -> cs.Mechanism:
    m = cs.Mechanism().add_body("block", mass=1.0, inertia=0.01)
    args = dict(axis=(1.0, 0.0), clearance=1e-4, slider_length=0.04)
    args.update(kw)
    return m.prismatic_clearance("ground", (0, 0), "block", name="guide", **args)


# (id, what the user writes, the field the core names, the value as written). A model's values are
# checked as the model is made (Dry(...), Lubricated(...)): named without its joint, which it
# does not know yet (a scene names the joint: scene/builder.py).
CASES: List[Tuple[str, Callable[[], cs.Mechanism], str, str]] = [
    ("mass", lambda: pendulum(mass=-2.0), "body 'arm'.mass", "-2.0"),
    ("inertia", lambda: pendulum(inertia=0.0), "body 'arm'.inertia", "0.0"),
    ("same bodies", lambda: pendulum().revolute("arm", (0, 0), "arm", (0.1, 0), name="self"), "joint 'self'.body_b", ""),
    ("axis", lambda: pendulum().add_body("b", mass=1.0, inertia=0.01).prismatic("ground", (0, 0), "b", (0, 0), axis=(0.0, 0.0), name="p"), "joint 'p'.axis", "[0.0, 0.0]"),
    ("clearance", lambda: pinned(clearance=-1e-4), "clearance joint 'pin'.clearance", "-0.0001"),
    ("journal radius", lambda: pinned(journal_radius=0.0), "clearance joint 'pin'.journal_radius", "0.0"),
    ("eccentricity", lambda: pinned(initial_eccentricity=(0.5, 0.0)), "clearance joint 'pin'.initial_eccentricity", "[0.5, 0.0]"),
    ("restitution", lambda: pinned(Dry(restitution=1.2)), "restitution", "1.2"),
    ("v1 below v0", lambda: pinned(Dry(v0=1e-2, v1=1e-3)), "v1", "0.001"),
    ("wear coefficient", lambda: pinned(Dry(wear=Archard(coefficient=-1e-4, hardness=2e9, length=0.02))), "wear.coefficient", "-0.0001"),
    ("wear depths", lambda: pinned(Dry(wear=Archard(1e-4, 2e9, 0.02, initial_bearing=[0.0] * 10))), "wear.initial_bearing", "10 depths"),
    ("viscosity", lambda: pinned(Lubricated(viscosity=-0.4)), "viscosity", "-0.4"),
    ("eps0", lambda: pinned(Lubricated(eps0=1.5)), "eps0", "1.5"),
    ("boundary friction alone", lambda: pinned(Lubricated(boundary_friction=0.1)), "boundary_friction", "0.1"),
    ("vogel without thermal", lambda: pinned(Lubricated(viscosity=Vogel(1e-4, 900.0, 150.0))), "thermal", "None"),
    ("thermal ambient", lambda: pinned(Lubricated(thermal=Thermal(-1.0, 10.0, 1.0))), "thermal.ambient", "-1.0"),
    ("film", lambda: pinned(Lubricated(film="medium")), "film", "medium"),
    ("slider length", lambda: slider(slider_length=0.0), "clearance joint 'guide'.slider_length", "0.0"),
    ("corner radius", lambda: slider(corner_radius=-1e-3), "clearance joint 'guide'.corner_radius", "-0.001"),
    ("spring stiffness", lambda: pendulum().spring("ground", (0, 0), "arm", (0, 0), stiffness=-5.0, name="s"), "force 's'.stiffness", "-5.0"),
    ("spring table order", lambda: pendulum().spring("ground", (0, 0), "arm", (0, 0), force_table={"deflection": [0.0, 0.0], "force": [0.0, 1.0]}, name="s"), "force 's'.force_table.x[1]", "0.0"),
    ("spring same bodies", lambda: pendulum().spring("arm", (0, 0), "arm", (0.1, 0), stiffness=1.0, name="s"), "force 's'.body_b", ""),
    ("rotational damping", lambda: pendulum().rotational_spring("ground", "arm", 1.0, damping=-1.0, name="r"), "force 'r'.damping", "-1.0"),
    ("load table order", lambda: pendulum().force("arm", (0, 0), {"t": [0.0, 1.0, 0.5], "fx": [0, 1, 2]}, name="f"), "force 'f'.fx.x[2]", "0.5"),
    ("load period", lambda: pendulum().torque("arm", {"t": [0.0, 2.0], "torque": [0, 1], "period": 1.0}, name="q"), "force 'q'.magnitude.period", "1.0"),
    ("load frame", lambda: pendulum().force("arm", (0, 0), (1.0, 0.0), frame="local", name="f"), "force 'f'.frame", "local"),
    ("torque reaction", lambda: pendulum().torque("arm", 1.0, reaction="arm", name="q"), "force 'q'.reaction", ""),
    ("motor stall torque", lambda: pendulum().motor("arm", stall_torque=0.0, no_load_speed=10.0, name="mo"), "force 'mo'.stall_torque", "0.0"),
    ("motor speed", lambda: pendulum().motor("arm", stall_torque=1.0, no_load_speed=0.0, name="mo"), "force 'mo'.no_load_speed", "0"),
]


@pytest.mark.parametrize("make, field, value", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_the_core_names_element_field_and_value(make: Callable[[], cs.Mechanism], field: str, value: str) -> None:
    made: List[cs.Mechanism] = []
    with pytest.raises(cs.InputError) as info:
        made.append(make())  # the core checks each element's values as it is added ...
        made[0].compile()  # ... and what it refers to when the mechanism compiles, before anything runs
    err = info.value
    assert err.field == field, (err.field, str(err))
    assert str(err).startswith(f"invalid {field} = "), str(err)
    assert value in str(err), (value, str(err))
    if made:  # a reference: the run says the same
        with pytest.raises(cs.InputError) as again:
            made[0].simulate(1e-3, progress=False)
        assert again.value.field == field


@pytest.mark.parametrize(
    "options, field, value",
    [
        ({"rtol": 1.0}, "rtol", "1.0"),
        ({"atol": -1e-9}, "atol", "-1e-09"),
        ({"h_min": 0.0}, "h_min", "0.0"),
        ({"h_max": -1.0}, "h_max", "-1.0"),
        ({"max_steps": True}, "max_steps", "True"),
        ({"max_steps": 2.5}, "max_steps", "2.5"),
        ({"integrator": "rk4", "step": -1e-6}, "step", "-1e-06"),
        ({"integrator": "euler"}, "integrator", "'euler'"),
        ({"integrator": "dopri5"}, "integrator", "'dopri5'"),  # one name per integrator: rk45
        ({"max_seconds": -1.0}, "max_seconds", "-1.0"),
    ],
)
def test_run_settings_checked_by_the_core(options: Any, field: str, value: str) -> None:
    m = models.slider_crank("dry")
    settings = m.run_settings(1e-4, **options)  # written as given
    with pytest.raises(cs.InputError) as info:
        m.compile().simulate(settings)
    assert info.value.field == field and value in str(info.value), str(info.value)
    with pytest.raises(cs.InputError):
        m.simulate(1e-4, progress=False, **options)


def test_plausibility_waits_for_valid_sizes() -> None:
    """An invalid size is the core's InputError, not first a PlausibilityWarning computed from it
    (the test suite turns those into errors)."""
    for make in (lambda: pinned(Lubricated(viscosity=-0.4)), lambda: pinned(clearance=-1e-4), lambda: pendulum(inertia=-1e-3)):
        with pytest.raises(cs.InputError):
            make()


def test_numbers_are_still_numbers_at_once() -> None:
    """What Python must know to write the description stays checked where it is given: a
    number that is not one, a model object of the wrong type, a choice that selects fields."""
    with pytest.raises(cs.InputError, match="body 'arm'.mass"):
        pendulum(mass="heavy")
    with pytest.raises(cs.InputError, match="model"):
        pinned(model="dry")
    with pytest.raises(cs.InputError, match="stiffness_form"):
        Dry(stiffness_form="round")
    assert math.isfinite(Dry().restitution)


def test_run_defaults_are_the_cores() -> None:
    """The integrator's defaults are defined once, in the core (Settings::default): the Python
    signatures show the same numbers."""
    import inspect

    from clearsim import _core, schema
    from clearsim.mechanism import Mechanism

    core = _core.DEFAULTS["settings"]
    assert (schema.RTOL, schema.ATOL, schema.H_MIN, schema.MAX_STEPS) == (core["rtol"], core["atol"], core["h_min"], core["max_steps"])
    sig = inspect.signature(Mechanism.run_settings).parameters
    assert (sig["rtol"].default, sig["atol"].default, sig["h_min"].default, sig["max_steps"].default) == (1e-6, 1e-9, 1e-14, 50_000_000)


@pytest.mark.parametrize(("options", "field", "value"), [({"t_out": [0.0, 0.05, 0.2]}, "t_out[2]", 0.2), ({"t0": 0.05, "t_out": [0.0, 0.1]}, "t_out[0]", 0.0)])
def test_output_times_the_run_would_drop_are_refused(options, field, value):
    """``simulate(0.1, t_out=...)`` with a time past t_end or before t0: an InputError naming the
    field and value before anything runs. Before: the run dropped the times outside [t0, t_end]
    without a word (a Result of 1 output for t_out = [0, 0.2])."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    with pytest.raises(clearsim.InputError, match=re.escape(f"invalid {field} = {value}")) as info:
        m.simulate(0.1, progress=False, **options)
    assert info.value.field == field


def test_mistakes_are_named_at_the_call_that_makes_them() -> None:
    """A value out of range is an InputError at the call that gives it (issue 36, item 6), by the
    core's checks of that element alone (one validator: the compile's), naming the element, the
    field and the value. Before: each was accepted and failed only at ``simulate``."""
    m = cs.Mechanism()
    with pytest.raises(cs.InputError, match=re.escape("invalid body 'crank'.mass = -1.0: must be positive")) as info:
        m.add_body("crank", mass=-1, inertia=1e-3)
    assert info.value.field == "body 'crank'.mass" and m.body_names == []
    with pytest.raises(cs.InputError, match=re.escape("invalid viscosity = -0.1: must be positive")) as info:
        Lubricated(viscosity=-0.1)
    assert info.value.field == "viscosity"
    with pytest.raises(cs.InputError, match=re.escape("invalid clearance joint 'A'.clearance = -0.001: must be positive")):
        models.nine_bar("dry", clearance=-1e-3)
    with pytest.raises(cs.InputError, match=re.escape("invalid force 'k'.stiffness = -5.0: must not be negative")):
        pendulum().spring("ground", (0, 0), "arm", (0, 0), stiffness=-5.0, name="k")
    with pytest.raises(cs.InputError, match=re.escape("invalid clearance joint 'B'.clearance = -0.0002")):
        models.nine_bar("dry").with_values({"B.clearance": -2e-4})
    # Names still resolve when the mechanism compiles: elements may come in any order.
    later = cs.Mechanism().revolute("ground", (0, 0), "arm", (0, 0.1), name="pivot")
    later.add_body("arm", mass=1.0, inertia=1e-3, position=(0.0, -0.1))
    assert later.compile().dof == 1


def test_a_keyword_typo_names_the_method_called() -> None:
    """``simulate(dt_ot=...)`` is a TypeError naming ``simulate`` and the keyword it nearly is.
    Before: ``Running.run_settings() got an unexpected keyword argument 'dt_ot'``, an internal
    method the user never called."""
    m = models.slider_crank("dry")
    for method in (m.simulate, m.simulate_with_ideal):
        with pytest.raises(TypeError, match=re.escape(f"Mechanism.{method.__name__}() got an unexpected keyword argument 'dt_ot'; did you mean 'dt_out'?")):
            method(0.001, dt_ot=1e-4, progress=False)  # type: ignore[call-arg]
