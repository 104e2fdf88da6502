"""Functional networks: one node per signal, edges from the asymmetry of the ISRN (section 2.4).

:func:`functional_network` normalizes each signal over the data it is given -- one analysis
window -- (``normalize="minmax"`` by default, section 3.3), computes the cross measures of every
unordered pair of nodes (:func:`funcnet.core.measures.pairwise_cross_measures`, Eq. 6-10) and
applies
the edge rule of :mod:`funcnet.network.rule` to the pairs table. A node is one signal (a column)
or a group of columns embedded jointly (a multichannel signal).

:class:`FunctionalNetwork` is the result, as data: the nodes, the pairs table (every pair's
numbers and flags, :mod:`funcnet.network.schema`), the edges, the :class:`NetworkParameters` that
made it and the number of samples; its readers and writers are in
:mod:`funcnet.network.readwrite`.
"""

from __future__ import annotations

import html
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Unpack

import numpy as np
import pandas as pd

from funcnet.core.embedding import thinning
from funcnet.core.measures import pairwise_cross_measures
from funcnet.evidence import check_evidence_arguments
from funcnet.network import readwrite
from funcnet.network._inputs import prepared_signals
from funcnet.network.direction import _direction_rows
from funcnet.network.edge_evidence import check_edge_rule, evidence_columns
from funcnet.network.rule import edges_from_pairs, rule_columns
from funcnet.network.schema import PAIR_DTYPES, RESULT_COLUMNS, pairs_frame
from funcnet.parameters import NetworkParameters, ParameterOverrides, resolve

if TYPE_CHECKING:
    import networkx as nx

__all__ = ["FunctionalNetwork", "functional_network"]


