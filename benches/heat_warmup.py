"""Cost and accuracy of heated oil (issue 37 item 4; docs/physics.md §4, *Heat*): the oil
temperature is a state integrated with the mechanism.

1. Warm-up: a 20 kg rotor (gravity-loaded journal, R = 20 mm, c = 40 µm, L = 10 mm, 100 rad/s,
   short film, an ISO VG 32 oil) warming from 40 °C with C/hA = 30 s and 120 s, against the same
   run at the constant viscosity μ(40 °C): steps, rejected steps and wall time (best of 3), with
   RADAU5 (the default for a lubricated joint). Target: ≤ 2× the constant-viscosity run.
2. The steady temperature against the heat balance T = T_amb + P(μ(T))/hA (Petroff's loss of a
   centred journal, root found here by bisection) after 40 time constants, with the integrator's
   own steps and with steps held to h_max, and the printed power loss against Petroff's at the
   printed temperature. Target: within 0.5 % of the rise whatever the step size.

    python benches/heat_warmup.py

On main (2639dce), where the temperature was advanced once per accepted step outside the
integrator, the warm-ups took 93 384 and 166 993 steps (857× and 1 518× the constant-viscosity
run's 109 and 110; 3.1 and 7.5 s); with this change 120 and 120 (1.10× and 1.09×).
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any, Dict, Optional, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))

from heat_reference import L, OIL, T_AMB, fixed_point, petroff_loss, rotor  # noqa: E402

import clearsim  # noqa: E402

REPEATS = 3


def timed(m: clearsim.Mechanism, t_end: float, **kw: Any) -> Tuple[float, Any]:
    best, res = math.inf, None
    for _ in range(REPEATS):
        start = time.perf_counter()
        res = m.simulate(t_end, progress=False, **kw)
        best = min(best, time.perf_counter() - start)
        assert res.completed, res.failure
    return best, res


def warm_up() -> None:
    print("1. warm-up of a loaded rotor (20 kg, RADAU5), best of", REPEATS)
    print(f"   {'C/hA':>6} {'run':>6} | {'steps':>6} {'rejected':>8} {'wall ms':>8} | constant μ: {'steps':>6} {'wall ms':>8} | ratio steps, wall | T_end [K]")
    for cap, h_a, t_end in ((3.0, 0.1, 60.0), (12.0, 0.1, 240.0)):
        heated = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=clearsim.Thermal(T_AMB, cap, h_a)), 20.0, 9.81)
        plain = rotor(clearsim.Lubricated(viscosity=OIL.viscosity(T_AMB), length=L, film="short"), 20.0, 9.81)
        wh, rh = timed(heated, t_end, dt_out=t_end / 100)
        wp, rp = timed(plain, t_end, dt_out=t_end / 100)
        sh, sp = int(rh.stats["steps"]), int(rp.stats["steps"])
        print(
            f"   {cap / h_a:5.0f}s {t_end:5.0f}s | {sh:6d} {int(rh.stats['rejected_steps']):8d} {wh * 1e3:8.1f} |             {sp:6d} {wp * 1e3:8.1f} |"
            f" {sh / sp:5.2f}x {wh / wp:5.2f}x | {rh.temperature('pin')[-1]:.3f}"
        )


def steady() -> None:
    print("2. a centred rotor's steady temperature after 40 C/hA (C = 1 J/K, hA = 0.1 W/K)")
    cap, h_a = 1.0, 0.1
    want = fixed_point(h_a)
    thermal = clearsim.Thermal(T_AMB, cap, h_a)
    m = rotor(clearsim.Lubricated(viscosity=OIL, length=L, film="short", thermal=thermal), 1.0, 0.0)
    for h_max in (None, 10.0, 1.0, 0.1):
        kw: Dict[str, Optional[float]] = {} if h_max is None else {"h_max": h_max}
        res = m.simulate(40 * cap / h_a, dt_out=cap / h_a, progress=False, **kw)
        temp, p = res.temperature("pin")[-1], res.power_loss("pin")[-1]
        err = (temp - want) / (want - T_AMB)
        print(
            f"   h_max {str(h_max):>5}: {int(res.stats['steps']):5d} steps, T = {temp:.6f} K, balance {want:.6f} K:"
            f" {100 * err:+.5f} % of the rise; P = {p:.5f} W, Petroff at T {petroff_loss(OIL.viscosity(temp)):.5f} W"
        )


if __name__ == "__main__":
    warm_up()
    steady()
