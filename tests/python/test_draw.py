"""Pictures and animations of a mechanism: valid files with the expected frames, and the
drawing's geometry (bodies where the assembly puts them, journals displaced by magnify × e)."""

import math
import pickle

import numpy as np
import pytest
from PIL import Image

import clearsim
from clearsim import draw, plots
from clearsim.cli import main
from clearsim.errors import InputError
from clearsim.scene import load_scene

SCENES = __import__("pathlib").Path(__file__).resolve().parents[2] / "scenes"


def _png_ok(path):
    with Image.open(path) as im:
        assert im.format == "PNG" and im.size[0] > 300 and im.size[1] > 200
        arr = np.asarray(im.convert("L"))
    assert arr.std() > 5  # not blank


@pytest.mark.parametrize("scene", ["nine_bar_lubricated.toml", "slider_crank_guide_clearance.toml", "four_bar_spring.toml", "engine.toml", "press_workpiece.toml"])
def test_mechanism_picture_of_every_example(tmp_path, scene):
    m = load_scene(SCENES / scene)
    fig = m.plot()
    _png_ok(plots.save(fig, tmp_path / "pose.png"))


def test_drawing_puts_bodies_at_their_assembled_pose():
    m = clearsim.models.slider_crank("dry", clearance=0.5e-3)
    fig = m.plot(t=0.0, magnify=100)
    ax = fig.axes[0]
    # The crank bar runs from the ground pivot (0, 0) to the crank pin (0.05, 0) at θ = 0.
    lines = [np.asarray(line.get_xydata()) for line in ax.lines]
    assert any(np.allclose(xy[[0, -1]], [[0.0, 0.0], [0.05, 0.0]], atol=1e-9) for xy in lines if len(xy) == 2)
    labels = [t.get_text() for t in ax.texts]
    assert any("×100" in t and "rod-slider" in t for t in labels)


def test_springs_are_labelled_at_their_middle_and_the_label_follows_them():
    m = load_scene(SCENES / "four_bar_spring.toml")
    res = m.simulate(0.1, dt_out=1e-3, progress=False)
    f = next(f for f in res.description["forces"] if f["kind"] == "spring_damper")
    for t in (0.0, 0.1):
        fig = res.plot_mechanism(t)
        (label,) = [x for x in fig.axes[0].texts if x.get_text() == "return-spring"]
        q = draw.states_at(res, np.array([t]))[0]
        middle = 0.5 * (draw._point(q, f["body_a"], f["point_a"]) + draw._point(q, f["body_b"], f["point_b"]))
        assert np.allclose(label.xy, middle, rtol=0, atol=1e-12)
    from matplotlib.figure import Figure

    ax = Figure().add_subplot()
    draw.draw(ax, res.description, q, labels=False)
    assert not [x for x in ax.texts if x.get_text() == "return-spring"]


def test_journal_drawn_at_magnified_eccentricity():
    m = clearsim.models.slider_crank("dry", clearance=0.5e-3)
    res = m.simulate(0.01, dt_out=1e-4, progress=False)
    fig = res.plot_mechanism(0.008, magnify=10)
    circles = [p for p in fig.axes[0].patches if type(p).__name__ == "Circle"]
    q = draw.states_at(res, np.array([0.008]))[0]
    c = res.description["clearance_joints"][0]
    b = draw._point(q, c["bearing_body"], c["bearing_point"])
    j = draw._point(q, c["journal_body"], c["journal_point"])
    centres = np.array([p.center for p in circles])
    assert np.min(np.hypot(*(centres - (b + 10 * (j - b))).T)) < 1e-12


def test_animation_is_a_gif_with_the_expected_frames(tmp_path):
    m = clearsim.models.slider_crank("dry", clearance=0.5e-3)
    res = m.simulate(0.024, dt_out=1e-4, progress=False)
    path = res.animate(tmp_path / "run.gif", speed=0.024 / 1.0, fps=12)  # the run in 1 s
    with Image.open(path) as im:
        assert im.format == "GIF" and im.n_frames == 12
        im.seek(6)
        assert np.asarray(im.convert("L")).std() > 5
    with pytest.raises(InputError) as e:
        res.animate(tmp_path / "run.avi")
    assert e.value.field == "path"
    # A result still pickles with its drawing data.
    again = pickle.loads(pickle.dumps(res))
    assert again.description == res.description


def test_cli_run_animates(tmp_path):
    out = tmp_path / "o"
    gif = tmp_path / "a.gif"
    assert main(["run", str(SCENES / "four_bar_spring.toml"), "-o", str(out), "--t-end", "0.02", "--no-plots", "--animate", str(gif), "--speed", "0.05", "-q"]) == 0
    with Image.open(gif) as im:
        assert im.n_frames == 10  # 0.02 s at 1/20 of real time, 25 frames/s


