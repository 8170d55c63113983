"""Archard wear at a dry revolute clearance joint against the closed form (docs/physics.md §12)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clearsim
import clearsim.plots
from clearsim import Archard, InputError

K, H, L = 1e-4, 2e9, 0.02
M, R_J, C, OMEGA, T = 2.0, 0.01, 1e-4, 50.0, 2.0


def spinning_pin(dt_out=None) -> clearsim.Result:
    """A pin driven at ω in a fixed bearing, resting on its bottom under gravity (no friction):
    the normal impulse over [0, T] is m g T once it rests, the slip speed R_j ω, so
    V = (k/H) m g R_j ω T."""
    m = clearsim.Mechanism(gravity=(0, -9.81))
    m.add_body("pin", mass=M, inertia=1e-3, position=(0, 0))
    m.driver("pin", omega=OMEGA)
    dry = clearsim.Dry(friction=0.0, restitution=0.5, wear=Archard(K, H, L))
    m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=dry)
    return m.simulate(T, dt_out=dt_out, rtol=1e-8, atol=1e-11, progress=False)


def worn_joint(wear: Archard) -> None:
    """Compile a dry joint with ``wear``: the core checks its values (issue 29, validation once)."""
    m = clearsim.Mechanism()
    m.add_body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.0))
    m.clearance_joint("pin", "ground", (0, 0), "b", (0, 0), journal_radius=0.01, clearance=1e-4, model=clearsim.Dry(wear=wear))
    m.compile()

def test_worn_volume_and_depth_against_the_closed_form():
    res = spinning_pin()
    volume = K / H * M * 9.81 * R_J * OMEGA * T
    assert res.wear_volume("J") == pytest.approx(volume, rel=1e-6)
    dphi = 2 * math.pi / 360
    angle, depth = res.wear("J")
    assert math.degrees(angle[np.argmax(depth)]) == pytest.approx(270.5)  # the bottom of the bearing
    assert depth.max() == pytest.approx(volume / (L * (R_J + C) * dphi), rel=1e-3)
    assert (depth * L * (R_J + C) * dphi).sum() == pytest.approx(volume, rel=1e-12)
    # The spinning journal wears all round: 15.9 turns spread the volume over every bin.
    _, journal = res.wear("J", "journal")
    assert np.all(journal > 0) and (journal * L * R_J * dphi).sum() == pytest.approx(volume, rel=1e-12)
    # Even all round (15.9 turns: the last 0.9 turn adds 6 %), but for the first impact's spot.
    assert np.median(journal) == pytest.approx(volume / (L * R_J * 2 * math.pi), rel=0.07)


def test_wear_does_not_depend_on_the_output_grid():
    coarse, fine = spinning_pin(dt_out=T / 4), spinning_pin(dt_out=T / 4000)
    assert np.array_equal(coarse.wear("J")[1], fine.wear("J")[1])


def test_wear_plot_and_errors():
    res = spinning_pin()
    fig = clearsim.plots.plot_wear(res, "J")
    assert len(fig.axes) == 2
    with pytest.raises(InputError) as err:
        worn_joint(Archard(-1e-4, H, L))
    assert err.value.field == "wear.coefficient"  # where the model is made, before its joint
    with pytest.raises(InputError, match="no wear"):
        clearsim.models.slider_crank("dry").simulate(1e-3, progress=False).wear("rod-slider")
    m = clearsim.Mechanism()
    m.add_body("s", mass=1.0, inertia=1e-3, position=(0, 0))
    with pytest.raises(InputError, match="revolute clearance joints only"):
        m.prismatic_clearance("ground", (0, 0), "s", (1, 0), 1e-3, 0.05, clearsim.Dry(wear=Archard(K, H, L)))


def test_fed_back_wear_lets_the_pin_sink_by_the_worn_depth():
    """With feedback the contact law measures penetration from the worn surfaces: the pin
    resting on the bottom of its bearing sinks, against the same run without feedback, by the
    bearing's depth at the bottom plus the journal's (spread all round as it spins)."""

    def run(feedback):
        m = clearsim.Mechanism(gravity=(0, -9.81))
        m.add_body("pin", mass=M, inertia=1e-3, position=(0, 0))
        m.driver("pin", omega=OMEGA)
        dry = clearsim.Dry(friction=0.0, restitution=0.5, wear=Archard(K, H, L, feedback=feedback))
        m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=dry)
        return m.simulate(T, dt_out=T / 20, rtol=1e-8, atol=1e-11, progress=False)

    plain, worn = run(False), run(True)
    sink = plain.position("pin")[-1, 1] - worn.position("pin")[-1, 1]
    _, bearing = worn.wear("J")
    _, journal = worn.wear("J", "journal")
    expected = bearing.max() + np.median(journal)
    assert expected > 1e-7  # 0.28 µm: well above the integration tolerance
    assert sink == pytest.approx(expected, rel=0.02)
    # The same volume is worn either way (the load and the slip do not change).
    assert worn.wear_volume("J") == pytest.approx(plain.wear_volume("J"), rel=1e-6)


def test_a_run_continues_from_the_worn_state_of_an_earlier_one():
    """Two runs of T/2, the second started from the first's worn depths, wear the pin resting
    on its bearing's bottom as deep as one run of T (the load and the slip are steady), and the
    second sinks as deep as the single run at its end: the depth it starts from is fed back."""

    def run(t_end, worn=None):
        m = clearsim.Mechanism(gravity=(0, -9.81))
        m.add_body("pin", mass=M, inertia=1e-3, position=(0, 0))
        m.driver("pin", omega=OMEGA)
        law = Archard(K, H, L, feedback=True, **({} if worn is None else {"initial_bearing": worn[0], "initial_journal": worn[1]}))
        m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=clearsim.Dry(friction=0.0, restitution=0.5, wear=law))
        return m.simulate(t_end, dt_out=t_end / 20, rtol=1e-8, atol=1e-11, progress=False)

    whole = run(T)
    first = run(T / 2)
    second = run(T / 2, (first.wear("J")[1], first.wear("J", "journal")[1]))
    assert second.wear("J")[1].max() == pytest.approx(whole.wear("J")[1].max(), rel=0.02)
    assert second.wear_volume("J") == pytest.approx(first.wear_volume("J"), rel=1e-3)  # only its own
    assert second.position("pin")[-1, 1] == pytest.approx(whole.position("pin")[-1, 1], abs=0.02 * whole.wear("J")[1].max())
    with pytest.raises(InputError, match="360") as err:
        worn_joint(Archard(K, H, L, initial_bearing=[0.0] * 10))
    assert err.value.field == "wear.initial_bearing"  # where the model is made, before its joint
    with pytest.raises(InputError) as err:
        worn_joint(Archard(K, H, L, initial_journal=[0.0] * 359 + [-1e-9]))
    assert err.value.field == "wear.initial_journal[359]"


def test_the_wear_mark_reads_the_books_inside_a_run():
    """``wear_mark`` (run settings) reads the books at a time inside the run: what a run of T
    had worn at T/2 is what a run stopped at T/2 wore (the same steps up to there, the mark
    interpolated within its step)."""
    from clearsim import _core

    def pin():
        m = clearsim.Mechanism(gravity=(0, -9.81))
        m.add_body("pin", mass=M, inertia=1e-3, position=(0, 0))
        m.driver("pin", omega=OMEGA)
        m.clearance_joint("J", "ground", (0, 0), "pin", (0, 0), journal_radius=R_J, clearance=C, model=clearsim.Dry(friction=0.0, restitution=0.5, wear=Archard(K, H, L)))
        return m

    m = pin()
    s = m.run_settings(T, t_out=np.array([0.0, T]), outputs=["states"], rtol=1e-8, atol=1e-11)
    s["wear_mark"] = T / 2
    book = _core.run_batch([m.description()], [s], 1)[0]["wear"][0]
    half = pin().simulate(T / 2, dt_out=T / 2, rtol=1e-8, atol=1e-11, progress=False)
    assert book["volume_at_mark"] == pytest.approx(half.wear_volume("J"), rel=1e-3)
    assert np.abs(book["bearing_at_mark"] - half.wear("J")[1]).max() < 1e-3 * half.wear("J")[1].max()
    s["wear_mark"] = 2 * T
    with pytest.raises(InputError, match="wear_mark"):
        _core.run_batch([m.description()], [s], 1)
