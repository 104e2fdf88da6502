"""Type stub of funcnet.plot: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.plot.network_diagram import (
    NO_COUPLING_EVIDENCE as NO_COUPLING_EVIDENCE,
    NetworkPieces as NetworkPieces,
    add_network_legend as add_network_legend,
    edge_evidence as edge_evidence,
    network_edges as network_edges,
    network_legend_handles as network_legend_handles,
    network_nodes as network_nodes,
    network_title as network_title,
    plot_network as plot_network,
    plot_no_network as plot_no_network,
    save_network as save_network,
)
from funcnet.plot.recurrence_plot import (
    plot_graph as plot_graph,
    plot_recurrence as plot_recurrence,
)
from funcnet.plot.signals import (
    add_signal_legend as add_signal_legend,
    plot_signals as plot_signals,
    shade_spans as shade_spans,
)
from funcnet.plot.stability_heatmap import plot_stability as plot_stability
from funcnet.plot.style import (
    BIDIRECTIONAL_COLOR as BIDIRECTIONAL_COLOR,
    DEGENERATE_COLOR as DEGENERATE_COLOR,
    DIRECTED_COLOR as DIRECTED_COLOR,
    GAP_COLOR as GAP_COLOR,
    KIND_COLORS as KIND_COLORS,
    PHASE_COLORS as PHASE_COLORS,
    SIGNAL_COLORS as SIGNAL_COLORS,
    SPAN_TITLE_PAD as SPAN_TITLE_PAD,
    glyph_markers as glyph_markers,
    phase_color as phase_color,
    signal_color as signal_color,
)
from funcnet.plot.timeline import plot_edge_timeline as plot_edge_timeline

__all__: list[str]
