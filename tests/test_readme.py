"""The README's commands run as written: its Python blocks, its shell commands, its make targets.

Each Python block runs in a fresh interpreter with the repository root as working directory. Each
``funcnet`` command of a shell block is checked in one of three ways: the cheap ones run as
written, their output redirected into a temporary folder; the long ones (a whole report, the
demo, a study) and those with placeholders run with ``--help``, which parses the command and its
options. Every ``make`` target named exists in the Makefile. Commands that read the shipped
recordings in ``data/`` need them there.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DATA = ROOT / "data"
# Commands that take minutes (a robot's report, every network of the paper, a study) or that
# name placeholders: checked with --help, not run.
LONG = ("inspect", "demo", "study", "compare", "simulate", "report")
PLACEHOLDERS = ("TRACE", "RUN", "REF", "DIR")


def _blocks(language: str) -> list[str]:
    text = README.read_text(encoding="utf-8")
    return re.findall(rf"^```{language}\n(.*?)^```$", text, flags=re.MULTILINE | re.DOTALL)


def _commands(program: str) -> list[str]:
    """Every command line of the shell blocks that starts with ``program``, continuation lines
    joined and comments cut."""
    found = []
    for block in _blocks("sh"):
        for line in block.replace("\\\n", " ").splitlines():
            line = line.split(" #", 1)[0].strip()
            if line.startswith(program + " "):
                found.append(" ".join(line.split()))
    return found


PYTHON_BLOCKS = _blocks("python")
FUNCNET = _commands("funcnet")
MAKE = _commands("make")


def _needs_data(text: str) -> None:
    for path in re.findall(r"\bdata/[\w./-]+", text):
        if not (ROOT / path).exists():
            pytest.skip(f"{path} is not in this checkout (the recordings ship in data/)")


def _run(args: list[str], tmp_path: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "OMP_WAIT_POLICY": "PASSIVE"}
    return subprocess.run([sys.executable, "-m", "funcnet", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=900)


def test_the_readme_is_short_and_starts_with_make():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200
    first = _blocks("sh")[0].splitlines()
    assert first[0].startswith("make demo") and first[1].startswith("make test")


def test_the_readme_has_commands_to_check():
    assert len(PYTHON_BLOCKS) >= 2
    assert len(FUNCNET) >= 5
    assert any(c.split()[1] not in LONG and "data/" in c for c in FUNCNET)


@pytest.mark.parametrize("command", MAKE)
def test_make_targets_exist(command):
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    targets = set(re.findall(r"^([\w-]+):", makefile, flags=re.MULTILINE))
    for target in command.split()[1:]:
        assert target in targets, f"make {target}: no such target"


@pytest.mark.parametrize("command", FUNCNET)
def test_funcnet_command_runs(command, tmp_path):
    args = shlex.split(command)[1:]
    placeholder = any(word in PLACEHOLDERS or word.startswith(("TRACE", "RUN", "REF", "DIR"))
                      for word in args)
    if not args or args == ["--help"]:
        result = _run(["--help"], tmp_path)
    elif placeholder or args[0] in LONG or "[" in command:
        result = _run([args[0], "--help"], tmp_path)
    else:
        _needs_data(command)
        # the output where the README puts it, moved into the temporary folder
        for flag in ("-o", "--out"):
            if flag in args:
                k = args.index(flag) + 1
                args[k] = str(tmp_path / Path(args[k]).name)
        result = _run(args, tmp_path)
        if "-o" in args:
            assert Path(args[args.index("-o") + 1]).exists()
    assert result.returncode == 0, f"{command}:\n{result.stderr[-3000:]}"


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_python_block_runs_on_its_own(index, tmp_path):
    block = PYTHON_BLOCKS[index]
    _needs_data(block)
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "OMP_WAIT_POLICY": "PASSIVE"}
    result = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True,
                            text=True, timeout=600, env=env)
    assert result.returncode == 0, f"block {index}:\n{block}\n{result.stderr[-3000:]}"
