"""Hard-case numerical-stability suite (issue "Hard cases and bad input").

Every case either finishes with finite outputs and a bounded constraint violation ‖Φ‖, or stops
with a :class:`clearsim.SimulationError` carrying a diagnosis. The cases, what each shows and
their figures of merit are tabulated in ``docs/hard_cases.md``; regenerate the table with
``MPLBACKEND=Agg python tests/python/hard_cases_table.py``.

The second half checks the failure paths: a run that cannot go on raises ``SimulationError``
with the time, the reason, the joint and its ε, and the partial result; Ctrl-C returns what was
computed.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional

import numpy as np
import pytest

import clearsim as cs
from clearsim import Dry, Lubricated, models

C = 0.5e-3  # default radial clearance of the models [m]
SC_REV = 60.0 / 5000.0  # one crank revolution of the slider-crank at 5000 rpm [s]
NB_CYCLE = 2 * math.pi / (5 * math.pi)  # one cycle of the nine-bar at −5π rad/s [s]


# ---------------------------------------------------------------------------- helpers
def mechanical_energy(m: cs.Mechanism, r: cs.Result) -> np.ndarray:
    """Kinetic + gravitational + elastic contact energy at each output [J].

    The contact energy of a dry joint is ∫K δⁿ dδ = K δⁿ⁺¹/(n + 1) (δ > 0)."""
    d = m.description()
    gx, gy = d["gravity"]
    e = np.zeros(len(r.t))
    for b in d["bodies"]:
        v = r.velocity(b["name"])
        p = r.position(b["name"])
        e += 0.5 * b["mass"] * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * b["inertia"] * v[:, 2] ** 2
        e -= b["mass"] * (gx * p[:, 0] + gy * p[:, 1])
    stiffness = m.compile().contact_stiffness
    for k, c in enumerate(d["clearance_joints"]):
        dry = c["model"] if c["model"]["kind"] == "dry" else c["model"]["dry"]
        n = dry["exponent"]
        delta = np.maximum(np.linalg.norm(r.eccentricity(c["name"]), axis=1) - c["clearance"], 0.0)
        e += stiffness[k] * delta ** (n + 1) / (n + 1)
    return e


def slip_speed(r: cs.Result, joint: str, journal: str, bearing: str, r_j: float, c: float) -> np.ndarray:
    """Tangential slip v_t = t·ė + R_j θ̇_j − R_b θ̇_i of the contact points (docs/physics.md §2)."""
    e = r.eccentricity(joint)
    ed = r.eccentricity_rate(joint)
    n = e / np.maximum(np.linalg.norm(e, axis=1), 1e-300)[:, None]
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    return np.sum(t * ed, axis=1) + r_j * r.velocity(journal)[:, 2] - (r_j + c) * r.velocity(bearing)[:, 2]


def free_slider_crank(restitution: float, friction: float = 0.0) -> cs.Mechanism:
    """The docs/physics.md §8 slider-crank without its driver and without gravity: the crank is spun to
    300 rad/s and the mechanism coasts, so the total energy is a conserved quantity (c_e = 1,
    no friction) or can only decrease (c_e < 1)."""
    m = models.slider_crank("dry", dry=Dry(restitution=restitution, friction=friction))
    bare = cs.Mechanism(gravity=(0.0, 0.0))
    d = m.description()
    for b in d["bodies"]:
        vel = [0.0, 0.025 * 300.0, 300.0] if b["name"] == "crank" else None
        bare.add_body(b["name"], mass=b["mass"], inertia=b["inertia"], position=b["position"], angle=b["angle"], velocity=vel)
    bare.revolute("ground", (0.0, 0.0), "crank", (-0.025, 0.0), name="crank-ground")
    bare.revolute("crank", (0.025, 0.0), "rod", (-0.06, 0.0), name="crank-rod")
    bare.prismatic("ground", (0.0, 0.0), "slider", (0.0, 0.0), axis=(1.0, 0.0), name="slider-guide")
    bare.clearance_joint(
        "rod-slider", "slider", (0.0, 0.0), "rod", (0.06, 0.0),
        journal_radius=9.5e-3, clearance=C, model=Dry(restitution=restitution, friction=friction),
    )
    return bare


def with_initial_eccentricity(m: cs.Mechanism, joint: str, e: tuple) -> cs.Mechanism:
    """Rebuild ``m``'s clearance joint ``joint`` through the public API with a start offset."""
    out = cs.Mechanism(gravity=tuple(m.gravity), baumgarte=tuple(m.baumgarte))
    d = m.description()
    ref = lambda b: b  # noqa: E731  # the description names bodies (the ground "ground")
    for b in d["bodies"]:
        out.add_body(b["name"], mass=b["mass"], inertia=b["inertia"], position=b["position"], angle=b["angle"])
    for j in d["joints"]:
        if j["kind"] == "revolute":
            out.revolute(ref(j["body_a"]), j["point_a"], ref(j["body_b"]), j["point_b"], name=j["name"])
        else:
            out.prismatic(ref(j["body_a"]), j["point_a"], ref(j["body_b"]), j["point_b"], axis=j["axis"], name=j["name"])
    for dr in d["drivers"]:
        law = dr["law"]
        out.driver(dr["body"], omega=law["omega"], angle0=law["angle0"], name=dr["name"])
    src = {c["name"]: c for c in m._clearance}  # model objects are not in the plain description
    for c in d["clearance_joints"]:
        out.clearance_joint(
            c["name"], ref(c["bearing_body"]), c["bearing_point"], ref(c["journal_body"]), c["journal_point"],
            journal_radius=c["journal_radius"], clearance=c["clearance"],
            model=_model_of(src[c["name"]]["model"]),
            initial_eccentricity=e if c["name"] == joint else c["initial_eccentricity"],
        )
    return out


