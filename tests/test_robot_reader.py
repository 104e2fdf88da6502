"""Reading traces: the real SINUMERIK trace against its own text, formats, frames, channel maps."""

from __future__ import annotations

import math
import re
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st

from funcnet.errors import ChannelError, ParameterError, RecordingWarning, TraceFormatError
from funcnet.robot.io.channels import DEFAULT_CHANNEL_MAP, ChannelMap, channel_map, check_entries
from funcnet.robot.io.read import read_trace
from funcnet.robot.recording import Recording
from funcnet.robot.signals import parse_signal_name


@pytest.fixture(scope="module")
def real(real_trace) -> Recording:
    return read_trace(real_trace)


def brute_force_grid(path: Path) -> tuple[list[str], dict[str, str], np.ndarray]:
    """An independent reading of a single-frame trace: regular expressions over its lines."""
    text = path.read_text(encoding="utf-8")
    period = min(float(v) for v in re.findall(r'<dataSignal [^>]*interval="([^"]+)"', text))
    ids = dict(re.findall(r'<dataSignal [^>]*id="(f\d+)"[^>]*name="([^"]+)"', text))
    stop_inc = float(re.search(r'stopInc="([^"]+)"', text)[1])
    n = round(stop_inc / period) + 1
    order = list(ids)
    grid = np.full((n, len(order)), np.nan)
    last = {key: math.nan for key in order}
    records = {}
    for line in text.splitlines():
        if "<rec " not in line:
            continue
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', line))
        records[round(float(attrs.pop("time")) / period)] = attrs
    for tick in range(n):
        for key, value in records.get(tick, {}).items():
            last[key] = float(value)
        grid[tick] = [last[key] for key in order]
    return order, ids, grid


# -- the real trace --------------------------------------------------------------------------


def test_real_trace_equals_an_independent_reading_of_its_text(real_trace, real):
    order, ids, grid = brute_force_grid(real_trace)
    by_name = {info.name: column for column, info in real.signals.items()}
    columns = [by_name[ids[key]] for key in order]
    np.testing.assert_array_equal(real.data[columns].to_numpy(), grid)


def test_real_trace_metadata(real_trace, real):
    assert real.sample_period == 0.002
    assert real.axis == 7
    assert real.start_time == "2012-01-20T20:01:47.526Z"
    assert real.source == str(real_trace)
    assert real.data.shape == (22709, 10)  # 45.416 s / 2 ms + 1 ticks, 10 channels
    assert real.data.index.name == "time" and real.data.index.dtype == np.float64
    # Tick k is the float of the decimal the controller writes for k * 2 ms.
    expected = [float(f"{2 * k / 1000:.3f}") for k in range(len(real.data))]
    np.testing.assert_array_equal(real.data.index, expected)
    assert real.data.index[0] == 0.0 and real.data.index[-1] == 45.416
    assert real.roles == {
        "AC": "/Nck/!SD/nckServoDataActCurr32 [u1, 7]",
        "MP": "/Nck/!SEMA/measPos1 [u1, 7]",
        "AP": "/Nck/!SEMA/measPos2 [u1, 7]",
        "RP": "/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 7]",
    }
    assert "nckServoDataFlwErr64" in real.data.columns and "aaStat" in real.data.columns
    assert real.signals["AP"].interval == 0.004 and real.signals["AP"].units_type == "posn"
    assert real.signals["AC"].interval == 0.002 and real.signals["AC"].data_type == "float"
    assert real.signals["aaStat"].data_type == "uword"


def test_real_trace_values_at_chosen_times(real):
    d = real.data
    # First record (t = 0): servo signals written; IPO signals are first written at 2 ms.
    assert d.at[0.0, "AC"] == -0.798340 and d.at[0.0, "RP"] == 0.0
    assert d.at[0.0, "nckServoDataFlwErr64"] == -0.000172
    assert np.isnan(d.at[0.0, "AP"]) and d.at[0.002, "AP"] == 0.000170
    # Carried forward: RP written at 0.000 holds until the move starts at 6.408 s.
    assert d.at[5.0, "RP"] == 0.0 and d.at[6.406, "RP"] == 0.0 and d.at[6.408, "RP"] == 0.000020
    # IPO grid: AP written at 6.998 and 7.002 (4 ms apart) holds over the servo tick between.
    assert d.at[6.998, "AP"] == 34.314170 and d.at[7.0, "AP"] == 34.314170
    assert d.at[7.002, "AP"] == 34.744260 and d.at[7.0, "MP"] == 34.354340
    assert d.at[7.0, "RP"] == 35.382080  # a servo value written at 7.000
    # Last record (t = 45.416): RP and AC written; AP carried from 45.414.
    assert d.at[45.416, "RP"] == 180.0 and d.at[45.416, "AC"] == 0.991272
    assert d.at[45.416, "AP"] == 180.0 and d.at[45.414, "AP"] == 180.0


