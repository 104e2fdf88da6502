"""Tests of the ``funcnet`` command line, in process (CliRunner) and as real subprocesses."""

from __future__ import annotations

import io
import json
import subprocess
import sys
import warnings
from pathlib import Path

import networkx as nx
import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet import cli
from funcnet.cli import app, messages, network_output, options as cli_options, selection

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

runner = CliRunner()


@pytest.fixture(scope="module")
def trial(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A short simulated trial (about 3 s at 500 Hz) written as a SINUMERIK trace."""
    from funcnet.sim import Trial, write_plan

    folder = tmp_path_factory.mktemp("cli") / "plan"
    write_plan([Trial("quick", "main", speed=350, tcp=1.6, step=1)], folder, workers=1)
    return folder / "quick.xml"


def _library_network(trace: Path, start: float, stop: float, signals=None, **parameters):
    from funcnet import window_networks
    from funcnet.robot import Window, read_recording

    recording = read_recording(trace, signals=signals)
    window = Window(f"{start:.3f}-{stop:.3f} s", start, stop)
    return window_networks(recording, [window], signals=signals, **parameters)[window.label]


def _assert_one_error_line(result, *needles: str) -> None:
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr  # no warning lines either
    assert lines[0].startswith("funcnet: error: ")
    assert "Traceback" not in result.output and "Usage:" not in result.output
    assert not set("╭│╰─") & set(result.output)  # no rich box
    for needle in needles:
        assert needle in lines[0]


# --------------------------------------------------------------------------------------------
# help


@pytest.mark.parametrize(
    ("command", "words"),
    [
        ([], ["demo", "simulate", "network", "inspect", "backlash", "study", "report"]),
        (["inspect"], ["TRACE", "--out", "--no-evidence", "--verbose"]),
        (["demo"], ["--out", "report"]),
        (["simulate"], ["--plan", "--seed", "manifest"]),
        (["network"], ["--signals", "--phase", "--window", "--mu", "--theiler", "--channels"]),
        (["study"], ["--scheduler", "local-cluster", "--workers", "resume"]),
        (["report"], ["RESULTS_DIR", "--out"]),
    ],
)
def test_help_is_the_reference(command: list[str], words: list[str]) -> None:
    result = runner.invoke(app, [*command, "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0
    for word in words:
        assert word in result.output


def test_version_and_bare_command() -> None:
    from funcnet import __version__

    version = runner.invoke(app, ["--version"])
    assert version.exit_code == 0 and version.stdout.strip() == f"funcnet {__version__}"
    bare = runner.invoke(app, [], env={"COLUMNS": "200"})  # the help, not an error line
    assert "Commands" in bare.stdout and "network" in bare.stdout and bare.stderr == ""
    # Flags show no value type in the help.
    (line,) = [text for text in bare.stdout.splitlines() if "--version" in text]
    assert "<bool>" not in line and "Print the version" in line


@pytest.mark.parametrize(
    ("arguments", "needles"),
    [
        (["network", "x.xml", "--bogus"], ["No such option", "--bogus"]),
        (["network"], ["Missing argument", "trace"]),
        (["no-such-command"], ["No such command", "no-such-command"]),
        (["network", "x.xml", "--dim", "three"], ["Invalid value", "--dim"]),
        (["netwrk", "x.xml"], ["netwrk", "Did you mean 'network'"]),
    ],
)
def test_usage_errors_are_one_plain_line(arguments: list[str], needles: list[str]) -> None:
    _assert_one_error_line(runner.invoke(app, arguments, env={"COLUMNS": "60"}), *needles)


# --------------------------------------------------------------------------------------------
# network


def test_network_prints_every_pair_of_the_real_trace(real_trace) -> None:
    result = runner.invoke(
        app, ["network", str(real_trace), "--window", "7:8", "--signals", "RP,AP,AC,V"]
    )
    assert result.exit_code == 0, result.output
    printed = pd.read_fwf(io.StringIO(result.stdout))
    expected = _library_network(real_trace, 7.0, 8.0, signals=["RP", "AP", "AC", "V"]).pairs
    # every column but direction_reason, a sentence (-o pairs.csv keeps it)
    assert list(printed.columns) == [c for c in expected.columns if c != "direction_reason"]
    columns = ["x", "y", "kind", "direction"]
    assert printed[columns].values.tolist() == expected[columns].values.tolist()
    np.testing.assert_allclose(printed["c_diff"], expected["c_diff"], atol=1e-6)
    # The real trace's AP is a 4 ms staircase: the warning is one plain line.
    assert "funcnet: warning: " in result.stderr and "staircase" in result.stderr


def test_network_default_signals_are_the_roles_plus_v(trial: Path, tmp_path: Path) -> None:
    out = tmp_path / "net.json"
    result = runner.invoke(
        app,
        [
            "network",
            str(trial),
            "--window",
            "0.5:1.1",
            "--dim",
            "2",
            "--delay",
            "5",
            "--mu",
            "0.1",
            "--normalize",
            "zscore",
            "--theiler",
            "2",
            "-o",
            str(out),
        ],
    )
    assert result.exit_code == 0, result.output
    from funcnet import FunctionalNetwork

    written = FunctionalNetwork.from_json(out.read_text())
    assert written.nodes == ("RP", "AP", "MP", "V", "RC", "AC")
    expected = _library_network(
        trial, 0.5, 1.1, dim=2, delay=5, mu=0.1, normalize="zscore", theiler=2
    )
    assert written == expected


def test_network_of_the_whole_recording(trial: Path, tmp_path: Path) -> None:
    from funcnet import FunctionalNetwork, functional_network
    from funcnet.robot import read_recording

    out = tmp_path / "whole.json"
    result = runner.invoke(app, ["network", str(trial), "--signals", "RP,MP", "--window", "all",
                                 "-o", str(out)])
    assert result.exit_code == 0, result.output
    written = FunctionalNetwork.from_json(out.read_text())
    data = read_recording(trial).data[["RP", "MP"]]  # every sample, none left out
    expected = functional_network(data, label="whole recording")
    assert written.n_samples == len(data)
    pd.testing.assert_frame_equal(written.pairs, expected.pairs)


def test_network_phase_and_drawings(trial: Path, tmp_path: Path) -> None:
    from funcnet.robot import detect_phases, phase_windows, read_recording

    braking = [
        w for w in phase_windows(detect_phases(read_recording(trial))) if w.phase == "braking"
    ]
    assert len(braking) == 1
    graphml, png, svg = tmp_path / "n.graphml", tmp_path / "n.png", tmp_path / "n.svg"
    for path in (graphml, png, svg):
        result = runner.invoke(app, ["network", str(trial), "--phase", "braking", "-o", str(path)])
        assert result.exit_code == 0, result.output
        assert f"wrote {path}" in result.stdout
    expected = _library_network(trial, braking[0].start, braking[0].stop)
    graph = nx.read_graphml(graphml)
    assert set(graph.nodes) == set(expected.nodes)
    assert graph.number_of_edges() == expected.to_networkx().number_of_edges()
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    text = svg.read_text()
    assert all(f'id="node:{name}"' in text for name in expected.nodes)


def test_network_rich_table_on_a_terminal(trial: Path, monkeypatch) -> None:
    monkeypatch.setattr(network_output, "is_terminal", lambda stream: True)
    result = runner.invoke(
        app, ["network", str(trial), "--window", "0.5:1.1"], env={"COLUMNS": "200"}
    )
    assert result.exit_code == 0, result.output
    assert "┃" in result.stdout or "│" in result.stdout  # a box-drawn table
    assert "c_diff" in result.stdout and "reads as x->y" in result.stdout
    assert "c_xy" in result.stdout and "eps_ordered" in result.stdout  # wide: more columns
    assert "degenerate" in result.stdout
    assert "…" not in result.stdout


def test_network_table_says_what_became_of_degenerate_pairs(trial: Path, monkeypatch) -> None:
    monkeypatch.setattr(network_output, "is_terminal", lambda stream: True)
    arguments = ["network", str(trial), "--window", "0.5:0.8", "--signals", "RP,AP"]
    for options, words in (([], "degenerate pairs are no edges"),
                           (["--keep-degenerate"], "degenerate pairs are flagged edges")):
        result = runner.invoke(app, [*arguments, *options], env={"COLUMNS": "200"})
        assert result.exit_code == 0, result.output
        assert words in " ".join(result.stdout.split())


def test_network_table_on_a_narrow_terminal(trial: Path, monkeypatch) -> None:
    monkeypatch.setattr(network_output, "is_terminal", lambda stream: True)
    result = runner.invoke(
        app, ["network", str(trial), "--window", "0.5:1.1"], env={"COLUMNS": "80"}
    )
    assert result.exit_code == 0, result.output
    assert "…" not in result.stdout  # nothing cut short
    assert max(len(line) for line in result.stdout.splitlines()) <= 80
    assert "-o net.json keeps every column" in " ".join(result.stdout.split())
    rows = [
        [cell.strip() for cell in line.split("│")[1:-1]]
        for line in result.stdout.splitlines()
        if line.startswith("│")
    ]
    expected = _library_network(trial, 0.5, 1.1).pairs
    # narrow: the weight is left out, the direction kept
    columns = ["x", "y", "kind", "direction", "c_diff", "t_diff"]
    assert [row[:4] for row in rows] == expected[columns[:4]].values.tolist()
    printed = np.array([[float(cell) for cell in row[4:6]] for row in rows])
    assert printed.shape == (len(expected), 2)
    # The degenerate flag is shown however narrow the terminal.
    assert [row[6] for row in rows] == [str(flag) for flag in expected["degenerate"]]
    # 3 significant digits of every number
    np.testing.assert_allclose(printed, expected[columns[4:]].to_numpy(), rtol=5e-3, atol=1e-12)


def test_network_options_are_checked_before_the_trace_is_read(trial: Path, tmp_path) -> None:
    # The window 0-0.2 s is before the motion: its constant signals would fail first.
    constant = ["--window", "0:0.2", "--signals", "RP,AP"]
    for option, needles in ((["--rr", "2"], ["rr", "2"]), (["--metric", "cosine"], ["cosine"])):
        result = runner.invoke(app, ["network", str(trial), *constant, *option])
        _assert_one_error_line(result, *needles)
        assert "constant" not in result.stderr
        missing = runner.invoke(app, ["network", str(tmp_path / "missing.xml"), *option])
        _assert_one_error_line(missing, *needles)
    bad = runner.invoke(app, ["network", str(trial), *constant, "--resample", "cubic"])
    _assert_one_error_line(bad, "--resample", "cubic")


def test_network_help_shows_the_defaults_of_network_parameters() -> None:
    import typer.main

    from funcnet import NetworkParameters

    command = typer.main.get_command(app).commands["network"]  # type: ignore[attr-defined]
    helps = {param.name: param.help or "" for param in command.params}
    defaults = NetworkParameters.defaults()
    shown = ["dim", "delay", "rr", "cr", "mu", "metric", "normalize", "measure", "rule", "theiler"]
    for name in shown:
        value = "none" if defaults[name] is None else defaults[name]
        assert helps[name].endswith(f"[default: {value}]"), (name, helps[name])
    assert helps["mu_c"].endswith("[default: --mu]")
    assert helps["mu_t"].endswith("[default: --mu]")
    assert "chebyshev" in helps["metric"] and "cityblock" in helps["metric"]


@pytest.mark.parametrize("command_name", ["network", "stability", "inspect"])
def test_an_option_for_every_network_parameter(command_name: str) -> None:
    import typer.main

    from funcnet import NetworkParameters

    command = typer.main.get_command(app).commands[command_name]  # type: ignore[attr-defined]
    flags = {opt for param in command.params for opt in param.opts}
    for name in NetworkParameters.names():
        if name not in cli_options.NO_OPTION:
            assert cli_options.FLAGS[name] in flags, name


def test_study_help_shows_the_default_workers() -> None:
    import typer.main

    from funcnet.study.backends import DEFAULT_WORKERS

    command = typer.main.get_command(app).commands["study"]  # type: ignore[attr-defined]
    (workers,) = [param for param in command.params if param.name == "workers"]
    assert (workers.help or "").endswith(f"[default: {DEFAULT_WORKERS}]")


def test_terminal_columns_are_pairs_columns() -> None:
    from funcnet.network.schema import PAIR_COLUMNS

    for narrow in (False, True):
        columns = network_output._shown_columns(narrow)
        assert set(columns) <= set(PAIR_COLUMNS) and "degenerate" in columns


def test_network_new_parameters(trial: Path, tmp_path: Path) -> None:
    from funcnet import FunctionalNetwork

    out = tmp_path / "net.json"
    arguments = ["network", str(trial), "--window", "0.5:0.8", "--signals", "RP,AP,AC"]
    options = ["--metric", "chebyshev", "--mu-c", "0.02", "--mu-t", "0.2", "--keep-degenerate"]
    result = runner.invoke(app, [*arguments, *options, "-o", str(out)])
    assert result.exit_code == 0, result.output
    written = FunctionalNetwork.from_json(out.read_text())
    parameters = written.parameters
    assert (parameters.metric, parameters.mu_c, parameters.mu_t) == ("supremum", 0.02, 0.2)
    assert parameters.degenerate == "keep"
    expected = _library_network(
        trial, 0.5, 0.8, signals=["RP", "AP", "AC"], metric="supremum", mu_c=0.02, mu_t=0.2,
        degenerate="keep",
    )
    assert written == expected


@pytest.mark.parametrize(
    ("option", "message"),
    [
        (["--mu-c", "-1"], "--mu-c must be finite and >= 0, got -1.0"),
        (["--dim", "0"], "--dim must be >= 1, got 0"),
        (["--metric", "cosine"], "--metric must be one of "),
        (["--rule", "pyunicorn", "--theiler", "2"], "--theiler must be 0 with rule="),
        (["--resample", "cubic"], "--resample must be one of decimate, interpolate"),
    ],
)
def test_network_bad_values_are_spelled_as_options(tmp_path: Path, option, message) -> None:
    # Checked before the (missing) trace is read.
    result = runner.invoke(app, ["network", str(tmp_path / "missing.xml"), *option])
    _assert_one_error_line(result, f"funcnet: error: {message}")


def test_a_degenerate_pair_through_the_command_line(tmp_path: Path) -> None:
    # Q takes three values: its recurrence threshold is 0, every pair with it is degenerate.
    t = np.arange(400) / 500.0
    noise = np.random.default_rng(0).normal(size=t.size)
    trace = tmp_path / "trace.csv"
    pd.DataFrame(
        {
            "time": t,
            "RP": np.sin(2 * np.pi * 1.3 * t),
            "AC": np.cos(2 * np.pi * 2.1 * t) + 0.1 * noise,
            "Q": np.round(np.sin(2 * np.pi * 1.3 * t)),
        }
    ).to_csv(trace, index=False)
    from funcnet import FunctionalNetwork

    arguments = ["network", str(trace), "--signals", "RP,AC,Q", "--window", "all"]
    dropped = runner.invoke(app, [*arguments, "-o", str(tmp_path / "net.json")])
    assert dropped.exit_code == 0, dropped.output
    assert "funcnet: warning: " in dropped.stderr and "degenerate" in dropped.stderr
    net = FunctionalNetwork.from_json((tmp_path / "net.json").read_text())
    flagged = net.pairs[net.pairs["degenerate"]]
    assert {tuple(sorted(p)) for p in flagged[["x", "y"]].values.tolist()} == {
        ("Q", "RP"), ("AC", "Q")
    }
    assert (flagged["degenerate_reason"] != "").all()
    assert "Q" not in set(net.edges["source"]) | set(net.edges["target"])

    kept = runner.invoke(
        app, [*arguments, "--keep-degenerate", "-o", str(tmp_path / "net.graphml")]
    )
    assert kept.exit_code == 0, kept.output
    graph = nx.read_graphml(tmp_path / "net.graphml")
    edges = {(u, v): bool(data["degenerate"]) for u, v, data in graph.edges(data=True)}
    assert any(flag and "Q" in pair for pair, flag in edges.items()), edges
    assert all(not flag for pair, flag in edges.items() if "Q" not in pair), edges

    plain = runner.invoke(app, arguments)  # piped: every column, the flag and its reason
    header = plain.stdout.splitlines()[0].split()
    assert "degenerate" in header and "degenerate_reason" in header


def test_network_normalize_none(trial: Path, tmp_path: Path) -> None:
    help_text = runner.invoke(app, ["network", "--help"], env={"COLUMNS": "200"}).stdout
    # the flag's own words, not the Python spelling (normalize=None)
    help_text = " ".join(help_text.split())
    assert "none (signals as recorded)" in help_text and "normalize=None" not in help_text
    out = tmp_path / "net.json"
    arguments = ["network", str(trial), "--window", "0.5:1.1", "--signals", "RP,AP,AC"]
    result = runner.invoke(app, [*arguments, "--normalize", "none", "-o", str(out)])
    assert result.exit_code == 0, result.output
    from funcnet import FunctionalNetwork

    expected = _library_network(trial, 0.5, 1.1, signals=["RP", "AP", "AC"], normalize=None)
    assert FunctionalNetwork.from_json(out.read_text()) == expected
    minmax = _library_network(trial, 0.5, 1.1, signals=["RP", "AP", "AC"])
    assert not expected.pairs["eps_x"].equals(minmax.pairs["eps_x"])  # it did change something


def test_network_phases_of_a_trace_with_several_moves(real_trace) -> None:
    from funcnet.robot import PHASES, detect_phases, phase_windows, read_recording

    # every phase detect_phases returns, standstill included, in --list-phases and --phase
    windows = phase_windows(detect_phases(read_recording(real_trace)), include=PHASES)
    assert sum(w.phase == "standstill" for w in windows) == 4
    cruises = [w for w in windows if w.phase == "cruise"]
    assert len(cruises) == 3
    result = runner.invoke(app, ["network", str(real_trace), "--phase", "cruise"])
    _assert_one_error_line(result, "occurs 3 times")
    for w in cruises:
        assert f"'{w.label}' ({w.start:g}-{w.stop:g} s)" in result.stderr

    listed = runner.invoke(app, ["network", str(real_trace), "--list-phases"])
    assert listed.exit_code == 0, listed.output
    lines = [" ".join(line.split()) for line in listed.stdout.splitlines()]
    assert lines[0] == "label phase start stop"
    assert lines[1:] == [f"{w.label} {w.phase} {w.start:.6g} {w.stop:.6g}" for w in windows]
    standstill = runner.invoke(app, ["network", str(real_trace), "--phase", "standstill"])
    _assert_one_error_line(standstill, "occurs 4 times")


@pytest.mark.parametrize("method", ["decimate", "interpolate"])
def test_network_resample_removes_the_staircases(real_trace, tmp_path: Path, method) -> None:
    from funcnet import FunctionalNetwork, window_networks
    from funcnet.robot import add_derived_signals, read_trace, resample, span_window

    out = tmp_path / "net.json"
    arguments = ["network", str(real_trace), "--window", "7:7.6", "--signals", "RP,AP,MP,V"]
    result = runner.invoke(app, [*arguments, "--resample", method, "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "staircase" not in result.stderr
    # Independently: resample the recording, then derive V on the new grid.
    recording = add_derived_signals(resample(read_trace(real_trace), method=method), ["V"])
    window = span_window(7.0, 7.6)
    expected = window_networks(recording, [window], signals=["RP", "AP", "MP", "V"])
    written = FunctionalNetwork.from_json(out.read_text())
    assert written == expected[window.label]
    assert written.n_samples == (150 if method == "decimate" else 300)


@pytest.mark.parametrize(
    ("terminal", "quiet", "drawn"),
    [(True, False, True), (True, True, False), (False, False, False)],
)
def test_network_progress_only_on_a_terminal_unless_quiet(
    trial: Path, tmp_path: Path, monkeypatch, terminal: bool, quiet: bool, drawn: bool
) -> None:
    monkeypatch.setattr(messages, "is_terminal", lambda stream: terminal)
    out = tmp_path / "net.json"
    arguments = ["network", str(trial), "--window", "0.5:0.8", "--signals", "RP,AP", "-o", str(out)]
    # rich draws on the captured stream as on a terminal (its documented overrides).
    env = {"TTY_COMPATIBLE": "1", "TTY_INTERACTIVE": "1"}
    result = runner.invoke(app, [*arguments, *(["--quiet"] if quiet else [])], env=env)
    assert result.exit_code == 0, result.output
    # the set-point check first (RP and AP: one set-point pair), then the file written
    check, wrote = result.stdout.splitlines()[:2], result.stdout.splitlines()[2:]
    assert check[0].startswith("Set-point check: Here the rule's arrows point into the set-point")
    assert "direction reading" in check[1] and "of 1 set-point pairs" in check[1]
    assert wrote == [f"wrote {out}"] and out.is_file()
    bar = "━" in result.stderr and "network" in result.stderr
    assert bar == drawn, result.stderr
    if not drawn:
        assert result.stderr == ""


@pytest.mark.parametrize(
    ("arguments", "needles"),
    [
        (["--window", "5:1"], ["--window"]),
        (["--window", "abc"], ["--window", "START:STOP"]),
        (["--window", "0.5:1.1", "--mu", "-1"], ["mu"]),
        (["--window", "0.5:1.1", "--signals", "RP,XX"], ["XX"]),
        (["--window", "50:60"], ["window"]),
        (["--window", "0.5:1.1", "--phase", "cruise"], ["--phase", "--window"]),
        (["--phase", "reversal"], ["reversal"]),
        (["--window", "0:0.2", "--signals", "RP,AP"], ["constant"]),
    ],
)
def test_network_bad_options(trial: Path, tmp_path: Path, arguments, needles) -> None:
    out = tmp_path / "net.json"
    result = runner.invoke(app, ["network", str(trial), *arguments, "-o", str(out)])
    _assert_one_error_line(result, *needles)
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_network_bad_files(real_trace, tmp_path: Path) -> None:
    out = tmp_path / "out" / "net.png"
    missing = tmp_path / "missing.xml"
    _assert_one_error_line(
        runner.invoke(app, ["network", str(missing), "-o", str(out)]), str(missing)
    )
    truncated = tmp_path / "truncated.xml"
    truncated.write_bytes(real_trace.read_bytes()[:5000])
    _assert_one_error_line(
        runner.invoke(app, ["network", str(truncated), "-o", str(out)]), str(truncated)
    )
    # The real trace's staircase warning is not printed when the command fails.
    negative = runner.invoke(app, ["network", str(real_trace), "--window", "7:8", "--mu", "-1"])
    _assert_one_error_line(negative, "mu")
    unknown = tmp_path / "net.pdf"
    _assert_one_error_line(
        runner.invoke(app, ["network", str(real_trace), "-o", str(unknown)]), ".pdf"
    )
    assert not (tmp_path / "out").exists() and not unknown.exists()


def test_errors_in_a_real_subprocess(tmp_path: Path) -> None:
    script = Path(sys.executable).parent / "funcnet"
    command = [str(script)] if script.exists() else [sys.executable, "-m", "funcnet.cli"]
    malformed = tmp_path / "bad.xml"
    malformed.write_text("<traceSession><traceData><dataFrame>")
    result = subprocess.run(
        [*command, "network", str(malformed)], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("funcnet: error: ")
    assert str(malformed) in result.stderr and result.stdout == ""
    usage = subprocess.run(
        [*command, "network", str(malformed), "--bogus"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert usage.returncode == 2 and usage.stdout == ""
    assert usage.stderr.startswith("funcnet: error: No such option: --bogus")
    assert usage.stderr.count("\n") == 1


# --------------------------------------------------------------------------------------------
# simulate, study, report, demo


def test_simulate_a_plan_file(tmp_path: Path) -> None:
    plan = tmp_path / "plan.toml"
    plan.write_text('[[group]]\nname = "fast"\nspeeds = [350]\ntcps = [1.2]\nsteps = [1]\n')
    out = tmp_path / "traces"
    result = runner.invoke(app, ["simulate", "--plan", str(plan), "--out", str(out), "--seed", "3"])
    assert result.exit_code == 0, result.output
    manifest = pd.read_csv(out / "manifest.csv")
    assert manifest["name"].tolist() == ["fast-v350-p12-s1"]
    assert manifest["seed"].tolist() == [3]
    trace = out / "fast-v350-p12-s1.xml"
    first = trace.read_bytes()
    assert "1 simulated, 0 skipped" in result.stdout
    again = runner.invoke(app, ["simulate", "--plan", str(plan), "--out", str(out), "--seed", "3"])
    assert again.exit_code == 0 and trace.read_bytes() == first
    assert "0 simulated, 1 skipped" in again.stdout
    reseeded = runner.invoke(app, ["simulate", "--plan", str(plan), "--out", str(out)])
    assert "1 simulated, 0 skipped" in reseeded.stdout
    bad = runner.invoke(app, ["simulate", "--plan", str(tmp_path / "none.toml"), "--out", str(out)])
    _assert_one_error_line(bad, "none.toml")


def test_simulate_knows_the_named_plans() -> None:
    from funcnet.sim import NAMED_PLANS

    result = runner.invoke(app, ["simulate", "--help"], env={"COLUMNS": "200"})
    # the help is wrapped to the terminal, possibly after a hyphen
    text = " ".join(result.stdout.replace("-\n", "-").split()).replace("- ", "-")
    for name in NAMED_PLANS:
        assert f"'{name}'" in text


def test_study_and_report_commands(trial: Path, tmp_path: Path) -> None:
    study = tmp_path / "study.toml"
    study.write_text(
        f'signals = ["RP", "AP", "V"]\n[recordings]\npaths = ["{trial}"]\n'
        '[[windows]]\nkind = "range"\nstart = 0.5\nstop = 1.1\n'
        '[[windows]]\nkind = "range"\nstart = 0.0\nstop = 0.2\n'
        "[network]\ndelay = [5, 10]\n"
    )
    out = tmp_path / "results"
    arguments = ["study", str(study), "--out", str(out), "--workers", "0"]
    first = runner.invoke(app, arguments)
    # The window before the motion has constant positions: reported, exit status 1.
    assert first.exit_code == 1, first.output
    assert "4 tasks: 4 computed, 0 already done, 2 failed" in first.stdout
    # one line per cause, its tasks counted
    assert first.stderr.count("funcnet: failed: ") == 1, first.stderr
    assert "funcnet: failed: 2 task(s)" in first.stderr
    # Warnings once per problem, counted over the tasks (not once more per task in-process).
    warned = [line for line in first.stderr.splitlines() if line.startswith("funcnet: warning")]
    assert all(" networks computed, e.g. " in line for line in warned), warned
    second = runner.invoke(app, arguments)
    assert "4 tasks: 0 computed, 4 already done, 2 failed" in second.stdout
    from funcnet.study import load_results

    rows = load_results(out)
    assert len(rows) == 2 * 3 and set(rows["delay"]) == {5, 10}
    document = json.loads((out / "study.json").read_text())
    assert document["provenance"]["command"]  # the command line is kept

    report = runner.invoke(app, ["report", str(out), "--out", str(tmp_path / "report")])
    assert report.exit_code == 0, report.output
    index = tmp_path / "report" / "index.html"
    assert report.stdout.strip() == f"report: {index}" and index.is_file()
    _assert_one_error_line(runner.invoke(app, ["report", str(tmp_path / "nothing")]), "nothing")

    study.write_text(study.read_text() + "mux = 1\n")
    _assert_one_error_line(runner.invoke(app, arguments), str(study), "mux")


def test_study_on_a_local_cluster_and_bad_schedulers(trial: Path, tmp_path: Path) -> None:
    study = tmp_path / "study.toml"
    study.write_text(
        f'signals = ["RP", "AP"]\n[recordings]\npaths = ["{trial}"]\n'
        '[[windows]]\nkind = "range"\nstart = 0.5\nstop = 1.1\n'
    )
    out = tmp_path / "results"
    base = ["study", str(study), "--out", str(out), "--quiet"]
    result = runner.invoke(app, [*base, "--scheduler", "local-cluster", "--workers", "1"])
    assert result.exit_code == 0, result.output
    assert "1 tasks: 1 computed" in result.stdout
    in_process = runner.invoke(
        app, ["study", str(study), "--out", str(tmp_path / "here"), "--workers", "0"]
    )
    assert in_process.exit_code == 0
    from funcnet.study import load_results

    pd.testing.assert_frame_equal(load_results(out), load_results(tmp_path / "here"))
    for scheduler in ("http://127.0.0.1:8786", "tcp://nohost", "local"):
        bad = runner.invoke(app, [*base, "--scheduler", scheduler])
        _assert_one_error_line(bad, "scheduler", scheduler)


@pytest.fixture
def tiny_demo(monkeypatch) -> list:
    """The demo on a one-trial plan and a stand-in report builder; its calls are returned."""
    import funcnet.paper.demo
    import funcnet.sim
    from funcnet._io import write_text_atomic
    from funcnet.sim import Trial

    # The whole paper plan takes minutes: the demo's wiring is tested on a one-trial plan.
    monkeypatch.setattr(
        funcnet.sim, "paper_plan", lambda: [Trial("tiny", "main", speed=350, tcp=1.2, step=1)]
    )
    calls = []

    def build_demo_report(plan_dir, out_dir, *, progress=None):
        from funcnet.errors import ThresholdWarning

        calls.append((Path(plan_dir), Path(out_dir), progress))
        # The real analyses warn per trial; the report counts those warnings.
        warnings.warn(ThresholdWarning("eps_xy is not below", problem="eps_order"), stacklevel=1)
        return write_text_atomic(Path(out_dir) / "index.html", "<html></html>")

    monkeypatch.setattr(funcnet.paper.demo, "build_demo_report", build_demo_report)
    return calls


def test_demo_simulates_the_plan_then_writes_the_report(tmp_path: Path, tiny_demo) -> None:
    out = tmp_path / "report"
    result = runner.invoke(app, ["demo", "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    assert (out / "plan" / "tiny.xml").is_file() and (out / "plan" / "manifest.csv").is_file()
    assert tiny_demo == [(out / "plan", out, None)]
    assert result.stdout.strip() == f"report: {out / 'index.html'}"
    assert result.stderr == ""  # the report counts the analyses' warnings


def test_demo_writes_into_out_of_the_current_folder(tmp_path: Path, monkeypatch, tiny_demo) -> None:
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["demo", "--quiet"])
    assert result.exit_code == 0, result.output
    out = (tmp_path / "out").resolve()
    assert (out / "plan" / "tiny.xml").is_file() and (out / "index.html").is_file()
    assert [(p.resolve(), o.resolve(), q) for p, o, q in tiny_demo] == [(out / "plan", out, None)]
    assert sorted(path.name for path in tmp_path.iterdir()) == ["out"]


def test_whole_recording_starts_where_every_signal_has_a_value(real_trace, tmp_path: Path) -> None:
    # In the real trace AP and MP are IPO signals: no value at the first 2 ms tick. A piece of
    # its first motion, with that gap put back at its start:
    import dataclasses

    from funcnet import FunctionalNetwork
    from funcnet.robot import read_trace

    moving = read_trace(real_trace).window(7.0, 7.6)
    data = moving.data.copy()
    data.iloc[0, data.columns.get_indexer(["AP", "MP"])] = float("nan")
    piece = tmp_path / "piece.parquet"
    dataclasses.replace(moving, data=data).to_parquet(piece)
    out = tmp_path / "net.json"
    nodes = "RP,AP,MP,AC"
    result = runner.invoke(app, ["network", str(piece), "--signals", nodes, "--window", "all",
                                 "-o", str(out)])
    assert result.exit_code == 0, result.output
    net = FunctionalNetwork.from_json(out.read_text())
    expected = _library_network(piece, 7.002, 7.6, signals=nodes.split(","))
    pd.testing.assert_frame_equal(net.pairs, expected.pairs)


# --------------------------------------------------------------------------------------------
# a quiet, consistent command line


def test_warnings_are_one_counted_line_and_verbose_lists_them(real_trace) -> None:
    arguments = ["network", str(real_trace), "--window", "7:7.5", "--signals", "RP,AP,AC"]
    quiet = runner.invoke(app, arguments)
    assert quiet.exit_code == 0, quiet.output
    warned = [line for line in quiet.stderr.splitlines() if line.startswith("funcnet: warning")]
    assert len(warned) == 1 and "staircase ×1" in warned[0] and "--verbose" in warned[0]
    loud = runner.invoke(app, [*arguments, "--verbose"])
    listed = [line for line in loud.stderr.splitlines() if line.startswith("funcnet: warning")]
    assert len(listed) >= 2
    # the library's Python spelling is re-spelled as the flag
    assert "--resample" in loud.stderr and "funcnet.robot.resample" not in loud.stderr


def test_unknown_and_repeated_signals_name_the_flag_and_what_can_be_derived(real_trace) -> None:
    result = runner.invoke(app, ["network", str(real_trace), "--signals", "RP,RC,AC"])
    _assert_one_error_line(result, "--signals: RC not in axis7-braking-trace.xml",
                           "derivable:", "FE (RP - AP)", "TORSION (MP - AP)")
    twice = runner.invoke(app, ["network", str(real_trace), "--signals", "RP,AC,RP"])
    _assert_one_error_line(twice, "--signals names RP more than once")


def test_drop_constant_and_a_sized_titled_drawing(trial: Path, tmp_path: Path) -> None:
    from matplotlib.image import imread

    arguments = ["network", str(trial), "--window", "2.5:3.3", "--signals", "RP,AP,RC,AC"]
    refused = runner.invoke(app, [*arguments, "--strict-constant"])
    assert refused.exit_code == 2 and "constant" in refused.stderr
    out = tmp_path / "net.png"
    done = runner.invoke(app, [*arguments, "-o", str(out), "--size", "800x600"])  # the default
    assert done.exit_code == 0, done.output
    said = [line for line in done.stderr.splitlines() if "constant inside the window" in line]
    assert len(said) == 1 and said[0].startswith(f"funcnet: warning: {trial}: ")
    assert "--strict-constant makes it an error" in said[0] and "in 1 of 1 window(s)" in said[0]
    assert imread(out).shape[:2] == (600, 800)
    bad = runner.invoke(app, [*arguments, "-o", str(out), "--size", "big"])
    _assert_one_error_line(bad, "--size must be WIDTHxHEIGHT")


def test_omp_wait_policy_is_the_applications_choice() -> None:
    code = ("import os; before = dict(os.environ); import funcnet, funcnet.cli; "
            "assert dict(os.environ) == before; print('ok')")
    env = {k: v for k, v in __import__("os").environ.items() if k != "OMP_WAIT_POLICY"}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            env=env, check=True)
    assert result.stdout.strip() == "ok"
    source = Path(cli.__file__).read_text(encoding="utf-8")
    main_body = source[source.index("def main() -> None:"):]
    assert 'os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")' in main_body


def test_network_without_a_window_is_one_network_per_phase_of_a_move(trial: Path,
                                                                     tmp_path: Path) -> None:
    from funcnet import FunctionalNetwork
    from funcnet.robot import detect_phases, phase_windows, read_recording

    expected = [w.label for w in phase_windows(detect_phases(read_recording(trial)))]
    result = runner.invoke(app, ["network", str(trial), "-o", str(tmp_path / "net.json")])
    assert result.exit_code == 0, result.output
    files = sorted(tmp_path.glob("net-*.json"))
    assert len(files) == len(expected) >= 3
    labels = {FunctionalNetwork.read(f).label for f in files}
    assert labels == set(expected)
    assert (tmp_path / "net-cruise.json").is_file()


def test_network_without_phases_says_how_to_give_a_window(tmp_path: Path) -> None:
    trace = tmp_path / "no-rp.csv"
    t = np.arange(0, 1, 0.002)
    pd.DataFrame({"time": t, "AP": np.sin(t), "AC": np.cos(3 * t)}).to_csv(trace, index=False)
    result = runner.invoke(app, ["network", str(trace), "--signals", "AP,AC"])
    _assert_one_error_line(result, "no phases can be detected", "--window START:STOP")


def test_network_refuses_a_forecast_over_the_limit_unless_forced(trial: Path, tmp_path: Path,
                                                                 monkeypatch) -> None:
    monkeypatch.setattr(selection, "COST_LIMIT_SECONDS", 1e-6)
    arguments = ["network", str(trial), "--window", "0.5:1.1", "--signals", "RP,AP,AC"]
    refused = runner.invoke(app, arguments)
    _assert_one_error_line(refused, "over a minute or 4 GiB", "--force", "states")
    forced = runner.invoke(app, [*arguments, "--force", "-o", str(tmp_path / "net.json")])
    assert forced.exit_code == 0, forced.output


# --------------------------------------------------------------------------------------------
# evidence


@pytest.fixture(scope="module")
def henon_trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A CSV trace of two coupled Hénon maps (C = 0.6) and independent noise."""
    from funcnet.validation.systems import henon_pair

    x = henon_pair(800, 0.6, seed=1)
    trace = tmp_path_factory.mktemp("henon") / "henon.csv"
    pd.DataFrame({"time": np.arange(len(x)) / 500.0, "X": x[:, 0], "Y": x[:, 1],
                  "N": np.random.default_rng(7).normal(size=len(x))}).to_csv(trace, index=False)
    return trace


def test_network_evidence_writes_the_columns_and_finds_the_coupled_pair(henon_trace, tmp_path):
    from funcnet.network.schema import EVIDENCE_COLUMNS

    out = tmp_path / "pairs.csv"
    arguments = ["network", str(henon_trace), "--signals", "X,Y,N", "--window", "all",
                 "--dim", "2", "--delay", "1", "--evidence", "--resamples", "0", "--seed", "3"]
    result = runner.invoke(app, [*arguments, "-o", str(out)])
    assert result.exit_code == 0, result.output
    pairs = pd.read_csv(out)
    assert set(EVIDENCE_COLUMNS) <= set(pairs.columns)
    by_pair = {frozenset(p): row for p, row in zip(zip(pairs["x"], pairs["y"], strict=True),
                                                    pairs.itertuples(), strict=True)}
    henon = by_pair[frozenset(("X", "Y"))]
    assert bool(henon.coupled) and henon.evidence in ("coupled", "coupled-directed")
    assert henon.coupling_p <= 0.05
    # the same numbers as the library's (K chosen from the number of pairs), same seed
    from funcnet import functional_network

    data = pd.read_csv(henon_trace)[["X", "Y", "N"]]
    library = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, seed=3,
                                 warn=False)
    assert np.allclose(pairs["coupling_p"], library.pairs["coupling_p"])
    assert pairs["surrogates"].tolist() == library.pairs["surrogates"].tolist()
    # printed (piped): the evidence columns too; without --evidence: none
    printed = runner.invoke(app, arguments)
    assert "coupling_p" in printed.stdout.splitlines()[0]
    plain = runner.invoke(app, arguments[:-5])
    assert "coupling_p" not in plain.stdout


