"""The server and the Python client import one way: no circle, counting every import
(inside functions and under ``TYPE_CHECKING`` too); the core's layers import only the
layers below them, and the core does no network or event-loop I/O and writes no file (it
reads its own: meshes, the schema, recordings)."""

from __future__ import annotations

import ast
from pathlib import Path

from tests.conftest import ROOT


def modules(top: Path) -> dict[str, Path]:
    """Every module under the package folder ``top``, by dotted name (``a.b``; ``a`` for
    ``a/__init__.py``)."""
    found = {}
    for path in sorted(top.rglob("*.py")):
        parts = path.relative_to(top.parent).with_suffix("").parts
        found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


def imported(name: str, path: Path, known: dict[str, Path]) -> set[str]:
    """The modules of ``known`` that module ``name`` (at ``path``) imports."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")[:len(package.split(".")) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            # `from x import y`: module x.y when there is one, else a name of module x
            found.update(f"{target}.{a.name}" if f"{target}.{a.name}" in known else target
                         for a in node.names)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name in known)
    return (found & known.keys()) - {name}


def import_graph(top: Path) -> dict[str, set[str]]:
    known = modules(top)
    return {name: imported(name, path, known) for name, path in known.items()}


def circle(graph: dict[str, set[str]]) -> list[str] | None:
    """One circle of imports in ``graph``, or None."""
    state: dict[str, str] = {}

    def visit(module: str, path: list[str]) -> list[str] | None:
        state[module] = "open"
        for other in sorted(graph[module]):
            if state.get(other) == "open":
                return path[path.index(other):] + [other]
            if other not in state and (found := visit(other, path + [other])):
                return found
        state[module] = "done"
        return None

    for module in sorted(graph):
        if module not in state and (found := visit(module, [module])):
            return found
    return None


def test_the_server_has_no_import_circle():
    graph = import_graph(ROOT / "server")
    assert "server.core.scene.scene" in graph["server.core.protocol.session"]   # the graph is read
    assert circle(graph) is None, " -> ".join(circle(graph) or [])


# server/core's layers, lowest first: each may import those before it, never one after
LAYERS = ["kit", "physics", "model", "scene", "protocol", "recording"]
NO_IO = {"fastapi", "starlette", "asyncio", "websockets", "uvicorn", "socket", "server.web"}


def test_the_cores_layers_import_only_the_layers_below_them():
    graph = import_graph(ROOT / "server")
    layers = {name.split(".")[2] for name in graph if name.startswith("server.core.")}
    assert layers == set(LAYERS)
    wrong = [f"{module} imports {other}" for module, imports in graph.items()
             if module.startswith("server.core.") for other in imports
             if other.startswith("server.core.")
             and LAYERS.index(other.split(".")[2]) > LAYERS.index(module.split(".")[2])]
    assert wrong == []


def test_the_server_imports_one_way_cli_demo_cluster_web_core():
    graph = import_graph(ROOT / "server")
    # every module of server/ has a tier (the package's own __init__ sets an environment
    # variable and imports nothing of it)
    order = ["server.core", "server.web", "server.cluster", "server.demo", "server.cli"]
    tier = {module: next((k for k, top in enumerate(order) if module == top or module.startswith(top + ".")),
                         None) for module in graph}
    assert [module for module, k in tier.items() if k is None] == ["server"]
    assert graph["server"] == set()
    assert "server.web.scenes.runner" in graph["server.cluster.worker_host"]  # the graph is read
    wrong = [f"{module} imports {other}" for module, imports in graph.items() for other in imports
             if tier[module] is not None and tier[other] > tier[module]]
    assert wrong == []


# server/web's folders, lowest first: each may import those before it, never one after
WEB_FOLDERS = ["storage", "connections", "recording", "process", "scenes", "http"]


def test_the_webs_folders_import_only_the_folders_below_them():
    graph = import_graph(ROOT / "server")
    folders = {name.split(".")[2] for name in graph if name.startswith("server.web.")}
    assert folders == set(WEB_FOLDERS)  # (a module beside the folders would be one more)
    wrong = [f"{module} imports {other}" for module, imports in graph.items()
             if module.startswith("server.web.") for other in imports
             if other.startswith("server.web.")
             and WEB_FOLDERS.index(other.split(".")[2]) > WEB_FOLDERS.index(module.split(".")[2])]
    assert wrong == []


def test_the_core_does_no_io():
    for path in (ROOT / "server" / "core").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
            bad = [n for n in names if any(n == io or n.startswith(f"{io}.") for io in NO_IO)]
            assert bad == [], f"{path.relative_to(ROOT)} imports {bad}"


# what writes, moves or deletes a file (the uploads, the scenes' files and recordings are
# kept by server/web/storage and server/web/recording, which hand the core open streams):
# Path's methods, and os's and shutil's functions
PATH_WRITES = {"write_bytes", "write_text", "unlink", "rename", "mkdir", "rmdir", "touch"}
MODULE_WRITES = {"os": {"remove", "replace", "rename", "unlink", "mkdir", "makedirs", "rmdir",
                        "utime", "truncate"}, "shutil": {"copy", "copyfile", "copytree", "move",
                                                         "rmtree"}}


def file_writes(source: str) -> list[str]:
    """The calls in ``source`` that change files: ``x.write_bytes(…)``, ``os.replace(…)``,
    ``x.replace(y)`` (a ``Path``'s: ``str.replace`` takes two), ``open(…, "w")``…"""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Call):
            continue
        function = node.func
        if isinstance(function, ast.Attribute):
            owner = function.value.id if isinstance(function.value, ast.Name) else None
            if function.attr in MODULE_WRITES.get(owner or "", ()) or owner not in MODULE_WRITES \
                    and (function.attr in PATH_WRITES
                         or function.attr == "replace" and len(node.args) == 1):
                found.append(ast.unparse(node))
        elif isinstance(function, ast.Name) and function.id == "open":
            modes = node.args[1:2] + [k.value for k in node.keywords if k.arg == "mode"]
            if any(isinstance(m, ast.Constant) and set(str(m.value)) & set("wax+") for m in modes):
                found.append(ast.unparse(node))
    return found


def test_the_core_writes_no_file():
    writes = {str(path.relative_to(ROOT)): file_writes(path.read_text())
              for path in (ROOT / "server" / "core").rglob("*.py")}
    assert {path: calls for path, calls in writes.items() if calls} == {}


def test_file_writes_are_found():
    assert file_writes("p.write_bytes(b'x')\nos.replace(a, b)\nopen(p, 'wb')\n"
                       "q.unlink(missing_ok=True)\nopen(p, mode='a')") == [
        "p.write_bytes(b'x')", "os.replace(a, b)", "open(p, 'wb')", "q.unlink(missing_ok=True)",
        "open(p, mode='a')"]
    assert file_writes("s.replace('a', 'b')\nopen(p, 'rb')\nopen(p)\nx.write(b)\n"
                       "items.remove(x)\nos.getpid()") == []


def test_the_python_client_has_no_import_circle():
    graph = import_graph(ROOT / "clients" / "python" / "virtual_prosthetics")
    assert "virtual_prosthetics.session" in graph["virtual_prosthetics.objects"]
    assert circle(graph) is None, " -> ".join(circle(graph) or [])


def test_a_circle_is_found_when_there_is_one():
    assert circle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert circle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None


def test_relative_imports_and_type_checking_ones_count(tmp_path):
    package = tmp_path / "pkg"
    (package / "sub").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "sub" / "__init__.py").write_text("from .. import b\n")
    (package / "a.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .sub import c\n")
    (package / "b.py").write_text("def f():\n    from . import a\n")
    (package / "sub" / "c.py").write_text("from ..b import f\n")
    graph = import_graph(package)
    assert graph["pkg.a"] == {"pkg.sub.c"} and graph["pkg.b"] == {"pkg.a"}
    assert graph["pkg.sub.c"] == {"pkg.b"} and circle(graph) is not None
