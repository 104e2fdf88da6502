"""Functional networks: one node per signal, edges from the asymmetry of the ISRN (section 2.3-2.4).

:func:`functional_network` first normalizes each signal over the data it is given -- one
analysis window -- (``normalize="minmax"`` by default, section 3.3); the measures of
:mod:`funcnet.measures` then use the signals as given.

For every unordered pair of signals (X, Y) the inter-system recurrence network gives the global
cross-clustering ``C^XY``, ``C^YX`` and cross-transitivity ``T^XY``, ``T^YX``
(:func:`funcnet.measures.pairwise_cross_measures`, Eq. 6-9) and their differences
``C_diff = C^XY - C^YX``, ``T_diff = T^XY - T^YX`` (Eq. 10). Each difference becomes an edge kind
with the threshold ``mu`` (section 2.4):

======================  ==============  =========================================================
difference              kind            meaning
======================  ==============  =========================================================
``diff <= -mu``         ``x->y``        X -> Y (the convention of the code the paper used)
``diff >= mu``          ``y->x``        Y -> X
``|diff| < mu``         bidirectional   symmetric coupling **or no coupling at all**
======================  ==============  =========================================================

(With ``mu = 0`` a difference of exactly 0 is bidirectional.) ``measure="both"`` (the default, as
in the code the paper used) intersects the two per-measure graphs: the same direction twice, or a
direction and a bidirectional relation, give that direction; two bidirectional relations give a
bidirectional edge; opposite directions give no edge, recorded as kind ``conflict``. The weight of
every pair is ``w = (|C_diff| + |T_diff|) / 2`` (Eq. 13), whatever the measure.

**Direction convention.** A *negative* difference reads as X -> Y. Section 2.4 of the paper states
both signs; the convention here is that of the code the paper ran, and it is checked by
``tests/test_direction.py`` on identical Henon maps driven one by the other. The asymmetry follows
the relative roughness of the two signals as much as the coupling: the rougher (faster, more
complex) signal tends to look like the driver, coupled or not. Read the README's "Direction"
section before reading an arrow between a smooth position and a rough current.
"""

from __future__ import annotations

import html
import json
import math
import numbers
import operator
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import networkx as nx
import pandas as pd

from funcnet._io import atomic_path, write_text_atomic
from funcnet.errors import ParameterError, SignalError
from funcnet.measures import pairwise_cross_measures
from funcnet.preprocess import _as_float_columns, _check_normalization
from funcnet.preprocess import normalize as normalize_signals
from funcnet.recurrence import _check_int, _check_options, _check_rate

__all__ = [
    "MEASURES",
    "PAIR_KINDS",
    "FunctionalNetwork",
    "functional_network",
    "check_parameters",
    "edge_kind",
    "combine_kinds",
    "edges_from_pairs",
]

MEASURES = ("both", "clustering", "transitivity")
PAIR_KINDS = ("x->y", "y->x", "bidirectional", "conflict")

_MEASURE_COLUMNS = (
    "c_xy",
    "c_yx",
    "t_xy",
    "t_yx",
    "c_diff",
    "t_diff",
    "eps_x",
    "eps_y",
    "eps_xy",
    "rr_x",
    "rr_y",
    "cr",
)
_PAIR_DTYPES = {
    "x": "str",
    "y": "str",
    **dict.fromkeys(_MEASURE_COLUMNS, "float64"),
    "eps_ordered": "bool",
    "rate_exceeded": "bool",
    "degenerate": "bool",
    "c_kind": "str",
    "t_kind": "str",
    "kind": "str",
    "weight": "float64",
}
_EDGE_DTYPES = {"source": "str", "target": "str", "weight": "float64", "kind": "str"}
_JSON_FORMAT = "funcnet.FunctionalNetwork"
_JSON_VERSION = 1


