"""Figures that compare OAS boundaries (the lowest overturning ap/ap,min over p) of several
structures: the paper's hypotheses and Fig. 19 (:mod:`rockarch.paper.results`), the background
figures 2 and 3 (:mod:`rockarch.paper.background`). The modules that compute the curves hand
over :class:`Panel` grids; the drawing lives here only.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rockarch.output.figures import save_figure, subplots

#: The y label of every boundary panel.
BOUNDARY_LABEL = r"lowest overturning $a_p/a_{p,\min}$ [-]"


@dataclass(frozen=True)
class Curve:
    """One boundary over p; non-finite values (no overturning in range) are left blank.

    ``fmt`` is a matplotlib format string ("k--"), ``style`` more line keywords.
    """

    label: str
    p: np.ndarray
    boundary: np.ndarray
    fmt: str = "-"
    style: dict = field(default_factory=lambda: {"lw": 1.5})


@dataclass(frozen=True)
class Panel:
    """One axes: a title and its curves."""

    title: str
    curves: Sequence[Curve]


def plot_boundaries(panels: Sequence[Sequence[Panel]], path: str | Path, *,
                    xlabel: str = "p [1/s]", suptitle: str | None = None,
                    panel_size: tuple[float, float] = (6.0, 4.4),
                    ylim: tuple[float, float] | None = (1.0, 8.0)) -> Path:
    """Draw a grid of boundary panels (rows of :class:`Panel`) and write it to ``path``.

    Axes share x and y; labels sit on the outer axes, and the legend on the first panel
    when every panel shows the same curves (else on each).
    """
    nrows, ncols = len(panels), max(len(row) for row in panels)
    fig, axes = subplots(nrows, ncols, figsize=(panel_size[0] * ncols, panel_size[1] * nrows),
                         sharex=True, sharey=True, squeeze=False)
    labels = {tuple(c.label for c in panel.curves) for row in panels for panel in row}
    for i, row in enumerate(panels):
        for j, panel in enumerate(row):
            ax = axes[i, j]
            for c in panel.curves:
                b = np.asarray(c.boundary, dtype=float)
                ax.plot(c.p, np.where(np.isfinite(b), b, np.nan), c.fmt, label=c.label,
                        **c.style)
            ax.set_title(panel.title, fontsize=9)
            ax.grid(alpha=0.3)
            if ylim is not None:
                ax.set_ylim(*ylim)
            if i == nrows - 1:
                ax.set_xlabel(xlabel)
            if j == 0:
                ax.set_ylabel(BOUNDARY_LABEL)
            if len(labels) > 1 or (i, j) == (0, 0):
                ax.legend(fontsize=8)
    if suptitle is not None:
        fig.suptitle(suptitle, fontsize=11)
    fig.tight_layout()
    return save_figure(fig, path)


def plot_regions(maps: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray, np.ndarray]],
                 path: str | Path) -> Path:
    """Overturned regions side by side (paper Fig. 2): each map is (title, p, ratio,
    overturned[p, ratio], boundary[p]); grey where the structure overturns."""
    fig, axes = subplots(1, len(maps), figsize=(6.0 * len(maps), 4.4), squeeze=False)
    for ax, (title, p, ratio, over, boundary) in zip(axes[0], maps, strict=True):
        ax.pcolormesh(p, ratio, np.asarray(over).T, cmap="Greys", vmin=0, vmax=1.6,
                      shading="nearest")
        ax.plot(p, boundary, "r-", lw=1.2, label="lowest overturning ratio")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("p [1/s]")
        ax.set_ylabel(r"$a_p/a_{p,\min}$ [-]")
        ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    return save_figure(fig, path)
