"""Runs that start at any t0 (issue 28, item 1; docs/physics.md §1 "Initial state"): the pose
given is the pose at t = 0, the drivers' reference time, and the state at t0 follows the drivers
from it on its branch, so a run from t0 continues a run from 0."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.reliability import Normal, Output, Study

SLIDER_CRANK_TURN = 60.0 / 5000.0  # [s] at the model's 5000 rpm
NINE_BAR_TURN = 2 * math.pi / (5 * math.pi)  # [s] at ω = −5π rad/s
TIGHT = dict(rtol=1e-11, atol=1e-13, progress=False)


@pytest.mark.parametrize("model, turn", [("slider_crank", SLIDER_CRANK_TURN), ("nine_bar", NINE_BAR_TURN)])
@pytest.mark.parametrize("turns", [0.25, 1.0, 2.5])
def test_a_run_from_t0_continues_the_run_from_0(model, turn, turns):
    """Ideal (one-DOF-free, fully driven) mechanisms: positions and angles of a run started at
    t0 = T/4, T, 2.5 T match the run from 0 at the same times to 1e-8 (m, rad). Before: the
    assembly at t0 started from the pose given (t = 0) and the slider-crank's rod flipped by
    180° at t0 = T; the check then blamed the user's joint points ("moves body 'crank' by
    0.0354 m and 90° from the pose given"), and the nine-bar did not assemble at all."""
    m = getattr(models, model)("ideal")
    t0 = turns * turn
    grid = t0 + np.linspace(0.0, 0.25 * turn, 26)
    late = m.simulate(grid[-1], t0=t0, t_out=grid, **TIGHT)
    whole = m.simulate(grid[-1], t_out=np.concatenate([[0.0], grid]), **TIGHT)
    assert late.completed and whole.completed
    for body in m.body_names:
        assert np.max(np.abs(late.position(body) - whole.position(body)[1:])) < 1e-8, body
        # The velocities at t0 too: the drivers' rates carried through the loop.
        assert np.max(np.abs(late.velocity(body)[0] - whole.velocity(body)[1])) < 1e-6, body


def test_the_pose_is_checked_where_it_was_given():
    """A crank's joint point given in the global frame is caught whatever t0 (the check compares
    the pose given with the assembly at t = 0), and a sound pose passes at any t0."""
    m = models.slider_crank("ideal")
    for t0 in (0.0, 0.3 * SLIDER_CRANK_TURN, 1.5 * SLIDER_CRANK_TURN):
        assert m.check_assembly(t0).shape == (9,)
    q = m.check_assembly(0.25 * SLIDER_CRANK_TURN)
    assert q[2] == pytest.approx(math.pi / 2, abs=1e-12)  # the crank's angle at T/4
    assert q[0:2] == pytest.approx([0.0, 0.025], abs=1e-12)  # its centroid on the circle, not moved back


def test_a_study_skips_start_up_cycles_on_a_slider_crank():
    """``Study(skip_cycles=k)`` analyses turns k … k + cycles of a run from 0; before, a
    skip that left the crank anywhere but at its starting angle was an AssemblyError blaming
    the joint points."""
    omega = 5000 * 2 * math.pi / 60
    study = Study(lambda clearance: models.slider_crank("dry", clearance=clearance), {"clearance": Normal(0.5e-3, 0.02e-3)},
                  Output(body="slider", component="x", quantity="acceleration"), 1e6, omega=omega, cycles=0.5,
                  skip_cycles=1.25, progress=False)  # fmt: skip
    est = study.monte_carlo(2)
    assert est.n_runs == 2 and not est.failures
    assert np.all(est.peaks > 0)


def test_a_start_beyond_a_dead_centre_names_it():
    """A slider-crank whose crank (50 mm) is longer than its rod (40 mm) can follow its driver
    only up to 53.1° (sin θ = 0.04/0.05): a start at T/4 (90°) is an AssemblyError naming the
    dead centre, its time and the driver, not a bare Newton failure."""
    m = models.slider_crank("ideal", crank_length=0.05, rod_length=0.04)
    with pytest.raises(clearsim.AssemblyError) as info:
        m.simulate(0.3 * SLIDER_CRANK_TURN, t0=0.25 * SLIDER_CRANK_TURN, progress=False)
    msg = str(info.value)
    t_dead = math.asin(0.04 / 0.05) / (5000 * 2 * math.pi / 60)
    assert "dead centre" in msg and "driver 'crank-drive'" in msg and "'rod' perpendicular to the guide" in msg
    assert info.value.t == pytest.approx(t_dead, rel=1e-6)


SCENE = Path(__file__).resolve().parents[2] / "scenes" / "slider_crank.toml"
STUDY = """
[study]
body = "slider"
component = "x"
quantity = "acceleration"
limit = 1e6
cycles = 0.25
skip_cycles = {skip}
methods = ["monte_carlo"]
samples = 2

[[study.input]]
path = "rod-slider.clearance"
distribution = "normal"
mean = 0.5e-3
std = 0.02e-3
"""


def scene_text(t0: float = 0.0, skip: float = 0.0, rod_length: float = 0.12) -> str:
    """The shipped slider-crank scene, started at ``t0`` for a quarter turn, with a [study] that
    skips ``skip`` turns; ``rod_length`` 0.04 m makes the crank (0.05 m) the longer."""
    text = SCENE.read_text(encoding="utf-8")
    text = text.replace("cycles = 2  ", f"t0 = {t0}\ncycles = 0.25  ", 1)
    if rod_length != 0.12:
        half = rod_length / 2
        text = text.replace("ends = [[0.05, 0.0], [0.16999999999999998, 0.0]]", f"ends = [[0.05, 0.0], [{0.05 + rod_length}, 0.0]]")
        text = text.replace("position = [0.16999999999999998, 0.0]", f"position = [{0.05 + rod_length}, 0.0]")
        text = text.replace("points = [[0.025, 0.0], [-0.06, 0.0]]", f"points = [[0.025, 0.0], [{-half}, 0.0]]")
        text = text.replace("journal_point = [0.06, 0.0]", f"journal_point = [{half}, 0.0]")
    return text + STUDY.format(skip=skip)


def test_both_commands_start_anywhere(tmp_path, capsys):
    """``clearsim run`` on a scene whose [simulation] starts at t0 = T/4, and ``clearsim
    reliability`` on one whose [study] skips 1.25 turns; before, both stopped at the pose check
    ("the assembly at t0 = 0.003 s moves body 'crank' by 0.0354 m and 90°")."""
    from clearsim.cli import main

    path = tmp_path / "sc.toml"
    path.write_text(scene_text(t0=0.25 * SLIDER_CRANK_TURN, skip=1.25), encoding="utf-8")
    assert main(["run", str(path), "-o", str(tmp_path / "run"), "--no-plots", "-q"]) == 0
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["run"]["failure"] is None
    assert main(["reliability", str(path), "-o", str(tmp_path / "rel"), "--no-plots", "-q"]) == 0


def test_reliability_names_a_dead_centre_before_its_window_in_one_line(tmp_path, capsys):
    """A slider-crank whose crank is longer than its rod cannot reach the window after 1.25
    turns: one line naming the dead centre and the driver, exit code 2, no traceback."""
    from clearsim.cli import main

    path = tmp_path / "lock.toml"
    path.write_text(scene_text(skip=1.25, rod_length=0.04), encoding="utf-8")
    assert main(["reliability", str(path), "-o", str(tmp_path / "rel"), "--no-plots", "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "dead centre" in err and "driver 'crank-drive'" in err
