"""Animation of an MDOF simulation: the blocks, the open joints, the ground motion (GIF).

The static parts (axes, labels, legend, the a_g(t) curve) are rendered once; each frame
restores that background and draws only what moves (the block polygons, the open joints,
the time marker, the title) on the Agg canvas, then maps the pixels onto one fixed
256-colour palette. Frames are taken at ``fps`` per second of simulated time (at most
``max_frames``, then spread evenly) and each is shown for the time to the next one, so the
GIF plays in real time.
The last frame is held and shows what its title says: the configuration at the last
record (after a collapse followed to rest, `rockarch animate`: where the blocks fell), with
the displacements magnified by the stated factor when they would otherwise be too small to
see.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.colors import to_rgb
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from PIL import Image
from tqdm import tqdm

from rockarch.core.console import bar_rows
from rockarch.core.paths import atomic_write
from rockarch.core.validate import in_range, integer
from rockarch.output.collapse_plots import draw_supports
from rockarch.output.figures import new_figure

if TYPE_CHECKING:
    from rockarch.mdof.simulate import MDOFResponse

#: Joint state -> colour and legend text (state 0, closed, is not drawn).
STATE_STYLE = {1: ("tab:red", "rotating about corner 0 (arch: intrados)"),
               2: ("tab:orange", "rotating about corner 1 (arch: extrados)"),
               3: ("magenta", "both corners open")}
#: Colour and legend text of a joint sliding (friction) between two frames.
SLIDE_STYLE = ("tab:blue", "sliding")
#: A joint slides in a frame if its tangential offset changed by more than this fraction of
#: the structure's size since the previous frame (and it is not open at both corners).
SLIDE_VISIBLE = 1e-4
#: Largest displacement of the held last frame, as a fraction of the structure's size.
FINAL_VISIBLE = 0.1
#: How long the last frame is held [s].
HOLD = 2.0
DPI = 100


@dataclass(frozen=True)
class FramePlan:
    """Which records become frames, how long each is shown, and the last frame's scale."""

    indices: np.ndarray
    durations_ms: np.ndarray
    magnify: float
    final_magnify: float


def _nice_floor(x: float) -> float:
    """The largest 1, 2 or 5 × 10^k not above x."""
    k = math.floor(math.log10(x))
    return max(m * 10.0**k for m in (1, 2, 5) if m * 10.0**k <= x)


def _world(resp: MDOFResponse, q: np.ndarray, body: int, pts: np.ndarray) -> np.ndarray:
    """Points (k, 2) of the assembly as built, carried by ``body`` to configuration q
    (scaled; body -1, the ground, does not move)."""
    pts = np.asarray(pts, float) * resp.scale
    if body < 0:
        return pts
    x, y, ph = q[body]
    c, s = math.cos(ph), math.sin(ph)
    rel = pts - resp.assembly.centroid[body] * resp.scale
    return np.stack([x + c * rel[:, 0] - s * rel[:, 1], y + s * rel[:, 0] + c * rel[:, 1]],
                    axis=1)


def _outlines(resp: MDOFResponse, q: np.ndarray) -> list[np.ndarray]:
    """Block outlines for the configuration ``q`` (nb, 3)."""
    a = resp.assembly
    return [_world(resp, q, a.body_of_polygon(ip), poly) for ip, poly in enumerate(a.polygons)]


def _joint_segment(resp: MDOFResponse, q: np.ndarray, k: int) -> np.ndarray:
    """Joint k's two corners in configuration q, carried by the body on the tail side of
    its normal (the lower/left one), or by the other body for a joint on the ground."""
    a = resp.assembly
    body = int(a.body_a[k]) if a.body_a[k] >= 0 else int(a.body_b[k])
    return _world(resp, q, body, a.corners[k])


def _offsets(resp: MDOFResponse, q: np.ndarray) -> np.ndarray:
    """Tangential offset of every joint with friction in configuration q (nj,): body b's
    corner 0 from body a's along a's face (docs/theory.md §9); 0 for joints that never
    slide."""
    a = resp.assembly
    out = np.zeros(a.n_joints)
    for k in np.flatnonzero(np.isfinite(a.mu)):
        ba, bb = int(a.body_a[k]), int(a.body_b[k])
        pa, pb = (_world(resp, q, j, a.corners[k, :1])[0] for j in (ba, bb))
        ph = q[ba, 2] if ba >= 0 else 0.0
        n = a.normal[k]
        tan = np.array([-(math.sin(ph) * n[0] + math.cos(ph) * n[1]),
                        math.cos(ph) * n[0] - math.sin(ph) * n[1]])
        out[k] = float(tan @ (pb - pa))
    return out


def _config(resp: MDOFResponse, i: int, magnify: float) -> np.ndarray:
    q0 = resp.q[0]
    return q0 + magnify * (resp.q[i] - q0)