def test_network_interval_rule_needs_evidence(henon_trace) -> None:
    base = ["network", str(henon_trace), "--window", "all"]
    _assert_one_error_line(runner.invoke(app, [*base, "--edge-rule", "interval"]),
                           "--edge-rule interval needs --evidence")
    _assert_one_error_line(runner.invoke(app, [*base, "--edge-rule", "mu"]), "--edge-rule")
    _assert_one_error_line(runner.invoke(app, [*base, "--evidence", "--alpha", "1.5"]),
                           "--alpha")
    _assert_one_error_line(
        runner.invoke(app, [*base, "--evidence", "--surrogate-method", "phase"]),
        "--surrogate-method")


def test_network_interval_rule_through_the_command_line(henon_trace, tmp_path) -> None:
    out = tmp_path / "net.json"
    result = runner.invoke(app, ["network", str(henon_trace), "--signals", "X,Y", "--window",
                                 "all", "--dim", "2", "--delay", "1", "--evidence",
                                 "--resamples", "20", "--surrogates", "19", "--edge-rule",
                                 "interval", "-o", str(out)])
    assert result.exit_code == 0, result.output
    from funcnet import FunctionalNetwork

    net = FunctionalNetwork.from_json(out.read_text())
    assert net.evidence["edge_rule"] == "interval" and net.evidence["resamples"] == 20
    assert net.evidence["surrogates"] == 19