def test_parquet_round_trip_is_lossless(real, tmp_path):
    path = real.to_parquet(tmp_path / "real.parquet")
    for back in (Recording.from_parquet(path), read_trace(path)):
        pd.testing.assert_frame_equal(back.data, real.data, check_exact=True)
        assert back.data.index.dtype == np.float64 and back.data.index.name == "time"
        assert back.roles == real.roles and back.signals == real.signals
        assert (back.source, back.start_time, back.sample_period, back.axis) == (
            real.source,
            real.start_time,
            real.sample_period,
            real.axis,
        )
        # NaN before the IPO signals' first record survives.
        assert np.isnan(back.data.iloc[0]["AP"])


def test_csv_round_trip(real, tmp_path):
    part = real.window(6.0, 9.0)
    path = tmp_path / "part.csv"
    part.data.to_csv(path)
    back = read_trace(path)
    np.testing.assert_array_equal(back.data.to_numpy(), part.data.to_numpy())
    np.testing.assert_array_equal(back.data.index, part.data.index)
    assert back.sample_period == 0.002
    assert {"RP", "AP", "MP", "AC"} <= set(back.roles)  # a column already named by a role


def test_csv_sparse_rows_are_carried_forward(tmp_path):
    path = tmp_path / "sparse.csv"
    path.write_text("time,RP,AC\n1.000,1,10\n1.002,2,20\n1.008,3,30\n")
    rec = read_trace(path)
    assert rec.data.index.tolist() == [1.0, 1.002, 1.004, 1.006, 1.008]
    assert rec.data["RP"].tolist() == [1, 2, 2, 2, 3]
    assert rec.data["AC"].tolist() == [10, 20, 20, 20, 30]


def test_plain_parquet_table_reads_like_csv(tmp_path):
    path = tmp_path / "plain.parquet"
    pd.DataFrame({"time": [0.0, 0.004, 0.008], "measPos2 [u1, 3]": [1.0, 2.0, 3.0]}).to_parquet(
        path
    )
    rec = read_trace(path)
    assert rec.sample_period == 0.004 and rec.axis == 3 and rec.data["AP"].tolist() == [1, 2, 3]


# -- synthetic traces: setups, frames, axes --------------------------------------------------


def trace_xml(frames: str, *, setup: str = "traceCaptureSetup_V20", servo: str = "0.002") -> str:
    return (
        '<?xml version="1.0" encoding="utf-8" ?>\n<traceSession version="01.00.03.02">\n'
        f'<{setup}><sampleRateSettings servoSampleRate="{servo}" ipo1SampleRate="0.004"/>'
        "<signalSettings>"
        '<signal key="s1" name="/Nck/!SEMA/measPos2 [u1, 1]" unitsType="posn" dataType="double"/>'
        f"</signalSettings></{setup}>\n"
        f"<traceData>{frames}</traceData></traceSession>\n"
    )


SIGNALS = (
    '<dataSignal id="f1" interval="0.002" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 1]" '
    'unitsType="posn" dataType="double"/>'
    '<dataSignal id="f2" interval="0.004" name="/Nck/!SEMA/measPos2 [u1, 1]" unitsType="posn" '
    'dataType="double"/>'
)


def test_plain_setup_and_no_interval_uses_servo_sample_rate(tmp_path):
    signals = '<dataSignal id="f1" name="/Nck/!SEMA/measPos2 [u1, 1]"/>'  # units from the setup
    frame = (
        f'<dataFrame><frameHeader startTime="2026-01-01T00:00:00.000Z" stopInc="0.010"/>{signals}'
        '<rec time="0.000" f1="1"/><rec time="0.006" f1="2"/></dataFrame>'
    )
    path = tmp_path / "plain.xml"
    path.write_text(trace_xml(frame, setup="traceCaptureSetup", servo="0.002"))
    rec = read_trace(path)
    assert rec.sample_period == 0.002
    assert rec.data["AP"].tolist() == [1, 1, 1, 2, 2, 2]  # through stopInc = 10 ms
    assert rec.signals["AP"].units_type == "posn" and rec.signals["AP"].data_type == "double"


