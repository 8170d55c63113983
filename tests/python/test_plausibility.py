"""Unit-plausibility warnings (issue 28 item 6): valid values that look like a unit slip (mm as m,
cP as Pa·s) or lie outside the range the film laws are meant for warn, once, naming the element,
the field, the value and the unit clearsim expected. No shipped model or scene warns (the
test suite turns a PlausibilityWarning into an error: tests/python/conftest.py)."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

import clearsim
from clearsim import Dry, Lubricated, PlausibilityWarning, models

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _caught(fn):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn()
    return out, [str(w.message) for w in caught if issubclass(w.category, PlausibilityWarning)]


def test_a_journal_radius_in_millimetres():
    m, found = _caught(lambda: models.slider_crank("dry", journal_radius=10))
    assert found == []  # the span is known only when the mechanism compiles
    _, found = _caught(lambda: m.compile())
    assert found == ["clearance joint 'rod-slider'.journal_radius = 10 m is larger than half the mechanism's span 0.17 m: did you give mm? clearsim takes metres"]
    _, again = _caught(lambda: (m.simulate(1e-4, progress=False), m.copy().with_values({"rod-slider.clearance": 4e-4}).compile()))
    assert again == []  # once per mechanism (and its copies), not once per run


def test_a_bearing_length_in_millimetres():
    m = models.slider_crank("lubricated", lubricated=Lubricated(viscosity=0.4, length=20))
    _, found = _caught(m.compile)
    assert len(found) == 1 and found[0].startswith("clearance joint 'rod-slider'.length = 20 m (the bearing's length) is more than 2 × the mechanism's span 0.17 m")
    assert found[0].endswith("did you give mm? clearsim takes metres")


@pytest.mark.parametrize(
    "viscosity, says",
    [(30.0, "did you give centipoise (mPa·s)? clearsim takes Pa·s (1 cP = 0.001 Pa·s: 30 cP = 0.03 Pa·s)"),
     (2e-5, "did you give a kinematic viscosity (m²/s) or Pa·s / 1000? clearsim takes the dynamic viscosity in Pa·s")],
)  # fmt: skip
def test_a_viscosity_outside_lubricating_oils(viscosity, says):
    _, found = _caught(lambda: models.slider_crank("lubricated", lubricated=Lubricated(viscosity=viscosity, length=0.04)))
    assert len(found) == 1 and found[0].startswith(f"clearance joint 'rod-slider'.viscosity = {viscosity:g} Pa·s") and says in found[0]


@pytest.mark.parametrize(
    "clearance, says",
    [(1.5e-3, "the film laws are thin-film theory, meant for R_j/c ≥ 10 (machine bearings R_j/c ≈ 1000): did you give millimetres, or the diametral clearance? clearsim takes the radial clearance in metres"),
     (0.5e-6, "thinner than machined surfaces are rough, where the smooth-film laws stop holding (meant for R_j/c ≤ 10000): is it given in metres? clearsim takes metres")],
)  # fmt: skip
def test_a_film_clearance_outside_the_film_laws(clearance, says):
    lub = Lubricated(viscosity=0.4, length=0.04, film="finite")
    _, found = _caught(lambda: models.slider_crank("lubricated", clearance=clearance, lubricated=lub))
    assert len(found) == 1 and found[0].startswith(f"clearance joint 'rod-slider'.clearance = {clearance:g} m") and says in found[0]


def test_a_dry_clearance_of_a_quarter_of_the_radius():
    _, found = _caught(lambda: models.slider_crank("dry", clearance=3e-3))
    assert found == ["clearance joint 'rod-slider'.clearance = 0.003 m is 0.316 × the journal radius 0.0095 m (machine bearings have c/R_j ≈ 0.001): is it given in metres? clearsim takes the radial clearance in metres"]


def test_plausible_values_pass_silently():
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        for c, lub in ((5e-6, Lubricated(viscosity=0.4, length=0.04)), (6e-4, Lubricated(viscosity=1e-3, length=0.02, film="short"))):
            models.slider_crank("lubricated", clearance=c, lubricated=lub).compile()
        models.nine_bar("dry", journal_radius=0.05).compile()


def test_no_shipped_model_or_scene_warns():
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        for kind in models.JOINT_KINDS:
            models.slider_crank(kind).compile()
            models.nine_bar(kind).compile()
        for path in sorted(SCENES.glob("*.toml")):
            clearsim.scene.load_scene_file(path).mechanism.compile()


def test_a_scene_warning_names_the_file_and_line(tmp_path):
    text = (SCENES / "compressor.toml").read_text().replace("viscosity = 0.02 ", "viscosity = 20.0 ")
    path = tmp_path / "c.toml"
    path.write_text(text)
    line = 1 + next(k for k, ln in enumerate(text.splitlines()) if ln.startswith("viscosity = 20.0"))
    _, found = _caught(lambda: clearsim.scene.load_scene_file(path))
    assert len(found) == 1 and found[0].startswith(f"{path}:{line}: clearance joint 'crank-pin'.viscosity = 20 Pa·s")


def _crank_rod_slider(scale: float, inertia_scale: float = 1.0) -> clearsim.Mechanism:
    """An offset slider-crank (crank 0.1 m, rod 0.3 m) with every coordinate × ``scale`` and the
    inertias × ``inertia_scale``."""
    s = scale
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("crank", mass=2.0, inertia=1.67e-3 * inertia_scale, ends=((0.0, 0.3 * s), (0.1 * s, 0.3 * s)))
    m.add_body("rod", mass=1.0, inertia=7.5e-3 * inertia_scale, ends=((0.1 * s, 0.3 * s), (0.4 * s, 0.3 * s)))
    m.add_body("slider", mass=1.0, inertia=1e-3 * inertia_scale, position=(0.4 * s, 0.3 * s))
    m.revolute("ground", (0.0, 0.3 * s), "crank", (-0.05 * s, 0.0))
    m.revolute("crank", (0.05 * s, 0.0), "rod", (-0.15 * s, 0.0))
    m.revolute("rod", (0.15 * s, 0.0), "slider", (0.0, 0.0))
    m.prismatic("ground", (0.0, 0.3 * s), "slider", (0.0, 0.0))
    m.driver("crank", omega=9.42)
    return m


def test_coordinates_in_mm_with_inertias_in_kg_m2_are_named():
    """A mechanism drawn in mm (crank 100, rod 300) with its inertias in kg m² ran without a word
    as a 400 m machine. Now each link whose inertia is ~1e-6 of a bar's of its mass between its
    joint points is a PlausibilityWarning naming the body, the inertia, the distance and the
    unit; the same mechanism in metres (or with a flywheel's large inertia) is silent."""
    with pytest.warns(clearsim.PlausibilityWarning) as caught:
        _crank_rod_slider(1000.0).compile()
    text = [str(w.message) for w in caught]
    assert any(t.startswith("body 'rod'.inertia = 0.0075 kg m² is 1e-06 × a uniform bar's") and "300 m apart" in t and "in mm?" in t for t in text)
    assert any(t.startswith("body 'crank'.inertia") for t in text) and not any("'slider'" in t for t in text)
    with warnings.catch_warnings():
        warnings.simplefilter("error", clearsim.PlausibilityWarning)
        _crank_rod_slider(1.0).compile()
        _crank_rod_slider(1.0, inertia_scale=1e3).compile()
        _crank_rod_slider(1000.0, inertia_scale=1e6).compile()  # all in mm and kg mm²: nothing tells


def _pendulum(scale: float, load_point: tuple = (0.0, 0.0)) -> clearsim.Mechanism:
    """A 0.3 m pendulum of 2 kg (a bar: J = m L²/12 = 0.015 kg m²) pivoted at its top end, with
    every coordinate × ``scale`` and a 10 N load at ``load_point`` (body frame)."""
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("arm", mass=2.0, inertia=0.015, position=(0.0, -0.15 * scale), angle=0.0)
    m.revolute("ground", (0.0, 0.0), "arm", (0.0, 0.15 * scale), name="pivot")
    m.force("arm", load_point, (10.0, 0.0), name="push")
    return m


def test_a_body_drawn_in_millimetres_is_named_at_compile():
    """A pendulum drawn in mm (its pivot 150 from its centroid) with its inertia in kg m² ran
    silently as a 300 m pendulum: one joint, so no two joint points to measure it by. Now its
    centroid counts as a point of the body: a PlausibilityWarning names the body and the unit
    when the mechanism compiles (not only when it runs); in metres it is silent."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        _pendulum(1.0).compile()
    m, found = _caught(lambda: _pendulum(1000.0))
    assert found == []
    _, found = _caught(m.compile)
    assert len(found) == 1 and found[0].startswith("body 'arm'.inertia = 0.015 kg m² is 4e-06 × a uniform bar's of its mass 2 kg between its joint points 150 m apart")
    assert "in mm?" in found[0]


def test_a_load_point_far_outside_its_body_is_named():
    """A load given in global coordinates (the pendulum's tip, 0.3 m below the pivot, written as
    the global point (0, -0.3) while the body frame's tip is (0, -0.15)), or in mm, lies far
    outside the body: a PlausibilityWarning names the force, its point and the unit. A load at
    the body's tip, or a little beyond its joints, is silent."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        _pendulum(1.0, (0.0, -0.15)).compile()
        _pendulum(1.0, (0.1, -0.3)).compile()  # a tool point beyond the body: 2.1 × its joint's reach
    _, found = _caught(_pendulum(1.0, (0.0, -150.0)).compile)
    assert found == ["force 'push'.point = (0, -150) m lies 150 m from the centroid of body 'arm', 1e+03 × as far as its joints (0.15 m): "
                     "is it given in global coordinates or in mm? clearsim takes the point in metres in the body's frame"]  # fmt: skip
    _, found = _caught(_pendulum(1.0, (0.0, -0.6)).compile)
    assert len(found) == 1 and found[0].startswith("force 'push'.point = (0, -0.6) m lies 0.6 m from the centroid of body 'arm', 4 × as far")


def test_a_rotor_in_one_bearing_is_no_mechanism_scale():
    """A journal-bearing test rig: an unbalanced rotor (centroid 0.1 mm off its journal) in one
    lubricated bearing, turned by a driver. Its bodies' positions span 0.1 mm, which is no scale
    for a 20 mm journal: no "did you give mm?". Before: "journal_radius = 0.02 m is larger than
    half the mechanism's span 0.0001 m"."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=5.0, inertia=2e-3, position=(1e-4, 0.0))
    m.clearance_joint("B", "ground", (0.0, 0.0), "rotor", (-1e-4, 0.0), journal_radius=0.02, clearance=20e-6,
                      model=Lubricated(viscosity=0.02, length=0.02, film="short"))  # fmt: skip
    m.driver("rotor", omega=300.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        m.compile()


FEEDER = Path(__file__).resolve().parents[1] / "data" / "scenes" / "feeder_six_bar.toml"


@pytest.mark.parametrize(
    "table, old, new, field, says",
    [
        ("[outputs]", 'point = [0.075, -0.015] }]', 'point = [75.0, -15.0] }]', "outputs.points[0].point = (75, -15) m", "is it given in mm?"),
        ("[study]", "point = [0.075, -0.015]               # the finger tip", "point = [75.0, -15.0]", "[study].point = (75, -15) m", "is it given in mm?"),
        # the finger tip's global position at the pose given, not its body-frame one
        ("[study]", "point = [0.075, -0.015]               # the finger tip", "point = [0.0608, 0.1640]", "[study].point = (0.0608, 0.164) m",
         "is it given in global coordinates?"),
    ],
    ids=["outputs-mm", "study-mm", "study-global"],
)  # fmt: skip
def test_an_output_point_in_mm_or_in_the_global_frame_is_named(tmp_path, table, old, new, field, says):
    """The feeder's finger tip (0.075, −0.015) m on the arm, written in mm or as its global position:
    a PlausibilityWarning at the point's line names the table, field and value (as a load point's)."""
    text = FEEDER.read_text()
    start = text.index(table)
    text = text[:start] + text[start:].replace(old, new, 1)
    path = tmp_path / "feeder.toml"
    path.write_text(text)
    line = 1 + text[: text.index(new, start)].count("\n")
    _, found = _caught(lambda: clearsim.scene.load_scene_file(path))
    assert len(found) == 1 and found[0].startswith(f"{path}:{line}: {field} lies") and says in found[0], found
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        clearsim.scene.load_scene_file(FEEDER)


def test_an_output_point_of_the_python_api_is_checked():
    """``res.point``, ``res.error(point=)``, ``simulate(extremes=[(body, point)])``,
    ``bifurcation(point=)``: the slider-crank rod (centroid 0.11 m from the crank's pivot, its
    joints 0.06 m away) with its slider end written in mm or as the global (0.17, 0) m warns; the
    body-frame end (0.06, 0) m does not."""
    m = models.slider_crank("ideal")
    res = m.simulate(1e-3, progress=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        res.point("rod", (0.06, 0.0))
        m.simulate(1e-4, extremes=[("rod", (0.06, 0.0))], progress=False)
    _, found = _caught(lambda: res.point("rod", (60.0, 0.0)))
    assert len(found) == 1 and found[0].startswith("point = (60, 0) m lies 60 m from the centroid of body 'rod'") and "in mm?" in found[0]
    _, found = _caught(lambda: res.point("rod", (0.17, 0.0), "velocity"))
    assert len(found) == 1 and "read as a global point it lies on the body (0.06 m from its centroid" in found[0]
    _, found = _caught(lambda: m.simulate(1e-4, extremes=[("rod", (0.17, 0.0))], progress=False))
    assert len(found) == 1 and found[0].startswith("extremes point = (0.17, 0) m")


def _pumped(angle, period=None, torque: bool = False) -> clearsim.Mechanism:
    """A plunger pump's crank (walk 6) with a load table over its driver's angle."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("crank", mass=1.0, inertia=1e-3, ends=((0.0, 0.0), (0.04, 0.0)))
    m.revolute("ground", (0.0, 0.0), "crank", (-0.02, 0.0))
    m.driver("crank", omega=157.0, name="motor")
    table = {"driver": "motor", "angle": list(angle), ("torque" if torque else "fx"): [0.0, 0.0, -7000.0, -7000.0, 0.0][: len(angle)]}
    if period is not None:
        table["period"] = period
    if torque:
        m.torque("crank", table, name="fluid")
    else:
        m.force("crank", (0.02, 0.0), table, name="fluid")
    return m


def test_a_load_table_over_a_crank_angle_in_degrees_is_named():
    """A load table over a driver's angle written in degrees (0 … 360, period 360) runs its load
    over 57 turns instead of one: a PlausibilityWarning names the table and the unit. Before, it
    ran silently (the pump's discharge stroke took the first 6 % of a turn of a 57-turn cycle).
    The same table in radians, a table over several turns in radians (a start-up of 10 turns) and
    one in time are silent."""
    degrees = [0.0, 180.0, 190.0, 350.0, 360.0]
    for m, field in ((_pumped(degrees, 360.0), "force 'fluid'.fx.period = 360 rad"), (_pumped(degrees), "force 'fluid'.fx.angle"),
                     (_pumped([0.0, 360.0, 720.0], 720.0, torque=True), "force 'fluid'.magnitude.period = 720 rad")):  # fmt: skip
        _, found = _caught(m.compile)
        assert len(found) == 1 and found[0].startswith(field), found
        assert "degrees" in found[0] and "radians" in found[0], found
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        import math

        _pumped([0.0, math.pi, math.pi + 0.17, 2 * math.pi - 0.17, 2 * math.pi], 2 * math.pi).compile()
        _pumped([0.0, 10 * math.pi, 20 * math.pi]).compile()  # a run-up over ten turns, in radians


def test_a_study_output_point_in_mm_warns() -> None:
    """``rel.Output(point=)`` in a Python Study is checked like the scene's ``[study] point``: a
    point 100 m from a 0.17 m slider-crank's rod is named, with its field, before the samples."""
    import warnings

    from clearsim import models
    from clearsim import reliability as rel

    def build(c: float) -> clearsim.Mechanism:
        return models.slider_crank("dry", clearance=c)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        study = rel.Study(build, {"c": rel.Normal(1e-4, 1e-5)}, rel.Output(body="rod", point=(100.0, 0.0), component="x"), limit=1e-3, cycles=0.25, progress=False)
        study.monte_carlo(2, seed=1)
    found = [str(w.message) for w in caught if "Output.point" in str(w.message)]
    assert len(found) == 1 and "mm" in found[0] and "'rod'" in found[0], found
