"""Third-party modules imported on first use: ``import clearsim`` does not pay for scipy's
submodules (``scipy.stats`` alone took a second of its 1.8 s, issue 29) until a method needs them.

``special = lazy("scipy.special")`` stands where ``from scipy import special`` stood; the first
attribute read imports the module, later reads go straight to it.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any, Optional


class _Lazy:
    """A module imported when one of its attributes is first read."""

    def __init__(self, name: str) -> None:
        self._name = name
        self._module: Optional[ModuleType] = None

    def __getattr__(self, attr: str) -> Any:
        if self._module is None:
            self._module = importlib.import_module(self._name)
        return getattr(self._module, attr)

    def __repr__(self) -> str:
        return f"<module {self._name!r} imported on first use>"


def lazy(name: str) -> Any:
    """The module ``name`` (``"scipy.special"``), imported when first used."""
    return _Lazy(name)


__all__ = ["lazy"]
