"""Load tables (docs/physics.md §10.3, ``clearsim.forces``): ``interpolation="cubic"`` against
closed forms through a run, a smooth rotating load whose points end no steps with the orbit of
the linear table's, periodic tables whose first point is off the wrap (they stalled the implicit
methods at the wrap corner on main), and bad input. The spline itself is tested against closed
forms in ``rust/table.rs`` (``cargo test table``); the step counts are benchmarked by
``benches/rotating_load.py``."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Dict

import numpy as np
import pytest

import clearsim

R, C, L, OMEGA, MU = 0.02, 4e-5, 0.01, 100.0, 0.0267


def rotor(load: Dict[str, Any], mass: float = 1.0) -> clearsim.Mechanism:
    """A rotor turning at OMEGA in a lubricated ground bearing (short film), loaded by ``load``."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("rotor", mass=mass, inertia=1e-3)
    m.driver("rotor", omega=OMEGA, angle0=0.0, name="spin")
    m.clearance_joint("pin", "ground", (0, 0), "rotor", (0, 0), journal_radius=R, clearance=C, model=clearsim.Lubricated(viscosity=MU, length=L, film="short"))
    m.force("rotor", (0.0, 0.0), load, name="load")
    return m


def test_a_cubic_table_of_a_cubic_load_gives_the_closed_form_motion() -> None:
    """A free body pushed by F(t) = a + b t + c t² + d t³ tabulated at six uneven times: the
    not-a-knot spline is that cubic, so the velocity is its integral over the mass, to the run's
    tolerance (a linear table misses by the chords' area)."""
    a, b, c, d, mass = 2.0, -3.0, 10.0, -6.0, 2.0
    ts = np.array([0.0, 0.1, 0.35, 0.5, 0.8, 1.0])
    force = a + b * ts + c * ts**2 + d * ts**3

    def run(interpolation: str) -> np.ndarray:
        m = clearsim.Mechanism(gravity=(0.0, 0.0))
        m.add_body("mass", mass=mass, inertia=1.0)
        m.force("mass", (0, 0), {"t": ts.tolist(), "fx": force.tolist(), "interpolation": interpolation})
        res = m.simulate(1.0, dt_out=0.25, integrator="rk45", rtol=1e-10, atol=1e-12, progress=False)
        return res.velocity("mass")[:, 0]

    t = np.array([0.0, 0.25, 0.5, 0.75, 1.0])
    want = (a * t + b * t**2 / 2 + c * t**3 / 3 + d * t**4 / 4) / mass
    assert np.allclose(run("cubic"), want, rtol=0, atol=1e-9)
    assert np.abs(run("linear") - want).max() > 1e-4


def rotating_load(points: int, interpolation: str) -> Dict[str, Any]:
    """F0 = 50 N turning with the rotor, tabulated every 360°/points, first point off the wrap."""
    rev = 2 * math.pi / OMEGA
    t = (np.arange(points) + 0.5) * rev / points
    return {"t": t.tolist(), "fx": (50.0 * np.cos(OMEGA * t)).tolist(), "fy": (50.0 * np.sin(OMEGA * t)).tolist(), "period": rev, "interpolation": interpolation}


def test_a_smooth_rotating_load_ends_no_steps_and_keeps_the_linear_tables_orbit() -> None:
    """720 points a revolution over 0.2 s (3 revolutions): the linear table ends a step at
    nearly every point it passes, the cubic one at none; the journal's orbit is the same within
    the run's tolerance atol + rtol |e|."""
    lin = rotor(rotating_load(720, "linear")).simulate(0.2, dt_out=1e-3, progress=False)
    cub = rotor(rotating_load(720, "cubic")).simulate(0.2, dt_out=1e-3, progress=False)
    assert lin.completed and cub.completed
    assert lin.stats["steps_to_switch"] > 1500 and cub.stats["steps_to_switch"] == 0
    assert cub.stats["steps"] < lin.stats["steps"] / 3
    e_lin, e_cub = lin._raw["joints"][:, 0, 0:2], cub._raw["joints"][:, 0, 0:2]
    assert np.all(np.abs(e_cub - e_lin) <= 1e-9 + 1e-6 * np.abs(e_lin))


