"""A scene's ``[parameters]``: named numbers that any numeric field of the scene may use, by name
or in a small arithmetic expression, evaluated safely (an AST walk over a whitelist; no
``eval``).

::

    [parameters]
    crank = 0.05                      # m
    rod = 0.15                        # m
    offset = "rod / 10"               # a parameter may use others (in any order, no cycles)

    [[body]]
    name = "rod"
    ends = [["crank", 0.0], ["crank + sqrt(rod**2 - offset**2)", "offset"]]

An expression holds numbers, parameter names, ``+ - * / **``, parentheses, unary minus, the
functions ``sqrt sin cos tan asin acos atan atan2 hypot radians degrees`` and the constant ``pi``.
``[[study.input]]`` with ``parameter = "rod"`` makes a parameter random: each sample rebuilds the
scene's mechanism with that value (every field written with it follows). Errors name the file,
the line, the key and the unknown name or the bad expression (:mod:`clearsim.scene`).
"""

from __future__ import annotations

import ast
import math
import re
from typing import Any, Callable, Dict, List, Mapping, Optional

__all__ = ["ExpressionError", "FUNCTIONS", "CONSTANTS", "NAME", "evaluate", "resolve", "read_parameters", "parameter_units"]

#: Fields of a scene that hold lengths or points [m] (their names in the scene's tables), besides
#: :data:`clearsim.schema.INPUT_UNITS`: what a parameter written in them measures.
LENGTH_FIELDS = ("points", "point", "position", "ends", "bearing_point", "journal_point", "point_a", "point_b", "offset", "origin")

#: The functions an expression may call, by name.
FUNCTIONS: Dict[str, Callable[..., float]] = {
    "sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan, "asin": math.asin, "acos": math.acos,
    "atan": math.atan, "atan2": math.atan2, "hypot": math.hypot, "radians": math.radians, "degrees": math.degrees,
}  # fmt: skip
#: Named constants an expression may use (not parameter names).
CONSTANTS: Dict[str, float] = {"pi": math.pi}
#: What a parameter's name looks like.
NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")

_BINARY: Dict[type, Callable[[float, float], float]] = {
    ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b, ast.Pow: lambda a, b: a**b,
}  # fmt: skip


class ExpressionError(ValueError):
    """An expression that cannot be evaluated: ``reason`` says why; ``name`` is the unknown
    name, if that is why."""

    def __init__(self, reason: str, name: Optional[str] = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.name = name


def evaluate(text: str, names: Mapping[str, float]) -> float:
    """The value of the expression ``text`` with the parameters ``names``; an
    :class:`ExpressionError` for a syntax error, an unknown name, an operation outside the
    whitelist or a result that is not a finite number."""
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise ExpressionError(f"{text!r} is not an arithmetic expression") from None
    try:
        value = _walk(tree.body, names)
    except ExpressionError:
        raise
    except (ValueError, ZeroDivisionError, OverflowError, TypeError) as err:  # sqrt(-1), 1/0, 10**999, a complex power
        raise ExpressionError(f"{text!r} cannot be evaluated ({err})") from None
    if isinstance(value, complex) or not math.isfinite(value):
        raise ExpressionError(f"{text!r} evaluates to {value!r}, not a finite number")
    return float(value)


def _walk(node: ast.AST, names: Mapping[str, float]) -> float:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id in names:
            return float(names[node.id])
        if node.id in CONSTANTS:
            return CONSTANTS[node.id]
        known = ", ".join(names) or "none: no [parameters] table"
        raise ExpressionError(f"unknown name {node.id!r} (parameters: {known})", node.id)
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        return _BINARY[type(node.op)](_walk(node.left, names), _walk(node.right, names))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        v = _walk(node.operand, names)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS and not node.keywords:
        return float(FUNCTIONS[node.func.id](*(_walk(a, names) for a in node.args)))
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id not in names:
        raise ExpressionError(f"unknown function {node.func.id!r} (known: {', '.join(FUNCTIONS)})", node.func.id)
    raise ExpressionError(f"{ast.unparse(node)!r} is not allowed (numbers, parameter names, + - * / **, parentheses and {', '.join(FUNCTIONS)})")


class _DefinitionError(ExpressionError):
    """A bad definition in ``[parameters]``: ``key`` is the parameter whose definition it is."""

    def __init__(self, key: str, reason: str) -> None:
        super().__init__(reason)
        self.key = key


def resolve(raw: Mapping[str, Any], overrides: Optional[Mapping[str, float]] = None, fail: Optional[Callable[[str, str], Exception]] = None) -> Dict[str, float]:
    """The parameters' values from their definitions ``raw`` (numbers or expressions of other
    parameters, in any order), each of ``overrides`` replacing its definition. ``fail(key,
    reason)`` makes the exception raised for a bad definition (default: :class:`ExpressionError`
    naming the parameter)."""
    defs: Dict[str, Any] = dict(raw)
    defs.update({k: float(v) for k, v in (overrides or {}).items()})
    values: Dict[str, float] = {}
    visiting: List[str] = []

    def value_of(key: str) -> float:
        if key in values:
            return values[key]
        if key in visiting:
            first = visiting[visiting.index(key)]
            raise _DefinitionError(first, f"the parameters refer to each other in a cycle ({' → '.join(visiting[visiting.index(key) :] + [key])})")
        d = defs[key]
        if isinstance(d, bool) or not isinstance(d, (int, float, str)):
            raise _DefinitionError(key, f"must be a number or an expression of other parameters, not {type(d).__name__}")
        if isinstance(d, str):
            visiting.append(key)
            try:
                v = evaluate(d, _Lazy(defs, value_of))
            except _DefinitionError:
                raise
            except ExpressionError as err:
                raise _DefinitionError(key, err.reason) from None
            finally:
                visiting.pop()
        else:
            v = float(d)
            if not math.isfinite(v):
                raise _DefinitionError(key, f"{v!r} is not a finite number")
        values[key] = v
        return v

    for key in defs:
        try:
            value_of(key)
        except _DefinitionError as err:
            raise (fail(err.key, err.reason) if fail is not None else ExpressionError(f"parameter {err.key!r}: {err.reason}", err.name)) from None
    return {key: values[key] for key in defs}


class _Lazy(Mapping[str, float]):
    """The parameters as a mapping that evaluates each on first use (definitions in any order)."""

    def __init__(self, defs: Mapping[str, Any], value_of: Callable[[str], float]) -> None:
        self.defs, self.value_of = defs, value_of

    def __getitem__(self, key: str) -> float:
        return self.value_of(key)

    def __contains__(self, key: object) -> bool:
        return key in self.defs

    def __iter__(self) -> Any:
        return iter(self.defs)

    def __len__(self) -> int:
        return len(self.defs)


def _scaled(node: ast.AST) -> List[str]:
    """The parameter names of an expression that is a sum of parameters each times or over a
    pure number (``-r2 / 2``, ``l6 - arm_half``: the parameters share the field's unit), or
    ``["?"]`` if it is anything else (a product of parameters, a function)."""
    if isinstance(node, ast.Expression):
        return _scaled(node.body)
    if isinstance(node, ast.Name):
        return [node.id] if node.id not in CONSTANTS else []
    if isinstance(node, ast.Constant):
        return []
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
        return _scaled(node.operand)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
        return _scaled(node.left) + _scaled(node.right)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)):
        def pure(n: ast.AST) -> bool:
            return not any(isinstance(x, ast.Name) and x.id not in CONSTANTS for x in ast.walk(n))

        if pure(node.right):  # p * 2, p / 2
            return _scaled(node.left)
        if isinstance(node.op, ast.Mult) and pure(node.left):  # 2 * p
            return _scaled(node.right)
    return ["?"]


