"""Stability of an edge: does a pair keep its kind when the settings change around the base?

The paper (section 5.2) names the open limit: there is no criterion for ``mu``, and the rates,
the embedding, the metric and the normalization are choices too. :func:`edge_stability`
computes a network's pairs at its base settings and at every setting of a grid around them,
and reports per pair the fraction of settings that keep the kind it has at the base
(``x->y``, ``y->x``, ``bidirectional``, ``conflict``), overall and per varied field.

**The default grid** (:func:`default_grid`) varies one field at a time around the base
parameters, keeping the others; with the paper's robot settings (section 3.4 and this
project's defaults: ``rr = cr = 0.05``, ``mu = 0.05``, ``m = 3``, ``tau = 10``):

=================  =======================================  ===================================
grid key           values                                   with the paper's settings
=================  =======================================  ===================================
``mu``             ``{0.5, 0.75, 1.5, 2} * mu``             0.025, 0.0375, 0.075, 0.1
``rr+cr``          ``{0.5, 0.75, 1.5, 2} * (rr, cr)``,      0.025 ... 0.1, both rates together
                   both rates scaled together
``dim``            ``m - 1``, ``m + 1`` (``>= 1``)          2, 4
``delay``          ``tau / 2``, ``2 tau`` (``>= 1``)        5, 20
``metric``         the other two metrics                    supremum, manhattan
``normalize``      the other of minmax / zscore             zscore
=================  =======================================  ===================================

Why these values: the factors 0.5-2 span the settings the literature uses around the paper's
0.05 (rates of 1-10 % are common in recurrence analysis, and the paper gives no criterion for
``mu``); the rates move together because the paper sets ``rr = cr`` and section 2.2 asks the
cross threshold to stay below the auto thresholds, which scaling both preserves; one step of the
dimension and a halved or doubled delay are the usual sensitivity checks of a delay embedding;
the three metrics and two normalizations are every choice the package offers besides the
base's. With ``mu_c`` or ``mu_t`` set, the key is ``mu_c+mu_t`` (both scaled). Values equal to
the base, invalid ones (a rate >= 1) and repeats are left out: 15 settings for the defaults.

**A grid of your own** is a mapping key -> values: a key is a field of
:class:`~funcnet.parameters.NetworkParameters` (every one except ``degenerate``, the counting
policy), or several joined by ``+`` (``"rr+cr"``) or given as a tuple, varied together (each
value then a tuple, one entry per field, or one value for all of them). ``full=False``: one key
at a time, the others at the base; ``full=True``: every combination (the product). A setting
that equals another one (or the base) is evaluated once: the counts are over distinct settings.

**Per-field columns.** ``stability_<key>`` (``+`` written ``_``: ``stability_rr_cr``) is the
fraction over the settings in which every *other* key is at its base value: with one key at a
time, that key's settings; with the product, the line through the base along that key (NaN when
the grid's values of the other keys do not include the base's).

**Degenerate pairs** (too few distinct states) follow the base parameters' ``degenerate``
policy. ``"drop"`` (default): a degenerate pair is no edge, so at a setting where a pair is
degenerate its kind counts as ``"degenerate"`` -- a pair that becomes degenerate loses its kind,
and a pair degenerate at the base keeps its "kind" only where it stays degenerate. ``"keep"``:
the pairs table's kind counts whatever the flag. ``degenerate_settings`` counts the settings in
which each pair is degenerate, under either policy.

**Work.** Settings that differ only in the rule's fields (``mu``, ``mu_c``, ``mu_t``,
``measure``) share one computation of the measures: the rule (:mod:`funcnet.network.rule`) is
re-applied to the same ``C_diff`` and ``T_diff``. Every other distinct setting is one pass of
the batched engine (:func:`funcnet.core.batch.batch_pairs`, bit-identical to
:func:`~funcnet.network.functional_network`), or of :func:`functional_network` for nodes of
several columns. The kinds are those of the paper's rule (``edge_rule="paper"``); the
interval rule of the evidence is not varied here.

Length: just over 600 lines; the grid's parsing, its checks and the counting belong together.
"""

from __future__ import annotations

import itertools
import numbers
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Unpack

