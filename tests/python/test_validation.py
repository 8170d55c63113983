"""Input validation: every bad value raises :class:`clearsim.InputError` whose message names the
field and the value (issue "Hard cases and bad input").

Each row of ``CASES`` is one mistake; the test checks the exception class, that ``err.field``
names the field, and that the message contains both the field and the offending value.
"""

from __future__ import annotations

import math
import warnings
import textwrap
from pathlib import Path
from typing import Any, Callable, List, Tuple

import numpy as np
import pytest

import clearsim as cs
from clearsim import Dry, Lubricated, models

NAN, INF = float("nan"), float("inf")


def body(m: cs.Mechanism = None, name: str = "a", **kw: Any) -> cs.Mechanism:
    m = cs.Mechanism() if m is None else m
    args = dict(mass=1.0, inertia=0.01, position=(0.1, 0.0))
    args.update(kw)
    return m.add_body(name, **args)


def pendulum() -> cs.Mechanism:
    return body().revolute("ground", (0, 0), "a", (-0.1, 0), name="pivot")


def clearance(**kw: Any) -> cs.Mechanism:
    args = dict(journal_radius=0.01, clearance=1e-4)
    args.update(kw)
    return body().clearance_joint("pin", "ground", (0, 0), "a", (-0.1, 0), **args)


def sc_run(**kw: Any) -> Any:
    return models.slider_crank("dry").simulate(1e-4, **kw)


def dry_in_mech(**kw: Any) -> Any:
    """Through the Rust core's own check (bypasses the dataclass check), as a scene or an old
    description would arrive."""
    m = models.slider_crank("dry")
    m._clearance[0]["model"].update(kw)
    return m.compile()


Row = Tuple[str, Callable[[], Any], str, str]

