"""Figure of an arch at collapse: contour, thrust line, hinges, displaced four-hinge mechanism."""

from __future__ import annotations

import numpy as np

from rockarch.arch.fourhinge import ArchMechanism, kinematics


def _rigid(points: np.ndarray, pivot: np.ndarray, angle: float, new_pivot: np.ndarray
           ) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    r = points - pivot
    return new_pivot + np.stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]], axis=1)


def displaced_parts(res: ArchMechanism, u: float) -> list[np.ndarray]:
    """Outlines (closed polygons) of the three moving parts at rotation u (Sect. 5)."""
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


def plot_mechanism(res: ArchMechanism, path: str, *, u: float | None = None) -> None:
    """Save a PNG: the arch, its thrust line at collapse, the hinges, the mechanism displaced.

    The displaced shape is drawn at u = delta/2 (half way to the neutral position) unless
    ``u`` is given.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = res.thrust.voussoirs
    arch = v.arch
    sig = np.linspace(0.0, 1.0, 1501)
    ip, ep = arch.joints_at(sig)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    outline = np.concatenate([ip, ep[::-1], ip[:1]])
    ax.fill(outline[:, 0], outline[:, 1], color="0.85", zorder=1, label="arch")
    ax.plot(outline[:, 0], outline[:, 1], color="0.4", lw=0.8, zorder=2)
    if v.n <= 200:
        for a, b in zip(v.intrados, v.extrados, strict=False):
            ax.plot([a[0], b[0]], [a[1], b[1]], color="0.55", lw=0.5, zorder=2)
    ax.plot(res.thrust.thrust[:, 0], res.thrust.thrust[:, 1], color="tab:red", lw=1.2,
            zorder=4, label=f"thrust line, ap,min = {res.ap_min:.3f} m/s²")
    uu = 0.5 * res.delta if u is None else float(u)
    for i, poly in enumerate(displaced_parts(res, uu)):
        ax.plot(poly[:, 0], poly[:, 1], color="tab:blue", lw=1.0, zorder=3,
                label=f"mechanism at u = {uu:.3g} rad" if i == 0 else None)
    for h in res.hinges:
        ax.plot(h.x, h.y, "o", ms=7, mfc="white" if h.side == "intrados" else "k",
                mec="k", zorder=5)
    ax.plot([], [], "o", mfc="white", mec="k", label="hinge on intrados")
    ax.plot([], [], "o", mfc="k", mec="k", label="hinge on extrados")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{arch.shape} arch l = {arch.span:g} m, f = {arch.rise:g} m: p = "
                 f"{res.p:.3f} 1/s, delta = {res.delta:.4f} rad")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3, fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
