"""The results folder's lock: flock on POSIX, msvcrt on Windows, and nothing of either at import."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from funcnet.errors import StudyError
from funcnet.study.store import exclusive

SRC = Path(__file__).resolve().parents[1] / "src"


def test_posix_lock_refuses_a_second_holder_and_is_released(tmp_path):
    with exclusive(tmp_path):
        with pytest.raises(StudyError, match="another study run is using this folder"):
            with exclusive(tmp_path):
                pass
    with exclusive(tmp_path):  # released on leaving, also after an error inside
        pass
    with pytest.raises(RuntimeError):
        with exclusive(tmp_path):
            raise RuntimeError
    with exclusive(tmp_path):
        pass


# Windows, as far as it can be without Windows: fcntl cannot be imported, and msvcrt is a
# stand-in that keeps its byte locks in a table, refusing a held byte as Windows does (OSError).
WINDOWS = textwrap.dedent("""
    import os, sys, types
    sys.modules["fcntl"] = None                      # import fcntl raises ImportError
    from funcnet import load_results                 # imports without fcntl
    from funcnet.errors import StudyError
    from funcnet.study.store import exclusive
    # installed after the imports: the standard library takes msvcrt's presence for Windows
    held, calls = set(), []
    def locking(fd, mode, nbytes):
        key = (os.fstat(fd).st_ino, os.lseek(fd, 0, os.SEEK_CUR), nbytes)
        calls.append((mode, key[1], nbytes))
        if mode == msvcrt.LK_NBLCK:
            if key in held:
                raise PermissionError(13, "Permission denied")
            held.add(key)
        elif mode == msvcrt.LK_UNLCK:
            held.remove(key)
    msvcrt = types.SimpleNamespace(LK_NBLCK=2, LK_UNLCK=0, locking=locking)
    sys.modules["msvcrt"] = msvcrt

    from pathlib import Path
    out = Path(sys.argv[1])
    with exclusive(out):
        try:
            with exclusive(out):
                raise SystemExit("a second holder was let in")
        except StudyError as exc:
            print("refused:", exc)
    with exclusive(out):
        pass
    assert not held, held
    assert [(m, at, n) for m, at, n in calls] == [(2, 0, 1), (2, 0, 1), (0, 0, 1),
                                                  (2, 0, 1), (0, 0, 1)], calls
    print("ok", load_results.__name__)
""")


def test_windows_lock_without_fcntl(tmp_path):
    result = subprocess.run([sys.executable, "-c", WINDOWS, str(tmp_path)], capture_output=True,
                            text=True, timeout=300, env={**os.environ, "PYTHONPATH": str(SRC)})
    assert result.returncode == 0, result.stderr
    assert "refused: " in result.stdout and "another study run is using this folder" in \
        result.stdout
    assert result.stdout.strip().endswith("ok load_results")


def test_load_results_imports_without_fcntl():
    code = ("import sys; sys.modules['fcntl'] = None\n"
            "import funcnet\nfrom funcnet import load_results\nfrom funcnet.study import store\n"
            "print(load_results.__module__)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=300, env={**os.environ, "PYTHONPATH": str(SRC)})
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "funcnet.study.store"
