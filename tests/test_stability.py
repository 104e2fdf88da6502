"""Stability of an edge over a grid of settings: API, figure, command line."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet import NetworkParameters, functional_network
from funcnet.errors import ParameterError, RecordingWarning, SignalError
from funcnet.network import stability as stability_module
from funcnet.network.stability import check_grid, default_grid, edge_stability, fitting_grid

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")


def _signals(n: int = 220, seed: int = 0) -> pd.DataFrame:
    """A rough driver, its smooth response, an unrelated rough signal, a slow sine."""
    rng = np.random.default_rng(seed)
    x = rng.random(n)
    return pd.DataFrame({
        "x": x,
        "y": np.convolve(x, np.ones(5) / 5)[:n],
        "z": rng.random(n),
        "s": np.sin(np.arange(n) / 7.0) + 0.05 * rng.standard_normal(n),
    })


def _kinds(data: pd.DataFrame, p: NetworkParameters, nodes=None) -> list[str]:
    """The brute-force reference: a whole network per setting, degenerate pairs as the policy
    says (no edge under "drop")."""
    pairs = functional_network(data, nodes=nodes, parameters=p, warn=False).pairs
    kinds = pairs["kind"].tolist()
    if p.degenerate == "drop":
        kinds = ["degenerate" if d else k for k, d in zip(kinds, pairs["degenerate"],
                                                           strict=True)]
    return kinds


def _setting(result, row: pd.Series) -> NetworkParameters:
    fields = [c for c in result.settings.columns if c not in ("setting", "varied", "pairs_kept")]
    return result.parameters.replace(**{f: row[f] for f in fields})


# --------------------------------------------------------------------------------------------
# an independent check: one functional_network per setting


def test_default_grid_matches_a_network_per_setting() -> None:
    data = _signals()
    result = edge_stability(data, delay=2)
    base = NetworkParameters(delay=2)
    assert result.parameters == base
    base_kinds = _kinds(data, base)
    assert result.table["kind"].tolist() == base_kinds
    assert len(result.settings) == int(result.table["settings"].iloc[0])
    reference = np.array([_kinds(data, _setting(result, row))
                          for _, row in result.settings.iterrows()]).T
    assert (result.kinds.to_numpy(dtype=object) == reference).all()
    kept = reference == np.array(base_kinds)[:, None]
    np.testing.assert_allclose(result.table["stability"], kept.mean(axis=1))
    assert result.table["kept"].tolist() == kept.sum(axis=1).tolist()
    assert result.settings["pairs_kept"].tolist() == kept.sum(axis=0).tolist()
    # One key at a time: each stability_<key> is over that key's own settings.
    for key in result.grid:
        column = result.table[f"stability_{key.replace('+', '_')}"]
        mine = (result.settings["varied"] == key).to_numpy()
        assert mine.sum() == len(result.grid[key])
        np.testing.assert_allclose(column, kept[:, mine].mean(axis=1))


def test_product_grid_matches_a_network_per_setting() -> None:
    data = _signals(160)
    grid = {"mu": [0.02, 0.05, 0.2], "dim": [2, 3]}
    result = edge_stability(data, delay=1, grid=grid, full=True)
    assert len(result.settings) == 6 and result.full
    base = NetworkParameters(delay=1)
    base_kinds = np.array(_kinds(data, base))
    reference = {(mu, dim): _kinds(data, base.replace(mu=mu, dim=dim))
                 for mu in grid["mu"] for dim in grid["dim"]}
    kept = {key: np.array(kinds) == base_kinds for key, kinds in reference.items()}
    np.testing.assert_allclose(result.table["stability"],
                               np.mean(list(kept.values()), axis=0))
    # The line through the base along each key.
    np.testing.assert_allclose(result.table["stability_mu"],
                               np.mean([kept[(mu, 3)] for mu in grid["mu"]], axis=0))
    np.testing.assert_allclose(result.table["stability_dim"],
                               np.mean([kept[(0.05, dim)] for dim in grid["dim"]], axis=0))


def test_multichannel_nodes_match_a_network_per_setting() -> None:
    data = _signals(150)
    nodes = {"A": ["x", "y"], "B": ["z", "s"]}
    grid = {"rr+cr": [0.1], "metric": ["supremum"]}
    result = edge_stability(data, nodes=nodes, delay=1, grid=grid)
    base = NetworkParameters(delay=1)
    assert result.table["kind"].tolist() == _kinds(data, base, nodes)
    for _, row in result.settings.iterrows():
        assert result.kinds[row["setting"]].tolist() == _kinds(data, _setting(result, row), nodes)


# --------------------------------------------------------------------------------------------
# closed cases


def test_identical_signals_keep_their_kind_for_every_mu() -> None:
    # A signal and its copy: C_diff = T_diff = 0 exactly, bidirectional under any mu >= 0.
    data = _signals(150)
    data["x_copy"] = data["x"]
    result = edge_stability(data, delay=1, grid={"mu": [0.0, 0.001, 0.3, 5.0]})
    row = result.table[(result.table["x"] == "x") & (result.table["y"] == "x_copy")].iloc[0]
    assert row["kind"] == "bidirectional"
    assert row["stability"] == 1.0 and row["stability_mu"] == 1.0 and row["kept"] == 4


def test_a_huge_mu_leaves_no_direction() -> None:
    # Every |diff| <= 1 < mu: each pair is bidirectional there, so only those keep their kind.
    result = edge_stability(_signals(150), delay=1, grid={"mu": [10.0]})
    expected = (result.table["kind"] == "bidirectional").astype(float)
    np.testing.assert_array_equal(result.table["stability"], expected)
    assert set(result.kinds[0]) == {"bidirectional"}
    assert (result.table["kind"] != "bidirectional").any()  # the case is not empty


def test_a_grid_of_the_base_alone_is_stable() -> None:
    result = edge_stability(_signals(150), delay=1, grid={"dim": [3]})
    assert result.table["settings"].tolist() == [1] * 6
    assert (result.table["stability"] == 1.0).all() and (result.table["changed_to"] == "").all()
    assert result.settings["varied"].tolist() == [""]


def test_repeated_settings_count_once() -> None:
    # mu = 0.05 is the base, as is dim = 3: one setting, not two.
    result = edge_stability(_signals(150), delay=1, grid={"mu": [0.05, 0.1], "dim": [3]})
    assert len(result.settings) == 2
    assert result.settings["varied"].tolist() == ["", "mu"]
    # stability_dim: the settings with mu at the base, i.e. the base alone.
    assert (result.table["stability_dim"] == 1.0).all()


def test_mu_only_settings_reuse_the_measures(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = []
    real = stability_module.batch_pairs

    def counted(*args, **kwargs):
        calls.append(kwargs["parameters"])
        return real(*args, **kwargs)

    monkeypatch.setattr(stability_module, "batch_pairs", counted)
    edge_stability(_signals(150), delay=1, grid={"mu": [0.01, 0.1, 0.2], "measure": ["clustering"]})
    assert calls == []  # only the rule changes: the base's numbers serve every setting
    edge_stability(_signals(150), delay=1, grid={"mu": [0.01, 0.1], "rr+cr": [0.1]}, full=True)
    assert len(calls) == 1 and calls[0].rr == calls[0].cr == 0.1


def test_degenerate_pairs_follow_the_policy() -> None:
    # q takes three values: its recurrence threshold is 0, every pair with q is degenerate.
    data = _signals(200)[["x", "z"]].copy()
    data["q"] = np.round(np.sin(np.arange(200) / 9.0))
    grid = {"mu": [0.01, 0.2]}
    dropped = edge_stability(data, delay=1, grid=grid)
    with_q = (dropped.table["x"] == "q") | (dropped.table["y"] == "q")
    assert with_q.sum() == 2
    assert (dropped.table.loc[with_q, "kind"] == "degenerate").all()
    assert (dropped.table.loc[with_q, "degenerate_settings"] == 2).all()
    assert (dropped.table.loc[with_q, "stability"] == 1.0).all()
    kept = edge_stability(data, delay=1, grid=grid, degenerate="keep")
    reference = functional_network(data, delay=1, warn=False).pairs["kind"]
    assert kept.table["kind"].tolist() == reference.tolist()
    assert kept.table["degenerate"].tolist() == with_q.tolist()


# --------------------------------------------------------------------------------------------
# the grid and its errors


def test_default_grid_around_the_paper_settings() -> None:
    grid = default_grid()
    assert grid["mu"] == (0.025, 0.0375, 0.075, 0.1)
    assert grid["rr+cr"] == ((0.025, 0.025), (0.0375, 0.0375), (0.075, 0.075), (0.1, 0.1))
    assert grid["dim"] == (2, 4) and grid["delay"] == (5, 20)
    assert grid["metric"] == ("supremum", "manhattan") and grid["normalize"] == ("zscore",)
    near = default_grid(NetworkParameters(rr=0.6, cr=0.3, dim=1, delay=1, mu_c=0.1))
    assert near["rr+cr"] == ((0.3, 0.15), (0.45, 0.225), (0.9, 0.45))  # 1.2 is no rate
    assert near["dim"] == (2,) and near["delay"] == (2,)
    assert near["mu_c+mu_t"][0] == (0.05, 0.025) and "mu" not in near
    per_signal = default_grid(NetworkParameters(rr=(0.05, 0.1)))
    assert per_signal["rr+cr"][0] == ((0.025, 0.05), 0.025)


@pytest.mark.parametrize(
    ("grid", "needles"),
    [
        ({"radius": [1]}, ["grid key 'radius'", "not a network parameter"]),
        ({"degenerate": ["keep"]}, ["'degenerate'", "how degenerate pairs count"]),
        ({"rr": [0.1, 2.0]}, ["grid 'rr'", "rr must be in (0, 1), got 2.0"]),
        ({"rr+cr": [(0.1, 0.1, 0.1)]}, ["'rr+cr'", "2 values"]),
        ({"metric": ["taxicab"]}, ["grid 'metric'", "metric must be one of"]),
        ({"mu": []}, ["'mu' has no values"]),
        ({"mu": 0.1}, ["'mu' must be a list of values"]),
        ({"rr": [0.1], "rr+cr": [0.2]}, ["field 'rr'", "'rr+cr'"]),
        ({}, ["grid is empty"]),
        ({1: [2]}, ["keys must be field names"]),
    ],
)
def test_bad_grids_are_named(grid, needles) -> None:
    with pytest.raises(ParameterError) as caught:
        edge_stability(_signals(60), delay=1, grid=grid)
    for needle in needles:
        assert needle in str(caught.value)
    with pytest.raises(ParameterError):
        check_grid(grid)


def test_other_errors() -> None:
    with pytest.raises(ParameterError, match="rr must be in"):
        edge_stability(_signals(60), rr=2.0)
    with pytest.raises(ParameterError, match="full must be True or False"):
        edge_stability(_signals(60), full="yes")
    with pytest.raises(ParameterError, match="more than 10000"):
        edge_stability(_signals(60), grid={"mu": list(np.linspace(0, 1, 200)),
                                           "rr": list(np.linspace(0.01, 0.5, 60))}, full=True)
    # A setting whose embedding does not fit the window: the error names the setting.
    with pytest.raises(SignalError, match=r"^setting delay=60: .*too short"):
        edge_stability(_signals(100), delay=1, grid={"delay": [60]})
    with pytest.raises(SignalError, match="at least two signals"):
        edge_stability(_signals(100)[["x"]], delay=1, grid={"mu": [0.1]})


def test_lists_from_toml_become_tuples() -> None:
    assert check_grid({"rr+cr": [[0.1, 0.2]]}) == {"rr+cr": ((0.1, 0.2),)}
    result = edge_stability(_signals(100), delay=1,
                            grid={"rr": [[0.1, 0.1, 0.1, 0.1]]})
    assert result.grid == {"rr": ((0.1, 0.1, 0.1, 0.1),)}


# --------------------------------------------------------------------------------------------
# the figure


def test_the_figure_draws_every_pair_and_key() -> None:
    from funcnet.plot import plot_stability

    result = edge_stability(_signals(150), delay=1, grid={"mu": [0.1], "rr+cr": [0.1]})
    ax = plot_stability(result)
    assert [t.get_text() for t in ax.get_xticklabels()] == ["all", "mu", "rr+cr"]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert labels[0] == f"x–y: {result.table['kind'].iloc[0]}" and len(labels) == 6
    cells = [t for t in ax.texts if (t.get_gid() or "").startswith("stability:")]
    assert len(cells) == 6 * 3
    assert {t.get_gid() for t in cells} >= {"stability:x-y:all", "stability:z-s:rr+cr"}
    values = {t.get_gid(): float(t.get_text()) for t in cells}
    assert values["stability:x-y:all"] == pytest.approx(result.table["stability"].iloc[0],
                                                        abs=0.005)
    sizes = [t.get_fontsize() for t in [*cells, *ax.get_xticklabels(), *ax.get_yticklabels(),
                                        ax.title, ax.xaxis.label, ax.yaxis.label]]
    assert min(sizes) >= 9
    with pytest.raises(ParameterError, match="EdgeStability"):
        plot_stability(pd.DataFrame({"x": [1]}))


# --------------------------------------------------------------------------------------------
# the command line


@pytest.fixture
def trace(tmp_path):
    t = np.arange(300) / 500.0
    rng = np.random.default_rng(1)
    path = tmp_path / "trace.csv"
    pd.DataFrame({
        "time": t,
        "RP": np.sin(2 * np.pi * 1.3 * t) + 0.01 * rng.standard_normal(t.size),
        "AC": np.cos(2 * np.pi * 2.1 * t) + 0.1 * rng.standard_normal(t.size),
        "RC": rng.standard_normal(t.size),
    }).to_csv(path, index=False)
    return path


def test_cli_writes_the_table_and_the_figure(trace, tmp_path) -> None:
    from funcnet.cli import app
    from funcnet.robot import read_recording

    runner = CliRunner()
    out = tmp_path / "stability.csv"
    arguments = ["stability", str(trace), "--signals", "RP,AC,RC", "--window", "all",
                 "--delay", "2", "--vary", "mu=0.02,0.1", "--vary", "rr+cr=0.1"]
    result = runner.invoke(app, [*arguments, "-o", str(out)])
    assert result.exit_code == 0, result.output
    written = pd.read_csv(out, keep_default_na=False)
    recording = read_recording(trace, signals=["RP", "AC", "RC"])
    reference = edge_stability(recording.data[["RP", "AC", "RC"]], delay=2,
                               grid={"mu": [0.02, 0.1], "rr+cr": [0.1]})
    assert written["window"].unique().tolist() == ["whole recording"]
    pd.testing.assert_frame_equal(
        written[list(reference.table.columns)], reference.table, check_dtype=False
    )
    png = tmp_path / "stability.png"
    result = runner.invoke(app, [*arguments, "-o", str(png)])
    assert result.exit_code == 0, result.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    printed = runner.invoke(app, arguments)
    assert printed.exit_code == 0 and "stability_rr_cr" in printed.output


@pytest.mark.parametrize(
    ("option", "message"),
    [
        (["--vary", "mu=-1"], "--vary 'mu': mu must be finite and >= 0"),
        (["--vary", "radius=1"], "--vary key 'radius' is not a network parameter"),
        (["--vary", "dim=two"], "--vary dim: 'two' is not an integer"),
        (["--vary", "mu"], "--vary must be KEY=V1,V2"),
        (["--rr", "2"], "--rr must be in (0, 1), got 2.0"),
        (["--full"], "--full needs --vary"),
        (["-o", "out.txt"], "unknown format"),
    ],
)
def test_cli_bad_values_are_one_line_exit_2(tmp_path, option, message) -> None:
    from funcnet.cli import app

    # Checked before the (missing) trace is read.
    result = CliRunner().invoke(app, ["stability", str(tmp_path / "missing.csv"), *option])
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("funcnet: error: ")
    assert message in lines[0]


def test_cli_constant_signal_is_an_error_or_dropped(trace, tmp_path) -> None:
    from funcnet.cli import app

    data = pd.read_csv(trace)
    data["MP"] = 1.0  # constant in the window; not over the whole recording (the reader's rule)
    data.loc[data.index[-1], "MP"] = 2.0
    data.to_csv(trace, index=False)
    window = f"{data['time'].iloc[0]}:{data['time'].iloc[-1]}"
    arguments = ["stability", str(trace), "--signals", "RP,AC,RC,MP", "--window", window,
                 "--delay", "2", "--vary", "mu=0.1"]
    failed = CliRunner().invoke(app, [*arguments, "--strict-constant"])
    assert failed.exit_code == 2 and "'MP' is constant" in failed.stderr
    out = tmp_path / "dropped.parquet"
    result = CliRunner().invoke(app, [*arguments, "-o", str(out)])  # the default: left out
    assert result.exit_code == 0, result.output
    table = pd.read_parquet(out)
    assert len(table) == 3 and "MP" not in set(table["x"]) | set(table["y"])
    said = [line for line in result.stderr.splitlines() if "constant inside the window" in line]
    assert len(said) == 1 and said[0].startswith(f"funcnet: warning: {trace}: "), said
    assert "in 1 of 1 window(s)" in said[0]
    assert said[0].endswith(" (MP)") and "--strict-constant makes it an error" in said[0]
    again = CliRunner().invoke(app, [*arguments, "--drop-constant", "-o", str(out)])
    assert again.exit_code == 0 and pd.read_parquet(out).equals(table)


@pytest.mark.parametrize("n", [30, 36, 37, 46, 47, 60])
def test_fitting_grid_keeps_exactly_the_values_a_window_can_embed(n) -> None:
    data = _signals(n)
    grid = default_grid()
    fitted, left_out = fitting_grid(grid, None, n)
    # the reference: each value alone, computed, and whether the embedding refuses it
    for key, values in check_grid(grid).items():
        for value in values:
            try:
                edge_stability(data, grid={key: [value]})
            except SignalError as error:
                assert "too short for the embedding" in str(error)
                assert f"{key}={value!r}" in left_out and value not in fitted.get(key, ())
            else:
                assert value in fitted[key] and f"{key}={value!r}" not in left_out
    assert edge_stability(data, grid=fitted).settings.shape[0] == sum(map(len, fitted.values()))


def test_cli_reads_a_short_window_over_the_settings_it_can_embed(tmp_path) -> None:
    """A KUKA phase of a few dozen samples: the settings of a larger embedding are left out
    of its grid (said in one line), the others computed as the library computes them."""
    from conftest import KUKA, REPO
    from funcnet.cli import app
    from funcnet.robot import detect_phases, phase_windows, read_recording

    run, channels = KUKA / "kr300-run-B.mat", REPO / "examples" / "kuka-kr300-channels.toml"
    recording = read_recording(run, channels=channels, axis=1)
    length = {w.label: len(recording.window(w.start, w.stop).data)
              for w in phase_windows(detect_phases(recording))}
    label = min((lab for lab in length if lab.startswith("cruise")), key=length.__getitem__)
    n = length[label]
    fitted, left_out = fitting_grid(None, None, n)
    assert left_out  # shorter than (4 - 1) * 10 + 7 or (3 - 1) * 20 + 7 samples
    out = tmp_path / "short.csv"
    result = CliRunner().invoke(app, ["stability", str(run), "--channels", str(channels),
                                      "--axis", "1", "--phase", label, "-o", str(out)])
    assert result.exit_code == 0, result.output
    said = [line for line in result.stderr.splitlines() if "too short for" in line]
    assert said == [f"funcnet: warning: {run}: settings whose embedding a window is too short "
                    "for ((dim - 1) * delay + 7 samples) left out of its grid: "
                    f"{label!r} ({n} samples: {', '.join(left_out)})"]
    window = next(w for w in phase_windows(detect_phases(recording)) if w.label == label)
    part = recording.window(window.start, window.stop).data[["RP", "AP", "MP", "V", "AC"]]
    expected = edge_stability(part, grid=fitted).table
    table = pd.read_csv(out)
    assert table["settings"].tolist() == expected["settings"].tolist()
    np.testing.assert_array_equal(table["stability"], expected["stability"])


# --------------------------------------------------------------------------------------------
# one rule for a constant signal, and for a missing value, in stability and in the pipeline


def _recording_with(column: np.ndarray):
    """A recording whose MP is ``column`` (not marked as a gap: built directly, as a library
    user may), beside three moving signals."""
    from funcnet.robot import Recording, SignalInfo

    t = np.arange(column.size) / 500.0
    rng = np.random.default_rng(3)
    data = pd.DataFrame({"RP": np.sin(2 * np.pi * 1.3 * t), "AC": rng.standard_normal(t.size),
                         "RC": rng.standard_normal(t.size), "MP": column},
                        index=pd.Index(t, name="time"))
    signals = {name: SignalInfo(name, None, None, 0.0) for name in data}
    return Recording(data, {}, signals, source="made.csv", sample_period=0.002)


def _stability_compute(recording, window):
    from funcnet.cli.network_commands import _compute

    return _compute(recording, [window], ["RP", "AC", "RC", "MP"],
                    NetworkParameters(dim=2, delay=1), {"mu": (0.1,)}, False, Path("made.csv"))


def _pipeline(recording, window):
    from funcnet.pipeline import window_networks

    return window_networks(recording, [window], signals=["RP", "AC", "RC", "MP"], dim=2,
                           delay=1)


@pytest.mark.parametrize("where", ["one", "every but one", "constant but one"])
def test_a_missing_value_is_the_same_error_in_stability_and_the_pipeline(where) -> None:
    from funcnet.errors import WindowError
    from funcnet.robot import Window

    column = np.random.default_rng(4).standard_normal(200)
    if where == "one":
        column[50] = np.nan
    elif where == "every but one":  # before: dropped by stability as constant (NaN > NaN)
        column[1:] = np.nan
    else:  # before: dropped by stability as constant (pandas skips the NaN)
        column[:] = 1.0
        column[50] = np.nan
    recording = _recording_with(column)
    window = Window("w", 0.0, 0.35)
    with pytest.raises(WindowError) as stability:
        _stability_compute(recording, window)
    with pytest.raises(WindowError) as pipeline:
        _pipeline(recording, window)
    for caught in (stability, pipeline):
        assert "signal 'MP' has no recorded value at some of its ticks" in str(caught.value)
    assert str(stability.value).startswith("made.csv: window 'w'")


def test_a_constant_signal_is_left_out_by_both() -> None:
    from funcnet.pipeline import constant_signals
    from funcnet.robot import Window

    column = np.full(200, 2.5)
    column[150:] = 3.0  # constant inside the window only
    recording = _recording_with(column)
    window = Window("w", 0.0, 0.25)
    part = recording.window(0.0, 0.25).data
    assert constant_signals(part, "w") == ("MP",) and np.ptp(part["MP"]) == 0
    with pytest.warns(RecordingWarning, match=r"'w' \(MP\)"):
        frames, _, _ = _stability_compute(recording, window)
    assert "MP" not in set(frames[0]["x"]) | set(frames[0]["y"])
    with pytest.warns(RecordingWarning, match=r"'w' \(MP\)"):
        networks = _pipeline(recording, window)
    assert networks["w"].window["dropped"] == ("MP",)


def test_constant_signals_against_the_range() -> None:
    from funcnet.pipeline import constant_signals

    rng = np.random.default_rng(5)
    part = pd.DataFrame({"a": rng.standard_normal(50), "b": np.full(50, -0.0),
                         "c": np.r_[np.full(49, 1.0), np.nextafter(1.0, 2.0)],
                         "d": np.r_[np.inf, np.ones(49)], "e": np.full(50, 7.0)})
    want = tuple(name for name in part if part[name].max() == part[name].min())
    assert constant_signals(part, "w") == want == ("b", "e")
