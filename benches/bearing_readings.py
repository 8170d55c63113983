"""The big-end bearing of scenes/con_rod_bearing.toml (Flores, Claro & Ambrósio 2006, 720° load
diagram at 2 000 rpm) with each film and with mass-conserving cavitation: its minimum film, peak
pressure, oil flow and friction power over the last of three load cycles, and what each costs
(steps, right-hand sides, CPU seconds of the run). The numbers of docs/examples.md and of
docs/physics.md §4, *Mass-conserving cavitation*:

    python benches/bearing_readings.py                 # short, long, finite, finite + jfo
    python benches/bearing_readings.py finite jfo      # some of them
    python benches/bearing_readings.py jfo:360         # the first 360° of crank from the Reynolds
                                                       # film's periodic state: steps and CPU only
    python benches/bearing_readings.py jfo:360 jfo:720 finite:720   # docs/physics.md §4's cost table

Measured (shared 2-core machine, load 8-10): jfo:360 4 811 steps (2 487 rejected), 45 546 rhs,
24 CPU s; jfo:720 14 508 steps, 130 802 rhs, 74 CPU s; finite:720 499 steps, 6 515 rhs, 0.01 s
(before the content moved inside the evaluation: jfo:360 32 222 steps, 88 s; jfo:720 did not
finish in 490 s).
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from clearsim.scene import load_scene_file

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes" / "con_rod_bearing.toml"
OMEGA = 2000 * 2 * math.pi / 60
PERIOD = 4 * math.pi / OMEGA
#: film → (film, cavitation) of the scene's joint.
CASES = {"short": ("short", None), "long": ("long", None), "finite": ("finite", None), "jfo": ("finite", "jfo")}


def run(case: str, tmp: Path) -> dict:
    film, cavitation = CASES[case]
    text = SCENE.read_text(encoding="utf-8").replace('film = "finite" ', f'film = "{film}" ')
    if cavitation:
        text = text.replace(f'film = "{film}" ', f'film = "{film}"\ncavitation = "{cavitation}" ')
    path = tmp / f"con_rod_{case}.toml"
    path.write_text(text, encoding="utf-8")
    m = load_scene_file(path).mechanism
    cpu = time.process_time()
    res = m.simulate(3 * PERIOD, dt_out=PERIOD / 720, outputs=["states", "joints", "film"], extremes=["big-end"], extremes_from=2 * PERIOD, progress=False)
    cpu = time.process_time() - cpu
    ext = res.extremes("big-end", "film_thickness")
    last = res.t >= 2 * PERIOD - 1e-12
    t = res.t[last]

    def mean(v: np.ndarray) -> float:
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)) / (t[-1] - t[0]))

    flow, peak, loss = res.flow("big-end")[last], res.peak_pressure("big-end")[last], res.power_loss("big-end")[last]
    return {
        "case": case, "steps": res.stats["steps"], "rejected": res.stats["rejected_steps"], "rhs": res.stats["rhs_evaluations"], "cpu_s": round(cpu, 2),
        "h_min_um": round(ext.min * 1e6, 4), "at_deg": round(math.degrees(OMEGA * ext.t_min) % 720, 1),
        "p_max_MPa": round(float(peak.max()) * 1e-6, 3), "p_max_at_deg": round(math.degrees(OMEGA * t[int(np.argmax(peak))]) % 720, 1),
        "side_cm3_s": round(mean(flow[:, 0]) * 1e6, 3), "supply_cm3_s": round(mean(flow[:, 1]) * 1e6, 3),
        "loss_mean_W": round(mean(loss), 2), "loss_peak_W": round(float(loss.max()), 2),
        "T_end_K": round(float(res.temperature("big-end")[-1]), 3),
    }  # fmt: skip


def probe(case: str, degrees: float, tmp: Path) -> dict:
    """What ``degrees`` of crank cost with the film of ``case`` from the default film's state at
    the start of its third cycle (periodic): steps, right-hand sides, Newton matrices, CPU s."""
    ref = load_scene_file(SCENE).mechanism.simulate(2 * PERIOD, dt_out=PERIOD / 720, progress=False)
    e0 = ref.eccentricity("big-end")[-1]
    film, cavitation = CASES[case]
    text = SCENE.read_text(encoding="utf-8").replace('film = "finite" ', f'film = "{film}" ')
    if cavitation:
        text = text.replace(f'film = "{film}" ', f'film = "{film}"\ncavitation = "{cavitation}" ')
    text = text.replace('model = "lubricated"', f'model = "lubricated"\ninitial_eccentricity = [{float(e0[0])!r}, {float(e0[1])!r}]')
    path = tmp / f"con_rod_{case}_probe.toml"
    path.write_text(text, encoding="utf-8")
    m = load_scene_file(path).mechanism
    cpu = time.process_time()
    res = m.simulate(2 * PERIOD + PERIOD * degrees / 720, t0=2 * PERIOD, dt_out=PERIOD / 720, progress=False)
    cpu = time.process_time() - cpu
    s = res.stats
    return {"case": case, "degrees": degrees, "steps": s["steps"], "rejected": s["rejected_steps"], "rhs": s["rhs_evaluations"], "jacobians": s["jacobians"], "cpu_s": round(cpu, 2)}


def main(cases: list) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            name, _, degrees = case.partition(":")
            print(probe(name, float(degrees), Path(tmp)) if degrees else run(case, Path(tmp)), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or list(CASES))
