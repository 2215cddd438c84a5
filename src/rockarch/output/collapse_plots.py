"""Drawing of the static collapse mechanism of an assembly (docs/theory.md §10).

The blocks at rest (grey), the moving blocks displaced along the mechanism's virtual
velocities (coloured, magnified so that the largest displacement is a tenth of the
structure's size), the corners that open (red dots) and the joints that slide (blue).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.patches import Polygon

from rockarch.core.constants import g_label
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.statics import Collapse, collapse
from rockarch.output.figures import new_figure, save_figure


def _moved(poly: np.ndarray, centre: np.ndarray, vel: np.ndarray, s: float) -> np.ndarray:
    u, v, om = vel * s
    c, sn = math.cos(om), math.sin(om)
    rel = poly - centre
    return centre + np.array([u, v]) + rel @ np.array([[c, sn], [-sn, c]])


def draw_supports(ax, assembly: Assembly, **kw) -> None:
    """The supports given as polygons (``assembly.info["supports"]``: rigid, moving with
    the ground), hatched."""
    for poly in assembly.info.get("supports", ()):
        ax.add_patch(Polygon(np.asarray(poly, float), closed=True, fc="0.75", ec="0.3",
                             hatch="///", lw=0.6, **kw))


def collapse_figure(assembly: Assembly, mech: Collapse | None = None):
    """Figure of the collapse mechanism (default: :func:`rockarch.mdof.statics.collapse` of the
    assembly with its own friction)."""
    a = assembly
    mech = collapse(a) if mech is None else mech
    fig = new_figure((7.0, 4.2), layout="constrained")
    ax = fig.subplots()
    vel = mech.velocity
    reach = max(float(np.max(np.abs(vel[:, :2]))), 1e-12)
    span = float(np.max(np.abs(vel[:, 2]))) * a.size
    s = 0.1 * a.size / max(reach, span, 1e-12)
    moving = mech.moving
    draw_supports(ax, a)
    for ip, poly in enumerate(a.polygons):
        i = a.body_of_polygon(ip)
        poly = np.asarray(poly, float)
        ax.add_patch(Polygon(poly, closed=True, fc="0.9", ec="0.6", lw=0.6))
        if moving[i]:
            ax.add_patch(Polygon(_moved(poly, a.centroid[i], vel[i], s), closed=True,
                                 fc=(0.95, 0.6, 0.2, 0.55), ec="k", lw=0.7))
    opened = np.argwhere(mech.opening)
    if len(opened):
        pts = np.array([a.corners[k, c] for k, c in opened])
        ax.plot(pts[:, 0], pts[:, 1], "o", color="crimson", ms=5, label="opening corner")
    for n, k in enumerate(np.flatnonzero(mech.sliding)):
        ax.plot(a.corners[k, :, 0], a.corners[k, :, 1], "-", color="tab:blue", lw=3,
                label="sliding joint" if n == 0 else None)
    ax.set_aspect("equal")
    ax.autoscale_view()
    # a slender structure (a column) is not drawn as a sliver: at least 0.6 as wide as tall
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    if x1 - x0 < 0.6 * (y1 - y0):
        mid, half = 0.5 * (x0 + x1), 0.3 * (y1 - y0)
        x0, x1 = mid - half, mid + half
        ax.set_xlim(x0, x1)
    # the figure's height follows the drawing's aspect (no empty band above the legend)
    fig.set_size_inches(7.0, min(max(0.8 * 7.0 * (y1 - y0) / (x1 - x0) + 1.8, 3.0), 7.5))
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    d = "+x" if mech.direction > 0 else "-x"
    ax.set_title(f"{a.name}\ncollapse at ap,min = {mech.ap_min:.4g} m/s² = "
                 f"{mech.lambda_:.4g} g ({g_label(a.g)}; ground accelerating {d})",
                 fontsize=9)
    if len(opened) or mech.sliding.any():  # below the axes: it covers no block
        fig.legend(loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    return fig


def plot_collapse(assembly: Assembly, path, mech: Collapse | None = None) -> Path:
    """Write :func:`collapse_figure` to ``path`` (PNG)."""
    return save_figure(collapse_figure(assembly, mech), path)