def edge_kind(diff: float, mu: float) -> str:
    """Edge kind of one asymmetry measure under the threshold ``mu`` (section 2.4).

    Parameters
    ----------
    diff : float
        ``C_diff`` or ``T_diff`` of the pair (X, Y) (Eq. 10).
    mu : float
        Bidirectionality threshold, ``>= 0``.

    Returns
    -------
    str
        ``"x->y"`` if ``diff <= -mu``, ``"y->x"`` if ``diff >= mu``, else ``"bidirectional"``
        (which covers "no coupling" too); a difference of exactly 0 is always bidirectional.

    References
    ----------
    Eq. 10 and section 2.4 of the paper; README "Direction" for the sign.

    Examples
    --------
    >>> edge_kind(-0.08, 0.05), edge_kind(0.05, 0.05), edge_kind(0.01, 0.05)
    ('x->y', 'y->x', 'bidirectional')
    """
    if diff < 0 and diff <= -mu:
        return "x->y"
    if diff > 0 and diff >= mu:
        return "y->x"
    return "bidirectional"


def combine_kinds(c_kind: str, t_kind: str) -> str:
    """Intersect the clustering and transitivity kinds of a pair (README method step 7).

    Parameters
    ----------
    c_kind, t_kind : {"x->y", "y->x", "bidirectional"}
        Kinds from ``C_diff`` and ``T_diff`` (:func:`edge_kind`).

    Returns
    -------
    str
        The common kind; a direction where the other measure is bidirectional; ``"conflict"``
        (no edge) for opposite directions.

    Examples
    --------
    >>> combine_kinds("x->y", "bidirectional"), combine_kinds("x->y", "y->x")
    ('x->y', 'conflict')
    """
    if c_kind == t_kind:
        return c_kind
    if c_kind == "bidirectional":
        return t_kind
    if t_kind == "bidirectional":
        return c_kind
    return "conflict"


def _pairs_frame(columns: dict[str, list[Any]]) -> pd.DataFrame:
    """The pairs table with its fixed column order and dtypes (also used by ``from_json``)."""
    return pd.DataFrame(
        {name: pd.Series(columns[name], dtype=dtype) for name, dtype in _PAIR_DTYPES.items()}
    )


def _edges_frame(columns: dict[str, list[Any]]) -> pd.DataFrame:
    return pd.DataFrame(
        {name: pd.Series(columns[name], dtype=dtype) for name, dtype in _EDGE_DTYPES.items()}
    )


def _kinds(pairs: pd.DataFrame | dict[str, list[Any]], measure: str) -> list[str]:
    """Edge kind of every pair under ``measure``, from the per-measure kinds."""
    if measure == "clustering":
        return list(pairs["c_kind"])
    if measure == "transitivity":
        return list(pairs["t_kind"])
    return [combine_kinds(c, t) for c, t in zip(pairs["c_kind"], pairs["t_kind"], strict=True)]


def edges_from_pairs(pairs: pd.DataFrame, kinds: Any = None) -> pd.DataFrame:
    """The edges table of a pairs table: directed edges point source -> target; no conflicts.

    Parameters
    ----------
    pairs : pandas.DataFrame
        At least the columns ``x, y, weight`` and, unless ``kinds`` is given, ``kind`` -- a
        :attr:`FunctionalNetwork.pairs` table, or one window's rows of a study's results.
    kinds : sequence of str, optional
        The kind of each pair (``x->y``, ``y->x``, ``bidirectional``, ``conflict``); default
        ``pairs["kind"]``.

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind`` (``directed`` or ``bidirectional``), one row per
        directed edge or bidirectional pair; a conflict has no edge (README method step 7).

    References
    ----------
    Section 2.4 (edges) and Eq. 13 (weights) of the paper.

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["A", "A", "B"], "y": ["B", "C", "C"],
    ...                       "kind": ["y->x", "bidirectional", "conflict"],
    ...                       "weight": [0.2, 0.01, 0.3]})
    >>> edges_from_pairs(pairs)[["source", "target", "kind"]].values.tolist()
    [['B', 'A', 'directed'], ['A', 'C', 'bidirectional']]
    """
    if kinds is None:
        kinds = pairs["kind"]
    columns: dict[str, list[Any]] = {name: [] for name in _EDGE_DTYPES}
    for x, y, weight, kind in zip(pairs["x"], pairs["y"], pairs["weight"], kinds, strict=True):
        if kind == "conflict":
            continue
        source, target = (y, x) if kind == "y->x" else (x, y)
        columns["source"].append(source)
        columns["target"].append(target)
        columns["weight"].append(weight)
        columns["kind"].append("bidirectional" if kind == "bidirectional" else "directed")
    return _edges_frame(columns)


