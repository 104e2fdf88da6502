"""Bad and hostile input: each gives one specific FuncnetError naming the file, quickly."""

from __future__ import annotations

import resource

import pytest

from funcnet.errors import ChannelError, FuncnetError, TraceFormatError, WindowError
from funcnet.robot.io.read import read_trace
from funcnet.robot.io.sinumerik import GRID_BYTES_FLOOR

HEAD = '<?xml version="1.0" encoding="utf-8" ?>\n<traceSession>\n<traceData>\n<dataFrame>\n'
SIGNALS = (
    ' <frameHeader startTime="2026-01-01T00:00:00.000Z" stopInc="0.010"/>\n'
    ' <dataSignal id="f1" interval="0.002" name="/Nck/!SD/nckServoDataActCurr32 [u1, 1]"/>\n'
    ' <dataSignal id="f2" interval="0.004" name="/Nck/!SEMA/measPos2 [u1, 1]"/>\n'
)
TAIL = "</dataFrame>\n</traceData>\n</traceSession>\n"


def trace(records: str, signals: str = SIGNALS) -> str:
    return HEAD + signals + records + TAIL


GOOD_RECORDS = ' <rec time="0.000" f1="1.0" f2="2.0"/>\n <rec time="0.002" f1="1.5"/>\n'


def expect(tmp_path, text: str | bytes, error: type[FuncnetError], match: str, name="t.xml"):
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    with pytest.raises(error, match=match) as err:
        read_trace(path)
    assert str(path) in str(err.value), "the message names the file"
    assert "\n" not in str(err.value), "one line"
    return str(err.value)


def test_the_good_trace_reads(tmp_path):
    path = tmp_path / "good.xml"
    path.write_text(trace(GOOD_RECORDS))
    assert read_trace(path).data["AC"].tolist() == [1.0, 1.5, 1.5, 1.5, 1.5, 1.5]


def billion_laughs(where: str) -> str:
    entities = '<!ENTITY lol "lol">\n' + "".join(
        f'<!ENTITY lol{i} "{(f"&lol{i - 1};" if i > 1 else "&lol;") * 10}">\n' for i in range(1, 10)
    )
    body = {
        "content": "<traceSession>&lol9;</traceSession>",
        "attribute": '<traceSession a="&lol9;"><traceData/></traceSession>',
        "record": trace('<rec time="0" f1="&lol9;"/>').split("\n", 1)[1],
    }[where]
    return f'<?xml version="1.0"?>\n<!DOCTYPE lolz [\n{entities}]>\n{body}'


@pytest.mark.parametrize("where", ["content", "attribute", "record"])
def test_billion_laughs_is_refused_without_expansion(tmp_path, where):
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    message = expect(
        tmp_path, billion_laughs(where), TraceFormatError, "DOCTYPE declaration.* at line 2 refused"
    )
    assert "entity expansion is never done" in message
    grown_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown_kib < 100_000, "a billion laughs would take gigabytes"


@pytest.mark.parametrize(
    "body",
    ["<traceSession>&xxe;</traceSession>", '<traceSession a="&xxe;"></traceSession>'],
)
def test_external_entity_is_refused_and_not_read(tmp_path, body):
    text = (
        f'<?xml version="1.0"?>\n<!DOCTYPE t [<!ENTITY xxe SYSTEM "file:///etc/passwd">]>\n{body}'
    )
    message = expect(
        tmp_path,
        text,
        TraceFormatError,
        r"DOCTYPE declaration( with entity declarations \(xxe\))? at line 2 refused: a trace "
        r"has none \(entity expansion is never done",
    )
    assert "root:" not in message


def test_external_dtd_is_refused(tmp_path):
    text = '<?xml version="1.0"?>\n<!DOCTYPE traceSession SYSTEM "http://example.invalid/t.dtd">\n'
    expect(
        tmp_path,
        text + trace(GOOD_RECORDS).split("\n", 1)[1],
        TraceFormatError,
        "DOCTYPE declaration at line 2 refused",
    )


