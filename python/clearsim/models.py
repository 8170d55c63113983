"""Ready-made mechanisms with the parameters (``docs/physics.md`` §7 and §8)."""

from __future__ import annotations

import math
from typing import Dict, Mapping, Optional, Tuple, Union

from .errors import InputError, check_choice
from .joints import Dry, Lubricated
from .mechanism import Mechanism

JOINT_KINDS = ("ideal", "dry", "lubricated")


def _kind(joints: str) -> str:
    return str(check_choice("joints", joints, JOINT_KINDS))


def _link(m: Mechanism, name: str, mass: float, inertia: float, p: Tuple[float, float], q: Tuple[float, float]) -> float:
    """Add a link from point p to point q (centroid at mid-length, local x along p→q)."""
    length = math.hypot(q[0] - p[0], q[1] - p[1])
    m.add_body(
        name,
        mass=mass,
        inertia=inertia,
        position=((p[0] + q[0]) / 2, (p[1] + q[1]) / 2),
        angle=math.atan2(q[1] - p[1], q[0] - p[0]),
    )
    return length


def _pin(
    m: Mechanism,
    name: str,
    kind: str,
    bearing: str,
    bearing_point: Tuple[float, float],
    journal: str,
    journal_point: Tuple[float, float],
    journal_radius: float,
    clearance: Optional[float],
    dry: Optional[Dry],
    lubricated: Optional[Lubricated],
) -> None:
    if kind == "ideal":
        m.revolute(bearing, bearing_point, journal, journal_point, name=name)
        return
    if clearance is None:
        raise InputError(f"invalid clearance = None: joints={kind!r} needs a clearance [m]", field="clearance", value=None)
    model = (dry or Dry()) if kind == "dry" else (lubricated or Lubricated())
    m.clearance_joint(
        name,
        bearing,
        bearing_point,
        journal,
        journal_point,
        journal_radius=journal_radius,
        clearance=clearance,
        model=model,
    )


def slider_crank(
    joints: str = "ideal",
    clearance: Optional[float] = 0.5e-3,
    rpm: float = 5000.0,
    *,
    crank_length: float = 0.05,
    rod_length: float = 0.12,
    journal_radius: float = 9.5e-3,
    dry: Optional[Dry] = None,
    lubricated: Optional[Lubricated] = None,
    gravity: Tuple[float, float] = (0.0, 0.0),
) -> Mechanism:
    """Slider-crank after Flores et al. (docs/physics.md §8), crank at constant ``rpm``, zero offset, the
    slider on the x axis, starting at top dead centre (θ = 0).

    Bodies ``crank``, ``rod``, ``slider``. ``joints="dry"`` or ``"lubricated"`` puts a clearance
    joint named ``"rod-slider"`` (bearing in the slider, journal on the rod) with the
    R_j = 9.5 mm and c = 0.5 mm (R_b = 10 mm); lubricated default μ = 0.4 Pa s, L = 40 mm.
    """
    kind = _kind(joints)
    r, l = crank_length, rod_length
    m = Mechanism(gravity=gravity)
    _link(m, "crank", 0.30, 1e-4, (0.0, 0.0), (r, 0.0))
    _link(m, "rod", 0.21, 2.5e-4, (r, 0.0), (r + l, 0.0))
    m.add_body("slider", mass=0.14, inertia=1e-4, position=(r + l, 0.0))
    m.revolute("ground", (0.0, 0.0), "crank", (-r / 2, 0.0), name="crank-ground")
    m.revolute("crank", (r / 2, 0.0), "rod", (-l / 2, 0.0), name="crank-rod")
    lub = lubricated or Lubricated(viscosity=0.4, length=0.04)
    _pin(m, "rod-slider", kind, "slider", (0.0, 0.0), "rod", (l / 2, 0.0), journal_radius, clearance, dry, lub)
    m.prismatic("ground", (0.0, 0.0), "slider", (0.0, 0.0), axis=(1.0, 0.0), name="slider-guide")
    m.driver("crank", omega=rpm * 2 * math.pi / 60.0, angle0=0.0, name="crank-drive")
    return m


