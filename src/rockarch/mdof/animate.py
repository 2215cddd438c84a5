"""Animation of an MDOF simulation: the blocks, the open joints, the ground motion."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rockarch.mdof.simulate import MDOFResponse

_STATE_COLOR = {1: "tab:red", 2: "tab:orange", 3: "magenta"}


def _joint_segment(resp: MDOFResponse, i: int, k: int) -> np.ndarray:
    """The joint's two corners at record i, carried by its lower/left body (ground fixed)."""
    a = resp.assembly
    corners = a.corners[k] * resp.scale
    body = k - 1 if k >= 1 else (k if k < a.n_blocks else -1)
    if body < 0 or body >= a.n_blocks:
        return corners
    x, y, ph = resp.q[i, body]
    c, s = math.cos(ph), math.sin(ph)
    rel = corners - a.centroid[body] * resp.scale
    return np.stack([x + c * rel[:, 0] - s * rel[:, 1], y + s * rel[:, 0] + c * rel[:, 1]],
                    axis=1)


def animate(resp: MDOFResponse, path: str | Path, *, fps: int = 20, max_frames: int = 150,
            magnify: float = 1.0) -> Path:
    """Write a GIF of the response (matplotlib's PillowWriter).

    Left: the blocks (displacements in the frame moving with the ground, optionally
    magnified), open joints in colour (red: rotating about corner 0 — the intrados of an
    arch —, orange: about corner 1, magenta: both corners open). Right: a_g(t) with the
    current time. ``max_frames`` frames at most, evenly spread over the record.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter
    from matplotlib.patches import Polygon

    path = Path(path)
    if not path.resolve().parent.is_dir():
        raise ValueError(f"{path.parent}: directory does not exist")
    if fps < 1 or max_frames < 2:
        raise ValueError("fps must be >= 1 and max_frames >= 2")
    if not (math.isfinite(magnify) and magnify >= 1):
        raise ValueError(f"magnify must be >= 1, got {magnify}")
    a = resp.assembly
    n_rec = resp.t.size
    frames = np.unique(np.linspace(0, n_rec - 1, min(max_frames, n_rec)).astype(int))
    q0 = resp.q[0]

    def outlines(i):
        if magnify == 1.0:
            return resp.corners_at(i)
        q_save = resp.q[i].copy()
        resp.q[i] = q0 + magnify * (q_save - q0)
        try:
            return resp.corners_at(i)
        finally:
            resp.q[i] = q_save

    fig, (ax, axg) = plt.subplots(1, 2, figsize=(10, 4.2),
                                  gridspec_kw={"width_ratios": [1.6, 1]})
    base = outlines(0)
    allpts = np.concatenate(base)
    span = np.ptp(allpts, axis=0).max()
    lo = allpts.min(axis=0) - 0.25 * span
    hi = allpts.max(axis=0) + 0.25 * span
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(min(lo[1], -0.05 * span), hi[1])
    ax.set_aspect("equal")
    ax.axhline(0.0, color="0.3", lw=1)
    patches = [ax.add_patch(Polygon(p, closed=True, fc="0.82", ec="0.25", lw=0.6))
               for p in base]
    joint_lines = [ax.plot([], [], lw=3, solid_capstyle="round")[0]
                   for _ in range(a.n_joints)]
    title = ax.set_title("")
    ax.set_xlabel("x [m] (frame moving with the ground)" +
                  (f", displacements ×{magnify:g}" if magnify != 1 else ""))
    mot = resp.ground
    t_end = resp.t[-1]
    if mot is not None:
        tt = np.linspace(0.0, max(t_end, 1e-9), 600)
        axg.plot(tt, np.interp(tt, mot.t, mot.a, left=0.0, right=0.0), color="tab:blue")
    axg.set_xlabel("t [s]")
    axg.set_ylabel("a_g [m/s²]")
    axg.grid(alpha=0.3)
    marker = axg.axvline(0.0, color="k", lw=1)
    fig.tight_layout()

    def update(fi):
        i = frames[fi]
        for patch, poly in zip(patches, outlines(i), strict=True):
            patch.set_xy(poly)
        n_open = 0
        for k, line in enumerate(joint_lines):
            st = int(resp.joints[i, k])
            if st:
                seg = _joint_segment(resp, i, k)
                if magnify != 1.0:
                    seg = a.corners[k] * resp.scale + magnify * (seg - a.corners[k] * resp.scale)
                line.set_data(seg[:, 0], seg[:, 1])
                line.set_color(_STATE_COLOR[st])
                n_open += 1
            else:
                line.set_data([], [])
        marker.set_xdata([resp.t[i], resp.t[i]])
        status = ""
        if resp.overturned and resp.t[i] >= (resp.t_overturn or np.inf) - 1e-9:
            status = "  COLLAPSE"
        title.set_text(f"t = {resp.t[i]:.2f} s, open joints: {n_open}{status}")
        return [*patches, *joint_lines, marker, title]

    anim = FuncAnimation(fig, update, frames=len(frames), blit=False)
    anim.save(str(path), writer=PillowWriter(fps=fps))
    plt.close(fig)
    return path
