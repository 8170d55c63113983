"""Short displays of clearsim's result objects: a one-line ``repr`` of the key numbers (arrays
by their shape, never their values) and a small HTML table for notebooks (``_repr_html_``).

A class shows itself with two one-line methods::

    def __repr__(self) -> str:
        return display.text(self, "pf", "interval", "n_runs", "failures")

    def _repr_html_(self) -> str:
        return display.html(self, "pf", "interval", "n_runs", "failures")

naming the attributes to show, in order (default: every dataclass field). :func:`png` is a
figure's picture for a notebook (``_repr_png_``: clearsim's figures, :class:`clearsim.plots.theme.NotebookFigure`,
and a Mechanism's drawing).
"""

from __future__ import annotations

import dataclasses
import html as _html
import math
from typing import Any, Iterable, List, Mapping, Optional, Sequence, Tuple

import numpy as np

#: The longest ``repr`` (characters): a result never prints pages.
MAX_REPR = 400
#: Display names of attribute names that say less than they could.
LABELS = {"pf": "p_f", "n_runs": "runs"}


def _number(x: Any) -> str:
    v = float(x)
    if isinstance(x, (bool, np.bool_)):
        return str(bool(x))
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return f"{v:.4g}" if math.isfinite(v) else str(v)


def short(value: Any, depth: int = 0) -> str:
    """A value in a few characters: numbers to 4 significant digits, arrays and long lists by
    their shape or length, small mappings and tuples of numbers in full."""
    if value is None or isinstance(value, str):
        return repr(value) if isinstance(value, str) and len(value) <= 40 else (repr(value[:37]) + "…" if isinstance(value, str) else "None")
    if isinstance(value, (bool, np.bool_, int, float, np.integer, np.floating)):
        return _number(value)
    if isinstance(value, np.ndarray):
        return f"array{value.shape}" if value.size != 1 else _number(value.reshape(-1)[0])
    if isinstance(value, Mapping):
        if depth > 0 or len(value) > 4:
            return f"{{{len(value)} entries}}"
        return "{" + ", ".join(f"{k!s}: {short(v, depth + 1)}" for k, v in value.items()) + "}"
    if isinstance(value, tuple) and hasattr(value, "_fields"):  # a NamedTuple, e.g. Estimate(p, lo, hi)
        return "(" + ", ".join(f"{k}={short(v, depth + 1)}" for k, v in zip(value._fields, value)) + ")"
    if isinstance(value, (list, tuple)):
        if len(value) <= 3 and all(isinstance(v, (int, float, np.integer, np.floating)) for v in value):
            inner = ", ".join(_number(v) for v in value)
            return f"({inner})" if isinstance(value, tuple) else f"[{inner}]"
        return f"[{len(value)} items]" if value else "[]"
    text = repr(value)
    limit = 60 if depth else 100
    return text if len(text) <= limit else f"<{type(value).__name__}>"


def _fields(obj: Any, names: Sequence[str]) -> List[Tuple[str, Any]]:
    if not names:
        names = [f.name for f in dataclasses.fields(obj)] if dataclasses.is_dataclass(obj) else list(vars(obj))
    out: List[Tuple[str, Any]] = []
    for name in names:
        value = getattr(obj, name, None)
        if name in ("failures",) and isinstance(value, (list, tuple)):
            value = len(value)  # a count: the reasons are in .failures / .failure_reasons()
        out.append((LABELS.get(name, name), value))
    return out


def line(name: str, rows: Iterable[Tuple[str, Any]]) -> str:
    """``name(label=value, ...)``, at most :data:`MAX_REPR` characters."""
    out = f"{name}({', '.join(f'{label}={short(value)}' for label, value in rows)})"
    return out if len(out) <= MAX_REPR else out[: MAX_REPR - 2] + "…)"


def text(obj: Any, *names: str) -> str:
    """``ClassName(name=value, ...)`` of the named attributes, at most :data:`MAX_REPR` characters."""
    return line(type(obj).__name__, _fields(obj, names))


def table(title: str, rows: Iterable[Tuple[str, Any]]) -> str:
    """An HTML table: a caption and one row per (label, value)."""
    cells = "".join(
        f"<tr><th style='text-align:left'>{_html.escape(str(k))}</th><td style='text-align:left'>{_html.escape(v if isinstance(v, str) else short(v))}</td></tr>"
        for k, v in rows
    )
    return f"<table><caption style='text-align:left'><b>{_html.escape(title)}</b></caption>{cells}</table>"


def html(obj: Any, *names: str) -> str:
    """The named attributes of ``obj`` as an HTML table captioned with its class name."""
    return table(type(obj).__name__, [(label, short(value)) for label, value in _fields(obj, names)])


def png(fig: Any, dpi: Optional[float] = None) -> bytes:
    """A matplotlib figure as PNG bytes at ``dpi`` (default: the figure's own, 100 for clearsim's
    figures), cropped to what it draws (a tight bounding box with a 0.05-inch margin: no wide
    white frame around a flat drawing)."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not hasattr(fig.canvas, "print_png"):
        FigureCanvasAgg(fig)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi if dpi is not None else fig.dpi, bbox_inches="tight", pad_inches=0.05)
    return buf.getvalue()


__all__ = ["MAX_REPR", "html", "line", "png", "short", "table", "text"]
