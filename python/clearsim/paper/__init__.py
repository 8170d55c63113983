"""The paper study: reproduction of the seed paper's study (docs/physics.md §7, paper §5),
``clearsim paper``.

The nine-bar mechanism (:func:`clearsim.models.nine_bar`) with clearance joints A and B is run

* for the **clearance study** at ω = −5π rad/s with c = 0.3 and 0.5 mm, dry and lubricated
  (μ = 0.4 Pa s, L = 50 mm), and
* for the **speed study** at c = 0.6 mm with ω = −5π and −8π rad/s, dry and lubricated,

together with the ideal mechanism at each speed, for ``cycles`` crank cycles (period 2π/|ω|) on an
output grid of 0.5° of crank angle. The errors of slider 9's y displacement, velocity and
acceleration against the ideal run (docs/physics.md §5) give the paper's Figs. 8–16 (error histories,
journal-centre orbits, FOSM reliability per 18° bin, docs/physics.md §6), CSV files of every curve and a
``report.md`` that sets our numbers next to the paper's and checks the paper's trends.

Start-up transient: the journals start centred (e = 0), so the first cycle contains the fall of
each journal to the bearing wall (dry) or the build-up of the film's equilibrium orbit
(lubricated). The pooled reliability statistics and the trend checks use cycles 2 … ``cycles``
(all cycles when ``cycles`` is 1); the displacement reliability is also given per cycle over
*all* cycles, like the paper's Fig. 11a, and the error peaks over the whole run and within the
first cycle (where all of the paper's reported peak times lie).

Entry point: :func:`run_paper_study`. The modules by job: cases.py (the runs it makes), runs.py
(running them through :mod:`clearsim.batch`), analysis.py (errors, peaks, FOSM per bin),
trends.py (the paper's claims checked), values.py (the paper's printed numbers), files.py (CSV
files and figures), report.py (``report.md``), reproduce.py (the entry point).
"""

from __future__ import annotations

from .cases import CASES, CLEARANCE_CASES, CLEARANCE_STUDY, FILMS, QUANTITIES, SPEED_STUDY, Case
from .files import RELIABILITY_HEADER
from .reproduce import run_paper_study

__all__ = ["CASES", "CLEARANCE_CASES", "CLEARANCE_STUDY", "FILMS", "QUANTITIES", "RELIABILITY_HEADER", "SPEED_STUDY", "Case", "run_paper_study"]