import numpy as np
import pandas as pd

from funcnet.core.batch import batch_pairs
from funcnet.core.embedding import min_samples
from funcnet.errors import FuncnetError, ParameterError, SignalError
from funcnet.network._inputs import column_names, float_columns, node_groups
from funcnet.network.functional import functional_network
from funcnet.network.rule import pair_kinds
from funcnet.parameters import METRICS, PAIR_FIELDS, NetworkParameters, ParameterOverrides, resolve

__all__ = [
    "EdgeStability", "edge_stability", "default_grid", "check_grid", "fitting_grid",
    "GRID_FIELDS", "DEFAULT_FACTORS",
]

#: The fields a grid may vary: every network parameter except ``degenerate`` (which says how
#: degenerate pairs count, :mod:`funcnet.network.stability`).
GRID_FIELDS: tuple[str, ...] = tuple(n for n in NetworkParameters.names() if n != "degenerate")
#: Factors of ``mu`` and of the rates in the default grid.
DEFAULT_FACTORS: tuple[float, ...] = (0.5, 0.75, 1.5, 2.0)
#: The effective kind of a degenerate pair under ``degenerate="drop"`` (no edge).
DEGENERATE = "degenerate"
# Settings of the product above this are refused (each is a network's worth of work).
_MAX_SETTINGS = 10_000
# Fields the measures depend on; settings equal in these share one computation.
_MEASURE_FIELDS = (*PAIR_FIELDS, "normalize")


@dataclass(frozen=True, eq=False)
class EdgeStability:
    """The stability of each pair's kind over a grid of settings (:func:`edge_stability`).

    Attributes
    ----------
    table : pandas.DataFrame
        One row per pair (as a network's pairs table): ``x``, ``y``, ``kind`` (at the base
        settings; ``"degenerate"`` for a degenerate pair under ``degenerate="drop"``),
        ``degenerate`` (at the base), ``stability`` (fraction of the settings with the base
        kind), ``kept`` (how many), ``settings`` (how many were evaluated),
        ``degenerate_settings``, ``changed_to`` (the most frequent other kind, ``""`` if none),
        then ``stability_<key>`` per grid key.
    settings : pandas.DataFrame
        One row per distinct setting evaluated: ``setting`` (its number, the column of
        :attr:`kinds`), ``varied`` (the keys whose values differ from the base, ``""`` for the
        base itself), one column per field of the grid (its value), ``pairs_kept``.
    kinds : pandas.DataFrame
        The kind of every pair (rows, as :attr:`table`) at every setting (columns
        ``0 .. len(settings) - 1``), degenerate pairs counted as above.
    parameters : NetworkParameters
        The base settings.
    grid : mapping
        Grid key (``"mu"``, ``"rr+cr"``, ...) -> the tuple of its values, as evaluated.
    full : bool
        Whether the grid is the product of its keys (else one key at a time).
    """

    table: pd.DataFrame
    settings: pd.DataFrame
    kinds: pd.DataFrame
    parameters: NetworkParameters
    grid: Mapping[str, tuple[Any, ...]]
    full: bool = False

    def __repr__(self) -> str:
        stable = int((self.table["stability"] == 1.0).sum())
        return (
            f"EdgeStability({len(self.table)} pairs, {len(self.settings)} settings over "
            f"{', '.join(self.grid) or 'nothing'}; {stable} pair(s) keep their kind at every "
            "setting)"
        )


# --------------------------------------------------------------------------------------------
# the grid


def _times(value: float, factor: float) -> float:
    """``value * factor`` to 12 digits: 0.0375, not 0.037500000000000006, in tables."""
    return float(f"{value * factor:.12g}")


def _scaled_rates(p: NetworkParameters, factor: float) -> tuple[Any, float] | None:
    rr = tuple(_times(r, factor) for r in p.rr) if isinstance(p.rr, tuple) else _times(p.rr,
                                                                                         factor)
    rates = [*(rr if isinstance(rr, tuple) else (rr,)), _times(p.cr, factor)]
    if not all(0.0 < r < 1.0 for r in rates):
        return None  # a rate of 1 or more is no rate: left out
    return rr, _times(p.cr, factor)


