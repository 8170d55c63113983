"""The heated rotor the oil-temperature tests and benches run, and the heat balance it is
checked against, written without clearsim's heat model (docs/physics.md §4, *Heat*):

- a rotor driven at OMEGA in a ground bearing (R = 20 mm, c = 40 µm, L = 10 mm, a short film),
  with an ISO VG 32 oil (Vogel: μ(40 °C) = 0.0267 Pa s, μ(100 °C) = 0.0047 Pa s);
- Petroff's power loss of a centred journal, 2πμR³Lω²/c, and the steady temperature where it
  equals what the ambient takes away, T = T_amb + P(μ(T))/hA, found by bisection.

Used by tests/python/test_heat.py, tests/python/test_dynamics.py and benches/heat_warmup.py.
"""

from __future__ import annotations

import math

import clearsim

R, C, L, OMEGA = 0.02, 4e-5, 0.01, 100.0
#: An oil of ISO VG 32 grade: μ(40 °C) = 0.0267 Pa s, μ(100 °C) = 0.0047 Pa s.
OIL = clearsim.Vogel(6.4e-5, 900.0, 164.0)
T_AMB = 313.15


def rotor(model: clearsim.Lubricated, mass: float = 1.0, gravity: float = 0.0) -> clearsim.Mechanism:
    """A rotor of ``mass`` [kg] driven at OMEGA in a ground bearing of clearance joint ``pin``
    with ``model``, under ``gravity`` [m/s²] (0: unloaded, centred)."""
    m = clearsim.Mechanism(gravity=(0.0, -gravity))
    m.add_body("rotor", mass=mass, inertia=1e-3)
    m.driver("rotor", omega=OMEGA, angle0=0.0)
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=model)
    return m


def petroff_loss(mu: float) -> float:
    """Petroff's power loss of a centred journal, 2πμR³Lω²/c [W]."""
    return 2 * math.pi * mu * R**3 * L * OMEGA**2 / C


def fixed_point(h_a: float) -> float:
    """The steady temperature [K]: the root of T − T_amb − P(μ(T))/hA by bisection."""
    lo, hi = T_AMB, T_AMB + petroff_loss(OIL.viscosity(T_AMB)) / h_a
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid - T_AMB - petroff_loss(OIL.viscosity(mid)) / h_a < 0 else (lo, mid)
    return lo


def rotor_scene(viscosity: str, heat_capacity: float, heat_transfer: float, t_end: float, simulation: str = "", film: str = "") -> str:
    """The unloaded rotor of :func:`rotor` as a scene file's text: its oil's ``viscosity`` as
    TOML (a number [Pa s], or ``{vogel = [a, b, c]}``), its heat model (ambient T_AMB,
    ``heat_capacity`` [J/K], ``heat_transfer`` [W/K]), run to ``t_end`` [s]; ``simulation``: more
    lines of the [simulation] table and tables after it, ``film``: more keys of the lubricated
    model."""
    return f"""
[mechanism]
gravity = [0.0, 0.0]
[simulation]
t_end = {t_end}
{simulation}
[[body]]
name = "rotor"
mass = 1.0
inertia = 1e-3
[[driver]]
body = "rotor"
omega = {OMEGA}
angle0 = 0.0
[[clearance_joint]]
name = "pin"
bearing_body = "ground"
bearing_point = [0.0, 0.0]
journal_body = "rotor"
journal_point = [0.0, 0.0]
journal_radius = {R}
clearance = {C}
model = "lubricated"
[clearance_joint.lubricated]
viscosity = {viscosity}
length = {L}
film = "short"
{film}
[clearance_joint.lubricated.thermal]
ambient = {T_AMB}
heat_capacity = {heat_capacity}
heat_transfer = {heat_transfer}
"""
