"""Tests of clearsim.plots: every function returns a Figure whose axes carry units, saves a
non-empty PNG and leaves no pyplot figure open."""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import clearsim  # noqa: E402
from clearsim import InputError, models, plots  # noqa: E402
from clearsim import reliability as rel  # noqa: E402

UNIT = re.compile(r"\[[^\]]+\]")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _visible_axes(fig):
    return [ax for ax in fig.axes if ax.get_visible()]


def _check_units(fig, need_x_everywhere=False):
    axes = _visible_axes(fig)
    assert axes
    for ax in axes:
        assert UNIT.search(ax.get_ylabel()), f"y label without unit: {ax.get_ylabel()!r}"
        if need_x_everywhere or ax.get_xlabel():
            assert UNIT.search(ax.get_xlabel()), f"x label without unit: {ax.get_xlabel()!r}"
    assert any(UNIT.search(ax.get_xlabel()) for ax in axes)


def _check_saved(fig, tmp_path, name):
    path = plots.save(fig, tmp_path / name)
    data = path.read_bytes()
    assert path.suffix == ".png" and data[:8] == PNG_MAGIC and len(data) > 5000
    return path


@pytest.fixture(autouse=True)
def _no_pyplot_leaks():
    before = set(plt.get_fignums())
    yield
    assert set(plt.get_fignums()) == before


def _histories():
    t = np.linspace(0.0, 0.4, 2001)
    w = 5 * np.pi
    rng = np.random.default_rng(0)
    spikes = 1200.0 * rng.standard_normal(t.size) * (rng.random(t.size) < 0.01)
    series = {
        "dry, c = 0.5 mm": {
            "displacement": 9e-4 * np.sin(w * t),
            "velocity": 0.3 * np.sin(3 * w * t),
            "acceleration": 400 * np.sin(5 * w * t) + spikes,
        },
        "lubricated, c = 0.5 mm": {
            "displacement": 4e-4 * np.sin(w * t + 0.5),
            "velocity": 0.05 * np.sin(2 * w * t),
            "acceleration": 6.0 * np.sin(2 * w * t),
        },
    }
    return t, series


def test_error_histories(tmp_path):
    t, series = _histories()
    fig = plots.plot_error_histories(t, series)
    assert isinstance(fig, Figure)
    axes = _visible_axes(fig)
    assert len(axes) == 3
    _check_units(fig)
    assert "[mm]" in axes[0].get_ylabel() and "[m/s]" in axes[1].get_ylabel() and "[m/s²]" in axes[2].get_ylabel()
    assert axes[2].get_xlabel() == "Time [s]"
    # dry ~1000 m/s² against lubricated ~6 m/s²: the acceleration panel is symlog, the
    # displacement panel (ratio ~2) linear
    assert axes[2].get_yscale() == "symlog" and axes[0].get_yscale() == "linear"
    # displacement drawn in mm
    ydata = [ln.get_ydata() for ln in axes[0].get_lines() if ln.get_label().startswith("dry")][0]
    assert np.max(np.abs(ydata)) == pytest.approx(0.9, rel=1e-3)
    assert axes[0].get_legend() is not None
    _check_saved(fig, tmp_path, "histories.png")


def test_error_histories_per_series_time_and_bad_input(tmp_path):
    t, series = _histories()
    fig = plots.plot_error_histories({k: t for k in series}, series, quantities=("velocity",), scale="linear")
    assert len(_visible_axes(fig)) == 1 and fig.axes[0].get_yscale() == "linear"
    _check_saved(fig, tmp_path, "velocity")  # suffix added
    with pytest.raises(InputError) as info:
        plots.plot_error_histories(t[:-1], series)
    assert "series" in info.value.field
    with pytest.raises(InputError) as info:
        plots.plot_error_histories(t, series, quantities=("jerk",))
    assert info.value.field == "quantity"
    with pytest.raises(InputError) as info:
        plots.plot_error_histories(t, series, scale="log")
    assert info.value.field == "scale"


def test_journal_orbits(tmp_path):
    th = np.linspace(0.0, 30.0, 3000)
    c = 3e-4
    orbits = {
        "A, dry": (c * np.cos(th) * np.abs(np.sin(3 * th)), c * np.sin(th)),
        "B, dry": (c * np.cos(th), c * np.sin(th)),
        "A, lubricated": (0.6 * c * np.cos(th), 0.4 * c * np.sin(th)),
    }
    fig = plots.plot_journal_orbits(orbits, c, transition_band=0.05 * c)
    assert isinstance(fig, Figure)
    axes = _visible_axes(fig)
    assert len(axes) == 3
    _check_units(fig, need_x_everywhere=True)
    for ax in axes:
        assert ax.get_aspect() == 1.0
        # unit circle and band circle drawn; orbit normalised by c
        radii = sorted(p.get_radius() for p in ax.patches)
        assert radii == pytest.approx([1.0, 1.05])
    x = axes[1].get_lines()[0].get_xdata()
    assert np.max(np.abs(x)) == pytest.approx(1.0, rel=1e-3)
    _check_saved(fig, tmp_path, "orbits.png")
    with pytest.raises(InputError) as info:
        plots.plot_journal_orbits(orbits, -1.0)
    assert info.value.field == "clearance"