def test_doctype_line_is_found_across_chunks(tmp_path):
    # The declaration after 70 000 blank lines (more than one 64 KiB chunk), split at a chunk
    # boundary: the line is counted, not guessed.
    head = '<?xml version="1.0"?>' + "\n" * 70_000
    head += " " * (65_536 - len(head) % 65_536 - 4)
    text = head + '<!DOCTYPE traceSession SYSTEM "t.dtd">\n' + trace(GOOD_RECORDS).split("\n", 1)[1]
    assert text.index("<!DOCTYPE") % 65_536 > 65_536 - 9  # the marker straddles two chunks
    expect(tmp_path, text, TraceFormatError, "DOCTYPE declaration at line 70001 refused")


def test_malformed_xml_names_the_line(tmp_path):
    text = trace(GOOD_RECORDS + ' <rec time="0.004" f1="2"></dataSignal>\n')
    message = expect(tmp_path, text, TraceFormatError, "not well-formed")
    assert "line 10" in message


def test_truncated_real_trace(real_trace, tmp_path):
    data = real_trace.read_bytes()
    expect(tmp_path, data[: len(data) // 2], TraceFormatError, "not well-formed")


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("", "empty file: not a trace"),
        (b"\x89PNG\r\n\x1a\n\x00\x00binary", "not well-formed"),
        ("<html><body><p>hello</p></body></html>", "not a SINUMERIK trace.*<html>"),
        ("<traceSession><traceCaptureSetup/></traceSession>", "no <traceData>"),
        ("<traceSession>" + "<a>" * 5000 + "</a>" * 5000 + "</traceSession>", "depth"),
    ],
)
def test_not_a_trace(tmp_path, text, match):
    expect(tmp_path, text, TraceFormatError, match)


def test_record_of_an_undeclared_signal(tmp_path):
    text = trace(GOOD_RECORDS + ' <rec time="0.004" f9="3"/>\n')
    message = expect(tmp_path, text, ChannelError, "'f9', which no <dataSignal>")
    assert "line 10" in message


def test_declared_signal_without_records(tmp_path):
    expect(tmp_path, trace(' <rec time="0" f1="1"/>\n'), ChannelError, "measPos2.*never recorded")


def test_duplicated_channel(tmp_path):
    twice = SIGNALS + ' <dataSignal id="f3" name="/Nck/!SEMA/measPos2 [u1, 1]"/>\n'
    expect(tmp_path, trace(GOOD_RECORDS, twice), ChannelError, "measPos2.*declared twice")
    same_id = SIGNALS + ' <dataSignal id="f2" name="/Nck/!SEMA/measPos1 [u1, 1]"/>\n'
    expect(tmp_path, trace(GOOD_RECORDS, same_id), ChannelError, "'f2' is declared twice")


@pytest.mark.parametrize("second", ["0.000", "-0.002"])
def test_time_not_increasing(tmp_path, second):
    text = trace(f' <rec time="0.002" f1="1" f2="2"/>\n <rec time="{second}" f1="2"/>\n')
    assert "line 9" in expect(tmp_path, text, TraceFormatError, "backwards|time >= 0")


def test_time_off_the_grid(tmp_path):
    text = trace(GOOD_RECORDS + ' <rec time="0.005" f1="2"/>\n')
    expect(tmp_path, text, TraceFormatError, "line 10.*not on the 2 ms grid")


def test_empty_data_frame(tmp_path):
    expect(tmp_path, trace(""), TraceFormatError, "data frame 1 has no records")
    expect(
        tmp_path,
        HEAD + "</dataFrame>\n</traceData>\n</traceSession>\n",
        TraceFormatError,
        "data frame 1 has no records",
    )


@pytest.mark.parametrize(
    ("record", "match"),
    [
        ('<rec time="0.004" f1="abc"/>', r"line 10: signal '/Nck/!SD/nckServoDataActCurr32.*'abc'"),
        ('<rec time="0.004" f1="nan"/>', "nckServoDataActCurr32.*not a finite number"),
        ('<rec time="soon" f1="1"/>', "line 10.*time='soon'"),
        ('<rec f1="1"/>', "line 10.*time=None"),
    ],
)
def test_text_where_a_number_belongs(tmp_path, record, match):
    expect(tmp_path, trace(GOOD_RECORDS + f" {record}\n"), TraceFormatError, match)


