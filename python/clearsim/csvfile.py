"""Every CSV file clearsim writes goes through this writer: a header row, one row per record,
numbers as the shortest text that reads back to the same float (Python's ``repr``: no digit
lost, none invented). A column with a unit is headed ``name [unit]`` with the unit in ASCII
(``m/s^2``, :func:`clearsim.schema.ascii_unit`), as ``Result.save``, ``clearsim run`` and
``clearsim reliability`` write them.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from .schema import ascii_unit

__all__ = ["column_name", "write_rows", "write_columns"]


def column_name(name: str, unit: Optional[str]) -> str:
    """``name [unit]`` (``slider9.y [m]``; the unit in ASCII), or ``name`` without a unit."""
    return name if unit is None else f"{name} [{ascii_unit(unit)}]"


def _cell(value: Any, blank_nonfinite: bool) -> Any:
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float):
        return "" if blank_nonfinite and not math.isfinite(value) else repr(value)
    return value


def write_rows(path: Union[str, Path], header: Sequence[str], rows: Iterable[Sequence[Any]], *, blank_nonfinite: bool = False) -> Path:
    """Write ``header`` and ``rows`` to ``path``; floats at full precision (``repr``), NaN and
    ±inf as ``nan``/``inf`` or, with ``blank_nonfinite``, as empty cells. Returns the path."""
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(list(header))
        for row in rows:
            w.writerow([_cell(v, blank_nonfinite) for v in row])
    return path


def write_columns(path: Union[str, Path], columns: Sequence[Tuple[str, Optional[str], Any]], *, blank_nonfinite: bool = False) -> Path:
    """Write equal-length columns ``(name, unit or None, values)`` to ``path``, one row per
    index, headed by :func:`column_name`. Returns the path."""
    rows = zip(*(np.asarray(values, dtype=float).tolist() for _, _, values in columns))
    return write_rows(path, [column_name(name, unit) for name, unit, _ in columns], rows, blank_nonfinite=blank_nonfinite)