def test_cli_animation_frames_follow_the_run(tmp_path, capsys):
    """Without --speed, 24 frames a crank turn (one per 15°) within [50, 400], or real time at
    25 frames/s without a constant-speed driver; the old default made every run 200 frames (8 s)."""
    from clearsim.cli import animation_frames

    assert [animation_frames(k * 0.012, 0.012) for k in (1, 5, 10, 100)] == [50, 120, 240, 400]
    assert [animation_frames(t, None) for t in (0.1, 3.0, 60.0)] == [50, 75, 400]
    # The slider-crank scene (5000 rpm: a turn in 12 ms) for three turns: 72 frames.
    gif = tmp_path / "a.gif"
    assert main(["run", str(SCENES / "slider_crank.toml"), "-o", str(tmp_path / "o"), "--t-end", "0.036", "--no-plots", "--animate", str(gif), "-q"]) == 0
    with Image.open(gif) as im:
        assert im.n_frames == 72
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    assert "24 frames a crank turn" in " ".join(capsys.readouterr().out.split())


@pytest.mark.parametrize("scene", ["engine.toml", "four_bar_spring.toml", "slider_crank_guide_clearance.toml", "nine_bar_lubricated.toml"])
def test_a_drawing_moved_to_a_pose_matches_one_drawn_there(scene):
    """Animations move the artists of one drawing (draw.Drawing.update) instead of drawing each
    frame anew: moved from q0 to q1 they must be where a drawing made at q1 puts them."""
    from matplotlib.figure import Figure

    m = load_scene(SCENES / scene)
    res = m.simulate(0.004, dt_out=1e-4, progress=False)
    q0, q1 = draw.states_at(res, np.array([0.0, 0.004]))
    size = draw.extent(res.description, q0)

    def geometry(drawing):
        out = []
        for a in drawing.artists:
            for getter in ("get_xydata", "get_xy", "get_center", "get_position"):
                if hasattr(a, getter) and not (getter == "get_position" and hasattr(a, "get_xy")):
                    out.append(np.asarray(getattr(a, getter)(), dtype=float).ravel())
                    break
            if hasattr(a, "xy") and not hasattr(a, "get_xy"):
                out.append(np.asarray(a.xy, dtype=float))
        return out

    moved = draw.Drawing(Figure().add_subplot(), res.description, q0, 5.0, size)
    moved.update(q1)
    fresh = draw.Drawing(Figure().add_subplot(), res.description, q1, 5.0, size)
    assert len(moved.artists) == len(fresh.artists) > 3
    for a, b in zip(geometry(moved), geometry(fresh)):
        assert np.allclose(a, b, rtol=0, atol=1e-12)
    assert not all(np.allclose(a, b) for a, b in zip(geometry(draw.Drawing(Figure().add_subplot(), res.description, q0, 5.0, size)), geometry(fresh)))


@pytest.mark.parametrize("scene", ["nine_bar_lubricated.toml", "engine.toml", "four_bar_spring.toml", "slider_crank_guide_clearance.toml"])
def test_the_labels_of_a_drawing_do_not_overlap(scene):
    """A still drawing moves its names clear of each other (the nine-bar's 'drive4', 'crank4' and
    'A (c = ..., ×10)' were written over each other at the same pin) and inside the axes."""
    m = load_scene(SCENES / scene)
    fig = m.plot()
    ax = fig.axes[0]
    fig.draw_without_rendering()
    boxes = [t.get_window_extent() for t in ax.texts if t.get_text()]
    assert len(boxes) >= 4
    for i, a in enumerate(boxes):
        for b in boxes[:i]:
            assert not a.overlaps(b), (a, b)
    frame = ax.get_window_extent().expanded(1.02, 1.02)
    assert all(frame.contains(b.x0, b.y0) and frame.contains(b.x1, b.y1) for b in boxes)


def test_a_mechanism_picture_is_cropped_to_its_drawing():
    """The notebook picture of a flat mechanism has no wide white frame: the slider-crank's
    drawing filled 55 % of its picture's height, the rest white above and below."""
    import io

    for m in (clearsim.models.slider_crank("dry"), clearsim.models.nine_bar("dry")):
        with Image.open(io.BytesIO(m._repr_png_())) as im:
            ink = np.asarray(im.convert("L")) < 250
        rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
        assert (rows[-1] - rows[0] + 1) / ink.shape[0] > 0.9 and (cols[-1] - cols[0] + 1) / ink.shape[1] > 0.9, ink.shape
