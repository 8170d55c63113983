"""Lubricated(film="finite") from Python: runs, differs from the closed forms where they are
wrong, and refuses bearings outside its L/D range by name."""

import math
import os

import pytest

import clearsim
from clearsim import _core
from clearsim.errors import InputError

MU, R, C = 0.4, 0.01, 5e-4


def sommerfeld(film, l_over_d, eps):
    length = 2 * R * l_over_d
    f = _core.film_force(film, MU, R, C, length, eps, 0.0, 50.0)
    return math.hypot(*f) * (C / R) ** 2 / (length * 2 * R * MU * 50.0)


def in_a_joint(model: object) -> None:
    """Compile ``model`` in a pinned body: its values are checked by the core (issue 29, validation once)."""
    m = clearsim.Mechanism()
    m.add_body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0, 0), "b", (0, 0), journal_radius=0.01, clearance=1e-4, model=model)  # type: ignore[arg-type]
    m.compile()

def test_finite_tends_to_the_short_form_for_short_bearings_and_departs_from_it_for_long_ones():
    assert sommerfeld("finite", 1 / 16, 0.3) == pytest.approx(sommerfeld("short", 1 / 16, 0.3), rel=0.03)
    assert sommerfeld("short", 2.5, 0.5) > 3 * sommerfeld("finite", 2.5, 0.5)


def test_nine_bar_runs_with_the_finite_bearing():
    lub = clearsim.Lubricated(viscosity=0.4, length=0.05, film="finite")
    m = clearsim.models.nine_bar("lubricated", 0.5e-3, lubricated=lub)
    res = m.simulate(0.1, dt_out=1e-3, progress=False)
    assert res.completed
    eps = [math.hypot(*e) / 0.5e-3 for e in res.eccentricity("B")]
    assert max(eps) < 1.0 and res.film_force("B").any()


@pytest.mark.filterwarnings("ignore::clearsim.errors.PlausibilityWarning")  # a 2 m bearing on purpose
def test_bearing_outside_the_finite_range_is_named():
    lub = clearsim.Lubricated(viscosity=0.4, length=2.0, film="finite")  # L/D = 100
    with pytest.raises(InputError) as e:  # named as the joint is added
        clearsim.models.nine_bar("lubricated", 0.5e-3, lubricated=lub)
    assert e.value.field == "clearance joint 'A'.film" and "L/D" in str(e.value)
    with pytest.raises(InputError):
        _core.film_force("finite", MU, R, C, 2.0, 0.5, 0.0, 50.0)


def attitude(supply, l_over_d, eps):
    f = _core.film_force("finite", MU, R, C, 2 * R * l_over_d, eps, 0.0, 50.0, supply=supply)
    return math.degrees(math.atan2(abs(f[1]), -f[0]))


def test_supply_line_is_the_default_and_changes_the_paper_bearing():
    """The default supply line (Butenschön's rotation table, the paper's P12) against the periodic
    film at the paper's L/D = 2.5, ε = 0.5: the attitude falls by ~10° (docs/physics.md §4)."""
    assert clearsim.Lubricated().supply == "widest_gap"
    assert _core.film_force("finite", MU, R, C, 0.05, 0.5, 0.0, 50.0) == _core.film_force("finite", MU, R, C, 0.05, 0.5, 0.0, 50.0, supply="widest_gap")
    assert attitude("none", 2.5, 0.5) - attitude("widest_gap", 2.5, 0.5) > 8.0
    # Butenschön, B/D = 1, ε = 0.3: β = 68.264° with the line.
    assert attitude("widest_gap", 1.0, 0.3) == pytest.approx(68.264, abs=0.5)
    assert attitude("none", 1.0, 0.3) > 70.5


def test_supply_is_checked_by_name():
    with pytest.raises(InputError) as e:
        in_a_joint(clearsim.Lubricated(film="finite", supply="feed_hole"))
    assert e.value.field == "supply"  # the Lubricated model is checked as it is made, before its joint
    with pytest.raises(InputError) as e:
        _core.film_force("finite", MU, R, C, 0.05, 0.5, 0.0, 50.0, supply="feed_hole")
    # The long films have their own convention (P12); the short film has no flow around.
    with pytest.raises(InputError) as e:  # as the model is made
        clearsim.Lubricated(film="long", supply="none")
    assert "supply" in str(e.value.field) and "finite" in str(e.value)


def test_a_second_process_loads_the_table_from_the_disk_cache(tmp_path):
    """Issue 28 item 9: the first process solves the table and writes it to the cache directory,
    the next one loads it (no solve) and gets the same numbers; a damaged file is solved again."""
    import subprocess
    import sys

    code = (
        "from clearsim import _core\n"
        "f = _core.film_force('finite', 0.4, 0.01, 5e-4, 0.0123, 0.42, 0.7, 31.0)\n"
        "print(*_core.finite_table_counts(), repr(f))\n"
    )
    env = dict(os.environ, CLEARSIM_CACHE_DIR=str(tmp_path / "cache"))

    def run():
        out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout.split(maxsplit=2)
        return int(out[0]), int(out[1]), out[2].strip()

    built, loaded, first = run()
    assert (built, loaded) == (1, 0)
    files = list((tmp_path / "cache").iterdir())
    assert len(files) == 1 and "widest_gap" in files[0].name
    assert run() == (0, 1, first)
    files[0].write_bytes(files[0].read_bytes()[:-100])
    assert run() == (1, 0, first)
