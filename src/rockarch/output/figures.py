"""Figures: the canvas helpers every figure uses, OAS maps (paper Fig. 2 style), time
histories and site OAS curves.

Figures are :class:`matplotlib.figure.Figure` objects on an Agg canvas created here, never
through ``pyplot``: the backend of an interactive session (Jupyter, an IDE) is untouched.
Show one in a notebook with ``display(fig)`` or by returning it from a cell.
"""

from __future__ import annotations

import io
import textwrap
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from rockarch.core.paths import atomic_write

SAFE_COLOR = "#f2f2f2"
UNSAFE_COLOR = "#6a9fd4"
DPI = 130


def new_figure(figsize: tuple[float, float] = (6.4, 4.6), **kwargs) -> Figure:
    """A figure on its own Agg canvas (no pyplot, no global state)."""
    fig = Figure(figsize=figsize, **kwargs)
    FigureCanvasAgg(fig)
    return fig


def subplots(nrows: int = 1, ncols: int = 1, *, figsize=(6.4, 4.6), **kwargs):
    """``(fig, axes)`` like ``pyplot.subplots`` but on :func:`new_figure`."""
    fig = new_figure(figsize)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def save_figure(fig: Figure, path, *, dpi: int = DPI) -> Path:
    """Save a figure atomically (format from the extension), cropped to its content."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    return atomic_write(path, lambda tmp: fig.savefig(tmp, format=fmt, dpi=dpi,
                                                      bbox_inches="tight"))


def png_bytes(fig: Figure, *, dpi: int = 110) -> bytes:
    """The figure as PNG bytes (cropped to its content), e.g. to inline in HTML."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    return buf.getvalue()


def _edges(x: np.ndarray) -> np.ndarray:
    if x.size == 1:
        return np.array([x[0] * 0.9, x[0] * 1.1])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])


def plot_oas(ds: xr.Dataset, ax=None, *, label: str | None = None, color: str = "k",
             show_map: bool = True, title: str | None = None):
    """Draw an OAS: unsafe cells shaded, the boundary as a line (paper Fig. 2).

    Returns the axes (a new figure's unless ``ax`` is given; ``ax.figure`` is the figure).
    Call several times on one axes to overlay boundaries (``show_map=False`` draws the
    boundary only).
    """
    if ax is None:
        ax = new_figure((6.4, 4.6)).subplots()
    p = ds["p"].values
    ratio = ds["ratio"].values
    if show_map:
        ax.pcolormesh(_edges(p), _edges(ratio), ds["overturned"].values.T.astype(float),
                      cmap=ListedColormap([SAFE_COLOR, UNSAFE_COLOR]), vmin=0, vmax=1,
                      shading="flat", rasterized=True)
    b = ds["boundary"].values
    ax.plot(p, b, "-", color=color, lw=1.6, label=label or "boundary (lowest overturning)")
    ax.set_xlabel("frequency parameter p [1/s]")
    ax.set_ylabel(r"$a_p / a_{p,\min}$ [-]")
    ax.set_xlim(_edges(p)[0], _edges(p)[-1])
    ax.set_ylim(_edges(ratio)[0], _edges(ratio)[-1])
    handles, _ = ax.get_legend_handles_labels()
    if show_map:
        handles += [Patch(color=UNSAFE_COLOR, label="overturns"),
                    Patch(color=SAFE_COLOR, label="safe", ec="0.6")]
    ax.legend(handles=handles, loc="upper right", fontsize=8)
    ax.set_title(title if title is not None else ds.attrs.get("title", "OAS"), fontsize=9)
    return ax


def _history(resp) -> tuple[np.ndarray, np.ndarray, float, str, str]:
    """(t, normalised rotation, ap,min, y label, title) of a block, mechanism or MDOF
    response. For MDOF the rotation is the largest block rotation over the reference
    mechanism's delta (the measure of ``max_rotation_ratio``)."""
    if hasattr(resp, "assembly"):
        a = resp.assembly
        x = np.abs(resp.q[:, :, 2]).max(axis=1) / a.delta_ref
        return (resp.t, x, a.ap_min, r"$\max_j |\varphi_j| / \delta$ [-]",
                f"{a.name}: {a.n_blocks} block{'s' if a.n_blocks != 1 else ''}; "
                f"{resp.motion_name}")
    if hasattr(resp, "block"):
        blk = resp.block
        title = (f"block p = {blk.p:.3g} 1/s, alpha = {blk.alpha:.4g} rad, r = {blk.r:.4f}; "
                 f"{resp.motion_name}")
        return resp.t, resp.theta / blk.alpha, blk.ap_min, r"$\theta / \alpha$ [-]", title
    mech = resp.mechanism
    level = np.where(resp.u >= 0, mech.plus.delta, mech.minus.delta)
    title = f"{mech.name}, p = {resp.p:.3g} 1/s; {resp.motion_name}"
    return resp.t, resp.u / level, mech.ap_min, r"$u / \delta$ [-]", title


#: Points per line of a time-history figure: longer histories are drawn by their minimum
#: and maximum in as many bins (what a figure a few thousand pixels wide can show).
DISPLAY_BINS = 5000


def for_display(t: np.ndarray, y: np.ndarray, bins: int = DISPLAY_BINS
                ) -> tuple[np.ndarray, np.ndarray]:
    """A long line (t, y) reduced to the minimum and maximum of y in each of ``bins`` equal
    runs of samples, in time order: the drawn envelope is the same, the figure's memory
    is not that of 5e6 points (docs/limits.md)."""
    n = t.size
    if n <= 4 * bins:
        return t, y
    edges = np.linspace(0, n, bins + 1).astype(np.int64)
    i_lo = np.array([s + int(np.argmin(y[s:e])) for s, e in zip(edges[:-1], edges[1:],
                                                                  strict=True)])
    i_hi = np.array([s + int(np.argmax(y[s:e])) for s, e in zip(edges[:-1], edges[1:],
                                                                  strict=True)])
    first = i_lo <= i_hi
    idx = np.empty(2 * bins, dtype=np.int64)
    idx[0::2] = np.where(first, i_lo, i_hi)
    idx[1::2] = np.where(first, i_hi, i_lo)
    return t[idx], y[idx]