CASES: List[Row] = [
    # id, thunk, field (substring of err.field), value as it must appear in the message
    ("mass zero", lambda: body(mass=0.0), "mass", "0.0"),
    ("mass negative", lambda: body(mass=-2.0), "mass", "-2.0"),
    ("mass nan", lambda: body(mass=NAN), "mass", "nan"),
    ("mass string", lambda: body(mass="heavy"), "mass", "'heavy'"),
    ("inertia zero", lambda: body(inertia=0.0), "inertia", "0.0"),
    ("inertia negative", lambda: body(inertia=-1e-3), "inertia", "-0.001"),
    ("inertia inf", lambda: body(inertia=INF), "inertia", "inf"),
    ("position nan", lambda: body(position=(NAN, 0.0)), "position[0]", "nan"),
    ("position not a pair", lambda: body(position=(1.0, 2.0, 3.0)), "position", "(1.0, 2.0, 3.0)"),
    ("angle inf", lambda: body(angle=-INF), "angle", "-inf"),
    ("velocity nan", lambda: body(velocity=(0.0, NAN, 0.0)), "velocity[1]", "nan"),
    ("clearance zero", lambda: clearance(clearance=0.0), "clearance", "0.0"),
    ("clearance negative (journal bigger than bearing)", lambda: clearance(clearance=-1e-4), "clearance", "-0.0001"),
    ("clearance nan", lambda: clearance(clearance=NAN), "clearance", "nan"),
    ("clearance below 1e-9 R_j", lambda: clearance(clearance=1e-20), "clearance", "1e-20"),
    ("core: clearance below 1e-9 R_j", lambda: (lambda m: (m._clearance[0].update(clearance=1e-300), m.compile()))(models.slider_crank("dry")), "clearance", "1e-300"),
    ("journal radius zero", lambda: clearance(journal_radius=0.0), "journal_radius", "0.0"),
    ("journal radius negative", lambda: clearance(journal_radius=-0.01), "journal_radius", "-0.01"),
    ("initial eccentricity inf", lambda: clearance(initial_eccentricity=(INF, 0.0)), "initial_eccentricity[0]", "inf"),
    ("initial eccentricity in units of c", lambda: clearance(initial_eccentricity=(0.5, 0.0)), "initial_eccentricity", "[0.5, 0.0]"),
    ("model of wrong type", lambda: clearance(model="dry"), "model", "'dry'"),
    ("viscosity zero", lambda: Lubricated(viscosity=0.0), "viscosity", "0.0"),
    ("viscosity negative", lambda: Lubricated(viscosity=-0.4), "viscosity", "-0.4"),
    ("viscosity nan", lambda: Lubricated(viscosity=NAN), "viscosity", "nan"),
    ("length zero", lambda: Lubricated(length=0.0), "length", "0.0"),
    ("length negative", lambda: Lubricated(length=-0.05), "length", "-0.05"),
    ("eps0 above 1", lambda: Lubricated(eps0=1.5), "eps0", "1.5"),
    ("eps0 negative", lambda: Lubricated(eps0=-1e-6), "eps0", "-1e-06"),
    ("m zero", lambda: Lubricated(m=0.0), "m", "0.0"),
    ("m one", lambda: Lubricated(m=1.0), "m", "1.0"),
    ("m nan", lambda: Lubricated(m=NAN), "m", "nan"),
    ("e0 zero", lambda: Lubricated(e0=0.0), "e0", "0.0"),
    ("eps_max one", lambda: Lubricated(eps_max=1.0), "eps_max", "1.0"),
    ("film unknown", lambda: Lubricated(film="medium"), "film", "medium"),
    ("lubricated dry law of wrong type", lambda: Lubricated(dry=0.9), "dry", "0.9"),
    ("restitution zero", lambda: Dry(restitution=0.0), "restitution", "0.0"),
    ("restitution above 1", lambda: Dry(restitution=1.2), "restitution", "1.2"),
    ("restitution negative", lambda: Dry(restitution=-0.5), "restitution", "-0.5"),
    ("friction negative", lambda: Dry(friction=-0.1), "friction", "-0.1"),
    ("friction inf", lambda: Dry(friction=INF), "friction", "inf"),
    ("v1 below v0", lambda: Dry(v0=1e-2, v1=1e-3), "v1", "0.001"),
    ("v1 equal v0", lambda: Dry(v0=1e-3, v1=1e-3), "v1", "0.001"),
    ("v0 negative", lambda: Dry(v0=-1e-4), "v0", "-0.0001"),
    ("youngs modulus zero", lambda: Dry(youngs_modulus=0.0), "youngs_modulus", "0.0"),  # one name, Python's, in errors too
    ("poisson 0.5", lambda: Dry(poisson_ratio=0.5), "poisson_ratio", "0.5"),
    ("exponent zero", lambda: Dry(exponent=0.0), "exponent", "0.0"),
    ("stiffness negative", lambda: Dry(stiffness=-1e9), "stiffness", "-1000000000.0"),
    ("impact speed floor zero", lambda: Dry(impact_speed_floor=0.0), "impact_speed_floor", "0.0"),
    ("normal law unknown", lambda: Dry(normal_law="kelvin"), "normal_law", "kelvin"),
    # The Rust core checks the same ranges (scene files and raw descriptions reach it directly).
    ("core: restitution above 1", lambda: dry_in_mech(restitution=1.5), "restitution", "1.5"),
    ("core: v1 below v0", lambda: dry_in_mech(v0=0.1, v1=0.01), "v1", "0.01"),
    ("core: friction nan", lambda: dry_in_mech(friction=NAN), "friction", "nan"),
    ("core: clearance zero", lambda: (lambda m: (m._clearance[0].update(clearance=0.0), m.compile()))(models.slider_crank("dry")), "clearance", "0"),
    ("core: eps0 out of range", lambda: (lambda m: (m._clearance[0]["model"].update(eps0=2.0), m.compile()))(models.nine_bar("lubricated")), "eps0", "2"),
    ("core: m out of range", lambda: (lambda m: (m._clearance[0]["model"].update(m=-0.5), m.compile()))(models.nine_bar("lubricated")), ".m", "-0.5"),
    ("core: viscosity zero", lambda: (lambda m: (m._clearance[0]["model"].update(viscosity=0.0), m.compile()))(models.nine_bar("lubricated")), "viscosity", "0"),
    # Names.
    # References to other elements are resolved when the mechanism compiles (any definition order).
    ("unknown body in joint", lambda: body().revolute("ground", (0, 0), "b", (0, 0)).compile(), "joint 'revolute1'.body_b", "'b'"),
    ("unknown bearing body", lambda: body().clearance_joint("pin", "hub", (0, 0), "a", (0, 0), journal_radius=0.01, clearance=1e-4).compile(), "clearance joint 'pin'.bearing_body", "'hub'"),
    ("unknown driven body", lambda: body().driver("crank", omega=1.0).compile(), "driver 'driver1'.body", "'crank'"),
    ("duplicate body", lambda: body(body(), "a"), "name", "'a'"),
    ("duplicate joint", lambda: pendulum().revolute("ground", (0, 0), "a", (0, 0), name="pivot"), "name", "'pivot'"),
    ("joint named like a driver", lambda: pendulum().driver("a", omega=1.0, name="d").revolute("ground", (1, 0), "a", (0, 0), name="d"), "name", "'d'"),
    ("body named ground", lambda: body(name="ground"), "name", "'ground'"),
    ("empty body name", lambda: body(name=""), "name", "''"),
    ("result: unknown body", lambda: models.slider_crank().simulate(1e-4).position("piston"), "body", "'piston'"),
    ("result: unknown joint", lambda: models.slider_crank("dry").simulate(1e-4).eccentricity("A"), "joint", "'A'"),
    # Non-finite numbers elsewhere.
    ("gravity inf", lambda: cs.Mechanism(gravity=(0.0, -INF)), "gravity[1]", "-inf"),
    ("baumgarte nan", lambda: cs.Mechanism(baumgarte=(NAN, 50.0)), "baumgarte[0]", "nan"),
    ("baumgarte negative", lambda: body(cs.Mechanism(baumgarte=(-1.0, 50.0))).compile(), "baumgarte.alpha", "-1"),
    ("joint point nan", lambda: body().revolute("ground", (0, NAN), "a", (0, 0)), "point_a[1]", "nan"),
    ("axis zero", lambda: body().prismatic("ground", (0, 0), "a", (0, 0), axis=(0.0, 0.0)), "axis", "[0.0, 0.0]"),
    ("driver omega nan", lambda: pendulum().driver("a", omega=NAN), "omega", "nan"),
    ("driver angle0 inf", lambda: pendulum().driver("a", omega=1.0, angle0=INF), "angle0", "inf"),
    ("driver polynomial inf", lambda: pendulum().driver("a", polynomial=[0.0, INF]), "polynomial[1]", "inf"),
    ("driver times nan", lambda: pendulum().driver("a", times=[0.0, NAN], angles=[0.0, 1.0]), "times[1]", "nan"),
    ("driver times not increasing", lambda: pendulum().driver("a", times=[0.0, 1.0, 0.5], angles=[0, 1, 2]).compile(), "times[2]", "0.5"),
    ("rpm nan", lambda: models.slider_crank(rpm=NAN), "omega", "nan"),
    # Run settings.
    ("t_end zero", lambda: models.slider_crank().simulate(0.0), "t_end", "0.0"),
    ("t_end negative", lambda: models.slider_crank().simulate(-1.0), "t_end", "-1.0"),
    ("t_end nan", lambda: models.slider_crank().simulate(NAN), "t_end", "nan"),
    ("t_end inf", lambda: models.slider_crank().simulate(INF), "t_end", "inf"),
    ("t_end before t0", lambda: models.slider_crank().simulate(0.5, t0=1.0), "t_end", "0.5"),
    ("t0 nan", lambda: models.slider_crank().simulate(1.0, t0=NAN), "t0", "nan"),
    ("rtol zero", lambda: sc_run(rtol=0.0), "rtol", "0.0"),
    ("rtol one", lambda: sc_run(rtol=1.0), "rtol", "1.0"),
    ("rtol nan", lambda: sc_run(rtol=NAN), "rtol", "nan"),
    ("atol negative", lambda: sc_run(atol=-1e-9), "atol", "-1e-09"),
    ("atol inf", lambda: sc_run(atol=INF), "atol", "inf"),
    ("h_min zero", lambda: sc_run(h_min=0.0), "h_min", "0.0"),
    ("h_max negative", lambda: sc_run(h_max=-1.0), "h_max", "-1.0"),
    ("max_steps zero", lambda: sc_run(max_steps=0), "max_steps", "0"),
    ("max_steps fractional", lambda: sc_run(max_steps=2.5), "max_steps", "2.5"),
    ("dt_out zero", lambda: sc_run(dt_out=0.0), "dt_out", "0.0"),
    ("t_out not increasing", lambda: sc_run(t_out=[0.0, 1e-5, 1e-5]), "t_out", "t_out"),
    ("t_out nan", lambda: sc_run(t_out=[0.0, NAN]), "t_out", "t_out"),
    ("rk4 without step", lambda: sc_run(integrator="rk4"), "step", "None"),
    ("rk4 step negative", lambda: sc_run(integrator="rk4", step=-1e-6), "step", "-1e-06"),
    ("integrator unknown", lambda: sc_run(integrator="euler"), "integrator", "'euler'"),
    ("outputs unknown", lambda: sc_run(outputs=["states", "pressure"]), "outputs", "pressure"),
    ("model kind unknown", lambda: models.slider_crank("greasy"), "joints", "'greasy'"),
]


