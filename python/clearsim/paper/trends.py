"""The paper study's trend checks: each of the paper's claims, compared with our runs."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from .analysis import Analysis, _min_R, _r_beta
from .cases import CLEARANCE_CASES, QUANTITIES, _ANGLE_TOL
from .values import DISPLACEMENT_CYCLE_MINIMA, MINIMA, PEAKS

HOLDS, FAILS, NOT_EVALUABLE = "holds", "does not hold", "not evaluable"


# ====================================================================== trends


@dataclass
class Check:
    comparison: str
    ours: str
    paper: str
    status: str


@dataclass
class Trend:
    number: str
    statement: str
    checks: List[Check] = field(default_factory=list)

    @property
    def status(self) -> str:
        ev = [c for c in self.checks if c.status != NOT_EVALUABLE]
        if not ev:
            return NOT_EVALUABLE
        k = sum(c.status == HOLDS for c in ev)
        return HOLDS if k == len(ev) else FAILS

    @property
    def tally(self) -> str:
        ev = [c for c in self.checks if c.status != NOT_EVALUABLE]
        if not ev:
            return "0 of 0 comparisons evaluable"
        return f"{sum(c.status == HOLDS for c in ev)} of {len(ev)} comparisons hold"


def _status(ok: Optional[bool]) -> str:
    if ok is None:
        return NOT_EVALUABLE
    return HOLDS if ok else FAILS


def _fmt(x: Optional[float], spec: str = ".4g") -> str:
    if x is None or not np.isfinite(x):
        return "–"
    return format(x, spec)


def _lower_reliability(trend: Trend, base: Analysis, harsher: Analysis, q: str, claim: str) -> None:
    """Add the check "the harsher case's minimum reliability of ``q`` is below the base case's"."""
    rb, rh = _min_R(base, q), _min_R(harsher, q)
    ok = None if not (np.isfinite(rb) and np.isfinite(rh)) else bool(rh < rb)
    pb, ph = MINIMA[base.case.key][q][2], MINIMA[harsher.case.key][q][2]
    trend.checks.append(
        Check(
            f"{base.case.kind}, {q}: {claim}",
            f"{_r_beta(harsher.pooled[q])} vs {_r_beta(base.pooled[q])}",
            f"{ph:.4f} vs {pb:.4f}",
            _status(ok),
        )
    )


def _trends(an: Dict[str, Analysis], cycles: int) -> List[Trend]:
    t1 = Trend("1", "Lubricated acceleration errors are below the dry ones (every dry/lubricated pair)")
    for speed, c in (("5", "0.3"), ("5", "0.5"), ("5", "0.6"), ("8", "0.6")):
        d, l = an[f"dry-c{c}-{speed}pi"], an[f"lub-c{c}-{speed}pi"]
        pd, pl = d.peak_analysed["acceleration"], l.peak_analysed["acceleration"]
        rd, rl = d.rms["acceleration"], l.rms["acceleration"]
        ok = None if not all(np.isfinite([pd, pl, rd, rl])) else bool(pl < pd and rl < rd)
        ppd = abs(PEAKS[d.case.key]["acceleration"][0])
        ppl = abs(PEAKS[l.case.key]["acceleration"][0])
        t1.checks.append(
            Check(
                f"c = {c} mm, ω = −{speed}π: lubricated vs dry, peak and RMS |error|",
                f"peak {_fmt(pl)} vs {_fmt(pd)} m/s² ({_fmt(pl / pd, '.2g')}×); RMS {_fmt(rl)} vs {_fmt(rd)} m/s²",
                f"peak {ppl:g} vs {ppd:g} m/s² ({ppl / ppd:.2g}×)",
                _status(ok),
            )
        )
    t2 = Trend("2", "Larger clearance → lower minimum reliability (0.5 vs 0.3 mm at −5π, per quantity)")
    t3 = Trend("3", "Faster drive → lower velocity and acceleration reliability (−8π vs −5π at 0.6 mm)")
    for kind in ("dry", "lub"):
        for q in QUANTITIES:
            _lower_reliability(t2, an[f"{kind}-c0.3-5pi"], an[f"{kind}-c0.5-5pi"], q, "min R at 0.5 mm < at 0.3 mm")
        for q in ("velocity", "acceleration"):
            _lower_reliability(t3, an[f"{kind}-c0.6-5pi"], an[f"{kind}-c0.6-8pi"], q, "min R at 8π < at 5π")
    later = f"cycles 2–{cycles}" if cycles >= 3 else "cycles 2, 3, … (needs 3 or more cycles)"
    t4a = Trend("4a", f"Displacement reliability minima recur at the same crank angle each cycle (all {cycles} cycle(s), start-up cycle included, as in Fig. 11a)")
    t4b = Trend("4b", f"Displacement reliability minima recur at the same crank angle each cycle ({later}, after the start-up cycle)")
    for key in CLEARANCE_CASES:
        a = an[key]
        minima = a.per_cycle.cycle_minima() if a.per_cycle is not None else []
        paper = DISPLACEMENT_CYCLE_MINIMA.get(key)
        paper_txt = ", ".join(f"{ang:g}°" for ang, _ in paper) if paper else "– (one cycle shown)"
        for trend, rows in ((t4a, minima), (t4b, [m for m in minima if m["cycle"] >= 1])):
            mods = [m["angle"] % 360.0 for m in rows]
            ok = None if len(rows) < 2 else bool(np.ptp(mods) < _ANGLE_TOL)
            ours = ", ".join(f"{m['angle']:g}°" for m in rows) or "–"
            if len(rows) >= 2:
                ours += f" (mod 360°: {', '.join(f'{x:g}°' for x in mods)})"
            trend.checks.append(Check(f"{a.case.label}", ours, paper_txt if trend is t4a else "–", _status(ok)))
    return [t1, t2, t3, t4a, t4b]
