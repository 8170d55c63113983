"""A TOML file read with line numbers: typed tables whose errors name the file, the line and the
key (tomllib gives no positions). Used by the scene files (:mod:`clearsim.scene`).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from ..errors import InputError
from .parameters import ExpressionError, evaluate

try:  # Python ≥ 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - Python < 3.11
    try:
        import tomli as _toml  # type: ignore[no-redef]
    except ModuleNotFoundError:
        _toml = None  # type: ignore[assignment]


# A location in the file: the table path, e.g. ("body", 2) for the third [[body]],
# ("clearance_joint", 0, "dry") for a sub-table, ("simulation",) or () for the top level.
Where = Tuple[Union[str, int], ...]


# ====================================================================== file text and lines
_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\[\]#]+?)\s*\]\]?\s*(#.*)?$")


def _split_key(dotted: str) -> Tuple[str, ...]:
    return tuple(part.strip().strip("\"'") for part in dotted.split("."))


class Source:
    """The text of a scene file, to find the line of a key (tomllib gives no positions).

    Finds the table of a location by counting ``[[name]]`` headers, then the key's line inside
    that table's span (its sub-tables included); falls back to the table's header line.
    """

    def __init__(self, path: Path, text: str) -> None:
        self.path = path
        self.lines = text.splitlines()
        #: The values of the scene's ``[parameters]`` (:mod:`.parameters`): a numeric field may
        #: be written as a name or an expression of them.
        self.parameters: Dict[str, float] = {}
        # (line index, is array table, name parts)
        self.headers: List[Tuple[int, bool, Tuple[str, ...]]] = []
        for k, line in enumerate(self.lines):
            m = _HEADER.match(line)
            if m:
                self.headers.append((k, m.group(1) == "[[", _split_key(m.group(2))))

    def _span(self, where: Where) -> Tuple[int, int, Optional[int]]:
        """(first line, end line, header line) of the table at ``where`` (of the deepest
        enclosing table written as a header if ``where`` itself is not)."""
        start, end, header = 0, len(self.lines), None
        if not where:
            return 0, (self.headers[0][0] if self.headers else len(self.lines)), None
        prefix: Tuple[str, ...] = ()
        k = 0
        while k < len(where):
            prefix += (str(where[k]),)
            following = where[k + 1] if k + 1 < len(where) else None
            nth = following if isinstance(following, int) else 0
            k += 2 if isinstance(following, int) else 1
            matches = [h for h, (n, _array, parts) in enumerate(self.headers) if start <= n < end and parts == prefix]
            if nth >= len(matches):
                break
            h = matches[nth]
            header = self.headers[h][0]
            start, end = header + 1, len(self.lines)
            for n, _array, parts in self.headers[h + 1 :]:
                if parts[: len(prefix)] != prefix or parts == prefix:
                    end = n
                    break
        return start, end, header

    def line(self, where: Where, key: Optional[str] = None) -> Optional[int]:
        """1-based line of ``key`` in the table at ``where`` (of the table itself if no key or
        the key is not written there); ``None`` if neither is found."""
        start, end, header = self._span(where)
        if key is not None:
            k = re.escape(key)
            patterns = (
                re.compile(rf"^\s*(?:{k}|\"{k}\"|'{k}')\s*="),  # key = ...
                re.compile(rf"[{{,.]\s*(?:{k}|\"{k}\"|'{k}')\s*="),  # inline table / dotted key
            )
            for pattern in patterns:
                for n in range(start, end):
                    if pattern.search(self.lines[n].split("#", 1)[0]):
                        return n + 1
            # A table written as a header: [key] or [[key]], [parent.key]
            sub = self._span(where + (key,))[2]
            if sub is not None:
                return sub + 1
        return None if header is None else header + 1

    def error(self, where: Where, key: Optional[str], message: str, value: Any = None) -> InputError:
        """An :class:`InputError` ``file:line: message`` with ``file``, ``line``, ``field``."""
        line = self.line(where, key)
        dotted = dotted_key(where, key)
        pos = f"{self.path}:{line}" if line is not None else f"{self.path}"
        return InputError(f"{pos}: {message}", field=dotted, value=value, file=str(self.path), line=line)


def dotted_key(where: Where, key: Optional[str]) -> str:
    """The dotted name of ``key`` at ``where`` (``body[2].mass``), as errors name fields."""
    parts: List[str] = []
    for p in where:
        if isinstance(p, int):
            parts[-1] += f"[{p}]"
        else:
            parts.append(p)
    if key is not None:
        parts.append(key)
    return ".".join(parts)


def _label(where: Where) -> str:
    """Human name of a table: ``[[body]] #3``, ``[simulation]``."""
    names = [p for p in where if isinstance(p, str)]
    if not names:
        return "top level"
    idx = [p for p in where if isinstance(p, int)]
    if idx:
        return f"[[{names[0]}]] #{idx[0] + 1}" + "".join(f" [{n}]" for n in names[1:])
    return "[" + ".".join(names) + "]"


# ====================================================================== typed table reader
REQUIRED = object()


def _type_name(value: Any) -> str:
    return {bool: "a boolean", str: "a string", int: "an integer", float: "a number", list: "an array", dict: "a table"}.get(
        type(value), type(value).__name__
    )


