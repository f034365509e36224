"""The study report's histograms (matplotlib): tick labels that are distinct, read as
numbers and lie inside the picture without overlapping — for a degenerate column (every
run the same value) and for a column spanning a wide range — and the SVG embedded in the
report carries them as text."""

import re

import numpy as np
import pytest

from pliant.studies.histogram import histogram_figure, histogram_svg


def drawn_tick_labels(fig):
    """The x tick labels matplotlib drew inside the axis range, with their extents."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    lo, hi = ax.get_xlim()
    return [(t.get_text(), t.get_window_extent(renderer)) for t in ax.get_xticklabels()
            if t.get_visible() and t.get_text() and lo <= t.get_position()[0] <= hi]


def number(label):
    return float(label.replace("\u2212", "-"))


def assert_readable(fig):
    labels = drawn_tick_labels(fig)
    texts = [t for t, _ in labels]
    assert len(texts) >= 3 and len(set(texts)) == len(texts), texts
    box = fig.bbox
    for text, extent in labels:
        assert box.x0 <= extent.x0 and extent.x1 <= box.x1, (text, extent, box)
        assert box.y0 <= extent.y0 and extent.y1 <= box.y1, (text, extent, box)
    for (a, ea), (b, eb) in zip(labels, labels[1:]):
        assert ea.x1 <= eb.x0, f"labels {a} and {b} overlap"
    return [number(t) for t in texts]


@pytest.mark.parametrize("values", [[40.0] * 12, [40.0, 40.0000001, 40.0], [0.0] * 5])
def test_a_degenerate_column_has_distinct_labels_around_its_value(values):
    numbers = assert_readable(histogram_figure(np.array(values), "N"))
    assert min(numbers) < values[0] < max(numbers), numbers


@pytest.mark.parametrize("values, limits", [([93.9, 281.4, 150.0], [131.0]), ([0.5, 2.0e6], [1.0]),
                                            ([4.0213, 4.0288, 4.025], [4.03]), ([1e-7, 3e-7], [])])
def test_a_wide_or_narrow_column_has_distinct_unclipped_labels(values, limits):
    fig = histogram_figure(np.array(values), "N", limits)
    numbers = assert_readable(fig)
    # the ticks span the values and the limits, read with the axis' multiplier (1e6, 1e-7)
    multiplier = fig.axes[0].xaxis.get_offset_text().get_text()
    scale = number(multiplier) if multiplier else 1.0
    lo, hi = min(values + limits), max(values + limits)
    assert min(numbers) * scale <= lo + 0.3 * (hi - lo)
    assert max(numbers) * scale >= hi - 0.3 * (hi - lo)


def test_the_embedded_svg_carries_the_labels_as_text():
    page = histogram_svg([40.0] * 12 + [None, float("nan")], "Peak hand force", "N", limits=[41.0])
    assert page.startswith("<figure><svg") and "(12 runs)</figcaption>" in page
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", page)
    assert "limit 41" in texts
    ticks = [t for t in texts if re.fullmatch(r"[\u2212-]?[0-9.]+", t)]
    assert len(set(ticks)) >= 3, texts
    assert histogram_svg([None], "Nothing", "N") == "<p>Nothing: no values.</p>"
