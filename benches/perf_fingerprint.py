"""The performance fingerprint: what a fixed set of runs costs, in counts that do not scatter.

Each run (dry, lubricated, heated, a chain, with and without the readings a run may ask for) is
made with default settings and its work counted: accepted steps, rejected steps, steps redone to
end on a switch, right-hand sides, Newton matrices (``jacobians``) and evaluations of the
clearance joints' force laws by every part of the run (``force_evaluations``: right-hand sides,
Newton matrices, outputs, tracked readings). The counts are stored in
``benches/perf_fingerprint.json``; ``tests/python/test_perf_fingerprint.py`` fails when a change
moves any of them, so a change of cost is never silent (issue 37: monitors that every lubricated
run paid for, 2.3–3.2× per RK45 step, showed in no step count). Timings stay with ``cargo
bench``; these are counts only, the same on every run of the same code.

    python benches/perf_fingerprint.py            # print the counts and what moved
    python benches/perf_fingerprint.py --update   # store them (say why in the commit message)

A change that moves the counts on purpose (a better step control, a new reading, a model change)
updates the file with ``--update`` and says in its commit message which counts moved and why.
``benches/fingerprint.py`` (the SHA of every number) stays the tool for refactorings that must
change no number at all. Takes a few seconds.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent))

import clearsim  # noqa: E402
from clearsim.models import nine_bar  # noqa: E402
from fixtures import CYCLE, MODELS  # noqa: E402

PATH = Path(__file__).resolve().parent / "perf_fingerprint.json"
#: The counts of a run's statistics that make its fingerprint.
COUNTS = ("steps", "rejected_steps", "steps_to_switch", "rhs_evaluations", "jacobians", "force_evaluations")


def heated() -> clearsim.Mechanism:
    """The lubricated nine-bar with the oil's temperature (Vogel's law, a heat balance of time
    constant 50 s from 40 °C; benches/thermal_cost.py's oil)."""
    vogel = clearsim.Vogel(0.4 * math.exp(-900.0 / (313.15 - 164.0)), 900.0, 164.0)
    thermal = clearsim.Thermal(ambient=313.15, heat_capacity=50.0, heat_transfer=1.0)
    return nine_bar("lubricated", clearance=0.5e-3, lubricated=clearsim.Lubricated(viscosity=vogel, length=0.05, thermal=thermal))


def chain(links: int = 20) -> clearsim.Mechanism:
    """A pendulum chain of ``links`` links (0.1 m, 1 kg, hanging at 30° below the horizontal
    under gravity), pinned end to end, every 4th joint a lubricated clearance joint (5 mm pin,
    0.1 mm clearance, μ = 0.1 Pa s, L = 10 mm), the others ideal."""
    m = clearsim.Mechanism()
    length, angle = 0.1, -math.pi / 6
    dx, dy = length * math.cos(angle), length * math.sin(angle)
    for i in range(links):
        m.add_body(f"link{i}", mass=1.0, inertia=length**2 / 12, position=((i + 0.5) * dx, (i + 0.5) * dy), angle=angle)
    for i in range(links):
        a, pa = ("ground", (0.0, 0.0)) if i == 0 else (f"link{i - 1}", (length / 2, 0.0))
        if i % 4 == 3:
            model = clearsim.Lubricated(viscosity=0.1, length=0.01)
            m.clearance_joint(f"c{i}", a, pa, f"link{i}", (-length / 2, 0.0), journal_radius=5e-3, clearance=1e-4, model=model)
        else:
            m.revolute(a, pa, f"link{i}", (-length / 2, 0.0))
    return m


#: name -> (mechanism builder, t_end [s], simulate's keywords): default settings unless named.
RUNS: Dict[str, Tuple[Callable[[], Any], float, Dict[str, Any]]] = {
    "slider_crank_dry, one cycle": (MODELS["slider_crank_dry"], CYCLE["slider_crank"], {}),
    "nine_bar_dry, 0.05 s": (MODELS["nine_bar_dry"], 0.05, {}),
    "slider_crank_lubricated, one cycle": (MODELS["slider_crank_lubricated"], CYCLE["slider_crank"], {}),
    "slider_crank_lubricated rk45, one cycle": (MODELS["slider_crank_lubricated"], CYCLE["slider_crank"], {"integrator": "rk45"}),
    "slider_crank_lubricated rk45 bearings, one cycle": (MODELS["slider_crank_lubricated"], CYCLE["slider_crank"], {"integrator": "rk45", "bearings": True}),
    "nine_bar_lubricated, one cycle": (MODELS["nine_bar_lubricated"], CYCLE["nine_bar"], {}),
    "nine_bar_lubricated bearings, one cycle": (MODELS["nine_bar_lubricated"], CYCLE["nine_bar"], {"bearings": True}),
    "nine_bar_lubricated extremes slider9, one cycle": (MODELS["nine_bar_lubricated"], CYCLE["nine_bar"], {"extremes": ["slider9"]}),
    "nine_bar_lubricated_mu004, one cycle": (MODELS["nine_bar_lubricated_mu004"], CYCLE["nine_bar"], {}),
    "nine_bar heated (Vogel, Thermal), 0.1 s": (heated, 0.1, {}),
    "chain of 20, lubricated every 4th, 0.05 s": (chain, 0.05, {}),
}


def measure() -> Dict[str, Dict[str, int]]:
    """The counts of every run of :data:`RUNS` (a failed run counts what it did before)."""
    out: Dict[str, Dict[str, int]] = {}
    for name, (build, t_end, kwargs) in RUNS.items():
        try:
            stats = build().simulate(t_end, progress=False, **kwargs).stats
        except clearsim.SimulationError as e:
            stats = e.result.stats if e.result is not None else {}
        out[name] = {k: int(stats.get(k, -1)) for k in COUNTS}
    return out


def stored() -> Dict[str, Dict[str, int]]:
    """The fingerprint in ``benches/perf_fingerprint.json`` (empty if there is none)."""
    return json.loads(PATH.read_text(encoding="utf-8"))["runs"] if PATH.exists() else {}


def differences(old: Dict[str, Dict[str, int]], new: Dict[str, Dict[str, int]]) -> List[str]:
    """One line per run whose counts moved (or that is new or gone), with the relative change."""
    lines = []
    for name in list(old) + [n for n in new if n not in old]:
        a, b = old.get(name), new.get(name)
        if a == b:
            continue
        if a is None or b is None:
            lines.append(f"{name}: {'new' if a is None else 'gone'}")
            continue
        moved = [f"{k} {a.get(k)} → {b.get(k)} ({(b.get(k, 0) - a.get(k, 0)) / max(a.get(k, 0), 1):+.1%})" for k in COUNTS if a.get(k) != b.get(k)]
        lines.append(f"{name}: " + ", ".join(moved))
    return lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--update", action="store_true", help=f"write the counts to {PATH.name}")
    args = ap.parse_args()
    new = measure()
    for name, counts in new.items():
        print(f"{name:52s} " + " ".join(f"{k}={v}" for k, v in counts.items()))
    diff = differences(stored(), new)
    print("\n" + ("\n".join(["moved against " + PATH.name + ":", *diff]) if diff else f"as stored in {PATH.name}"))
    if args.update:
        PATH.write_text(json.dumps({"about": "counts of benches/perf_fingerprint.py's runs; update with --update and say why in the commit", "runs": new}, indent=1) + "\n", encoding="utf-8")
        print("wrote", PATH)


if __name__ == "__main__":
    main()
