"""Readers and writers of functional networks: JSON, GraphML, networkx.

The ``degenerate`` flag travels through every format: the pairs table keeps it with its reason,
and every edge -- in the edges table, as a networkx or a GraphML arc -- carries a boolean
``degenerate`` attribute (True only for a pair kept with ``degenerate="keep"``).

- **JSON** (:func:`to_json`, :func:`fields_from_json`): the whole network (with its evidence
  columns and settings when it has them), floats bit for bit
  (Python's ``json`` writes each float as its shortest round-tripping ``repr``). Format
  ``funcnet.FunctionalNetwork`` version 2. A version-2 file with
  evidence written before the ``untestable`` label gets its ``evidence`` labels and the
  ``evidence_reason`` column read from its test's columns (the numbers are unchanged).
- **networkx** (:func:`to_networkx`): every node, one arc per directed edge and two per
  bidirectional one.
- **GraphML** (:func:`write`): the networkx graph for other tools (scalar attributes only: the
  parameters as one JSON string) plus the JSON document as the graph attribute ``funcnet``, so
  that :func:`read_fields` restores the network exactly.

The readers return the fields of a :class:`~funcnet.network.FunctionalNetwork` (its constructor
arguments), which :meth:`FunctionalNetwork.read <funcnet.network.FunctionalNetwork.read>` and
:meth:`~funcnet.network.FunctionalNetwork.from_json` turn into the network; this module stays
below the class it serializes.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from funcnet._io import atomic_path, write_text_atomic
from funcnet.errors import ParameterError
from funcnet.network.edge_evidence import with_readings
from funcnet.network.schema import EDGE_COLUMNS, edges_frame, pairs_frame
from funcnet.parameters import NetworkParameters

if TYPE_CHECKING:
    import networkx as nx

    from funcnet.network.functional import FunctionalNetwork

__all__ = ["FORMAT", "VERSION", "ARC_EVIDENCE", "to_json", "fields_from_json", "to_networkx",
           "write", "read_fields"]

FORMAT = "funcnet.FunctionalNetwork"
VERSION = 2
_SUFFIXES = (".json", ".graphml")


def to_json(network: FunctionalNetwork) -> str:
    """The network as a JSON document; :func:`fields_from_json` restores it exactly.

    Parameters
    ----------
    network : FunctionalNetwork

    Returns
    -------
    str
        An object with ``format``, ``version``, ``label``, ``nodes``, ``channels``,
        ``parameters`` (:meth:`NetworkParameters.to_dict`), ``n_samples``, ``window`` and the
        ``pairs`` and ``edges`` tables column by column.

    Examples
    --------
    >>> import json
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(203)
    >>> network = functional_network(np.column_stack([x, x + 0.1 * rng.random(203)]), delay=1)
    >>> document = json.loads(to_json(network))
    >>> document["version"], document["edges"]["degenerate"]
    (2, [False])
    """
    document = {
        "format": FORMAT,
        "version": VERSION,
        "label": network.label,
        "nodes": list(network.nodes),
        "channels": None if network.channels is None else {
            node: list(columns) for node, columns in network.channels.items()
        },
        "parameters": network.parameters.to_dict(),
        "n_samples": network.n_samples,
        **({} if network.state_step == 1 else {"state_step": network.state_step}),
        "window": None if network.window is None else dict(network.window),
        **({} if network.evidence is None else {"evidence": dict(network.evidence)}),
        "pairs": {str(name): network.pairs[name].tolist() for name in network.pairs.columns},
        "edges": {name: network.edges[name].tolist() for name in EDGE_COLUMNS},
    }
    return json.dumps(document, indent=1)


def _tuples(value: Any) -> Any:
    """JSON lists back to tuples (the fields hold tuples)."""
    if isinstance(value, list):
        return tuple(_tuples(item) for item in value)
    if isinstance(value, dict):
        return {key: _tuples(item) for key, item in value.items()}
    return value


def _pairs_read(document: Mapping[str, Any]) -> pd.DataFrame:
    """The pairs table of a version-2 document; one written before the ``untestable`` label
    and the ``evidence_reason`` column gets both, read from its test's columns."""
    columns = _with_direction(document["pairs"])
    if "evidence" not in columns or "evidence_reason" in columns:
        return pairs_frame(columns)
    alpha = float((document.get("evidence") or {})["alpha"])
    frame = with_readings(pd.DataFrame(columns), alpha)
    return pairs_frame({name: frame[name].tolist() for name in frame.columns})


#: The direction reason of a file written before the direction reading.
NOT_READ = "not read: the file was written before the direction reading"


