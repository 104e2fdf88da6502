"""One functional network per window (funcnet.pipeline.window_networks), and its warnings."""

from __future__ import annotations

import ast
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import funcnet.pipeline
from funcnet.errors import (
    ChannelError,
    DegenerateWarning,
    FuncnetWarning,
    ParameterError,
    RecordingWarning,
    SignalError,
    StaircaseWarning,
    ThresholdWarning,
    WindowError,
)
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.parameters import NetworkParameters
from funcnet.pipeline import (
    CONSTANT_POLICIES,
    WindowFailure,
    window_evidence,
    window_networks,
    window_warnings,
)
from funcnet.robot.io.read import read_trace
from funcnet.robot.phases import detect_phases
from funcnet.robot.preprocess import add_derived_signals, resample
from funcnet.robot.recording import Recording, SignalInfo
from funcnet.robot.windows import Window, phase_windows, sliding_windows


@pytest.fixture(scope="module")
def real(real_trace) -> Recording:
    return add_derived_signals(read_trace(real_trace), ["V"])


@pytest.fixture(scope="module")
def phases(real):
    return detect_phases(real)


def _caught(call, *args, **kwargs):
    """The result of ``call`` and the warnings it emitted (test code may catch them)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call(*args, **kwargs)
    return result, caught


# Real signals do not always give eps_XY < eps_X, eps_Y; the network says so, and that is not
# what this test is about.
@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_per_phase_of_the_real_braking_motion(real, phases):
    first_move = phase_windows(phases)[:4]
    with pytest.warns(StaircaseWarning, match=r"AP, MP change at most every 4 ms") as record:
        networks = window_networks(real, first_move)
    staircase = [w.message for w in record if isinstance(w.message, StaircaseWarning)]
    assert staircase[0].signals == ("AP", "MP") and staircase[0].problem == "staircase"
    assert list(networks) == ["early spin-up 1", "late spin-up 1", "cruise 1", "braking 1"]
    for window in first_move:
        network = networks[window.label]
        assert network.label == window.label
        assert network.nodes == ("RP", "AP", "MP", "V", "AC")  # the paper's, RC not recorded
        assert len(network.pairs) == 10
    # The braking network is the network of the braking window cut by hand.
    braking = first_move[-1]
    index = real.data.index
    cut = real.data[(index >= braking.start - 1e-9) & (index < braking.stop - 1e-9)]
    assert len(cut) == round(braking.duration / 0.002)
    expected = functional_network(
        cut[["RP", "AP", "MP", "V", "AC"]], label=braking.label, warn=False
    )
    network = networks[braking.label]
    assert network.nodes == expected.nodes
    pd.testing.assert_frame_equal(network.pairs, expected.pairs)
    pd.testing.assert_frame_equal(network.edges, expected.edges)
    assert network.parameters == expected.parameters == NetworkParameters()
    assert network.n_samples == expected.n_samples == len(cut)
    # ... and the network says where it comes from.
    assert dict(network.window) == {
        "label": "braking 1",
        "start": braking.start,
        "stop": braking.stop,
        "phase": "braking",
        "offset": 0.0,
        "source": real.source,
        "dropped": (),
    }
    assert "axis7-braking-trace.xml" in real.source


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_after_decimation_warn_no_staircase(real, phases):
    coarse = resample(real)
    braking = phase_windows(phases, include=["braking"])[:1]
    with warnings.catch_warnings():
        warnings.simplefilter("error", StaircaseWarning)
        networks = window_networks(coarse, braking, signals=["RP", "AP", "AC"], dim=2, delay=5)
    network = networks["braking 1"]
    assert network.nodes == ("RP", "AP", "AC")
    assert network.parameters.dim == 2 and network.parameters.delay == 5


@pytest.mark.filterwarnings("ignore::funcnet.errors.StaircaseWarning")
def test_window_networks_refuses_bad_windows(real):
    with pytest.raises(WindowError, match=r"axis7-braking-trace.xml: window \[40, 50\) s"):
        window_networks(real, [Window("late", 40.0, 50.0)])
    with pytest.raises(WindowError, match="'AP' has no recorded value"):
        window_networks(real, [Window("start", 0.0, 0.2)], signals=["RP", "AP"])
    with pytest.raises(WindowError, match="occur more than once"):
        window_networks(real, [Window("w", 1.0, 2.0), Window("w", 2.0, 3.0)])
    with pytest.raises(ChannelError, match="'RC'"):
        window_networks(real, [Window("w", 7.0, 8.0)], signals=["RP", "RC"])
    assert np.isnan(real.data.at[0.0, "AP"])


def test_recording_rows_are_the_rows_of_its_window(real):
    """The batched path takes each window's rows from Recording.rows: those Recording.window
    keeps, ticks on and off the grid, and its error for a window outside."""
    times = real.data.index.to_numpy()
    for start, stop in ((7.0, 7.3), (7.0011, 7.3009), (6.9991, 7.2999), (0.0, 0.002)):
        first, last = real.rows(start, stop)
        kept = real.window(start, stop).data.index.to_numpy()
        assert kept.tolist() == times[first:last].tolist()
        assert ((kept >= start - 1e-6) & (kept < stop)).all()
    with pytest.raises(WindowError, match=r"window \[40, 50\) s is not inside"):
        real.rows(40.0, 50.0)


# --------------------------------------------------------------------------------------------
# a small synthetic recording: RP and AP move throughout, AC is constant before 1 s


@pytest.fixture(scope="module")
def synthetic() -> Recording:
    t = np.arange(0, 3, 0.002)
    data = pd.DataFrame(
        {
            "RP": np.sin(5 * t),
            "AP": np.sin(5 * t - 0.3),
            "AC": np.where(t < 1, 0.25, np.cos(7 * t)),
        },
        index=pd.Index(t, name="time"),
    )
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    return Recording(data, {}, info, source="/data/synthetic.csv", sample_period=0.002)


@pytest.fixture(scope="module")
def quantized() -> Recording:
    """AC is quantized (too few distinct states) before 1.5 s, AP after."""
    t = np.arange(0, 3, 0.002)
    ap, ac = np.sin(5 * t - 0.3), np.cos(7 * t)
    data = pd.DataFrame(
        {
            "RP": np.sin(5 * t),
            "AP": np.where(t >= 1.5, np.round(ap), ap),
            "AC": np.where(t < 1.5, np.round(ac), ac),
        },
        index=pd.Index(t, name="time"),
    )
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    return Recording(data, {}, info, source="q.csv", sample_period=0.002)


STILL = Window("still", 0.2, 0.8, phase="standstill")
MOVING = [Window(f"w{k}", 1.0 + 0.3 * k, 1.6 + 0.3 * k, phase="cruise") for k in range(4)]
QUANTIZED = [Window("a", 0.2, 0.8), Window("b", 1.6, 2.2), Window("c", 0.9, 1.4)]


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_record_their_window_and_survive_json(synthetic):
    networks = window_networks(synthetic, [STILL, *MOVING], signals=["RP", "AP"], delay=5)
    for window in (STILL, *MOVING):
        network = networks[window.label]
        assert network.window["label"] == window.label
        assert network.window["start"] == window.start
        assert network.window["stop"] == window.stop
        assert network.window["phase"] == window.phase
        assert network.window["source"] == "/data/synthetic.csv"
        assert tuple(network.window["dropped"]) == ()
        assert network.n_samples == round(window.duration / 0.002)
        again = FunctionalNetwork.from_json(network.to_json())
        assert again == network
        assert again.window["start"] == window.start


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_window_evidence_equals_each_windows_network_computed_with_evidence(synthetic):
    windows = [STILL, *MOVING]
    plain = window_networks(synthetic, windows, signals=["RP", "AP"], delay=5)
    found = window_evidence(synthetic, plain, windows, surrogates=19, resamples=20, seed=3)
    for window in windows:
        part = synthetic.window(window.start, window.stop).data[["RP", "AP"]]
        direct = functional_network(part, delay=5, label=window.label, warn=False,
                                    evidence=True, surrogates=19, resamples=20, seed=3)
        got = found[window.label]
        assert got.window == plain[window.label].window  # the window's record is kept
        assert got.pairs.equals(direct.pairs) and got.edges.equals(direct.edges)
        assert got.evidence == direct.evidence and got.label == window.label


# 25 samples, dim 3, delay 1: 23 states, enough for the network; the smaller subsamples of the
# asymmetry intervals keep one block of ceil(sqrt(23)) = 5 states, fewer than an embedding needs.
SHORT = Window("short", 2.0, 2.05, phase="braking")


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_collect_leaves_out_a_window_without_network_and_says_why(synthetic):
    windows = [STILL, MOVING[0], SHORT]  # AC is constant in STILL: strict, no network there
    found = window_networks(synthetic, windows, constant="error", errors="collect", dim=3,
                            delay=1)
    assert list(found) == ["w0", "short"]
    with pytest.raises(SignalError) as raised:  # the error the raising path gives that window
        window_networks(synthetic, [STILL], constant="error", dim=3, delay=1)
    assert found.failures == (WindowFailure("still", "network", str(raised.value)),)
    # the windows that have a network have the one each gets alone
    for window in (MOVING[0], SHORT):
        alone = window_networks(synthetic, [window], dim=3, delay=1)[window.label]
        assert found[window.label] == alone
    assert window_networks(synthetic, [MOVING[0]], dim=3, delay=1).failures == ()
    with pytest.raises(ParameterError, match="errors must be one of raise, collect"):
        window_networks(synthetic, windows, errors="ignore")
    with pytest.raises(ParameterError, match="dim"):  # the call's own errors are raised
        window_networks(synthetic, windows, errors="collect", dim=0)


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_collect_leaves_out_the_intervals_of_a_window_too_short_for_them(synthetic):
    windows = [MOVING[0], SHORT]
    plain = window_networks(synthetic, windows, dim=3, delay=1)
    # every pair's intervals (an untestable pair's are drawn only when asked for)
    settings = {"surrogates": 19, "resamples": 20, "seed": 3, "intervals": "all"}
    # the network works, its evidence does not: the intervals' subsamples are too short
    with pytest.raises(SignalError, match=r"M >= 7 states.*got shape \(5, 3\)"):
        window_evidence(synthetic, plain, windows, **settings)
    found = window_evidence(synthetic, plain, windows, errors="collect", **settings)
    [failure] = found.failures
    assert (failure.window, failure.part) == ("short", "intervals")
    assert failure.message.startswith("/data/synthetic.csv: window 'short' [2, 2.05) s: ")
    assert "got shape (5, 3)" in failure.message
    # the long window: its full evidence, as if computed alone
    whole = window_evidence(synthetic, {"w0": plain["w0"]}, [MOVING[0]], **settings)["w0"]
    assert found["w0"] == whole
    # the short one: the coupling test without the intervals, as functional_network gives it
    part = synthetic.window(SHORT.start, SHORT.stop).data
    direct = functional_network(part, dim=3, delay=1, label="short", warn=False, evidence=True,
                                surrogates=19, resamples=0, seed=3)
    short = found["short"]
    assert short.pairs.equals(direct.pairs) and short.edges.equals(direct.edges)
    assert short.pairs["c_diff_low"].isna().all() and "coupling_p" in short.pairs
    assert short.evidence is not None and short.evidence["resamples"] == 0
    assert short.window == plain["short"].window
    # a bad setting is the caller's: raised before any window, not collected
    with pytest.raises(ParameterError, match="alpha"):
        window_evidence(synthetic, plain, windows, errors="collect", alpha=2.0)


def test_errors_inside_a_window_name_file_window_and_span(synthetic):
    with pytest.raises(SignalError) as caught:
        window_networks(synthetic, [MOVING[0], STILL], constant="error")
    # The same class and the original message, after the file, the label and the span.
    with pytest.raises(SignalError) as direct:
        functional_network(synthetic.window(STILL.start, STILL.stop).data, warn=False)
    assert str(caught.value) == f"/data/synthetic.csv: window 'still' [0.2, 0.8) s: {direct.value}"
    assert "signal 'AC' is constant" in str(caught.value)
    # A window too short for the embedding: the error of functional_network, located.
    short = Window("short", 1.0, 1.01)
    with pytest.raises(SignalError, match=r"^/data/synthetic.csv: window 'short' \[1, 1.01\) s: "):
        window_networks(synthetic, [short], delay=10)
    with pytest.raises(SignalError, match=r"window 'w0' .*at least two"):
        window_networks(synthetic, [MOVING[0]], signals=["RP"], constant="drop")


def _flagged(recording: Recording, windows, **overrides) -> dict[str, list[str]]:
    """Problem -> the windows whose own network flags it, each window computed on its own."""
    flagged: dict[str, list[str]] = {}
    for window in windows:
        part = recording.window(window.start, window.stop).data
        pairs = functional_network(part, label=window.label, warn=False, **overrides).pairs
        problems = {
            "eps_order": (~pairs["eps_ordered"]).any(),
            "rate_exceeded": (pairs["rate_exceeded"] & ~pairs["degenerate"]).any(),
            "degenerate": pairs["degenerate"].any(),
        }
        for problem, present in problems.items():
            if present:
                flagged.setdefault(problem, []).append(window.label)
    return flagged


def test_threshold_warnings_once_per_problem_naming_their_windows(synthetic):
    expected = _flagged(synthetic, MOVING, delay=5)
    assert expected and sum(map(len, expected.values())) > len(expected)  # repeats exist
    networks, caught = _caught(window_networks, synthetic, MOVING, delay=5)
    threshold = [w for w in caught if issubclass(w.category, ThresholdWarning)]
    assert sorted(w.message.problem for w in threshold) == sorted(expected)  # one per problem
    for w in threshold:
        concerned = expected[w.message.problem]
        second = str(w.message).splitlines()[-1]
        assert second == (
            f"/data/synthetic.csv: in {len(concerned)} of {len(MOVING)} window(s): "
            + ", ".join(repr(label) for label in concerned)
        )
        assert w.filename == __file__  # points at the caller's line
        assert w.message.window == (concerned[0] if len(concerned) == 1 else None)
        # The pairs of every window that has the problem, each once.
        per_window = [
            x for x in window_warnings(networks) if x.problem == w.message.problem
        ]
        assert [x.window for x in per_window] == concerned
        assert set(w.message.pairs) == {pair for x in per_window for pair in x.pairs}
        assert len(set(w.message.pairs)) == len(w.message.pairs)


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_per_window_warnings_are_those_functional_network_gives(synthetic):
    """window_warnings reads the same flags functional_network warns about, window by window."""
    networks = window_networks(synthetic, MOVING, delay=5)
    ours = {(w.window, w.problem): w for w in window_warnings(networks)}
    for window in MOVING:
        part = synthetic.window(window.start, window.stop).data
        _, caught = _caught(functional_network, part, label=window.label, delay=5)
        theirs = [w.message for w in caught if isinstance(w.message, ThresholdWarning)]
        mine = {key[1]: w for key, w in ours.items() if key[0] == window.label}
        assert {w.problem for w in theirs} == set(mine)
        for w in theirs:
            assert type(w) is type(mine[w.problem])
            assert (w.pairs, w.signals, w.message) == (
                mine[w.problem].pairs, mine[w.problem].signals, mine[w.problem].message
            )
            assert str(mine[w.problem]) == f"{window.label}: {w.message}"


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_constant_signals_dropped_per_window(synthetic):
    windows = [STILL, MOVING[0]]
    with pytest.warns(RecordingWarning) as said:  # the default: dropped, and said once
        networks = window_networks(synthetic, windows)
    [left_out] = [w.message for w in said if isinstance(w.message, RecordingWarning)]
    assert left_out.problem == "constant" and left_out.signals == ("AC",)
    assert str(left_out) == (
        "/data/synthetic.csv: constant inside the window, left out of it (a normalization needs "
        "a range; constant='error' makes it an error): in 1 of 2 window(s): 'still' (AC)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        assert window_networks(synthetic, windows, constant="drop") == networks
    still, moving = networks["still"], networks["w0"]
    assert still.nodes == ("RP", "AP") and tuple(still.window["dropped"]) == ("AC",)
    assert moving.nodes == ("RP", "AP", "AC") and tuple(moving.window["dropped"]) == ()
    # The network without AC is the network of RP and AP alone.
    alone = functional_network(
        synthetic.window(STILL.start, STILL.stop).data[["RP", "AP"]], warn=False
    )
    pd.testing.assert_frame_equal(still.pairs, alone.pairs)
    # Without normalization a constant signal is no error: nothing is dropped.
    unscaled = window_networks(synthetic, [STILL], constant="drop", normalize=None)
    assert unscaled["still"].nodes == ("RP", "AP", "AC")
    assert tuple(unscaled["still"].window["dropped"]) == ()
    with pytest.raises(WindowError, match=r"synthetic.csv: window 'still' .*\['AC'\].*two"):
        window_networks(synthetic, [STILL], signals=["RP", "AC"], constant="drop")
    with pytest.raises(ParameterError, match="constant") as caught:
        window_networks(synthetic, [STILL], constant="ignore")
    assert caught.value.parameter == "constant"
    assert CONSTANT_POLICIES == ("error", "drop")


def test_one_problem_with_other_details_is_one_warning(quantized):
    # Each window's degenerate structure has its own signal: AC in 'a' and 'c', AP in 'b'.
    networks, caught = _caught(window_networks, quantized, QUANTIZED, delay=5)
    per_window = [w for w in window_warnings(networks) if w.problem == "degenerate"]
    assert [(w.window, w.signals) for w in per_window] == [
        ("a", ("AC",)), ("b", ("AP",)), ("c", ("AC",))
    ]
    degenerate = [w.message for w in caught if isinstance(w.message, DegenerateWarning)]
    assert len(degenerate) == 1
    warning = degenerate[0]
    assert isinstance(warning, ThresholdWarning) and warning.problem == "degenerate"
    assert warning.signals == ("AC", "AP") and warning.window is None
    assert set(warning.pairs) == {("RP", "AC"), ("AP", "AC"), ("RP", "AP")}
    first, second = str(warning).splitlines()
    assert "signal(s) AC, AP" in first
    assert second == "q.csv: in 3 of 3 window(s): 'a', 'b', 'c'"


def test_a_window_where_a_signal_barely_moves_gives_a_located_degenerate_warning(quantized):
    windows = [Window("moving", 1.6, 2.2), Window("quantized", 0.2, 0.8)]
    networks, caught = _caught(window_networks, quantized, windows, signals=["RP", "AC"],
                               delay=5)
    degenerate = [w for w in caught if isinstance(w.message, DegenerateWarning)]
    assert len(degenerate) == 1
    warning = degenerate[0].message
    assert warning.problem == "degenerate"
    assert warning.window == "quantized"
    assert warning.signals == ("AC",)
    assert warning.pairs == (("RP", "AC"),)
    assert str(warning).startswith("quantized: ")
    assert degenerate[0].filename == __file__
    assert networks["quantized"].pairs["degenerate"].tolist() == [True]
    assert networks["moving"].pairs["degenerate"].tolist() == [False]
    # Degenerate pairs are not edges by default.
    assert networks["quantized"].edges.empty
    # The warning survives pickling with its data (a process pool sends it back).
    import pickle

    again = pickle.loads(pickle.dumps(warning))
    assert (type(again), again.window, again.pairs, again.signals) == (
        DegenerateWarning, "quantized", (("RP", "AC"),), ("AC",)
    )


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_two_threads_at_once_get_their_own_results(synthetic, quantized):
    jobs = [(synthetic, MOVING), (quantized, QUANTIZED)]
    sequential = [window_networks(rec, windows, delay=5) for rec, windows in jobs]
    barrier = threading.Barrier(2)

    def run(job):
        barrier.wait(timeout=60)  # both calls at once, in two threads
        return window_networks(*job, delay=5)

    with ThreadPoolExecutor(max_workers=2) as pool:
        parallel = list(pool.map(run, jobs))
    for alone, together in zip(sequential, parallel, strict=True):
        assert list(alone) == list(together)
        for label in alone:
            assert alone[label] == together[label]
        # Each call's warnings are its own networks' warnings, the same as alone.
        assert _described(window_warnings(together)) == _described(window_warnings(alone))
    assert _described(window_warnings(parallel[0])) != _described(window_warnings(parallel[1]))


def test_each_of_two_threads_emits_the_warnings_of_its_own_call(synthetic, quantized):
    jobs = [(synthetic, MOVING), (quantized, QUANTIZED)]
    alone = [
        [w.message for w in _caught(window_networks, rec, windows, delay=5)[1]]
        for rec, windows in jobs
    ]
    assert _described(alone[0]) != _described(alone[1])
    barrier = threading.Barrier(2)
    lock = threading.Lock()
    seen: dict[int, list] = {}

    def show(message, category, filename, lineno, file=None, line=None):
        with lock:
            seen.setdefault(threading.get_ident(), []).append(message)

    def run(job):
        barrier.wait(timeout=60)  # both calls at once, in two threads
        window_networks(*job, delay=5)
        return threading.get_ident()

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = show
        with ThreadPoolExecutor(max_workers=2) as pool:
            threads = list(pool.map(run, jobs))
    assert threads[0] != threads[1]
    for thread, expected in zip(threads, alone, strict=True):
        assert _described(seen[thread]) == _described(expected)


def _described(found: list[FuncnetWarning]) -> list[tuple]:
    return [(type(w), w.problem, w.window, w.pairs, w.signals, str(w)) for w in found]


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_parameters_and_overrides(synthetic):
    windows = MOVING[:2]
    by_name = window_networks(synthetic, windows, delay=5, rr=0.1)
    bundled = window_networks(synthetic, windows, parameters=NetworkParameters(delay=5, rr=0.1))
    mixed = window_networks(synthetic, windows, parameters=NetworkParameters(delay=5), rr=0.1)
    for label in by_name:
        assert by_name[label] == bundled[label] == mixed[label]
        assert by_name[label].parameters == NetworkParameters(delay=5, rr=0.1)
    calls = []
    with pytest.raises(ParameterError, match="^rr must be in") as caught:
        window_networks(synthetic, windows, rr=2.0, progress=lambda *a: calls.append(a))
    assert caught.value.parameter == "rr" and calls == []  # refused before any window
    with pytest.raises(ParameterError, match="radius"):
        window_networks(synthetic, windows, radius=0.1)


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_progress_and_any_windows(synthetic):
    calls = []
    windows = sliding_windows(synthetic, 0.6, 0.5, start=1.0, stop=3.0)
    networks = window_networks(synthetic, windows, delay=5, progress=lambda *a: calls.append(a))
    assert list(networks) == ["1.000-1.600 s", "1.500-2.100 s", "2.000-2.600 s"]
    assert calls == [(k + 1, 3, label) for k, label in enumerate(networks)]
    assert all(network.window["phase"] is None for network in networks.values())


def test_the_pipeline_catches_no_warnings():
    """Warnings come from the pairs tables' flags, never from catch_warnings or their text."""
    source = Path(funcnet.pipeline.__file__).read_text(encoding="utf-8")
    tree = ast.parse(source)
    names = {
        node.attr if isinstance(node, ast.Attribute) else node.id
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute | ast.Name)
    }
    assert "catch_warnings" not in names
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import)
                for alias in node.names}
    assert "re" not in imported


