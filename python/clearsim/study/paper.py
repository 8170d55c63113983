"""Deprecated: :mod:`clearsim.paper` (the entry point :func:`clearsim.paper.run_paper_study`)."""

from __future__ import annotations

from ..paper import CASES, CLEARANCE_CASES, CLEARANCE_STUDY, FILMS, QUANTITIES, RELIABILITY_HEADER, SPEED_STUDY, Case, run_paper_study

__all__ = ["CASES", "CLEARANCE_CASES", "CLEARANCE_STUDY", "FILMS", "QUANTITIES", "RELIABILITY_HEADER", "SPEED_STUDY", "Case", "run_paper_study"]