def _with_direction(columns: Mapping[str, Any]) -> dict[str, Any]:
    """A pairs document's columns with ``direction`` and ``direction_reason``: a file written
    before them gets ``none`` and :data:`NOT_READ` (its conditional-recurrence ``direction``,
    ``direction_index`` and ``direction_p`` are dropped: another reading)."""
    out = dict(columns)
    if "direction_reason" in out:
        return out
    for name in ("direction", "direction_index", "direction_p"):
        out.pop(name, None)
    n = len(out["x"])
    out["direction"], out["direction_reason"] = ["none"] * n, [NOT_READ] * n
    return out


def fields_from_json(text: str) -> dict[str, Any]:
    """The fields of the network a JSON document holds.

    Parameters
    ----------
    text : str
        A document from :func:`to_json`.

    Returns
    -------
    dict
        The constructor arguments of :class:`~funcnet.network.FunctionalNetwork`.

    Raises
    ------
    ParameterError
        ``text`` is not JSON, not a functional network, or of an unknown version.

    Examples
    --------
    >>> fields_from_json('{"format": "something else"}')
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: text is not a funcnet functional network in JSON: format is \
'something else', not 'funcnet.FunctionalNetwork'
    """
    try:
        document = json.loads(text)
        if not isinstance(document, dict) or document.get("format") != FORMAT:
            found = document.get("format") if isinstance(document, dict) else document
            raise ValueError(f"format is {found!r}, not {FORMAT!r}")
        version = document.get("version")
        if version != VERSION:
            raise ValueError(f"unknown version {version!r}")
        channels = document["channels"]
        window = document["window"]
        return {
            "nodes": tuple(document["nodes"]),
            "pairs": _pairs_read(document),
            "edges": edges_frame(document["edges"]),
            "parameters": NetworkParameters.from_mapping(document["parameters"]),
            "n_samples": int(document["n_samples"]),
            "state_step": int(document.get("state_step", 1)),
            "label": document["label"],
            "window": None if window is None else _tuples(window),
            "channels": None if channels is None else {
                node: tuple(columns) for node, columns in channels.items()
            },
            "evidence": document.get("evidence"),
        }
    except (ValueError, KeyError, TypeError, AttributeError) as error:
        # ParameterError is a ValueError: a bad parameter or table in the file lands here too.
        raise ParameterError(f"text is not a funcnet functional network in JSON: {error}") from None


def to_networkx(network: FunctionalNetwork) -> nx.DiGraph:
    """The network as a :class:`networkx.DiGraph`.

    Parameters
    ----------
    network : FunctionalNetwork

    Returns
    -------
    networkx.DiGraph
        Every node, even one without edges. A directed edge is one arc, a bidirectional
        relation two arcs; each arc has the attributes ``weight`` (Eq. 13), ``kind``
        (``directed`` or ``bidirectional``), ``degenerate``, ``direction`` (the pair's
        :mod:`~funcnet.network.direction` reading, ``"A->B"`` in node names, or ``"none"``)
        and ``direction_reason``. The arcs are the rule's edges: a pair without one (a
        conflict) keeps its direction in the pairs table only. The graph attributes hold
        ``label``, ``parameters`` (:meth:`NetworkParameters.to_dict`) and ``n_samples``.
        A network with evidence adds, on every arc, :data:`ARC_EVIDENCE`: ``coupling_p``,
        ``coupled``, ``evidence`` and ``evidence_reason``.

    References
    ----------
    Section 2.4 and Eq. 13 of the paper.

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(203)
    >>> network = functional_network(np.column_stack([x, x + 0.1 * rng.random(203)]), delay=1)
    >>> arc = to_networkx(network).edges["0", "1"]
    >>> arc["kind"], arc["direction"]
    ('bidirectional', 'none')
    """
    import networkx as nx  # here: a page or a JSON file never needs it (its import is slow)

    graph = nx.DiGraph(
        label=network.label,
        parameters=network.parameters.to_dict(),
        n_samples=network.n_samples,
    )
    graph.add_nodes_from(network.nodes)
    evidence = _edge_evidence(network)
    directions = _edge_directions(network)
    for source, target, weight, kind, degenerate in network.edges[list(EDGE_COLUMNS)].itertuples(
        index=False
    ):
        attributes = {"weight": float(weight), "kind": str(kind), "degenerate": bool(degenerate)}
        attributes.update(directions.get(frozenset((source, target)), {}))
        attributes.update(evidence.get(frozenset((source, target)), {}))
        graph.add_edge(source, target, **attributes)
        if kind == "bidirectional":
            graph.add_edge(target, source, **attributes)
    return graph


#: The evidence columns an arc carries (networkx, GraphML), when the network has them.
ARC_EVIDENCE = ("coupling_p", "coupled", "evidence", "evidence_reason")