def _model_of(d: Dict) -> object:
    def dry(x: Dict) -> Dry:
        return Dry(
            normal_law=x["normal_law"], youngs_modulus=x["youngs_modulus"], poisson_ratio=x["poisson_ratio"],
            journal_youngs_modulus=x["journal_youngs_modulus"], journal_poisson_ratio=x["journal_poisson_ratio"],
            restitution=x["restitution"], exponent=x["exponent"], stiffness=x["stiffness"],
            stiffness_form=x["stiffness_form"], length=x.get("length"),
            friction=x["friction"], v0=x["v0"], v1=x["v1"], impact_speed_floor=x["impact_speed_floor"],
        )

    if d["kind"] == "dry":
        return dry(d)
    return Lubricated(
        viscosity=d["viscosity"], length=d["length"], film=d["film"], eps0=d["eps0"], m=d["m"],
        e0=d.get("e0"), eps_max=d["eps_max"], dry=dry(d["dry"]), supply=d.get("supply", "widest_gap"),
    )


# ---------------------------------------------------------------------------- the cases
@dataclass
class Case:
    """One hard case: how to build and run it, and what it must show."""

    id: str
    shows: str
    build: Callable[[], cs.Mechanism]
    t_end: float
    run: Dict = field(default_factory=dict)
    #: Bound on max ‖Φ‖ over the outputs [m, rad].
    phi_bound: float = 1e-6
    #: Extra checks: f(case, mechanism, result, metrics) -> None (asserts); may add metrics.
    check: Optional[Callable] = None
    #: "conserved", "dissipative", "cycles" or None (driven: energy not a figure of merit).
    energy: Optional[str] = None


@dataclass
class Outcome:
    case: Case
    mechanism: cs.Mechanism
    result: cs.Result
    error: Optional[cs.SimulationError]
    wall: float
    metrics: Dict


def _check_1um(case, m, r, metrics):
    # c → 0 reproduces the ideal mechanism (docs/physics.md §9): slider position within a few clearances.
    ideal = models.slider_crank("ideal").simulate(case.t_end, **case.run)
    dx = np.max(np.abs(r.position("slider")[:, 0] - ideal.position("slider")[:, 0]))
    metrics["max Δx vs ideal [m]"] = dx
    assert dx < 20e-6, dx