def test_network_help_lists_the_evidence_options() -> None:
    result = runner.invoke(app, ["network", "--help"])
    for option in ("--evidence", "--surrogates", "--alpha", "--seed", "--resamples",
                   "--edge-rule", "--surrogate-method"):
        assert option in result.stdout, option



@pytest.mark.parametrize("command", ["backlash", "inspect", "network", "study", "report", "demo",
                                     "simulate"])
def test_help_shows_no_python_types(command: str) -> None:
    result = runner.invoke(app, [command, "--help"])
    assert result.exit_code == 0
    assert "list[" not in result.stdout and "Path]" not in result.stdout
    if command in ("backlash", "inspect"):
        assert "TRACE <path>..." in result.stdout


def test_inspect_passes_the_network_options(trial: Path, tmp_path: Path, monkeypatch) -> None:
    import funcnet.inspection.run
    import funcnet.report.inspect
    from funcnet import NetworkParameters

    calls: list[dict] = []

    def recorded(*paths, **keywords):
        calls.append(keywords)
        return "inspections"

    def written(inspections, out_dir, **keywords):
        assert inspections == "inspections"  # the page draws what the inspection step gave
        return tmp_path / "index.html"

    monkeypatch.setattr(funcnet.inspection.run, "inspect_files", recorded)
    monkeypatch.setattr(funcnet.report.inspect, "write_inspections", written)
    options = ["--rr", "0.1", "--mu-c", "0.2", "--normalize", "none", "--metric", "chebyshev",
               "--keep-degenerate"]
    result = runner.invoke(app, ["inspect", str(trial), "-o", str(tmp_path), *options])
    assert result.exit_code == 0, result.output
    (keywords,) = calls
    assert keywords["parameters"] == NetworkParameters(
        rr=0.1, mu_c=0.2, normalize=None, metric="supremum", degenerate="keep"
    )
    plain = runner.invoke(app, ["inspect", str(trial), "-o", str(tmp_path)])
    assert plain.exit_code == 0 and calls[1]["parameters"] == NetworkParameters()
    # A bad value is one line naming the option, before any trace is read.
    _assert_one_error_line(runner.invoke(app, ["inspect", "missing.xml", "--dim", "0"]),
                           "--dim must be >= 1, got 0")
    assert len(calls) == 2