def plot_response(resp, motion=None) -> Figure:
    """Normalised rotation (theta/alpha or u/delta) and a_g/ap,min over time, impacts and
    overturning marked; ``resp`` is a block, mechanism or MDOF response (one that slid: its
    largest joint slip, :meth:`rockarch.mdof.MDOFResponse.slip`, between the two). Returns
    the figure."""
    t, x, ap_min, ylabel, title = _history(resp)
    slid = getattr(resp, "sliding_contacts_max", 0) > 0  # MDOF with friction, and it slid
    fig = new_figure((7.5, 6.6 if slid else 5.2))
    if slid:
        ax1, ax3, ax2 = fig.subplots(3, 1, sharex=True,
                                     gridspec_kw={"height_ratios": [2, 1, 1]})
        ax3.plot(*for_display(t, 1e3 * resp.slip()), "g-", lw=1.0)
        ax3.set_ylabel("largest joint\nslip [mm]")
    else:
        ax1, ax2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    ax1.plot(*for_display(t, x), "k-", lw=1.0)
    ax1.axhline(1.0, color="r", ls=":", lw=0.8)
    if x.min() < 0:  # signed rotation (block, SDOF mechanism); the MDOF measure is >= 0
        ax1.axhline(-1.0, color="r", ls=":", lw=0.8)
    if resp.impacts and hasattr(resp, "impact_times"):
        ax1.plot(resp.impact_times, np.zeros_like(resp.impact_times), "|", color="0.4", ms=6,
                 label=f"impacts ({resp.impacts})")
    t_end = max(resp.t_end, t[-1])
    if resp.overturned:  # drawn whole where it ends the axes (a history stops at overturning)
        ax1.plot([resp.t_overturn], [np.interp(resp.t_overturn, t, x)], "rx", ms=9,
                 clip_on=False, label=f"overturned at t = {resp.t_overturn:.3f} s")
    ax1.set_ylabel(ylabel)
    ax1.set_title(title, fontsize=9)
    if ax1.get_legend_handles_labels()[0]:  # an MDOF response has impacts but no times
        # in the upper corner away from the red x (at the top right when the history ends
        # at overturning, the legend's corner before)
        right = resp.overturned and resp.t_overturn > 0.5 * t_end
        ax1.legend(loc="upper left" if right else "upper right", fontsize=8)
    if motion is not None:
        tt = np.concatenate([motion.t, [motion.duration, t_end]])
        aa = np.concatenate([motion.a, [0.0, 0.0]])
        ax2.plot(*for_display(tt, aa / ap_min), "b-", lw=0.8)
    ax2.axhline(1.0, color="0.5", ls=":", lw=0.8)
    ax2.axhline(-1.0, color="0.5", ls=":", lw=0.8)
    ax2.set_ylabel(r"$a_g / a_{p,\min}$ [-]")
    ax2.set_xlabel("t [s]")
    ax2.set_xlim(0, t_end)
    fig.tight_layout()
    return fig


def record_label(name: str, width: int = 60) -> str:
    """A record's name for a legend: whole, wrapped on lines of ``width`` characters."""
    return "\n".join(textwrap.wrap(str(name), width)) or "?"


#: Largest number of records named one by one in a site figure's legend.
MAX_NAMED_RECORDS = 12


def plot_site(ds: xr.Dataset) -> Figure:
    """The records' OAS boundaries of a site OAS, their envelope and percentile curve.

    The legend sits below the axes and holds every record's full name (wrapped, never cut);
    above :data:`MAX_NAMED_RECORDS` records they are thin grey lines with one entry.
    """
    fig = new_figure((7.5, 4.6))
    ax = fig.subplots()
    p = ds["p"].values
    n = ds.sizes["record"]
    for k in range(n):
        if n <= MAX_NAMED_RECORDS:
            ax.plot(p, ds["boundary"].values[k], lw=0.8,
                    label=record_label(ds["record_name"].values[k]))
        else:
            ax.plot(p, ds["boundary"].values[k], lw=0.6, color="0.65",
                    label=f"{n} records" if k == 0 else None)
    env, char = ds["envelope"].values, ds["characteristic"].values
    pct = f"{ds.attrs['percentile']:g}th percentile"
    if np.array_equal(env, char, equal_nan=True):  # e.g. the 50th of two records: one line
        ax.plot(p, env, "k-", lw=2, label=f"envelope (= the {pct})")
    else:  # the percentile drawn over the envelope, visible where they coincide
        ax.plot(p, env, "k-", lw=2, label="envelope")
        ax.plot(p, char, "--", color="C3", lw=1.4, label=pct, zorder=3)
    safe = ~np.isfinite(env)  # no record overturns the block within the ratio range
    if safe.any() and "ratio" in ds:
        top = float(ds["ratio"].values[-1])
        ax.plot(p[safe], np.full(int(safe.sum()), top), "^", color="0.3", ms=4,
                label=f"no record overturns up to ap/ap,min = {top:g}")
    ax.set_xlim(p[0], p[-1])
    ax.set_xlabel("frequency parameter p [1/s]")
    ax.set_ylabel("lowest overturning ap/ap,min [-]")
    ax.set_title(ds.attrs["title"], fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              ncol=1 if n <= 6 else 2, frameon=False)
    return fig