#: Periodic tables whose first point is not at the wrap, with a large step between their last and
#: first values (a sawtooth): on main each stopped with a step-size underflow at the wrap corner
#: x₀ + k·period (the table held its last value there, then jumped).
WRAP_CASES = [
    ("time", "radau", 72, 1.0, 2000.0, 1.0, 1e-10),
    ("time", "rodas4", 720, 0.5, 2000.0, 1.0, 1e-11),
    ("angle", "radau", 72, 1.0, 20000.0, 0.1, 1e-11),
    ("angle", "rodas4", 72, 0.5, 20000.0, 0.1, 1e-11),
]


@pytest.mark.parametrize("kind, method, points, offset, f0, mass, atol", WRAP_CASES)
@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_a_periodic_table_off_the_wrap_runs_through_its_corner(kind: str, method: str, points: int, offset: float, f0: float, mass: float, atol: float, interpolation: str) -> None:
    s = (np.arange(points) + offset) / points
    values = {"fx": (f0 * s).tolist(), "fy": (f0 * np.sin(2 * np.pi * s)).tolist()}
    if interpolation == "cubic":  # linear: the default, no key (so the case runs on main too)
        values["interpolation"] = interpolation
    if kind == "time":
        table = {"t": (0.1 * s).tolist(), "period": 0.1, **values}
    else:
        table = {"driver": "spin", "angle": (2 * np.pi * s).tolist(), "period": 2 * np.pi, **values}
    res = rotor(table, mass).simulate(0.2, integrator=method, atol=atol, dt_out=0.01, progress=False, max_seconds=60)
    assert res.completed, res.failure


def test_a_periodic_table_is_continuous_over_the_wrap() -> None:
    """Between its last point and its first one period on, a linear periodic table is the straight
    line between them (read back through a free body's velocity: the impulse of that ramp)."""
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("mass", mass=1.0, inertia=1.0)
    # Points at 0.25 and 0.75 s of a 1 s period: 0 → 4 N, then back to 0 at 1.25 s.
    m.force("mass", (0, 0), {"t": [0.25, 0.75], "fx": [0.0, 4.0], "period": 1.0})
    res = m.simulate(1.25, dt_out=1.25, integrator="rk45", rtol=1e-10, atol=1e-12, progress=False)
    # ∫ over [0, 1.25]: the ramp down from 2 N at 0 (halfway from 4 N at −0.25 s to 0 at 0.25 s)
    # to 0 at 0.25 (0.25 N s), the ramp up (1 N s), the ramp down (1 N s).
    assert res.velocity("mass")[-1, 0] == pytest.approx(2.25, abs=1e-9)


def test_bad_table_input_names_its_field() -> None:
    m = clearsim.Mechanism(gravity=(0.0, 0.0))
    m.add_body("mass", mass=1.0, inertia=1.0)
    with pytest.raises(clearsim.InputError, match="interpolation"):
        m.force("mass", (0, 0), {"t": [0.0, 1.0], "fx": [0.0, 1.0], "interpolation": "quadratic"})
    with pytest.raises(clearsim.InputError, match=r"force 'saw'.fx.y\[2\]"):  # as it is added
        m.force("mass", (0, 0), {"t": [0.0, 0.5, 1.0], "fx": [0.0, 1.0, 2.0], "period": 1.0, "interpolation": "cubic"}, name="saw")


def test_the_scene_key(tmp_path: Path) -> None:
    scene = tmp_path / "load.toml"
    scene.write_text(
        """
[mechanism]
gravity = [0.0, 0.0]
[simulation]
t_end = 0.01
[[body]]
name = "mass"
mass = 1.0
inertia = 1.0
[[force]]
type = "force"
body = "mass"
value = { t = [0.0, 0.5, 1.0, 1.5], fx = [0.0, 1.0, 0.0, 1.0], interpolation = "cubic" }
"""
    )
    m = clearsim.load_scene(scene)
    assert m.description()["forces"][0]["fx"]["table"]["interpolation"] == "cubic"
    scene.write_text(scene.read_text().replace('"cubic"', '"spline"'))
    with pytest.raises(clearsim.InputError, match="interpolation"):
        clearsim.load_scene(scene)
