"""The study report's histograms, drawn by matplotlib: a run count per bin of one outcome,
with vertical lines at its limits, as inline SVG (text kept as text, so the page stays
small and searchable).

The axes are matplotlib's: its tick locator picks 1-2-5 steps, a degenerate range (every
run gave the same value, to six digits) is widened by 5 % around the value,
the labels are plain numbers (no offset such as "+4.02e0") and constrained layout keeps
every label inside the picture."""

from __future__ import annotations

import html
import io
from typing import Iterable, Sequence

import numpy as np

import matplotlib

matplotlib.use("Agg")  # no display: figures are only written
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.ticker import MaxNLocator, ScalarFormatter  # noqa: E402

#: The picture's size [inch] at 100 dpi: 560 × 200 pixels, as the report lays them out.
SIZE_IN = (5.6, 2.0)
BAR = "#4a7fb5"
LIMIT = "#c0392b"


def finite_values(values: Iterable) -> np.ndarray:
    """The finite numbers among ``values`` (a run without the outcome gives None or NaN)."""
    return np.asarray([x for x in values if x is not None and np.isfinite(x)], dtype=float)


def histogram_figure(values: np.ndarray, unit: str, limits: Sequence[float] = (), bins: int = 20) -> Figure:
    """The histogram of finite ``values`` (at least one) over an axis that also holds the
    ``limits``, each drawn as a labelled vertical line."""
    lo = float(min(values.min(), *limits)) if len(limits) else float(values.min())
    hi = float(max(values.max(), *limits)) if len(limits) else float(values.max())
    if hi - lo <= 1e-6 * max(abs(lo), abs(hi)):  # the same to six digits: ±5 % around it
        centre = 0.5 * (lo + hi)
        half = 0.05 * abs(centre) if centre != 0.0 else 0.05
        lo, hi = centre - half, centre + half
    fig = Figure(figsize=SIZE_IN, dpi=100, layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.hist(values, bins=bins, range=(lo, hi), color=BAR)
    for x in limits:
        ax.axvline(x, color=LIMIT, linewidth=2)
        ax.annotate(f"limit {x:.4g}", (x, 1.0), xycoords=("data", "axes fraction"), color=LIMIT, fontsize=9,
                    xytext=(3 if x <= 0.5 * (lo + hi) else -3, -10), textcoords="offset points",
                    ha="left" if x <= 0.5 * (lo + hi) else "right")
    ax.set_xlim(lo, hi)
    plain = ScalarFormatter(useOffset=False)
    ax.xaxis.set_major_formatter(plain)
    ax.yaxis.set_major_locator(MaxNLocator(nbins=4, integer=True))
    ax.set_xlabel(unit, fontsize=9)
    ax.set_ylabel("runs", fontsize=9)
    ax.tick_params(labelsize=8)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return fig


def figure_svg(fig: Figure) -> str:
    """``fig`` as an SVG element (no XML prolog), its text as text."""
    buffer = io.StringIO()
    with plt.rc_context({"svg.fonttype": "none", "svg.hashsalt": "pliant"}):
        fig.savefig(buffer, format="svg", metadata={"Date": None})
    text = buffer.getvalue()
    return text[text.index("<svg"):]


def histogram_svg(values, title: str, unit: str, limits: Sequence[float] = (), bins: int = 20) -> str:
    """A figure for the report: the histogram of ``values`` (None and NaN left out) with
    its caption, or a line saying there are no values."""
    v = finite_values(values)
    if len(v) == 0:
        return f"<p>{html.escape(title)}: no values.</p>"
    svg = figure_svg(histogram_figure(v, unit, [float(x) for x in limits], bins))
    return f"<figure>{svg}<figcaption>{html.escape(title)} ({len(v)} runs)</figcaption></figure>"