def test_several_frames_share_one_time_base(tmp_path):
    frames = (
        f'<dataFrame><frameHeader startTime="2026-01-01T00:00:00.000Z" stopInc="0.004"/>{SIGNALS}'
        '<rec time="0.000" f1="1" f2="10"/><rec time="0.002" f1="2"/></dataFrame>'
        f'<dataFrame><frameHeader startTime="2026-01-01T00:00:00.010Z" stopInc="0.002"/>{SIGNALS}'
        '<rec time="0.000" f1="5"/><rec time="0.002" f2="50"/></dataFrame>'
    )
    path = tmp_path / "frames.xml"
    path.write_text(trace_xml(frames))
    rec = read_trace(path)
    assert rec.data.index.tolist() == [0.0, 0.002, 0.004, 0.006, 0.008, 0.01, 0.012]
    np.testing.assert_array_equal(rec.data["RP"], [1, 2, 2, np.nan, np.nan, 5, 5])
    # Not carried across frames: AP is unknown in frame 2 until written at 12 ms.
    np.testing.assert_array_equal(rec.data["AP"], [10, 10, 10, np.nan, np.nan, np.nan, 50])


def test_frames_without_start_time_follow_each_other(tmp_path):
    frames = (
        f"<dataFrame>{SIGNALS}"
        '<rec time="0.000" f1="1" f2="10"/><rec time="0.002" f1="2"/></dataFrame>'
        f'<dataFrame>{SIGNALS}<rec time="0.000" f1="3" f2="30"/></dataFrame>'
    )
    path = tmp_path / "frames.xml"
    path.write_text(trace_xml(frames))
    assert read_trace(path).data["RP"].tolist() == [1, 2, 3]


def test_overlapping_frames_are_refused(tmp_path):
    frames = (
        f'<dataFrame><frameHeader startTime="2026-01-01T00:00:00.000Z" stopInc="0.004"/>{SIGNALS}'
        '<rec time="0.000" f1="1" f2="10"/></dataFrame>'
        f'<dataFrame><frameHeader startTime="2026-01-01T00:00:00.002Z" stopInc="0.004"/>{SIGNALS}'
        '<rec time="0.000" f1="1" f2="10"/></dataFrame>'
    )
    path = tmp_path / "overlap.xml"
    path.write_text(trace_xml(frames))
    with pytest.raises(TraceFormatError, match="before the previous frame ends") as err:
        read_trace(path)
    assert str(path) in str(err.value)


def two_axes_trace(tmp_path) -> Path:
    signals = (
        '<dataSignal id="f1" interval="0.002" name="/Nck/!SEMA/measPos2 [u1, 1]"/>'
        '<dataSignal id="f2" interval="0.002" name="/Nck/!SEMA/measPos2 [u1, 2]"/>'
        '<dataSignal id="f3" interval="0.002" name="/Channel/!SEMA/stopCode"/>'
    )
    frame = f'<dataFrame>{signals}<rec time="0" f1="1" f2="2" f3="7"/></dataFrame>'
    path = tmp_path / "axes.xml"
    path.write_text(trace_xml(frame))
    return path


def test_several_axes_need_an_axis(tmp_path):
    path = two_axes_trace(tmp_path)
    with pytest.raises(ChannelError, match=r"axes \[1, 2\]") as err:
        read_trace(path)
    assert str(path) in str(err.value)
    rec = read_trace(path, axis=2)
    assert rec.axis == 2 and rec.data.iloc[0].to_dict() == {"AP": 2.0, "stopCode": 7.0}
    with pytest.raises(ChannelError, match="axis 3 is not in the trace"):
        read_trace(path, axis=3)


# -- channel maps ----------------------------------------------------------------------------


def test_parse_signal_name():
    parts = parse_signal_name("/Nck/!SEMA/measPos2 [u1, 12]")
    assert (parts.path, parts.base, parts.unit, parts.axis) == ("/Nck/!SEMA/", "measPos2", 1, 12)
    assert parse_signal_name("RP").base == "RP" and parse_signal_name("RP").axis is None


