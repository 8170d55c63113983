"""Every import of the reliability rooms runs downward: no module of python/clearsim/reliability
(or clearsim.montecarlo, built on it) imports, directly or through others, a module that imports
it — function-level imports included (issue 29)."""

import ast
from pathlib import Path

PKG = Path(__file__).resolve().parents[2] / "python" / "clearsim"


def _graph():
    mods = {}
    for p in PKG.rglob("*.py"):
        parts = list(p.relative_to(PKG.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        mods[".".join(parts)] = p
    mods["clearsim._core"] = PKG / "_core.pyi"  # the extension module: a leaf
    edges = {m: set() for m in mods}
    for m, p in mods.items():
        if m == "clearsim._core":
            continue
        base_parts = m.split(".") if p.name == "__init__.py" else m.split(".")[:-1]
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = ".".join(base_parts[: len(base_parts) - node.level + 1] + ([node.module] if node.module else [])) if node.level else node.module
                subs = [f"{base}.{a.name}" for a in node.names if f"{base}.{a.name}" in mods]
                targets = subs if len(subs) == len(node.names) else [base, *subs]
            else:
                continue
            edges[m] |= {t for t in targets if t in mods and t != m}
    return edges


def _reaches(edges, start, goal):
    seen, todo = set(), [start]
    while todo:
        m = todo.pop()
        for t in edges[m]:
            if t == goal:
                return True
            if t not in seen:
                seen.add(t)
                todo.append(t)
    return False


def test_reliability_rooms_import_downward():
    edges = _graph()
    rooms = [m for m in edges if m.startswith("clearsim.reliability") or m == "clearsim.montecarlo"]
    assert len(rooms) > 10
    circles = [(a, b) for a in rooms for b in edges[a] if _reaches(edges, b, a)]
    assert not circles, f"import circles: {circles}"


def test_every_clearsim_module_imports_downward():
    """The whole package: no circle (export ↔ result and mechanism ↔ running were the last)."""
    edges = _graph()
    circles = sorted((a, b) for a in edges for b in edges[a] if _reaches(edges, b, a))
    assert not circles, f"import circles: {circles}"
