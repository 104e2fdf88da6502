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


def _pixels(path):
    from PIL import Image

    with Image.open(path) as image:
        return image.mode, np.asarray(image)


def test_saved_pixels_equal_matplotlibs_two_pass_save(tmp_path):
    ours = save_figure(_figure(), tmp_path / "ours.png")
    reference = tmp_path / "reference.png"
    _figure().savefig(reference, format="png", dpi=100)
    mode, pixels = _pixels(ours)
    reference_mode, expected = _pixels(reference)
    # every pixel opaque: saved without the alpha channel, the same colours
    assert (mode, reference_mode) == ("RGB", "RGBA")
    assert (expected[..., 3] == 255).all()
    np.testing.assert_array_equal(pixels, expected[..., :3])


def test_a_figure_with_transparent_pixels_keeps_its_alpha(tmp_path):
    fig = Figure(figsize=(2.0, 2.0))
    fig.patch.set_alpha(0.0)
    fig.add_axes((0.2, 0.2, 0.6, 0.6)).plot([0, 1], [0, 1])
    mode, pixels = _pixels(save_figure(fig, tmp_path / "clear.png"))
    assert mode == "RGBA"
    assert pixels[0, 0, 3] == 0 and (pixels[..., 3] == 255).any()


def test_a_figure_at_another_dpi_keeps_its_layout_engine(tmp_path):
    fig = _figure()
    save_figure(fig, tmp_path / "big.png", dpi=150)
    assert fig.get_layout_engine() is not None  # saved by matplotlib's own path
    fig = _figure()
    save_figure(fig, tmp_path / "plain.png")
    assert fig.get_layout_engine() is None