def test_default_channel_map_roles():
    roles = {
        "/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 1]": "RP",
        "/Nck/!SEMA/measPos2 [u1, 1]": "AP",
        "/Nck/!SEMA/measPos1 [u1, 1]": "MP",
        "/Nck/!SD/nckServoDataActCurr32 [u1, 1]": "AC",
        "/Nck/!SD/nckServoDataCmdCurr32 [u1, 1]": "RC",
        "/Nck/!SD/nckServoDataFlwErr64 [u1, 1]": None,
    }
    for name, role in roles.items():
        assert DEFAULT_CHANNEL_MAP.role_of(name) == role


def test_channel_map_from_dict_toml_and_path_keys(real_trace, real, tmp_path):
    toml = tmp_path / "roles.toml"
    toml.write_text('[channels]\nnckServoDataFlwErr64 = "FE"\n"/Nck/!SEMA/measPos1" = "AP"\n')
    rec = read_trace(real_trace, channels=toml)
    assert rec.roles["FE"] == "/Nck/!SD/nckServoDataFlwErr64 [u1, 7]"
    assert rec.roles["AP"] == "/Nck/!SEMA/measPos1 [u1, 7]"  # AP reassigned, measPos2 unmapped
    np.testing.assert_array_equal(rec.data["AP"], real.data["MP"])
    assert "measPos2" in rec.data.columns and "MP" not in rec.data.columns
    no_defaults = tmp_path / "bare.toml"
    no_defaults.write_text('defaults = false\n[channels]\nmeasPos2 = "AP"\n')
    assert read_trace(real_trace, channels=no_defaults).roles == {"AP": real.roles["AP"]}
    assert channel_map({"x": "RC"}).role_of("/a/x [u1, 1]") == "RC"


