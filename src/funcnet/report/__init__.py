"""Static HTML reports: the paper's analyses [1]_ on the simulated plan, a study's results, a trace.

Every report is one ``index.html`` with PNG figures beside it in ``figures/`` and nothing
loaded from elsewhere (no CDN, no script, no web font), so the folder can be archived, mailed or
opened offline; every file is written atomically. Each page opens with its summary and a table
of contents, then its figures; the tables come last.

===================  ===========================================================================
module               what it holds
===================  ===========================================================================
``html``             page building: escaping, tables (pairs columns from
                     :mod:`funcnet.network.schema`), figures, contents, :func:`save_figure`
``demo``             :func:`build_demo_report`: :func:`funcnet.paper.run_paper_analyses` and
                     the paper's figures on a simulated plan
``study``            :func:`write_report`: a study's results folder
``inspect``          :func:`inspect_trace`: the engineer's report of one or several traces
``inspect_figures``  its figures
``inspect_text``     its words: the summary of a trace (its gaps, moves, turns, windows)
===================  ===========================================================================

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "build_demo_report": "funcnet.report.demo",
    "write_report": "funcnet.report.study_report",
    "save_figure": "funcnet.report.html",
    "inspect_trace": "funcnet.report.inspect",
    "write_inspection": "funcnet.report.inspect",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