def _fosm_curves(per_cycle=False):
    ang = np.linspace(0.0, 3 * 360.0, 3 * 720, endpoint=False)
    out = {}
    for label, amp in (("dry, c = 0.3 mm", 1.2), ("lubricated, c = 0.3 mm", 0.8)):
        err = amp * 1e-3 * (1.0 + 0.6 * np.cos(np.radians(ang - 207.0)))
        res = rel.fosm(err, ang, "displacement", per_cycle=per_cycle)
        out[label] = res.per_cycle if per_cycle else res
    return out


def test_reliability_plot(tmp_path):
    results = _fosm_curves(per_cycle=True)
    curves = {k: (r.bin_starts, r.reliability) for k, r in results.items()}
    fig = plots.plot_reliability(curves, "displacement")
    assert isinstance(fig, Figure)
    _check_units(fig, need_x_everywhere=True)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "Crank angle [deg]"
    texts = [t.get_text() for t in ax.texts]
    assert "198°, R = " + f"{results['dry, c = 0.3 mm'].min_reliability:.4f}" in texts
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("min R" in s and "198°" in s for s in legend)
    _check_saved(fig, tmp_path, "reliability.png")
    # FosmResult objects are accepted directly
    fig = plots.plot_reliability(_fosm_curves(), "velocity")
    _check_units(fig)
    with pytest.raises(InputError):
        plots.plot_reliability({"x": ([0.0, 18.0], [0.9])})


def test_reliability_panels(tmp_path):
    curves = _fosm_curves()
    fig = plots.plot_reliability_panels({"displacement": curves, "velocity": curves, "acceleration": curves})
    assert len(_visible_axes(fig)) == 3
    _check_units(fig, need_x_everywhere=True)
    assert "Velocity" in fig.axes[1].get_ylabel()
    _check_saved(fig, tmp_path, "panels.png")


def test_fosm_vs_mc(tmp_path):
    rng = np.random.default_rng(2)
    a = np.arange(0.0, 360.0, 1.0)
    g = 0.5 + 0.5 * np.abs(np.sin(np.radians(a)))
    err = rng.normal(1.5e-3, 5e-4, 500)[:, None] * g[None, :]
    mc = rel.mc_bin_reliability(err, a, upper=0.002)
    nominal = rel.fosm(1.5e-3 * g, a, (0.0, 0.002))
    fig = plots.plot_fosm_vs_mc(
        mc.bin_starts, {"FOSM, pooled MC": mc.fosm.reliability, "FOSM, nominal": nominal.reliability},
        mc.reliability, mc.lo, mc.hi, "displacement", confidence=0.95,
    )
    assert isinstance(fig, Figure)
    axes = _visible_axes(fig)
    assert len(axes) == 2 and axes[1].get_yscale() == "log"
    _check_units(fig)
    _check_saved(fig, tmp_path, "fosm_mc.png")
    with pytest.raises(InputError) as info:
        plots.plot_fosm_vs_mc(mc.bin_starts, mc.fosm.reliability, mc.reliability[:-1], mc.lo, mc.hi)
    assert info.value.field == "mc_R"


def test_work_precision(tmp_path):
    rows = [
        {"method": m, "wall_time": c * tol**-0.25, "error": tol * (1 + c), "rtol": tol}
        for m, c in (("rk4", 1.0), ("rk45", 0.5), ("dop853", 0.3))
        for tol in (1e-3, 1e-4, 1e-5, 1e-6)
    ]
    rows.append({"method": "rk4", "wall_time": 1.0, "error": 0.0, "rtol": 1e-9})  # skipped (log axes)
    fig = plots.plot_work_precision(rows, annotate="rtol", y_label="Slider displacement error", y_unit="m")
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert ax.get_xlabel() == "Wall time [s]" and ax.get_ylabel() == "Slider displacement error [m]"
    assert len(ax.get_lines()) == 3 and all(len(ln.get_xdata()) == 4 for ln in ax.get_lines())
    _check_saved(fig, tmp_path, "wp.png")
    with pytest.raises(InputError) as info:
        plots.plot_work_precision([{"method": "rk4", "error": 1.0}])
    assert info.value.field == "rows[0].wall_time"