def _edge_directions(network: FunctionalNetwork) -> dict[frozenset[str], dict[str, Any]]:
    """Per unordered pair, its ``direction`` as ``"A->B"`` in node names (or ``"none"``) and
    ``direction_reason``."""
    found: dict[frozenset[str], dict[str, Any]] = {}
    for x, y, direction, reason in network.pairs[["x", "y", "direction",
                                                  "direction_reason"]].itertuples(index=False):
        arrow = {"x->y": f"{x}->{y}", "y->x": f"{y}->{x}"}.get(str(direction), "none")
        found[frozenset((x, y))] = {"direction": arrow, "direction_reason": str(reason)}
    return found


def _edge_evidence(network: FunctionalNetwork) -> dict[frozenset[str], dict[str, Any]]:
    """Per unordered pair, the evidence attributes of its arcs (empty without evidence)."""
    if "evidence" not in network.pairs.columns:
        return {}
    found: dict[frozenset[str], dict[str, Any]] = {}
    for row in network.pairs[["x", "y", *ARC_EVIDENCE]].itertuples(index=False):
        x, y, p_value, coupled, reading, reason = row
        found[frozenset((x, y))] = {
            "coupling_p": float(p_value), "coupled": bool(coupled),
            "evidence": str(reading), "evidence_reason": str(reason),
        }
    return found


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in _SUFFIXES:
        # funcnet.network sits below funcnet.plot: it names the drawing call, it cannot draw
        drawing = (" (a picture is drawn by funcnet.plot.save_network(network, path), what "
                   "`funcnet network -o net.png` does)" if suffix in (".png", ".svg", ".pdf")
                   else "")
        raise ParameterError.of(
            "path", f"must end in .json or .graphml, got {path.name!r}{drawing}"
        )
    return suffix


def write(network: FunctionalNetwork, path: str | os.PathLike[str]) -> Path:
    """Write the network atomically, in the format its suffix names.

    Parameters
    ----------
    network : FunctionalNetwork
    path : path-like
        ``*.json`` (:func:`to_json`) or ``*.graphml`` (:func:`to_networkx`, with the parameters
        as one JSON string graph attribute and the JSON document as the attribute
        ``funcnet``); either reads back exactly (:func:`read_fields`).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        Any other suffix (nothing is written).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(203)
    >>> network = functional_network(np.column_stack([x, x + 0.1 * rng.random(203)]), delay=1)
    >>> out = write(network, pathlib.Path(tempfile.mkdtemp()) / "copy.graphml")
    >>> import networkx as nx
    >>> nx.read_graphml(out).edges["0", "1"]["degenerate"]
    False
    """
    path = Path(path)
    if _suffix(path) == ".json":
        return write_text_atomic(path, to_json(network))
    graph = to_networkx(network)
    # GraphML attributes are scalars: no None, no dict.
    graph.graph = {
        "parameters": json.dumps(network.parameters.to_dict()),
        "n_samples": network.n_samples,
        "funcnet": to_json(network),
    }
    if network.label is not None:
        graph.graph["label"] = network.label
    import networkx as nx

    with atomic_path(path) as tmp:
        nx.write_graphml(graph, tmp)
    return path


def read_fields(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The fields of the network in a file from :func:`write` (``*.json`` or ``*.graphml``).

    Parameters
    ----------
    path : path-like

    Returns
    -------
    dict
        The constructor arguments of :class:`~funcnet.network.FunctionalNetwork`.

    Raises
    ------
    ParameterError
        Another suffix, or a file that holds no functional network (a GraphML file from
        another tool or an older funcnet holds no pairs table); the message names the file.
    FileNotFoundError
        No file at ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> rng = np.random.default_rng(0)
    >>> x = rng.random(203)
    >>> network = functional_network(np.column_stack([x, x + 0.1 * rng.random(203)]), delay=1)
    >>> out = write(network, pathlib.Path(tempfile.mkdtemp()) / "copy.json")
    >>> read_fields(out)["nodes"]
    ('0', '1')
    """
    path = Path(path)
    suffix = _suffix(path)
    try:
        if suffix == ".json":
            return fields_from_json(path.read_text(encoding="utf-8"))
        import networkx as nx

        try:
            graph = nx.read_graphml(path)
        except (ValueError, KeyError, TypeError, SyntaxError) as error:
            # ElementTree's ParseError is a SyntaxError.
            raise ParameterError(f"not a GraphML file: {error}") from None
        if "funcnet" not in graph.graph:
            raise ParameterError(
                "this GraphML file holds the graph but not the pairs table (another tool or an "
                "older funcnet wrote it), so it cannot be read back as a FunctionalNetwork"
            )
        return fields_from_json(graph.graph["funcnet"])
    except (ParameterError, UnicodeDecodeError) as error:
        raise ParameterError(f"{path}: {error}") from None
