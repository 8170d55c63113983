"""Every CSV file the command line writes heads a column ``name [unit]`` with a unit from one
list (ASCII, ``1`` for a dimensionless quantity), or by a bare name from one explicit list of
labels, counts, probabilities and reliability indices (issue 29: one CSV writer, shared headers
with units, one name per concept). On the old code: ``A.eps [-]``, ``bin_start_deg``,
``wall_time_s``, ``mean_depth_m``, ``angle_deg``, ``count``, ``B.clearance``."""

from __future__ import annotations

import csv
import re
from pathlib import Path
from typing import Dict, List

import pytest

from clearsim.cli import main
from clearsim.csvfile import column_name, report_header
from clearsim.reliability.report import input_column

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"

#: The units a header may carry (SI and the crank angle's degree, in ASCII).
UNITS = {"s", "m", "m/s", "m/s^2", "rad", "rad/s", "rad/s^2", "deg", "N", "N m", "W", "K", "kg", "kg m^2", "Pa", "Pa s", "J/K", "W/K", "1"}
#: Bare names: labels, counts, probabilities (with their interval ends), coefficients of
#: variation, reliability indices β and R, Sobol indices.
BARE = {
    "method", "mode", "output", "input", "error_unit",  # labels ("error_unit": the unit of the row)
    "runs", "cycle", "cycles", "samples",  # counts
    "pf", "interval_low", "interval_high", "cov", "beta", "reliability",  # probabilities, indices
    "first", "first_low", "first_high", "total", "total_low", "total_high",  # Sobol indices
}  # fmt: skip
SOBOL_AT_N = re.compile(r"(first|total)_n\d+")
#: A column whose unit varies by row, named in the file's ``error_unit`` column (as clearsim paper does).
ROW_UNIT = {"mu_s_error_unit", "sigma_s_error_unit"}
HEADER = re.compile(r"(?P<name>[A-Za-z0-9_.\-]+) \[(?P<unit>[^\]]+)\]")


def _bad_cells(header: List[str]) -> List[str]:
    bad = []
    for cell in header:
        m = HEADER.fullmatch(cell)
        if m is not None:
            ok = m["unit"] in UNITS
        else:
            ok = cell in BARE or SOBOL_AT_N.fullmatch(cell) is not None or (cell in ROW_UNIT and "error_unit" in header)
        if not ok:
            bad.append(cell)
    return bad


def _headers(out: Path) -> Dict[str, List[str]]:
    files = sorted(out.glob("*.csv"))
    assert files, out
    return {p.name: next(csv.reader(p.open(encoding="utf-8"))) for p in files}


def _check(out: Path, expect: set) -> Dict[str, List[str]]:
    headers = _headers(out)
    assert expect <= set(headers), sorted(headers)
    bad = {name: _bad_cells(h) for name, h in headers.items()}
    assert not any(bad.values()), {k: v for k, v in bad.items() if v}
    return headers


def _nine_bar_study(tmp_path: Path, *, system: bool) -> Path:
    """scenes/nine_bar_reliability.toml over a quarter turn without its tolerance design; with
    ``system``, two outputs: the slider's y error and joint B's eccentricity ratio ε (dimensionless)."""
    text = (SCENES / "nine_bar_reliability.toml").read_text()
    text = text[: text.index("[study.tolerance]")].replace("cycles = 1.0", "cycles = 0.25", 1)
    if system:
        text = text.replace('body = "slider9"\ncomponent = "y"\nquantity = "displacement"', "", 1).replace("limit = 1.1e-3", "", 1)
        text += '\n[[study.output]]\nbody = "slider9"\ncomponent = "y"\nquantity = "displacement"\nlimit = 1.1e-3\n'
        text += '\n[[study.output]]\njoint = "B"\nquantity = "eccentricity"\nlimit = 0.95\n'
    path = tmp_path / ("system.toml" if system else "one.toml")
    path.write_text(text)
    return path


def test_clearsim_run_headers(tmp_path):
    """bodies, ideal bodies, errors, joints (ε [1]) and the FOSM tables of [reliability]."""
    out = tmp_path / "run"
    assert main(["run", str(SCENES / "nine_bar.toml"), "-o", str(out), "--t-end", "0.4", "--no-plots", "-q"]) == 0
    names = {"bodies.csv", "bodies_ideal.csv", "errors.csv", "joints.csv"} | {f"reliability_{q}.csv" for q in ("displacement", "velocity", "acceleration")}
    headers = _check(out, names)
    assert "A.eps [1]" in headers["joints.csv"]
    for q, unit in (("displacement", "m"), ("velocity", "m/s"), ("acceleration", "m/s^2")):
        assert headers[f"reliability_{q}.csv"] == ["cycle", "bin_start [deg]", "bin_centre [deg]", "samples", f"mu_s [{unit}]", f"sigma_s [{unit}]",
                                                   f"mu_S [{unit}]", f"sigma_S [{unit}]", "beta", "reliability"]  # fmt: skip