def test_bad_channel_maps(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[channels\n")
    with pytest.raises(ChannelError, match="bad.toml"):
        channel_map(bad)
    bad.write_text("channels = 3\n")
    with pytest.raises(ChannelError, match="bad.toml"):
        channel_map(bad)
    with pytest.raises(ParameterError, match="role"):
        ChannelMap({"measPos2": "not a role"})


def test_channel_entry_the_wrong_way_round_is_refused_with_a_hint(real_trace, tmp_path):
    toml = tmp_path / "roles.toml"
    toml.write_text('[channels]\nRC = "nckServoDataCmdVelCtrlIn64"\n')
    with pytest.raises(ChannelError) as err:
        read_trace(real_trace, channels=toml)
    message = str(err.value)
    assert str(real_trace) in message and f"channel map {toml}" in message
    assert "entry 'RC' = 'nckServoDataCmdVelCtrlIn64' matches no signal of the trace" in message
    assert 'entries are "signal name" = "ROLE"' in message
    assert "did you mean 'nckServoDataCmdVelCtrlIn64' = 'RC'?" in message
    # Written the right way round (and in lower case), the same entry assigns the role.
    toml.write_text('[channels]\nnckServoDataCmdVelCtrlIn64 = "rc"\n')
    assert (
        read_trace(real_trace, channels=toml)
        .roles["RC"]
        .startswith("/Nck/!SD/nckServoDataCmdVelCtrlIn64 [")
    )


def test_channel_entry_naming_no_signal_is_refused(real_trace, real):
    with pytest.raises(
        ChannelError, match="channels: entry 'noSuchSignal' = 'RC' matches no"
    ) as err:
        read_trace(real_trace, channels={"noSuchSignal": "RC"})
    message = str(err.value)
    assert str(real_trace) in message and "did you mean" not in message
    assert "measPos2" in message  # the trace's signals are listed
    # A path-qualified key matches only on its path.
    with pytest.raises(ChannelError, match="'/Nck/!SD/measPos1' = 'AP'"):
        read_trace(real_trace, channels={"/Nck/!SD/measPos1": "AP"})
    # The defaults are not checked: the real trace has no RC signal and reads without one.
    assert "nckServoDataCmdCurr32" not in str(real.signals) and "RC" not in real.roles


def test_channel_entries_are_checked_on_every_format(real, tmp_path):
    bad = {"measPos9": "MP"}
    stored = real.to_parquet(tmp_path / "r.parquet")
    with pytest.raises(ChannelError, match="measPos9"):
        read_trace(stored, channels=bad)
    csv = tmp_path / "t.csv"
    csv.write_text("time,measPos2,aaStat\n0,1,2\n0.002,3,4\n")
    with pytest.raises(ChannelError, match="measPos9") as err:
        read_trace(csv, channels=bad)
    assert str(csv) in str(err.value)
    assert read_trace(csv, channels={"measPos2": "ap"}).roles == {"AP": "measPos2"}


def test_paper_roles_are_case_insensitive_others_kept():
    cmap = channel_map({"sigA": "rp", "sigB": "Ac", "sigC": "torque"})
    assert [cmap.role_of(name) for name in ("sigA", "sigB", "sigC")] == ["RP", "AC", "torque"]
    # "rp" replaces the default RP entry like "RP" would.
    assert cmap.role_of("nckServoDataCmdPos2ndEnc64") is None
    check_entries(cmap, ["/a/sigA [u1, 1]", "sigB", "sigC"], "t.xml")  # all match


def test_recording_repr_is_short(real, real_trace):
    text = repr(real)
    assert text.startswith(f"Recording(source={str(real_trace)!r}, duration=45.418 s, ")
    assert "sample_period=0.002 s, axis=7" in text
    assert "AP (measPos2)" in text and "aaStat" in text
    assert len(text) < 400 and "\n" not in text  # neither the table nor the signal metadata


def test_two_signals_for_one_role_are_refused(real_trace, tmp_path):
    with pytest.raises(ChannelError, match="role AP is given by two signals") as err:
        read_trace(real_trace, channels=ChannelMap({"measPos1": "AP", "measPos2": "AP"}))
    assert str(real_trace) in str(err.value)


def test_recording_window_is_half_open(real):
    part = real.window(7.0, 7.01)
    assert part.data.index.tolist() == [7.0, 7.002, 7.004, 7.006, 7.008]
    assert part.source == real.source and part.signals == real.signals


# -- properties ------------------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.integers(0, 40),  # tick
            st.sampled_from(["f1", "f2"]),
            st.floats(-1e6, 1e6, allow_nan=False).map(lambda v: round(v, 6)),
        ),
        min_size=1,
        max_size=60,
    )
)
def test_sparse_records_carry_forward_like_brute_force(tmp_path_factory, writes):
    """Random sparse writes of a servo (f1) and an IPO (f2, odd ticks only) signal."""
    records: dict[int, dict[str, float]] = {}
    for tick, key, value in writes:
        if key == "f2" and tick % 2 == 0:
            tick += 1
        records.setdefault(tick, {})[key] = value
    records.setdefault(0, {}).setdefault("f1", 0.5)  # both signals get recorded
    records.setdefault(1, {}).setdefault("f2", -0.5)
    lines = [
        f'<rec time="{tick * 0.002:.6f}"'
        + "".join(f' {key}="{value:.6f}"' for key, value in sorted(fields.items()))
        + "/>"
        for tick, fields in sorted(records.items())
    ]
    path = tmp_path_factory.mktemp("prop") / "t.xml"
    path.write_text(trace_xml(f"<dataFrame>{SIGNALS}{''.join(lines)}</dataFrame>"))
    written = {key: {f[key] for f in records.values() if key in f} for key in ("f1", "f2")}
    # A signal written with one value only is constant over the recording: left out, said.
    constant = {key for key, values in written.items() if len(values) == 1}
    if constant == {"f1", "f2"}:
        with pytest.raises(TraceFormatError, match="every signal is constant"):
            read_trace(path)
        return
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rec = read_trace(path)
    said = {s for w in caught if isinstance(w.message, RecordingWarning) for s in w.message.signals}
    column = {"f1": "RP", "f2": "AP"}
    assert said == {column[key] for key in constant}
    last = {"f1": math.nan, "f2": math.nan}
    for tick in range(max(records) + 1):
        last.update(records.get(tick, {}))
        for key in ("f1", "f2"):
            if column[key] in rec.data:
                assert rec.data[column[key]].iloc[tick] == pytest.approx(
                    last[key], nan_ok=True, abs=0
                )
    assert len(rec.data) == max(records) + 1


def test_reading_compiles_nothing(real_trace):
    # The reader must not pull in Numba: nothing is compiled on the first call.
    code = (
        "import sys; from funcnet.robot import read_trace; "
        f"read_trace({str(real_trace)!r}); "
        "print(sorted(m for m in ('numba', 'funcnet.core.recurrence') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
