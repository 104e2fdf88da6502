"""Drawing: functional networks, recurrence matrices, signals and edge timelines.

Everything here draws what it is given -- a network, a recurrence matrix, a
window of signals -- and computes nothing: no recurrence, no measure, no network. The paper's
figures, which compute their data and then draw it with these functions, are in
:mod:`funcnet.paper.figures`. Single-panel functions take ``ax=`` and return it; figure-level
helpers take a :class:`matplotlib.figure.Figure`. Everything works on the Agg backend.

=====================  ====================================================================
module                 what it holds
=====================  ====================================================================
``style``              the shared conventions: colours of signals, edges, kinds and phases
``network_diagram``    networks in a circular layout, their legend, title and image file
``recurrence_plot``    recurrence plots and the graphs of adjacency matrices
``signals``            signals over time with shaded phases or windows, the signals' legend
``timeline``           every pair's edge kind and weight over sliding windows
``stability_heatmap``  each pair's stability over a settings grid, as a heatmap
=====================  ====================================================================

Drawing conventions (docs/guide/method.md step 8, paper section 3.4 [1]_): nodes on a circle,
one per signal, every node drawn even without edges; directed edges black with an arrow head at
the target, bidirectional edges red; line width proportional to the weight of Eq. 13 on an
absolute scale, so that widths compare across panels (the paper reads "edges thinning as speed
grows" from them).
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

from funcnet._lazy import attach

_EXPORTS = {
    "DIRECTED_COLOR": "funcnet.plot.style",
    "BIDIRECTIONAL_COLOR": "funcnet.plot.style",
    "DEGENERATE_COLOR": "funcnet.plot.style",
    "SIGNAL_COLORS": "funcnet.plot.style",
    "KIND_COLORS": "funcnet.plot.style",
    "SPAN_TITLE_PAD": "funcnet.plot.style",
    "PHASE_COLORS": "funcnet.plot.style",
    "GAP_COLOR": "funcnet.plot.style",
    "signal_color": "funcnet.plot.style",
    "phase_color": "funcnet.plot.style",
    "glyph_markers": "funcnet.plot.style",
    "network_edges": "funcnet.plot.network_diagram",
    "network_nodes": "funcnet.plot.network_diagram",
    "network_legend_handles": "funcnet.plot.network_diagram",
    "add_network_legend": "funcnet.plot.network_diagram",
    "add_signal_legend": "funcnet.plot.signals",
    "plot_network": "funcnet.plot.network_diagram",
    "plot_no_network": "funcnet.plot.network_diagram",
    "plot_recurrence": "funcnet.plot.recurrence_plot",
    "plot_graph": "funcnet.plot.recurrence_plot",
    "plot_signals": "funcnet.plot.signals",
    "shade_spans": "funcnet.plot.signals",
    "plot_edge_timeline": "funcnet.plot.timeline",
    "plot_stability": "funcnet.plot.stability_heatmap",
    "network_title": "funcnet.plot.network_diagram",
    "save_network": "funcnet.plot.network_diagram",
    "edge_evidence": "funcnet.plot.network_diagram",
    "NO_COUPLING_EVIDENCE": "funcnet.plot.network_diagram",
    "NetworkPieces": "funcnet.plot.network_diagram",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