def plan_frames(resp: MDOFResponse, fps: int, max_frames: int, magnify: float) -> FramePlan:
    """Frames at ``fps`` per simulated second (at most ``max_frames``), ending at the last
    record; the held last frame's magnification is ``magnify`` raised (to 1, 2 or 5 × 10^k)
    until its largest displacement is visible."""
    t = resp.t
    last = t.size - 1
    t_end = float(t[last])
    n = max(2, min(max_frames, int(math.floor(fps * t_end + 1e-9)) + 1, last + 1))
    idx = np.searchsorted(t[:last + 1], np.linspace(0.0, t_end, n))
    idx = np.unique(np.clip(idx, 0, last))
    idx[-1] = last
    dur = np.append(np.diff(t[idx]) * 1000.0, HOLD * 1000.0)
    base = np.concatenate(_outlines(resp, resp.q[0]))
    size = float(np.ptp(base, axis=0).max())
    moved = np.concatenate(_outlines(resp, resp.q[last])) - base
    disp = float(np.abs(moved).max())
    final = magnify
    if disp > 1e-12 * size and disp * magnify < FINAL_VISIBLE * size:  # else: at rest
        final = max(magnify, _nice_floor(FINAL_VISIBLE * size / disp))
    return FramePlan(idx, np.maximum(np.round(dur, -1), 20.0), magnify, final)


def _title(resp: MDOFResponse, i: int, n_open: int, magnify: float, final: bool,
           n_slide: int | None = None) -> str:
    text = f"t = {resp.t[i]:.2f} s, open joints: {n_open}"
    if n_slide is not None:
        text += f", sliding: {n_slide}"
    if final:
        if resp.overturned:
            text = (f"COLLAPSE at t = {resp.t_overturn:.3f} s (overturning criterion); "
                    f"t = {resp.t[i]:.2f} s, open joints: {n_open}")
        else:
            text += " (end, safe)"
    if magnify != 1.0:
        text += f", displacements ×{magnify:g}"
    return text


#: Most frames per second of a GIF (its frame delays are whole hundredths of a second).
MAX_FPS = 100
#: Most frames of one GIF (each frame is rendered and held compressed: ~10 kB each).
MAX_FRAMES = 10_000
#: Largest magnification of the displacements (beyond it the drawing leaves the figure).
MAX_MAGNIFY = 1e4


def check_options(fps: int, max_frames: int, magnify: float) -> None:
    """Reject frame rates outside [1, :data:`MAX_FPS`], frames outside [2,
    :data:`MAX_FRAMES`], magnifications outside [1, :data:`MAX_MAGNIFY`] (ValueError naming
    the ``rockarch animate`` option)."""
    fps, max_frames = integer("--fps", fps), integer("--frames", max_frames)
    if not 1 <= fps <= MAX_FPS:
        raise ValueError(f"--fps must lie in [1, {MAX_FPS}] (a GIF's frame delays are whole "
                         f"hundredths of a second), got {fps}")
    if not 2 <= max_frames <= MAX_FRAMES:
        raise ValueError(f"--frames must lie in [2, {MAX_FRAMES}], got {max_frames}")
    in_range("--magnify", magnify, 1.0, MAX_MAGNIFY)