#: Nine-bar geometry of docs/physics.md §7 at t = 0 (assembly refines it).
NINE_BAR_POINTS: Dict[str, Tuple[float, float]] = {
    "O1": (0.0, 0.0),
    "O4": (0.0, -0.40),
    "B1": (0.10, 0.0),  # crank 1 tip (θ1 = 0)
    "A": (0.0, -0.30),  # crank 4 tip (θ4 = π/2): clearance joint A
    "C": (0.2919, -0.2306),
    "D": (0.6756, -0.1176),
    "H": (0.45, 0.15),
    "B": (0.59, -0.4570),  # slider pin: clearance joint B
}

#: (mass [kg], inertia [kg m²]) of docs/physics.md §7.
NINE_BAR_INERTIA: Dict[str, Tuple[float, float]] = {
    "crank1": (0.20, 1.667e-4),
    "rod2": (0.50, 3.750e-3),
    "rod3": (0.50, 3.750e-3),
    "crank4": (0.20, 1.667e-4),
    "rocker6": (0.55, 5.615e-3),
    "rod7": (0.65, 8.667e-3),
    "rod8": (0.55, 5.615e-3),
    "slider9": (1.50, 1.000e-3),
}


def nine_bar(
    joints: str = "ideal",
    clearance: Union[None, float, Mapping[str, float]] = 0.5e-3,
    omega: float = -5.0 * math.pi,
    *,
    journal_radius: float = 10e-3,
    dry: Optional[Dry] = None,
    lubricated: Optional[Lubricated] = None,
    gravity: Tuple[float, float] = (0.0, -9.81),
) -> Mechanism:
    """The paper's 2-DOF nine-bar press mechanism (docs/physics.md §7).

    Cranks 1 and 4 turn at ``omega`` [rad/s] from θ1 = 0 and θ4 = π/2. Bodies ``crank1, rod2,
    rod3, crank4, rocker6, rod7, rod8, slider9``; the slider moves on the vertical guide
    x = 0.59 m. ``joints="dry"`` or ``"lubricated"`` makes joints ``"A"`` (crank 4 – rod 3, bearing
    in crank 4) and ``"B"`` (rod 8 – slider 9, bearing in the slider) clearance joints with
    R_j = 10 mm and the given radial ``clearance`` [m] (μ = 0.4 Pa s, L = 50 mm by default); a
    mapping ``{"A": c_A, "B": c_B}`` gives each joint its own.
    """
    kind = _kind(joints)
    if isinstance(clearance, Mapping):
        unknown = set(clearance) - {"A", "B"}
        if unknown or len(clearance) != 2:
            raise InputError(f"invalid clearance = {dict(clearance)!r}: give both joints' clearances as {{'A': c_A, 'B': c_B}} [m]", field="clearance", value=dict(clearance))
        c_a: Optional[float] = clearance["A"]
        c_b: Optional[float] = clearance["B"]
    else:
        c_a = c_b = clearance
    P = NINE_BAR_POINTS
    I = NINE_BAR_INERTIA
    m = Mechanism(gravity=gravity)
    half = {}
    for name, (a, b) in {
        "crank1": ("O1", "B1"),
        "rod2": ("B1", "C"),
        "rod3": ("A", "C"),
        "crank4": ("O4", "A"),
        "rocker6": ("H", "D"),
        "rod7": ("C", "D"),
        "rod8": ("D", "B"),
    }.items():
        length = _link(m, name, I[name][0], I[name][1], P[a], P[b])
        half[name] = length / 2
    # Nominal lengths of docs/physics.md §7 (the points above are rounded to 0.1 mm).
    half.update(crank1=0.05, rod2=0.15, rod3=0.15, crank4=0.05, rocker6=0.175, rod7=0.20, rod8=0.175)
    m.add_body("slider9", mass=I["slider9"][0], inertia=I["slider9"][1], position=P["B"])

    def end(body: str, sign: int) -> Tuple[float, float]:
        return (sign * half[body], 0.0)

    m.revolute("ground", P["O1"], "crank1", end("crank1", -1), name="O1")
    m.revolute("crank1", end("crank1", 1), "rod2", end("rod2", -1), name="B1")
    m.revolute("ground", P["O4"], "crank4", end("crank4", -1), name="O4")
    lub = lubricated or Lubricated(viscosity=0.4, length=0.05)
    _pin(m, "A", kind, "crank4", end("crank4", 1), "rod3", end("rod3", -1), journal_radius, c_a, dry, lub)
    m.revolute("rod2", end("rod2", 1), "rod7", end("rod7", -1), name="C-rod2")
    m.revolute("rod3", end("rod3", 1), "rod7", end("rod7", -1), name="C-rod3")
    m.revolute("rod7", end("rod7", 1), "rocker6", end("rocker6", 1), name="D-rocker6")
    m.revolute("rod7", end("rod7", 1), "rod8", end("rod8", -1), name="D-rod8")
    m.revolute("ground", P["H"], "rocker6", end("rocker6", -1), name="H")
    _pin(m, "B", kind, "slider9", (0.0, 0.0), "rod8", end("rod8", 1), journal_radius, c_b, dry, lub)
    m.prismatic("ground", (0.59, 0.0), "slider9", (0.0, 0.0), axis=(0.0, 1.0), name="guide")
    m.driver("crank1", omega=omega, angle0=0.0, name="drive1")
    m.driver("crank4", omega=omega, angle0=math.pi / 2, name="drive4")
    return m


