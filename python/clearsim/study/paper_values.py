"""Deprecated: :mod:`clearsim.paper.values`."""

from __future__ import annotations

from ..paper.values import DISPLACEMENT_CYCLE_MINIMA, MINIMA, PEAKS

__all__ = ["PEAKS", "MINIMA", "DISPLACEMENT_CYCLE_MINIMA"]