class _Renderer:
    """The figure of an animation: static parts drawn once, :meth:`frame` redraws only the
    moving artists (animated=True) over the saved background and returns the pixels."""

    def __init__(self, resp: MDOFResponse, plan: FramePlan) -> None:
        self.resp = resp
        self.fig = fig = new_figure((10, 4.1), dpi=DPI)
        ax, axg = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1]})
        rest = _outlines(resp, resp.q[0])
        sup = [np.asarray(p, float) for p in resp.assembly.info.get("supports", ())]
        self.friction = bool(np.isfinite(resp.assembly.mu).any())
        self._structure_axes(ax, rest + sup, _outlines(
            resp, _config(resp, int(plan.indices[-1]), plan.final_magnify)), self.friction)
        draw_supports(ax, resp.assembly)
        self._ground_axes(axg)
        fig.subplots_adjust(left=0.07, right=0.98, top=0.9, bottom=0.25, wspace=0.25)
        # add_artist, not add_patch: the limits are set above, and add_patch's data-limit
        # update walks every curve segment (the larger part of the drawing time otherwise)
        self.patches = [ax.add_artist(Polygon(p, closed=True, fc="0.82", ec="0.25", lw=0.6,
                                              animated=True)) for p in rest]
        self.joint_lines = [ax.plot([], [], lw=3, solid_capstyle="round", animated=True)[0]
                            for _ in range(resp.assembly.n_joints)]
        self.marker = axg.axvline(0.0, color="k", lw=1, animated=True)
        self.last_offsets = _offsets(resp, resp.q[0])
        self.slide_tol = SLIDE_VISIBLE * float(np.ptp(np.concatenate(rest), axis=0).max())
        self.title = fig.suptitle("", fontsize=11, animated=True)
        fig.canvas.draw()
        self.background = fig.canvas.copy_from_bbox(fig.bbox)

    @staticmethod
    def _structure_axes(ax, rest: list[np.ndarray], last: list[np.ndarray],
                        friction: bool) -> None:
        """Limits holding the rest and the last (magnified) configuration, ground line,
        labels, the outline at rest, the legend of the joint colours (sliding: with
        friction)."""
        pts = np.concatenate([*rest, *last])
        span = float(np.ptp(pts, axis=0).max())
        lo, hi = pts.min(axis=0) - 0.15 * span, pts.max(axis=0) + 0.15 * span
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(min(lo[1], -0.05 * span), hi[1])
        ax.set_aspect("equal")
        ax.axhline(0.0, color="0.3", lw=1)
        ax.set_xlabel("x [m] (frame moving with the ground)")
        ax.set_ylabel("y [m]")
        ax.add_collection(PolyCollection(rest, closed=True, facecolors="none",
                                         edgecolors="0.65", linestyles="--", linewidths=0.5),
                          autolim=False)
        ax.legend(handles=[Line2D([], [], color=c, lw=3, label=f"joint {lab}")
                           for c, lab in [*STATE_STYLE.values(),
                                          *([SLIDE_STYLE] if friction else [])]]
                  + [Line2D([], [], color="0.65", ls="--", lw=0.8, label="at rest")],
                  loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=7,
                  frameon=False)

    def _ground_axes(self, axg) -> None:
        mot = self.resp.ground
        if mot is not None:
            tt = np.linspace(0.0, max(float(self.resp.t[-1]), 1e-9), 600)
            axg.plot(tt, np.interp(tt, mot.t, mot.a, left=0.0, right=0.0), color="tab:blue")
        axg.set_xlabel("t [s]")
        axg.set_ylabel("a_g [m/s²]")
        axg.grid(alpha=0.3)

    def frame(self, i: int, magnify: float, final: bool) -> np.ndarray:
        """RGB pixels (h, w, 3) of record i."""
        resp, canvas = self.resp, self.fig.canvas
        canvas.restore_region(self.background)
        q = _config(resp, i, magnify)
        for patch, poly in zip(self.patches, _outlines(resp, q), strict=True):
            patch.set_xy(poly)
        n_open = n_slide = 0
        offsets = _offsets(resp, resp.q[i]) if self.friction else self.last_offsets
        for k, line in enumerate(self.joint_lines):
            st = int(resp.joints[i, k])
            slides = st != 3 and abs(offsets[k] - self.last_offsets[k]) > self.slide_tol
            if st or slides:
                seg = _joint_segment(resp, q, k)
                line.set_data(seg[:, 0], seg[:, 1])
                line.set_color(SLIDE_STYLE[0] if slides else STATE_STYLE[st][0])
            n_open += bool(st)
            n_slide += slides
            line.set_visible(bool(st) or slides)
        self.last_offsets = offsets
        self.marker.set_xdata([resp.t[i], resp.t[i]])
        self.title.set_text(_title(resp, i, n_open, magnify, final,
                                   n_slide if self.friction else None))
        for artist in [*self.patches, *self.joint_lines, self.marker, self.title]:
            self.fig.draw_artist(artist)
        return np.asarray(canvas.buffer_rgba())[..., :3].copy()


def _palette(first: np.ndarray) -> Image.Image:
    """One 256-colour palette for every frame: the first frame's colours plus the joint
    colours (which it may not show yet)."""
    swatch = np.array([[int(c * 255) for c in to_rgb(col)]
                       for col, _ in [*STATE_STYLE.values(), SLIDE_STYLE]], dtype=np.uint8)
    img = first.copy()
    img[:swatch.shape[0], :1] = swatch[:, None, :]
    return Image.fromarray(img).quantize(256, method=Image.Quantize.FASTOCTREE)


def animate(resp: MDOFResponse, path: str | Path, *, fps: int = 20, max_frames: int = 150,
            magnify: float = 1.0, progress: bool | None = None) -> Path:
    """Write a GIF of an MDOF response (atomically).

    Left: the blocks (displacements in the frame moving with the ground, optionally
    magnified), open joints coloured by their state and joints sliding since the previous
    frame in blue (legend). Right: a_g(t) with the
    current time. Frames: :func:`plan_frames`. ``progress``: a progress bar on stderr
    (default: when stderr is a terminal).
    """
    check_options(fps, max_frames, magnify)
    plan = plan_frames(resp, fps, max_frames, magnify)
    renderer = _Renderer(resp, plan)
    palette = _palette(renderer.frame(0, plan.magnify, False))
    show = sys.stderr.isatty() if progress is None else progress
    n = plan.indices.size

    def frames():
        with tqdm(total=n, desc="frames", unit="frame", disable=not show,
                  file=sys.stderr, leave=False, nrows=bar_rows()) as bar:
            for k, i in enumerate(plan.indices):
                final = k == n - 1
                rgb = renderer.frame(int(i), plan.final_magnify if final else plan.magnify,
                                     final)
                bar.update(1)
                yield Image.fromarray(rgb).quantize(palette=palette, dither=Image.Dither.NONE)

    it = frames()
    head = next(it)

    def write(tmp: Path) -> None:
        head.save(tmp, format="GIF", save_all=True, append_images=it, loop=0,
                  duration=[int(d) for d in plan.durations_ms])

    return atomic_write(path, write)