@dataclass(frozen=True, eq=False)
class FunctionalNetwork:
    """A functional network: signals as nodes, directed weighted edges from ISRN asymmetry.

    Build it with :func:`functional_network`; it keeps every pair's numbers, not only the graph.

    Attributes
    ----------
    nodes : tuple of str
        Signal names, in the order of the input columns.
    pairs : pandas.DataFrame
        One row per unordered pair (columns ``x``, ``y`` in input order): ``c_xy``, ``c_yx``,
        ``t_xy``, ``t_yx`` (Eq. 6-9), ``c_diff``, ``t_diff`` (Eq. 10), thresholds ``eps_x``,
        ``eps_y``, ``eps_xy`` and achieved rates ``rr_x``, ``rr_y``, ``cr``, the flags
        ``eps_ordered`` (``eps_xy < min(eps_x, eps_y)``), ``rate_exceeded`` (ties pushed a rate
        above its target) and ``degenerate`` (a block of the pair has a degenerate recurrence
        structure -- threshold 0 or a rate above twice its target, e.g. a signal that barely
        moves -- so its arrow is meaningless; the edge is kept), the per-measure kinds
        ``c_kind``, ``t_kind``, the ``kind`` under the network's measure (``x->y``, ``y->x``,
        ``bidirectional`` or ``conflict``) and the ``weight`` of Eq. 13.
    edges : pandas.DataFrame
        ``source``, ``target``, ``weight``, ``kind`` (``directed`` or ``bidirectional``); a
        directed edge points from the inferred driver to the driven signal.
    parameters : dict
        The parameters that produced the network (dim, delay, rr, cr, mu, metric, normalize,
        measure, rule, theiler, n_samples).
    label : str or None
        A name for the network (e.g. the analysis window).

    Notes
    -----
    Two networks compare equal when nodes, label, parameters and both tables are equal.

    References
    ----------
    Eq. 10 (asymmetry), section 2.4 (edges, ``mu``), Eq. 13 (weights) of the paper.
    """

    nodes: tuple[str, ...]
    pairs: pd.DataFrame
    edges: pd.DataFrame
    parameters: dict[str, Any]
    label: str | None = None

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FunctionalNetwork):
            return NotImplemented
        return (
            self.nodes == other.nodes
            and self.label == other.label
            and self.parameters == other.parameters
            and self.pairs.equals(other.pairs)
            and self.edges.equals(other.edges)
        )

    __hash__ = None  # type: ignore[assignment]  # holds DataFrames

    def edges_for(self, measure: str) -> pd.DataFrame:
        """Edges of the network under another measure, at the same ``mu``.

        Parameters
        ----------
        measure : {"both", "clustering", "transitivity"}
            ``"clustering"`` uses ``C_diff`` only, ``"transitivity"`` ``T_diff`` only, ``"both"``
            their intersection (README method step 7). Weights stay those of Eq. 13.

        Returns
        -------
        pandas.DataFrame
            Columns ``source``, ``target``, ``weight``, ``kind``, as :attr:`edges`.

        Raises
        ------
        ParameterError
            Unknown ``measure``.

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])  # a noisy copy: no arrow
        >>> network = functional_network(data, names=["x", "y"], delay=1)
        >>> network.edges_for("transitivity")
          source target    weight           kind
        0      x      y  0.027588  bidirectional
        """
        return edges_from_pairs(self.pairs, _kinds(self.pairs, _check_measure(measure)))

    def to_networkx(self) -> nx.DiGraph:
        """The network as a :class:`networkx.DiGraph`.

        Every node is present, even one without edges. A directed edge is one arc, a bidirectional
        relation two arcs; each arc has the attributes ``weight`` (Eq. 13) and ``kind``. The graph
        attributes hold ``label`` and a copy of ``parameters``.

        Returns
        -------
        networkx.DiGraph

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])  # a noisy copy: no arrow
        >>> graph = functional_network(data, names=["x", "y"], delay=1).to_networkx()
        >>> sorted(graph.edges(data="kind"))
        [('x', 'y', 'bidirectional'), ('y', 'x', 'bidirectional')]
        """
        graph = nx.DiGraph(label=self.label, parameters=dict(self.parameters))
        graph.add_nodes_from(self.nodes)
        for source, target, weight, kind in self.edges.itertuples(index=False):
            graph.add_edge(source, target, weight=float(weight), kind=kind)
            if kind == "bidirectional":
                graph.add_edge(target, source, weight=float(weight), kind=kind)
        return graph

    def to_json(self) -> str:
        """Serialize to JSON; :meth:`from_json` restores an equal network, floats bit for bit.

        Python's ``json`` writes each float as its shortest round-tripping ``repr``, so no digit is
        lost.

        Returns
        -------
        str

        Examples
        --------
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])  # a noisy copy: no arrow
        >>> network = functional_network(data, names=["x", "y"], delay=1, label="copy")
        >>> FunctionalNetwork.from_json(network.to_json()) == network
        True
        """
        document = {
            "format": _JSON_FORMAT,
            "version": _JSON_VERSION,
            "label": self.label,
            "nodes": list(self.nodes),
            "parameters": self.parameters,
            "pairs": {name: self.pairs[name].tolist() for name in _PAIR_DTYPES},
            "edges": {name: self.edges[name].tolist() for name in _EDGE_DTYPES},
        }
        return json.dumps(document, indent=1)

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
        try:
            document = json.loads(text)
            if document.get("format") != _JSON_FORMAT:
                raise ValueError(f"format is {document.get('format')!r}, not {_JSON_FORMAT!r}")
            if document.get("version") != _JSON_VERSION:
                raise ValueError(f"unknown version {document.get('version')!r}")
            return cls(
                nodes=tuple(document["nodes"]),
                pairs=_pairs_frame(document["pairs"]),
                edges=_edges_frame(document["edges"]),
                parameters=document["parameters"],
                label=document["label"],
            )
        except (ValueError, KeyError, TypeError, AttributeError) as error:
            raise ParameterError(
                f"text is not a funcnet functional network in JSON: {error}"
            ) from None

    def write(self, path: str | os.PathLike[str]) -> Path:
        """Write the network atomically, in the format its suffix names.

        Parameters
        ----------
        path : path-like
            ``*.json`` (:meth:`to_json`, lossless) or ``*.graphml`` (:meth:`to_networkx`; the
            parameters are stored as one JSON string graph attribute, the pairs table is not).
            :meth:`read` reads ``*.json`` back.

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
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])  # a noisy copy: no arrow
        >>> network = functional_network(data, names=["x", "y"], delay=1)
        >>> out = network.write(pathlib.Path(tempfile.mkdtemp()) / "copy.graphml")
        >>> sorted(nx.read_graphml(out).nodes)
        ['x', 'y']
        """
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix == ".json":
            return write_text_atomic(path, self.to_json())
        if suffix == ".graphml":
            graph = self.to_networkx()
            # GraphML attributes are scalars: no None, no dict.
            graph.graph = {"parameters": json.dumps(self.parameters)}
            if self.label is not None:
                graph.graph["label"] = self.label
            with atomic_path(path) as tmp:
                nx.write_graphml(graph, tmp)
            return path
        raise ParameterError(f"path must end in .json or .graphml, got {path.name!r}")

    @classmethod
    def read(cls, path: str | os.PathLike[str]) -> FunctionalNetwork:
        """Read a network written by :meth:`write` as ``*.json``; an exact round trip.

        Parameters
        ----------
        path : path-like
            A ``*.json`` file from :meth:`write` (or :meth:`to_json`).

        Returns
        -------
        FunctionalNetwork
            Equal to the network written, floats bit for bit.

        Raises
        ------
        ParameterError
            A ``*.graphml`` file (it holds no pairs table, so no network can be restored from it),
            any other suffix, or a file that is not a functional network; the message names it.
        FileNotFoundError
            No file at ``path``.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> import numpy as np
        >>> rng = np.random.default_rng(0)
        >>> x = rng.random(203)
        >>> data = np.column_stack([x, x + 0.1 * rng.random(203)])
        >>> network = functional_network(data, names=["x", "y"], delay=1)
        >>> out = network.write(pathlib.Path(tempfile.mkdtemp()) / "copy.json")
        >>> FunctionalNetwork.read(out) == network
        True
        """
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix == ".graphml":
            raise ParameterError(
                f"{path}: a GraphML file holds the graph but not the pairs table, so it cannot be "
                "read back as a FunctionalNetwork; write and read .json instead"
            )
        if suffix != ".json":
            raise ParameterError(f"path must end in .json, got {path.name!r}")
        try:
            return cls.from_json(path.read_text(encoding="utf-8"))
        except (ParameterError, UnicodeDecodeError) as error:
            raise ParameterError(f"{path}: {error}") from None

    def _summary(self) -> str:
        kinds = self.pairs["kind"]
        directed = int(kinds.isin(["x->y", "y->x"]).sum())
        bidirectional = int((kinds == "bidirectional").sum())
        conflicts = int((kinds == "conflict").sum())
        label = "" if self.label is None else f"{self.label!r}, "
        return (
            f"FunctionalNetwork({label}{len(self.nodes)} nodes, {directed} directed, "
            f"{bidirectional} bidirectional, {conflicts} conflict; "
            f"measure={self.parameters.get('measure')!r}, mu={self.parameters.get('mu')})"
        )

    def __repr__(self) -> str:
        return self._summary()

    def _repr_html_(self) -> str:
        return f"<p><code>{html.escape(self._summary())}</code></p>" + self.edges.to_html(
            index=False, float_format=lambda value: f"{value:.4f}"
        )


