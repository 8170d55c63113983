"""Cycle jumping against simulating every cycle (issue 31, item 4; docs/reliability.md, "Reliability over life").

The dry slider-crank (c = 0.5 mm, 5000 rpm) with Archard wear fed back at its rod–slider pin,
the wear coefficient raised to k = 1e-2 so that 200 cycles wear ~0.1 mm (a real life's depth
in 200 turns). Its impacts are chaotic: a 1 nm change of the clearance changes the deepest bin
after 200 cycles by ±12 % and the peak by ±3 %, so both sides are ensembles of 8 mechanisms
with clearances 0.5 mm + 0…7 nm, compared by their means (± their standard error).

Every cycle: one run of 202 turns each: the worn state after 200 turns (its wear mark) and the
peak |x error| of the slider over turn 201–202. Cycle jumping: ``Study.life`` in blocks (1
settling turn + 1 analysed turn), the same quantities at N = 200, for several ``max_growth``.

    python benches/life_cycle_jumping.py [k]      (about 2 minutes on 2 cores)
"""

import math
import sys
import time

import numpy as np

import clearsim
from clearsim import Archard, Dry
from clearsim import reliability as rel
from clearsim.reliability.life import WEAR_BINS, StudyBlocks, life

RPM = 5000.0
LIFE = 200
ENSEMBLE = 8


def study(k: float, settle: float = 1.0) -> rel.Study:
    def build(clearance):
        return clearsim.models.slider_crank("dry", clearance=clearance, rpm=RPM, dry=Dry(wear=Archard(k, 2e9, 0.02, feedback=True)))

    return rel.Study(build, {"clearance": rel.Normal(0.5e-3, 1e-9)}, rel.Output(body="slider", component="x"), limit=1e-3,
                     omega=RPM * 2 * math.pi / 60, cycles=1.0, skip_cycles=settle, progress=False)  # fmt: skip


def groove(depth: np.ndarray, width: int = 11) -> float:
    """Deepest mean depth over ``width`` adjacent 1° bins (the contact wanders over ~10°)."""
    wrapped = np.concatenate([depth[-width:], depth, depth[:width]])
    return float(np.convolve(wrapped, np.ones(width) / width, "same")[width:-width].max())


def measures(peaks: np.ndarray, worn: np.ndarray) -> dict:
    b, j = worn[:, :WEAR_BINS], worn[:, WEAR_BINS : 2 * WEAR_BINS]
    return {
        "peak": peaks,
        "volume": b.sum(axis=1),  # ∝ the worn volume (bearing)
        "groove bearing": np.array([groove(x) for x in b]),
        "groove journal": np.array([groove(x) for x in j]),
        "deepest bin bearing": b.max(axis=1),
        "deepest bin journal": j.max(axis=1),
    }


def every_cycle(k: float) -> dict:
    st = study(k, settle=LIFE + 1.0)
    worn = np.zeros((ENSEMBLE, 2 * WEAR_BINS))

    def mark(_k, _description, settings):
        settings["wear_mark"] = LIFE * 60.0 / RPM

    def keep(i, raw):
        book = raw["wear"][0]
        worn[i] = np.concatenate([book["bearing_at_mark"], book["journal_at_mark"]])

    t = time.perf_counter()
    ev, _ = st.run_samples(st.values(np.arange(ENSEMBLE, dtype=float)[:, None]), on_job=mark, on_raw=keep, show=False)
    print(f"every cycle: {ENSEMBLE} runs of {LIFE + 2} turns, {time.perf_counter() - t:.1f} s")
    return measures(ev.values[:, 0], worn)


def main() -> None:
    k = float(sys.argv[1]) if len(sys.argv) > 1 else 1e-2
    ref = every_cycle(k)
    print("  " + "  ".join(f"{name} {v.mean() * (1e3 if name == 'peak' else 1e6):.4g} {'mm' if name == 'peak' else 'µm'} (±{v.std(ddof=1) / v.mean():.0%})"
                           for name, v in ref.items() if name != "volume"))
    for growth in (0.005, 0.01, 0.02, 0.04):
        runner = StudyBlocks(study(k))
        t = time.perf_counter()
        res = life(runner, np.arange(ENSEMBLE, dtype=float)[:, None], [LIFE], max_growth=growth, surfaces=runner.surfaces)
        wall = time.perf_counter() - t
        got = measures(res.peaks[:, -1, 0], res.worn)
        cells = []
        for name, v in got.items():
            se = math.sqrt(v.var(ddof=1) / v.size + ref[name].var(ddof=1) / v.size) / ref[name].mean()
            cells.append(f"{name} {v.mean() / ref[name].mean() - 1:+.1%} (±{se:.1%})")
        print(f"max_growth {growth:5.3f}: {res.blocks.mean():.1f} blocks ({res.blocks.mean() * 2:.0f} turns) a sample, {wall:.1f} s: " + ", ".join(cells))


if __name__ == "__main__":
    main()