def test_clearsim_reliability_headers(tmp_path):
    """reliability.csv, samples.csv, sobol.csv and fosm.csv of one output, then of a series
    system with a dimensionless output (ε), whose fosm.csv names each row's unit."""
    one, system = tmp_path / "one", tmp_path / "system"
    assert main(["reliability", str(_nine_bar_study(tmp_path, system=False)), "-o", str(one), "--methods", "monte_carlo,sobol,fosm", "--samples", "4", "--no-plots", "-q"]) == 0
    headers = _check(one, {"reliability.csv", "samples.csv", "sobol.csv", "fosm.csv"})
    assert headers["samples.csv"] == ["A.clearance [m]", "B.clearance [m]", "peak [m]", "first_passage_time [s]"]
    assert headers["fosm.csv"] == ["bin_start [deg]", "mu_s [m]", "sigma_s [m]", "beta", "reliability"]
    assert "wall_time [s]" in headers["reliability.csv"]
    assert main(["reliability", str(_nine_bar_study(tmp_path, system=True)), "-o", str(system), "--methods", "monte_carlo,fosm", "--samples", "3", "--no-plots", "-q"]) == 0
    headers = _check(system, {"reliability.csv", "samples.csv", "fosm.csv"})
    assert headers["samples.csv"][2:] == ["slider9.y.displacement [m]", "B.eccentricity [1]", "slider9.y.displacement.first_passage_time [s]", "B.eccentricity.first_passage_time [s]"]
    rows = list(csv.DictReader((system / "fosm.csv").open(encoding="utf-8")))
    assert {(r["output"], r["error_unit"]) for r in rows} == {("slider9.y.displacement", "m"), ("B.eccentricity", "1")}


def test_life_csv_headers(tmp_path):
    """life.csv of a [study.life] on a worn pin: peaks in the output's unit, depths in m."""
    base = (SCENES / "slider_crank.toml").read_text()
    base = base.replace("v1 = 1e-2                             # m/s", "v1 = 1e-2\nwear = { coefficient = 1e-2, hardness = 2e9, length = 0.02, feedback = true }", 1)
    assert "wear = {" in base
    base += (
        '\n[study]\nbody = "slider"\ncomponent = "x"\nquantity = "displacement"\nlimit = 0.59e-3\nskip_cycles = 1.0\nmethods = ["monte_carlo"]\nsamples = 3\n'
        '\n[[study.input]]\npath = "rod-slider.clearance"\ndistribution = "normal"\nmean = 0.5e-3\nstd = 0.02e-3\n'
        "\n[study.life]\ncycles = [0, 20]\n"
    )  # fmt: skip
    scene = tmp_path / "worn.toml"
    scene.write_text(base)
    out = tmp_path / "life"
    assert main(["reliability", str(scene), "-o", str(out), "--no-plots", "-q"]) == 0
    headers = _check(out, {"life.csv", "reliability.csv", "samples.csv"})
    assert headers["life.csv"] == ["cycles", "pf", "interval_low", "interval_high", "reliability", "mean_peak [m]", "max_peak [m]", "mean_depth [m]", "max_depth [m]"]


@pytest.mark.parametrize(
    "cell, ok",
    [("A.eps [1]", True), ("A.eps [-]", False), ("bin_start_deg", False), ("wall_time_s", False), ("t [s]", True), ("x [m or rad]", False),
     ("mu_s_error_unit", False), ("first_n16", True), ("beta", True)],
)  # fmt: skip
def test_the_check_itself(cell, ok):
    """The check refuses the old spellings (and a row-unit column without its error_unit column)."""
    assert (_bad_cells([cell]) == []) is ok


def test_one_spelling_of_a_dimensionless_unit():
    """``-``, ``1`` and no unit text all head a dimensionless column ``[1]``; report rows' keys
    map to the shared names; a random input's path takes its field's unit."""
    assert column_name("A.eps", "-") == column_name("A.eps", "1") == column_name("A.eps", "") == "A.eps [1]"
    assert report_header(["angle_deg", "count", "mu_s", "wall_time_s", "max_depth_m", "beta"], "m/s²") == [
        "bin_start [deg]", "samples", "mu_s [m/s^2]", "wall_time [s]", "max_depth [m]", "beta"
    ]  # fmt: skip
    assert input_column("B.clearance") == "B.clearance [m]" and input_column("B.viscosity") == "B.viscosity [Pa s]" and input_column("B.eps0") == "B.eps0 [1]"


def test_no_negative_zero_is_written(tmp_path: Path) -> None:
    """A dry joint's power loss is −0.0 in floating point; a CSV says 0.0 (the walk's pump read
    ``-0.0`` in joints.csv)."""
    from clearsim.csvfile import write_columns

    path = write_columns(tmp_path / "z.csv", [("t", "s", [0.0, 1.0]), ("power_loss", "W", [-0.0, -2.5])])
    text = path.read_text()
    assert "-0.0" not in text and "-2.5" in text
