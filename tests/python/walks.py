"""The mechanisms of the user-path walks (tests/data/scenes: a toggle press, a shaper, a
walking-beam pump, a windscreen wiper), shared by the tests of the features each walk checked."""

from __future__ import annotations

import csv
import re
from pathlib import Path
from typing import List, Tuple

import numpy as np

SCENES = Path(__file__).resolve().parents[1] / "data" / "scenes"
TOGGLE = SCENES / "toggle_press.toml"
SHAPER = SCENES / "shaper.toml"
PUMP = SCENES / "beam_pump.toml"
WIPER = SCENES / "wiper.toml"


def pump_scene(tmp_path: Path, methods: str) -> Path:
    """The pump's scene with the [study]'s methods replaced and no [study.life] (its minutes of
    worn cycles are not what these tests look at)."""
    text = PUMP.read_text(encoding="utf-8")
    text = re.sub(r"^methods = \[[^]]*\]", f"methods = {methods}", text[: text.index("\n[study.life]")], count=1, flags=re.M)
    path = tmp_path / "pump.toml"
    path.write_text(text, encoding="utf-8")
    return path


def read_csv(path: Path) -> Tuple[List[str], np.ndarray]:
    """A clearsim CSV file: its header and its rows as numbers."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array(rows[1:], dtype=float)