def default_grid(parameters: NetworkParameters | None = None) -> dict[str, tuple[Any, ...]]:
    """The default grid around ``parameters``: one field at a time (module docstring).

    Parameters
    ----------
    parameters : NetworkParameters, optional
        The base (default: the defaults, the paper's settings).

    Returns
    -------
    dict
        Grid key -> tuple of values; values equal to the base, invalid or repeated are left out.

    Examples
    --------
    >>> grid = default_grid()
    >>> grid["mu"], grid["dim"], grid["delay"], grid["metric"], grid["normalize"]
    ((0.025, 0.0375, 0.075, 0.1), (2, 4), (5, 20), ('supremum', 'manhattan'), ('zscore',))
    >>> grid["rr+cr"][0]
    (0.025, 0.025)
    """
    p = parameters if parameters is not None else NetworkParameters()
    grid: dict[str, list[Any]] = {}
    if p.mu_c is None and p.mu_t is None:
        grid["mu"] = [_times(p.mu, f) for f in DEFAULT_FACTORS]
    else:
        grid["mu_c+mu_t"] = [(_times(p.mu_clustering, f), _times(p.mu_transitivity, f))
                             for f in DEFAULT_FACTORS]
    grid["rr+cr"] = [r for f in DEFAULT_FACTORS if (r := _scaled_rates(p, f)) is not None]
    grid["dim"] = [d for d in (p.dim - 1, p.dim + 1) if d >= 1]
    grid["delay"] = [max(1, p.delay // 2), 2 * p.delay]
    grid["metric"] = [m for m in METRICS if m != p.metric]
    grid["normalize"] = [n for n in ("minmax", "zscore") if n != p.normalize]
    base = {
        "mu": p.mu, "mu_c+mu_t": (p.mu_clustering, p.mu_transitivity), "rr+cr": (p.rr, p.cr),
        "dim": p.dim, "delay": p.delay,
    }
    out: dict[str, tuple[Any, ...]] = {}
    for key, values in grid.items():
        kept: list[Any] = []
        for value in values:
            if value != base.get(key) and value not in kept:
                kept.append(value)
        if kept:
            out[key] = tuple(kept)
    return out


def _key_fields(key: Any) -> tuple[str, tuple[str, ...]]:
    """``(label, fields)`` of a grid key: ``"rr+cr"`` or ``("rr", "cr")`` -> both."""
    if isinstance(key, str):
        fields = tuple(part.strip() for part in key.split("+"))
    elif isinstance(key, tuple) and key and all(isinstance(k, str) for k in key):
        fields = key
    else:
        raise ParameterError.of(
            "grid", f"keys must be field names (or several joined by '+'), got {key!r}"
        )
    for name in fields:
        if name not in GRID_FIELDS:
            why = ("is how degenerate pairs count, not a setting to vary" if name == "degenerate"
                   else f"is not a network parameter ({', '.join(GRID_FIELDS)})")
            raise ParameterError(f"grid key {name!r} {why}", parameter="grid",
                                 detail=f"key {name!r} {why}")
    if len(set(fields)) != len(fields):
        raise ParameterError.of("grid", f"key {key!r} names a field twice")
    return "+".join(fields), fields


def _changes(fields: tuple[str, ...], value: Any, label: str) -> dict[str, Any]:
    """The field -> value changes of one value of a key (a tuple for a joint key)."""
    if len(fields) == 1:
        return {fields[0]: _plain(value)}
    if isinstance(value, (tuple, list)):
        if len(value) != len(fields):
            raise ParameterError.of(
                "grid", f"{label!r}: a value must be one value or {len(fields)} values "
                f"({', '.join(fields)}), got {value!r}"
            )
        return {name: _plain(v) for name, v in zip(fields, value, strict=True)}
    return dict.fromkeys(fields, _plain(value))


def _plain(value: Any) -> Any:
    """Lists (a TOML array, JSON) as tuples; numpy scalars as Python numbers."""
    if isinstance(value, list):
        return tuple(_plain(v) for v in value)
    if isinstance(value, np.generic):
        return value.item()
    return value


def _parse_grid(grid: Any, base: NetworkParameters) -> dict[str, tuple[tuple[str, ...],
                                                                      list[dict[str, Any]]]]:
    """Grid label -> (its fields, the changes of each of its values), every value checked."""
    if grid is None:
        grid = default_grid(base)
    if not isinstance(grid, Mapping):
        raise ParameterError.of(
            "grid", f"must be a mapping field -> values, got {type(grid).__name__}"
        )
    if not grid:
        raise ParameterError.of("grid", "is empty: give at least one field and its values")
    parsed: dict[str, tuple[tuple[str, ...], list[dict[str, Any]]]] = {}
    seen: dict[str, str] = {}
    for key, values in grid.items():
        label, fields = _key_fields(key)
        for name in fields:
            if name in seen:
                raise ParameterError.of(
                    "grid", f"field {name!r} is in the keys {seen[name]!r} and {label!r}"
                )
            seen[name] = label
        if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, np.ndarray)):
            raise ParameterError.of(
                "grid", f"{label!r} must be a list of values, got {values!r}"
            )
        if len(values) == 0:
            raise ParameterError.of("grid", f"{label!r} has no values")
        changes = [_changes(fields, value, label) for value in values]
        for change in changes:
            _setting(base, change, label)  # each value checked before any work
        parsed[label] = (fields, changes)
    return parsed