@dataclass(frozen=True, eq=False)
class FunctionalNetwork:
    """A functional network: signals as nodes, directed weighted edges from ISRN asymmetry.

    Build it with :func:`functional_network`; it keeps every pair's numbers, not only the graph.

    Attributes
    ----------
    nodes : tuple of str
        Node names, in the order of the input columns (or of the ``nodes`` mapping).
    pairs : pandas.DataFrame
        One row per unordered pair (``x`` before ``y`` in node order), the columns of
        :data:`funcnet.network.schema.PAIR_COLUMNS`: ``c_xy``, ``c_yx``, ``t_xy``, ``t_yx``
        (Eq. 6-9), ``c_diff``, ``t_diff`` (Eq. 10), the thresholds and achieved rates, the flags
        ``eps_ordered``, ``rate_exceeded``, ``degenerate`` (too few distinct states: the pair's
        arrow means nothing) with its ``degenerate_reason``, the per-measure kinds ``c_kind``,
        ``t_kind``, the ``kind`` under the network's measure and the ``weight`` of Eq. 13.
    edges : pandas.DataFrame
        ``source, target, weight, kind, degenerate`` (:func:`funcnet.network.edges_from_pairs`
        under ``parameters.degenerate``): a directed edge points from the inferred driver to
        the driven node; degenerate pairs are no edges unless ``degenerate="keep"``.
    parameters : NetworkParameters
        The parameters that produced the network.
    n_samples : int
        Samples per signal (the window's length).
    label : str or None
        A name for the network (e.g. the analysis window).
    window : mapping or None
        Where the data comes from (e.g. a recording's window: label, start, stop, phase,
        source, dropped signals), as the pipeline records it; JSON-able values.
    channels : mapping or None
        Node name -> its columns, when nodes were given as groups of columns; None when every
        node is the column of its name.
    evidence : mapping or None
        With ``evidence=True``: the settings of the evidence (``surrogates`` asked, ``alpha``,
        ``seed``, ``resamples``, ``level``, ``edge_rule``), and the pairs table has the
        :data:`~funcnet.network.schema.EVIDENCE_COLUMNS`; None otherwise.
    state_step : int
        The measures and the evidence read every ``state_step``-th state (``max_states``).

    Notes
    -----
    Two networks compare equal when every attribute is equal, the tables cell for cell.

    References
    ----------
    Eq. 10 (asymmetry), section 2.4 (edges, ``mu``), Eq. 13 (weights) of the paper.
    """

    nodes: tuple[str, ...]
    pairs: pd.DataFrame
    edges: pd.DataFrame
    parameters: NetworkParameters
    n_samples: int
    label: str | None = None
    window: Mapping[str, Any] | None = None
    channels: Mapping[str, tuple[str, ...]] | None = None
    evidence: Mapping[str, Any] | None = None
    state_step: int = 1

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FunctionalNetwork):
            return NotImplemented
        return (
            self.nodes == other.nodes
            and self.label == other.label
            and self.parameters == other.parameters
            and self.n_samples == other.n_samples
            and self.state_step == other.state_step
            and _plain(self.window) == _plain(other.window)
            and _plain(self.channels) == _plain(other.channels)
            and _plain(self.evidence) == _plain(other.evidence)
            and self.pairs.equals(other.pairs)
            and self.edges.equals(other.edges)
        )

    __hash__ = None  # type: ignore[assignment]  # holds DataFrames

    @classmethod
    def from_pairs(cls, pairs: pd.DataFrame, parameters: NetworkParameters | None = None, *,
                   nodes: Sequence[str] | None = None, label: str | None = None,
                   window: Mapping[str, Any] | None = None) -> FunctionalNetwork:
        """The network of a pairs table, its edges by the edge rule (e.g. a study's rows).

        Parameters
        ----------
        pairs : pandas.DataFrame
            At least ``x``, ``y``, ``kind`` and ``weight``; a ``degenerate`` column holding
            anything but True (missing, or NaN in rows of older results) means not degenerate.
        parameters : NetworkParameters, optional
            The parameters that produced the table (default :class:`NetworkParameters`()); their
            ``degenerate`` policy decides whether degenerate pairs are edges.
        nodes : sequence of str, optional
            The nodes, in order (default the signals of ``x`` and ``y`` in order of appearance).
        label : str, optional
            A name for the network.
        window : mapping, optional
            Where the data comes from (:attr:`window`).

        Returns
        -------
        FunctionalNetwork
            The table as its ``pairs`` (``degenerate`` a boolean column), its edges
            (:func:`funcnet.network.edges_from_pairs`); the table does not record the window's
            length: ``n_samples`` is 0.

        Raises
        ------
        ParameterError
            A column missing.

        References
        ----------
        Section 2.4 (edges) and Eq. 13 (weights) of the paper.

        Examples
        --------
        >>> import pandas as pd
        >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["y->x", "x->y"],
        ...                       "weight": [0.2, 0.4], "degenerate": [False, True]})
        >>> net = FunctionalNetwork.from_pairs(pairs)
        >>> net.nodes, net.edges[["source", "target"]].values.tolist()
        (('A', 'B', 'C'), [['B', 'A']])
        >>> kept = FunctionalNetwork.from_pairs(pairs, NetworkParameters(degenerate="keep"))
        >>> kept.edges["degenerate"].tolist()
        [False, True]
        """
        parameters = NetworkParameters() if parameters is None else parameters
        flags = (pairs["degenerate"].eq(True) if "degenerate" in pairs.columns
                 else pd.Series(False, index=pairs.index))
        pairs = pairs.assign(degenerate=flags.astype(bool))
        nodes = tuple(dict.fromkeys(str(n) for n in [*pairs["x"], *pairs["y"]])
                      if nodes is None else nodes)
        return cls(nodes=nodes, pairs=pairs,
                   edges=edges_from_pairs(pairs, degenerate=parameters.degenerate),
                   parameters=parameters, n_samples=0, label=label, window=window)

    def edges_for(self, measure: str | None = None, *,
                  degenerate: str | None = None) -> pd.DataFrame:
        """Edges of the network under another measure or degenerate policy, at the same ``mu``.

        Parameters
        ----------
        measure : {"both", "clustering", "transitivity"}, optional
            ``"clustering"`` uses ``C_diff`` only, ``"transitivity"`` ``T_diff`` only, ``"both"``
            their intersection (section 2.4); default the network's. Weights stay those of
            Eq. 13.
        degenerate : {"drop", "keep"}, optional
            Leave degenerate pairs out, or keep them as edges flagged ``degenerate``; default
            the network's ``parameters.degenerate``.

        Returns
        -------
        pandas.DataFrame
            Columns ``source, target, weight, kind, degenerate``, as :attr:`edges`.

        Raises
        ------
        ParameterError
            Unknown ``measure`` or ``degenerate``.

        References
        ----------
        Section 2.4 and Eq. 13 of the paper.

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])  # a noisy copy: no arrow
        >>> network = functional_network(data, names=["x", "y"], delay=1)
        >>> network.edges_for("transitivity")
          source target    weight           kind  degenerate
        0      x      y  0.027588  bidirectional       False
        """
        return edges_from_pairs(
            self.pairs,
            measure=self.parameters.measure if measure is None else measure,
            degenerate=self.parameters.degenerate if degenerate is None else degenerate,
        )

    # ----------------------------------------------------------------------------------------
    # readers and writers (funcnet.network.readwrite)

    def to_networkx(self) -> nx.DiGraph:
        """The network as a :class:`networkx.DiGraph` (:func:`readwrite.to_networkx
        <funcnet.network.readwrite.to_networkx>`).

        Returns
        -------
        networkx.DiGraph
            Every node; one arc per directed edge, two per bidirectional one, each with
            ``weight``, ``kind`` and ``degenerate``; graph attributes ``label``, ``parameters``
            (a dict) and ``n_samples``.

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])
        >>> graph = functional_network(data, names=["x", "y"], delay=1).to_networkx()
        >>> sorted(graph.edges(data="kind"))
        [('x', 'y', 'bidirectional'), ('y', 'x', 'bidirectional')]
        """
        return readwrite.to_networkx(self)

    def to_json(self) -> str:
        """Serialize to JSON; :meth:`from_json` restores an equal network, floats bit for bit.

        Returns
        -------
        str

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])
        >>> network = functional_network(data, names=["x", "y"], delay=1, label="copy")
        >>> FunctionalNetwork.from_json(network.to_json()) == network
        True
        """
        return readwrite.to_json(self)

    @classmethod
    def from_json(cls, text: str) -> FunctionalNetwork:
        """Restore a network written by :meth:`to_json`.

        Parameters
        ----------
        text : str
            The JSON document.

        Returns
        -------
        FunctionalNetwork

        Raises
        ------
        ParameterError
            ``text`` is not JSON or not a functional network of a known format version.

        Examples
        --------
        See :meth:`to_json`.
        """
        return cls(**readwrite.fields_from_json(text))

    def write(self, path: str | os.PathLike[str]) -> Path:
        """Write the network atomically, ``*.json`` or ``*.graphml`` (:func:`readwrite.write
        <funcnet.network.readwrite.write>`); :meth:`read` reads both back exactly.

        Parameters
        ----------
        path : path-like

        Returns
        -------
        pathlib.Path
            ``path``.

        Raises
        ------
        ParameterError
            Any other suffix.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])
        >>> network = functional_network(data, names=["x", "y"], delay=1)
        >>> out = network.write(pathlib.Path(tempfile.mkdtemp()) / "copy.graphml")
        >>> import networkx as nx
        >>> sorted(nx.read_graphml(out).nodes), FunctionalNetwork.read(out) == network
        (['x', 'y'], True)
        """
        return readwrite.write(self, path)

    @classmethod
    def read(cls, path: str | os.PathLike[str]) -> FunctionalNetwork:
        """Read a network written by :meth:`write`; an exact round trip.

        Parameters
        ----------
        path : path-like
            A ``*.json`` or ``*.graphml`` file from :meth:`write`.

        Returns
        -------
        FunctionalNetwork

        Raises
        ------
        ParameterError
            Another suffix, or a file that holds no functional network; the message names it.
        FileNotFoundError
            No file at ``path``.

        Examples
        --------
        See :meth:`write`.
        """
        return cls(**readwrite.read_fields(path))

    # ----------------------------------------------------------------------------------------

    def _summary(self) -> str:
        flagged = self.pairs["degenerate"].to_numpy(dtype=bool)
        kinds = self.pairs["kind"][~flagged]
        directed = int(kinds.isin(["x->y", "y->x"]).sum())
        bidirectional = int((kinds == "bidirectional").sum())
        conflicts = int((kinds == "conflict").sum())
        degenerate = f", {int(flagged.sum())} degenerate" if flagged.any() else ""
        if "coupled" in self.pairs.columns:
            degenerate += f"; {int(self.pairs['coupled'].sum())} coupled"
        label = "" if self.label is None else f"{self.label!r}, "
        p = self.parameters
        mu = (
            f"mu={p.mu}" if p.mu_c is None and p.mu_t is None
            else f"mu_c={p.mu_clustering}, mu_t={p.mu_transitivity}"
        )
        return (
            f"FunctionalNetwork({label}{len(self.nodes)} nodes, {directed} directed, "
            f"{bidirectional} bidirectional, {conflicts} conflict{degenerate}; "
            f"measure={p.measure!r}, {mu})"
        )

    def __repr__(self) -> str:
        return self._summary()

    def _repr_html_(self) -> str:
        return f"<p><code>{html.escape(self._summary())}</code></p>" + self.edges.to_html(
            index=False, float_format=lambda value: f"{value:.4f}"
        )


