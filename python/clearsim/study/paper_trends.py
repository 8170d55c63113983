"""Deprecated: :mod:`clearsim.paper.trends`."""

from __future__ import annotations

from ..paper.trends import FAILS, HOLDS, NOT_EVALUABLE, Check, Trend, _trends

__all__ = ["Check", "Trend", "HOLDS", "FAILS", "NOT_EVALUABLE", "_trends"]
