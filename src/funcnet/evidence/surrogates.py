"""Twin surrogates for the dependence test (an option beside the time-shift lattice).

A twin surrogate (Thiel et al. 2006) keeps one signal's dynamics and destroys its time alignment
with the other signal without needing stationarity of a time shift:

* **Twins** are states with identical neighbourhoods: identical columns of the recurrence
  matrix *with* its main diagonal, ``R = A + I``, at the threshold the network uses. Two twins
  are neighbours of each other and of the same other states, so the recurrence plot cannot tell
  which of them the trajectory visits.
* **A surrogate trajectory** starts at a random state; at each step, when the current state
  ``k`` has twins it moves on from ``k`` or from one of its twins with equal probability, and
  goes to that state's successor (its next time). A successor past the end restarts at a random
  state (as pyunicorn 1.0's ``_twin_surrogates_s``). The surrogate is a sequence of indices
  ``idx`` into the signal's states; its recurrence matrix at the same threshold is
  ``R[idx[u], idx[v]]`` -- read, never recomputed. pyunicorn also ignores twins closer than 7
  time steps; not done here: at rr = 0.05 states whose only twins are that close were 0-6 of
  500 in the benchmark's systems (white noise, Hénon, Lorenz, Rössler, AR(1)).

With few twins (the usual case at a fixed recurrence rate of 5 % for flows and noise; Thiel et
al. choose the threshold to get enough of them) a surrogate is mostly a random start run to the
end and restarted: a random circular shift with random joins. Where that is not valid is
measured in docs/validation/evidence.md.

References
----------
M. Thiel, M. C. Romano, J. Kurths, M. Rolfs, R. Kliegl, "Twin surrogates to test for complex
synchronisation", Europhys. Lett. 75, 535-541 (2006).
N. Marwan, M. C. Romano, M. Thiel, J. Kurths, "Recurrence plots for the analysis of complex
systems", Phys. Rep. 438, 237-329 (2007), section 3.7.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from funcnet.errors import ParameterError
from funcnet.evidence._kernels import _twin_walks

__all__ = ["TwinPlan", "twin_groups", "twin_plan"]


def twin_groups(a: np.ndarray) -> np.ndarray:
    """Label of each state's twin class: states with identical columns of ``A + I``.

    Parameters
    ----------
    a : ndarray of uint8 or bool, shape (M, M)
        A recurrence matrix without self-loops (``PackedRecurrence.to_dense()``).

    Returns
    -------
    ndarray of int64, shape (M,)
        Equal labels for twins; a state without twins has a label of its own.

    Examples
    --------
    >>> a = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 0]], dtype=np.uint8)
    >>> twin_groups(a).tolist()  # states 0 and 1 see each other and nothing else
    [1, 1, 0]
    """
    r = np.asarray(a, dtype=bool).copy()
    if r.ndim != 2 or r.shape[0] != r.shape[1]:
        raise ParameterError.of("a", f"must be a square matrix, got shape {r.shape}")
    np.fill_diagonal(r, True)
    # A matrix is symmetric: columns are rows; pack them to compare whole neighbourhoods.
    packed = np.packbits(r, axis=1)
    _, labels = np.unique(packed, axis=0, return_inverse=True)
    return np.asarray(labels, dtype=np.int64).reshape(-1)


@dataclass(frozen=True)
class TwinPlan:
    """The twin surrogates of Y for one dependence test.

    Attributes
    ----------
    n_states : int
        ``M``, states per signal; the observed window and every surrogate hold all of them.
    indices : ndarray of int64, shape (K, M)
        Each surrogate's sequence of Y's state indices.
    twins : int
        States of Y that have at least one twin.
    """

    n_states: int
    indices: np.ndarray
    twins: int

    @property
    def surrogates(self) -> int:
        """``K``, the number of surrogates."""
        return int(self.indices.shape[0])

    @property
    def length(self) -> int:
        """``L = M``: states per window (twin surrogates need no shortened window)."""
        return self.n_states


def twin_plan(a_y: np.ndarray, surrogates: int, *, seed: Any = 0) -> TwinPlan:
    """``K`` twin surrogates of the signal whose recurrence matrix is ``a_y`` (module notes).

    Parameters
    ----------
    a_y : ndarray, shape (M, M)
        Y's recurrence matrix without self-loops, at the network's threshold.
    surrogates : int
        ``K``, at least 1.
    seed : int or sequence of int
        Seeds :func:`numpy.random.default_rng`.

    Returns
    -------
    TwinPlan

    Raises
    ------
    ParameterError
        ``surrogates < 1`` or a matrix that is not square.

    References
    ----------
    Thiel et al. (2006), the twin-surrogate algorithm.

    Examples
    --------
    >>> a = np.zeros((30, 30), dtype=np.uint8)
    >>> a[4, 20] = a[20, 4] = 1  # states 4 and 20 are twins
    >>> plan = twin_plan(a, 5, seed=0)
    >>> plan.surrogates, plan.twins, plan.indices.shape
    (5, 2, (5, 30))
    """
    if isinstance(surrogates, bool) or not isinstance(surrogates, (int, np.integer)) or \
            surrogates < 1:
        raise ParameterError.of("surrogates", f"must be an integer >= 1, got {surrogates!r}")
    labels = twin_groups(a_y)
    m = labels.size
    counts = np.bincount(labels)
    # Members of each twin class, in one array sliced by class.
    order = np.argsort(labels, kind="stable").astype(np.int64)
    first = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    rng = np.random.default_rng(seed)
    # Every random draw is made here, so the walk is a pure function of them.
    starts = rng.integers(0, m, size=int(surrogates)).astype(np.int64)
    choices = rng.random((int(surrogates), m))
    restarts = rng.integers(0, m, size=(int(surrogates), m)).astype(np.int64)
    indices = _twin_walks(labels, counts.astype(np.int64), order, first, starts, choices,
                          restarts)
    return TwinPlan(n_states=int(m), indices=indices, twins=int(np.sum(counts[labels] > 1)))
