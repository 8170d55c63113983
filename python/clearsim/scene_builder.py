"""Deprecated: the old place of :mod:`clearsim.scene.builder` (building a scene file's
Mechanism entry by entry); a thin re-export kept so old imports work. Import
``clearsim.scene.builder`` instead."""

from .scene.builder import (  # noqa: F401  (private names old code and tests reach)
    _BODY_KEYS,
    _CLEARANCE_KEYS,
    _DRIVER_KEYS,
    _FORCE_KEYS,
    _JOINT_KEYS,
    _MECHANISM_KEYS,
    _PRISMATIC_CLEARANCE_KEYS,
    _Builder,
    _read_model,
)
