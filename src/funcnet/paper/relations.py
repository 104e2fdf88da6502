"""What a network shows between two signals, read in the claim language.

A network's pairs table says, per pair, one kind of :data:`funcnet.network.schema.PAIR_KINDS`;
:func:`pair_kind` reads it for an ordered pair, :func:`relation` writes it in the claim
language of :mod:`funcnet.paper.claims` and :func:`relation_holds` checks a claim against it.
A pair flagged ``degenerate`` (too few distinct states) shows no readable relation.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", section 2.4
   (kinds of edges) and section 4.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pandas as pd

from funcnet.network.schema import PAIR_KINDS
from funcnet.paper.claims import parse_claim

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = ["DEGENERATE", "pair_kind", "relation", "relation_holds", "pairs_of", "nodes_of",
           "is_degenerate"]

_X_Y, _Y_X, _BIDIRECTIONAL, _CONFLICT = PAIR_KINDS
_REVERSED = {_X_Y: _Y_X, _Y_X: _X_Y}

#: Why a claim about a degenerate pair is not evaluable.
DEGENERATE = "degenerate recurrence structure (a signal barely moves in the window)"


def pairs_of(net: FunctionalNetwork) -> pd.DataFrame:
    """The pairs table of a network."""
    return net.pairs


def pair_kind(net: FunctionalNetwork, a: str, b: str) -> str | None:
    """The kind of the pair (a, b) in a network, read with ``a`` as ``x``.

    Parameters
    ----------
    net : FunctionalNetwork
        A network.
    a, b : str
        Node names.

    Returns
    -------
    str or None
        One of :data:`funcnet.network.schema.PAIR_KINDS` (``"x->y"``: ``a`` drives ``b``), or
        ``None`` when the network has no such pair.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(
    ...     pd.DataFrame({"x": ["RP"], "y": ["AP"], "kind": ["y->x"], "weight": [0.1]}))
    >>> pair_kind(net, "RP", "AP"), pair_kind(net, "AP", "RP"), pair_kind(net, "RP", "V")
    ('y->x', 'x->y', None)
    """
    if a == b:
        return None
    table = pairs_of(net)
    for x, y, kind in zip(table["x"], table["y"], table["kind"], strict=True):
        if (x, y) == (a, b):
            return str(kind)
        if (x, y) == (b, a):
            return _REVERSED.get(kind, str(kind))
    return None


def relation(net: FunctionalNetwork, a: str, b: str) -> str | None:
    """The relation a network shows between signals ``a`` and ``b``, in the claim language.

    Parameters
    ----------
    net : FunctionalNetwork
        A network.
    a, b : str
        Node names.

    Returns
    -------
    str or None
        ``"a->b"`` or ``"b->a"`` (the driver first), ``"a<->b"`` (bidirectional: mutual or no
        coupling, paper section 2.4), ``"a-/-b"`` (conflict between C_diff and T_diff: no
        edge), or ``None`` when the network has no such pair.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(
    ...     pd.DataFrame({"x": ["RP"], "y": ["AP"], "kind": ["y->x"], "weight": [0.1]}))
    >>> relation(net, "RP", "AP"), relation(net, "AP", "RP"), relation(net, "RP", "V")
    ('AP->RP', 'AP->RP', None)
    """
    kind = pair_kind(net, a, b)
    if kind is None:
        return None
    if kind == _BIDIRECTIONAL:
        return f"{a}<->{b}"
    if kind == _CONFLICT:
        return f"{a}-/-{b}"
    return f"{a}->{b}" if kind == _X_Y else f"{b}->{a}"


def relation_holds(net: FunctionalNetwork, claim: str) -> tuple[bool | None, str | None]:
    """Whether a network shows a claimed relation.

    Parameters
    ----------
    net : FunctionalNetwork
        A network.
    claim : str
        ``"A->B"``, ``"A<->B"``, ``"A-/-B"`` or ``"A!<->B"``
        (:func:`funcnet.paper.claims.parse_claim`).

    Returns
    -------
    (bool or None, str or None)
        Whether it holds and the relation seen; ``(None, None)`` when the pair is absent or
        flagged ``degenerate`` (not evaluable).

    Raises
    ------
    ParameterError
        When ``claim`` is not written in one of the four forms.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["RC"], "y": ["AC"], "kind": ["bidirectional"],
    ...                       "weight": [0.01]})
    >>> net = FunctionalNetwork.from_pairs(pairs)
    >>> relation_holds(net, "AC<->RC"), relation_holds(net, "RC->AC")[0]
    ((True, 'AC<->RC'), False)
    >>> relation_holds(FunctionalNetwork.from_pairs(pairs.assign(degenerate=True)), "AC<->RC")
    (None, None)
    """
    parsed = parse_claim(claim)
    kind = pair_kind(net, parsed.a, parsed.b)
    if kind is None or is_degenerate(net, parsed.a, parsed.b):
        return None, None
    return parsed.holds(kind), relation(net, parsed.a, parsed.b)


def is_degenerate(net: FunctionalNetwork, a: str, b: str) -> bool:
    """Whether the pair of ``a`` and ``b`` is flagged ``degenerate`` (False without the column)."""
    table = pairs_of(net)
    if "degenerate" not in table.columns:
        return False
    pair = table[table["x"].isin((a, b)) & table["y"].isin((a, b))]
    # Rows of older results mixed with newer ones hold NaN there: not degenerate.
    return bool(pair["degenerate"].eq(True).any())


def nodes_of(net: FunctionalNetwork) -> set[str]:
    """The nodes of a network."""
    return set(net.nodes)
