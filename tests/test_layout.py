"""The package's layout follows its data flow: the import graph of ``src/funcnet``, parsed.

Every ``import`` and ``from ... import`` of every module counts, those inside functions too, and
so does ``importlib.import_module("funcnet...")`` with a literal name; only imports under
``if TYPE_CHECKING:`` do not. ``from funcnet import name`` (and ``funcnet.name`` after
``import funcnet``) counts as an import of the module the lazy table of ``funcnet/__init__.py``
names for ``name``, so that a module cannot reach the core out of sight through the top level.
The lazy ``__init__`` tables themselves are exempt from the layers (they load on demand), but
every module they name must exist and every name must resolve.

Imports only go down the list of layers. The test bench (the simulator ``funcnet.sim``, the
paper's analyses ``funcnet.paper``, ``funcnet.validation``) sits beside the library: no library
module imports it at its top, and only a study (when it simulates) and the command line reach it
from inside a function. At most eight modules stand directly in ``src/funcnet``.
"""

from __future__ import annotations

import ast
import importlib
import re
import subprocess
import sys
import tomllib
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from importlib.metadata import packages_distributions
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "funcnet"

# (group, rank): a module may import modules of its own group or of a lower rank, except where
# FORBIDDEN says otherwise. Groups of one rank are siblings and import nothing of each other.
LAYERS: dict[str, tuple[str, float]] = {
    "funcnet.errors": ("base", 0),
    "funcnet._io": ("base", 0),
    "funcnet.parameters": ("base", 0),
    "funcnet._lazy": ("base", 0),
    # the numerical core, funcnet/core: kernels and thresholds below the recurrences
    "funcnet.core.normalization": ("core1", 1),
    "funcnet.core.embedding": ("core1", 1),
    "funcnet.core._isrn_kernels": ("core1", 1),
    "funcnet.core.thresholds": ("core1", 1),
    "funcnet.core._batch_kernels": ("core1", 1),  # below the measures, which use them
    "funcnet.core._keys": ("core1", 1),
    "funcnet.core.recurrence": ("recurrence", 2),
    "funcnet.core.measures": ("measures", 3),
    "funcnet.core.kinds": ("measures", 3),
    "funcnet.core.batch": ("batch", 3.25),
    "funcnet.robot": ("robot", 1),
    "funcnet.evidence": ("evidence", 3.5),
    "funcnet.network": ("network", 4),
    "funcnet.pipeline": ("pipeline", 5),
    "funcnet.plot": ("plot", 6),
    "funcnet.diagnosis": ("diagnosis", 7),
    "funcnet.study": ("study", 7),
    "funcnet.inspection": ("inspection", 7.5),
    "funcnet.comparison": ("comparison", 7.5),
    "funcnet.track": ("track", 7.75),
    "funcnet.report": ("report", 8),
    "funcnet.cli": ("cli", 9),
    "funcnet.__main__": ("cli", 9),
    # the test bench
    "funcnet.validation.systems": ("systems", 1),
    "funcnet.sim": ("sim", 1.5),
    "funcnet.paper": ("paper", 8.5),
    "funcnet.validation": ("validation", 8.5),
}
BENCH = ("funcnet.sim", "funcnet.paper", "funcnet.validation")
# Library modules that may reach the bench from inside a function: a study that simulates its
# plan, and the command line's simulate, demo and backlash-report commands.
LAZY_BENCH_USERS = ("funcnet.study", "funcnet.cli")
# Beyond the ranks: the L1 groups import only the base (sim also robot), not each other.
FORBIDDEN: dict[str, tuple[str, ...]] = {
    "robot": ("core1", "systems", "sim"),
    "sim": ("core1", "systems"),
    "core1": ("robot", "sim", "systems"),
    "systems": ("core1", "robot", "sim"),
}
CORE = "funcnet.core"
ROBOT_MAY_NOT_IMPORT = ("funcnet.core.recurrence", "funcnet.core.measures", "funcnet.network",
                        "funcnet.pipeline")