def test_bad_header_number(tmp_path):
    bad = SIGNALS.replace('stopInc="0.010"', 'stopInc="ten"')
    expect(tmp_path, trace(GOOD_RECORDS, bad), TraceFormatError, "stopInc='ten'")


def test_far_future_time_is_refused_not_allocated(tmp_path):
    # 1e12 s on a 2 ms grid would be 8 TB of float64; refused from the file's size.
    text = trace(
        GOOD_RECORDS + ' <rec time="1000000000000.000" f1="2"/>\n',
        SIGNALS.replace(' stopInc="0.010"', ""),
    )
    expect(tmp_path, text, TraceFormatError, "more than a file of this size can hold")
    huge_stop = SIGNALS.replace('stopInc="0.010"', f'stopInc="{GRID_BYTES_FLOOR:d}"')
    expect(tmp_path, trace(GOOD_RECORDS, huge_stop), TraceFormatError, "more than a file")


def test_records_after_the_frame_end(tmp_path):
    text = trace(GOOD_RECORDS + ' <rec time="0.100" f1="2"/>\n')
    expect(tmp_path, text, TraceFormatError, "after its stopInc")


def test_csv_with_nan_or_text(tmp_path):
    good = "time,RP,AC\n0.000,1,2\n0.002,1.5,2\n"
    # A missing value is a gap (tests/test_robot_formats.py); text where a number belongs is not.
    expect(tmp_path, good + "0.004,1,volts\n", TraceFormatError, "line 4.*'AC'.*'volts'", "c.csv")
    expect(tmp_path, good + "0.004,1,3\n0.006,,4\n0.008,x1,4\n", TraceFormatError,
           "line 6.*'RP'.*'x1'", "c.csv")
    expect(tmp_path, good + "0.004,1,inf\n", TraceFormatError, "line 4.*'AC'.*'inf'", "c.csv")
    expect(tmp_path, good + ",1,3\n", TraceFormatError, "line 4: time is missing",
           "c.csv")
    expect(tmp_path, good + "0.002,1,2\n", TraceFormatError, "line 4.*does not increase", "c.csv")
    expect(tmp_path, good + "0.005,1,2\n", TraceFormatError, "line 4.*not on the", "c.csv")
    expect(tmp_path, "RP,AC\n1,2\n", TraceFormatError, "one 'time' column", "c.csv")
    expect(tmp_path, "", TraceFormatError, "empty file: not a trace", "c.csv")
    expect(tmp_path, "\n", TraceFormatError, "not a readable CSV", "c.csv")
    # Times are printed as plain numbers, not as np.float64(...).
    off_grid = "time,RP\n0,1\n0.002,2\n0.004,3\n0.0075,4\n"
    message = expect(tmp_path, off_grid, TraceFormatError, "line 5: time 0.0075 is not", "c.csv")
    assert "np." not in message
    message = expect(tmp_path, good + "0.001,1,2\n", TraceFormatError, "time 0.001 does", "c.csv")
    assert "np." not in message
    expect(tmp_path, 'time,RP\n0,1\n0.002,"2\n', TraceFormatError, "CSV", "c.csv")


def test_not_parquet_and_unknown_suffix(tmp_path):
    expect(tmp_path, "just text", TraceFormatError, "not a readable Parquet", "p.parquet")
    expect(tmp_path, "time,RP\n", TraceFormatError, "unknown trace format '.txt'", "t.txt")


def test_a_directory_is_not_a_trace(tmp_path):
    for name in ("traces", "traces.xml"):
        (tmp_path / name).mkdir()
        with pytest.raises(TraceFormatError, match="is a directory, not a trace file") as err:
            read_trace(tmp_path / name)
        assert str(tmp_path / name) in str(err.value)


def test_window_longer_than_the_recording(tmp_path):
    path = tmp_path / "good.xml"
    path.write_text(trace(GOOD_RECORDS))
    rec = read_trace(path)
    with pytest.raises(WindowError, match=r"\[0, 1\) s is not inside the recording") as err:
        rec.window(0.0, 1.0)
    assert str(path) in str(err.value)
