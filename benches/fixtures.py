"""The Python models whose descriptions the Rust tests and benches load from ``tests/data``.

Run ``python benches/fixtures.py`` to (re)write the JSON fixtures after a model changes;
``tests/python/test_fixtures.py`` fails while a fixture differs from the current model.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Callable, Dict

from clearsim.joints import Lubricated
from clearsim.models import nine_bar, slider_crank

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"

#: fixture name -> builder of the Python model (docs/physics.md §7, §8).
MODELS: Dict[str, Callable[[], Any]] = {
    "nine_bar_ideal": lambda: nine_bar("ideal"),
    "nine_bar_dry": lambda: nine_bar("dry", clearance=0.5e-3),
    "nine_bar_lubricated": lambda: nine_bar("lubricated", clearance=0.5e-3),
    # The stiff hard case: μ = 0.04 Pa s, the journals sink into the film-to-contact transition.
    "nine_bar_lubricated_mu004": lambda: nine_bar(
        "lubricated", clearance=0.5e-3, lubricated=Lubricated(viscosity=0.04, length=0.05)
    ),
    "slider_crank_ideal": lambda: slider_crank("ideal"),
    "slider_crank_dry": lambda: slider_crank("dry"),
    "slider_crank_lubricated": lambda: slider_crank("lubricated"),
}

#: One crank cycle [s] of each family at its default speed.
CYCLE = {"nine_bar": 2 * math.pi / (5 * math.pi), "slider_crank": 60.0 / 5000.0}


def plain(desc: Any) -> Any:
    """The description as JSON would give it back (tuples become lists)."""
    return json.loads(json.dumps(desc))


def fixture_path(name: str) -> Path:
    return DATA / f"{name}.json"


def main() -> None:
    for name, build in MODELS.items():
        path = fixture_path(name)
        path.write_text(json.dumps(plain(build().description()), indent=1, sort_keys=True) + "\n")
        print("wrote", path)


if __name__ == "__main__":
    main()