def _check_measure(measure: Any) -> str:
    if measure not in MEASURES:
        raise ParameterError(
            f"measure must be one of {', '.join(map(repr, MEASURES))}, got {measure!r}"
        )
    return measure


def _check_mu(mu: Any) -> float:
    if isinstance(mu, bool) or not isinstance(mu, numbers.Real):
        raise ParameterError(f"mu must be a number >= 0, got {mu!r}")
    mu = float(mu)
    if not math.isfinite(mu) or mu < 0:
        raise ParameterError(f"mu must be finite and >= 0, got {mu}")
    return mu


def check_parameters(
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    mu: float = 0.05,
    metric: str = "euclidean",
    normalize: str | None = "minmax",
    measure: str = "both",
    rule: str = "funcnet",
    theiler: int = 0,
) -> None:
    """Validate the parameters of :func:`functional_network` without any data.

    :func:`functional_network` calls it first, so a caller (the command line) can reject bad
    values before it reads a trace and gets the very same message.

    Parameters
    ----------
    dim, delay, rr, cr, mu, metric, normalize, measure, rule, theiler
        As in :func:`functional_network`.

    Raises
    ------
    ParameterError
        The first bad value; the message names the parameter: ``dim``/``delay`` not an integer
        ``>= 1``, ``rr``/``cr`` outside (0, 1), ``mu`` negative or not finite, an unknown
        ``metric``/``normalize``/``measure``/``rule``, ``theiler`` not an integer ``>= 0`` (or
        not 0 with ``rule="pyunicorn"``).

    Examples
    --------
    >>> check_parameters(rr=0.1, metric="supremum")
    >>> check_parameters(rr=2)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: rr must be in (0, 1), got 2.0
    """
    _check_measure(measure)
    _check_mu(mu)
    _check_normalization(normalize)
    _check_int(dim, "dim", 1)
    _check_int(delay, "delay", 1)
    _check_options(metric, rule, theiler)
    _check_rate(rr, "rr")
    _check_rate(cr, "cr")


