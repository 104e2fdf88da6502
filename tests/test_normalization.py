"""Tests of funcnet.core.normalization.normalize (section 3.3 min-max, z-score, validation)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st
from hypothesis.extra.numpy import arrays

from funcnet.core.normalization import normalize
from funcnet.errors import ParameterError, SignalError


def test_minmax_per_column_against_closed_form():
    x = np.array([[2.0, -1.0], [4.0, 3.0], [3.0, 1.0], [6.0, -1.0]])
    expected = np.array([[0.0, 0.0], [0.5, 1.0], [0.25, 0.5], [1.0, 0.0]])
    np.testing.assert_array_equal(normalize(x), expected)


def test_minmax_reaches_both_ends_exactly():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(500, 4)) * [1e-6, 1.0, 1e3, 7.0] + [5.0, -2.0, 1e4, 0.0]
    out = normalize(x, "minmax")
    np.testing.assert_array_equal(out.min(axis=0), 0.0)
    np.testing.assert_array_equal(out.max(axis=0), 1.0)
    # Order inside each column is kept.
    np.testing.assert_array_equal(
        np.argsort(out, axis=0, kind="stable"), np.argsort(x, axis=0, kind="stable")
    )


def test_zscore_against_closed_form():
    x = np.array([[1.0, 10.0], [2.0, 10.0], [6.0, 40.0]])
    mean = x.mean(axis=0)
    std = np.sqrt(((x - mean) ** 2).mean(axis=0))  # population std, ddof = 0
    np.testing.assert_allclose(normalize(x, "zscore"), (x - mean) / std, rtol=0, atol=1e-15)
    out = normalize(x, "zscore")
    np.testing.assert_allclose(out.mean(axis=0), 0.0, atol=1e-15)
    np.testing.assert_allclose(out.std(axis=0), 1.0, rtol=1e-14)


def test_none_passes_values_through_as_float64():
    x = np.array([[1, 2], [3, 3]], dtype=np.int32)
    out = normalize(x, None)
    assert out.dtype == np.float64
    np.testing.assert_array_equal(out, x)
    # A constant signal is fine when nothing is scaled.
    np.testing.assert_array_equal(normalize(np.ones(5), None), np.ones(5))


def test_one_dimensional_signal_keeps_its_shape():
    out = normalize([3.0, 1.0, 2.0])
    assert out.shape == (3,)
    np.testing.assert_array_equal(out, [1.0, 0.0, 0.5])


def test_dataframe_keeps_index_and_columns():
    index = pd.Index([0.0, 0.002, 0.004], name="time")
    frame = pd.DataFrame({"RP": [0.0, 1.0, 2.0], "AC": [5.0, -5.0, 0.0]}, index=index)
    out = normalize(frame)
    assert isinstance(out, pd.DataFrame)
    pd.testing.assert_index_equal(out.index, index)
    assert list(out.columns) == ["RP", "AC"]
    np.testing.assert_array_equal(out.to_numpy(), [[0.0, 1.0], [0.5, 0.0], [1.0, 0.5]])


@pytest.mark.parametrize("method", ["minmax", "zscore"])
def test_constant_signal_is_an_error_naming_it(method):
    frame = pd.DataFrame({"RP": [0.0, 1.0, 2.0], "AC": [0.25, 0.25, 0.25]})
    with pytest.raises(SignalError, match=r"signal 'AC' is constant \(value 0.25\)"):
        normalize(frame, method)


def test_constant_signal_named_by_names_argument():
    x = np.column_stack([np.arange(4.0), np.full(4, 7.0)])
    with pytest.raises(SignalError, match="'current'"):
        normalize(x, names=["position", "current"])
    with pytest.raises(SignalError, match="signal '1'"):
        normalize(x)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("method", ["minmax", "zscore", None])
def test_nan_and_inf_are_errors_naming_the_signal_and_sample(bad, method):
    x = np.column_stack([np.arange(6.0), np.arange(6.0)])
    x[4, 1] = bad
    with pytest.raises(SignalError, match=r"signal 'MP' holds NaN or infinite values .*sample 4"):
        normalize(x, method, names=["AP", "MP"])


def test_unknown_method_is_a_parameter_error():
    with pytest.raises(ParameterError, match="normalize must be one of"):
        normalize(np.arange(3.0), "max")


def test_names_of_wrong_length_is_a_parameter_error():
    with pytest.raises(ParameterError, match="names has 1 entries for 2 signal"):
        normalize(np.zeros((3, 2)), names=["a"])


def test_non_numeric_column_is_a_signal_error_naming_it():
    frame = pd.DataFrame({"RP": [0.0, 1.0], "note": ["a", "b"]})
    with pytest.raises(SignalError, match="signal 'note' is not numeric"):
        normalize(frame)
    with pytest.raises(SignalError, match="real numbers"):
        normalize(np.array([["a", "b"], ["c", "d"]]))


def test_empty_and_three_dimensional_input_are_errors():
    with pytest.raises(SignalError, match="empty"):
        normalize(np.zeros((0, 2)))
    with pytest.raises(SignalError, match="1-D or 2-D"):
        normalize(np.zeros((2, 2, 2)))


def test_range_beyond_float64_is_an_error_not_nan():
    with pytest.raises(SignalError, match="range beyond float64"):
        normalize(np.array([-1e308, 1e308, 0.0]), names="huge")


def test_input_is_not_modified():
    x = np.array([[1.0, 2.0], [3.0, 5.0]])
    before = x.copy()
    normalize(x)
    normalize(x, "zscore")
    np.testing.assert_array_equal(x, before)


finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)


@settings(max_examples=60, deadline=None)
@given(
    x=arrays(np.float64, st.integers(2, 40), elements=finite),
    scale=st.floats(min_value=1e-3, max_value=1e3),
    shift=st.floats(min_value=-1e3, max_value=1e3),
)
def test_minmax_is_invariant_under_positive_affine_maps(x, scale, shift):
    if x.max() - x.min() < 1e-3:  # keep the affine image's rounding far below the tolerance
        x = np.append(x, x.min() + 1.0)
    reference = normalize(x)
    np.testing.assert_allclose(normalize(scale * x + shift), reference, rtol=0, atol=1e-6)
    assert reference.min() == 0.0 and reference.max() == 1.0
