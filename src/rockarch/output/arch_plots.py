"""Arch drawings: the contour, thrust line, hinges and displaced four-hinge mechanism, and the
design check's arch with its replacement catenaries.

Each drawing is a ``draw_*(ax, ...)`` function on a given axes, so a figure can combine them
(e.g. the design report adds the replacement band with :func:`draw_replacement_band`); the
``*_figure`` functions build the figures the CLI and the report write.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rockarch.arch.fourhinge import ArchMechanism, kinematics
from rockarch.output.figures import new_figure, save_figure


def _rigid(points: np.ndarray, pivot: np.ndarray, angle: float, new_pivot: np.ndarray
           ) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    r = points - pivot
    return new_pivot + np.stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]], axis=1)


def displaced_parts(res: ArchMechanism, u: float) -> list[np.ndarray]:
    """Outlines (closed polygons) of the three moving parts at rotation u (paper Sect. 5)."""
    v = res.thrust.voussoirs
    mech = res.mechanism
    k = kinematics(mech, u)
    j = mech.joints
    h = mech.hinges
    sig = np.linspace(v.sigma[j[0]], v.sigma[j[3]], 1201)
    ip, ep = v.arch.joints_at(sig)
    out = []
    pivots = [(h[0], float(k.phi[0, 0]), h[0]), (h[1], float(k.phi[1, 0]), k.h2[0]),
              (h[3], float(k.phi[2, 0]), h[3])]
    for part in range(3):
        lo, hi = v.sigma[j[part]], v.sigma[j[part + 1]]
        sel = (sig >= lo) & (sig <= hi)
        poly = np.concatenate([ip[sel], ep[sel][::-1], ip[sel][:1]])
        piv, ang, new = pivots[part]
        out.append(_rigid(poly, piv, ang, new))
    return out


def draw_arch(ax, arch, *, color: str = "0.85", edge: str = "0.4", label: str = "arch"):
    """The arch's contour, filled."""
    ip, ep = arch.joints_at(np.linspace(0.0, 1.0, 1501))
    outline = np.concatenate([ip, ep[::-1], ip[:1]])
    ax.fill(outline[:, 0], outline[:, 1], color=color, zorder=1, label=label)
    ax.plot(outline[:, 0], outline[:, 1], color=edge, lw=0.8, zorder=2)


def draw_hinges(ax, hinges, *, ms: float = 7, legend: bool = True, offset=(0.0, 0.0)
                ) -> None:
    """Hinges: white on the intrados, black on the extrados (shifted by ``offset``)."""
    for h in hinges:
        ax.plot(h.x + offset[0], h.y + offset[1], "o", ms=ms,
                mfc="white" if h.side == "intrados" else "k", mec="k", zorder=5)
    if legend:
        ax.plot([], [], "o", mfc="white", mec="k", label="hinge on intrados")
        ax.plot([], [], "o", mfc="k", mec="k", label="hinge on extrados")


def draw_thrust_line(ax, res: ArchMechanism, label: str | None = None, offset=(0.0, 0.0)
                     ) -> None:
    """The thrust line at collapse of a four-hinge analysis (shifted by ``offset``)."""
    th = res.thrust.thrust + np.asarray(offset, dtype=float)
    ax.plot(th[:, 0], th[:, 1], color="tab:red", lw=1.2, zorder=4,
            label=label or f"thrust line at collapse, ap,min = {res.ap_min:.3f} m/s²")


def _finish(ax, ncol: int) -> None:
    """Equal axes, labels, and the legend below the x label (constrained layout)."""
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.figure.legend(loc="outside lower center", ncol=ncol, fontsize=7, frameon=False)


def _figsize(arch, width: float = 8.0) -> tuple[float, float]:
    """Figure size matching the arch's aspect (no empty band above or below it)."""
    return width, max(2.0, width * 0.8 * (arch.rise + arch.thickness) / arch.span + 1.6)


