"""A network's evidence columns: the reading of :mod:`funcnet.evidence` added to its pairs table.

:func:`add_evidence` adds them to a plain network already computed (one window's network of
:func:`funcnet.pipeline.window_networks`, say) from the data it was computed from; it gives
exactly what ``functional_network(..., evidence=True)`` gives, without computing the measures
again.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Unpack

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError
from funcnet.evidence import (
    EDGE_RULES,
    check_evidence_arguments,
    evidence_readings,
    interval_kind,
    pairwise_evidence,
)
from funcnet.evidence.pairs import PairEvidence
from funcnet.network._inputs import PreparedSignals, prepared_signals
from funcnet.network.rule import edges_from_pairs, kinds_for
from funcnet.network.schema import (
    EVIDENCE_COLUMNS,
    EVIDENCE_DTYPES,
    PAIR_COLUMNS,
    pairs_frame,
)
from funcnet.parameters import EvidenceSettings, NetworkParameters

if TYPE_CHECKING:
    from funcnet.network.functional import FunctionalNetwork

__all__ = ["add_evidence", "check_edge_rule", "check_evidence_settings", "evidence_columns",
           "with_readings"]


def check_edge_rule(edge_rule: Any, evidence: bool) -> None:
    """Raise a :class:`ParameterError` for an unknown ``edge_rule`` or ``"interval"`` without
    evidence.

    Examples
    --------
    >>> check_edge_rule("interval", evidence=True)
    >>> check_edge_rule("interval", evidence=False)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: edge_rule 'interval' needs evidence=True
    """
    if edge_rule not in EDGE_RULES:
        raise ParameterError.of("edge_rule", f"must be one of {', '.join(EDGE_RULES)}; got "
                                f"{edge_rule!r}")
    if edge_rule == "interval" and not evidence:
        raise ParameterError.of("edge_rule", "'interval' needs evidence=True")


def check_evidence_settings(**settings: Unpack[EvidenceSettings]) -> None:
    """Check the evidence keywords of :func:`add_evidence` before any data is read.

    Parameters
    ----------
    **settings
        ``surrogates``, ``alpha``, ``seed``, ``resamples``, ``surrogate_method``,
        ``edge_rule``, ``intervals``; those not given take :func:`add_evidence`'s defaults.

    Raises
    ------
    ParameterError
        The first bad value, as :func:`add_evidence` says it.
    TypeError
        A keyword :func:`add_evidence` does not take.

    Examples
    --------
    >>> check_evidence_settings(alpha=0.01, resamples=0)
    >>> check_evidence_settings(edge_rule="interval", alpha=2.0)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: alpha must be in (0, 1), got 2.0
    """
    bound = inspect.signature(add_evidence).bind(None, None, **settings)
    bound.apply_defaults()
    given = bound.arguments
    check_edge_rule(given["edge_rule"], evidence=True)
    check_evidence_arguments(given["surrogates"], given["alpha"], given["resamples"],
                             given["surrogate_method"], given["intervals"])


def evidence_columns(pairs: pd.DataFrame, prepared: PreparedSignals, p: NetworkParameters, *,
                     surrogates: int | None, alpha: float, seed: int, resamples: int,
                     surrogate_method: str, edge_rule: str, intervals: str = "coupled",
                     tests: Mapping[tuple[str, str], Any] | None = None, step: int = 1,
                     ) -> tuple[pd.DataFrame, dict[str, Any]]:
    """A plain pairs table with the evidence columns, and the settings that made them.

    Under ``edge_rule="interval"`` the kinds follow the interval rule
    (:func:`funcnet.evidence.interval_kind`), and every pair's intervals are drawn (the rule
    reads them), whatever ``intervals``.

    Parameters
    ----------
    pairs : pandas.DataFrame
        The network's plain pairs table (:data:`~funcnet.network.schema.PAIR_COLUMNS`).
    prepared : PreparedSignals
        The nodes' signals the table was computed from.
    p : NetworkParameters
        The network's parameters.
    surrogates, alpha, seed, resamples, surrogate_method, edge_rule, intervals
        As in :func:`funcnet.network.functional_network` (checked by the caller).
    tests : mapping, optional
        The pairs' coupling tests already run (:func:`funcnet.evidence.pairwise_evidence`).
    step : int
        The network's ``state_step``: the evidence reads the states its measures read.

    Returns
    -------
    (pandas.DataFrame, dict)
        The pairs table with the evidence columns, and the network's ``evidence`` settings.
    """
    if edge_rule == "interval":
        intervals = "all"
    # the table's own differences: the measures are not computed again
    observed = {(str(x), str(y)): (float(c), float(t)) for x, y, c, t in zip(
        pairs["x"].tolist(), pairs["y"].tolist(), pairs["c_diff"].tolist(),
        pairs["t_diff"].tolist(), strict=True)}
    found = pairwise_evidence(
        list(prepared.signals), names=list(prepared.names), parameters=p, surrogates=surrogates,
        alpha=alpha, seed=seed, resamples=resamples, surrogate_method=surrogate_method,
        intervals=intervals, observed=observed, tests=tests, step=step,
        auto_eps=_auto_eps(pairs, prepared.names),
    )
    settings = {"surrogates": surrogates, "alpha": float(alpha), "seed": int(seed),
                "resamples": int(resamples), "level": 0.95, "edge_rule": edge_rule,
                "surrogate_method": surrogate_method, "intervals": intervals}
    return _with_evidence(pairs, found, p, edge_rule, float(alpha)), settings


def _auto_eps(pairs: pd.DataFrame, names: Sequence[str]) -> list[float] | None:
    """Each node's recurrence threshold from the pairs table; None if one is not there or not
    a threshold an explicit ``eps`` can be (0: a node whose rate falls on tied zero distances,
    whose rate search is then run again)."""
    found = dict(zip(pairs["y"], pairs["eps_y"], strict=True))
    found.update(zip(pairs["x"], pairs["eps_x"], strict=True))
    eps = [float(found.get(name, math.nan)) for name in names]
    return None if any(not (math.isfinite(e) and e > 0) for e in eps) else eps


def _with_evidence(pairs: pd.DataFrame, found: Mapping[tuple[str, str], PairEvidence],
                   p: NetworkParameters, edge_rule: str, alpha: float) -> pd.DataFrame:
    # the plain columns as the table holds them (no round trip through Python lists)
    columns: dict[str, Any] = {name: pairs[name] for name in PAIR_COLUMNS}
    rows = [found[(x, y)] for x, y in zip(pairs["x"].tolist(), pairs["y"].tolist(),
                                          strict=True)]
    if edge_rule == "interval":
        c_kinds = [interval_kind(e.c_diff, e.c_diff_low, e.c_diff_high, p.mu_clustering)
                   for e in rows]
        t_kinds = [interval_kind(e.t_diff, e.t_diff_low, e.t_diff_high, p.mu_transitivity)
                   for e in rows]
        kinds = kinds_for(pd.DataFrame({"c_kind": c_kinds, "t_kind": t_kinds}), p.measure)
        columns.update(c_kind=c_kinds, t_kind=t_kinds, kind=kinds.tolist())
    tested = {name: [getattr(e, name) for e in rows]
              for name in EVIDENCE_COLUMNS if name not in _READING_COLUMNS}
    kind = columns["kind"] if edge_rule == "interval" else pairs["kind"].tolist()
    columns["evidence"], columns["evidence_reason"] = evidence_readings(
        tested["coupled"], tested["coupling_p"], tested["surrogates"],
        _directed(pairs["direction"].tolist()), kind, alpha)
    for name, values in tested.items():  # each column an array of its dtype
        columns[name] = np.array(values, dtype=EVIDENCE_DTYPES[name])
    return pairs_frame(columns)


def _directed(directions: list[str]) -> list[str]:
    """The ``direction`` column as the readings take it: ``""`` where it is ``"none"``."""
    return ["" if d == "none" else d for d in directions]


#: The evidence columns read from the others (:func:`funcnet.evidence.evidence_readings`).
_READING_COLUMNS = ("evidence", "evidence_reason")


def with_readings(pairs: pd.DataFrame, alpha: float) -> pd.DataFrame:
    """One network's pairs table with its ``evidence`` and ``evidence_reason`` read again.

    For tables written before the ``untestable`` label and the reason existed (a JSON file, a
    study's rows): the labels follow from the columns the test wrote (``coupled``,
    ``coupling_p``, ``surrogates``, ``direction``, ``kind``), exactly as a fresh network's.

    Parameters
    ----------
    pairs : pandas.DataFrame
        The pairs of one network with the evidence columns (``evidence_reason`` may be missing;
        other columns are kept).
    alpha : float
        The level the network's evidence was computed at.

    Returns
    -------
    pandas.DataFrame
        A copy with both columns (``evidence_reason`` right after ``evidence``).

    Examples
    --------
    >>> old = pd.DataFrame({"coupled": [False], "coupling_p": [0.6], "surrogates": [4],
    ...                     "direction": [""], "kind": ["x->y"], "evidence": ["asymmetry-only"]})
    >>> with_readings(old, 0.05)[["evidence", "evidence_reason"]].values.tolist()
    [['untestable', 'K=4 surrogates: smallest p 0.2 > alpha 0.05']]
    """
    labels, reasons = evidence_readings(pairs["coupled"].astype(bool).tolist(),
                                        pairs["coupling_p"].tolist(),
                                        pairs["surrogates"].tolist(),
                                        _directed(pairs["direction"].astype(str).tolist()),
                                        pairs["kind"].astype(str).tolist(), alpha)
    out = pairs.copy()
    out["evidence"] = pd.Series(labels, index=pairs.index, dtype="str")
    reason = pd.Series(reasons, index=pairs.index, dtype="str")
    if "evidence_reason" in out.columns:
        out["evidence_reason"] = reason
    else:
        out.insert(out.columns.get_loc("evidence") + 1, "evidence_reason", reason)
    return out


def add_evidence(network: FunctionalNetwork, data: Any, *, surrogates: int | None = None,
                 alpha: float = 0.05, seed: int = 0, resamples: int = 200,
                 surrogate_method: str = "shift", edge_rule: str = "paper",
                 intervals: str = "coupled",
                 tests: Mapping[tuple[str, str], Any] | None = None) -> FunctionalNetwork:
    """The network with the evidence columns, from the data it was computed from.

    Equal to ``functional_network(data, ..., evidence=True, ...)`` with the network's nodes and
    parameters; its measures are not computed again.

    Parameters
    ----------
    network : FunctionalNetwork
        A plain network (without evidence).
    data : pandas.DataFrame or array_like, shape (N, k)
        The samples the network was computed from: a DataFrame with a column per node (or per
        channel of a multichannel node; other columns are ignored), or, for one-column nodes
        only, an array with one column per node in node order.
    surrogates, alpha, seed, resamples, surrogate_method, edge_rule, intervals
        As in :func:`funcnet.network.functional_network`.
    tests : mapping, optional
        ``{(x, y): DependenceResult or None}`` for every pair: the coupling tests already run
        over a longer span (the whole segment of a robot network cut into parts); none is run
        here (:func:`funcnet.evidence.pairwise_evidence`).

    Returns
    -------
    FunctionalNetwork
        The same nodes, parameters, label and window; the pairs table with the evidence
        columns; under ``edge_rule="interval"`` the kinds and edges of that rule.

    Raises
    ------
    ParameterError
        A bad evidence argument; ``network`` already with evidence; ``data`` with another number
        of samples than the network or without one of its nodes' columns; an array for a
        network with multichannel nodes.
    SignalError
        As :func:`funcnet.network.functional_network` for the data's columns.

    References
    ----------
    docs/validation/evidence.md (the dependence test, the intervals, the readings).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> from funcnet.validation.systems import henon_pair
    >>> data = henon_pair(300, 0.6, seed=0)
    >>> plain = functional_network(data, names=["x", "y"], delay=1, warn=False)
    >>> full = add_evidence(plain, data, surrogates=19, resamples=0)
    >>> full == functional_network(data, names=["x", "y"], delay=1, warn=False, evidence=True,
    ...                            surrogates=19, resamples=0)
    True
    >>> full.pairs.loc[0, ["kind", "direction", "evidence"]].tolist()  # x drives y
    ['x->y', 'x->y', 'coupled-directed']
    """
    check_evidence_settings(surrogates=surrogates, alpha=alpha, resamples=resamples,
                            surrogate_method=surrogate_method, edge_rule=edge_rule,
                            intervals=intervals)
    if network.evidence is not None:
        raise ParameterError.of("network", "already has evidence columns")
    channels = network.channels or {node: (node,) for node in network.nodes}
    if isinstance(data, pd.DataFrame):
        # the network named its columns as str (functional_network), so compare them so
        data = data.rename(columns=str)
        missing = [c for node in network.nodes for c in channels[node] if c not in data.columns]
        if missing:
            raise ParameterError.of("data", f"has no column(s) {missing} of the network's "
                                    f"nodes; it has {list(data.columns)}")
        prepared = prepared_signals(data, None, dict(channels), network.parameters.normalize)
    elif any(len(columns) > 1 for columns in channels.values()):
        raise ParameterError.of("data", "must be a DataFrame with the channel columns of the "
                                "network's multichannel nodes (an array cannot say which "
                                "column is which channel)")
    else:
        prepared = prepared_signals(data, list(network.nodes), None,
                                    network.parameters.normalize)
    if prepared.n_samples != network.n_samples:
        raise ParameterError.of("data", f"has {prepared.n_samples} samples; the network was "
                                f"computed from {network.n_samples}")
    pairs, settings = evidence_columns(
        network.pairs, prepared, network.parameters, surrogates=surrogates, alpha=alpha,
        seed=seed, resamples=resamples, surrogate_method=surrogate_method, edge_rule=edge_rule,
        intervals=intervals, tests=tests, step=network.state_step,
    )
    edges = edges_from_pairs(pairs, degenerate=network.parameters.degenerate)
    return dataclasses.replace(network, pairs=pairs, edges=edges, evidence=settings)
