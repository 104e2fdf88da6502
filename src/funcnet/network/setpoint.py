"""The set-point check: the arrows of one or many networks against what a recording fixes.

A robot's position set-point ``RP`` is computed ahead by the path planner from the program;
nothing measured on the axis feeds back into it. Two facts follow, as safe as the recording's
channel names:

* **no arrow into a set-point**: an arrow ``X -> RP`` (X any other signal) contradicts the
  recording;
* **no arrow between two set-points**: the planner computes every axis's ``RP`` together (one
  interpolation of one path), so ``A1.RP -> A2.RP`` is no influence either.

An arrow out of a set-point (``RP -> AP``, ``RP -> AC``, ...) is allowed: the axis follows its
set-point. The current set-point ``RC`` is *not* a set-point here: it is the controller's output,
computed from ``RP``, ``AP`` and ``MP``, so arrows into it are allowed. The derived velocity
``V`` (from ``AP``) is a signal like any other.

:func:`setpoint_check` counts, per pair type (the other node's role, or ``RP-RP`` between two
set-points), the arrows into the set-point (contradicted), out of it (allowed) and the pairs
without an arrow, for the paper's ``kind`` or the ``direction`` reading
(:mod:`funcnet.network.direction`); :meth:`SetpointCheck.sentence` says it in one sentence, as
every page and ``funcnet network`` print it before the drawing.

Roles are read from node names: ``RP`` or ``A<n>.RP`` (the axis prefix of a recording of
several axes); a degenerate pair is no arrow and is not counted.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import pandas as pd

from funcnet.errors import ParameterError

__all__ = ["SETPOINT_ROLES", "SetpointCount", "SetpointCheck", "node_role", "setpoint_check"]

#: Roles that are set-points: nothing in a robot drives them.
SETPOINT_ROLES: tuple[str, ...] = ("RP",)

#: The columns whose arrows the check reads.
CHECKED_COLUMNS: tuple[str, ...] = ("kind", "direction")

#: The pair type of two set-points.
BETWEEN = "RP-RP"


def node_role(name: str) -> str:
    """The role of a node: its name without an axis prefix (``A2.RP`` -> ``RP``).

    Examples
    --------
    >>> node_role("A2.RP"), node_role("AC"), node_role("A1.act_torque_rel_nm")
    ('RP', 'AC', 'act_torque_rel_nm')
    """
    head, dot, tail = str(name).partition(".")
    if dot and head[:1] == "A" and head[1:].isdigit():
        return tail
    return str(name)


@dataclass(frozen=True)
class SetpointCount:
    """The set-point pairs of one type.

    Attributes
    ----------
    pair_type : str
        The other node's role (``AC``, ``MP``, ...), or ``RP-RP`` between two set-points.
    into : int
        Arrows into the set-point (for ``RP-RP``: arrows between the two): contradicted.
    out : int
        Arrows out of the set-point: allowed.
    undirected : int
        Pairs without an arrow (bidirectional, conflict, ``none``).
    """

    pair_type: str
    into: int
    out: int
    undirected: int

    @property
    def pairs(self) -> int:
        """Pairs counted."""
        return self.into + self.out + self.undirected


@dataclass(frozen=True)
class SetpointCheck:
    """The arrows of one or many networks against the set-point facts (module notes).

    Attributes
    ----------
    column : str
        ``"kind"`` (the paper's rule) or ``"direction"``.
    counts : tuple of SetpointCount
        Per pair type, in order of first appearance (``RP-RP`` last).
    networks : int
        Networks read.
    """

    column: str
    counts: tuple[SetpointCount, ...]
    networks: int

    @property
    def into(self) -> int:
        """Arrows into a set-point, between-set-point arrows included: contradicted."""
        return sum(c.into for c in self.counts)

    @property
    def out(self) -> int:
        """Arrows out of a set-point: allowed."""
        return sum(c.out for c in self.counts)

    @property
    def pairs(self) -> int:
        """Set-point pairs counted."""
        return sum(c.pairs for c in self.counts)

    @property
    def between(self) -> int:
        """Arrows between two set-points (part of :attr:`into`)."""
        return sum(c.into for c in self.counts if c.pair_type == BETWEEN)

    @property
    def contradicted_share(self) -> float:
        """:attr:`into` over the set-point pairs (NaN without any)."""
        return self.into / self.pairs if self.pairs else float("nan")

    def table(self) -> pd.DataFrame:
        """One row per pair type: ``pair_type, into, out, undirected, pairs``.

        Examples
        --------
        >>> check = SetpointCheck("kind", (SetpointCount("AC", 2, 1, 0),), 1)
        >>> check.table().values.tolist()
        [['AC', 2, 1, 0, 3]]
        """
        return pd.DataFrame(
            [(c.pair_type, c.into, c.out, c.undirected, c.pairs) for c in self.counts],
            columns=["pair_type", "into", "out", "undirected", "pairs"],
        )

    def sentence(self) -> str:
        """The check in one sentence, for a page or the command line.

        Examples
        --------
        >>> SetpointCheck("kind", (SetpointCount("AC", 25, 7, 3),), 12).sentence()
        "Here the rule's arrows point into the set-point 25 times and out of it 7 times: on \
this recording they do not read as direction (nothing drives a set-point)."
        >>> SetpointCheck("direction", (SetpointCount("AC", 0, 4, 31),), 12).sentence()
        'Here the direction reading points into the set-point 0 times and out of it 4 times \
(31 of 35 set-point pairs undecided): nothing on this recording contradicts it.'
        """
        if not self.pairs:
            what = "the rule's arrows" if self.column == "kind" else "the direction reading"
            return (f"No set-point (RP) among the nodes: nothing on this recording checks "
                    f"{what}.")
        rule = self.column == "kind"
        subject = "the rule's arrows point" if rule else "the direction reading points"
        between = (f" and {_times(self.between)} between two set-points" if self.between
                   else "")
        text = (f"Here {subject} into the set-point {_times(self.into - self.between)}"
                f"{between} and out of it {_times(self.out)}")
        if not rule:
            undecided = sum(c.undirected for c in self.counts)
            text += f" ({undecided} of {self.pairs} set-point pairs undecided)"
        if not self.into:
            return text + ": nothing on this recording contradicts " + ("them." if rule
                                                                        else "it.")
        if rule:
            return (text + ": on this recording they do not read as direction (nothing "
                    "drives a set-point).")
        return (text + f": {self.into} of {self.pairs} set-point pairs "
                f"({self.contradicted_share:.0%}) contradict it (nothing drives a set-point).")


def _times(n: int) -> str:
    return "once" if n == 1 else f"{n} times"


def _tables(networks: Any) -> list[pd.DataFrame]:
    """The pairs tables of one network, a pairs table, or many of either (a mapping's
    values)."""
    if isinstance(networks, pd.DataFrame) or hasattr(networks, "pairs"):
        networks = [networks]
    elif isinstance(networks, Mapping):
        networks = list(networks.values())
    elif not isinstance(networks, Iterable):
        raise ParameterError.of("networks", f"must be a FunctionalNetwork, a pairs table or "
                                f"several, got {type(networks).__name__}")
    tables = []
    for item in networks:
        table = item if isinstance(item, pd.DataFrame) else getattr(item, "pairs", None)
        if not isinstance(table, pd.DataFrame):
            raise ParameterError.of("networks", f"holds a {type(item).__name__}, not a "
                                    "FunctionalNetwork or a pairs table")
        tables.append(table)
    return tables


def setpoint_check(networks: Any, *, column: str = "kind",
                   setpoints: Iterable[str] = SETPOINT_ROLES) -> SetpointCheck:
    """Count the arrows into and out of the set-points of one network or many (module notes).

    Parameters
    ----------
    networks : FunctionalNetwork, pandas.DataFrame, or a sequence or mapping of them
        Networks or their pairs tables (``x``, ``y``, ``degenerate`` and ``column``).
    column : {"kind", "direction"}
        Whose arrows: the paper's rule or the direction reading.
    setpoints : iterable of str
        The set-point roles (default ``("RP",)``).

    Returns
    -------
    SetpointCheck

    Raises
    ------
    ParameterError
        Unknown ``column``, a table without it, or ``networks`` of another type.

    Examples
    --------
    >>> pairs = pd.DataFrame({"x": ["RP", "RP", "RP", "AP"], "y": ["AP", "AC", "MP", "AC"],
    ...                       "kind": ["y->x", "x->y", "bidirectional", "y->x"],
    ...                       "degenerate": [False] * 4})
    >>> check = setpoint_check(pairs)
    >>> check.into, check.out, check.table().values.tolist()
    (1, 1, [['AP', 1, 0, 0, 1], ['AC', 0, 1, 0, 1], ['MP', 0, 0, 1, 1]])
    """
    if column not in CHECKED_COLUMNS:
        raise ParameterError.of("column", f"must be one of {list(CHECKED_COLUMNS)}, got "
                                f"{column!r}")
    roles = set(setpoints)
    tables = _tables(networks)
    found: dict[str, list[int]] = {}
    for table in tables:
        if column not in table.columns:
            raise ParameterError.of("networks", f"a pairs table has no column {column!r}")
        flags = (table["degenerate"].eq(True) if "degenerate" in table.columns
                 else pd.Series(False, index=table.index))
        for x, y, arrow, flagged in zip(table["x"], table["y"], table[column], flags,
                                        strict=True):
            x_set, y_set = node_role(x) in roles, node_role(y) in roles
            if bool(flagged) or not (x_set or y_set):
                continue
            if x_set and y_set:
                key, into, out = BETWEEN, arrow in ("x->y", "y->x"), False
            else:
                key = node_role(y) if x_set else node_role(x)
                towards = "x->y" if y_set else "y->x"
                into, out = arrow == towards, arrow in ("x->y", "y->x") and arrow != towards
            counts = found.setdefault(key, [0, 0, 0])
            counts[0 if into else 1 if out else 2] += 1
    order = [k for k in found if k != BETWEEN] + ([BETWEEN] if BETWEEN in found else [])
    return SetpointCheck(column=column,
                         counts=tuple(SetpointCount(k, *found[k]) for k in order),
                         networks=len(tables))
