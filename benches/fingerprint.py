"""Fingerprints of what a set of runs computes, to show a restructuring changed no number.

Every fixture model (ideal, dry and lubricated slider-crank and nine-bar, the stiff μ = 0.04 Pa s
nine-bar) with every integrator, every example scene with its own settings, and a few study
evaluations (the peaks the integrator tracks between output samples) are run; each prints one
line: its step statistics (steps, rejected, steps to a switch, right-hand sides, Jacobians, t
reached) and a SHA-256 of every number it returned (states, joint channels, impacts, violation,
peaks) except wall times. Two commits compute the same numbers when their outputs are equal:

    python benches/fingerprint.py > before.txt      # on the old commit
    python benches/fingerprint.py > after.txt       # on the new one
    diff before.txt after.txt                       # empty: bit-identical

Runs are short (one crank cycle); the whole set takes about a minute.
"""

from __future__ import annotations

import hashlib
import math
import sys
import warnings
from pathlib import Path
from typing import Any, Callable, Dict, List

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))

from fixtures import CYCLE, MODELS  # noqa: E402

#: Integrators and the keywords each needs (rk4 takes a fixed step).
METHODS: Dict[str, Dict[str, Any]] = {
    "rk45": {},
    "dop853": {},
    "radau": {},
    "rodas4": {},
    "rk4": {"step": 2e-6},
}
#: Counters of a run's statistics that must match exactly.
STAT_KEYS = ("steps", "rejected_steps", "steps_to_switch", "rhs_evaluations", "jacobians", "t_reached")


def digest(value: Any, h: "hashlib._Hash", path: str = "") -> None:
    """Feed every number below ``value`` into ``h`` (keys sorted; wall times, the integrator's
    name, which the raw result carries since the core resolves ``"auto"``, and the count of
    force-law evaluations, a cost that a refactoring may lower without changing a number
    (``benches/perf_fingerprint.py`` keeps it), left out)."""
    if isinstance(value, dict):
        for key in sorted(value):
            if "wall" in str(key) or key in ("integrator", "force_evaluations"):
                continue
            h.update(str(key).encode())
            digest(value[key], h, f"{path}.{key}")
    elif isinstance(value, (list, tuple)):
        h.update(f"[{len(value)}".encode())
        for item in value:
            digest(item, h, path)
    elif isinstance(value, np.ndarray):
        h.update(str(value.shape).encode())
        h.update(np.ascontiguousarray(value, dtype=np.float64).tobytes() if value.dtype.kind in "fiub" else repr(value.tolist()).encode())
    elif isinstance(value, float):
        h.update(np.float64(value).tobytes())
    else:
        h.update(repr(value).encode())


def line(name: str, raw: Dict[str, Any]) -> str:
    stats = raw.get("stats", {})
    counts = " ".join(f"{k}={stats.get(k)!r}" for k in STAT_KEYS if k in stats)
    h = hashlib.sha256()
    digest(raw, h)
    err = raw.get("error")
    tail = f" error={str(err)[:60]!r}" if err else ""
    return f"{name:48s} {counts} sha={h.hexdigest()[:16]}{tail}"


def fixture_runs() -> List[str]:
    out = []
    for name, build in MODELS.items():
        family = "nine_bar" if name.startswith("nine") else "slider_crank"
        t_end = CYCLE[family]
        for method, extra in METHODS.items():
            if method == "rk4" and family == "nine_bar":
                extra = {"step": 2e-5}
            try:
                res = build().simulate(t_end, integrator=method, dt_out=t_end / 200, progress=False, **extra)
                out.append(line(f"{name}/{method}", res._raw))
            except Exception as e:  # a failure is part of the fingerprint
                out.append(f"{name + '/' + method:48s} raised {type(e).__name__}: {str(e)[:80]}")
    return out


def scene_runs() -> List[str]:
    from clearsim.scene import load_scene_file

    out = []
    for path in sorted((ROOT / "scenes").glob("*.toml")):
        try:
            scene = load_scene_file(path)
            res = scene.simulate()
            out.append(line(f"scene {path.name}", res._raw))
        except Exception as e:
            out.append(f"{'scene ' + path.name:48s} raised {type(e).__name__}: {str(e)[:80]}")
    return out


def study_runs() -> List[str]:
    from clearsim.models import nine_bar
    from clearsim.reliability import Normal, Output, Study

    out = []
    for joints in ("dry", "lubricated"):
        def build(clearance: float, joints: str = joints) -> Any:
            return nine_bar(joints, clearance=clearance)

        study = Study(build, {"clearance": Normal(0.5e-3, 0.02e-3)}, output=Output(body="slider9", component="y"), limit=1e-3, omega=-5 * math.pi, cycles=1)
        try:
            ev, _ = study.evaluate({"clearance": np.array([0.48e-3, 0.5e-3, 0.53e-3])})
            h = hashlib.sha256()
            digest({k: v for k, v in vars(ev).items()}, h)
            out.append(f"{'study nine_bar ' + joints:48s} sha={h.hexdigest()[:16]}")
        except Exception as e:
            out.append(f"{'study nine_bar ' + joints:48s} raised {type(e).__name__}: {str(e)[:80]}")
    return out


def main() -> None:
    warnings.simplefilter("ignore")
    for part in (fixture_runs, scene_runs, study_runs):
        for text in part():
            print(text, flush=True)


if __name__ == "__main__":
    main()