def through_core(made: Any) -> None:
    """Compile what a mistake made, if it did not raise yet: the values' ranges are checked once,
    by the Rust core when the mechanism compiles (issue 29, "validation once"); a clearance
    model is compiled in a pendulum."""
    if isinstance(made, cs.Mechanism):
        made.compile()
    elif isinstance(made, (Dry, Lubricated)):
        clearance(model=made).compile()


@pytest.mark.parametrize("thunk, field, value", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_error_names_field_and_value(thunk, field, value):
    with pytest.raises(cs.InputError) as info:
        through_core(thunk())
    err = info.value
    assert isinstance(err, ValueError) and isinstance(err, cs.ClearsimError)
    assert field in err.field, f"field {err.field!r} does not name {field!r}"
    msg = str(err)
    assert err.field in msg or field in msg, msg
    assert value in msg, f"{value!r} not in message {msg!r}"
    assert msg.startswith("invalid ") or ": invalid " in msg or "no such" in msg, msg


def test_clearance_message_explains_journal_versus_bearing_radius():
    """"Journal radius not below the bearing radius": our API takes R_j and c (R_b = R_j + c),
    so the mistake is c ≤ 0 and the message says what that means."""
    for c in (0.0, -1e-4):
        with pytest.raises(cs.InputError) as info:
            clearance(clearance=c).compile()
        msg = str(info.value)
        assert "journal radius" in msg and "bearing radius" in msg and "R_b = R_j + c" in msg
    m = models.slider_crank("dry")
    m._clearance[0]["clearance"] = -1e-4  # the core's own check says the same
    with pytest.raises(cs.InputError, match="journal radius R_j = 0.0095 must be below the bearing radius"):
        m.compile()


def test_rust_errors_map_to_input_error_with_field():
    m = models.slider_crank("dry")
    m._clearance[0]["model"]["restitution"] = 2.0
    with pytest.raises(cs.InputError) as info:
        m.simulate(1e-3)
    assert info.value.field == "clearance joint 'rod-slider'.restitution"
    assert "must lie in (0, 1]" in str(info.value)


def test_valid_edge_values_are_accepted():
    Dry(restitution=1.0, friction=0.0, v0=0.0, v1=1e-6, poisson_ratio=-0.5)
    Lubricated(eps0=0.0, m=0.999, eps_max=0.999999, e0=1e-9)
    clearance(initial_eccentricity=(2e-4, 0.0)).compile()  # exactly 2 c: allowed
    r = pendulum().simulate(1e-3, rtol=0.999, max_steps=10**6)
    assert r.completed


def test_idealized_after_a_run():
    """Mechanism.idealized() (a deep copy) works once the mechanism holds a compiled model."""
    m = models.slider_crank("dry")
    m.simulate(1e-4)
    ideal = m.idealized()
    assert ideal.clearance_joint_names == [] and m.clearance_joint_names == ["rod-slider"]
    assert ideal.simulate(1e-4).completed


# ---------------------------------------------------------------------------- scene files
from clearsim import scene  # noqa: E402  (a real import: an import error must fail, not skip)

SCENE = textwrap.dedent(
    """\
    [mechanism]
    gravity = [0.0, 0.0]

    [[body]]
    name = "crank"
    mass = 0.30
    inertia = 1.0e-4
    ends = [[0.0, 0.0], [0.05, 0.0]]

    [[body]]
    name = "rod"
    mass = 0.21
    inertia = 2.5e-4
    ends = [[0.05, 0.0], [0.17, 0.0]]

    [[body]]
    name = "slider"
    mass = 0.14
    inertia = 1.0e-4
    position = [0.17, 0.0]

    [[joint]]
    type = "revolute"
    bodies = ["ground", "crank"]
    points = [[0.0, 0.0], [-0.025, 0.0]]

    [[joint]]
    type = "revolute"
    bodies = ["crank", "rod"]
    points = [[0.025, 0.0], [-0.06, 0.0]]

    [[joint]]
    type = "prismatic"
    bodies = ["ground", "slider"]
    points = [[0.0, 0.0], [0.0, 0.0]]
    axis = [1.0, 0.0]

    [[driver]]
    body = "crank"
    rpm = 5000.0

    [[clearance_joint]]
    name = "rod-slider"
    bearing_body = "slider"
    bearing_point = [0.0, 0.0]
    journal_body = "rod"
    journal_point = [0.06, 0.0]
    journal_radius = 9.5e-3
    clearance = 0.5e-3
    model = "dry"

    [clearance_joint.dry]
    restitution = 0.9
    friction = 0.1

    [simulation]
    t_end = 0.001
    """
)

# (id, old text, new text, field substring, text the message must contain)
SCENE_MISTAKES = [
    ("mass zero", "mass = 0.30", "mass = 0.0", "mass", "0.0"),
    ("mass string", "mass = 0.30", 'mass = "heavy"', "mass", "heavy"),
    ("mass nan", "mass = 0.30", "mass = nan", "mass", "nan"),
    ("inertia negative", "inertia = 2.5e-4", "inertia = -2.5e-4", "inertia", "-0.00025"),
    ("clearance zero", "clearance = 0.5e-3", "clearance = 0.0", "clearance", "0"),
    ("journal radius inf", "journal_radius = 9.5e-3", "journal_radius = inf", "journal_radius", "inf"),
    ("restitution above 1", "restitution = 0.9", "restitution = 1.5", "restitution", "1.5"),
    ("unknown key", "friction = 0.1", "friction = 0.1\nfriktion = 0.2", "friktion", "friktion"),
    ("unknown body", 'journal_body = "rod"', 'journal_body = "rodd"', "journal_body", "rodd"),
    ("duplicate body", 'name = "slider"', 'name = "rod"', "name", "rod"),
    ("unknown joint type", 'type = "prismatic"', 'type = "helical"', "type", "helical"),
    ("missing mass", "mass = 0.14\n", "", "mass", "mass"),
    ("t_end zero", "t_end = 0.001", "t_end = 0.0", "t_end", "0"),
    ("rtol out of range", "t_end = 0.001", "t_end = 0.001\nrtol = 2.0", "rtol", "2"),
    ("point not a pair", "bearing_point = [0.0, 0.0]", "bearing_point = [0.0]", "bearing_point", "bearing_point"),
]


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "scene.toml"
    p.write_text(text)
    return p


def test_scene_baseline_loads(tmp_path):
    m = scene.load_scene(_write(tmp_path, SCENE))
    assert m.body_names == ["crank", "rod", "slider"]
    assert m.simulate(1e-4).completed


@pytest.mark.parametrize("old, new, field, text", [s[1:] for s in SCENE_MISTAKES], ids=[s[0] for s in SCENE_MISTAKES])
def test_scene_mistake_names_field_file_and_line(tmp_path, old, new, field, text):
    assert old in SCENE
    path = _write(tmp_path, SCENE.replace(old, new, 1))
    with pytest.raises(cs.InputError) as info:
        scene.load_scene(path)
    err = info.value
    msg = str(err)
    assert field in err.field or field in msg, (err.field, msg)
    assert text in msg, msg
    assert str(path) in msg and getattr(err, "file", None) == str(path)


def test_scene_invalid_toml_and_missing_file(tmp_path):
    path = _write(tmp_path, SCENE.replace("mass = 0.30", "mass = = 0.30", 1))
    with pytest.raises(cs.InputError, match="invalid TOML") as info:
        scene.load_scene(path)
    assert info.value.line is not None
    with pytest.raises(cs.InputError) as info:
        scene.load_scene(tmp_path / "nope.toml")
    assert "nope.toml" in str(info.value)


def test_two_drivers_on_one_body_are_named():
    """A second driver on a driven body used to end as 'residual = NaN' in the assembly."""
    m = cs.models.slider_crank("ideal")
    m.driver("crank", omega=100.0, name="second")
    with pytest.raises(cs.InputError, match="already driven by driver") as info:
        m.simulate(1e-3, progress=False)
    assert info.value.field == "driver 'second'.body" and info.value.value == "crank"


def test_lubricated_clearance_must_be_small_against_the_radius():
    """0.2 m of clearance on a 5 mm pin (a unit slip) is refused for a film, where it is given;
    warned for dry."""
    with pytest.raises(cs.InputError, match=r"c/R_j = 40.0 > 0.25.*thin-film") as info:
        cs.models.slider_crank("lubricated", clearance=0.2, journal_radius=5e-3)
    assert info.value.field == "clearance joint 'rod-slider'.clearance" and float(info.value.value) == 0.2
    with pytest.warns(UserWarning, match="is it given in metres"):
        cs.models.slider_crank("dry", clearance=0.2, journal_radius=5e-3)


def _two_links(duplicate: bool, reach: float = 0.15) -> cs.Mechanism:
    m = cs.Mechanism(gravity=(0.0, 0.0))
    m.add_body("a", mass=1.0, inertia=0.01, position=(0.05, 0.0))
    m.add_body("b", mass=1.0, inertia=0.01, position=(0.15, 0.0))
    m.revolute("ground", (0.0, 0.0), "a", (-0.05, 0.0), name="pivot")
    m.revolute("a", (0.05, 0.0), "b", (-0.05, 0.0), name="elbow")
    if duplicate:
        m.revolute("a", (0.05, 0.0), "b", (-0.05, 0.0), name="elbow_again")
    return m


def test_a_redundant_joint_is_named():
    """Two identical pins between the same bodies: the assembly names one of them."""
    with pytest.raises(cs.AssemblyError, match="revolute joint 'elbow(_again)?'.*redundant"):
        _two_links(duplicate=True).simulate(0.01, progress=False)


def test_a_loop_that_cannot_close_names_a_joint():
    """A four-bar whose ground pivots are 1 m apart with 0.1 m links cannot assemble: the
    error names a joint of the loop instead of a bare residual."""
    m = cs.Mechanism(gravity=(0.0, 0.0))
    m.add_body("crank", mass=1.0, inertia=0.01, position=(0.05, 0.0))
    m.add_body("rod", mass=1.0, inertia=0.01, position=(0.15, 0.0))
    m.add_body("rocker", mass=1.0, inertia=0.01, position=(1.0, 0.05))
    m.revolute("ground", (0.0, 0.0), "crank", (-0.05, 0.0), name="O2")
    m.revolute("crank", (0.05, 0.0), "rod", (-0.05, 0.0), name="A")
    m.revolute("rod", (0.05, 0.0), "rocker", (0.0, -0.05), name="B")
    m.revolute("ground", (1.0, 0.0), "rocker", (0.0, -0.05), name="O4")
    m.driver("crank", omega=1.0)
    with pytest.raises(cs.AssemblyError, match=r"revolute joint '(O2|A|B|O4)'"):
        m.simulate(0.01, progress=False)


def test_a_joint_point_in_the_wrong_frame_is_an_assembly_error_before_the_run():
    """The rocker's pin given in global coordinates (1.0, 0.1) instead of its body frame: the
    assembly would have to move the rocker far; before anything runs, an AssemblyError names
    the body, how far it would move and the joint whose points lie apart at the poses given.
    With ``assembly_tolerance = None`` the run goes ahead from the assembled pose."""
    m = cs.Mechanism(gravity=(0.0, 0.0))
    m.add_body("crank", mass=1.0, inertia=0.01, position=(0.05, 0.0))
    m.add_body("rod", mass=1.0, inertia=0.01, position=(0.25, 0.05))
    m.add_body("rocker", mass=1.0, inertia=0.01, position=(0.4, 0.05), angle=math.pi / 2)
    m.revolute("ground", (0.0, 0.0), "crank", (-0.05, 0.0), name="O2")
    m.revolute("crank", (0.05, 0.0), "rod", (-0.15, -0.05), name="A")
    m.revolute("rod", (0.15, 0.05), "rocker", (0.05, 0.0), name="B")
    m.revolute("ground", (0.4, 0.0), "rocker", (-0.05, 0.0), name="O4")
    m.driver("crank", omega=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.simulate(0.01, progress=False)  # the right frames: no error, no warning
        assert m.check_assembly(0.0).shape == (9,)
    bad = cs.Mechanism(gravity=(0.0, 0.0))
    for b in m._bodies:
        bad.add_body(b["name"], mass=1.0, inertia=0.01, position=tuple(b["position"]), angle=b.get("angle", 0.0))
    bad.revolute("ground", (0.0, 0.0), "crank", (-0.05, 0.0), name="O2")
    bad.revolute("crank", (0.05, 0.0), "rod", (-0.15, -0.05), name="A")
    bad.revolute("rod", (0.15, 0.05), "rocker", (0.4, 0.1), name="B")  # global, not body frame
    bad.revolute("ground", (0.4, 0.0), "rocker", (-0.05, 0.0), name="O4")
    bad.driver("crank", omega=1.0)
    with pytest.raises(cs.AssemblyError) as e:
        bad.simulate(0.01, progress=False)
    err = e.value
    assert err.body in ("rod", "rocker") and err.joint == "B" and err.t == 0.0 and err.result is None
    assert err.field == "joint 'B'" and err.value == pytest.approx(0.364, abs=1e-3)  # [m] apart at the poses given
    assert err.moved > 0.2 * 0.45
    msg = str(err)
    assert f"moves body '{err.body}' by" in msg and "joint 'B' has its two points" in msg and "body frame, not global" in msg
    with pytest.raises(cs.AssemblyError, match="joint 'B'"):
        bad.simulate_with_ideal(0.01)
    from clearsim import reliability as rel

    study = rel.Study(lambda load: bad, inputs={"load": rel.Normal(1.0, 0.1)}, output=rel.Output(body="rocker", component="theta"),
                      limit=1.0, omega=1.0, cycles=0.01, progress=False)  # fmt: skip
    with pytest.raises(cs.AssemblyError, match="joint 'B'"):
        study.monte_carlo(4)
    study._assembly_checked = False
    with pytest.raises(cs.AssemblyError, match="joint 'B'"):
        study.fosm()
    bad.assembly_tolerance = None
    try:
        bad.simulate(0.01, progress=False)
    except cs.AssemblyError as other:  # pragma: no cover - the check must not fire
        assert "moves body" not in str(other)
    except cs.ClearsimError:
        pass


def test_a_link_can_be_given_by_its_ends():
    """``add_body(ends=...)`` (the Python side of the scenes' ``ends``): centroid at mid-length,
    angle along the line; with position or angle too, or with coinciding ends, an InputError."""
    import math

    m = cs.Mechanism()
    m.add_body("rod", mass=1.0, inertia=1e-3, ends=((0.0, 0.0), (0.3, 0.4)))
    b = m.description()["bodies"][0]
    assert b["position"] == pytest.approx([0.15, 0.2]) and b["angle"] == pytest.approx(math.atan2(0.4, 0.3))
    with pytest.raises(cs.InputError) as e:
        m.add_body("bad", mass=1.0, inertia=1e-3, ends=((0, 0), (1, 0)), angle=0.2)
    assert e.value.field == "body 'bad'.angle" and "either ends or position/angle" in str(e.value)
    with pytest.raises(cs.InputError) as e:
        m.add_body("bad", mass=1.0, inertia=1e-3, ends=((0.1, 0.1), (0.1, 0.1)))
    assert e.value.field == "body 'bad'.ends" and "coincide" in str(e.value)
    with pytest.raises(cs.InputError) as e:
        m.add_body("bad", mass=1.0, inertia=1e-3, ends=((0.1, 0.1),))
    assert e.value.field == "body 'bad'.ends"


def test_run_options_name_every_run_setting():
    """The typed keyword arguments of ``simulate`` (``RunOptions``) are exactly the parameters
    of ``run_settings``: the two stay in step."""
    import inspect

    from clearsim.running import RunOptions

    params = [p for p in inspect.signature(cs.Mechanism.run_settings).parameters.values() if p.kind is p.KEYWORD_ONLY]
    assert sorted(p.name for p in params) == sorted(RunOptions.__annotations__)


def test_run_settings_enter_the_core_through_serde_and_bad_ones_are_named():
    """The settings dict crosses the binding the way a description does (serde): an unknown
    key, a wrong type or an inconsistent monitor is an InputError naming its path, and values
    JSON cannot carry (∞, numpy arrays and scalars) arrive intact."""
    m = models.slider_crank(joints="dry")
    compiled = m.compile()
    good = m.run_settings(0.002, dt_out=1e-3)
    spec = {"coordinate": 4, "quantity": "displacement", "t_start": 0.0, "bin_width": 1e-3, "bins": np.int64(2),
            "limit": math.inf, "samples_per_step": 8}
    raw = compiled.simulate(dict(good, monitors=[spec], max_seconds=math.inf))
    assert raw["t"].shape == (3,)
    assert raw["monitors"][0]["first_passage"] != raw["monitors"][0]["first_passage"]  # never: NaN

    def error(settings: Any) -> cs.InputError:
        with pytest.raises(cs.InputError) as info:
            compiled.simulate(settings)
        return info.value

    e = error(dict(good, rtoll=1e-3))
    assert e.field == "rtoll" and "unknown field `rtoll`" in str(e)
    e = error(dict(good, integrator="euler"))
    assert e.field == "integrator" and "unknown variant `euler`" in str(e)
    e = error(dict(good, outputs={"states": "yes"}))
    assert e.field == "outputs.states" and "expected a boolean" in str(e)
    e = error(dict(good, monitors=[dict(spec, quantity="speed")]))
    assert e.field == "monitors[0].quantity"
    e = error(dict(good, monitors=[dict(spec, reference="nominall")]))  # a reference is named, not shipped
    assert e.field == "monitors[0].reference" and "nominal" in str(e)
    e = error(dict(good, monitors=[dict(spec, reference={"t": np.array([0.0, 1.0])})]))
    assert e.field == "monitors[0].reference" and "expected a string" in str(e)
    e = error(dict(good, monitors=[dict(spec, bins=0)]))
    assert e.field == "monitors[0].bins"
