"""Deprecated: :mod:`clearsim.paper.files`."""

from __future__ import annotations

from ..paper.files import RELIABILITY_HEADER, _error_files, _orbit_files, _reliability_files, _summary_csvs, _write_csv

__all__ = ["RELIABILITY_HEADER", "_error_files", "_orbit_files", "_reliability_files", "_summary_csvs", "_write_csv"]
