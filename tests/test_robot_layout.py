"""The robot package sits below the numerical core; it and the simulator have no import cycle.

The import graph of the whole package is tested in test_layout.py; this pins the robot part.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

ROBOT = Path(__file__).resolve().parents[1] / "src" / "funcnet" / "robot"
SIM = ROBOT.parent / "sim"
# What robot may import from funcnet: the bottom layer and itself.
BOTTOM = ("funcnet.errors", "funcnet._io", "funcnet.parameters", "funcnet._lazy")


def _module(path: Path) -> str:
    parts = path.relative_to(ROBOT.parents[1]).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> set[str]:
    """Every funcnet module ``path`` imports, at any depth (inside functions too)."""
    found: set[str] = set()
    package = _module(path) if path.name == "__init__.py" else _module(path).rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{parent}.{base}" if base else parent
            found.add(base)
            # ``from funcnet.sim import axis`` imports the module funcnet.sim.axis
            found |= {f"{base}.{alias.name}" for alias in node.names}
    return {name for name in found if name == "funcnet" or name.startswith("funcnet.")}


def _is_module(name: str) -> bool:
    """A funcnet module (a file or a package) of that name exists (not a class or function)."""
    path = ROBOT.parents[1].joinpath(*name.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _real_modules(names: set[str]) -> set[str]:
    return {name for name in names if _is_module(name)}


def _robot_files() -> list[Path]:
    return sorted(path for path in ROBOT.rglob("*.py"))  # the readers of robot/io too


def _sim_files() -> list[Path]:
    return sorted(SIM.glob("*.py"))


@pytest.mark.parametrize("path", _robot_files(), ids=lambda p: p.relative_to(ROBOT).as_posix())
def test_robot_imports_nothing_numerical(path):
    imported = _real_modules(_imports(path))
    allowed = {name for name in imported if name in BOTTOM or name == "funcnet.robot"}
    allowed |= {
        name
        for name in imported
        if name.startswith("funcnet.robot.")
    }
    assert imported <= allowed, f"{path.name} imports {sorted(imported - allowed)}"


def test_robot_lazy_table_names_only_robot_modules():
    import funcnet.robot

    for name, module in funcnet.robot._EXPORTS.items():
        assert module.startswith("funcnet.robot."), name
        assert hasattr(importlib.import_module(module), name), (name, module)


@pytest.mark.parametrize("path", _sim_files(), ids=lambda p: p.name)
def test_sim_imports_only_robot_and_the_bottom_layer(path):
    imported = _real_modules(_imports(path))
    bad = {
        name
        for name in imported
        if name not in BOTTOM and name != "funcnet"
        and not name.startswith(("funcnet.robot", "funcnet.sim"))
    }
    assert not bad, f"sim/{path.name} imports {sorted(bad)}"


def test_no_import_cycle_in_robot():
    files = _robot_files() + _sim_files()
    graph = {
        _module(path): {
            name
            for name in _real_modules(_imports(path))
            if name.startswith(("funcnet.robot", "funcnet.sim")) and name != _module(path)
        }
        for path in files
        if path.name != "__init__.py"  # lazy tables: strings, not imports
    }
    state: dict[str, int] = {}

    def visit(node: str, trail: list[str]) -> None:
        if state.get(node) == 2:
            return
        assert state.get(node) != 1, f"import cycle: {' -> '.join([*trail, node])}"
        state[node] = 1
        for child in sorted(graph.get(node, ())):
            visit(child, [*trail, node])
        state[node] = 2

    for module in sorted(graph):
        visit(module, [])
    assert "funcnet.sim.trial" in graph["funcnet.sim.axis"]
    assert "funcnet.sim.axis" not in graph["funcnet.sim.trial"]


@pytest.mark.parametrize("path", _robot_files() + _sim_files(),
                         ids=lambda p: p.relative_to(ROBOT.parent).as_posix())
def test_module_length(path):
    lines = path.read_text(encoding="utf-8").count("\n")
    assert lines <= 900
    if lines > 600:
        docstring = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
        assert "600 lines" in docstring, f"{path.name}: {lines} lines without a reason"


def test_the_robot_package_exports_no_simulator():
    import funcnet.robot

    assert not hasattr(funcnet.robot, "Trial") and "simulate_trial" not in funcnet.robot.__all__
    assert funcnet.robot.read_recording.__module__ == "funcnet.robot.io.read"
