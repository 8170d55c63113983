"""clearsim.progress: a long run shows a bar with the time left, and one switch
(``clearsim.set_progress`` or ``CLEARSIM_PROGRESS=0``) hides every bar. The bars' one-second
delay is set to zero here, so runs of a fraction of a second show what a long one would."""

from __future__ import annotations

import re

import pytest

import clearsim
from clearsim import models, progress


@pytest.fixture
def bars_at_once(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "_enabled", None)  # follow the environment, restored after
    monkeypatch.setattr(progress, "_is_terminal", lambda: True)  # pytest's capture is no terminal


def test_progress_shows_the_time_left_and_one_switch_hides_every_bar(capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch, bars_at_once: None) -> None:
    m = models.nine_bar("dry")
    m.simulate(3.0, dt_out=0.01)  # ~0.4 s of work: several refreshes of the bar (every 0.1 s)
    err = capfd.readouterr().err
    assert "simulating" in err and re.search(r"<\d\d:\d\d", err), err[-300:]  # elapsed<remaining, estimated
    clearsim.set_progress(False)
    m.simulate(0.2, dt_out=0.01)
    assert capfd.readouterr().err == ""
    progress._enabled = None  # back to the environment
    monkeypatch.setenv("CLEARSIM_PROGRESS", "0")
    m.simulate(0.2, dt_out=0.01)
    assert capfd.readouterr().err == ""
    monkeypatch.delenv("CLEARSIM_PROGRESS")
    m.simulate(0.2, dt_out=0.01)  # and shown again: the switches were what hid it
    assert "simulating" in capfd.readouterr().err


def test_a_bar_into_a_log_redraws_rarely(capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """Piped into a log (stderr no terminal), a text bar redraws every NON_TTY_INTERVAL seconds,
    not ten times a second (a user's 14 s pump run wrote ~140 carriage returns into the log)."""
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "_enabled", True)
    monkeypatch.setattr(progress, "_is_terminal", lambda: False)
    models.nine_bar("dry").simulate(3.0, dt_out=0.01)  # ~0.4 s: 4+ redraws in a terminal
    assert capfd.readouterr().err.count("\r") <= 3
    monkeypatch.setattr(progress, "_is_terminal", lambda: True)
    models.nine_bar("dry").simulate(3.0, dt_out=0.01)
    assert capfd.readouterr().err.count("\r") >= 4


def test_the_delay_is_one_second_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without ``delay`` a bar waits :data:`clearsim.progress.DELAY` = 1 s (short runs print
    nothing: test_clearance.py's ``test_a_short_run_shows_no_progress_bar``)."""
    monkeypatch.setattr(progress, "_enabled", True)
    assert progress.DELAY == 1.0
    for delay, want in ((None, 1.0), (0.0, 0.0)):
        b = progress.bar(10, "x", delay=delay)
        assert b.delay == want
        b.close()


def test_a_run_shorter_than_the_delay_creates_no_bar(monkeypatch: pytest.MonkeyPatch) -> None:
    """Nothing is made for a run that ends before the delay (in a notebook, every bar made was
    eleven widget models, never closed: 301 short runs left 3 311)."""
    from tqdm.std import tqdm

    monkeypatch.setattr(progress, "_enabled", True)
    before = len(tqdm._instances)
    models.slider_crank("dry").simulate(0.002, dt_out=1e-4)
    with progress.bar(10, "short") as b:
        b.update(10)
        assert len(tqdm._instances) == before


def test_a_notebook_bar_closes_every_widget_it_opened(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """A bar that goes away when done (the default) closes all the widget models it opened: the
    box, the bar, its labels and their layout and style models (tqdm closes the box only)."""
    from ipywidgets.widgets.widget import _instances
    from tqdm.notebook import tqdm as notebook_bar

    monkeypatch.setattr(progress, "_enabled", True)
    monkeypatch.setattr(progress, "bar_class", lambda: notebook_bar)
    before = len(_instances)
    with progress.bar(10, "long", delay=0.0) as b:
        b.update(5)
        assert len(_instances) - before >= 4  # shown: a box, a bar, two labels (and their models)
    assert len(_instances) == before


def test_form_shows_its_runs_and_iterations(capfd: pytest.CaptureFixture[str], bars_at_once: None) -> None:
    """FORM (minutes on a mechanism: 14 runs and more an iteration) counts its runs and shows
    the iteration, |u| and g in a bar, like the sampling methods' bars; a model without
    ``progress`` (a LimitState) or with it off shows none."""
    import time

    from clearsim.reliability import LimitState, Normal

    def g(x):
        time.sleep(0.05)  # a slow model: the bar refreshes (every 0.1 s)
        return 3.0 - x["a"] - 0.05 * x["b"] ** 2

    model = LimitState(g, {"a": Normal(0, 1), "b": Normal(0, 1)})
    model.form()
    assert capfd.readouterr().err == ""
    model.progress = True  # as a Study has it
    res = model.form()
    err = capfd.readouterr().err
    assert "FORM" in err and "iteration" in err and "|u|" in err, err[-300:]
    assert re.search(r"FORM: \d+run", err) and max(int(n) for n in re.findall(r"FORM: (\d+)run", err)) <= res.n_runs, err[-300:]
    model.progress = False
    model.form()
    assert capfd.readouterr().err == ""