def check_grid(grid: Mapping[Any, Sequence[Any]] | None,
               parameters: NetworkParameters | None = None) -> dict[str, tuple[Any, ...]]:
    """The grid as :func:`edge_stability` evaluates it, every key and value checked (no data).

    Parameters
    ----------
    grid : mapping or None
        As :func:`edge_stability`'s ``grid``; None: :func:`default_grid` of ``parameters``.
    parameters : NetworkParameters, optional
        The base (default: the defaults).

    Returns
    -------
    dict
        Key (fields joined by ``+``) -> tuple of values.

    Raises
    ------
    ParameterError
        As :func:`edge_stability` for the grid.

    Examples
    --------
    >>> check_grid({("rr", "cr"): [0.1], "mu": [0.1, 0.2]})
    {'rr+cr': ((0.1, 0.1),), 'mu': (0.1, 0.2)}
    >>> check_grid({"radius": [0.1]})
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: grid key 'radius' is not a network parameter (dim, delay, rr, \
cr, eps, metric, rule, theiler, mu, mu_c, mu_t, normalize, measure)
    """
    base = parameters if parameters is not None else NetworkParameters()
    return {label: tuple(_value(change, fields) for change in changes)
            for label, (fields, changes) in _parse_grid(grid, base).items()}


def fitting_grid(grid: Mapping[Any, Sequence[Any]] | None, parameters: NetworkParameters | None,
                 n_samples: int) -> tuple[dict[str, tuple[Any, ...]], tuple[str, ...]]:
    """The grid without the values whose embedding a window of ``n_samples`` cannot hold.

    A value (its key's fields changed, the others at the base) needs ``(dim - 1) * delay + 7``
    samples; one that needs more is left out, and a key left without values too. A short
    window is then read over the settings it can hold, not refused for the others. With
    ``full=True`` each value is checked against the base, not against every combination.

    Parameters
    ----------
    grid : mapping or None
        As :func:`edge_stability`'s ``grid``; None: :func:`default_grid` of ``parameters``.
    parameters : NetworkParameters, optional
        The base (default: the defaults).
    n_samples : int
        The window's length in samples.

    Returns
    -------
    grid : dict
        Key -> the values kept (as :func:`check_grid`); empty when none fits.
    left_out : tuple of str
        Each value left out, as ``"delay=20"``.

    Examples
    --------
    >>> fitting_grid({"delay": [5, 20], "mu": [0.1]}, None, 44)
    ({'delay': (5,), 'mu': (0.1,)}, ('delay=20',))
    """
    base = parameters if parameters is not None else NetworkParameters()
    kept: dict[str, tuple[Any, ...]] = {}
    left_out: list[str] = []
    for label, (fields, changes) in _parse_grid(grid, base).items():
        values = []
        for change in changes:
            setting = base.replace(**change)
            value = _value(change, fields)
            if min_samples(setting.dim, setting.delay) > n_samples:
                left_out.append(f"{label}={value!r}")
            else:
                values.append(value)
        if values:
            kept[label] = tuple(values)
    return kept, tuple(left_out)


