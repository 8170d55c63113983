"""Deprecated: the old place of :mod:`clearsim.scene.study` (the ``[study]`` table of a scene
file); kept so ``clearsim.reliability.scene`` imports work. Import ``clearsim.scene.study``
instead.

Every name is looked up in :mod:`clearsim.scene.study` when it is first asked for, not imported
here: the reliability rooms sit below the scene rooms and import nothing of them (issue 29,
"every import runs downward")."""

from __future__ import annotations

import importlib
from typing import Any, List


def __getattr__(name: str) -> Any:
    return getattr(importlib.import_module("clearsim.scene.study"), name)


def __dir__() -> List[str]:
    return sorted(vars(importlib.import_module("clearsim.scene.study")))
