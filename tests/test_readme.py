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

from conftest import need_real_trace

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
FIRST_EXAMPLE = "data/kuka-kr300/kr300-run-A.mat"  # shipped: a clone alone runs it
FIRST_MAP = "examples/kuka-kr300-channels.toml"


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


def test_the_second_section_is_your_own_trace_and_starts_on_a_shipped_recording():
    headings = re.findall(r"^## (.+)$", README.read_text(encoding="utf-8"), flags=re.MULTILINE)
    assert headings[0] == "Your own trace"
    text = README.read_text(encoding="utf-8")
    section = text.split("## Your own trace", 1)[1]
    first = re.search(r"^```sh\n(.*?)^```$", section, flags=re.MULTILINE | re.DOTALL)
    assert first is not None
    command = next(line for line in first.group(1).splitlines() if line.startswith("funcnet"))
    assert command.startswith(f"funcnet inspect {FIRST_EXAMPLE} --channels {FIRST_MAP} -o ")
    assert (ROOT / FIRST_EXAMPLE).is_file() and (ROOT / FIRST_MAP).is_file()
    assert (ROOT / FIRST_EXAMPLE).parent.joinpath("LICENSE").is_file()
    assert "../shared/data/sinumerik/axis7-braking-trace.xml" in section  # the later examples'


def test_shell_placeholders_are_marked():
    for block in _blocks("sh"):
        placeholders = {word for word in ("TRACE", "HOST:PORT", "DIR") if word in block}
        if placeholders:
            assert "placeholder" in block, block


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_python_block_runs_on_its_own(index, tmp_path):
    block = PYTHON_BLOCKS[index]
    if "../shared/data/sinumerik" in block:
        need_real_trace()
    result = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True,
                            text=True, timeout=600)
    assert result.returncode == 0, f"block {index}:\n{block}\n{result.stderr[-3000:]}"