def _setting(base: NetworkParameters, changes: Mapping[str, Any], label: str) -> NetworkParameters:
    try:
        return base.replace(**changes)
    except ParameterError as error:
        # `grid 'rr+cr': rr must be in (0, 1), got 2.0`: the key and the field's own message.
        raise ParameterError(f"grid {label!r}: {error}", parameter=error.parameter,
                             detail=error.detail) from None
    except TypeError as error:  # an unhashable or odd value NetworkParameters cannot compare
        raise ParameterError.of("grid", f"{label!r}: bad value ({error})") from None


def _settings(parsed: Mapping[str, tuple[tuple[str, ...], list[dict[str, Any]]]],
              base: NetworkParameters, full: bool) -> list[NetworkParameters]:
    """The distinct settings of the grid, in grid order (one key at a time, or the product)."""
    if full:
        size = int(np.prod([len(changes) for _, changes in parsed.values()], dtype=np.float64))
        if size > _MAX_SETTINGS:
            raise ParameterError.of(
                "grid", f"has {size} settings in full (product) mode, more than {_MAX_SETTINGS}"
            )
        combos = [
            {name: value for change in combo for name, value in change.items()}
            for combo in itertools.product(*(changes for _, changes in parsed.values()))
        ]
    else:
        combos = [change for _, changes in parsed.values() for change in changes]
    found: list[NetworkParameters] = []
    for combo in combos:
        setting = base.replace(**combo)
        if setting not in found:
            found.append(setting)
    return found


# --------------------------------------------------------------------------------------------
# the measures and the kinds


class _Measures:
    """The pairs' ``c_diff``, ``t_diff`` and ``degenerate`` of one set of measure fields."""

    def __init__(self, data: Any, names: Any, nodes: Any) -> None:
        self.data, self.names, self.nodes = data, names, nodes
        columns = column_names(data, names)
        node_names, groups = node_groups(nodes, columns)
        self.node_names = node_names
        self.single = all(len(group) == 1 for group in groups)
        # The batched engine takes plain columns: one per node (no multichannel node).
        self.values = (
            float_columns(data, [g[0] for g in groups], columns) if self.single else None
        )
        self.cache: dict[tuple[Any, ...], pd.DataFrame] = {}

    def base(self, p: NetworkParameters) -> pd.DataFrame:
        """The base setting, through :func:`functional_network` (its checks, its errors)."""
        pairs = functional_network(self.data, names=self.names, nodes=self.nodes, parameters=p,
                                   warn=False).pairs
        table = pairs[["x", "y", "c_diff", "t_diff", "degenerate"]].copy()
        self.cache[_measure_key(p)] = table
        return table

    def of(self, p: NetworkParameters, label: str) -> pd.DataFrame:
        key = _measure_key(p)
        if key not in self.cache:
            try:
                self.cache[key] = self._compute(p)
            except FuncnetError as error:
                text = str(error).removeprefix("window 0: ")
                error.args = (f"setting {label}: {text}",)
                raise
        return self.cache[key]

    def _compute(self, p: NetworkParameters) -> pd.DataFrame:
        if self.values is None:
            return functional_network(self.data, names=self.names, nodes=self.nodes,
                                      parameters=p, warn=False).pairs[
                ["x", "y", "c_diff", "t_diff", "degenerate"]].copy()
        result = batch_pairs(self.values[np.newaxis], names=self.node_names, parameters=p)
        return pd.DataFrame({
            "x": [x for x, _ in result.pairs], "y": [y for _, y in result.pairs],
            "c_diff": result["c_diff"][0], "t_diff": result["t_diff"][0],
            "degenerate": result["degenerate"][0].astype(bool),
        })


def _measure_key(p: NetworkParameters) -> tuple[Any, ...]:
    return tuple(getattr(p, name) for name in _MEASURE_FIELDS)