def test_style_is_scoped():
    before = dict(matplotlib.rcParams)
    with plots.style():
        assert matplotlib.rcParams["axes.grid"] is True
    plots.plot_reliability(_fosm_curves(), "displacement")
    assert dict(matplotlib.rcParams) == before


def test_series_style_consistent_by_kind():
    st = plots.series_style(["dry, c = 0.3 mm", "lubricated, c = 0.3 mm", "ideal", "dry, c = 0.5 mm"])
    assert st["dry, c = 0.3 mm"]["linestyle"] == st["dry, c = 0.5 mm"]["linestyle"] == "-"
    assert st["lubricated, c = 0.3 mm"]["linestyle"] == "--" and st["ideal"]["linestyle"] == ":"
    assert st["dry, c = 0.3 mm"]["color"] != st["dry, c = 0.5 mm"]["color"]
    assert st["dry, c = 0.3 mm"]["color"] != st["lubricated, c = 0.3 mm"]["color"]
    # the same label gets the same style in every figure
    assert plots.series_style(["lubricated, c = 0.3 mm"])["lubricated, c = 0.3 mm"] == st["lubricated, c = 0.3 mm"]


def test_save_closes_pyplot_figures(tmp_path):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    num = fig.number
    path = plots.save(fig, tmp_path / "sub" / "pyplot.png")
    assert path.exists() and path.stat().st_size > 0
    assert num not in plt.get_fignums()


def test_minimum_labels_do_not_overlap(tmp_path):
    """Four curves whose minima sit 18° apart at nearly the same R (the paper's Fig. 16c had two
    labels written over each other): every label box is clear of every other."""
    a = np.arange(0.0, 360.0, 18.0)
    curves = {}
    for k, (where, depth) in enumerate([(18.0, 0.91), (36.0, 0.99), (18.0, 0.905), (36.0, 0.985)]):
        r = np.full_like(a, 0.999) - 0.001 * k
        r[a == where] = depth
        curves[f"{'dry' if k % 2 else 'lubricated'}, case {k}"] = (a, r)
    fig = plots.plot_reliability_panels({"acceleration": curves, "velocity": curves})
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    for ax in fig.axes:
        boxes = [t.get_window_extent(renderer) for t in ax.texts if "R = " in t.get_text()]
        assert len(boxes) == 4
        for i in range(4):
            for j in range(i + 1, 4):
                assert not boxes[i].overlaps(boxes[j]), (ax.get_title(), i, j)
    plots.save(fig, tmp_path / "labels.png")


def test_a_scene_name_as_title_fits_its_figure():
    """``clearsim run`` titles its figures with the scene's name: the shipped slider-crank's
    (56 characters) on its one-joint orbit figure, and a 90-character title on an error figure,
    are wrapped inside the figure, and so is the orbit legend. Before: cut off at both edges."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from clearsim import plots

    t = np.linspace(0.0, 1.0, 50)
    figs = [
        plots.plot_journal_orbits({"rod-slider (dry)": (1e-4 * np.cos(t), 1e-4 * np.sin(t))}, 5e-4,
                                  title="slider-crank, dry clearance joint rod-slider, c = 0.5 mm"),  # fmt: skip
        plots.plot_error_histories(t, {"dry": {"displacement": 1e-4 * t}}, quantities=["displacement"], title="x" * 45 + " " + "y" * 44),
    ]
    for fig in figs:
        FigureCanvasAgg(fig).draw()
        renderer = fig.canvas.get_renderer()
        width = fig.bbox.width
        boxes = [fig._suptitle.get_window_extent(renderer)] + [leg.get_window_extent(renderer) for leg in fig.legends]
        for box in boxes:
            assert box.x0 >= 0.0 and box.x1 <= width, (box, width)


def test_journal_orbits_given_a_result_say_what_they_take():
    """``plots.plot_journal_orbits(res, c)`` (a Result where ``{label: (e_x, e_y)}`` belongs) and a
    clearance mapping without an orbit's label are InputErrors saying what to give. Before:
    ``TypeError: 'Result' object is not iterable`` and ``KeyError: 'pin'``."""
    from clearsim import plots

    res = models.slider_crank("dry").simulate(0.001, dt_out=1e-4, progress=False)
    with pytest.raises(clearsim.InputError, match=r"invalid orbits = Result: must be a mapping .*res.eccentricity"):
        plots.plot_journal_orbits(res, 0.5e-3)
    with pytest.raises(clearsim.InputError, match="invalid clearance: no value for 'pin'"):
        plots.plot_journal_orbits({"pin": res.eccentricity("rod-slider").T}, {"rod-slider": 0.5e-3})
    assert plots.plot_journal_orbits({"pin": res.eccentricity("rod-slider").T}, {"pin": 0.5e-3}).axes