def parameter_units(data: Mapping[str, Any], units: Mapping[str, str]) -> Dict[str, str]:
    """The unit of each ``[parameters]`` name, from the fields that use it (a scene's raw tables
    ``data``): the field's unit (``units`` by field name, or m for :data:`LENGTH_FIELDS`) where
    every field of a known unit that uses it has that unit and uses it scaled by numbers only
    (``"-l5 / 2"``, ``"l6 - arm_half"``); none where a field uses it otherwise (``"r * sin(a)"``)."""
    names = set((data.get("parameters") or {}).keys())
    found: Dict[str, set] = {}

    def walk(v: Any, key: str) -> None:
        if isinstance(v, dict):
            for k, item in v.items():
                if k != "parameters" or key:
                    walk(item, str(k))
        elif isinstance(v, list):
            for item in v:
                walk(item, key)
        elif isinstance(v, str) and key:
            try:
                used = _scaled(ast.parse(v, mode="eval"))
            except SyntaxError:
                return
            unit = "m" if key in LENGTH_FIELDS else units.get(key)
            if "?" in used:  # anything else (a product of parameters, a function): no unit for its names
                used, unit = [x.id for x in ast.walk(ast.parse(v, mode="eval")) if isinstance(x, ast.Name)], None
            elif unit is None:  # a field of no known unit (a study input's mean, its parameter's name) says nothing
                return
            for n in used:
                if n in names:
                    found.setdefault(n, set()).add(unit)

    walk({k: v for k, v in data.items() if k != "parameters"}, "")
    return {n: next(iter(u)) for n, u in found.items() if len(u) == 1 and None not in u}


def read_parameters(top: Any, overrides: Optional[Mapping[str, float]] = None) -> Dict[str, float]:
    """The values of the ``[parameters]`` table of a scene (``top``: its top-level
    :class:`~clearsim.scene.toml_reader.Table`), each of ``overrides`` replacing its definition;
    errors located at the key's line."""
    raw = top.data.get("parameters")
    if raw is None:
        return {}
    t = top.table("parameters", tuple(raw) if isinstance(raw, dict) else ())
    for key in t.data:
        if not NAME.match(key):
            raise t.error(key, f"invalid parameter name {key!r}: letters, digits and _, not starting with a digit (expressions use it)", key)
        if key in FUNCTIONS or key in CONSTANTS:
            raise t.error(key, f"invalid parameter name {key!r}: the name of a {'function' if key in FUNCTIONS else 'constant'} expressions use", key)
    return resolve(t.data, overrides, fail=lambda key, reason: t.error(key, f"invalid parameters.{key} = {t.data[key]!r}: {reason}", t.data[key]))