def _check_micrometre_film(case, m, r, metrics):
    """A µm film holds the journal near the bearing centre: it never touches the wall after the
    start, the slider follows the ideal mechanism within a few clearances (c → 0, docs/physics.md
    §9), and the run costs thousands of steps (c = 0.5 mm: a few hundred; 1 µm on the nine-bar
    ~2·10⁴), not the 10⁵–10⁶ of the stalls these cases were added for."""
    for j in r.joint_names:
        c = next(cj["clearance"] for cj in m.description()["clearance_joints"] if cj["name"] == j)
        eps = np.linalg.norm(r.eccentricity(j), axis=1) / c
        late = eps[len(eps) // 10:]
        metrics[f"max ε {j} after 10 %"] = float(late.max())
        assert late.max() < 1.0, f"journal {j} reached ε = {late.max():.3f}"
    body = "slider" if "slider" in r.body_names else "slider9"
    kind = "slider_crank" if body == "slider" else "nine_bar"
    ideal = getattr(models, kind)("ideal").simulate(case.t_end, **case.run)
    dev = float(np.max(np.abs(r.position(body)[:, :2] - ideal.position(body)[:, :2])))
    metrics["max Δ slider vs ideal [m]"] = dev
    c = m.description()["clearance_joints"][0]["clearance"]
    assert dev < 4 * c, f"slider {dev:.3g} m from the ideal mechanism's (c = {c:g} m)"
    assert r.stats["steps"] < 30_000, r.stats


def _check_impacts(case, m, r, metrics):
    assert sum(r.impacts.values()) > 0, "the journal never hit the bearing"
    for j in r.joint_names:
        eps = np.linalg.norm(r.eccentricity(j), axis=1) / m.description()["clearance_joints"][0]["clearance"]
        metrics[f"max ε {j}"] = float(eps.max())
        assert eps.max() < 1.5, f"journal {j} sank {eps.max():.3f} clearances into the wall"


def _check_transition(case, m, r, metrics):
    w = max(float(r.dry_weight(j).max()) for j in r.joint_names)
    metrics["max dry weight"] = w
    states = np.concatenate([r.contact_state(j) for j in r.joint_names])
    assert w > 0.0 and np.any(states >= 1), "the journals never reached the film-to-contact band"


def _check_centred(case, m, r, metrics):
    e0 = np.linalg.norm(r.eccentricity("rod-slider")[0])
    assert e0 == 0.0
    f0 = r.joint_force("rod-slider")[0]
    assert np.all(f0 == 0.0), f"a centred journal has no film force (no 0/0): {f0}"
    assert np.linalg.norm(r.eccentricity("rod-slider")[-1]) > 0.0


def _check_in_contact(case, m, r, metrics):
    eps0 = np.linalg.norm(r.eccentricity("rod-slider")[0]) / C
    metrics["ε at t0"] = eps0
    assert eps0 > 1.0 and r.contact_state("rod-slider")[0] >= 1
    assert np.all(np.linalg.norm(r.eccentricity("rod-slider"), axis=1) / C < 1.2)


def _check_friction(cf):
    def check(case, m, r, metrics):
        fn, ft = r.contact_force("rod-slider").T
        state = r.contact_state("rod-slider")
        v = slip_speed(r, "rod-slider", "rod", "slider", 9.5e-3, C)
        touching = fn > 0
        crossings = int(np.sum(np.diff(np.sign(v[touching])) != 0))
        metrics["slip sign changes in contact"] = crossings
        assert np.any(state == 2)
        assert crossings > 0, "slip speed never crossed zero during contact"
        if cf == 0.0:
            assert np.all(ft == 0.0)
        else:
            assert np.any(ft != 0.0)
            assert np.all(np.abs(ft) <= cf * fn * (1 + 1e-9) + 1e-12)
            # Friction opposes the slip wherever the full Coulomb value acts.
            full = np.abs(v) > 1e-2
            assert np.all(ft[full] * v[full] <= 0.0)

    return check


def _check_toggle(case, m, r, metrics):
    a = r.acceleration("slider")[:, 0]
    metrics["peak slider acc [m/s²]"] = float(np.max(np.abs(a)))
    # Near the toggle (l → r is a bifurcation at θ = 90°: slider at the crank pivot) the ideal
    # slider acceleration peaks at about 7 r ω² (1.3 r ω² for the usual l = 2.4 r).
    ideal = models.slider_crank("ideal", rod_length=0.0505, rpm=1000.0).simulate(case.t_end, **case.run)
    omega = 1000 * 2 * math.pi / 60
    assert np.max(np.abs(ideal.acceleration("slider")[:, 0])) > 5 * 0.05 * omega**2


def _finite_table_built(m: cs.Mechanism) -> cs.Mechanism:
    """Build the finite-bearing table of the slider-crank's journal (L/D = 40/19) before the run,
    so that the runtime column times the run, not the one-off table (a few seconds)."""
    cs._core.film_force("finite", 0.4, 0.0095, 1e-6, 0.04, 0.5, 0.0, 100.0, supply="none")
    return m


def _micrometre_case(clearance: str, model: str, shows: str, wall: bool = False) -> Case:
    """A lubricated model with a µm clearance (``"5 µm"``) at default settings, one crank turn,
    journal centred or released at rest at ε = 0.99 (``wall``), checked by
    :func:`_check_micrometre_film`."""
    c = float(clearance.split()[0]) * 1e-6
    build_model = getattr(models, model)
    if wall:
        build = lambda: with_initial_eccentricity(build_model("lubricated", clearance=c), "rod-slider", (0.99 * c, 0.0))  # noqa: E731
        where = "starts at the wall (ε = 0.99)"
    else:
        build = lambda: build_model("lubricated", clearance=c)  # noqa: E731
        where = "starts centred"
    period = SC_REV if model == "slider_crank" else NB_CYCLE
    label = f"lubricated c = {clearance}, {where}" if model == "slider_crank" else f"nine-bar lubricated c = {clearance}"
    return Case(label, f"{shows}; default settings, 1 {'revolution' if model == 'slider_crank' else 'cycle'}", build, period,
                dict(dt_out=period / (200 if model == "slider_crank" else 400)), check=_check_micrometre_film)  # fmt: skip


CASES: List[Case] = [
    Case(
        "dry c = 1 µm",
        "stiff contact, tiny clearance: finishes and reproduces the ideal slider-crank (c → 0)",
        lambda: models.slider_crank("dry", clearance=1e-6),
        2 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_1um,
    ),
    Case(
        "dry c = 2 mm",
        "large clearance: free flights and hard impacts, penetration stays small",
        lambda: models.slider_crank("dry", clearance=2e-3),
        2 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_impacts,
    ),
    Case(
        "nine-bar ω = −20π rad/s",
        "four times the paper's speed, two dry joints, 2 cycles",
        lambda: models.nine_bar("dry", omega=-20 * math.pi),
        0.2, dict(dt_out=1e-4), check=_check_impacts,
    ),
    Case(
        "slider-crank 10 000 rpm",
        "twice the validation speed, dry, 5 revolutions",
        lambda: models.slider_crank("dry", rpm=10000.0),
        5 * SC_REV / 2, dict(dt_out=SC_REV / 400), check=_check_impacts,
    ),
    Case(
        "lubricated μ = 0.04 Pa·s",
        "thin oil: both nine-bar journals sink into the film-to-contact band (P18), 1 cycle",
        lambda: models.nine_bar("lubricated", lubricated=Lubricated(viscosity=0.04, length=0.05)),
        NB_CYCLE, dict(dt_out=1e-4), check=_check_transition,
    ),
    Case(
        "lubricated, starts centred (ε = 0)",
        "no 0/0 at ε = 0 (n undefined, ε^m scaling), slider-crank, 2 revolutions",
        lambda: models.slider_crank("lubricated"),
        2 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_centred,
    ),
    _micrometre_case("5 µm", "slider_crank", "a machine-bearing clearance (R/c = 1900): the stiff film holds the journal near the centre, where the long bearing's force used to jump (docs/physics.md §4)"),
    _micrometre_case("5 µm", "slider_crank", "the same journal released next to the wall: the film pushes it back to the centre within microseconds", wall=True),
    _micrometre_case("5 µm", "nine_bar", "both nine-bar journals in 5 µm films"),
    _micrometre_case("1 µm", "slider_crank", "R/c = 9500, the smallest clearance of the range: the journal stays within 1e-4 c of the centre"),
    _micrometre_case("1 µm", "nine_bar", "both nine-bar journals in 1 µm films"),
    Case(
        "lubricated c = 1 µm, finite bearing, in a whirl (ε = 0.05)",
        "the journal starts off-centre and whirls at about half the crank speed; the periodic Reynolds-condition film (finite, supply='none', L/D = 2.1) keeps a strong squeeze damping there, where the long bearing's half-Sommerfeld film does not and the finite film with its supply line (the default) crawls like it (docs/hard_cases.md, below); default settings, 1 revolution",
        lambda: _finite_table_built(with_initial_eccentricity(
            models.slider_crank("lubricated", clearance=1e-6, lubricated=cs.Lubricated(viscosity=0.4, length=0.04, film="finite", supply="none")),
            "rod-slider", (0.05e-6, 0.0))),
        SC_REV, dict(dt_out=SC_REV / 200), check=_check_micrometre_film,
    ),
    Case(
        "lubricated, starts in contact (ε = 1.03)",
        "start inside the transition band with penetration: no spurious impact blow-up",
        lambda: with_initial_eccentricity(models.slider_crank("lubricated"), "rod-slider", (1.03 * C, 0.0)),
        2 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_in_contact,
    ),
    Case(
        "restitution 1.0 (coasting, frictionless)",
        "elastic impacts: energy conserved to the integrator tolerance",
        lambda: free_slider_crank(1.0),
        0.1, dict(dt_out=1e-5, rtol=1e-8, atol=1e-11), energy="conserved",
    ),
    Case(
        "restitution 0.3 (coasting, frictionless)",
        "strongly dissipative impacts: energy never rises, it falls",
        lambda: free_slider_crank(0.3),
        0.1, dict(dt_out=1e-5, rtol=1e-8, atol=1e-11), energy="dissipative",
    ),
    Case(
        "restitution 0.3, driven",
        "driven slider-crank with c_e = 0.3, 3 revolutions",
        lambda: models.slider_crank("dry", dry=Dry(restitution=0.3)),
        3 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_impacts,
    ),
    Case(
        "restitution 1.0, driven",
        "driven slider-crank with purely elastic impacts, 3 revolutions",
        lambda: models.slider_crank("dry", dry=Dry(restitution=1.0)),
        3 * SC_REV, dict(dt_out=SC_REV / 200), check=_check_impacts,
    ),
    Case(
        "friction 0",
        "frictionless contact: no tangential force while slip changes sign",
        lambda: models.slider_crank("dry", dry=Dry(friction=0.0)),
        3 * SC_REV, dict(dt_out=SC_REV / 2000), check=_check_friction(0.0),
    ),
    Case(
        "friction 0.5",
        "heavy friction with slip speeds crossing zero (modified Coulomb ramp, P5)",
        lambda: models.slider_crank("dry", dry=Dry(friction=0.5)),
        3 * SC_REV, dict(dt_out=SC_REV / 2000), check=_check_friction(0.5),
    ),
    Case(
        "nine-bar 50 cycles",
        "long run: constraint drift and energy bounded, no NaN (dry, −5π rad/s, 20 s)",
        lambda: models.nine_bar("dry"),
        50 * NB_CYCLE, dict(dt_out=1e-3), energy="cycles",
    ),
    Case(
        "near-toggle slider-crank",
        "rod 1 % longer than the crank: near the l = r bifurcation at θ = 90° (rod almost "
        "perpendicular to the guide, slider acceleration ≈ 7 r ω²), dry, 1000 rpm, 1 revolution",
        lambda: models.slider_crank("dry", rod_length=0.0505, rpm=1000.0),
        0.06, dict(dt_out=1e-5), check=_check_toggle,
    ),
]


def run_case(case: Case) -> Outcome:
    m = case.build()
    start = time.perf_counter()
    err: Optional[cs.SimulationError] = None
    try:
        r = m.simulate(case.t_end, **case.run)
    except cs.SimulationError as e:
        err, r = e, e.result
    wall = time.perf_counter() - start
    metrics: Dict = {
        "max ‖Φ‖": float(np.max(r.constraint_violation)) if len(r.t) else float("nan"),
        "min step": float(r.stats["min_step"]),
        "steps": int(r.stats["steps"]),
        "impacts": int(sum(r.impacts.values())),
        "runtime": wall,
        "t_reached": float(r.stats["t_reached"]),
    }
    if case.energy and len(r.t):
        e = mechanical_energy(m, r)
        if case.energy in ("conserved", "dissipative"):
            metrics["energy drift"] = float((e[-1] - e[0]) / e[0])
            metrics["max energy rise"] = float((e.max() - e[0]) / e[0])
        else:
            per = int(round(NB_CYCLE / (r.t[1] - r.t[0])))
            ideal = models.nine_bar("ideal").simulate(NB_CYCLE, dt_out=r.t[1] - r.t[0])
            ei = mechanical_energy(models.nine_bar("ideal"), ideal)
            swing = float(ei.max() - ei.min())
            metrics["energy drift"] = float((e[-per:].mean() - e[:per].mean()) / swing)
            metrics["energy range / ideal range"] = float((e.max() - e.min()) / swing)
    return Outcome(case, m, r, err, wall, metrics)


def assert_healthy(o: Outcome) -> None:
    """Finished with finite outputs and bounded ‖Φ‖, or stopped with a full diagnosis."""
    r = o.result
    if o.error is not None:
        e = o.error
        assert e.t is not None and math.isfinite(e.t) and e.reason
        assert e.result is r and r.t[-1] <= e.t + 1e-15
        pytest.fail(f"{o.case.id}: stopped with a diagnosis (not expected for this case): {e}")
    assert r.completed
    assert r.stats["t_reached"] == pytest.approx(o.case.t_end, rel=1e-12)
    for name in r.body_names:
        for arr in (r.position(name), r.velocity(name), r.acceleration(name)):
            assert np.all(np.isfinite(arr)), f"non-finite output of {name}"
    for j in r.joint_names:
        assert np.all(np.isfinite(r.eccentricity(j))) and np.all(np.isfinite(r.joint_force(j)))
    assert np.all(np.isfinite(r.constraint_violation))
    assert o.metrics["max ‖Φ‖"] < o.case.phi_bound, o.metrics


@pytest.fixture(scope="module")
def outcomes() -> Dict[str, Outcome]:
    return {}


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_hard_case(case: Case, outcomes) -> None:
    o = run_case(case)
    outcomes[case.id] = o
    assert_healthy(o)
    if case.check is not None:
        case.check(case, o.mechanism, o.result, o.metrics)
    if case.energy == "conserved":
        assert abs(o.metrics["energy drift"]) < 1e-4 and o.metrics["max energy rise"] < 1e-4, o.metrics
        assert o.metrics["impacts"] > 10
    elif case.energy == "dissipative":
        assert o.metrics["max energy rise"] < 1e-5, o.metrics
        assert o.metrics["energy drift"] < -1e-3, o.metrics
    elif case.energy == "cycles":
        assert abs(o.metrics["energy drift"]) < 0.02, o.metrics
        assert o.metrics["energy range / ideal range"] < 2.0, o.metrics


# ---------------------------------------------------------------------------- failures
def _assert_diagnosed(e: cs.SimulationError, words: str, joint: Optional[str] = "any") -> cs.Result:
    assert isinstance(e.t, float) and math.isfinite(e.t)
    assert words in e.reason and words in str(e)
    assert e.reason.startswith(str(e).split(";")[0])
    r = e.result
    assert isinstance(r, cs.Result) and not r.completed and r.failure is e
    if len(r.t):
        assert r.t[-1] <= e.t + 1e-15
        assert np.all(np.isfinite(r.position(r.body_names[0])))
    if joint is None:
        assert e.joint is None and e.eccentricity is None
    else:
        assert e.joint in r.joint_names and f"joint '{e.joint}'" in e.reason
        assert isinstance(e.eccentricity, float)
    return r


def test_step_size_floor_raises_with_joint_and_partial_result():
    with pytest.raises(cs.SimulationError) as info:
        models.nine_bar("dry").simulate(0.1, h_min=1e-5, dt_out=1e-4)
    e = info.value
    r = _assert_diagnosed(e, "step size underflow")
    assert e.eccentricity > 1.0, "the step collapsed at an impact"
    assert f"ε = {e.eccentricity:.6f}" in e.reason
    assert 0.0 < e.t < 0.1 and len(r.t) > 10 and r.stats["t_reached"] == pytest.approx(e.t)


@pytest.mark.parametrize("step", [1e-3, 3e-4, 1e-4])
def test_blow_up_reported_as_any_simulation_error_names_joint(step):
    # A fixed RK4 step far too long for the contact stiffness: the state blows up. It surfaces
    # as a penetration beyond max(c, 0.05 R_j) (ε > 2 here), a non-finite state or a singular
    # KKT matrix; either way the message names the joint and its absurd ε, and the partial
    # result is kept.
    with pytest.raises(cs.SimulationError) as info:
        models.slider_crank("dry").simulate(0.02, integrator="rk4", step=step, dt_out=2e-5)
    e = info.value
    r = _assert_diagnosed(e, "at t =")
    assert e.joint == "rod-slider" and e.eccentricity > 1.9
    # The first absurd step stops the run (at 1e-3 s that is the first step: only t = 0 is kept).
    assert len(r.t) >= 1 and r.t[-1] <= e.t


def test_step_budget_raises_with_partial_result():
    with pytest.raises(cs.SimulationError) as info:
        models.nine_bar("dry").simulate(0.1, max_steps=200, dt_out=1e-4)
    r = _assert_diagnosed(info.value, "maximum number of steps (200)")
    assert len(r.t) > 1


def _unassemblable() -> cs.Mechanism:
    # The slider guide runs 0.5 m above a crank and rod that reach 0.17 m: no assembly exists.
    m = cs.Mechanism(gravity=(0, 0))
    m.add_body("crank", mass=0.3, inertia=1e-4, position=(0.025, 0))
    m.add_body("rod", mass=0.2, inertia=1e-4, position=(0.1, 0.0))
    m.add_body("slider", mass=0.1, inertia=1e-4, position=(0.2, 0.5))
    m.revolute("ground", (0, 0), "crank", (-0.025, 0))
    m.revolute("crank", (0.025, 0), "rod", (-0.06, 0))
    m.clearance_joint("pin", "slider", (0, 0), "rod", (0.06, 0), journal_radius=5e-3, clearance=1e-4)
    m.prismatic("ground", (0, 0.5), "slider", (0, 0))
    m.driver("crank", omega=10.0)
    return m


def test_assembly_failure_raises_assembly_error():
    with pytest.raises(cs.AssemblyError) as info:
        _unassemblable().simulate(0.1)
    e = info.value
    assert isinstance(e, cs.SimulationError) and e.t == 0.0
    assert "assembly failed" in e.reason and "residual" in e.reason
    assert e.result is not None and len(e.result.t) == 0 and not e.result.completed
    with pytest.raises(cs.AssemblyError):
        _unassemblable().initial_state()


_LONG_RUN = r"""
import json, sys, time, warnings
import clearsim as cs
m = cs.models.nine_bar("dry")
m.compile()
print("READY", flush=True)
start = time.time()
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    r = m.simulate(1.0e4, dt_out=1e-2)
import numpy as np
print(json.dumps({
    "t_reached": r.stats["t_reached"], "t_last": float(r.t[-1]), "n": len(r.t),
    "completed": r.completed, "failure": type(r.failure).__name__,
    "warnings": [str(x.message) for x in w], "wall": time.time() - start,
    "finite": bool(np.all(np.isfinite(r.position("slider9")))),
}), flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_ctrl_c_returns_partial_result():
    p = subprocess.Popen([sys.executable, "-c", _LONG_RUN], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline().strip() == "READY"
        time.sleep(1.0)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 0, err
    info = json.loads(out.strip().splitlines()[-1])
    assert not info["completed"] and info["failure"] == "InterruptedRun"
    assert 0.0 < info["t_reached"] < 1.0e4 and info["n"] > 1 and info["t_last"] <= info["t_reached"]
    assert info["finite"]
    assert info["wall"] < 5.0, "the run did not stop promptly"
    assert any("interrupted at t =" in w and "partial result" in w for w in info["warnings"])


@pytest.mark.parametrize("start, budget, says", [(0.05, 1.0, "film='finite', supply='none' (the periodic film) damps it"), (0.99, None, "start it centred or off the wall")])
def test_a_stalled_micrometre_film_says_what_to_try(start, budget, says):
    """A 1 µm long-bearing film that stalls — in its whirl near the centre (stopped by the
    wall-time budget) or released at rest against the wall (step-size underflow at t = 0) — says
    what to try (docs/hard_cases.md); the diagnosis before it stays."""
    m = with_initial_eccentricity(models.slider_crank("lubricated", clearance=1e-6), "rod-slider", (start * 1e-6, 0.0))
    with pytest.raises(cs.SimulationError) as info:
        m.simulate(SC_REV, dt_out=SC_REV / 200, progress=False, **({"max_seconds": budget} if budget else {}))
    msg = str(info.value)
    assert says in msg and "R/c = 9500" in msg and "joint 'rod-slider'" in msg
    assert ("wall-time budget" if budget else "step size underflow") in msg
    assert info.value.result is not None


def test_a_micrometre_film_stopped_by_hand_gets_the_hint_too():
    """A crawling 1 µm long-film run that the user interrupts (Ctrl-C, here a progress callback
    that raises KeyboardInterrupt) returns its partial result with a warning that carries the
    same advice as a run out of budget."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the definition-time warning of a µm long film
        m = with_initial_eccentricity(models.slider_crank("lubricated", clearance=1e-6), "rod-slider", (0.05e-6, 0.0))
    settings = m.run_settings(SC_REV, dt_out=SC_REV / 200)

    def stop(t):
        raise KeyboardInterrupt

    raw = m.compile().simulate(settings, stop)
    assert isinstance(raw["error"], cs.InterruptedRun)
    with pytest.warns(RuntimeWarning, match=r"interrupted at t = .*partial result; hint: joint 'rod-slider' has a 1 µm 'long' film.*film='finite'"):
        res = m._finish(raw, settings)
    assert not res.completed and len(res.t) >= 1


def test_a_release_at_the_wall_that_cannot_start_says_so_at_any_clearance():
    """The short film released at rest against the wall stops at t = 0 up to c = 20 µm
    (docs/hard_cases.md): the diagnosis says the release is the trouble, whatever R/c."""
    m = with_initial_eccentricity(models.slider_crank("lubricated", clearance=20e-6, lubricated=cs.Lubricated(viscosity=0.4, length=0.04, film="short")),
                                  "rod-slider", (0.99 * 20e-6, 0.0))  # fmt: skip
    with pytest.raises(cs.SimulationError) as info:
        m.simulate(SC_REV, dt_out=SC_REV / 200, progress=False, max_seconds=10.0)
    msg = str(info.value)
    assert info.value.t == 0.0 and "step size underflow" in msg
    assert "20 µm 'short' film (R/c = 475)" in msg and "released at rest against the wall" in msg and "start it centred or off the wall" in msg


def test_no_hint_where_the_clearance_is_not_micrometre():
    """The hint is for µm films only: a 0.5 mm joint that runs out of steps gets the bare diagnosis."""
    with pytest.raises(cs.SimulationError) as info:
        models.slider_crank("lubricated").simulate(SC_REV, progress=False, max_steps=5)
    assert "hint" not in str(info.value)


def test_a_micrometre_long_film_warns_when_defined():
    """Before anything runs, a long-bearing film with R_j/c ≥ 4 000 warns that a whirl near the
    centre can crawl and names the remedy; the finite film, a 0.5 mm long film and a 3 µm one
    (R_j/c = 3 167, which finishes from the whirl: docs/hard_cases.md) do not."""
    import warnings

    with pytest.warns(UserWarning, match=r"clearance joint 'rod-slider': a 'long' film in a 1 µm clearance \(R_j/c = 9500\).*film='finite'"):
        models.slider_crank("lubricated", clearance=1e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        models.slider_crank("lubricated", clearance=1e-6, lubricated=cs.Lubricated(viscosity=0.4, length=0.04, film="finite"))
        models.slider_crank("lubricated", clearance=3e-6)
        models.slider_crank("lubricated")