TOP_LEVEL_MODULES = 8
PLOT_MAY_NOT_IMPORT = ("funcnet.core.recurrence", "funcnet.core.measures", "funcnet.pipeline")
MAX_LINES, REASON_LINES = 900, 600
# A module over 600 lines says why in its docstring, on a line such as
# "Length: the TOML schema and its checks belong together." or "... over 600 lines because ...".
REASON = re.compile(
    r"^\s*(length|size|why (this|it) is (so )?long|long because)\s*:|"
    r"\b(over|more than|above|exceeds?)\s+(~\s*)?600\s+lines\b",
    re.IGNORECASE | re.MULTILINE,
)


# --------------------------------------------------------------------------------------------
# the modules and their imports


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def modules() -> dict[str, Path]:
    """Every module of the package: dotted name -> file."""
    return {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


@cache
def _tree(name: str) -> ast.Module:
    path = modules()[name]
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def _is_package(name: str) -> bool:
    return modules()[name].name == "__init__.py"


@cache
def lazy_table(name: str) -> dict[str, str] | None:
    """The ``_EXPORTS`` table (name -> module) of a package ``__init__``, if it has one."""
    if name not in modules() or not _is_package(name):
        return None
    for node in _tree(name).body:
        targets = (
            node.targets if isinstance(node, ast.Assign)
            else [node.target] if isinstance(node, ast.AnnAssign) else []
        )
        if any(isinstance(t, ast.Name) and t.id == "_EXPORTS" for t in targets):
            assert node.value is not None
            table = ast.literal_eval(node.value)
            assert isinstance(table, dict), f"{name}._EXPORTS is not a dict literal"
            return {str(k): str(v) for k, v in table.items()}
    return None


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _walk(node: ast.AST) -> Iterator[ast.AST]:
    """Every node below ``node``, except the bodies of ``if TYPE_CHECKING:``."""
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.If) and _is_type_checking(child.test):
            for other in child.orelse:
                yield other
                yield from _walk(other)
            continue
        yield child
        yield from _walk(child)


def _absolute(module: str | None, level: int, importer: str) -> str:
    if level == 0:
        return module or ""
    base = importer.split(".")
    if not _is_package(importer):
        base = base[:-1]
    base = base[: len(base) - (level - 1)]
    return ".".join([*base, module] if module else base)


def _target(package: str, name: str) -> str:
    """What ``from package import name`` imports: a submodule, a lazily exported name's module,
    or the package itself."""
    if f"{package}.{name}" in modules():
        return f"{package}.{name}"
    table = lazy_table(package)
    if table is not None and name in table:
        return table[name]
    return package


@dataclass(frozen=True)
class Import:
    importer: str
    imported: str
    line: int

    def __str__(self) -> str:
        return f"{self.importer} (line {self.line}) imports {self.imported}"


@cache
def imports(name: str) -> tuple[Import, ...]:
    """The funcnet modules ``name`` imports (deduplicated by target, first line kept)."""
    return _imports_of(_tree(name), name)


