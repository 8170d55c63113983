"""The forcing period of a mechanism: what a Poincaré section, a spectrum or a bifurcation
diagram strobes at when no period is given — one turn of a constant-speed driver, 2π/ω of a
harmonic driver or load, the period of a periodic load table in time.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping

from ..errors import InputError

#: Periods closer than this (relative) are the same forcing.
_SAME = 1e-9


def _periods(desc: Mapping[str, Any]) -> List[float]:
    out: List[float] = []
    for d in desc.get("drivers", []):
        law = d["law"]
        if law["kind"] == "constant_speed" and law["omega"] != 0:
            out.append(2 * math.pi / abs(float(law["omega"])))
        elif law["kind"] == "harmonic":
            out.append(2 * math.pi / float(law["omega"]))
    for f in desc.get("forces", []):
        for key in ("fx", "fy", "magnitude"):
            p = f.get(key)
            if not isinstance(p, Mapping):
                continue
            if p.get("kind") == "harmonic":
                out.append(2 * math.pi / float(p["omega"]))
            elif p.get("kind") == "table" and p["argument"]["kind"] == "time" and p["table"].get("period"):
                out.append(float(p["table"]["period"]))
    return out


def forcing_period(mechanism: Any) -> float:
    """The period [s] of a mechanism's forcing (a :class:`clearsim.Mechanism` or its
    description): 2π/|ω| of its constant-speed drivers, 2π/ω of its harmonic drivers and loads,
    the period of its periodic time tables: the longest of them, when every other divides it (a
    crank and a load at twice its frequency); an InputError when they do not, or when there is
    none — then give ``period=``."""
    desc: Dict[str, Any] = mechanism.description() if hasattr(mechanism, "description") else dict(mechanism)
    periods = _periods(desc)
    if not periods:
        raise InputError("invalid period = None: the mechanism has no periodic forcing (constant-speed or harmonic driver, harmonic load, periodic time table); give period= [s]", field="period", value=None)
    longest = max(periods)
    for p in periods:
        ratio = longest / p
        if abs(ratio - round(ratio)) > _SAME * ratio:
            raise InputError(
                f"invalid period = None: the forcings' periods {sorted(set(round(x, 12) for x in periods))} s are not commensurate; give period= [s]",
                field="period", value=None,
            )  # fmt: skip
    return longest


__all__ = ["forcing_period"]
