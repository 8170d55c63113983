"""The performance fingerprint (benches/perf_fingerprint.py): the counts of work of a fixed set of
runs — steps, rejections, right-hand sides, Newton matrices and force-law evaluations — must equal
the stored ones in benches/perf_fingerprint.json, so that no change of cost goes unseen (issue 37:
always-on monitors made every lubricated RK45 step 2.3–3.2× dearer and no count showed it)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("clearsim_perf_fingerprint", ROOT / "benches" / "perf_fingerprint.py")
assert _spec is not None and _spec.loader is not None
fingerprint = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fingerprint)


def test_the_counts_of_work_are_the_stored_ones() -> None:
    stored = fingerprint.stored()
    assert stored, f"no fingerprint in {fingerprint.PATH}: run python benches/perf_fingerprint.py --update"
    moved = fingerprint.differences(stored, fingerprint.measure())
    assert not moved, (
        "the performance fingerprint moved:\n  " + "\n  ".join(moved) + "\nIf the change means to move them, run "
        "`python benches/perf_fingerprint.py --update` and say in the commit message which counts moved and why "
        "(a change of cost must be on purpose; per-step timings: cargo bench)."
    )


def test_a_change_of_work_shows_in_the_fingerprint() -> None:
    """The counts see work that no step count shows: tracking the bearing summary adds force-law
    evaluations only (its start and the last step's end), exact film monitors add thousands."""
    build, t_end, _ = fingerprint.RUNS["slider_crank_lubricated rk45, one cycle"]
    m = build()
    plain = m.simulate(t_end, integrator="rk45", progress=False).stats
    tracked = m.simulate(t_end, integrator="rk45", bearings=True, progress=False).stats
    monitored = m.simulate(t_end, integrator="rk45", extremes=["rod-slider"], progress=False).stats
    same = ("steps", "rejected_steps", "rhs_evaluations")
    assert [plain[k] for k in same] == [tracked[k] for k in same] == [monitored[k] for k in same]
    assert tracked["force_evaluations"] == plain["force_evaluations"] + 1  # the start; the steps reuse the last stage's
    assert monitored["force_evaluations"] > plain["force_evaluations"] + 3 * plain["steps"]
    assert fingerprint.differences({"a": {"steps": 1}}, {"a": {"steps": 2}}) == ["a: steps 1 → 2 (+100.0%)"]