def functional_network(
    data: Any,
    *,
    names: Any = None,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    mu: float = 0.05,
    metric: str = "euclidean",
    normalize: str | None = "minmax",
    measure: str = "both",
    rule: str = "funcnet",
    theiler: int = 0,
    label: str | None = None,
) -> FunctionalNetwork:
    """Functional network of simultaneously sampled signals (section 2.3-2.4, 3.4).

    Each signal is normalized, embedded and its recurrence network computed once; every unordered
    pair (X, Y), X before Y in column order, gives ``C^XY``, ``C^YX``, ``T^XY``, ``T^YX``
    (:func:`funcnet.measures.pairwise_cross_measures`), the differences of Eq. 10, an edge kind
    under ``mu`` and the weight of Eq. 13 (see the module notes for the rule).

    Parameters
    ----------
    data : pandas.DataFrame or array_like, shape (N, k)
        Time on axis 0, one signal per column, ``k >= 2``. A DataFrame's columns (as ``str``)
        become the node names.
    names : sequence of str, optional
        Node names; default the DataFrame's columns, else ``"0"``, ``"1"``, ...
    dim, delay : int
        Embedding dimension and delay in samples (Eq. 1).
    rr, cr : float in (0, 1)
        Recurrence rate inside each signal and cross-recurrence rate between two signals
        (section 3.4: 0.05 each).
    mu : float >= 0
        Bidirectionality threshold on ``C_diff`` and ``T_diff`` (section 3.4: 0.05).
    metric : {"euclidean", "supremum", "manhattan"}
        Phase-space distance (Eq. 2-3 use Euclidean).
    normalize : {"minmax", "zscore", None}
        Per-signal scaling before the embedding (:func:`funcnet.preprocess.normalize`); the
        paper uses min-max (section 3.3).
    measure : {"both", "clustering", "transitivity"}
        Which asymmetry sets :attr:`FunctionalNetwork.edges`: both (intersection, the default),
        ``C_diff`` only or ``T_diff`` only. The others stay available via
        :meth:`FunctionalNetwork.edges_for`.
    rule : {"funcnet", "pyunicorn"}
        Threshold rule (:func:`funcnet.measures.cross_measures`).
    theiler : int
        Theiler window for the recurrence networks of the signals.
    label : str, optional
        Stored on the network (e.g. the window's name).

    Returns
    -------
    FunctionalNetwork

    Raises
    ------
    SignalError
        Fewer than two signals; a signal not numeric, with NaN/inf, constant under ``"minmax"``
        or ``"zscore"``, or too short for the embedding; the message names it.
    ParameterError
        Any value :func:`check_parameters` rejects (checked before the data is read);
        ``names`` of the wrong length or with duplicates.

    Warns
    -----
    ThresholdWarning
        At most one per kind of problem, naming the pairs by their signals: ``eps_xy`` not below
        ``eps_x`` and ``eps_y``, or achieved rates above their targets (ties); the pairs table
        flags them too (``eps_ordered``, ``rate_exceeded``). A degenerate recurrence structure
        (threshold 0 or a rate above twice its target: too few distinct states, e.g. a signal
        that barely moves) gets its own warning naming the signal; those pairs' arrows are
        meaningless, and the pairs table flags them (``degenerate``).

    References
    ----------
    Eq. 10 (asymmetry), section 2.4 (edges and ``mu``), Eq. 13 (weights), section 3.4 (rates and
    ``mu`` of the robot study). Direction convention: the README's "Direction" section.

    Examples
    --------
    A rough driver ``x``, its smooth response ``y`` (a moving average: x -> y) and a rough ``z``
    coupled to nothing:

    >>> import warnings
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(300)
    >>> y = np.convolve(x, np.ones(5) / 5)[:300]
    >>> z = rng.random(300)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     network = functional_network(np.column_stack([x, y, z]), names=["x", "y", "z"],
    ...                                  delay=1)
    >>> network
    FunctionalNetwork(3 nodes, 2 directed, 1 bidirectional, 0 conflict; measure='both', mu=0.05)
    >>> network.edges
      source target    weight           kind
    0      x      y  0.317522       directed
    1      x      z  0.021947  bidirectional
    2      z      y  0.433247       directed

    ``z -> y`` has no coupling behind it: the rougher signal looks like the driver
    (the README's "Direction" section). At rr = cr = 0.05, ``eps_xy`` is rarely below ``eps_x`` and
    ``eps_y`` for signals this different; the pairs table flags it and a warning says so:

    >>> from funcnet.errors import ThresholdWarning
    >>> [w.category.__name__ for w in caught if issubclass(w.category, ThresholdWarning)][:1]
    ['ThresholdWarning']
    >>> bool(network.pairs["eps_ordered"].all())
    False
    """
    check_parameters(
        dim=dim,
        delay=delay,
        rr=rr,
        cr=cr,
        mu=mu,
        metric=metric,
        normalize=normalize,
        measure=measure,
        rule=rule,
        theiler=theiler,
    )
    mu = float(mu)
    values, nodes = _as_float_columns(data, names)
    if len(nodes) < 2:
        raise SignalError(f"a functional network needs at least two signals, got {len(nodes)}")
    duplicates = sorted({name for name in nodes if nodes.count(name) > 1})
    if duplicates:
        source = "names" if names is not None else "the columns of data"
        raise ParameterError(f"{source} must be unique; repeated: {', '.join(duplicates)}")
    values = normalize_signals(values, normalize, names=nodes)
    results = pairwise_cross_measures(
        values,
        names=nodes,
        dim=dim,
        delay=delay,
        rr=rr,
        cr=cr,
        metric=metric,
        rule=rule,
        theiler=theiler,
    )
    pair_names = [(nodes[i], nodes[j]) for i, j in results]
    measures = list(results.values())

    columns: dict[str, list[Any]] = {
        "x": [x for x, _ in pair_names],
        "y": [y for _, y in pair_names],
        **{name: [float(getattr(r, name)) for r in measures] for name in _MEASURE_COLUMNS},
        "eps_ordered": [bool(r.eps_ordered) for r in measures],
        "rate_exceeded": [bool(r.rate_exceeded) for r in measures],
        "degenerate": [bool(r.degenerate) for r in measures],
    }
    columns["c_kind"] = [edge_kind(diff, mu) for diff in columns["c_diff"]]
    columns["t_kind"] = [edge_kind(diff, mu) for diff in columns["t_diff"]]
    columns["kind"] = _kinds(columns, measure)
    columns["weight"] = [
        (abs(c) + abs(t)) / 2 for c, t in zip(columns["c_diff"], columns["t_diff"], strict=True)
    ]
    pairs = _pairs_frame(columns)
    parameters = {
        "dim": operator.index(dim),
        "delay": operator.index(delay),
        "rr": float(rr),
        "cr": float(cr),
        "mu": mu,
        "metric": metric,
        "normalize": normalize,
        "measure": measure,
        "rule": rule,
        "theiler": operator.index(theiler),
        "n_samples": int(values.shape[0]),
    }
    return FunctionalNetwork(
        nodes=tuple(nodes),
        pairs=pairs,
        edges=edges_from_pairs(pairs),
        parameters=parameters,
        label=None if label is None else str(label),
    )
