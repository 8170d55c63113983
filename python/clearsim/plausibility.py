"""Plausibility of a mechanism's numbers: a :class:`~clearsim.PlausibilityWarning` for a value
that is valid but looks like a unit slip (millimetres where clearsim takes metres, centipoise
where it takes Pa·s) or lies outside the range the film laws are meant for. Each message names
the element, the field, the value and the unit clearsim expected.

Checks of one joint run when it is added (:func:`joint_findings`); those that need the whole
mechanism — its size, its pose given against the assembly — are the core's, when it compiles
(``rust/compile/plausibility.rs``, ``rust/pose.rs``: ``CompiledModel.warnings``). Each finding is
warned once per mechanism (:func:`warn_new`), not once per run, at the user's line.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from typing import Any, Dict, List, Optional, Sequence, Set, Tuple

from ._core import output_point_finding
from .errors import PlausibilityWarning
from .joints import MICROMETRE_FILM_RATIO

#: Dynamic viscosities [Pa s] of liquid lubricants at their working temperature lie inside this
#: range (water 0.001, engine oils hot 0.005–0.05, cold gear oils up to a few Pa s).
VISCOSITY_RANGE = (1e-4, 5.0)
#: R_j/c for which the film laws (thin-film Reynolds theory, smooth surfaces) are meant: c ≪ R_j
#: (machine bearings R_j/c ≈ 1000; the paper's exaggerated clearances reach R_j/c ≈ 16), and a
#: clearance well above the roughness of machined surfaces (≈ 1 µm at R_j = 10 mm).
FILM_RATIO_RANGE = (10.0, 1e4)
#: c/R_j above which a dry clearance warns (a lubricated one above 0.25 is an error).
DRY_CLEARANCE_RATIO = 0.25
#: A finding: the field (``clearance joint 'pin'.viscosity``) and the message.
Finding = Tuple[str, str]


def joint_findings(name: str, r_j: float, c: float, model: Dict[str, Any]) -> List[Finding]:
    """What looks wrong in one revolute clearance joint on its own (``model``: its plain-data
    model, ``Dry._as_dict()`` or ``Lubricated._as_dict()``)."""
    j = f"clearance joint '{name}'"
    out: List[Finding] = []
    if model["kind"] == "dry":
        if c > DRY_CLEARANCE_RATIO * r_j:
            out.append((f"{j}.clearance", f"{j}.clearance = {c:g} m is {c / r_j:.3g} × the journal radius {r_j:g} m (machine bearings have "
                        "c/R_j ≈ 0.001): is it given in metres? clearsim takes the radial clearance in metres"))  # fmt: skip
        return out
    # A Vogel law ({"vogel": [a, b, c]}) is checked in the core (T > c); a constant here.
    mu = math.nan if isinstance(model["viscosity"], dict) else float(model["viscosity"])
    lo, hi = VISCOSITY_RANGE
    if mu > hi:
        out.append((f"{j}.viscosity", f"{j}.viscosity = {mu:g} Pa·s is above {hi:g} Pa·s, thicker than lubricating oils at their working "
                    f"temperature (0.005–0.5 Pa·s): did you give centipoise (mPa·s)? clearsim takes Pa·s (1 cP = 0.001 Pa·s: {mu:g} cP = {mu * 1e-3:g} Pa·s)"))  # fmt: skip
    elif 0.0 < mu < lo:  # μ ≤ 0 is the core's InputError
        out.append((f"{j}.viscosity", f"{j}.viscosity = {mu:g} Pa·s is below {lo:g} Pa·s, thinner than water (0.001 Pa·s): the film laws "
                    "are for liquid lubricants; did you give a kinematic viscosity (m²/s) or Pa·s / 1000? clearsim takes the dynamic "
                    "viscosity in Pa·s (= kinematic viscosity × density)"))  # fmt: skip
    ratio = r_j / c
    if ratio < FILM_RATIO_RANGE[0]:
        out.append((f"{j}.clearance", f"{j}.clearance = {c:g} m is {c / r_j:.3g} × the journal radius {r_j:g} m: the film laws are thin-film "
                    f"theory, meant for R_j/c ≥ {FILM_RATIO_RANGE[0]:g} (machine bearings R_j/c ≈ 1000): did you give millimetres, or the "
                    "diametral clearance? clearsim takes the radial clearance in metres"))  # fmt: skip
    elif ratio > FILM_RATIO_RANGE[1]:
        out.append((f"{j}.clearance", f"{j}.clearance = {c:g} m is R_j/{ratio:.3g} ({c * 1e6:.3g} µm on a {r_j:g} m journal): thinner than "
                    f"machined surfaces are rough, where the smooth-film laws stop holding (meant for R_j/c ≤ {FILM_RATIO_RANGE[1]:g}): "
                    "is it given in metres? clearsim takes metres"))  # fmt: skip
    return out


def output_point_findings(description: Dict[str, Any], body: str, point: Sequence[float], field: str) -> List[Finding]:
    """What looks wrong in an output point (``point`` [m] on ``body`` of ``description``, named
    ``field``): in mm or in the global frame, by the core's rule against the mechanism's size
    (``rust/compile/plausibility.rs``, ``output_point``: as a load point is checked)."""
    found = output_point_finding(description, body, (float(point[0]), float(point[1])), field)
    return [found] if found is not None else []


def micrometre_film_note(name: str, r_j: float, c: float, film: str) -> Optional[str]:
    """A note (a plain UserWarning, not a plausibility one: the value is meant) on a long-bearing
    film in a µm clearance, where a whirl near the centre can make the run crawl."""
    if film not in ("long", "long_paper") or r_j / c < MICROMETRE_FILM_RATIO:
        return None
    return (f"clearance joint '{name}': a {film!r} film in a {c * 1e6:.3g} µm clearance (R_j/c = {r_j / c:.0f}): a journal that whirls "
            "near the centre (started off-centre, say) meets the half-Sommerfeld film's negative squeeze damping and the run can "
            "crawl (measured at R_j ≈ 10 mm: docs/hard_cases.md, µm films); film='finite', supply='none' damps it")


def _user_stacklevel() -> int:
    """The stacklevel of :func:`warnings.warn` (called from :func:`warn_new`) that points at the
    first frame outside the clearsim package: the user's line that added or ran the element."""
    package = os.path.dirname(os.path.abspath(__file__))
    frame = sys._getframe(2)  # warn_new's caller: stacklevel 2 of a warn in warn_new
    level = 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(package + os.sep):
        frame = frame.f_back  # type: ignore[assignment]
        level += 1
    return level


def warn_new(findings: Sequence[Tuple[str, str]], warned: Set[str]) -> None:
    """Warn each finding ``(field, message)`` whose message is not in ``warned`` (then add it):
    once per mechanism and its copies, not once per run, at the user's line."""
    level = _user_stacklevel()
    for field, message in findings:
        if message in warned:
            continue
        warned.add(message)
        w = PlausibilityWarning(message)
        w.field = field  # type: ignore[attr-defined]  # where a scene file relocates it
        warnings.warn(w, stacklevel=level)


__all__ = ["FILM_RATIO_RANGE", "VISCOSITY_RANGE", "joint_findings", "micrometre_film_note", "output_point_findings", "warn_new"]
