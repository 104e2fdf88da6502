"""funcnet.robot.complete_span: the span where every signal has a recorded value."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import WindowError
from funcnet.robot import Recording, SignalInfo, complete_span


def recording(ap: list[float], rc: list[float] | None = None) -> Recording:
    t = np.arange(len(ap)) * 0.002
    data = pd.DataFrame({"RC": rc if rc is not None else np.arange(len(ap), dtype=float),
                         "AP": ap}, index=pd.Index(t, name="time"))
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    return Recording(data, {}, info, source="trace.csv", sample_period=0.002)


def test_the_span_starts_at_the_first_tick_where_every_signal_has_a_value():
    rec = recording([np.nan, np.nan, 1.0, 1.5, 2.0, 2.5])
    window = complete_span(rec)
    assert (window.label, window.start, window.phase) == ("whole recording", 0.004, None)
    assert window.stop == pytest.approx(0.012)  # one period past the last tick
    # the window holds exactly the recorded ticks (start <= time < stop)
    part = rec.window(window.start, window.stop).data
    assert len(part) == 4 and not part.isna().any().any()


def test_a_recording_complete_from_its_first_tick_spans_all_of_it():
    rec = recording([0.0, 1.0, 2.0])
    window = complete_span(rec)
    assert window.start == 0.0 and len(rec.window(window.start, window.stop).data) == 3


def test_no_complete_tick_names_the_recording():
    rec = recording([np.nan, 1.0, np.nan], rc=[0.0, np.nan, 1.0])
    with pytest.raises(WindowError, match="trace.csv: no tick where every signal"):
        complete_span(rec)
