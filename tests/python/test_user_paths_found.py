"""Defects found by walking a user's paths (issue 28 item 2 and the walk of a mechanism of our
own, docs/examples.md): each is a focused test here, and its cell in the user-path matrix
(test_user_paths.py) covers its class."""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Output, Study

OMEGA = 5000 * 2 * math.pi / 60  # [rad/s] the slider-crank model's crank


def _dry(clearance: float) -> clearsim.Mechanism:
    return models.slider_crank("dry", clearance=clearance)


@pytest.mark.parametrize("cycles", [0.1, 0.5])
def test_a_window_shorter_than_a_turn_leaves_its_unseen_bins_empty(cycles):
    """clearsim.monte_carlo and Study.fosm over less than a turn: the crank-angle bins the window
    never reaches hold no sample (NaN, as fosm() leaves empty bins), the others are analysed.
    Before: ``InputError: invalid mu_s = nan: must be a number`` (the unseen bins' 0/0 mean
    reached the reliability index), and the per-bin Monte Carlo reliability said R = 1 there."""
    mc = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, omega=OMEGA, cycles=cycles, body="slider",
                              component="x", allowable={"displacement": (0.0, 1e-3)}, progress=False)  # fmt: skip
    bins = mc.bins["displacement"]
    n_seen = int(round(cycles * 360 / 18))
    assert np.all(np.isfinite(bins.reliability[:n_seen])) and np.all(np.isnan(bins.reliability[n_seen:]))
    assert np.all(bins.n_samples[n_seen:] == 0) and np.all(bins.n_samples[:n_seen] == 2)
    assert np.all(np.isfinite(bins.fosm.beta[:n_seen])) and np.all(np.isnan(bins.fosm.beta[n_seen:]))
    assert bins.fosm.min_angle < cycles * 360
    study = Study(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3,
                  omega=OMEGA, cycles=cycles, progress=False)  # fmt: skip
    fosm = study.fosm()
    assert np.all(np.isfinite(fosm.reliability[:n_seen])) and np.all(np.isnan(fosm.reliability[n_seen:]))


def test_simulate_with_ideal_takes_the_options_of_simulate():
    """``progress=False``, which every ``simulate`` call in a script carries, is accepted by
    ``simulate_with_ideal`` too. Before: ``TypeError: Running.run_settings() got an unexpected
    keyword argument 'progress'``."""
    m = _dry(0.5e-3)
    res, ideal = m.simulate_with_ideal(0.002, progress=False, dt_out=1e-4)
    assert res.completed and ideal.completed and len(res.t) == len(ideal.t) == 21


def test_each_clearance_joint_is_drawn_at_its_own_bearing():
    """A drawing of a mechanism with two revolute clearance joints (the nine-bar's A and B, at
    t = 0 and mid-run) puts each joint's magnified bearing at its own bearing point and its
    journal inside it. Before: every joint's bearing was drawn at the last joint's (the update
    closure looked up the loop's last ``centre``), the others' journals metres away."""
    from matplotlib.patches import Circle

    m = models.nine_bar("dry", clearance=0.5e-3)
    res = m.simulate(0.05, dt_out=0.01, progress=False)
    desc = m.description()
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


