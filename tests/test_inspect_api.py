"""The API rough edges a new user hits on the way to inspecting a trace."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import FuncnetError, ParameterError, TraceError


def _recording_with_a_late_signal(tmp_path: Path):
    from funcnet.robot import read_trace

    path = tmp_path / "trace.csv"
    # AP is written from the second tick on, as the 4 ms IPO signals of a SINUMERIK trace
    path.write_text("time,RP,AP\n0.000,0.0,\n0.002,0.1,0.0\n0.004,0.2,0.1\n0.006,0.3,0.2\n")
    return read_trace(path)


def test_read_trace_of_a_missing_file_is_a_trace_error_naming_it(tmp_path):
    from funcnet.robot import read_trace

    missing = tmp_path / "missing.xml"
    with pytest.raises(TraceError, match="missing.xml: no such file") as caught:
        read_trace(missing)
    assert isinstance(caught.value, FuncnetError)
    assert caught.value.path == str(missing)


def test_a_csv_written_from_rec_data_reads_back(tmp_path):
    from funcnet.robot import read_trace

    rec = _recording_with_a_late_signal(tmp_path)
    assert np.isnan(rec.data["AP"].iloc[0])  # not recorded yet: NaN, as in the XML
    rec.data.to_csv(tmp_path / "copy.csv")
    again = read_trace(tmp_path / "copy.csv")
    pd.testing.assert_frame_equal(again.data, rec.data, check_names=False)


def test_an_empty_cell_after_a_signals_first_value_is_a_gap_and_text_an_error(tmp_path):
    from funcnet.errors import RecordingWarning, TraceFormatError
    from funcnet.robot import read_trace

    path = tmp_path / "holes.csv"
    path.write_text("time,RP,AP\n0.000,0.0,1\n0.002,0.1,\n0.004,0.2,2\n")
    with pytest.warns(RecordingWarning, match="missing values at 0.002-0.004 s"):
        assert read_trace(path).gaps == ((0.002, 0.004),)
    path.write_text("time,RP,AP\n0.000,0.0,1\n0.002,0.1,n.a.\n")
    with pytest.raises(TraceFormatError, match="line 3: column 'AP' holds 'n.a.'"):
        read_trace(path)


def _network():
    from funcnet.network import functional_network

    return functional_network(np.random.default_rng(1).random((150, 3)), names=["RP", "AP", "AC"],
                              delay=1, warn=False, label="cruise 1")


def test_net_write_png_names_the_drawing_call(tmp_path):
    net = _network()
    with pytest.raises(ParameterError, match=r"funcnet\.plot\.save_network"):
        net.write(tmp_path / "net.png")
    assert not (tmp_path / "net.png").exists()


def test_save_network_is_titled_and_sized(tmp_path):
    from matplotlib.image import imread

    from funcnet.plot import network_title, save_network

    net = _network()
    out = save_network(net, tmp_path / "net.png", size=(9, 6))
    assert imread(out).shape[:2] == (600, 900)
    title = network_title(net, source="/far/away/axis7.xml")
    assert title.startswith("axis7.xml · cruise 1")
    assert "m = 3, τ = 1, RR = 0.05" in title
    with pytest.raises(ParameterError, match="size"):
        save_network(net, tmp_path / "bad.png", size=(0, 3))


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_edge_timeline_takes_what_window_networks_returns():
    from funcnet import window_networks
    from funcnet.plot import plot_edge_timeline
    from funcnet.robot import Recording, SignalInfo, Window

    t = np.arange(0, 2, 0.002)
    rng = np.random.default_rng(0)
    data = pd.DataFrame({"RP": np.sin(3 * t), "AC": np.cos(5 * t) + rng.normal(0, .1, t.size)},
                        index=pd.Index(t, name="time"))
    info = {c: SignalInfo(c, None, None, 0.002) for c in data}
    rec = Recording(data, {}, info, source="x.csv", sample_period=0.002)
    nets = window_networks(rec, [Window("a", 0.1, 0.7), Window("b", 0.9, 1.5)], delay=2)
    ax = plot_edge_timeline(nets)
    times = sorted({float(x) for c in ax.collections for x, _ in c.get_offsets()})
    assert times == pytest.approx([0.4, 1.2])
    # keyed by label, a network without a window has no place on the timeline
    from funcnet.network import FunctionalNetwork

    with pytest.raises(ParameterError, match="not a time"):
        plot_edge_timeline({"a": FunctionalNetwork.from_pairs(nets["a"].pairs)})


def test_inspect_files_checks_first_and_reads_each_file_when_its_turn_comes(tmp_path):
    # The inspection step of `funcnet inspect`: arguments refused before any file is read, and
    # a file read only when iteration reaches it (its page is drawn before the next is read).
    from funcnet.inspection import inspect_files

    with pytest.raises(ParameterError, match="rr"):
        inspect_files(tmp_path / "missing.csv", rr=2.0)
    first, second = tmp_path / "first.csv", tmp_path / "second.csv"
    inspections = inspect_files(first, second, channels={"q": "RP"})  # neither exists: no error
    assert inspections.paths == (first, second) and inspections.axis is None
    assert inspections.channels.role_of("q") == "RP"
    with pytest.raises(TraceError, match="first.csv: no such file"):
        next(iter(inspections))
