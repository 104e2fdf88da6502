"""A reader's warning points at the caller's line, however deep in funcnet it was given."""

from __future__ import annotations

import warnings

import pytest

from funcnet.errors import RecordingWarning
from funcnet.robot import read_recording, read_trace


@pytest.mark.parametrize("read", [read_trace, read_recording])
def test_duplicate_columns_warn_at_the_callers_line(read, tmp_path):
    path = tmp_path / "twice.csv"
    path.write_text("time,RP,x,x\n0,0,1,2\n0.1,1,1,2\n0.2,2,1,2\n0.3,3,1,2\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read(path)
    duplicate = [w for w in caught if isinstance(w.message, RecordingWarning)
                 and w.message.problem == "duplicate"]
    assert len(duplicate) == 1, [str(w.message) for w in caught]
    assert duplicate[0].filename == __file__