def _kinds(measures: pd.DataFrame, p: NetworkParameters) -> np.ndarray:
    """Each pair's kind under ``p``'s rule; ``"degenerate"`` for a degenerate pair under
    ``degenerate="drop"`` (it is no edge)."""
    kinds = pair_kinds(measures[["c_diff", "t_diff"]], p)["kind"].to_numpy(dtype=object)
    if p.degenerate == "drop":
        kinds = np.where(measures["degenerate"].to_numpy(dtype=bool), DEGENERATE, kinds)
    return kinds.astype(object)


def _describe(setting: NetworkParameters, base: NetworkParameters,
              fields: Sequence[str]) -> str:
    changed = [f"{name}={getattr(setting, name)!r}" for name in fields
               if getattr(setting, name) != getattr(base, name)]
    return ", ".join(changed) or "the base"


# --------------------------------------------------------------------------------------------
# the function


def edge_stability(
    data: Any,
    *,
    names: Any = None,
    nodes: Mapping[str, str | Sequence[str]] | None = None,
    parameters: NetworkParameters | None = None,
    grid: Mapping[Any, Sequence[Any]] | None = None,
    full: bool = False,
    **overrides: Unpack[ParameterOverrides],
) -> EdgeStability:
    """Per pair, the fraction of a grid of settings that keep the kind it has at the base.

    Parameters
    ----------
    data, names, nodes
        As :func:`funcnet.network.functional_network` (one analysis window).
    parameters : NetworkParameters, optional
        The base settings (default: the defaults, the paper's); ``**overrides`` by name.
    grid : mapping, optional
        Grid key -> sequence of values. A key is a field of
        :class:`~funcnet.parameters.NetworkParameters` (not ``degenerate``), or fields joined
        by ``+`` (``"rr+cr"``) or a tuple of them, varied together. Default:
        :func:`default_grid` of the base (module docstring: ``mu`` and the rates times 0.5,
        0.75, 1.5, 2; ``dim`` +-1; ``delay`` halved and doubled; the other metrics and
        normalization).
    full : bool
        False (default): one key at a time, the others at the base. True: every combination.
    **overrides
        Network parameters by name, applied to ``parameters``.

    Returns
    -------
    EdgeStability
        ``.table`` per pair: ``kind`` at the base, ``stability`` (fraction of the distinct
        settings with that kind), ``kept``, ``settings``, ``degenerate_settings``,
        ``changed_to``, ``stability_<key>`` per key; ``.settings``, ``.kinds``,
        ``.parameters``, ``.grid``.

    Raises
    ------
    ParameterError
        A bad parameter; a grid key that is not a field (or is ``degenerate``), a field in
        two keys, no values, or a value the field does not accept (the message names the key
        and the field); a product of more than 10,000 settings.
    SignalError
        As :func:`functional_network` at the base; at another setting (e.g. a window too short
        for a larger embedding) the message starts with ``setting delay=20:``.

    Notes
    -----
    Degenerate pairs follow the base's ``degenerate`` policy (module docstring): with
    ``"drop"`` a pair degenerate at a setting counts as kind ``"degenerate"`` there.

    References
    ----------
    Section 2.4 (the rule and ``mu``), 3.3-3.4 (normalization, rates, embedding) and 5.2 (no
    criterion for ``mu``) of the paper.

    Examples
    --------
    A rough driver and its smooth response, and an unrelated rough signal:

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(300)
    >>> y = np.convolve(x, np.ones(5) / 5)[:300]
    >>> z = rng.random(300)
    >>> result = edge_stability(np.column_stack([x, y, z]), names=["x", "y", "z"], delay=1)
    >>> result
    EdgeStability(3 pairs, 14 settings over mu, rr+cr, dim, delay, metric, normalize; 2 pair(s) \
keep their kind at every setting)
    >>> result.table[["x", "y", "kind", "stability", "stability_mu"]]
       x  y           kind  stability  stability_mu
    0  x  y           x->y   1.000000           1.0
    1  x  z  bidirectional   0.857143           0.5
    2  y  z           y->x   1.000000           1.0
    >>> edge_stability(np.column_stack([x, y]), delay=1, grid={"rr": [2.0]})
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: grid 'rr': rr must be in (0, 1), got 2.0
    """
    base = resolve(parameters, overrides)
    if not isinstance(full, bool):
        raise ParameterError.of("full", f"must be True or False, got {full!r}")
    parsed = _parse_grid(grid, base)
    settings = _settings(parsed, base, full)
    measures = _Measures(data, names, nodes)
    if len(measures.node_names) < 2:
        raise SignalError(
            f"a functional network needs at least two signals, got {len(measures.node_names)}"
        )
    base_measures = measures.base(base)
    base_kinds = _kinds(base_measures, base)
    fields = [name for fields_, _ in parsed.values() for name in fields_]
    kinds = np.empty((len(base_kinds), len(settings)), dtype=object)
    degenerate_count = np.zeros(len(base_kinds), dtype=np.int64)
    for s, setting in enumerate(settings):
        found = measures.of(setting, _describe(setting, base, fields))
        kinds[:, s] = _kinds(found, setting)
        degenerate_count += found["degenerate"].to_numpy(dtype=bool)
    kept = kinds == base_kinds[:, None]
    table = pd.DataFrame({
        "x": base_measures["x"].to_numpy(dtype=object),
        "y": base_measures["y"].to_numpy(dtype=object),
        "kind": base_kinds,
        "degenerate": base_measures["degenerate"].to_numpy(dtype=bool),
    })
    count = len(settings)
    table["stability"] = kept.mean(axis=1)
    table["kept"] = kept.sum(axis=1).astype(np.int64)
    table["settings"] = np.int64(count)
    table["degenerate_settings"] = degenerate_count
    table["changed_to"] = [_most_common(row[~keep]) for row, keep in zip(kinds, kept,
                                                                         strict=True)]
    at_base = {label: np.array([all(getattr(s, f) == getattr(base, f) for f in key_fields)
                                for s in settings], dtype=bool)
               for label, (key_fields, _) in parsed.items()}
    for label in parsed:
        others = [at_base[other] for other in parsed if other != label]
        line = np.logical_and.reduce(others) if others else np.ones(count, dtype=bool)
        column = f"stability_{label.replace('+', '_')}"
        table[column] = kept[:, line].mean(axis=1) if line.any() else np.nan
    for name in ("x", "y", "kind", "changed_to"):
        table[name] = table[name].astype("str")
    return EdgeStability(
        table=table,
        settings=_settings_table(settings, base, parsed, at_base, kept),
        kinds=pd.DataFrame(kinds, columns=pd.RangeIndex(count)).astype("str"),
        parameters=base,
        grid={label: tuple(_value(change, fields_) for change in changes)
              for label, (fields_, changes) in parsed.items()},
        full=full,
    )


