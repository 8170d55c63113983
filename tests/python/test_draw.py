"""Pictures and animations of a mechanism: valid files with the expected frames, and the
drawing's geometry (bodies where the assembly puts them, journals displaced by magnify × e)."""

import math
import pickle

import matplotlib

import numpy as np
import pytest
from PIL import Image

import clearsim
from clearsim import draw, models, plots
from clearsim.cli import main
from clearsim.errors import InputError
from clearsim.scene import load_scene
from walks import PUMP

SCENES = __import__("pathlib").Path(__file__).resolve().parents[2] / "scenes"


def _png_ok(path):
    with Image.open(path) as im:
        assert im.format == "PNG" and im.size[0] > 300 and im.size[1] > 200
        arr = np.asarray(im.convert("L"))
    assert arr.std() > 5  # not blank


def test_a_mechanism_picture_is_cropped_to_its_drawing():
    """The notebook picture of a flat mechanism has no wide white frame: the slider-crank's
    drawing filled 55 % of its picture's height, the rest white above and below."""
    import io

    for m in (clearsim.models.slider_crank("dry"), clearsim.models.nine_bar("dry")):
        with Image.open(io.BytesIO(m._repr_png_())) as im:
            ink = np.asarray(im.convert("L")) < 250
        rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
        assert (rows[-1] - rows[0] + 1) / ink.shape[0] > 0.9 and (cols[-1] - cols[0] + 1) / ink.shape[1] > 0.9, ink.shape


def test_each_clearance_joint_is_drawn_at_its_own_bearing():
    """A drawing of a mechanism with two revolute clearance joints (the nine-bar's A and B, at
    t = 0 and mid-run) puts each joint's magnified bearing at its own bearing point and its
    journal inside it. Before: every joint's bearing was drawn at the last joint's (the update
    closure looked up the loop's last ``centre``), the others' journals metres away."""
    from matplotlib.patches import Circle

    m = models.nine_bar("dry", clearance=0.5e-3)
    res = m.simulate(0.05, dt_out=0.01, progress=False)
    desc = res.description  # as the core read it: bodies by index
    names = [b["name"] for b in desc["bodies"]]
    for t in (0.0, 0.05):
        fig = res.plot_mechanism(t, magnify=10)
        circles = [p for p in fig.axes[0].patches if isinstance(p, Circle)]
        for c in desc["clearance_joints"]:
            body = names[c["bearing_body"]]
            q = res.position(body)[np.searchsorted(res.t, t)]
            rot = np.array([[math.cos(q[2]), -math.sin(q[2])], [math.sin(q[2]), math.cos(q[2])]])
            centre = q[:2] + rot @ np.asarray(c["bearing_point"])
            label = next(x for x in fig.axes[0].texts if x.get_text().startswith(f"{c['name']} (c ="))
            assert np.allclose(label.xy, centre, atol=1e-9), c["name"]
            bearing = [p for p in circles if np.allclose(p.center, centre, atol=1e-9) and p.zorder == 4]
            journal = [p for p in circles if p.zorder == 5 and np.hypot(*(np.asarray(p.center) - centre)) <= 10 * c["clearance"] * 1.01]
            assert len(bearing) == 1 and len(journal) == 1, c["name"]


def test_plot_mechanism_outside_the_run_echoes_the_time_given():
    """``res.plot_mechanism(t)`` at a t outside the run (or NaN) is an InputError that names the
    t given and the run's span. Before: ``invalid t: the run covers [0, 0.05] s`` (which t?), and
    NaN drew a figure of NaN positions."""
    res = clearsim.load_scene(PUMP).simulate(0.05, dt_out=1e-3, progress=False)
    with pytest.raises(clearsim.InputError, match=r"invalid t = 0\.7 s: outside the run, which covers \[0, 0\.05\] s") as info:
        res.plot_mechanism(0.7)
    assert info.value.value == 0.7
    with pytest.raises(clearsim.InputError, match=r"invalid t = -0\.01 s: outside the run"):
        res.plot_mechanism(-0.01)
    with pytest.raises(clearsim.InputError, match=r"invalid t = nan: must be a finite time"):
        res.plot_mechanism(float("nan"))


def _label_boxes(fig):
    """The visible labels of a pose's drawing and their boxes [pixels] as the renderer draws them."""
    from clearsim.label_layout import renderer_of

    renderer = renderer_of(fig)
    texts = [t for t in fig.axes[0].texts if t.get_visible() and t.get_text()]
    return texts, [t.get_window_extent(renderer) for t in texts]


