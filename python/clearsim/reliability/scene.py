"""Deprecated: the old place of the ``[study]`` table's reader, now :mod:`clearsim.scene.study`;
kept so that old code reaching it through this module's path still works.

Each name is looked up there when first asked for, and not imported here: the reliability
rooms sit below the scene rooms and depend on nothing of them (issue 29, "every import runs
downward")."""

from __future__ import annotations

import importlib
from typing import Any, List

#: The module this one redirects to (a runtime lookup on first use, the one way this
#: deprecated path reaches above the reliability rooms).
_NEW_HOME = "clearsim.scene.study"


def __getattr__(name: str) -> Any:
    return getattr(importlib.import_module(_NEW_HOME), name)


def __dir__() -> List[str]:
    return sorted(vars(importlib.import_module(_NEW_HOME)))
