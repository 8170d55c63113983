"""Cost of heat and roughness on a lubricated cycle (issue 30 item 6): the paper's lubricated
nine-bar (docs/physics.md §7, c = 0.5 mm, μ = 0.4 Pa s at 40 °C, L = 50 mm) run over one crank
cycle four ways — a constant viscosity (the plain film), with the oil temperature (Vogel's law,
``Thermal``), with rough surfaces (``roughness``, ``boundary_friction``) and with both — each the
best of 5 wall times, and the ratios to the plain film (target ≤ 1.5×):

    python benches/thermal_cost.py

A timing only: the tests check what the runs compute (tests/python/test_heat.py).
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Dict, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent))

import clearsim  # noqa: E402
from clearsim.models import nine_bar  # noqa: E402
from fixtures import CYCLE  # noqa: E402

#: An oil of μ = 0.4 Pa s at 313.15 K (the paper's value, at 40 °C here): b = 900 K, c = 164 K.
VOGEL = clearsim.Vogel(0.4 * math.exp(-900.0 / (313.15 - 164.0)), 900.0, 164.0)
#: Oil and housing of 50 J/K, cooled at 1 W/K (time constant 50 s), from 40 °C.
THERMAL = clearsim.Thermal(ambient=313.15, heat_capacity=50.0, heat_transfer=1.0)
REPEATS = 5


def variants() -> Dict[str, clearsim.Lubricated]:
    return {
        "constant viscosity": clearsim.Lubricated(viscosity=0.4, length=0.05),
        "heat": clearsim.Lubricated(viscosity=VOGEL, length=0.05, thermal=THERMAL),
        "roughness": clearsim.Lubricated(viscosity=0.4, length=0.05, roughness=0.5e-6, boundary_friction=0.1),
        "heat + roughness": clearsim.Lubricated(viscosity=VOGEL, length=0.05, thermal=THERMAL, roughness=0.5e-6, boundary_friction=0.1),
    }


def best_time(lub: clearsim.Lubricated) -> Tuple[float, int]:
    """Best wall time [s] of REPEATS runs and the run's accepted steps."""
    m = nine_bar("lubricated", clearance=0.5e-3, lubricated=lub)
    best, steps = math.inf, 0
    for _ in range(REPEATS):
        start = time.perf_counter()
        res = m.simulate(CYCLE["nine_bar"], dt_out=1e-3, progress=False)
        best = min(best, time.perf_counter() - start)
        assert res.completed, res.failure
        steps = int(res.stats["steps"])
    return best, steps


def main() -> None:
    times = {name: best_time(lub) for name, lub in variants().items()}
    base = times["constant viscosity"][0]
    print(f"lubricated nine-bar, one cycle ({CYCLE['nine_bar']:.3f} s), best of {REPEATS}:")
    for name, (t, steps) in times.items():
        print(f"  {name:20s} {t * 1e3:8.1f} ms  {t / base:5.2f}x  {steps} steps")


if __name__ == "__main__":
    main()
