"""Drawing: functional networks, recurrence matrices, signals and edge timelines.

Everything here draws what it is given -- a network or its pairs table, a recurrence matrix, a
window of signals -- and computes nothing: no recurrence, no measure, no network. The paper's
figures, which compute their data and then draw it with these functions, are in
:mod:`funcnet.paper.figures`. Single-panel functions take ``ax=`` and return it; figure-level
helpers take a :class:`matplotlib.figure.Figure`. Everything works on the Agg backend.

==============  ===========================================================================
module          what it holds
==============  ===========================================================================
``style``       the shared conventions: colours of signals, edges, kinds and phases
``network``     networks in a circular layout, their legend, title and image file
``recurrence``  recurrence plots and the graphs of adjacency matrices
``signals``     signals over time with shaded phases or windows, the signals' legend
``timeline``    every pair's edge kind and weight over sliding windows
==============  ===========================================================================

Drawing conventions (README method step 8, paper section 3.4): nodes on a circle, one per signal,
every node drawn even without edges; directed edges black with an arrow head at the target,
bidirectional edges red; line width proportional to the weight of Eq. 13 on an absolute scale, so
that widths compare across panels (the paper reads "edges thinning as speed grows" from them).
Edges of degenerate pairs (too few distinct states: their arrow means nothing) are present only
when a network keeps them (``degenerate="keep"``); they are drawn dashed and grey.

Every drawn artist carries a ``gid`` (``"node:RP"``, ``"edge:RP->AP:directed"``,
``"phase:cruise"``, ``"window:-20 ms"``) so that tests and users can find what was drawn.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4
   and Figures 1, 2, 5, 9, 10 and 11.
"""

from __future__ import annotations

# Names the single module plot.py had (helpers included), so that no import anywhere changes.
from funcnet._io import atomic_path as atomic_path
from funcnet.errors import ParameterError as ParameterError
from funcnet.network.rule import edges_from_pairs as edges_from_pairs
from funcnet.network.schema import PAIR_KINDS as PAIR_KINDS
from funcnet.plot.network_diagram import (
    NO_COUPLING_EVIDENCE,
    add_network_legend,
    edge_evidence,
    network_edges,
    network_legend_handles,
    network_nodes,
    network_title,
    plot_network,
    plot_no_network,
    save_network,
)
from funcnet.plot.network_diagram import _network_nodes as _network_nodes
from funcnet.plot.network_diagram import _node_radius as _node_radius
from funcnet.plot.network_diagram import _trim as _trim
from funcnet.plot.recurrence_plot import plot_graph, plot_recurrence
from funcnet.plot.signals import _spans as _spans
from funcnet.plot.signals import add_signal_legend, plot_signals, shade_spans
from funcnet.plot.stability_heatmap import plot_stability
from funcnet.plot.style import _BIDIRECTIONAL as _BIDIRECTIONAL
from funcnet.plot.style import _CONFLICT as _CONFLICT
from funcnet.plot.style import _OTHER_COLORS as _OTHER_COLORS
from funcnet.plot.style import _PHASE_SHADES as _PHASE_SHADES
from funcnet.plot.style import _X_Y as _X_Y
from funcnet.plot.style import _Y_X as _Y_X
from funcnet.plot.style import (
    BIDIRECTIONAL_COLOR,
    DEGENERATE_COLOR,
    DIRECTED_COLOR,
    KIND_COLORS,
    PHASE_COLORS,
    SIGNAL_COLORS,
    SPAN_TITLE_PAD,
    phase_color,
    signal_color,
)
from funcnet.plot.style import _new_axes as _new_axes
from funcnet.plot.timeline import _pair_table as _pair_table
from funcnet.plot.timeline import _reference_weights as _reference_weights
from funcnet.plot.timeline import _window_time as _window_time
from funcnet.plot.timeline import plot_edge_timeline

__all__ = [
    "DIRECTED_COLOR",
    "BIDIRECTIONAL_COLOR",
    "DEGENERATE_COLOR",
    "SIGNAL_COLORS",
    "KIND_COLORS",
    "SPAN_TITLE_PAD",
    "PHASE_COLORS",
    "signal_color",
    "phase_color",
    "network_edges",
    "network_nodes",
    "network_legend_handles",
    "add_network_legend",
    "add_signal_legend",
    "plot_network",
    "plot_no_network",
    "plot_recurrence",
    "plot_graph",
    "plot_signals",
    "shade_spans",
    "plot_edge_timeline",
    "plot_stability",
    "network_title",
    "save_network",
    "edge_evidence",
    "NO_COUPLING_EVIDENCE",
]
