"""Figures: OAS maps (paper Fig. 2 style) and block time histories. Matplotlib, Agg backend."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

from rockarch.block import BlockResponse  # noqa: E402
from rockarch.motion import GroundMotion  # noqa: E402

SAFE_COLOR = "#f2f2f2"
UNSAFE_COLOR = "#6a9fd4"


def save_figure(fig, path) -> Path:
    """Save a figure atomically (temporary file renamed on success) and close it."""
    path = Path(path)
    if path.parent and not path.parent.exists():
        raise ValueError(f"{path.parent}: directory does not exist")
    tmp = path.with_name(f".{path.name}.part{path.suffix}")
    try:
        fig.savefig(tmp, dpi=130, bbox_inches="tight")
        tmp.replace(path)
    finally:
        plt.close(fig)
        if tmp.exists():
            tmp.unlink()
    return path


def _edges(x: np.ndarray) -> np.ndarray:
    if x.size == 1:
        return np.array([x[0] * 0.9, x[0] * 1.1])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])


def plot_oas(ds: xr.Dataset, ax=None, *, label: str | None = None, color: str = "k",
             show_map: bool = True, title: str | None = None):
    """Draw an OAS: unsafe cells shaded, the boundary as a line (paper Fig. 2).

    Returns the axes. Call several times on one axes to overlay boundaries
    (``show_map=False`` draws the boundary only).
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.6))
    p = ds["p"].values
    ratio = ds["ratio"].values
    if show_map:
        ax.pcolormesh(_edges(p), _edges(ratio), ds["overturned"].values.T.astype(float),
                      cmap=ListedColormap([SAFE_COLOR, UNSAFE_COLOR]), vmin=0, vmax=1,
                      shading="flat", rasterized=True)
    b = ds["boundary"].values
    ax.plot(p, b, "-", color=color, lw=1.6, label=label or "boundary (lowest overturning)")
    ax.set_xlabel("frequency parameter p [1/s]")
    ax.set_ylabel(r"$a_p / a_{p,\min}$")
    ax.set_xlim(_edges(p)[0], _edges(p)[-1])
    ax.set_ylim(_edges(ratio)[0], _edges(ratio)[-1])
    if show_map:
        from matplotlib.patches import Patch

        handles, labels = ax.get_legend_handles_labels()
        handles += [Patch(color=UNSAFE_COLOR, label="overturns"),
                    Patch(color=SAFE_COLOR, label="safe", ec="0.6")]
        ax.legend(handles=handles, loc="upper right", fontsize=8)
    else:
        ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title if title is not None else ds.attrs.get("title", "OAS"), fontsize=9)
    return ax


def plot_response(resp, motion: GroundMotion | None = None):
    """Normalised rotation (theta/alpha or u/delta) and a_g/ap,min over time, impacts and
    overturning marked; ``resp`` is a block or mechanism response. Returns the figure."""
    if isinstance(resp, BlockResponse):
        blk = resp.block
        t, x, ap_min = resp.t, resp.theta / blk.alpha, blk.ap_min
        ylabel = r"$\theta / \alpha$"
        title = (f"block p = {blk.p:.3g} 1/s, alpha = {blk.alpha:.4g} rad, r = {blk.r:.4f}; "
                 f"{resp.motion_name}")
        t_c, over = resp.t_overturn, resp.overturned
    else:
        mech = resp.mechanism
        level = np.where(resp.u >= 0, mech.plus.delta, mech.minus.delta)
        t, x, ap_min = resp.t, resp.u / level, mech.ap_min
        ylabel = r"$u / \delta$"
        title = f"{mech.name}, p = {resp.p:.3g} 1/s; {resp.motion_name}"
        t_c, over = resp.t_overturn, resp.overturned
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7.5, 5.2), sharex=True,
                                   gridspec_kw={"height_ratios": [2, 1]})
    ax1.plot(t, x, "k-", lw=1.0)
    ax1.axhline(1.0, color="r", ls=":", lw=0.8)
    ax1.axhline(-1.0, color="r", ls=":", lw=0.8)
    if resp.impacts:
        ax1.plot(resp.impact_times, np.zeros_like(resp.impact_times), "|", color="0.4", ms=6,
                 label=f"impacts ({resp.impacts})")
    if over:
        ax1.plot([t_c], [np.sign(x[-1])], "rx", ms=9, label=f"overturned at t = {t_c:.3f} s")
    ax1.set_ylabel(ylabel)
    ax1.set_title(title, fontsize=9)
    if resp.impacts or over:
        ax1.legend(loc="upper right", fontsize=8)
    t_end = max(resp.t_end, t[-1])
    if motion is not None:
        tt = np.concatenate([motion.t, [motion.duration, t_end]])
        aa = np.concatenate([motion.a, [0.0, 0.0]])
        ax2.plot(tt, aa / ap_min, "b-", lw=0.8)
    ax2.axhline(1.0, color="0.5", ls=":", lw=0.8)
    ax2.axhline(-1.0, color="0.5", ls=":", lw=0.8)
    ax2.set_ylabel(r"$a_g / a_{p,\min}$")
    ax2.set_xlabel("t [s]")
    ax2.set_xlim(0, t_end)
    fig.tight_layout()
    return fig


def plot_site(ds: xr.Dataset):
    """The records' OAS boundaries of a site OAS, their envelope and percentile curve."""
    fig, ax = plt.subplots(figsize=(7, 4.4))
    for k in range(ds.sizes["record"]):
        ax.plot(ds["p"].values, ds["boundary"].values[k], lw=0.8,
                label=str(ds["record_name"].values[k])[:50])
    ax.plot(ds["p"].values, ds["envelope"].values, "k-", lw=2, label="envelope")
    ax.plot(ds["p"].values, ds["characteristic"].values, "k--", lw=1.2,
            label=f"{ds.attrs['percentile']:g}th percentile")
    ax.set_xlabel("frequency parameter p [1/s]")
    ax.set_ylabel("lowest overturning ap/ap,min")
    ax.set_title(ds.attrs["title"], fontsize=9)
    ax.legend(fontsize=7)
    return fig
