"""The study report's histogram axes: 1-2-5 ticks whose labels are distinct, exact and
inside the picture — also when every run gave the same value."""

import re

import pytest

from pliant.studies.report import axis_ticks, histogram_svg


def tick_labels(svg):
    return re.findall(r'<text class="tick" x="([-0-9.]+)"[^>]*>([^<]*)</text>', svg)


def svg_width(svg):
    return float(re.search(r'<svg width="([0-9.]+)"', svg).group(1))


@pytest.mark.parametrize("values", [[40.0] * 12, [40.0, 40.0000001, 40.0], [0.0] * 5])
def test_a_degenerate_axis_has_distinct_labels_around_its_value(values):
    svg = histogram_svg(values, "Peak hand force", "N")
    ticks = tick_labels(svg)
    labels = [label for _, label in ticks]
    assert len(labels) >= 3 and len(set(labels)) == len(labels), labels
    value = values[0]
    numbers = [float(label) for label in labels]
    assert min(numbers) < value < max(numbers), labels


@pytest.mark.parametrize("lo, hi", [(4.0213, 4.0288), (211.31, 211.94), (93.9, 281.4), (0.94, 1.0),
                                    (1e-7, 3e-7), (-3.0, 7.3)])
def test_axis_labels_are_distinct_and_read_their_tick_values(lo, hi):
    first, last, values, labels = axis_ticks(lo, hi)
    assert first <= lo and last >= hi
    assert 3 <= len(values) <= 11
    assert len(set(labels)) == len(labels), labels
    step = values[1] - values[0]
    for value, label in zip(values, labels):
        assert abs(float(label) - value) < 1e-6 * step, (value, label)


def test_tick_labels_lie_inside_the_picture():
    svg = histogram_svg([4.0213, 4.0288, 4.025], "Peak force of clip 'c1'", "N", limits=[4.03])
    width = svg_width(svg)
    for x, label in tick_labels(svg):
        half = 3.5 * len(label)  # 10-px digits are about 6 px wide: a generous half-width
        assert half <= float(x) <= width - half, (x, label, width)
