"""`clearsim reliability scene.toml` and the scene's [study] table."""

import csv
from pathlib import Path

import pytest

from clearsim.cli import main
from clearsim.errors import InputError
from clearsim.scene import load_scene_file

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
    assert len(samples) == 16 and {"A.clearance", "B.clearance", "peak [m]"} <= set(samples[0])
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
