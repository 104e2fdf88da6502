"""One bad value, every entry point, one message: each names the parameter as it spells it.

The detail (``must be in (0, 1), got 2.0``) comes from :class:`funcnet.NetworkParameters`, the
one place that checks it; the Python API says ``rr``, a study file ``<file>: [network] rr`` and
the command line ``--rr``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet import NetworkParameters, ParameterError
from funcnet.cli import app

# (parameter, bad value in Python and TOML, the same on the command line)
BAD_VALUES = [
    ("rr", 2.0, "2"),
    ("metric", "cosine", "cosine"),
    ("dim", 0, "0"),
]
IDS = [name for name, _, _ in BAD_VALUES]


def _detail(name: str, value: Any) -> str:
    """What NetworkParameters says about the value, without the parameter's name."""
    with pytest.raises(ParameterError) as caught:
        NetworkParameters(**{name: value})
    assert caught.value.parameter == name and caught.value.detail
    return caught.value.detail


@pytest.fixture(scope="module")
def signals() -> pd.DataFrame:
    t = np.arange(400) / 500.0
    rng = np.random.default_rng(0)
    return pd.DataFrame(
        {
            "RP": np.sin(2 * np.pi * 1.3 * t),
            "AP": np.sin(2 * np.pi * 1.3 * t - 0.2) + 0.01 * rng.normal(size=t.size),
            "AC": np.cos(2 * np.pi * 2.1 * t) + 0.1 * rng.normal(size=t.size),
        },
        index=pd.Index(t, name="time"),
    )


@pytest.fixture(scope="module")
def trace(signals: pd.DataFrame, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small CSV trace (RP, AP, AC) that every entry point can read."""
    path = tmp_path_factory.mktemp("entry") / "trace.csv"
    signals.reset_index().to_csv(path, index=False)
    return path


@pytest.mark.parametrize(("name", "value", "_text"), BAD_VALUES, ids=IDS)
def test_network_parameters(name: str, value: Any, _text: str) -> None:
    with pytest.raises(ParameterError) as caught:
        NetworkParameters(**{name: value})
    assert str(caught.value) == f"{name} {_detail(name, value)}"
    assert caught.value.spelled("--x") == f"--x {_detail(name, value)}"
    with pytest.raises(ParameterError, match=None) as replaced:
        NetworkParameters().replace(**{name: value})
    assert str(replaced.value) == str(caught.value)


@pytest.mark.parametrize(("name", "value", "_text"), BAD_VALUES, ids=IDS)
def test_functional_network(signals: pd.DataFrame, name: str, value: Any, _text: str) -> None:
    from funcnet import functional_network

    with pytest.raises(ParameterError) as caught:
        functional_network(signals, **{name: value})
    assert str(caught.value) == f"{name} {_detail(name, value)}"
    with pytest.raises(ParameterError) as given:
        functional_network(signals, parameters=NetworkParameters(), **{name: value})
    assert str(given.value) == str(caught.value)


@pytest.mark.parametrize(("name", "value", "_text"), BAD_VALUES, ids=IDS)
def test_window_networks(trace: Path, name: str, value: Any, _text: str) -> None:
    from funcnet import window_networks
    from funcnet.robot import read_recording, span_window

    recording = read_recording(trace, signals=["RP", "AP", "AC"])
    with pytest.raises(ParameterError) as caught:
        window_networks(recording, [span_window(0.1, 0.7)], **{name: value})
    assert str(caught.value) == f"{name} {_detail(name, value)}"


@pytest.mark.parametrize(("name", "value", "_text"), BAD_VALUES, ids=IDS)
def test_pair_measures(signals: pd.DataFrame, name: str, value: Any, _text: str) -> None:
    from funcnet import cross_measures
    from funcnet.core.measures import pairwise_cross_measures

    x, y = signals["RP"].to_numpy(), signals["AC"].to_numpy()
    with pytest.raises(ParameterError) as pair:
        cross_measures(x, y, **{name: value})
    assert str(pair.value) == f"{name} {_detail(name, value)}"
    with pytest.raises(ParameterError) as pairs:
        pairwise_cross_measures([x, y], **{name: value})
    assert str(pairs.value) == str(pair.value)


def _toml(value: Any) -> str:
    return f'"{value}"' if isinstance(value, str) else repr(value)


@pytest.mark.parametrize("grid", [False, True], ids=["value", "grid"])
@pytest.mark.parametrize(("name", "value", "_text"), BAD_VALUES, ids=IDS)
def test_study_file(
    trace: Path, tmp_path: Path, name: str, value: Any, _text: str, grid: bool
) -> None:
    from funcnet.errors import StudyError
    from funcnet.study import load_study

    study = (tmp_path / "study.toml").resolve()
    toml_value = _toml(value)
    if grid:  # a list spans a grid: a good value first, the bad one is still named
        toml_value = f"[{_toml(NetworkParameters.defaults()[name])}, {toml_value}]"
    study.write_text(
        f'signals = ["RP", "AP", "AC"]\n[recordings]\npaths = ["{trace}"]\n'
        '[[windows]]\nkind = "range"\nstart = 0.1\nstop = 0.7\n'
        f"[network]\n{name} = {toml_value}\n"
    )
    with pytest.raises(StudyError) as caught:
        load_study(study)
    assert str(caught.value) == f"{study}: [network] {name} {_detail(name, value)}"


@pytest.mark.parametrize(("name", "value", "text"), BAD_VALUES, ids=IDS)
def test_command_line(trace: Path, name: str, value: Any, text: str) -> None:
    result = CliRunner().invoke(app, ["network", str(trace), f"--{name}", text])
    assert result.exit_code == 2, result.output
    assert result.stderr == f"funcnet: error: --{name} {_detail(name, value)}\n"
    assert result.stdout == ""
