"""Figures of a record suite: response spectra of its records (``rockarch records info
--plot``). Agg canvases of :mod:`rockarch.output.figures` (no pyplot state)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rockarch.motion import intensity as im
from rockarch.motion.suite import Suite
from rockarch.output.figures import subplots

#: Periods of the plotted spectra [s].
PLOT_PERIODS = np.geomspace(0.05, 5.0, 60)


def plot_spectra(suite: Suite, periods: Sequence[float] = PLOT_PERIODS, *,
                 damping: float = im.DAMPING, normalise: bool = True, ax=None,
                 band: tuple[float, float] = (16.0, 84.0), max_labels: int = 8):
    """Sa(T) of every record (Sa/PGA if ``normalise``), their median and a percentile band.

    A suite of up to ``max_labels`` records has each record coloured and labelled; a larger
    one has them in thin grey. Returns the figure.
    """
    per = np.asarray(periods, dtype=float)
    sa = np.array([im.spectral_acceleration(m, per, damping) / (m.pga if normalise else 1.0)
                   for m in suite.motions])
    if ax is None:
        fig, ax = subplots(figsize=(6.5, 4.2))
    else:
        fig = ax.figure
    if len(suite) > 1:
        lo, hi = np.percentile(sa, band, axis=0)
        ax.fill_between(per, lo, hi, color="C0", alpha=0.2,
                        label=f"{band[0]:g}–{band[1]:g} % of {len(suite)} records")
        ax.plot(per, np.median(sa, axis=0), color="C0", lw=2, label="median")
    labelled = len(suite) <= max_labels
    for k, (name, row) in enumerate(zip(suite.names, sa, strict=True)):
        if labelled:
            ax.plot(per, row, lw=0.9, color=f"C{k % 9 + 1}", label=name[:32])
        else:
            ax.plot(per, row, lw=0.4, color="0.6", zorder=0,
                    label="records" if k == 0 else None)
    ax.set_xscale("log")
    ax.set_xlabel("T [s]")
    ax.set_ylabel(f"Sa{' / PGA' if normalise else ' [m/s²]'} ({100 * damping:g} % damping)")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    return fig