def test_a_scene_error_comes_after_the_unit_slip_that_caused_it(tmp_path, capsys):
    """The compressor's crank pin given as ``journal_radius = 10`` (mm as m): the finite film's
    L/D = 0.0006 stops the scene, and the warning that names the real cause (a journal radius of
    the order of the mechanism: mm?) is printed before that error. Before: the warning, caught
    while the file was read, was dropped with the error, which advises another film model."""
    from pathlib import Path

    from clearsim.cli import main

    text = (Path(__file__).resolve().parents[2] / "scenes" / "compressor.toml").read_text(encoding="utf-8")
    assert text.count("journal_radius = 10e-3 ") == 1
    path = tmp_path / "mm.toml"
    path.write_text(text.replace("journal_radius = 10e-3 ", "journal_radius = 10 "), encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # conftest makes a PlausibilityWarning an error
        assert main(["run", str(path), "-o", str(tmp_path / "out"), "-q", "--no-plots"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    mm = next(k for k, line in enumerate(lines) if "journal_radius = 10 m" in line and "did you give mm?" in line)
    assert lines[mm].startswith(f"clearsim: warning: {path}:") and lines[-1].startswith("clearsim: error: ") and mm < len(lines) - 1
    assert "L/D" in lines[-1]


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
        _crank_rod_slider(1000.0).description()
    text = [str(w.message) for w in caught]
    assert any(t.startswith("body 'rod'.inertia = 0.0075 kg m² is 1e-06 × a uniform bar's") and "300 m apart" in t and "in mm?" in t for t in text)
    assert any(t.startswith("body 'crank'.inertia") for t in text) and not any("'slider'" in t for t in text)
    with warnings.catch_warnings():
        warnings.simplefilter("error", clearsim.PlausibilityWarning)
        _crank_rod_slider(1.0).description()
        _crank_rod_slider(1.0, inertia_scale=1e3).description()
        _crank_rod_slider(1000.0, inertia_scale=1e6).description()  # all in mm and kg mm²: nothing tells


# ---------------------------------------------------------------- walk 2: a toggle press of our own
TOGGLE = Path(__file__).resolve().parents[1] / "data" / "scenes" / "toggle_press.toml"
SHAPER = Path(__file__).resolve().parents[1] / "data" / "scenes" / "shaper.toml"


def test_extremes_of_the_bearing_readings_are_tracked_when_asked():
    """``simulate(extremes=[joint])`` tracks a clearance joint's film thickness, friction torque
    and power loss too (lubricated or dry), and each extreme bounds the stored samples and
    agrees with them on a fine output grid; the dry line-contact pin's peak torque is μ R_j F_N
    at its peak contact force. Before: ``extremes("A", "friction_torque")`` said the run did
    not track its extremes, and so did every reading of the dry pin, though both were asked for."""
    m = clearsim.load_scene(TOGGLE)
    res = m.simulate(0.1, dt_out=2e-5, extremes=["A", "P"], progress=False)
    for joint in ("A", "P"):
        for quantity, values in (("film_thickness", res.film_thickness(joint)), ("friction_torque", res.friction_torque(joint)),
                                 ("power_loss", res.power_loss(joint))):  # fmt: skip
            x = res.extremes(joint, quantity)
            span = values.max() - values.min()
            assert x.max >= values.max() - 1e-12 * abs(values.max()) and x.min <= values.min() + 1e-12 * abs(values.min())
            assert x.max - values.max() < 0.1 * span and values.min() - x.min < 0.1 * span, (joint, quantity)
    torque, contact = res.extremes("P", "friction_torque"), res.extremes("P", "contact_force")
    assert torque.max == pytest.approx(0.1 * 8e-3 * contact.max, rel=1e-6) and torque.t_max == pytest.approx(contact.t_max)


def test_a_series_study_states_that_every_output_must_hold():
    """The repr of a study of several outputs (a series system: it fails when any passes its
    limit) states what holds when it is safe: each output within its limit, joined by "and".
    Before: "film thickness of joint A ≥ 5e-07 m or y displacement error ≤ 0.0005 m"."""
    from clearsim.reliability.scene import scene_study
    from clearsim.scene import load_scene_file

    text = repr(scene_study(load_scene_file(TOGGLE), progress=False))
    assert "film thickness of joint A ≥ 5e-07 m and y displacement error of ram ≤ 0.0005 m" in text and " or " not in text


def test_normal_and_lognormal_inputs_stay_finite_far_in_the_tails():
    """``x = F⁻¹(Φ(u))`` of a Normal and a LogNormal input is the closed form at any u (mean + std u,
    exp(μ_ln + σ_ln u)). Before: Φ(u) rounded to 1 beyond u ≈ 38 and the input became inf, which a
    FORM step handed to the user's build (``clearance joint 'A'.clearance = inf``)."""
    from clearsim.reliability import LogNormal

    u = np.array([-50.0, -40.0, 0.0, 40.0, 50.0])
    assert np.allclose(Normal(40e-6, 4e-6).from_standard_normal(u), 40e-6 + 4e-6 * u, rtol=1e-14, atol=0.0)
    d = LogNormal(0.1, 0.01)
    mu, s = d.log_params
    assert np.allclose(d.from_standard_normal(u), np.exp(mu + s * u), rtol=1e-12, atol=0.0)


def test_form_of_a_series_system_with_a_mode_that_never_fails():
    """The toggle press's study, in miniature: a film mode that fails at β = −0.62 and a ram-error
    mode whose margin flattens out at g = 0.18 as the pin clearance grows (it never fails; its
    first HL-RF step from a slope of −0.0127 jumps to u ≈ 50). FORM keeps its search within
    |u| ≤ 37, reports the safe mode as β = 37 with a ReliabilityWarning, and the series p_f is the
    film mode's Φ(0.62); no input it asks for is non-finite. Before: the jump to u ≈ 50 made the
    clearance inf (then, with the closed-form transform, 50 iterations on at the tail), and the
    study stopped with the build's ``InputError``."""
    from clearsim.errors import ReliabilityWarning
    from clearsim.reliability import LimitState, LogNormal

    seen = []
    mu_ln, s_ln = LogNormal(0.1, 0.01).log_params

    def g(x):
        c, mu = x["c"], x["mu"]
        seen.append(np.concatenate([c, mu]))
        film = -0.0986 - 0.111 * (c - 40e-6) / 4e-6 + 0.0963 * (np.log(mu) - mu_ln) / s_ln  # linear in u
        ram = 0.18 + 0.46 * np.exp(-(c - 40e-6) / 145e-6)
        return [film, ram]

    model = LimitState(g, {"c": Normal(40e-6, 4e-6), "mu": LogNormal(0.1, 0.01)}, modes=["film", "ram"])
    with pytest.warns(ReliabilityWarning, match=r"not reached within \|u\| ≤ 37"):
        res = model.form()
    assert np.all(np.isfinite(np.concatenate(seen)))
    assert res.modes[1].beta == 37.0 and res.modes[1].pf < 1e-299
    assert res.modes[0].beta == pytest.approx(-0.0986 / math.hypot(0.111, 0.0963), rel=1e-3)
    assert res.pf == pytest.approx(res.modes[0].pf, rel=1e-9)


def _csv(path):
    import csv

    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array(rows[1:], dtype=float)


@pytest.mark.parametrize("scene, t_end, joint, clearance", [(TOGGLE, 0.1, "A", 40e-6), (SHAPER, 0.0667, "A", 30e-6)])
def test_walked_scenes_run_and_study_from_the_cli(tmp_path, scene, t_end, joint, clearance):
    """The walks' own mechanisms (a toggle press, a shaper's quick return; each a lubricated and a
    dry pin) through ``clearsim run`` (a short --t-end, figures on) and ``clearsim reliability``
    (2 Monte Carlo samples of their [study], skip_cycles = 1). The joints CSV's film thickness is
    c − |e| at every sample, and its power loss is at least the Couette shear's |T| ω_rel."""
    import json

    from clearsim.cli import main

    out = tmp_path / "run"
    assert main(["run", str(scene), "-o", str(out), "-q", "--t-end", str(t_end)]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["run"]["t_reached"] == pytest.approx(t_end) and summary["run"]["failure"] is None
    assert 0 < summary["run"]["bearings"][joint]["min_film_thickness"] < clearance
    head, data = _csv(out / "joints.csv")
    col = {h: k for k, h in enumerate(head)}
    if f"{joint}.film_thickness [m]" in col:
        e = np.hypot(data[:, col[f"{joint}.ex [m]"]], data[:, col[f"{joint}.ey [m]"]])
        assert np.allclose(data[:, col[f"{joint}.film_thickness [m]"]], clearance - e, rtol=0.0, atol=1e-15)
        assert np.all(data[:, col[f"{joint}.power_loss [W]"]] >= 0.0)
    assert (out / "orbits.png").stat().st_size > 0 and (out / "summary.md").read_text(encoding="utf-8").count("| A |") == 1
    rel = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(rel), "-q", "--methods", "monte_carlo", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(np.isfinite(samples[:, head.index("A.film_thickness [m]")]))
    assert "| monte_carlo | system |" in (rel / "report.md").read_text(encoding="utf-8")


# ---------------------------------------------------------------- walk 3: a walking-beam pump of our own
PUMP = Path(__file__).resolve().parents[1] / "data" / "scenes" / "beam_pump.toml"


def _pump_scene(tmp_path: Path, methods: str) -> Path:
    """The pump's scene with the [study]'s methods replaced and no [study.life] (its minutes of
    worn cycles are not what these tests look at)."""
    text = PUMP.read_text(encoding="utf-8")
    text = re.sub(r"^methods = \[[^]]*\]", f"methods = {methods}", text[: text.index("\n[study.life]")], count=1, flags=re.M)
    path = tmp_path / "pump.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_reliability_method_that_stops_keeps_what_the_others_found(tmp_path, capsys, monkeypatch):
    """``clearsim reliability`` with methods monte_carlo, form, fosm where FORM finds no design
    point (as on the pump's noisy plunger error, after 2 min): the Monte Carlo rows are written,
    report.md names the method that stopped and the ones it left unrun, and the command exits
    with the error. Before: the ReliabilityError escaped run_study, and report.md said
    "Written before it stopped: nothing"."""
    import csv

    from clearsim.cli import main
    from clearsim.errors import ReliabilityError

    def no_design_point(self, *args, **kwargs):
        raise ReliabilityError("FORM did not converge: no design point after 50 iterations")

    monkeypatch.setattr(Study, "form", no_design_point)
    scene = _pump_scene(tmp_path, '["monte_carlo", "form", "fosm"]')
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "-q", "--samples", "2", "--no-plots"]) != 0
    assert "no design point" in capsys.readouterr().err
    assert {r["method"] for r in csv.DictReader((out / "reliability.csv").open(encoding="utf-8"))} == {"monte_carlo"}
    assert (out / "samples.csv").exists()
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "Stopped at form: FORM did not converge" in report and "Not run: fosm." in report and "| monte_carlo |" in report


def test_fosm_all_by_default_takes_the_outputs_fosm_applies_to():
    """``Study.fosm_all()`` on a series system of an error and a film thickness (a lower limit)
    analyses the error, bit for bit as ``fosm_all(outputs=[0])``; it analysed "every output" and
    so raised ``invalid output = 1`` for an output the user never named."""
    m_study = Study(lambda c: models.slider_crank("lubricated", clearance=c), {"c": Normal(0.5e-3, 0.01e-3)},
                    [Output(body="slider", component="x", quantity="displacement"), Output(joint="rod-slider", quantity="film_thickness")],
                    [1e-4, clearsim.reliability.Limit.below(1e-6)], cycles=0.25, progress=False)  # fmt: skip
    (res,) = m_study.fosm_all()
    (named,) = m_study.fosm_all(outputs=[0])
    np.testing.assert_array_equal(res.reliability, named.reliability)
    with pytest.raises(clearsim.InputError, match="lower limit"):
        m_study.fosm_all(outputs=[1])


def test_a_study_whose_build_does_not_take_an_input_says_so():
    """``Study(lambda cA: ..., {"cB": ...})`` (an input renamed in one place) is an InputError
    naming the inputs and build's parameters when the study is made, and a build that returns
    something else than a Mechanism one naming what it returned. Before: ``TypeError: <lambda>()
    got an unexpected keyword argument 'cB'``; ``AttributeError: 'tuple' object has no attribute
    'description'`` (or ``'check_assembly'``)."""
    with pytest.raises(clearsim.InputError, match=r"invalid inputs = \['cB'\]: build\(cA\) does not take them by name"):
        Study(lambda cA: _dry(cA), {"cB": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3, progress=False)
    for omega in (None, OMEGA):  # the nominal mechanism read at once, or first built by a method
        with pytest.raises(clearsim.InputError, match=r"invalid build: it returned a tuple, not a clearsim.Mechanism"):
            Study(lambda cA: (_dry(cA),), {"cA": Normal(0.5e-3, 0.01e-3)}, Output(body="slider", component="x", quantity="displacement"), 1e-3, omega=omega, progress=False).fosm()
    study = Study(lambda cA, **rest: _dry(cA), {"cA": Normal(0.5e-3, 0.01e-3), "speed": 1.0}, Output(body="slider", component="x", quantity="displacement"), 1e-3, progress=False)
    assert study.omega == pytest.approx(OMEGA)


def test_monte_carlo_without_omega_takes_the_driver_speed_as_study_does():
    """``clearsim.monte_carlo`` without ``omega`` (and no input named omega) takes the nominal
    mechanism's constant-speed driver's, as ``Study`` does: the same bins as ``omega=OMEGA``.
    Before: ``invalid omega = 'omega': not a sampled input`` for an omega never given."""
    kwargs = dict(body="slider", component="x", allowable={"displacement": (0.0, 1e-3)}, cycles=0.25, progress=False)
    mc = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, **kwargs)
    given = clearsim.monte_carlo(_dry, {"clearance": Normal(0.5e-3, 0.01e-3)}, 2, omega=OMEGA, **kwargs)
    np.testing.assert_array_equal(mc.bins["displacement"].reliability, given.bins["displacement"].reliability)
    for q in mc.peaks:
        np.testing.assert_array_equal(mc.peaks[q], given.peaks[q])


def test_a_bad_lubricated_field_in_a_scene_names_its_joint(tmp_path):
    """A negative viscosity (or a restitution above 1) in ``[clearance_joint.lubricated]`` /
    ``[clearance_joint.dry]`` names the joint, the field and the value, as ``with_values`` does.
    Before: ``invalid viscosity = -0.2: must be positive`` (which of the joints?)."""
    text = PUMP.read_text(encoding="utf-8")
    for old, new, said in (("viscosity = 0.2 ", "viscosity = -0.2 ", "invalid clearance joint 'A'.viscosity = -0.2: must be positive"),
                           ("restitution = 0.8", "restitution = 1.8", "invalid clearance joint 'O4'.restitution = 1.8")):  # fmt: skip
        path = tmp_path / "bad.toml"
        path.write_text(text.replace(old, new, 1), encoding="utf-8")
        with pytest.raises(clearsim.InputError) as info:
            clearsim.load_scene(path)
        assert said in str(info.value) and str(info.value).startswith(f"{path}:")


def test_the_old_paper_runs_module_keeps_its_public_names():
    """``clearsim.study.paper_runs`` (deprecated) still has every public name it had before the
    paper study moved to clearsim.paper. Before: ``CSV_UNIT`` was gone (ImportError)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from clearsim.study.paper_runs import CSV_UNIT
    assert CSV_UNIT["acceleration"] == "m_per_s2"


def test_fosm_of_a_film_only_study_is_refused_before_anything_runs(tmp_path, capsys):
    """A [study] whose only output is a film thickness (a lower limit) with methods = ["form",
    "fosm"]: an InputError naming methods before any run. Before: FORM ran (12 s), then FOSM
    stopped with ``invalid output = 0``."""
    from clearsim.cli import EXIT_ERROR, main

    text = _pump_scene(tmp_path, '["form", "fosm"]').read_text(encoding="utf-8")
    start = text.index('[[study.output]]\nbody = "plunger"')
    text = text[:start] + text[text.index("[[study.output]]", start + 1) :]
    scene = tmp_path / "film.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "-q"]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert "invalid methods = ['form', 'fosm']: fosm compares an error" in err and len(err.strip().splitlines()) == 1
    assert not (out / "reliability.csv").exists()


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


def test_the_pump_runs_studies_and_animates_from_the_cli(tmp_path, capsys):
    """The walking-beam pump (a Watt-type six-bar with a plunger; a lubricated short-bearing crank
    pin and a dry, worn saddle bearing) through ``clearsim run`` over its first turn and a bit
    with ``--animate`` (a turn is 24 frames: the 50-frame floor) and ``clearsim reliability``
    (2 Monte Carlo samples and FOSM of its [study], skip_cycles = 1). The film thickness in
    joints.csv is c − |e|; [reliability]'s FOSM printed by ``run`` does not change with dt_out."""
    import json
    import re

    from PIL import Image

    from clearsim.cli import main

    scene = _pump_scene(tmp_path, '["monte_carlo", "fosm"]')
    printed = {}
    for dt_out in ("1e-3", "4e-3"):
        path = tmp_path / f"pump_{dt_out}.toml"
        path.write_text(scene.read_text(encoding="utf-8").replace("dt_out = 1e-3 ", f"dt_out = {dt_out} "), encoding="utf-8")
        out = tmp_path / f"run_{dt_out}"
        args = ["run", str(path), "-o", str(out), "--no-plots"] + (["--animate", str(out / "run.gif")] if dt_out == "1e-3" else [])
        assert main(args) == 0
        printed[dt_out] = re.findall(r"FOSM \w+: min R = .*", capsys.readouterr().out)
    assert len(printed["1e-3"]) == 3 and printed["1e-3"] == printed["4e-3"]
    out = tmp_path / "run_1e-3"
    with Image.open(out / "run.gif") as gif:
        assert gif.n_frames == 50
    head, _ = _csv(out / "reliability_acceleration.csv")  # name [unit], as every clearsim CSV file (was angle_deg, mu_s, ...)
    assert head == ["cycle", "bin_start [deg]", "bin_centre [deg]", "samples", "mu_s [m/s^2]", "sigma_s [m/s^2]", "mu_S [m/s^2]", "sigma_S [m/s^2]", "beta", "reliability"]
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["run"]["failure"] is None and 0 < summary["run"]["bearings"]["A"]["min_film_thickness"] < 30e-6
    head, data = _csv(out / "joints.csv")
    col = {h: k for k, h in enumerate(head)}
    e = np.hypot(data[:, col["A.ex [m]"]], data[:, col["A.ey [m]"]])
    assert np.allclose(data[:, col["A.film_thickness [m]"]], 30e-6 - e, rtol=0.0, atol=1e-15)
    rel = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(rel), "-q", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(np.isfinite(samples[:, head.index("A.film_thickness [m]")]))
    report = (rel / "report.md").read_text(encoding="utf-8")
    assert "| monte_carlo | system |" in report and "FOSM `plunger.y.displacement`" in report


WIPER = Path(__file__).resolve().parents[1] / "data" / "scenes" / "wiper.toml"


def test_the_wiper_runs_and_studies_from_the_cli(tmp_path, capsys):
    """The windscreen-wiper four-bar (walk 4: a crank-rocker with a lubricated crank pin A and a
    dry rocker pin B) through ``clearsim run`` and ``clearsim reliability``. The "auto" integrator
    resolves to radau (a lubricated joint), named beside its setting in summary.json; [reliability]'s
    FOSM printed by ``run`` is the same whatever dt_out and t0 (its crank angle is |ω| t from
    t = 0); the rocker's angle error is bounded by the play: the pin B can sit c_A + c_B off the
    ideal, which turns the 50 mm rocker by at most (c_A + c_B)/(r sin μ) (μ ≥ 30°, the
    transmission angle), and by more than nothing."""
    import json

    from clearsim.cli import main

    text = WIPER.read_text(encoding="utf-8")
    printed = {}
    for label, edit in (("base", text), ("dt_out", text.replace("dt_out = 2e-3 ", "dt_out = 5e-4 ")),
                        ("t0", text.replace("cycles = 2 ", "t0 = 0.25\ncycles = 2 "))):  # fmt: skip
        assert edit != text or label == "base"
        path = tmp_path / f"wiper_{label}.toml"
        path.write_text(edit, encoding="utf-8")
        out = tmp_path / f"run_{label}"
        assert main(["run", str(path), "-o", str(out), "--no-plots"]) == 0
        printed[label] = re.findall(r"FOSM \w+: min R = [0-9.]+ \(β = [-0-9.]+\) at (\d+)°", capsys.readouterr().out)
    assert len(printed["base"]) == 3 and printed["base"] == printed["dt_out"] == printed["t0"]
    summary = json.loads((tmp_path / "run_base" / "summary.json").read_text(encoding="utf-8"))
    assert summary["integrator"] == "radau" and summary["integrator_setting"] == "auto"
    assert summary["run"]["failure"] is None and 0 < summary["run"]["bearings"]["A"]["min_film_thickness"] < 20e-6
    head, data = _csv(tmp_path / "run_base" / "errors.csv")
    peak = np.max(np.abs(data[:, head.index("rocker.displacement_error.theta [rad]")]))
    assert 0.0 < peak < (20e-6 + 0.1e-3) / (0.05 * math.sin(math.radians(30)))
    rel = tmp_path / "rel"
    assert main(["reliability", str(WIPER), "-o", str(rel), "-q", "--methods", "monte_carlo,fosm", "--samples", "2", "--no-plots"]) == 0
    head, samples = _csv(rel / "samples.csv")
    assert samples.shape[0] == 2 and np.all(samples[:, head.index("peak [rad]")] < 5e-3)
    report = (rel / "report.md").read_text(encoding="utf-8")
    assert "monte_carlo" in report and "FOSM" in report


def test_a_scene_run_from_a_later_t0_says_where_it_started(tmp_path):
    """``clearsim run`` of a scene with ``t0 = 0.25`` (``cycles = 2``: t_end = t0 + 2 s): summary.json
    and summary.md give the window the run covered, t0 as well as t_end, and the first output
    time is t0. Before: both said only ``t_end = 2.25 s``, so a reader took it for a 2.25 s run."""
    import json

    from clearsim.cli import main

    path = tmp_path / "wiper_t0.toml"
    path.write_text(WIPER.read_text(encoding="utf-8").replace("cycles = 2 ", "t0 = 0.25\ncycles = 2 "), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out), "-q", "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["t0"] == 0.25 and summary["t_end"] == pytest.approx(2.25, abs=1e-12)
    head, data = _csv(out / "bodies.csv")
    assert data[0, 0] == summary["t0"]
    assert "t0 = 0.25 s, t_end = 2.25 s" in (out / "summary.md").read_text(encoding="utf-8")


@pytest.mark.parametrize(("options", "field", "value"), [({"t_out": [0.0, 0.05, 0.2]}, "t_out[2]", 0.2), ({"t0": 0.05, "t_out": [0.0, 0.1]}, "t_out[0]", 0.0)])
def test_output_times_the_run_would_drop_are_refused(options, field, value):
    """``simulate(0.1, t_out=...)`` with a time past t_end or before t0: an InputError naming the
    field and value before anything runs. Before: the run dropped the times outside [t0, t_end]
    without a word (a Result of 1 output for t_out = [0, 0.2])."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    with pytest.raises(clearsim.InputError, match=re.escape(f"invalid {field} = {value}")) as info:
        m.simulate(0.1, progress=False, **options)
    assert info.value.field == field
