"""Thrust-line limit analysis of a voussoir arch as a 4-variable LP (docs/theory.md Eqs. 4.1–4.3).

Unknowns z = (H, V, M0, lambda): the left springing reaction (H, V), its moment M0 about the
first joint's axis point, and the horizontal load multiplier. Every voussoir k carries its weight
W_k = m_k*g (down) and a horizontal inertia load of magnitude lambda*W_k.

**Sign convention (direction).** ``direction = +1`` means a ground acceleration a_g = +lambda*g
(ground pushed to the right): the inertia loads point to the **left** (-x) and the arch
collapses towards the left. ``direction = -1`` is the mirror case. lambda >= 0 is always the
magnitude; ap_min = lambda*g.

At joint i (axis point P_i, tangent t_i, normal n_i to the extrados, length d_i) the part left of
the joint transmits S_i = (H + h*sum W, V - sum W) (h = -direction*lambda) and the moment
M_i about P_i; the thrust line crosses the joint at P_i + e_i*n_i with e_i = -M_i/N_i,
N_i = t_i.S_i. Admissible: |M_i| <= N_i*d_i/2 (no tension, thrust line inside the joint).
e_i = -d_i/2 is a hinge on the intrados, e_i = +d_i/2 on the extrados.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, linprog

from rockarch.arch.cutting import Voussoirs, voussoirs
from rockarch.arch.geometry import CONTINUOUS_BLOCKS, Arch
from rockarch.core.constants import G
from rockarch.core.validate import in_range, positive, show

_LAMBDA_CAP = 1e3  # a "mechanism" needing more than 1000 g is no mechanism


@dataclass(frozen=True)
class Hinge:
    """One hinge of the collapse mechanism: joint index, position, side (Sect. 4–5)."""

    joint: int
    x: float
    y: float
    side: str  # "intrados" | "extrados"

    def to_dict(self, joint: bool = True) -> dict:
        return {"x": self.x, "y": self.y, "side": self.side,
                "joint": self.joint if joint else None}


@dataclass(frozen=True)
class ThrustResult:
    """Result of the limit analysis (docs/theory.md §4).

    Attributes
    ----------
    lambda_ : float
        Collapse multiplier (horizontal load / weight).
    ap_min : float
        lambda_*g, m/s².
    direction : int
        +1: ground acceleration to the right, arch falls to the left; -1: mirrored.
    H, V, M0 : float
        Left springing reaction (per unit depth, unit density: scale by density*g/g).
    thrust : (N+1, 2) points where the thrust line crosses each joint.
    eccentricity : (N+1,) e_i (positive towards the extrados).
    normal_force : (N+1,) N_i (compression > 0), in units of mass*g.
    hinges : tuple of Hinge, left to right: the points where the thrust line touches the
        ring (four on a four-bar mechanism; 2, 3 or 5 on some very thick rings).
    voussoirs : the discretised arch.
    g : float
    """

    lambda_: float
    ap_min: float
    direction: int
    H: float
    V: float
    M0: float
    thrust: np.ndarray
    eccentricity: np.ndarray
    normal_force: np.ndarray
    hinges: tuple[Hinge, ...]
    voussoirs: Voussoirs
    g: float

    @property
    def reactions(self) -> dict:
        """Springing reactions (force per unit depth for unit density, times g)."""
        v = self.voussoirs
        w = float(np.sum(v.mass)) * self.g
        h = -self.direction * self.lambda_ * w
        return {"left": (self.H * self.g, self.V * self.g),
                "right": (-(self.H * self.g + h), w - self.V * self.g)}


def _assemble(v: Voussoirs, direction: int) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                      np.ndarray]:
    """M_i = a_i.z + b_i and N_i = c_i.z + e_i for z = (H, V, M0, lambda), vectorised."""
    m = v.mass
    wc = np.concatenate([[0.0], np.cumsum(m)])
    sx = np.concatenate([[0.0], np.cumsum(m * v.centroid[:, 0])])
    sy = np.concatenate([[0.0], np.cumsum(m * v.centroid[:, 1])])
    x, y = v.points[:, 0], v.points[:, 1]
    x0, y0 = x[0], y[0]
    hs = -float(direction)  # horizontal load = hs*lambda*W
    a = np.empty((len(x), 4))
    a[:, 0] = -(y0 - y)
    a[:, 1] = x0 - x
    a[:, 2] = 1.0
    a[:, 3] = -hs * (sy - y * wc)
    b = -(sx - x * wc)
    tx, ty = v.tangent[:, 0], v.tangent[:, 1]
    c = np.empty_like(a)
    c[:, 0] = tx
    c[:, 1] = ty
    c[:, 2] = 0.0
    c[:, 3] = hs * tx * wc
    e = -ty * wc
    return a, b, c, e


def _solve(v: Voussoirs, direction: int, lam: float | None):
    """Max lambda (lam None) or feasibility at lambda = lam. Returns linprog result or None."""
    a, b, c, e = _assemble(v, direction)
    hd = 0.5 * v.thickness[:, None]
    # M - N d/2 <= 0 (intrados side), -M - N d/2 <= 0 (extrados side)
    a_ub = np.vstack([a - hd * c, -a - hd * c])
    b_ub = np.concatenate([-b + hd[:, 0] * e, b + hd[:, 0] * e])
    if lam is None:
        bounds = [(None, None)] * 3 + [(0.0, _LAMBDA_CAP)]
        cost = np.array([0.0, 0.0, 0.0, -1.0])
    else:
        bounds = [(None, None)] * 3 + [(lam, lam)]
        cost = np.zeros(4)
    # scaling: variables in units of the total weight W (H, V), W*span (M0); each row divided
    # by W*d_i/2 so that HiGHS's feasibility tolerance is one on the eccentricity ratio 2e/d
    wt = float(np.sum(v.mass))
    span = float(np.ptp(v.points[:, 0])) or 1.0
    col = np.array([wt, wt, wt * span, 1.0])
    row = np.tile(wt * hd[:, 0], 2)
    res = linprog(cost, A_ub=a_ub * col[None, :] / row[:, None], b_ub=b_ub / row,
                  bounds=bounds, method="highs",
                  options={"primal_feasibility_tolerance": 1e-9,
                           "dual_feasibility_tolerance": 1e-9})
    if res.status == 0:
        res.x = res.x * col
    return res if res.status == 0 else None


def _hinges_from(v: Voussoirs, ecc: np.ndarray, res) -> tuple[Hinge, ...]:
    """The four hinges: the active constraints with the largest multipliers (alternating)."""
    n1 = len(ecc)
    ratio = ecc / (0.5 * v.thickness)
    lam_dual = -np.asarray(res.ineqlin.marginals)  # >= 0, hinge rotation rates (virtual work)
    dual = lam_dual.reshape(2, n1)
    strength = dual.max(axis=0)
    side_of = np.where(dual[0] >= dual[1], 0, 1)  # 0: M = +N d/2 (intrados), 1: extrados
    cand = np.flatnonzero(strength > 1e-9 * max(strength.max(), 1e-300))
    if len(cand) != 4:
        # degenerate vertex: fall back on clusters of the eccentricity ratio near +-1
        near = np.flatnonzero(np.abs(ratio) >= 1 - 1e-7)
        groups: list[list[int]] = []
        for i in near:
            if groups and i == groups[-1][-1] + 1 and np.sign(ratio[i]) == np.sign(
                    ratio[groups[-1][-1]]):
                groups[-1].append(i)
            else:
                groups.append([i])
        cand = np.array([g[int(np.argmax(np.abs(ratio[g])))] for g in groups], dtype=int)
        side_of = np.where(ratio < 0, 0, 1)
    out = []  # four on a four-bar mechanism; 3 or 5 on some very thick rings (checked by
    # rockarch.arch.fourhinge, which needs four)
    for i in sorted(int(k) for k in cand):
        intr = side_of[i] == 0
        p = v.intrados[i] if intr else v.extrados[i]
        out.append(Hinge(joint=i, x=float(p[0]), y=float(p[1]),
                         side="intrados" if intr else "extrados"))
    return tuple(out)


def _validate_direction(direction: int) -> int:
    if direction not in (1, -1):
        raise ValueError(f"direction must be +1 or -1, got {show(direction)}")
    return int(direction)


def limit_analysis(arch: Arch | Voussoirs, blocks: int | None = None, *, g: float = G,
                   direction: int = 1) -> ThrustResult:
    """Largest horizontal multiplier lambda with an admissible thrust line (Eqs. (4.1)–(4.3)).

    Parameters
    ----------
    arch : Arch or Voussoirs
        The arch (cut into ``blocks`` voussoirs) or an already discretised one.
    blocks : int, optional
        Number of voussoirs; default :data:`CONTINUOUS_BLOCKS` (the "continuous" arch whose
        hinges sit at the maximum eccentricities: the critical optimal mechanism).
    g : float
        Gravity, m/s².
    direction : {+1, -1}
        +1: ground acceleration to the right (inertia loads to the left). See module docstring.

    Raises
    ------
    ValueError
        If the arch cannot carry its own weight (with its minimum thickness in the message).
    """
    g = positive("g", g)
    direction = _validate_direction(direction)
    v = arch if isinstance(arch, Voussoirs) else voussoirs(arch, blocks or CONTINUOUS_BLOCKS)
    res = _solve(v, direction, None)
    if res is None:
        raise ValueError(_too_thin_message(v))
    h, vv, m0, lam = (float(z) for z in res.x)
    if lam >= _LAMBDA_CAP * (1 - 1e-9):
        raise ValueError("no collapse mechanism: the arch resists any horizontal acceleration "
                         "(is it a solid wall?)")
    a, b, c, e = _assemble(v, direction)
    z = res.x
    mom = a @ z + b
    nf = c @ z + e
    ecc = -mom / nf
    thrust = v.points + ecc[:, None] * v.normal
    hinges = _hinges_from(v, ecc, res)
    return ThrustResult(lambda_=lam, ap_min=lam * g, direction=direction, H=h, V=vv, M0=m0,
                        thrust=thrust, eccentricity=ecc, normal_force=nf, hinges=hinges,
                        voussoirs=v, g=g)


def is_admissible(v: Voussoirs, lambda_: float = 0.0, *, direction: int = 1) -> bool:
    """True if a compression-only thrust line fits inside the arch at multiplier lambda_."""
    return _solve(v, _validate_direction(direction), float(lambda_)) is not None


def _too_thin_message(v: Voussoirs) -> str:
    arch = v.arch
    if arch.uniform_thickness is None:
        return ("the arch cannot carry its own weight: no compression-only thrust line fits "
                "inside it")
    try:
        d = minimum_thickness(arch, blocks=v.n)
    except ValueError:
        return ("the arch cannot carry its own weight at any thickness this axis can hold")
    t = arch.uniform_thickness
    return (f"the arch cannot carry its own weight: minimum thickness is {d:.6g} m "
            f"(d/l = {d / arch.span:.6g}), given {t:.6g} m (d/l = {t / arch.span:.6g})")


def minimum_thickness(arch: Arch, lambda_: float = 0.0, *, blocks: int | None = None,
                      direction: int = 1, rtol: float = 1e-7) -> float:
    """Smallest uniform thickness of ``arch``'s axis with an admissible thrust line.

    The limit analysis of docs/theory.md §4, gravity only (``lambda_ = 0``) or with a
    horizontal multiplier ``lambda_`` (ground acceleration lambda_*g). The mass model and
    axis of ``arch`` are kept; its own thickness is ignored. Root finding on
    lambda_max(d) - lambda_ (brentq), with a feasibility bisection where the LP is
    infeasible. Default blocks: 1000 (the continuous limit to ~1e-6).

    Raises ValueError if even the thickest arch the axis can hold is not enough.
    """
    lambda_ = in_range("lambda", lambda_, 0.0, _LAMBDA_CAP)
    direction = _validate_direction(direction)
    if arch.uniform_thickness is None and arch.shape != "pointed":
        raise ValueError("minimum thickness needs an arch with a uniform thickness")
    n = blocks or 1000
    span = arch.span

    def lam_of(d: float) -> float:
        """lambda_max(d) - lambda_, or -1 - (distance) when infeasible at lambda = 0."""
        v = voussoirs(arch.with_thickness(d), n)
        res = _solve(v, direction, None)
        if res is None:
            return -1.0 - lambda_
        return float(res.x[3]) - lambda_

    # largest thickness the axis can hold: search downwards from d = span
    hi = span
    for _ in range(60):
        try:
            arch.with_thickness(hi)
            break
        except ValueError:
            hi *= 0.8
    else:  # pragma: no cover
        raise ValueError("could not find a thickness this axis can hold")
    if lam_of(hi) < 0:
        raise ValueError(f"no thickness up to {hi:.6g} m (the most this axis can hold) carries "
                         f"lambda = {lambda_:g}")
    lo = 1e-6 * span
    if lam_of(lo) >= 0:
        return lo if lambda_ > 0 else 0.0
    # bisect until both sides are feasible at lambda = 0 or the bracket is tight, then brentq
    for _ in range(200):
        if hi - lo <= rtol * hi:
            break
        mid = 0.5 * (lo + hi)
        f = lam_of(mid)
        if f >= 0:
            hi = mid
        elif f > -1.0 - lambda_:  # feasible under gravity, lambda below the target
            return brentq(lam_of, mid, hi, xtol=rtol * hi * 0.1, rtol=rtol)
        else:
            lo = mid
    return hi
