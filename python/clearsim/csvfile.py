"""Every CSV file clearsim writes goes through this writer: a header row, one row per record,
numbers as the shortest text that reads back to the same float (Python's ``repr``: no digit
lost, none invented). A column with a unit is headed ``name [unit]`` with the unit in ASCII
(``m/s^2``, :func:`clearsim.schema.ascii_unit`), as ``Result.save``, ``clearsim run``,
``clearsim reliability`` and ``clearsim paper`` write them. A dimensionless quantity of the
physics (ε, a contact state) is headed ``name [1]``; labels, counts, probabilities and
reliability indices (``method``, ``runs``, ``pf``, ``beta``, ``reliability``) by a bare name.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from .errors import InputError
from .schema import ascii_unit

__all__ = ["DIMENSIONLESS", "QUANTITY", "REPORT_COLUMNS", "column_name", "file_unit", "report_header", "write_rows", "write_columns"]

#: The unit of a dimensionless quantity in a file header: ``1`` (the SI unit one, SI Brochure
#: §2.3.3; what CF/UDUNITS and pint read, and what ``Result.save(".nc")`` writes), never ``-``,
#: which Python text (axis labels, docstrings: ``R [-]``) may still use, as it writes ``m/s²``.
DIMENSIONLESS = "1"
#: Stands, in :data:`REPORT_COLUMNS`, for the unit of the analysed quantity (m, m/s, ...).
QUANTITY = "<quantity>"
#: Report columns whose Python key (a dict key of the public API: ``FosmResult.to_rows()``, the
#: rows of ``reliability.csv``) carries its unit as a suffix or is spelled otherwise in the
#: tables → (column name, unit or None). Keys not listed keep their name and have no unit.
REPORT_COLUMNS: Dict[str, Tuple[str, Optional[str]]] = {
    "angle_deg": ("bin_start", "deg"), "centre_deg": ("bin_centre", "deg"), "count": ("samples", None), "n_samples": ("samples", None),
    "mu_s": ("mu_s", QUANTITY), "sigma_s": ("sigma_s", QUANTITY), "mu_S": ("mu_S", QUANTITY), "sigma_S": ("sigma_S", QUANTITY),
    "wall_time_s": ("wall_time", "s"), "mean_peak": ("mean_peak", QUANTITY), "max_peak": ("max_peak", QUANTITY),
    "mean_depth_m": ("mean_depth", "m"), "max_depth_m": ("max_depth", "m"),
}  # fmt: skip


def file_unit(unit: str) -> str:
    """``unit`` as a file header writes it: ASCII (:func:`clearsim.schema.ascii_unit`), a
    dimensionless one (``-``, ``1`` or empty) as :data:`DIMENSIONLESS`."""
    return DIMENSIONLESS if unit in ("-", "1", "") else ascii_unit(unit)


def column_name(name: str, unit: Optional[str]) -> str:
    """``name [unit]`` (``slider9.y [m]``, ``A.eps [1]``; the unit in ASCII), or ``name``
    without a unit."""
    return name if unit is None else f"{name} [{file_unit(unit)}]"


def report_header(keys: Iterable[str], quantity_unit: Optional[str] = None) -> List[str]:
    """The CSV header of report rows with these dict ``keys`` (:data:`REPORT_COLUMNS`):
    ``angle_deg`` → ``bin_start [deg]``, ``mu_s`` → ``mu_s [m]`` for ``quantity_unit="m"``."""
    out = []
    for key in keys:
        name, unit = REPORT_COLUMNS.get(key, (key, None))
        if unit == QUANTITY:
            if quantity_unit is None:
                raise InputError(f"invalid quantity_unit = None: column {key!r} has the unit of the analysed quantity", field="quantity_unit", value=None)
            unit = quantity_unit
        out.append(column_name(name, unit))
    return out


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
    # + 0.0 writes a negative zero (a dry joint's power loss −0.0) as 0.0.
    rows = zip(*((np.asarray(values, dtype=float) + 0.0).tolist() for _, _, values in columns))
    return write_rows(path, [column_name(name, unit) for name, unit, _ in columns], rows, blank_nonfinite=blank_nonfinite)