def mechanism_figure(res: ArchMechanism, *, u: float | None = None):
    """The arch, its thrust line at collapse, the hinges, the mechanism displaced.

    The displaced shape is drawn half way to the neutral position (u = delta_u/2 on the
    dynamics' coordinate, docs/theory.md Eq. 5.6), unless ``u`` is given: part 1's rotation
    (the linkage's coordinate, the same as u for direction +1).
    """
    v = res.thrust.voussoirs
    arch = v.arch
    fig = new_figure(_figsize(arch), layout="constrained")
    ax = fig.subplots()
    draw_arch(ax, arch)
    if v.n <= 200:
        for a, b in zip(v.intrados, v.extrados, strict=False):
            ax.plot([a[0], b[0]], [a[1], b[1]], color="0.55", lw=0.5, zorder=2)
    draw_thrust_line(ax, res, f"thrust line, ap,min = {res.ap_min:.3f} m/s²")
    uu = 0.5 * res.delta_linkage if u is None else float(u)
    # the label on the coordinate the text output prints (delta_u), whichever the direction
    label = (f"mechanism half way to neutral, u = {0.5 * res.delta:.3g} rad" if u is None
             else f"mechanism at part 1's rotation {uu:.3g} rad")
    for i, poly in enumerate(displaced_parts(res, uu)):
        ax.plot(poly[:, 0], poly[:, 1], color="tab:blue", lw=1.0, zorder=3,
                label=label if i == 0 else None)
    draw_hinges(ax, res.hinges)
    ax.set_title(f"{arch.shape} arch l = {arch.span:g} m, f = {arch.rise:g} m: p = "
                 f"{res.p:.3f} 1/s, delta = {res.delta_end:.4f} rad (part {res.end_part}, "
                 "Table 1)", fontsize=10)
    _finish(ax, 3)
    return fig


def plot_mechanism(res: ArchMechanism, path, *, u: float | None = None) -> Path:
    """Write :func:`mechanism_figure` to ``path`` (PNG, atomically)."""
    return save_figure(mechanism_figure(res, u=u), path, dpi=120)


def draw_replacement_band(ax, result) -> None:
    """Both replacement catenaries inside the original contour, in the original's
    coordinates (the chosen rule drawn thicker and shaded), the original's springing joints
    and the replacement's springing points on them (docs/theory.md Eqs. 7.3–7.6)."""
    sig = np.linspace(0.0, 1.0, 1201)
    oi, oe = result.arch.joints_at(np.array([0.0, 1.0]))
    for k in (0, 1):
        ax.plot([oi[k, 0], oe[k, 0]], [oi[k, 1], oe[k, 1]], color="0.2", lw=1.4, zorder=3,
                label="springing joints" if k == 0 else None)
    for rep, style in ((result.replacement.lower_bound, ":"),
                       (result.replacement.equivalent, "--")):
        shift = rep.springings[0]
        ri, re_ = rep.arch.joints_at(sig)
        ri, re_ = ri + shift, re_ + shift
        chosen = rep.rule == result.rule
        lab = (f"replacement ({rep.rule}), d = {rep.thickness:.3f} m, l′ = {rep.span:.3f} m, "
               f"f′ = {rep.rise:.3f} m")
        if chosen:
            band = np.concatenate([ri, re_[::-1], ri[:1]])
            ax.fill(band[:, 0], band[:, 1], color="tab:blue", alpha=0.15, zorder=2)
        ax.plot(ri[:, 0], ri[:, 1], "b" + style, lw=1.6 if chosen else 0.9, label=lab)
        ax.plot(re_[:, 0], re_[:, 1], "b" + style, lw=1.6 if chosen else 0.9)
    pts = result.chosen.springings
    ax.plot(pts[:, 0], pts[:, 1], "s", ms=5, mfc="tab:blue", mec="k", zorder=6,
            label="replacement springings (on the springing joints)")


def design_arch_figure(result):
    """The design check's arch, both replacement catenaries with their springings, the
    chosen one's thrust line and hinges."""
    fig = new_figure(_figsize(result.arch), layout="constrained")
    ax = fig.subplots()
    draw_arch(ax, result.arch, color="0.88", edge="0.45")
    draw_replacement_band(ax, result)
    chosen = result.chosen.mechanism
    shift = result.chosen.springings[0]
    # the replacement's mechanism, not the arch's (`rockarch arch` draws the arch's own)
    draw_thrust_line(ax, chosen, offset=shift, label=(
        f"replacement's thrust line at collapse and its four hinges, ap,min = "
        f"{chosen.ap_min:.3f} m/s²"))
    draw_hinges(ax, chosen.hinges, ms=6, legend=False, offset=shift)
    _finish(ax, 2)
    return fig