__all__ = ["slider_crank", "nine_bar", "NINE_BAR_POINTS", "NINE_BAR_INERTIA"]


def driven_pendulum(drive: float, *, q: float = 2.0, drive_omega: float = 2.0 / 3.0, theta0: float = 0.2) -> Mechanism:
    """Baker & Gollub's damped driven pendulum, θ'' + θ'/q + sin θ = g cos(ω_D t), as a
    mechanism (Baker & Gollub, *Chaotic Dynamics*, 1996; docs/physics.md §13): body ``"bob"``
    (1 kg, its centroid 0.5 m below the pivot, J = 0.75 kg m², so 1 kg m² about the pivot),
    gravity 2 m/s² (m g l = 1 N m), a rotational damper of 1/q N m s to the ground and the
    torque ``clearsim.Harmonic(drive, drive_omega)`` [N m, rad/s]. Its angle θ is the bob's body
    angle, starting at ``theta0`` [rad] at rest. Time is the equation's own (1 s a unit), so the
    Baumgarte rates are 5 1/s, a few times its natural frequency of 1 rad/s (the default 50 1/s,
    set for machines turning at thousands of rpm, would make its steps 10–30 times shorter)."""
    from .forces import Harmonic

    m = Mechanism(gravity=(0.0, -2.0), baumgarte=(5.0, 5.0))
    m.add_body("bob", mass=1.0, inertia=0.75, position=(0.5 * math.sin(theta0), -0.5 * math.cos(theta0)), angle=theta0)
    m.revolute("ground", (0.0, 0.0), "bob", (0.0, 0.5), name="pivot")
    m.rotational_spring("ground", "bob", 0.0, damping=1.0 / q, angle0=0.0, name="damper")
    m.torque("bob", Harmonic(drive, drive_omega), name="drive")
    return m


def _ball_start(gamma: float, e: float, period: float, gravity: float) -> Tuple[float, float]:
    """(table phase θ0 [rad], height [m] of the ball above the table at t = 0) that put a ball
    moving with the table at t = 0 on the one-bounce-a-period orbit of restitution ``e``: it
    lands at the phase φ of that orbit (cos φ = π(1 − e)/((1 + e) Γ), sin φ > 0) at −g T/2."""
    w = 2 * math.pi / period
    amp = gamma * gravity / w**2
    phi = math.acos(math.pi * (1 - e) / ((1 + e) * gamma))
    # Landing at ω t_i + θ0 = φ (mod 2π) at −gT/2 from the table's speed A ω cos θ0 at t = 0:
    # ω t_i = Γ cos θ0 + π, so θ0 + Γ cos θ0 = φ − π (mod 2π), solved by bisection on [−π, π].
    f = lambda th: th + gamma * math.cos(th)  # noqa: E731
    target = phi - math.pi
    while target < f(-math.pi):
        target += 2 * math.pi
    while target > f(math.pi):
        target -= 2 * math.pi
    lo, hi = -math.pi, math.pi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < target:
            lo = mid
        else:
            hi = mid
    th0 = 0.5 * (lo + hi)
    u0 = amp * w * math.cos(th0)
    t_hit = (u0 + gravity * period / 2) / gravity
    return th0, amp * math.sin(phi) - amp * math.sin(th0) + t_hit * (gravity * period / 2 - u0) / 2