def test_the_staircase_warning_has_one_wording(real_trace: Path) -> None:
    # The library's warning, the study's summary and the command line's line say the same.
    import warnings

    from funcnet import window_networks
    from funcnet.errors import StaircaseWarning
    from funcnet.robot import read_recording, span_window
    from funcnet.study.tasks import task_warnings

    recording = read_recording(real_trace, signals=["RP", "AP", "MP"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        networks = window_networks(recording, [span_window(7.0, 7.3)], signals=["RP", "AP"])
    (library,) = [str(w.message) for w in caught if isinstance(w.message, StaircaseWarning)]
    assert library.startswith(f"{real_trace}: AP change at most every 4 ms but are analysed "
                              "on the 2 ms grid (staircases)")
    found = {p: m for p, _, m in task_warnings(networks, recording, ["RP", "AP"], str(real_trace))}
    assert found["staircase"] == library
    cli_line = library.replace("funcnet.robot.resample decimates or interpolates them",
                               "--resample decimate or --resample interpolate brings them "
                               "onto one grid")
    for command in ("network", "stability"):
        arguments = [command, str(real_trace), "--window", "7:7.3", "--signals", "RP,AP",
                     "--verbose"]
        if command == "stability":
            arguments += ["--vary", "mu=0.1"]
        result = runner.invoke(app, arguments)
        assert result.exit_code == 0, result.output
        assert f"funcnet: warning: {cli_line}" in result.stderr.splitlines(), result.stderr


@pytest.mark.parametrize("module", ["funcnet", "funcnet.cli"])
def test_python_m_runs_the_command_line(module: str) -> None:
    import funcnet

    result = subprocess.run([sys.executable, "-m", module, "--version"], capture_output=True,
                            text=True, timeout=120, check=False)
    assert (result.returncode, result.stdout) == (0, f"funcnet {funcnet.__version__}\n")