def test_per_signal_rates_follow_the_signals_a_window_keeps(synthetic):
    rates = (0.05, 0.06, 0.07)
    networks, caught = _caught(
        window_networks, synthetic, [STILL, MOVING[0]], constant="drop", rr=rates, delay=5
    )
    assert networks["w0"].parameters.rr == rates
    assert networks["still"].parameters.rr == (0.05, 0.06)  # AC dropped, and its rate
    alone = functional_network(
        synthetic.window(STILL.start, STILL.stop).data[["RP", "AP"]], rr=(0.05, 0.06), delay=5,
        warn=False,
    )
    pd.testing.assert_frame_equal(networks["still"].pairs, alone.pairs)
    # The warnings of a window read its pairs with the pair's own rates.
    _, direct = _caught(
        functional_network, synthetic.window(MOVING[0].start, MOVING[0].stop).data,
        rr=rates, delay=5,
    )
    mine = [w for w in window_warnings(networks) if w.window == "w0"]
    theirs = [w.message for w in direct if isinstance(w.message, FuncnetWarning)]
    assert [(type(w), w.problem, w.pairs, w.signals) for w in mine] == [
        (type(w), w.problem, w.pairs, w.signals) for w in theirs
    ]


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_a_window_with_a_constant_signal_leaves_the_others_in_the_batch(synthetic):
    windows = [STILL, *MOVING]  # AC constant in STILL: dropped there, per window
    found = window_networks(synthetic, windows, constant="drop", dim=3, delay=1)
    assert found["still"].window["dropped"] == ("AC",)
    for window in windows:  # each as computed alone (the moving ones through the batch)
        alone = window_networks(synthetic, [window], constant="drop", dim=3, delay=1)
        assert found[window.label] == alone[window.label]
