"""Saving a report figure: the layout run once before saving gives the pixels of matplotlib's
own two-pass save."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from funcnet.report.html import save_figure


def _figure() -> Figure:
    fig = Figure(figsize=(6.0, 4.0), layout="constrained")
    axes = fig.subplots(2, 2)
    x = np.linspace(0.0, 10.0, 200)
    for k, ax in enumerate(axes.flat):
        ax.plot(x, np.sin(x * (k + 1)), label=f"signal {k}")
        ax.set_title(f"a rather long title number {k}")
        ax.set_ylabel("amplitude [unit]")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.suptitle("four panels")
    return fig


def test_saved_pixels_equal_matplotlibs_two_pass_save(tmp_path):
    ours = save_figure(_figure(), tmp_path / "ours.png")
    reference = tmp_path / "reference.png"
    _figure().savefig(reference, format="png", dpi=100, pil_kwargs={"compress_level": 3})
    assert ours.read_bytes() == reference.read_bytes()


def test_a_figure_at_another_dpi_keeps_its_layout_engine(tmp_path):
    fig = _figure()
    save_figure(fig, tmp_path / "big.png", dpi=150)
    assert fig.get_layout_engine() is not None  # saved by matplotlib's own path
    fig = _figure()
    save_figure(fig, tmp_path / "plain.png")
    assert fig.get_layout_engine() is None
