"""Deprecated: the old place of :mod:`clearsim.scene.toml_reader` (a TOML file read with line
numbers); a thin re-export kept so old imports work. Import ``clearsim.scene.toml_reader``
instead."""

from .scene.toml_reader import REQUIRED, Source, Table, Where, dotted_key, read_toml  # noqa: F401

__all__ = ["REQUIRED", "Source", "Table", "Where", "dotted_key", "read_toml"]
