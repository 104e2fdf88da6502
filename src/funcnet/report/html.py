"""Page building for the static HTML reports: escaping, tables, figures, the page itself.

A report is one ``index.html`` with PNG figures beside it in ``figures/`` and nothing loaded
from elsewhere (no CDN, no script, no web font). Every file is written atomically
(:mod:`funcnet._io`): a report folder never holds a half-written figure or page.
"""

from __future__ import annotations

import datetime as _dt
import html
import os
import re
import sys
from collections import Counter
from collections.abc import Callable, Iterable, Mapping
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import pandas as pd

from funcnet._io import atomic_path
from funcnet.network.schema import EVIDENCE_COLUMNS, PAIR_COLUMNS

__all__ = ["Progress", "PACKAGES", "save_figure", "escape", "table", "mapping_table",
           "provenance", "pairs_table", "figure_html", "page", "step", "contents",
           "repeated_texts", "page_processes", "PAGE_WORKERS"]

Progress = Callable[[int, int, str], None] | None
_HYPHENATED = re.compile(r"(\S*-\S*)")
#: Packages whose versions a report records.
PACKAGES = ("numpy", "numba", "scipy", "pandas", "pyarrow", "networkx", "matplotlib")

_STYLE = """
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;max-width:1240px;margin:2em auto;
padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;font-size:.82em;margin:.5em 0;max-width:100%;display:block;
overflow-x:auto}
th,td{border:1px solid #ccc;padding:2px 6px;text-align:left;vertical-align:top;
overflow-wrap:break-word;hyphens:none}
td.hash{font-family:ui-monospace,monospace;word-break:break-all;min-width:12ch}
pre{white-space:pre-wrap;overflow-wrap:anywhere}
th{background:#f3f3f3}td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #eee}
figcaption{font-size:.88em;color:#444}
.yes{background:#d9f2d9}.partly{background:#fff2c2}.no{background:#f8d4d4}.na{background:#e8e8f4}
.ne{background:#e6e6e6;font-style:italic}
details{margin:.3em 0}summary{cursor:pointer}code{font-size:.9em}
.nb{white-space:nowrap}
.note{background:#f6f6f6;border-left:4px solid #999;padding:.5em 1em}
nav.toc{background:#fafafa;border:1px solid #ddd;padding:.3em 1em;margin:1em 0}
nav.toc ol{margin:.2em 0;padding-left:1.5em;columns:2}
.verdict{background:#eef5ff;border-left:4px solid #4a78c2;padding:.5em 1em}
"""


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: int = 100) -> Path:
    """Save a matplotlib figure as PNG, atomically.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        Target file (``.png``).
    dpi : int
        Resolution.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    _settle_layout(fig, dpi)
    with atomic_path(path) as tmp:
        _write_png(fig, tmp, dpi)
    return Path(path)


def _write_png(fig: Any, path: Path, dpi: int) -> None:
    """The figure's pixels as PNG: RGB where every pixel is opaque (as the report's are).

    ``savefig`` writes the RGBA buffer; without an alpha channel that is never used zlib has a
    quarter less to compress, the same colours. zlib level 3, not PIL's 6: files ~8% larger,
    encoding ~40% faster. A figure saved at another dpi than its own, or under settings that
    change what ``savefig`` draws (a tight box, transparency, another face colour), is saved
    by ``savefig``.
    """
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    rc = matplotlib.rcParams
    if (fig.dpi != dpi or fig.get_layout_engine() is not None or rc["savefig.bbox"] is not None
            or rc["savefig.transparent"] or str(rc["savefig.facecolor"]) != "auto"
            or str(rc["savefig.edgecolor"]) != "auto"):
        fig.savefig(path, format="png", dpi=dpi, pil_kwargs={"compress_level": 3})
        return
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    # PIL reads the buffer in place and drops the alpha in C: a NumPy slice of it was copied
    # twice (a tenth of a second for a tall figure)
    image = Image.frombuffer("RGBA", canvas.get_width_height(physical=True),
                             canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
    if image.getchannel("A").getextrema() == (255, 255):
        image = image.convert("RGB")
    image.save(path, format="png", compress_level=3, dpi=(dpi, dpi))


def _settle_layout(fig: Any, dpi: int) -> None:
    """Run a figure's layout engine once and switch it off before saving.

    With a layout engine on, ``savefig`` draws the whole figure twice: a dry run (every
    artist, to run the layout first) and the pixels. The layout alone gives the same positions
    (the dry run calls it before drawing anything), so the saved pixels are the same and the
    dry run's drawing is saved (a tenth of a robot page's time). Only at the figure's own dpi,
    which the layout is computed at.
    """
    engine = fig.get_layout_engine()
    if engine is None or fig.dpi != dpi or not hasattr(engine, "execute"):
        return
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    engine.execute(fig)
    # None, not "none": "none" leaves a placeholder engine, and savefig still dry-runs for it.
    with matplotlib.rc_context({"figure.autolayout": False,
                                "figure.constrained_layout.use": False}):
        fig.set_layout_engine(None)


def page_processes(pages: int) -> Any:
    """Processes that write pages beside this one (a robot's axis pages while this one writes
    the robot's): a :class:`~concurrent.futures.ProcessPoolExecutor` of at most
    :data:`PAGE_WORKERS` processes, one per page; ``contextlib.nullcontext(None)`` (no pool:
    write them here) where fewer than two CPUs are this process's or processes cannot fork.

    Forked, not spawned: a spawned worker would import matplotlib, pandas and funcnet again (a
    few seconds each), more than a page costs. A forked child only draws (matplotlib, pandas,
    no compiled kernel of funcnet's and no thread pool of its own); the computation that used
    threads is over before the first page is drawn.

    Examples
    --------
    >>> with page_processes(1) as pool:  # one page: written here
    ...     print(pool)
    None
    """
    import contextlib
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    workers = min(PAGE_WORKERS, pages, (cpus or 1))
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return contextlib.nullcontext(None)
    _drawing_imported()
    return ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork"))


def _drawing_imported() -> None:
    """The modules a page draws with, imported here before the children fork: each child
    would import them again (half a second each)."""
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.figure  # noqa: F401
    import PIL.PngImagePlugin  # noqa: F401

    import funcnet.network.setpoint  # noqa: F401
    import funcnet.plot.network_diagram  # noqa: F401
    import funcnet.plot.signals  # noqa: F401
    import funcnet.plot.timeline  # noqa: F401
    import funcnet.study.provenance  # noqa: F401


#: The most processes that draw a robot's axis pages at once.
PAGE_WORKERS = 2


def escape(value: Any) -> str:
    """``value`` as text safe inside HTML (quotes too).

    Examples
    --------
    >>> escape('<a href="x">')
    '&lt;a href=&quot;x&quot;&gt;'
    """
    return html.escape(str(value), quote=True)


def _format(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _cells(column: Any, items: list[Any], css: Callable[[Any], str] | None) -> list[str]:
    """The ``<td>`` elements of one column's values."""
    texts = [escape(_format(v)) for v in items]
    # A hyphen is a break opportunity: "4.1-early-rp-drives" would wrap inside the word.
    texts = [_HYPHENATED.sub(r'<span class="nb">\1</span>', t) if "-" in t else t
             for t in texts]
    if css is not None:
        return [f'<td class="{css(v)}">{t}</td>' if css(v) else f"<td>{t}</td>"
                for v, t in zip(items, texts, strict=True)]
    if "sha256" in str(column):  # a long hash wraps instead of widening the page
        return [f'<td class="hash">{t}</td>' for t in texts]
    return [f'<td class="num">{t}</td>' if isinstance(v, int | float)
            and not isinstance(v, bool) else f"<td>{t}</td>"
            for v, t in zip(items, texts, strict=True)]


def table(frame: pd.DataFrame, *, classes: Mapping[str, Callable[[Any], str]] | None = None
          ) -> str:
    """A small HTML table (escaped), numbers right-aligned, hashes (``*sha256*``) wrapped.

    Examples
    --------
    >>> table(pd.DataFrame({"a": [1.5], "b": ["<x>"]})).split("<tbody>")[1]
    '<tr><td class="num">1.5</td><td>&lt;x&gt;</td></tr></tbody></table>'
    """
    classes = classes or {}
    head = "".join(f"<th>{escape(c)}</th>" for c in frame.columns)
    # every column's values as Python objects at once (a Series per column costs more)
    values = frame.to_numpy(object).T.tolist() if len(frame) else [[] for _ in frame.columns]
    columns = [_cells(c, v, classes.get(c)) for c, v in zip(frame.columns, values, strict=True)]
    rows = "".join("<tr>" + "".join(cells) + "</tr>" for cells in zip(*columns, strict=True))
    return f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"


def mapping_table(mapping: Mapping[str, Any], key: str = "name", value: str = "value") -> str:
    """A two-column table of a mapping (values as text; a value not set, None, as "—")."""
    return table(pd.DataFrame({key: list(mapping), value: ["—" if v is None else str(v)
                                                           for v in mapping.values()]}))


def provenance(items: Mapping[str, Any] | None = None, *, qualifier: str = "",
               date: _dt.datetime | None = None) -> dict[str, Any]:
    """A report's provenance: the date (UTC) and command of this run, ``items``, then the
    versions of Python, funcnet and :data:`PACKAGES`.

    ``qualifier`` tells this run's entries from others' (``"report"``: ``report date (UTC)``,
    ``report command``, ``version of numpy (report)``); ``date`` defaults to now.

    Examples
    --------
    >>> list(provenance({"trace": "t.xml"}))[:4]
    ['date (UTC)', 'command', 'trace', 'version of python']
    """
    from funcnet.study import package_versions

    before, after = (f"{qualifier} ", f" ({qualifier})") if qualifier else ("", "")
    return {
        f"{before}date (UTC)": (date or _dt.datetime.now(_dt.UTC)).isoformat(timespec="seconds"),
        f"{before}command": " ".join([Path(sys.argv[0]).name, *sys.argv[1:]]),
        **(items or {}),
        **{f"version of {k}{after}": v for k, v in package_versions(PACKAGES).items()},
    }


def pairs_table(pairs: pd.DataFrame) -> str:
    """A pairs table: the columns of :data:`funcnet.network.schema.PAIR_COLUMNS` it has.

    The schema's order, whatever the table's; then the evidence columns
    (:data:`~funcnet.network.schema.EVIDENCE_COLUMNS`) and a study's ``stability`` when they
    hold values; other columns (a study's identity and parameter columns) are left out.

    Examples
    --------
    >>> import pandas as pd
    >>> rows = pd.DataFrame({"kind": ["x->y"], "recording": ["a.xml"], "y": ["B"], "x": ["A"]})
    >>> pairs_table(rows).count("<th>"), pairs_table(rows).index("<th>x</th>") < pairs_table(
    ...     rows).index("<th>kind</th>")
    (3, True)
    """
    # direction_reason stays in the files: a sentence per pair would fill a page
    columns = [c for c in PAIR_COLUMNS if c in pairs.columns and c != "direction_reason"]
    # a network with evidence (or a study's stability): those columns too, when they hold any
    for extra in (EVIDENCE_COLUMNS, ("stability",)):
        if extra[-1] in pairs.columns and pairs[extra[-1]].notna().any():
            columns += [c for c in extra if c in pairs.columns]
    return table(pairs[columns])


def figure_html(out_dir: Path, name: str, fig: Any, caption: str) -> str:
    """Save ``fig`` as ``figures/NAME.png`` under ``out_dir``; its ``<figure>`` element."""
    save_figure(fig, out_dir / "figures" / f"{name}.png")
    return (f'<figure id="{escape(name)}"><img src="figures/{escape(name)}.png" '
            f'alt="{escape(caption)}"><figcaption>{escape(caption)}</figcaption></figure>')


def contents(sections: Iterable[tuple[str, str]]) -> str:
    """A table of contents: links to the page's sections, given as ``(id, title)``.

    Examples
    --------
    >>> contents([("summary", "Summary")])
    '<nav class="toc"><b>Contents</b><ol><li><a href="#summary">Summary</a></li></ol></nav>'
    """
    items = "".join(f'<li><a href="#{escape(key)}">{escape(title)}</a></li>'
                    for key, title in sections)
    return f'<nav class="toc"><b>Contents</b><ol>{items}</ol></nav>'


def page(title: str, body: Iterable[str]) -> str:
    """The whole HTML page: title, the inline style, ``body``'s parts in order."""
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{escape(title)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(body) + "</body></html>\n")


def step(progress: Progress, done: int, total: int, description: str) -> None:
    """Report progress, if anyone listens."""
    if progress is not None:
        progress(done, total, description)




class _Blocks(HTMLParser):
    """The text of each block of a page: a table cell, paragraph, list item, caption."""

    _BLOCKS = frozenset({"td", "th", "p", "li", "figcaption", "summary", "h1", "h2", "h3"})

    def __init__(self) -> None:
        super().__init__()
        self.blocks: list[str] = []
        self._open: list[list[str]] = []

    def handle_starttag(self, tag: str, attrs: Any) -> None:
        if tag in self._BLOCKS:
            self._open.append([])

    def handle_endtag(self, tag: str) -> None:
        if tag in self._BLOCKS and self._open:
            text = " ".join("".join(self._open.pop()).split())
            if text:
                self.blocks.append(text)

    def handle_data(self, data: str) -> None:
        if self._open:
            self._open[-1].append(data)


def repeated_texts(document: str, *, longer_than: int = 60, most: int = 2) -> dict[str, int]:
    """The texts of a page said more than ``most`` times: what a page should say once.

    Texts that differ only in their numbers count as one (every number read as ``#``): the
    same sentence with another count is the same sentence.

    Parameters
    ----------
    document : str
        An HTML page.
    longer_than : int
        Only blocks (table cells, paragraphs, list items, captions) of more characters count.
    most : int
        How often a text may appear.

    Returns
    -------
    dict
        Text -> how often, for the texts over the limit.

    Examples
    --------
    >>> cells = "".join(f"<td>{k} in continuous motion, {'x' * 40}</td>" for k in (1, 2, 3))
    >>> repeated_texts("<table><tr>" + cells + "</tr></table>")
    {'# in continuous motion, xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx': 3}
    >>> repeated_texts("<p>short</p>" * 5)
    {}
    """
    parser = _Blocks()
    parser.feed(document)
    counts = Counter(re.sub(r"\d+(\.\d+)?", "#", text) for text in parser.blocks
                     if len(text) > longer_than)
    return {text: n for text, n in counts.items() if n > most}


def setpoint_html(networks: Any) -> str:
    """How far the arrows can be trusted, first on a page: the set-point check
    (:func:`funcnet.network.setpoint_check`) of the rule's arrows and of the ``direction``
    reading over the page's networks (or pairs tables), one paragraph."""
    from funcnet.network.setpoint import setpoint_check

    tables = list(networks.values()) if isinstance(networks, Mapping) else list(networks)
    if not tables:
        return ""
    sentences = [setpoint_check(tables, column="kind").sentence()]
    if all("direction" in getattr(t, "pairs", t).columns for t in tables):
        sentences.append(setpoint_check(tables, column="direction").sentence())
        sentences.append("The drawings show the direction reading's arrows (a signal whose "
                         "past improves the other's prediction); undecided pairs are pale "
                         "lines.")
    return ('<p class="verdict" id="setpoint-check"><b>How far the arrows can be trusted.</b> '
            + escape(" ".join(sentences)) + "</p>")
