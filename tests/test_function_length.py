"""No function body in ``src/funcnet`` is over 80 lines.

A body is measured from its first statement after the docstring to its last line, comments,
blank lines and nested functions included (a nested function counts in its parent and again on
its own). ruff's complexity rules measure branches, not length; this is the check of length.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "funcnet"
MAX_BODY = 80

# Functions allowed over the limit, each with its reason. "path::name" relative to src/funcnet.
EXEMPT = {
    # A Numba kernel compiled as one loop: split into calls it would lose the inlined inner loop
    # that makes the simulator's step cheap (the reason stands beside the kernel too).
    "sim/_kernel.py::axis_kernel",
}

# Long functions not yet split into named steps; the list only shrinks. A function listed here
# that is no longer long fails the test, so the list cannot go stale.
PENDING: set[str] = set()


def body_length(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines from the first statement after the docstring to the function's last line."""
    body = node.body
    if (len(body) > 1 and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
            and isinstance(body[0].value.value, str)):
        body = body[1:]
    assert node.end_lineno is not None
    return node.end_lineno - body[0].lineno + 1


def long_functions(root: Path = PACKAGE, limit: int = MAX_BODY) -> dict[str, int]:
    """``{"path::name": length}`` of every function under ``root`` whose body is over ``limit``."""
    found = {}
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = body_length(node)
                if length > limit:
                    found[f"{path.relative_to(root).as_posix()}::{node.name}"] = length
    return found


def test_no_function_body_over_80_lines() -> None:
    found = long_functions()
    listed = "\n".join(f"  {key}: {n} lines" for key, n in sorted(found.items()))
    unexpected = sorted(set(found) - EXEMPT - PENDING)
    assert not unexpected, (f"function bodies over {MAX_BODY} lines (split them into named "
                            f"steps): {unexpected}\nall long functions:\n{listed}")


def test_the_exemptions_are_still_needed() -> None:
    found = long_functions()
    stale = sorted((EXEMPT | PENDING) - set(found))
    assert not stale, f"no longer over {MAX_BODY} lines, remove from the lists: {stale}"


def test_the_measure(tmp_path: Path) -> None:
    # docstring left out; comments, blank lines and a nested function counted
    source = ('def f():\n    """Doc\n\n    string."""\n    x = 1\n\n    # why\n'
              "    def g():\n        return x\n    return g\n"
              "def h():\n    return 1\n")
    (tmp_path / "m.py").write_text(source)
    assert long_functions(tmp_path, limit=0) == {"m.py::f": 6, "m.py::g": 1, "m.py::h": 1}
    assert long_functions(tmp_path, limit=5) == {"m.py::f": 6}