def _most_common(values: np.ndarray) -> str:
    if values.size == 0:
        return ""
    counted = Counter(values.tolist()).most_common()
    # Ties go to the kind named first in a fixed order, so the table does not depend on order.
    top = counted[0][1]
    return str(min((kind for kind, n in counted if n == top),
                   key=lambda kind: _KIND_ORDER.get(kind, len(_KIND_ORDER))))


_KIND_ORDER = {"x->y": 0, "y->x": 1, "bidirectional": 2, "conflict": 3, DEGENERATE: 4}


def _value(change: Mapping[str, Any], fields: tuple[str, ...]) -> Any:
    values = tuple(change[name] for name in fields)
    return values[0] if len(values) == 1 else values


def _settings_table(settings: Sequence[NetworkParameters], base: NetworkParameters,
                    parsed: Mapping[str, tuple[tuple[str, ...], Any]],
                    at_base: Mapping[str, np.ndarray], kept: np.ndarray) -> pd.DataFrame:
    varied = [
        "+".join(label for label in parsed if not at_base[label][s]) for s in range(len(settings))
    ]
    columns: dict[str, Any] = {"setting": np.arange(len(settings), dtype=np.int64),
                               "varied": pd.Series(varied, dtype="str")}
    for fields_, _ in parsed.values():
        for name in fields_:
            values = [getattr(s, name) for s in settings]
            plain = all(isinstance(v, (numbers.Real, str)) for v in values)
            columns[name] = pd.Series(values, dtype=None if plain else object)
    columns["pairs_kept"] = kept.sum(axis=0).astype(np.int64)
    return pd.DataFrame(columns)
