"""Deprecated: the paper study is :mod:`clearsim.paper` (``clearsim paper``); this package and its
modules ``paper``, ``paper_runs``, ``paper_files``, ``paper_report``, ``paper_trends`` and
``paper_values`` only re-export its names under their old paths (the word "study" now names
:class:`clearsim.reliability.Study` alone). Nothing imports it on ``import clearsim``.
"""

from __future__ import annotations

__all__ = ["paper"]