def bouncing_ball(
    gamma: float,
    *,
    restitution: float = 0.5,
    frequency: float = 50.0,
    clearance: float = 2e-3,
    ball_radius: float = 10e-3,
    height: Optional[float] = None,
    table_phase: Optional[float] = None,
    gravity: float = 9.81,
) -> Mechanism:
    """A ball bouncing on a table that vibrates vertically, z = A sin(ω t) with the shaking
    acceleration Γ = A ω²/g = ``gamma`` (Holmes 1982; docs/physics.md §13): a Scotch yoke
    (``crank`` turning at ω = 2π ``frequency`` about a pivot 0.1 m beside the table's vertical
    guide, ``block``, ``table``) moves the table exactly harmonically; the ``ball`` (33 g, a
    steel ball's mass, radius ``ball_radius`` [m]) hits the bottom of a bore ``clearance`` [m]
    larger in the table: a dry clearance joint ``"impact"`` (the Flores et al. law,
    ``restitution`` c_e, no friction). A stiff, critically damped horizontal spring-damper
    (``"centring"``, to a ground point 1 m aside) and rotational spring-damper (``"spin"``) hold
    the ball on the vertical line and its angle at 0 (their motions decay at ≥ 250 1/s and their
    vertical pull is below 1e-4 of its weight), so only its bouncing is left. The ball starts
    moving with the table (a clearance joint starts held), ``height`` [m] above the table's
    surface with the table at phase ``table_phase`` [rad] (z = A sin(ω t + table_phase)); by
    default both are chosen so that it lands at the phase and speed of the one-bounce-a-period
    orbit of c_e = ``restitution`` (cos φ = π(1 − c_e)/((1 + c_e) Γ), sin φ > 0, v = −g T/2:
    Holmes 1982) when Γ allows that orbit (else it starts at the table's phase 0 from the orbit's
    apex g T²/8): dropped anyhow, it may lock onto the table or bounce every other period. The
    chosen phase is the crank driver's ``angle0``."""
    w = 2 * math.pi * frequency
    amp = gamma * gravity / w**2
    period = 2 * math.pi / w
    if gamma > math.pi * (1 - restitution) / (1 + restitution):
        th0, h = _ball_start(gamma, restitution, period, gravity)
    else:
        th0, h = 0.0, gravity * period**2 / 8
    th0 = th0 if table_phase is None else table_phase
    h = h if height is None else height
    z0 = amp * math.sin(th0)
    m = Mechanism(gravity=(0.0, -gravity))
    m.add_body("crank", mass=0.1, inertia=1e-5, position=(0.1, 0.0), angle=th0)
    m.add_body("block", mass=0.01, inertia=1e-7, position=(0.1 + amp * math.cos(th0), z0))
    m.add_body("table", mass=1.0, inertia=1e-3, position=(0.0, z0))
    mass, e0 = 0.033, -clearance + h
    m.add_body("ball", mass=mass, inertia=1.3e-6, position=(0.0, z0 + e0))
    m.revolute("ground", (0.1, 0.0), "crank", (0.0, 0.0), name="crank-ground")
    m.revolute("crank", (amp, 0.0), "block", (0.0, 0.0), name="crank-pin")
    m.prismatic("table", (0.0, 0.0), "block", (0.0, 0.0), axis=(1.0, 0.0), name="slot")
    m.prismatic("ground", (0.0, 0.0), "table", (0.0, 0.0), axis=(0.0, 1.0), name="table-guide")
    stiffness = mass * 250.0**2
    y_mid = -clearance + gravity * period**2 / 16  # the ball's mean height over the bounce
    m.spring("ground", (-1.0, y_mid), "ball", (0.0, 0.0), stiffness, damping=2 * mass * 250.0, free_length=1.0, name="centring")
    m.rotational_spring("ground", "ball", 1.3e-6 * 1000.0**2, damping=2 * 1.3e-6 * 1000.0, angle0=0.0, name="spin")
    m.clearance_joint(
        "impact", "table", (0.0, 0.0), "ball", (0.0, 0.0), journal_radius=ball_radius, clearance=clearance,
        initial_eccentricity=(0.0, e0), model=Dry(normal_law="flores", restitution=restitution, friction=0.0),
    )  # fmt: skip
    m.driver("crank", omega=w, angle0=th0, name="shaker")
    return m
