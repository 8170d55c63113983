"""Plausibility of a mechanism's numbers: a :class:`~clearsim.PlausibilityWarning` for a value
that is valid but looks like a unit slip (millimetres where clearsim takes metres, centipoise
where it takes Pa·s) or lies outside the range the film laws are meant for. Each message names
the element, the field, the value and the unit clearsim expected.

Checks of one joint run when it is added (:func:`joint_findings`); those that need the whole
mechanism's size (:func:`mechanism_findings`) when it compiles. Each finding is warned once per
mechanism (:func:`warn_new`), not once per run.
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Dict, List, Optional, Sequence, Set, Tuple

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
#: A journal radius above this fraction of the mechanism's span, or a bearing length above this
#: multiple of it, is more likely millimetres than metres.
JOURNAL_SPAN_RATIO = 0.5
LENGTH_SPAN_RATIO = 2.0
#: A body's inertia below this fraction of a uniform bar's, m d²/12 over its joint points d apart,
#: is more likely coordinates in mm with the inertia in kg m² (a ratio of about 1e-6).
BAR_INERTIA_RATIO = 1e-3
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


def micrometre_film_note(name: str, r_j: float, c: float, film: str) -> Optional[str]:
    """A note (a plain UserWarning, not a plausibility one: the value is meant) on a long-bearing
    film in a µm clearance, where a whirl near the centre can make the run crawl."""
    if film not in ("long", "long_paper") or r_j / c < MICROMETRE_FILM_RATIO:
        return None
    return (f"clearance joint '{name}': a {film!r} film in a {c * 1e6:.3g} µm clearance (R_j/c = {r_j / c:.0f}): a journal that whirls "
            "near the centre (started off-centre, say) meets the half-Sommerfeld film's negative squeeze damping and the run can "
            "crawl (measured at R_j ≈ 10 mm: docs/hard_cases.md, µm films); film='finite', supply='none' damps it")


def span(desc: Dict[str, Any]) -> float:
    """The mechanism's size [m]: the diagonal of the box around its bodies' centroids and its
    joints' points at the poses given (a resolved description)."""
    bodies = desc["bodies"]

    def at(body: Optional[int], p: Sequence[float]) -> Tuple[float, float]:
        if body is None:
            return float(p[0]), float(p[1])
        b = bodies[body]
        c, s = math.cos(b.get("angle", 0.0)), math.sin(b.get("angle", 0.0))
        return b["position"][0] + c * p[0] - s * p[1], b["position"][1] + s * p[0] + c * p[1]

    pts = [tuple(b["position"]) for b in bodies]
    for j in desc["joints"]:
        pts += [at(j["body_a"], j["point_a"]), at(j["body_b"], j["point_b"])]
    for j in desc["clearance_joints"]:
        pts += [at(j["bearing_body"], j["bearing_point"]), at(j["journal_body"], j["journal_point"])]
    for f in desc.get("forces", []):
        if f["kind"] == "spring_damper":
            pts += [at(f["body_a"], f["point_a"]), at(f["body_b"], f["point_b"])]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys)) if pts else 0.0


def _point_spread(desc: Dict[str, Any]) -> List[float]:
    """Per body, the largest distance between two of its points that joints, clearance joints
    and springs attach to [m] (body frame)."""
    points: List[List[Tuple[float, float]]] = [[] for _ in desc["bodies"]]
    pairs = [("body_a", "point_a"), ("body_b", "point_b")]
    for j in desc["joints"]:
        for body, point in pairs:
            if j[body] is not None:
                points[j[body]].append(tuple(j[point]))
    for j in desc["clearance_joints"]:
        for body, point in (("bearing_body", "bearing_point"), ("journal_body", "journal_point")):
            if j[body] is not None:
                points[j[body]].append(tuple(j[point]))
    for f in desc.get("forces", []):
        if f["kind"] == "spring_damper":
            for body, point in pairs:
                if f[body] is not None:
                    points[f[body]].append(tuple(f[point]))
    return [max((math.dist(a, b) for a in ps for b in ps), default=0.0) for ps in points]


def mechanism_findings(desc: Dict[str, Any]) -> List[Finding]:
    """What looks wrong against the mechanism's size: a journal radius or a bearing length of
    the order of the whole mechanism, a body far lighter in inertia than a bar between its joint
    points (lengths in mm, inertia in kg m²) (a resolved description)."""
    out: List[Finding] = []
    for b, d in zip(desc["bodies"], _point_spread(desc)):
        bar = float(b["mass"]) * d * d / 12.0
        if bar > 0.0 and 0.0 < float(b["inertia"]) < BAR_INERTIA_RATIO * bar:  # invalid sizes are the core's errors
            i_b = f"body '{b['name']}'.inertia"
            out.append((i_b, f"{i_b} = {float(b['inertia']):g} kg m² is {float(b['inertia']) / bar:.1g} × a uniform bar's of its mass "
                        f"{float(b['mass']):g} kg between its joint points {d:.3g} m apart (m d²/12 = {bar:.3g} kg m²): are the points "
                        "and positions in mm? clearsim takes metres (and kg m²)"))  # fmt: skip
    size = span(desc)
    if not size > 0.0:
        return out
    for cj in desc["clearance_joints"]:
        j = f"clearance joint '{cj['name']}'"
        r_j = float(cj["journal_radius"])
        if r_j > JOURNAL_SPAN_RATIO * size:
            out.append((f"{j}.journal_radius", f"{j}.journal_radius = {r_j:g} m is larger than {'half ' if JOURNAL_SPAN_RATIO == 0.5 else ''}the "
                        f"mechanism's span {size:.3g} m: did you give mm? clearsim takes metres"))  # fmt: skip
        model = cj["model"]
        if model.get("kind") == "lubricated" and float(model["length"]) > LENGTH_SPAN_RATIO * size:
            length = float(model["length"])
            out.append((f"{j}.length", f"{j}.length = {length:g} m (the bearing's length) is more than {LENGTH_SPAN_RATIO:g} × the mechanism's "
                        f"span {size:.3g} m: did you give mm? clearsim takes metres"))  # fmt: skip
    return out


def warn_new(findings: Sequence[Finding], warned: Set[str], stacklevel: int) -> None:
    """Warn each finding whose message is not in ``warned`` (then add it): once per mechanism
    and its copies, not once per run."""
    for field, message in findings:
        if message in warned:
            continue
        warned.add(message)
        w = PlausibilityWarning(message)
        w.field = field  # type: ignore[attr-defined]  # where a scene file relocates it
        warnings.warn(w, stacklevel=stacklevel + 1)


__all__ = ["FILM_RATIO_RANGE", "VISCOSITY_RANGE", "joint_findings", "mechanism_findings", "micrometre_film_note", "span", "warn_new"]