def _imports_of(tree: ast.Module, name: str) -> tuple[Import, ...]:
    found: dict[str, int] = {}

    def add(target: str, line: int) -> None:
        if target == "funcnet" or target.startswith("funcnet."):
            found.setdefault(target, line)

    bound: dict[str, str] = {}  # local names bound to a funcnet module
    for node in _walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "funcnet" or alias.name.startswith("funcnet."):
                    if alias.asname is None:
                        bound["funcnet"] = "funcnet"  # `import funcnet.x` binds `funcnet`
                    else:
                        bound[alias.asname] = alias.name
                add(alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            package = _absolute(node.module, node.level, name)
            for alias in node.names:
                target = _target(package, alias.name) if alias.name != "*" else package
                if target == f"{package}.{alias.name}":
                    bound[alias.asname or alias.name] = target
                add(target, node.lineno)
        elif isinstance(node, ast.Call) and node.args:
            function, first = node.func, node.args[0]
            called = function.attr if isinstance(function, ast.Attribute) else getattr(
                function, "id", None
            )
            if called in ("import_module", "__import__") and isinstance(first, ast.Constant):
                if isinstance(first.value, str):
                    add(first.value, node.lineno)
    # `funcnet.functional_network`, `robot.read_trace`: attributes of a bound module.
    for node in _walk(tree):
        chain = _attribute_chain(node)
        if chain is None or chain[0] not in bound:
            continue
        module = bound[chain[0]]
        for part in chain[1:]:
            if f"{module}.{part}" not in modules():
                module = _target(module, part)
                break
            module = f"{module}.{part}"
        add(module, getattr(node, "lineno", 0))
    return tuple(Import(name, target, line) for target, line in found.items())


def _attribute_chain(node: ast.AST) -> list[str] | None:
    """``["a", "b", "c"]`` for the expression ``a.b.c``; None for anything else."""
    parts: list[str] = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not parts or not isinstance(node, ast.Name):
        return None
    return [node.id, *reversed(parts)]


def _layer(name: str) -> tuple[str, float] | None:
    """The layer of a module: its own entry or its closest package's; private siblings
    (``funcnet._measures_kernels``) share the layer of the module they serve."""
    parts = name.split(".")
    while parts:
        key = ".".join(parts)
        if key in LAYERS:
            return LAYERS[key]
        parts.pop()
    if name.startswith("funcnet._"):
        private = name.removeprefix("funcnet._")
        for key, layer in LAYERS.items():
            public = key.removeprefix("funcnet.")
            if "." not in public and not public.startswith("_") and private.startswith(public):
                return layer
    return None


def _exempt(name: str) -> bool:
    """The lazy re-export tables, and the top-level package (``__version__``)."""
    return name == "funcnet" or lazy_table(name) is not None


def _all_imports() -> list[Import]:
    return [edge for name in modules() for edge in imports(name)]


# --------------------------------------------------------------------------------------------
# the rules


def test_every_module_has_a_place_in_the_flow() -> None:
    unplaced = [name for name in modules() if not _exempt(name) and _layer(name) is None]
    assert not unplaced, f"modules with no layer (add them to LAYERS): {unplaced}"


def test_every_imported_funcnet_module_exists() -> None:
    missing = [str(e) for e in _all_imports() if e.imported not in modules()]
    assert not missing, "\n".join(missing)


def test_no_import_against_the_flow() -> None:
    wrong = []
    for edge in _all_imports():
        if _exempt(edge.importer) or _exempt(edge.imported):
            continue
        source, target = _layer(edge.importer), _layer(edge.imported)
        if source is None or target is None:
            continue  # reported by the test above
        (group, rank), (other, other_rank) = source, target
        if group == other:
            continue
        if other_rank >= rank or other in FORBIDDEN.get(group, ()):
            wrong.append(f"{edge} (layer {group} {rank} -> {other} {other_rank})")
    assert not wrong, "imports against the flow:\n" + "\n".join(wrong)


def _top_level_imports(name: str) -> set[str]:
    """The funcnet modules ``name`` imports outside any function (what loading it loads)."""
    tree = _tree(name)
    body: list[ast.AST] = []
    for node in tree.body:
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            body += node.orelse
        elif not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            body.append(node)
    module = ast.Module(body=body, type_ignores=[])  # type: ignore[arg-type]
    return {edge.imported for edge in _imports_of(module, name)}


def test_the_library_does_not_import_its_bench() -> None:
    wrong = []
    for name in modules():
        if _under(name, BENCH) or _exempt(name):
            continue
        every = {e.imported for e in imports(name)}
        top = _top_level_imports(name)
        for target in sorted(every):
            if not _under(target, BENCH):
                continue
            if target in top or not _under(name, LAZY_BENCH_USERS):
                wrong.append(f"{name} imports {target}")
    assert not wrong, "the library reaches its test bench:\n" + "\n".join(wrong)


def test_the_core_has_its_own_room() -> None:
    top = [path.name for path in PACKAGE.glob("*.py")]
    assert len(top) <= TOP_LEVEL_MODULES, f"{len(top)} modules in src/funcnet: {sorted(top)}"
    # Outside the core, its private names (a leading underscore) are never imported.
    private = []
    for name in modules():
        if _under(name, (CORE,)):
            continue
        for node in _walk(_tree(name)):
            if isinstance(node, ast.ImportFrom) and node.module and _under(node.module, (CORE,)):
                private += [f"{name} line {node.lineno}: {node.module}.{alias.name}"
                            for alias in node.names if alias.name.startswith("_")]
    assert not private, "the core's private names used outside it:\n" + "\n".join(private)


def test_reading_and_diagnosing_load_no_bench() -> None:
    code = (
        "import sys, funcnet\n"
        "from funcnet.inspection import inspect_recording\n"
        "from funcnet.diagnosis import diagnose_recording\n"
        "for name in funcnet.__all__: getattr(funcnet, name)\n"
        f"print(sorted(m for m in sys.modules if m.startswith({BENCH!r})))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )
    assert result.stdout.strip() == "[]", result.stdout


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of two or more modules (Tarjan): the cycles."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def connect(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                connect(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            connect(node)
    return cycles


def test_no_import_cycle() -> None:
    graph: dict[str, set[str]] = {name: set() for name in modules()}
    for edge in _all_imports():
        if edge.imported in graph and edge.imported != edge.importer:
            graph[edge.importer].add(edge.imported)
    cycles = _cycles(graph)
    assert not cycles, f"import cycles: {cycles}"


def _robot_module(name: str) -> bool:
    return name == "funcnet.robot" or name.startswith("funcnet.robot.")


def _under(name: str, roots: tuple[str, ...]) -> bool:
    return any(name == root or name.startswith(f"{root}.") for root in roots)


def test_robot_imports_none_of_the_numerical_core() -> None:
    wrong = [
        str(e) for e in _all_imports()
        if _robot_module(e.importer) and _under(e.imported, ROBOT_MAY_NOT_IMPORT)
    ]
    # Its lazy table included: a name it re-exports must not be reached through the core.
    table = lazy_table("funcnet.robot") or {}
    wrong += [
        f"funcnet.robot's table: {key} -> {module}"
        for key, module in table.items() if _under(module, ROBOT_MAY_NOT_IMPORT)
    ]
    assert not wrong, "\n".join(wrong)


def test_robot_loads_none_of_the_numerical_core() -> None:
    # At run time too: every name funcnet.robot exports, in a fresh interpreter.
    code = (
        "import sys, funcnet.robot as r\n"
        "for name in r.__all__: getattr(r, name)\n"
        f"print([m for m in sys.modules if m.startswith({ROBOT_MAY_NOT_IMPORT!r})])\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )
    assert result.stdout.strip() == "[]", result.stdout


def test_plot_draws_what_it_is_given() -> None:
    wrong = [
        str(e) for e in _all_imports()
        if _under(e.importer, ("funcnet.plot",))
        and (_under(e.imported, PLOT_MAY_NOT_IMPORT) or e.imported == "funcnet.network.functional")
    ]
    assert not wrong, "\n".join(wrong)


def test_plot_calls_no_functional_network() -> None:
    calls = []
    for name in modules():
        if not _under(name, ("funcnet.plot",)):
            continue
        for node in ast.walk(_tree(name)):
            if isinstance(node, ast.Call):
                function = node.func
                called = function.attr if isinstance(function, ast.Attribute) else getattr(
                    function, "id", None
                )
                if called in ("functional_network", "window_networks", "cross_measures"):
                    calls.append(f"{name} line {node.lineno}: {called}")
    assert not calls, "\n".join(calls)


def test_module_sizes() -> None:
    too_long, unexplained = [], []
    for name, path in modules().items():
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > MAX_LINES:
            too_long.append(f"{name}: {lines} lines")
        elif lines > REASON_LINES:
            docstring = ast.get_docstring(_tree(name)) or ""
            if not REASON.search(docstring):
                unexplained.append(f"{name}: {lines} lines")
    assert not too_long, f"modules over {MAX_LINES} lines: {too_long}"
    assert not unexplained, (
        f"modules over {REASON_LINES} lines without a reason line in their docstring "
        f"(e.g. 'Length: ...' or '... over 600 lines because ...'): {unexplained}"
    )


# --------------------------------------------------------------------------------------------
# the lazy tables


def _tables() -> list[tuple[str, str, str]]:
    return [
        (package, key, module)
        for package in modules()
        for key, module in (lazy_table(package) or {}).items()
    ]


def test_lazy_tables_exist() -> None:
    assert lazy_table("funcnet") and lazy_table("funcnet.robot")


def test_lazy_tables_name_existing_modules() -> None:
    missing = [f"{p}.{k} -> {m}" for p, k, m in _tables() if m not in modules()]
    assert not missing, f"lazy tables naming modules that do not exist: {missing}"


@pytest.mark.parametrize(
    ("package", "name", "module"), _tables(), ids=[f"{p}.{k}" for p, k, _ in _tables()]
)
def test_lazy_names_resolve(package: str, name: str, module: str) -> None:
    value = getattr(importlib.import_module(package), name)
    assert value is getattr(importlib.import_module(module), name)
    assert name in importlib.import_module(package).__all__


# The names users and other tools import: they stay where they are.
KEPT_NAMES = {
    "funcnet": (
        "NetworkParameters functional_network window_networks cross_measures isrn_measures embed "
        "auto_recurrence cross_recurrence add_evidence window_evidence inspect_trace "
        "FunctionalNetwork FuncnetError FuncnetWarning ThresholdWarning DegenerateWarning "
        "StaircaseWarning __version__"
    ).split(),
    "funcnet.core.recurrence": ["estimate_cost"],
    "funcnet.robot": ("read_trace read_recording add_derived_signals detect_phases "
                      "phase_windows sliding_windows").split(),
    "funcnet.core.embedding": [], "funcnet.core.measures": [], "funcnet.network": [],
    "funcnet.pipeline": [], "funcnet.evidence": [], "funcnet.plot": [],
}


@pytest.mark.parametrize(
    ("module", "name"),
    [(module, name) for module, names in KEPT_NAMES.items() for name in [None, *names]],
)
def test_kept_names_resolve(module: str, name: str | None) -> None:
    imported = importlib.import_module(module)
    if name is not None:
        assert getattr(imported, name) is not None
        if _is_package(module):
            assert name in imported.__all__


def test_no_export_is_hidden_by_a_module_of_its_name() -> None:
    # `from funcnet.paper import evaluate` would give the module funcnet.paper.evaluate once it
    # is imported: a lazily exported name must not be the name of a submodule.
    hidden = [f"{package}.{name}" for package, name, _ in _tables()
              if f"{package}.{name}" in modules()]
    assert not hidden, hidden


_DOTTED = re.compile(r"\bfuncnet(?:\.[A-Za-z_]\w*)+")
_FROM = re.compile(r"from (funcnet(?:\.\w+)*) import (\([^)]*\)|\w+(?:, \w+)*)")


def _documented_names() -> list[tuple[str, str]]:
    """``(file, dotted name)`` of every funcnet name the README and the docs use."""
    found = []
    for path in [SRC.parent / "README.md", *sorted((SRC.parent / "docs").rglob("*.md"))]:
        text = path.read_text(encoding="utf-8")
        found += [(path.name, match.group(0)) for match in _DOTTED.finditer(text)]
        for match in _FROM.finditer(text):
            names = re.findall(r"\w+", match.group(2))
            found += [(path.name, f"{match.group(1)}.{name}") for name in names]
    return sorted(set(found))


def test_docs_use_only_exported_names() -> None:
    # Every funcnet.NAME the README and docs teach resolves, and a name taken from a package
    # (funcnet.X, funcnet.robot.X) is one the package exports.
    wrong = []
    for file, dotted in _documented_names():
        parts = dotted.split(".")
        depth = len(parts)
        while ".".join(parts[:depth]) not in modules() and depth > 1:
            depth -= 1
        module = ".".join(parts[:depth])
        rest = parts[depth:]
        if not rest:
            continue
        value: object = importlib.import_module(module)
        if _is_package(module) and rest[0] not in value.__all__:  # type: ignore[attr-defined]
            wrong.append(f"{file}: {dotted} ({rest[0]} is not in {module}.__all__)")
            continue
        try:
            for part in rest:
                value = getattr(value, part)
        except AttributeError:
            wrong.append(f"{file}: {dotted} does not resolve")
    assert not wrong, "\n".join(wrong)


def test_the_checks_themselves() -> None:
    # The parser itself: a function-level import, `import funcnet` + attribute, import_module,
    # a relative import, and one under TYPE_CHECKING (not counted).
    source = (
        "from __future__ import annotations\n"
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from funcnet.core.measures import CrossMeasures\n"
        "def f():\n"
        "    import funcnet\n"
        "    return funcnet.functional_network\n"
        "def g():\n"
        "    from importlib import import_module\n"
        "    return import_module('funcnet.core.recurrence')\n"
        "from . import _io\n"
        "from .errors import ParameterError\n"
    )
    found = {e.imported for e in _imports_of(ast.parse(source), "funcnet.pipeline")}
    network = lazy_table("funcnet")["functional_network"]  # type: ignore[index]
    assert {network, "funcnet.core.recurrence", "funcnet._io", "funcnet.errors"} <= found
    assert "funcnet.core.measures" not in found
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


# --------------------------------------------------------------------------------------------
# the maintainer's picture of it (docs/develop.md)


def _develop_layout() -> list[str]:
    """The module paths of the layout block of docs/develop.md (relative to src/funcnet)."""
    text = (SRC.parent / "docs" / "develop.md").read_text(encoding="utf-8")
    block = text.split("```\nsrc/funcnet/\n", 1)[1].split("```", 1)[0]
    paths, folders = [], []  # folders: the open folder at each indentation
    for line in block.splitlines():
        entry = line.split()[0] if line.strip() else ""
        if not entry or entry.startswith("src/"):
            continue
        depth = (len(line) - len(line.lstrip())) // 2 - 1
        if depth < 0:
            continue  # tests/, benchmarks/
        folders = folders[:depth]
        if entry.endswith("/"):
            folders.append(entry.rstrip("/"))
        elif entry.endswith(".py"):
            paths.append("/".join([*folders, entry]))
    return paths


def test_develop_layout_matches_the_tree() -> None:
    listed = _develop_layout()
    present = sorted(
        path.relative_to(PACKAGE).as_posix() for path in PACKAGE.rglob("*.py")
        if path.name != "__init__.py" or path.parent == PACKAGE
    )
    assert len(listed) == len(set(listed)), "a module is listed twice"
    assert sorted(listed) == present, (
        f"missing from docs/develop.md: {sorted(set(present) - set(listed))}; "
        f"not in the tree: {sorted(set(listed) - set(present))}"
    )


# --------------------------------------------------------------------------------------------
# the dependencies it declares


def _third_party_imports() -> dict[str, str]:
    """Top-level name of every non-funcnet, non-standard-library import -> one importer."""
    found: dict[str, str] = {}
    for name in modules():
        for node in ast.walk(_tree(name)):
            if isinstance(node, ast.Import):
                tops = [alias.name.split(".")[0] for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                tops = [node.module.split(".")[0]]
            else:
                continue
            for top in tops:
                if top != "funcnet" and top not in sys.stdlib_module_names:
                    found.setdefault(top, name)
    return found


def _declared() -> tuple[set[str], dict[str, set[str]]]:
    project = tomllib.loads((SRC.parent / "pyproject.toml").read_text())["project"]

    def names(requirements: list[str]) -> set[str]:
        return {canonicalize_name(Requirement(r).name) for r in requirements}

    extras = {
        extra: names(requirements)
        | {canonicalize_name(e) for r in requirements for e in Requirement(r).extras}
        for extra, requirements in project["optional-dependencies"].items()
    }
    return names(project["dependencies"]), extras


def test_every_import_is_a_declared_dependency_and_back() -> None:
    runtime, extras = _declared()
    distributions = packages_distributions()
    imported: dict[str, str] = {}
    for top, importer in _third_party_imports().items():
        for dist in distributions.get(top, [top]):
            imported[canonicalize_name(dist)] = importer
    optional = extras["dask"]  # imported only where a study runs on a Dask cluster
    undeclared = {d: m for d, m in imported.items() if d not in runtime | optional}
    assert not undeclared, f"imported but not declared in pyproject.toml: {undeclared}"
    unused = runtime - set(imported)
    assert not unused, f"declared but never imported by the package: {sorted(unused)}"
    pinned = [r for r in tomllib.loads((SRC.parent / "pyproject.toml").read_text())["project"][
        "dependencies"] if "==" in r]
    assert not pinned, f"runtime dependencies are ranges (pins go to constraints.txt): {pinned}"


def test_constraints_pin_every_dependency() -> None:
    lines = (SRC.parent / "constraints.txt").read_text().splitlines()
    pins = {
        canonicalize_name(name): version
        for name, version in (
            line.split("==", 1) for line in map(str.strip, lines)
            if line and not line.startswith("#")
        )
    }
    project = tomllib.loads((SRC.parent / "pyproject.toml").read_text())["project"]
    extras = [r for group in project["optional-dependencies"].values() for r in group]
    for requirement in map(Requirement, [*project["dependencies"], *extras]):
        name = canonicalize_name(requirement.name)
        assert name in pins, f"{name} is not pinned in constraints.txt"
        assert requirement.specifier.contains(pins[name]), (str(requirement), pins[name])


def test_data_files_ship_with_the_package() -> None:
    config = tomllib.loads((SRC.parent / "pyproject.toml").read_text())["tool"]["setuptools"]
    patterns = [p for patterns in config.get("package-data", {}).values() for p in patterns]
    data = [
        path for path in PACKAGE.rglob("*")
        if path.is_file() and path.suffix not in (".py", ".pyc", ".nbi", ".nbc")
        and "__pycache__" not in path.parts
    ]
    unshipped = [str(p.relative_to(PACKAGE)) for p in data
                 if not any(p.match(pattern) for pattern in patterns)]
    assert not unshipped, f"data files no package-data pattern of pyproject.toml ships: {unshipped}"


# --------------------------------------------------------------------------------------------
# what an editor and a type checker see


def test_no_catch_all_keywords() -> None:
    # `**overrides: Any` hides the keywords a user may pass: spell them out, or type them against
    # one contract (``Unpack[ParameterOverrides]``, PEP 692).
    hidden = []
    for name in modules():
        for node in ast.walk(_tree(name)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.args.kwarg:
                annotation = node.args.kwarg.annotation
                if annotation is None or ast.unparse(annotation) == "Any":
                    hidden.append(f"{name}.{node.name}(**{node.args.kwarg.arg})")
    assert not hidden, hidden


def test_the_keyword_contracts_match_the_parameters() -> None:
    import typing

    from funcnet.parameters import BlockOverrides, NetworkParameters, ParameterOverrides

    fields = typing.get_type_hints(NetworkParameters)
    keywords = typing.get_type_hints(ParameterOverrides)
    assert keywords == {name: fields[name] for name in NetworkParameters.names()}
    assert set(typing.get_type_hints(BlockOverrides)) == set(keywords) - {"rr", "cr", "eps"}


def test_the_package_ships_its_types() -> None:
    assert (PACKAGE / "py.typed").is_file()
    config = tomllib.loads((SRC.parent / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert {"py.typed", "*.pyi"} <= set(config["package-data"]["*"])
    # every lazy export is visible to a type checker: a stub beside each lazy __init__
    for package in modules():
        table = lazy_table(package)
        if not table:
            continue
        stub = modules()[package].with_suffix(".pyi")
        assert stub.is_file(), f"{package} has a lazy table and no {stub.name}"
        seen: dict[str, str] = {}
        for node in ast.parse(stub.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.ImportFrom) and node.module:
                seen.update({a.asname or a.name: node.module for a in node.names})
        assert seen == table, f"{package}: {stub.name} differs from _EXPORTS"


def test_no_private_module_of_a_third_party_package() -> None:
    private = []
    for name in modules():
        for node in ast.walk(_tree(name)):
            targets = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                       [node.module] if isinstance(node, ast.ImportFrom) and node.module
                       and node.level == 0 else [])
            for target in targets:
                parts = target.split(".")
                if parts[0] != "funcnet" and any(p.startswith("_") for p in parts[1:]):
                    private.append(f"{name}: {target}")
    assert not private, private
