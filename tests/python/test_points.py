"""Points fixed on a body as outputs (issue 36 item 2): ``Result.point``, ``Result.error(...,
point=)``, ``Result.errors_table``, the exports, a scene's ``[outputs] points`` through
``clearsim run`` and the drawings, checked against closed forms: a crank tip on an ideal
constant-speed crank (|v| = ω r, |a| = ω² r), the slider-crank's coupler-point curve from the
crank angle (position, and its rates by central differences of the closed form), and the
identity point (0, 0) ≡ the centroid."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.cli import main
from clearsim.scene import load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"
R, L = 0.05, 0.12  # slider-crank crank and rod lengths [m]
RPM = 3000.0
OMEGA = RPM * 2 * math.pi / 60
TIGHT = dict(rtol=1e-10, atol=1e-13)
#: A point on the rod (rod frame, centroid at mid-length, x from crank pin to slider) [m].
ROD_POINT = (0.02, 0.015)


@pytest.fixture(scope="module")
def ideal_run():
    m = models.slider_crank("ideal", rpm=RPM, gravity=(0.0, -9.81))
    return m.simulate(0.75 * 60 / RPM, dt_out=1e-4, progress=False, **TIGHT)


def coupler_closed_form(t: np.ndarray, point=ROD_POINT) -> np.ndarray:
    """Global position of a rod point of the zero-offset slider-crank from the crank angle ωt."""
    th = OMEGA * t
    bx, by = R * np.cos(th), R * np.sin(th)  # crank pin
    phi = -np.arcsin(R * np.sin(th) / L)  # rod angle (pin → slider on the x axis)
    px, py = point[0] + L / 2, point[1]  # the point relative to the crank pin, rod frame
    return np.column_stack([bx + np.cos(phi) * px - np.sin(phi) * py, by + np.sin(phi) * px + np.cos(phi) * py])


def test_crank_tip_of_a_constant_speed_crank(ideal_run):
    res = ideal_run
    tip = (R / 2, 0.0)  # the crank's centroid is at mid-length
    x, v, a = (res.point("crank", tip, q) for q in ("displacement", "velocity", "acceleration"))
    assert x.shape == v.shape == a.shape == (len(res.t), 2)
    th = OMEGA * res.t
    np.testing.assert_allclose(x, R * np.column_stack([np.cos(th), np.sin(th)]), rtol=0, atol=1e-9 * R)
    np.testing.assert_allclose(np.hypot(*v.T), OMEGA * R, rtol=1e-8)
    np.testing.assert_allclose(np.hypot(*a.T), OMEGA**2 * R, rtol=1e-7)
    np.testing.assert_allclose(v, OMEGA * R * np.column_stack([-np.sin(th), np.cos(th)]), rtol=0, atol=1e-8 * OMEGA * R)
    np.testing.assert_allclose(a, -(OMEGA**2) * x, rtol=0, atol=1e-7 * OMEGA**2 * R)  # centripetal


def test_coupler_point_of_the_slider_crank(ideal_run):
    res = ideal_run
    t = res.t
    np.testing.assert_allclose(res.point("rod", ROD_POINT), coupler_closed_form(t), rtol=0, atol=1e-9)
    h = 1e-6  # rates of the closed form by central differences (errors ~ (ωh)² ≈ 1e-7)
    v = (coupler_closed_form(t + h) - coupler_closed_form(t - h)) / (2 * h)
    a = (coupler_closed_form(t + h) - 2 * coupler_closed_form(t) + coupler_closed_form(t - h)) / h**2
    np.testing.assert_allclose(res.point("rod", ROD_POINT, "velocity"), v, rtol=0, atol=1e-6 * OMEGA * R)
    np.testing.assert_allclose(res.point("rod", ROD_POINT, "acceleration"), a, rtol=0, atol=1e-4 * OMEGA**2 * R)


def test_the_centroid_is_the_point_00(ideal_run):
    res = ideal_run
    for body in res.body_names:
        np.testing.assert_array_equal(res.point(body, (0, 0)), res.position(body)[:, :2])
        np.testing.assert_array_equal(res.point(body, (0.0, 0.0), "velocity"), res.velocity(body)[:, :2])
        np.testing.assert_array_equal(res.point(body, [0, 0], "acceleration"), res.acceleration(body)[:, :2])


def test_point_errors_against_the_ideal_run():
    m = models.slider_crank("dry", rpm=RPM)
    res, ideal = m.simulate_with_ideal(0.2 * 60 / RPM, dt_out=2e-5, progress=False)
    for q in ("displacement", "velocity", "acceleration"):
        body = res.error(ideal, "rod", q)
        assert body.shape == (len(res.t), 3)  # today's centroid errors, unchanged
        err = res.error(ideal, "rod", q, point=ROD_POINT)
        assert err.shape == (len(res.t), 2)
        np.testing.assert_array_equal(err, res.point("rod", ROD_POINT, q) - ideal.point("rod", ROD_POINT, q))
        np.testing.assert_array_equal(res.error(ideal, "rod", q, point=(0, 0)), body[:, :2])
    # the ideal run's rod point follows the closed-form curve: the error is the clearance's doing
    np.testing.assert_allclose(ideal.point("rod", ROD_POINT), coupler_closed_form(ideal.t), rtol=0, atol=1e-7)
    assert np.max(np.abs(res.error(ideal, "rod", "displacement", point=ROD_POINT))) > 1e-5

    table = res.errors_table(ideal, points={"tool": ("rod", ROD_POINT)}, quantities=["displacement", "acceleration"])
    assert list(table.columns) == ["tool.displacement_error.x", "tool.displacement_error.y", "tool.acceleration_error.x", "tool.acceleration_error.y"]
    assert table.attrs["units"]["tool.acceleration_error.y"] == "m/s²" and table.index.name == "t"
    np.testing.assert_array_equal(table["tool.displacement_error.y"].to_numpy(), res.error(ideal, "rod", "displacement", point=ROD_POINT)[:, 1])
    every = res.errors_table(ideal)  # default: every body, every quantity
    assert every.shape[1] == 3 * 3 * 3 and every.attrs["units"]["crank.velocity_error.theta"] == "rad/s"
    np.testing.assert_array_equal(every["slider.velocity_error.x"].to_numpy(), res.error(ideal, "slider", "velocity")[:, 0])


@pytest.mark.parametrize(
    "args, field",
    [
        (("rod", (0.1,)), "point"),
        (("rod", (0.1, float("nan"))), "point"),
        (("rod", "ab"), "point"),
        (("rod", (0.1, 0.0), "speed"), "quantity"),
        (("pin", (0.1, 0.0)), "body"),
    ],
)
def test_bad_points_are_named(ideal_run, args, field):
    with pytest.raises(clearsim.InputError) as info:
        ideal_run.point(*args)
    assert info.value.field == field


def test_points_in_exports_and_drawings(ideal_run, tmp_path):
    res = ideal_run
    points = {"tool": ("rod", ROD_POINT)}
    df = res.to_pandas(points=points)
    assert df.attrs["units"]["tool.x_ddot"] == "m/s²"
    np.testing.assert_array_equal(df["tool.y_dot"].to_numpy(), res.point("rod", ROD_POINT, "velocity")[:, 1])
    res.save(tmp_path / "r.csv", points=points)
    header = (tmp_path / "r.csv").read_text().splitlines()[0].split(",")
    assert ["tool.x [m]", "tool.y [m]", "tool.x_dot [m/s]", "tool.y_dot [m/s]", "tool.x_ddot [m/s^2]", "tool.y_ddot [m/s^2]"] == header[-6:]
    with pytest.raises(clearsim.InputError, match="points"):
        res.to_pandas(points={"tool": ("pin", (0, 0))})
    with pytest.raises(clearsim.InputError, match="already a body's or joint's name"):
        res.to_pandas(points={"slider": ("rod", ROD_POINT)})  # its columns would overwrite the slider's

    t = float(res.t[len(res.t) // 2])
    fig = res.plot_mechanism(t, points=points, trace=True)
    lines = {tuple(np.round(ln.get_xydata()[0], 12)): ln for ln in fig.axes[0].lines if len(ln.get_xydata()) == len(res.t)}
    path = res.point("rod", ROD_POINT)
    assert tuple(np.round(path[0], 12)) in lines  # the traced path: every stored output
    np.testing.assert_allclose(lines[tuple(np.round(path[0], 12))].get_xydata(), path)
    texts = [a.get_text() for a in fig.axes[0].texts]
    assert "tool" in texts
    x0, x1 = fig.axes[0].get_xlim()
    assert x0 <= path[:, 0].min() and path[:, 0].max() <= x1  # the axes hold the path
    with pytest.raises(clearsim.InputError, match="trace"):
        res.plot_mechanism(t, trace=True)  # nothing to trace

    m = models.slider_crank("ideal", rpm=RPM)
    fig = m.plot(points={"tool": ("rod", ROD_POINT)})
    marks = [ln for ln in fig.axes[0].lines if ln.get_marker() == "o" and len(ln.get_xydata()) == 1]
    np.testing.assert_allclose(marks[0].get_xydata()[0], coupler_closed_form(np.array([0.0]))[0], atol=1e-9)
    gif = res.animate(tmp_path / "a.gif", points=points, max_frames=5)
    assert gif.stat().st_size > 1000


SCENE_POINTS = """
[outputs]
bodies = ["slider"]
components = ["x"]
joints = ["rod-slider"]
points = [{name = "tool", body = "rod", point = [0.02, 0.015]}]
"""


def _scene_with(tmp_path: Path, outputs: str, name: str = "sc.toml") -> Path:
    text = (SCENES / "slider_crank.toml").read_text(encoding="utf-8")
    text = text.split("[outputs]")[0].replace("rpm = 5000.0", f"rpm = {RPM}") + outputs
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_scene_points_through_clearsim_run(tmp_path):
    path = _scene_with(tmp_path, SCENE_POINTS)
    scene = load_scene_file(path)
    assert [(p.name, p.body, p.point) for p in scene.outputs.points] == [("tool", "rod", ROD_POINT)]
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out), "--t-end", "0.004", "-q"]) == 0
    rows = np.loadtxt(out / "bodies_ideal.csv", delimiter=",", skiprows=1)
    header = (out / "bodies.csv").read_text().splitlines()[0].split(",")
    # components = ["x"]: the point's x only, named as the bodies' columns
    assert header == ["t [s]", "slider.position.x [m]", "slider.velocity.x [m/s]", "slider.acceleration.x [m/s^2]",
                      "tool.position.x [m]", "tool.velocity.x [m/s]", "tool.acceleration.x [m/s^2]"]  # fmt: skip
    np.testing.assert_allclose(rows[:, 4], coupler_closed_form(rows[:, 0])[:, 0], rtol=0, atol=1e-7)  # the ideal twin's coupler curve
    errors = (out / "errors.csv").read_text().splitlines()[0].split(",")
    assert errors[-3:] == ["tool.displacement_error.x [m]", "tool.velocity_error.x [m/s]", "tool.acceleration_error.x [m/s^2]"]
    assert (out / "points.png").stat().st_size > 10_000
    assert (out / "tool_x_error.png").stat().st_size > 10_000
    summary = (out / "summary.md").read_text()
    assert "tool.displacement_error.x" in summary


@pytest.mark.parametrize(
    "entry, words",
    [
        ('points = [{name = "tool", body = "pin", point = [0.02, 0.0]}]', "outputs.points[0].body = 'pin'"),
        ('points = [{name = "tool", body = "rod", point = [0.02]}]', "outputs.points[0].point"),
        ('points = [{name = "tool", body = "rod", point = [nan, 0.0]}]', "finite"),
        ('points = [{name = "slider", body = "rod", point = [0.02, 0.0]}]', "already the name"),
        ('points = [{name = "tool", body = "rod", point = [0.02, 0.0], frame = "body"}]', "unknown key 'frame'"),
        ('points = [{body = "rod", point = [0.02, 0.0]}]', "missing key 'name'"),
    ],
)
def test_scene_point_errors_name_file_and_line(tmp_path, entry, words):
    path = _scene_with(tmp_path, f"[outputs]\nbodies = [\"slider\"]\n{entry}\n")
    with pytest.raises(clearsim.InputError) as info:
        load_scene_file(path)
    text = str(info.value)
    assert words in text and f"{path}:" in text
    line = path.read_text().splitlines().index(entry) + 1
    assert info.value.line in (line, line - 2)  # the entry's line (a missing key: the table's header)


def test_an_error_in_a_later_inline_point_names_its_line(tmp_path):
    entries = ['  {name = "tool", body = "rod", point = [0.02, 0.0]},', '  {name = "tip", body = "pin", point = [0.02, 0.0]},']  # an inline table is one line
    path = _scene_with(tmp_path, "[outputs]\npoints = [\n" + "\n".join(entries) + "\n]\n")
    with pytest.raises(clearsim.InputError) as info:
        load_scene_file(path)
    assert info.value.line == path.read_text().splitlines().index(entries[1]) + 1
    assert "outputs.points[1].body = 'pin'" in str(info.value) and str(info.value).startswith(f"{path}:{info.value.line}: ")


def test_scene_points_as_array_of_tables(tmp_path):
    path = _scene_with(tmp_path, '[outputs]\nbodies = ["slider"]\n\n[[outputs.points]]\nname = "tool"\nbody = "rod"\npoint = [0.02, 0.015]\n\n[[outputs.points]]\nname = "pin"\nbody = "rod"\npoint = [0.06, 0.0]\n')
    scene = load_scene_file(path)
    assert [p.name for p in scene.outputs.points] == ["tool", "pin"]
    run = scene.run()
    assert run.result.tracked_points == scene.outputs.points
    np.testing.assert_array_equal(run.errors[("pin", "velocity")], run.result.error(run.ideal, "rod", "velocity", point=(0.06, 0.0)))