class Table:
    """One TOML table being read: typed getters whose errors point at the key's line."""

    def __init__(self, src: Source, where: Where, data: Any, known: Sequence[str]) -> None:
        if not isinstance(data, dict):
            parent = where[:-2] if isinstance(where[-1], int) else where[:-1]
            raise src.error(parent, _last_name(where), f"invalid {dotted_key(where, None)}: must be a table, not {_type_name(data)}", data)
        self.src, self.where, self.data = src, where, data
        for key in data:
            if key not in known:
                raise src.error(
                    where, key, f"unknown key '{key}' in {_label(where)} (known: {', '.join(known)})", data[key]
                )

    def __contains__(self, key: str) -> bool:
        return key in self.data

    def error(self, key: Optional[str], message: str, value: Any = None) -> InputError:
        return self.src.error(self.where, key, message, value)

    def _get(self, key: str, default: Any) -> Any:
        if key in self.data:
            return self.data[key]
        if default is REQUIRED:
            raise self.error(None, f"missing key '{key}' in {_label(self.where)}")
        return default

    def _bad(self, key: str, value: Any, what: str) -> InputError:
        return self.error(key, f"invalid {dotted_key(self.where, key)} = {value!r}: must be {what}, not {_type_name(value)}", value)

    def number(self, key: str, default: Any = REQUIRED) -> Any:
        value = self._get(key, default)
        if key not in self.data:
            return value
        return self._as_number(key, value)

    def _as_number(self, key: str, value: Any, whole: Any = None, what: str = "a number") -> float:
        """``value`` (the field ``key``, or an entry of ``whole``) as a float: a number, or a
        name or an expression of the scene's ``[parameters]`` written as a string."""
        if isinstance(value, str):
            try:
                return evaluate(value, self.src.parameters)
            except ExpressionError as err:
                shown = value if whole is None else whole
                raise self.error(key, f"invalid {dotted_key(self.where, key)} = {shown!r}: must be {what} or an expression of [parameters]: {err.reason}", shown) from None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self._bad(key, value if whole is None else whole, what)
        return float(value)

    def integer(self, key: str, default: Any = REQUIRED) -> Any:
        value = self._get(key, default)
        if key in self.data and (isinstance(value, bool) or not isinstance(value, int)):
            raise self._bad(key, value, "an integer")
        return value

    def boolean(self, key: str, default: Any = REQUIRED) -> Any:
        value = self._get(key, default)
        if key in self.data and not isinstance(value, bool):
            raise self._bad(key, value, "true or false")
        return value

    def string(self, key: str, default: Any = REQUIRED, choices: Optional[Sequence[str]] = None) -> Any:
        value = self._get(key, default)
        if key not in self.data:
            return value
        if not isinstance(value, str):
            raise self._bad(key, value, "a string")
        if choices is not None and value not in choices:
            raise self.error(key, f"invalid {dotted_key(self.where, key)} = {value!r}: must be one of {', '.join(choices)}", value)
        return value

    def strings(self, key: str, default: Any = REQUIRED, choices: Optional[Sequence[str]] = None) -> Any:
        value = self._get(key, default)
        if key not in self.data:
            return value
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise self._bad(key, value, "an array of strings")
        for v in value:
            if choices is not None and v not in choices:
                raise self.error(key, f"invalid {dotted_key(self.where, key)} entry {v!r}: must be one of {', '.join(choices)}", value)
        return list(value)

    def numbers(self, key: str, default: Any = REQUIRED, length: Optional[int] = None) -> Any:
        value = self._get(key, default)
        if key not in self.data:
            return value
        what = f"an array of {length} numbers" if length else "an array of numbers"
        if not isinstance(value, list) or (length is not None and len(value) != length):
            raise self._bad(key, value, what)
        return [self._as_number(key, v, value, what) for v in value]

    def point(self, key: str, default: Any = REQUIRED) -> Any:
        return self.numbers(key, default, length=2)

    def points(self, key: str, count: int, default: Any = REQUIRED) -> Any:
        value = self._get(key, default)
        if key not in self.data:
            return value
        what = f"an array of {count} points [x, y]"
        if not isinstance(value, list) or len(value) != count or not all(isinstance(p, list) and len(p) == 2 for p in value):
            raise self._bad(key, value, what)
        return [[self._as_number(key, v, value, what) for v in p] for p in value]

    def table(self, key: str, known: Sequence[str]) -> Optional["Table"]:
        if key not in self.data:
            return None
        return Table(self.src, self.where + (key,), self.data[key], known)

    def array_of_tables(self, key: str, known: Sequence[str]) -> List["Table"]:
        value = self.data.get(key, [])
        if not isinstance(value, list):
            raise self.error(key, f"invalid {key}: must be written as [[{key}]] tables", value)
        return [Table(self.src, self.where + (key, k), entry, known) for k, entry in enumerate(value)]


def _last_name(where: Where) -> Optional[str]:
    names = [p for p in where if isinstance(p, str)]
    return names[-1] if names else None



def read_toml(path: Path) -> Tuple[Source, Dict[str, Any]]:
    if _toml is None:  # pragma: no cover - Python < 3.11 without tomli
        raise InputError(
            f"{path}: reading scene files on Python < 3.11 needs the 'tomli' package: pip install tomli", field="file", value=str(path)
        )
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise InputError(f"{path}: cannot read the scene file: {err.strerror or err}", field="file", value=str(path), file=str(path)) from None
    except UnicodeDecodeError as err:
        raise InputError(
            f"{path}: the scene file is not UTF-8 text (byte {err.start}); save it as UTF-8", field="file", value=str(path), file=str(path)
        ) from None
    src = Source(path, text)
    try:
        data = _toml.loads(text)
    except _toml.TOMLDecodeError as err:
        m = re.search(r"line (\d+)", str(err))
        line = int(m.group(1)) if m else None
        pos = f"{path}:{line}" if line else str(path)
        raise InputError(f"{pos}: invalid TOML: {err}", field="file", value=str(path), file=str(path), line=line) from None
    return src, data
