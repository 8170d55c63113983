"""Deprecated: :mod:`clearsim.paper.report`."""

from __future__ import annotations

from ..paper.report import _films_section, _report

__all__ = ["_report", "_films_section"]
