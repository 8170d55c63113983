"""Lubricated(film="finite") from Python: runs, differs from the closed forms where they are
wrong, and refuses bearings outside its L/D range by name."""

import math

import pytest

import clearsim
from clearsim import _core
from clearsim.errors import InputError

MU, R, C = 0.4, 0.01, 5e-4


def sommerfeld(film, l_over_d, eps):
    length = 2 * R * l_over_d
    f = _core.film_force(film, MU, R, C, length, eps, 0.0, 50.0)
    return math.hypot(*f) * (C / R) ** 2 / (length * 2 * R * MU * 50.0)


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
    m = clearsim.models.nine_bar("lubricated", 0.5e-3, lubricated=lub)
    with pytest.raises(InputError) as e:
        m.simulate(0.01, progress=False)
    assert "film" in str(e.value.field) and "L/D" in str(e.value)
    with pytest.raises(InputError):
        _core.film_force("finite", MU, R, C, 2.0, 0.5, 0.0, 50.0)
