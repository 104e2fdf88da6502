"""Atomic output leaves the process state alone: the umask is never changed to be read."""

from __future__ import annotations

import os
import stat
import threading

from funcnet._io import write_text_atomic


def test_atomic_write_never_touches_the_umask(tmp_path, monkeypatch):
    def forbidden(mask: int) -> int:
        raise AssertionError("os.umask was called")

    old = os.umask(0o027)
    try:
        monkeypatch.setattr(os, "umask", forbidden)
        path = write_text_atomic(tmp_path / "a.txt", "x")
    finally:
        monkeypatch.undo()
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == 0o640


def test_concurrent_atomic_writes_each_land_whole(tmp_path):
    def write(i: int) -> None:
        write_text_atomic(tmp_path / f"{i % 4}.txt", chr(65 + i) * 1000)

    threads = [threading.Thread(target=write, args=(i,)) for i in range(32)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for path in tmp_path.iterdir():
        text = path.read_text()
        assert len(set(text)) == 1 and len(text) == 1000
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]
