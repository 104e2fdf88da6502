"""Every block of the README fenced exactly ```python runs as written, on its own.

Each block runs in a fresh interpreter with the repository root as working directory: no
variables from an earlier block, no output of ``make demo``. The shell blocks are checked for
what a reader copies: the first is ``make demo`` / ``make test``; placeholders are marked.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
TRACE = ROOT.parent / "shared" / "data" / "sinumerik" / "axis7-braking-trace.xml"


def _blocks(language: str) -> list[str]:
    text = README.read_text(encoding="utf-8")
    return re.findall(rf"^```{language}\n(.*?)^```$", text, flags=re.MULTILINE | re.DOTALL)


PYTHON_BLOCKS = _blocks("python")


def test_the_readme_has_python_blocks_and_its_first_block_is_make():
    assert len(PYTHON_BLOCKS) >= 3
    first = re.search(r"^```(\w*)\n(.*?)^```$", README.read_text(encoding="utf-8"),
                      flags=re.MULTILINE | re.DOTALL)
    assert first is not None and first.group(1) == "sh"
    assert first.group(2).splitlines()[0].startswith("make demo")
    assert "make test" in first.group(2)


def test_the_second_section_is_your_own_trace():
    headings = re.findall(r"^## (.+)$", README.read_text(encoding="utf-8"), flags=re.MULTILINE)
    assert headings[0] == "Your own trace"
    text = README.read_text(encoding="utf-8")
    assert "../shared/data/sinumerik/axis7-braking-trace.xml" in text
    assert "funcnet inspect" in text


def test_shell_placeholders_are_marked():
    for block in _blocks("sh"):
        placeholders = {word for word in ("TRACE", "HOST:PORT", "DIR") if word in block}
        if placeholders:
            assert "placeholder" in block, block


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_python_block_runs_on_its_own(index, tmp_path):
    block = PYTHON_BLOCKS[index]
    if "../shared/data/sinumerik" in block and not TRACE.is_file():
        pytest.skip(f"the real trace is not at {TRACE}")
    result = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True,
                            text=True, timeout=600)
    assert result.returncode == 0, f"block {index}:\n{block}\n{result.stderr[-3000:]}"
