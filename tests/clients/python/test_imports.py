"""The Python client's modules import one another one way: no circle, counting every
import (inside functions and under ``TYPE_CHECKING`` too)."""

from __future__ import annotations

import ast
from pathlib import Path

from tests.conftest import ROOT

PACKAGE = ROOT / "clients" / "python" / "virtual_prosthetics"


def imports_of(path: Path, package: Path) -> set[str]:
    """The modules of ``package`` that the module at ``path`` imports, by file stem."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            names = [node.module] if node.module else [alias.name for alias in node.names]
            found.update(name.split(".")[0] for name in names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.startswith(package.name):
            found.add(node.module.split(".")[1] if "." in node.module else "__init__")
    return {name for name in found if (package / f"{name}.py").exists()}


def circle(graph: dict[str, set[str]]) -> list[str] | None:
    """One circle of imports in ``graph``, or None."""
    state: dict[str, str] = {}

    def visit(module: str, path: list[str]) -> list[str] | None:
        state[module] = "open"
        for other in sorted(graph[module]):
            if state.get(other) == "open":
                return path[path.index(other):] + [other] if other in path else [module, other]
            if other not in state and (found := visit(other, path + [other])):
                return found
        state[module] = "done"
        return None

    for module in sorted(graph):
        if module not in state and (found := visit(module, [module])):
            return found
    return None


def test_the_python_client_has_no_import_circle():
    graph = {p.stem: imports_of(p, PACKAGE) for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    assert circle(graph) is None, " -> ".join(circle(graph))


def test_a_circle_is_found_when_there_is_one():
    assert circle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert circle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None
