"""Static HTML reports: a study's results, a trace's inspection, the backlash trend.

Every report is one ``index.html`` with PNG figures beside it in ``figures/`` and nothing
loaded from elsewhere (no CDN, no script, no web font), so the folder can be archived, mailed or
opened offline; every file is written atomically. Each page opens with its summary and a table
of contents, then its figures; the tables come last.

====================  ==========================================================================
module                what it holds
====================  ==========================================================================
``html``              page building: escaping, tables (pairs columns from
                      :mod:`funcnet.network.schema`), figures, contents, :func:`save_figure`
``study``             :func:`write_report`: a study's results folder
``inspect``           :func:`write_inspections`: the engineer's report of one or several traces
                      (:func:`inspect_trace`: the inspection and the report in one call)
``inspect_figures``   its figures
``figure_geometry``   their fixed layouts: axes placed where their measured texts leave room
``inspect_text``      its words: the summary of a trace (its gaps, moves, turns, windows)
``backlash_page``     :func:`write_backlash_page`: the backlash diagnoses of several traces
``repetitions_page``  the repetitions' page (``inspect --repeated``)
``track_page``        :func:`write_trends`: a fleet's trend page (``funcnet track show``)
====================  ==========================================================================

The paper's demo report [1]_ is :func:`funcnet.paper.demo.build_demo_report` (the bench).

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "write_report": "funcnet.report.study_report",
    "save_figure": "funcnet.report.html",
    "inspect_trace": "funcnet.report.inspect",
    "write_inspection": "funcnet.report.inspect",
    "write_inspections": "funcnet.report.inspect",
    "write_backlash_page": "funcnet.report.backlash_page",
    "write_trends": "funcnet.report.track_page",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
