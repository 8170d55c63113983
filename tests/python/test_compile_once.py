"""Each description is compiled once (issue 29, criterion 3): a scene file is checked by the core
when it loads, and its run uses that compiled model instead of compiling it a second time."""

from __future__ import annotations

from pathlib import Path
from typing import Any, List

import pytest

from clearsim import running
from clearsim.scene import load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def test_a_scene_compiles_its_mechanism_once(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: List[Any] = []
    real = running._core.compile

    def counting(description: Any) -> Any:
        calls.append(description)
        return real(description)

    monkeypatch.setattr(running._core, "compile", counting)
    scene = load_scene_file(SCENES / "slider_crank.toml").with_overrides(t_end=0.01)
    assert len(calls) == 1  # the load's check
    scene.run(ideal=False)
    assert len(calls) == 1  # the run reused it
