"""Studies built on clearsim: ready-made reproductions of published analyses.

:mod:`clearsim.study.paper` reproduces the seed paper's study (docs/physics.md §7): clearance sizes
0.3/0.5 mm and drive speeds 5π/8π rad/s of the nine-bar mechanism, dry against lubricated,
with error histories, journal orbits and FOSM dynamic-accuracy reliability
(``clearsim paper`` on the command line).
"""

from __future__ import annotations

__all__ = ["paper"]
