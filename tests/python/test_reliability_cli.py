"""`clearsim reliability scene.toml` and the scene's [study] table."""

import csv
from pathlib import Path

import pytest

from clearsim.cli import main
from clearsim.errors import InputError
from clearsim.scene import load_scene_file
from clearsim.reliability import Study
from walks import PUMP, pump_scene as _pump_scene

pytest.importorskip("openturns", reason="the rare-event methods need clearsim[uq]")

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "nine_bar_reliability.toml"


def test_cli_writes_tables_figure_and_report(tmp_path):
    out = tmp_path / "rel"
    # Without the scene's [study.tolerance] table: its design (seven FORM analyses, three
    # quarters of the time) is not what this test checks.
    text = SCENE.read_text()
    start = text.index("[study.tolerance]")
    end = text.index("\n[", start + 1) if "\n[" in text[start + 1 :] else len(text)
    scene = tmp_path / SCENE.name
    scene.write_text(text[:start] + text[end:])
    code = main(["reliability", str(scene), "-o", str(out), "--methods", "monte_carlo,form", "--samples", "16", "-q"])
    assert code == 0
    rows = list(csv.DictReader((out / "reliability.csv").open()))
    assert [r["method"] for r in rows] == ["monte_carlo", "form"]
    form = rows[1]
    assert 1e-5 < float(form["pf"]) < 1e-3 and int(form["runs"]) > 10  # the scene's limit: p_f ≈ 1e-4
    samples = list(csv.DictReader((out / "samples.csv").open()))
    assert len(samples) == 16 and {"A.clearance [m]", "B.clearance [m]", "peak [m]"} <= set(samples[0])
    assert (out / "reliability.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "FOSM" in (out / "report.md").read_text()


def test_study_inputs_are_set_by_path():
    scene = load_scene_file(SCENE)
    s = scene.study
    assert set(s.inputs) == {"A.clearance", "B.clearance"} and s.limit == 1.1e-3
    m = scene.mechanism.with_values({"B.clearance": 6e-4})
    assert m.description()["clearance_joints"][1]["clearance"] == 6e-4
    assert scene.mechanism.description()["clearance_joints"][1]["clearance"] == 5e-4


@pytest.mark.parametrize(
    "edit, field, words",
    [
        (("limit = 1.1e-3", ""), None, "missing key 'limit'"),
        (('path = "B.clearance"', 'path = "Q.clearance"'), "path", "no element named 'Q'"),
        (('distribution = "normal"\nmean = 0.5e-3\nstd = 0.05e-3\n\n[study.tolerance]', 'distribution = "normal"\nmean = 0.5e-3\nstd = -0.05e-3\n\n[study.tolerance]'), "std", "must not be negative"),
        (('methods = ["form", "importance_sampling", "sobol"]', 'methods = ["form", "guess"]'), "methods", "guess"),
        # the window and the estimators' settings (walk 5: named without their line before)
        (("cycles = 1.0", "cycles = 1.0\nskip_cycles = -1.0"), "skip_cycles", "invalid study.skip_cycles = -1.0"),
        (("cycles = 1.0", "cycles = 0.0"), "cycles", "invalid study.cycles = 0.0"),
        (("cov = 0.1", "cov = -0.1"), "cov", "invalid study.cov = -0.1"),
        (("cycles = 1.0", "cycles = 1.0\nbin_width = 0.0"), "bin_width", "invalid study.bin_width = 0.0"),
    ],
)
def test_bad_study_tables_are_named(tmp_path, edit, field, words):
    text = SCENE.read_text()
    assert edit[0] in text
    path = tmp_path / "s.toml"
    path.write_text(text.replace(edit[0], edit[1], 1))
    with pytest.raises(InputError) as e:
        load_scene_file(path)
    assert words in str(e.value)
    assert e.value.line is not None


def _system_scene(tmp_path):
    """The nine-bar scene with two outputs: the slider's y error (above) and joint B's smallest
    film thickness (below), over a quarter turn, without the tolerance design."""
    text = SCENE.read_text()
    text = text.replace('body = "slider9"\ncomponent = "y"\nquantity = "displacement"', "", 1)
    text = text.replace("limit = 1.1e-3", "", 1).replace("cycles = 1.0", "cycles = 0.25", 1)
    text = text[: text.index("[study.tolerance]")]
    text += '''
[[study.output]]
body = "slider9"
component = "y"
quantity = "displacement"
limit = 1.1e-3

[[study.output]]
joint = "B"
quantity = "film_thickness"
limit = 6e-5
side = "below"
'''
    path = tmp_path / "system.toml"
    path.write_text(text)
    return path


def test_cli_writes_every_failure_mode_of_a_system(tmp_path):
    path = _system_scene(tmp_path)
    s = load_scene_file(path).study
    assert [o.name for o in s.outputs] == ["slider9.y.displacement", "B.film_thickness"] and s.limits[1].side == "below"
    out = tmp_path / "rel"
    assert main(["reliability", str(path), "-o", str(out), "--methods", "monte_carlo", "--samples", "12", "-q"]) == 0
    rows = list(csv.DictReader((out / "reliability.csv").open()))
    assert [(r["method"], r["mode"]) for r in rows] == [("monte_carlo", "system"), ("monte_carlo", "slider9.y.displacement"), ("monte_carlo", "B.film_thickness")]
    assert float(rows[0]["pf"]) >= max(float(rows[1]["pf"]), float(rows[2]["pf"]))
    samples = list(csv.DictReader((out / "samples.csv").open()))
    assert len(samples) == 12 and {"slider9.y.displacement [m]", "B.film_thickness [m]"} <= set(samples[0])
    assert all(float(r["B.film_thickness [m]"]) < 5e-4 for r in samples)  # c (1 − ε_max) < c
    assert "series system" in (out / "report.md").read_text()


def test_outputs_are_given_one_way():
    text = SCENE.read_text().replace("seed = 0", 'seed = 0\n\n[[study.output]]\njoint = "B"\nquantity = "eccentricity"\nlimit = 0.9', 1)
    path = Path(__import__("tempfile").mkdtemp()) / "both.toml"
    path.write_text(text)
    with pytest.raises(InputError, match="either as \\[\\[study.output\\]\\] tables or by"):
        load_scene_file(path)


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


def test_the_reliability_report_says_fosm_skipped_the_film_output(tmp_path, capsys):
    """``clearsim reliability`` on the pump's series [study] (the plunger's error and the crank
    pin's film thickness, a lower limit) with ``--methods fosm``: FOSM analyses the error and
    says, on stdout and in report.md, that it skipped ``A.film_thickness`` and why. Before: the
    film output vanished from the FOSM results without a word."""
    from clearsim.cli import main

    text = PUMP.read_text(encoding="utf-8")
    scene = tmp_path / "pump.toml"
    scene.write_text(text[: text.index("\n[study.life]")], encoding="utf-8")
    out = tmp_path / "out"
    assert main(["reliability", str(scene), "-o", str(out), "--methods", "fosm", "--no-plots"]) == 0
    said = capsys.readouterr().out
    assert "fosm                 skips A.film_thickness (film thickness of joint A ≥ 5e-06 m): FOSM compares an error" in said
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "FOSM skipped `A.film_thickness` (film thickness of joint A ≥ 5e-06 m): FOSM compares an error with an allowable range [0, limit]" in report
    assert "FOSM `plunger.y.displacement` (nominal mechanism, 18° bins" in report


def test_sobol_alone_draws_its_panel(tmp_path):
    """`--methods sobol` alone: the figure has the Sobol panel only (there is no p_f to draw).
    It crashed after the runs with `IndexError: pop from empty list` while drawing."""
    from PIL import Image

    text = SCENE.read_text()
    start = text.index("[study.tolerance]")
    scene = tmp_path / SCENE.name
    scene.write_text(text[:start])
    out = tmp_path / "rel"
    assert main(["reliability", str(scene), "-o", str(out), "--methods", "sobol", "--samples", "8", "-q"]) == 0
    rows = list(csv.DictReader((out / "sobol.csv").open()))
    assert [r["input"] for r in rows] == ["A.clearance", "B.clearance"]
    with Image.open(out / "reliability.png") as im:
        assert im.size[0] < 1.5 * im.size[1]  # one panel, not a p_f panel beside it
    assert "Sobol indices" in (out / "report.md").read_text()