@pytest.mark.parametrize("scene", ["nine_bar.toml", "press_workpiece.toml", "engine.toml"])
def test_labels_of_a_shipped_scene_do_not_overlap(scene):
    """Joint, body, driver and load labels are moved apart where they would overlap (the nine-bar's
    crank4, drive4 and 'A (c = 0.5 mm, ×10)' were written over each other) and off the magnified
    bearings, each staying within a few lines of what it names; in the saved figure too."""
    m = load_scene(SCENES / scene)
    for fig in (m.plot(), m.plot(t=0.01)):
        fig.savefig(__import__("io").BytesIO(), format="png")  # the layout the file gets
        texts, boxes = _label_boxes(fig)
        assert len(texts) >= 5
        clash = [(texts[i].get_text(), texts[j].get_text()) for i in range(len(boxes)) for j in range(i + 1, len(boxes)) if boxes[i].overlaps(boxes[j])]
        assert not clash, clash
        for t in texts:  # offsets in points from the anchor: a label stays by what it names
            assert np.hypot(*t.xyann) < 60, (t.get_text(), t.xyann)


def test_a_zero_load_draws_no_arrow():
    """A load that is zero at the drawn time draws neither arrow nor label; a table load draws
    its value then (its direction), and again nothing where the table is back at zero."""
    from matplotlib.patches import FancyArrowPatch

    m = clearsim.models.slider_crank("dry", clearance=0.5e-3)
    m.force("crank", (0.0, 0.0), (0.0, 0.0), name="nothing")
    m.force("slider", (0.0, 0.0), {"t": [0.0, 0.01, 0.02], "fx": [0.0, -100.0, 0.0], "fy": [0.0, 50.0, 0.0]}, name="press")

    def loads(t):
        ax = m.plot(t=t).axes[0]
        arrows = [a for a in ax.patches if isinstance(a, FancyArrowPatch) and a.get_visible() and a.get_edgecolor()[:3] == matplotlib.colors.to_rgb(draw.FORCE_COLOUR)]
        names = {x.get_text() for x in ax.texts if x.get_visible()}
        return arrows, names

    arrows, names = loads(0.0)
    assert not arrows and "press" not in names and "nothing" not in names
    arrows, names = loads(0.005)  # half way up the table: (−50, 25) N
    assert len(arrows) == 1 and "press" in names and "nothing" not in names
    tail, head = (np.asarray(p) for p in arrows[0]._posA_posB)
    d = head - tail
    assert np.allclose(d / np.hypot(*d), np.array([-100.0, 50.0]) / np.hypot(100.0, 50.0), atol=1e-9)
    arrows, names = loads(0.02)
    assert not arrows and "press" not in names


def test_labels_keep_off_the_point_markers():
    """A tracked point on a clearance joint (the feeder's finger pin D and its arm's O6 bore): no
    label — the clearance's own, a body's, the point's name — covers a point's marker, in the
    pose drawn by Mechanism.plot and Result.plot_mechanism (before: 'D (c = 50 µm, ×…)' lay on the
    marker of a point at D)."""
    from clearsim.label_layout import renderer_of

    path = __import__("pathlib").Path(__file__).resolve().parents[1] / "data" / "scenes" / "feeder_six_bar.toml"
    m = load_scene(path)
    points = {"pin": ("arm", (0.025, 0.0)), "bore": ("arm", (-0.075, 0.0)), "tip": ("arm", (0.075, -0.015))}
    res = m.simulate(0.01, dt_out=1e-3, progress=False)
    for fig in (m.plot(points=points), res.plot_mechanism(0.005, points=points)):
        fig.savefig(__import__("io").BytesIO(), format="png")
        renderer = renderer_of(fig)
        ax = fig.axes[0]
        markers = [ln for ln in ax.lines if ln.get_marker() == "o" and ln.get_markerfacecolor() != "none" and len(ln.get_xdata()) == 1]
        assert len(markers) >= 3
        texts = [t for t in ax.texts if t.get_visible() and t.get_text()]
        covered = [(t.get_text(), k) for t in texts for k, mk in enumerate(markers) if t.get_window_extent(renderer).overlaps(mk.get_window_extent(renderer))]
        assert not covered, covered