def _plain(value: Any) -> Any:
    """Lists as tuples, recursively (what survives a JSON round trip compares equal)."""
    if isinstance(value, Mapping):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return tuple(_plain(item) for item in value)
    return value


def functional_network(
    data: Any,
    *,
    names: Any = None,
    nodes: Mapping[str, str | Sequence[str]] | None = None,
    parameters: NetworkParameters | None = None,
    label: str | None = None,
    warn: bool = True,
    evidence: bool = False,
    surrogates: int | None = None,
    alpha: float = 0.05,
    seed: int = 0,
    resamples: int = 200,
    surrogate_method: str = "shift",
    edge_rule: str = "paper",
    intervals: str = "coupled",
    steps: Mapping[str, float] | None = None,
    max_states: int | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> FunctionalNetwork:
    """Functional network of simultaneously sampled signals (section 2.3-2.4, 3.4).

    Each column is normalized, each node embedded (a group of columns jointly: each column
    embedded with ``dim``, ``delay`` and the states concatenated) and its recurrence network
    computed once; every unordered pair of nodes (X, Y), X first in node order, gives ``C^XY``,
    ``C^YX``, ``T^XY``, ``T^YX`` (:func:`funcnet.core.measures.pairwise_cross_measures`), the
    differences of Eq. 10, a kind under ``mu_c``/``mu_t`` and the weight of Eq. 13
    (:mod:`funcnet.network.rule`).

    Parameters
    ----------
    data : pandas.DataFrame or array_like, shape (N, k)
        Time on axis 0, one signal per column. A DataFrame's columns (as ``str``) name them.
    names : sequence of str, optional
        Column names; default the DataFrame's columns, else ``"0"``, ``"1"``, ...
    nodes : mapping, optional
        Node name -> a column name or a list of column names (a multichannel node, embedded
        jointly); columns not named are left out. Every node has the same number of columns
        (the states of X and Y share one space in ``CR_XY``, Eq. 3). Default: one node per
        column, named as it.
    parameters : NetworkParameters, optional
        Every parameter (default :class:`NetworkParameters`'s defaults): embedding (``dim``,
        ``delay``), rates (``rr`` one or one per node, ``cr``) or thresholds (``eps``),
        ``metric``, ``rule``, ``theiler``, ``mu``/``mu_c``/``mu_t``, ``normalize`` (per column,
        before the embedding; section 3.3: min-max), ``measure`` and ``degenerate``.
    label : str, optional
        Stored on the network (e.g. the window's name).
    warn : bool
        Emit the threshold warnings of the pairs (:func:`funcnet.core.measures.threshold_warnings`);
        with False, the flags in the pairs table are the only record.
    evidence : bool
        Add the evidence columns (:data:`~funcnet.network.schema.EVIDENCE_COLUMNS`): the
        joint-recurrence dependence test with time-shift surrogates (BH-adjusted across the
        pairs), half-sampling intervals of ``C_diff`` and ``T_diff``, the direction index and
        each pair's reading (:mod:`funcnet.evidence`). Off by default: the plain network is
        unchanged, bit for bit, and as fast.
    surrogates : int, optional
        Surrogates per pair; default enough for a lone discovery among the pairs under BH
        (:func:`funcnet.evidence.default_surrogates`: 99, or ``m / alpha - 1`` for ``m``
        pairs). Short windows hold fewer (the ``surrogates`` column says how many).
    alpha : float
        Level of the coupling and direction decisions.
    seed : int
        Seeds the subsamples; the same seed gives the same table.
    resamples : int
        Resamples for the intervals (subsamples of two sizes, one set per network; 0: no
        intervals, their columns NaN).
    surrogate_method : {"shift", "twin"}
        Surrogates of the dependence test: the non-circular time-shift lattice (default) or
        twin surrogates (:mod:`funcnet.evidence.surrogates`; validity in
        docs/validation/evidence.md).
    edge_rule : {"paper", "interval"}
        ``"paper"`` (default): ``|diff| >= mu`` (section 2.4). ``"interval"`` (needs
        ``evidence=True``): a measure is directed only when its interval excludes 0 and
        ``|diff| >= mu``; ``c_kind``, ``t_kind`` and ``kind`` then follow this rule.
    intervals : {"coupled", "testable", "all"}
        Whose intervals are drawn (the others' are NaN): by default only those of the pairs
        whose coupling test rejects at ``alpha`` (an interval qualifies a coupling; without one
        there is nothing to qualify); ``"testable"`` those whose test can reach ``alpha``
        (known from the window's size before anything is computed); ``"all"`` every pair's. Under
        ``edge_rule="interval"`` every pair's, whatever this says.
    steps : mapping of str to float, optional
        Column name -> the precision it is logged with, in its unit
        (:func:`~funcnet.network.precision.logged_step` of the whole channel, when ``data`` is
        a window of it); a column not named: read from ``data``. The direction shows no
        improvement of a signal its own past predicts to within its step.
    max_states : int, optional
        Most embedded states the measures and the evidence read (their cost grows about as
        the cube of the states): a longer window keeps every ``d``-th state, each embedded at
        the full rate (:func:`funcnet.core.embedding.thinning`; the network's ``state_step``);
        the direction reading keeps every sample. Default: every state.
    **overrides
        Any parameter by name, applied to ``parameters`` (``delay=1``).

    Returns
    -------
    FunctionalNetwork

    Raises
    ------
    ParameterError
        A bad parameter (checked before the data is read; the message names it); ``names`` of
        the wrong length or repeated; ``nodes`` naming an unknown column, a column twice,
        groups of different sizes, or not a mapping.
    SignalError
        Fewer than two nodes; a column not numeric, with NaN/inf, constant under ``"minmax"``
        or ``"zscore"``, or too short for the embedding; the message names it.

    Warns
    -----
    ThresholdWarning
        With ``warn``: ``eps_xy`` not below ``eps_x`` and ``eps_y``, or ties pushing achieved
        rates above their targets, naming the pairs; a :class:`~funcnet.errors.DegenerateWarning`
        for pairs with too few distinct states (no edges unless ``degenerate="keep"``).

    References
    ----------
    Eq. 10 (asymmetry), section 2.4 (edges and ``mu``), Eq. 13 (weights), section 3.4 (rates and
    ``mu`` of the robot study). Direction convention: :mod:`funcnet.network.rule`.

    Examples
    --------
    A rough driver ``x``, its smooth response ``y`` (a moving average: x -> y) and a rough ``z``
    coupled to nothing:

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(300)
    >>> y = np.convolve(x, np.ones(5) / 5)[:300]
    >>> z = rng.random(300)
    >>> network = functional_network(np.column_stack([x, y, z]), names=["x", "y", "z"],
    ...                              delay=1, warn=False)
    >>> network
    FunctionalNetwork(3 nodes, 2 directed, 1 bidirectional, 0 conflict; measure='both', mu=0.05)
    >>> network.edges
      source target    weight           kind  degenerate
    0      x      y  0.317522       directed       False
    1      x      z  0.021947  bidirectional       False
    2      z      y  0.433247       directed       False

    ``z -> y`` has no coupling behind it: the rougher signal looks like the driver (the
    direction guide, docs/guide/direction.md). At rr = cr = 0.05, ``eps_xy`` is rarely below
    ``eps_x`` and ``eps_y`` for signals this different; the pairs table flags it:

    >>> bool(network.pairs["eps_ordered"].all())
    False
    """
    p = resolve(parameters, overrides)
    check_edge_rule(edge_rule, evidence)
    if evidence:
        check_evidence_arguments(surrogates, alpha, resamples, surrogate_method, intervals)
    thinning(1, max_states)  # checked before the data is read
    prepared = prepared_signals(data, names, nodes, p.normalize, steps)
    step = thinning(prepared.n_samples - (p.dim - 1) * p.delay, max_states)
    results = pairwise_cross_measures(list(prepared.signals), names=list(prepared.names),
                                      parameters=p, warn=warn, step=step)
    pairs = _pairs_table(results, p, dict(zip(prepared.names, prepared.signals, strict=True)),
                         dict(zip(prepared.names, prepared.steps, strict=True)))
    settings = None
    if evidence:
        pairs, settings = evidence_columns(
            pairs, prepared, p, surrogates=surrogates, alpha=alpha, seed=seed,
            resamples=resamples, surrogate_method=surrogate_method, edge_rule=edge_rule,
            intervals=intervals, step=step,
        )
    channels = None if nodes is None else {
        name: tuple(prepared.columns[i] for i in group)
        for name, group in zip(prepared.names, prepared.groups, strict=True)
    }
    return FunctionalNetwork(
        nodes=prepared.names,
        pairs=pairs,
        edges=edges_from_pairs(pairs, degenerate=p.degenerate),
        parameters=p,
        n_samples=prepared.n_samples,
        label=None if label is None else str(label),
        channels=channels,
        evidence=settings,
        state_step=step,
    )


def _pairs_table(results: Mapping[tuple[str, str], Any], parameters: NetworkParameters,
                 signals: Mapping[str, Any], steps: Mapping[str, float]) -> pd.DataFrame:
    """The pairs table of pairwise results (keyed by node names), the rule applied and the
    direction read from the nodes' ``signals`` (logged with ``steps``): each column an array
    of its dtype, the table made once."""
    first = [str(x) for x, _ in results]
    second = [str(y) for _, y in results]
    columns: dict[str, Any] = {"x": first, "y": second,
                               **_result_arrays(list(results.values()))}
    columns.update(rule_columns(columns["c_diff"], columns["t_diff"], parameters))
    columns.update(_direction_rows(first, second, columns["degenerate"].tolist(), signals,
                                   parameters, steps=steps))
    return pairs_frame(columns)


def _result_arrays(measures: Sequence[Any]) -> dict[str, np.ndarray]:
    """The :data:`~funcnet.network.schema.RESULT_COLUMNS` of a list of cross measures
    (:class:`~funcnet.core.measures.CrossMeasures`), one array per column in its dtype:
    float64, bool, and str as objects (what the pairs table's columns hold)."""
    return {name: np.array([getattr(r, name) for r in measures],
                           dtype=object if PAIR_DTYPES[name] == "str" else PAIR_DTYPES[name])
            for name in RESULT_COLUMNS}
