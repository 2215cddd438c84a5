"""The finite motion of an assembly's collapse mechanism: its neutral angle δ (Eq. (10.5b)).

The limit analysis (:mod:`rockarch.mdof.statics`) gives the collapse mechanism as virtual
velocities of the blocks at the undeformed configuration. Followed to finite rotations, a
mechanism of several rigid parts is a linkage: blocks whose joints stay closed move as one
rigid *part*, and two parts (or a part and the ground) turn about the joint corner where
their relative velocity vanishes, a *hinge*. Its neutral configuration, where gravity stops
restoring it (V'(θ) = 0, docs/theory.md Eq. (3.5)), is reached at a rotation δ that for an
arch is much smaller than the initial estimate tan δ = Q_y/Q_x of Eq. (10.5): the hinges'
geometry changes as the mechanism opens (for the four-hinge arch this is the neutral angle
of §5, computed here for any rocking mechanism).

Coordinate: θ, the rotation of the *leading part*, the part hinged to the ground on the
side towards which the inertia load pushes (for an arch: part 1 of §5, whose rotation u is
the coordinate of the four-hinge mechanism, so that an arch's δ and p are those of §5). The
closure of the hinges at a given θ is solved by Newton's method on the parts' positions; δ
is the root of V'(θ) = g·Σ m·ẏ, found by stepping θ and bisecting (scipy's ``brentq``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

#: Relative velocity (over the largest) below which a joint corner is a hinge (the LP's
#: duals are accurate to ~1e-9 of their scale).
PIVOT_TOL = 1e-6
#: θ is stepped by δ_lin/STEPS_PER_DELTA up to MAX_OVER_DELTA·δ_lin (or π/2) looking for the
#: sign change of V'(θ).
STEPS_PER_DELTA = 40
MAX_OVER_DELTA = 4.0
#: A finite δ within this relative distance of the initial estimate is the estimate itself
#: (one rigid part turning about a hinge: tan δ = Q_y/Q_x exactly, Housner's α for a block).
SAME = 1e-9


@dataclass(frozen=True)
class Linkage:
    """The mechanism's rigid parts and hinges (ground: part -1)."""

    mass: np.ndarray  # (K,) mass of each part
    centroid: np.ndarray  # (K, 2) its centroid in the undeformed configuration
    hinges: tuple  # (part a, part b, (x, y)) per hinge
    coordinate: int  # the part whose rotation is θ (the leading part)
    sign: float  # +1 / -1: the sense in which that part turns in the mechanism
    rate: float  # |ω| of that part in the mechanism velocities (max|ω| = 1)


def linkage(mass, centroid, corners, body_a, body_b, velocity,
            direction: int) -> Linkage | None:
    """The rigid parts and hinges of the mechanism ``velocity`` ((nb, 3): u, v, ω per
    block) under a ground acceleration of sign ``direction``; None if it does not
    rotate."""
    mass = np.asarray(mass, float)
    vel = np.asarray(velocity, float)
    nb = len(mass)
    big = float(np.abs(vel).max()) if vel.size else 0.0
    if big <= 0.0 or float(np.abs(vel[:, 2]).max()) <= PIVOT_TOL * big:
        return None
    moving = np.abs(vel).max(axis=1) > PIVOT_TOL * big
    rel = corner_velocity(vel, centroid, corners, body_b) - corner_velocity(
        vel, centroid, corners, body_a)
    pivot = np.linalg.norm(rel, axis=2) <= PIVOT_TOL * max(float(np.abs(rel).max()), 1e-300)
    # blocks that do not move are the ground (node nb); closed joints weld their blocks
    ends = []
    for body in (np.asarray(body_a), np.asarray(body_b)):
        ends.append(np.where((body >= 0) & moving[np.maximum(body, 0)], body, nb))
    end_a, end_b = ends
    weld = np.flatnonzero(pivot.all(axis=1))
    graph = coo_matrix((np.ones(len(weld)), (end_a[weld], end_b[weld])), shape=(nb + 1,) * 2)
    label = connected_components(graph, directed=False)[1]
    # parts: the components of moving blocks not welded to the ground, by their first block
    roots = list(dict.fromkeys(label[i] for i in range(nb) if moving[i]
                               and label[i] != label[nb]))
    part = {r: j for j, r in enumerate(roots)}
    of = np.array([part.get(label[i], -1) for i in range(nb + 1)])
    pm = np.array([mass[of[:nb] == j].sum() for j in range(len(roots))])
    pc = np.array([(mass[of[:nb] == j, None] * np.asarray(centroid)[of[:nb] == j]).sum(axis=0)
                   / pm[j] for j in range(len(roots))]).reshape(-1, 2)
    hinges = []
    for k in range(len(pivot)):
        a, b = int(of[end_a[k]]), int(of[end_b[k]])
        if a != b and pivot[k].sum() == 1:
            hinges.append((a, b, tuple(np.asarray(corners)[k, int(np.argmax(pivot[k]))])))
    # the leading part: hinged to the ground furthest along the inertia load (-direction·x)
    grounded = [(direction * h[2][0], h[0] + h[1] + 1) for h in hinges if -1 in h[:2]]
    if not grounded:
        return None
    lead = min(grounded)[1]
    om = vel[np.flatnonzero(of[:nb] == lead)[0], 2]
    return Linkage(mass=pm, centroid=pc, hinges=tuple(hinges), coordinate=int(lead),
                   sign=math.copysign(1.0, om), rate=abs(float(om)))


def neutral_angle(mass, centroid, corners, body_a, body_b, velocity, direction: int,
                  delta_lin: float) -> tuple[float, float]:
    """(δ, rate): the rotation θ of the leading part at which the mechanism ``velocity``,
    followed as a linkage, reaches its neutral configuration V'(θ) = 0 (Eq. (10.5b)), and
    that part's |ω| in ``velocity`` (max|ω| = 1).

    ``(delta_lin, 1)`` (Eq. (10.5): tan δ = Q_y/Q_x) for a mechanism of one rigid part, and
    where the finite δ equals it (a rocking frame); ``delta_lin`` also sets the search's
    scale. δ = nan where the linkage cannot be followed (a part not held by hinges, more
    than one degree of freedom, no neutral configuration before MAX_OVER_DELTA·δ_lin): the
    caller keeps δ_lin.
    """
    lk = linkage(mass, centroid, corners, body_a, body_b, velocity, direction)
    if lk is None or not math.isfinite(delta_lin) or delta_lin <= 0.0:
        return math.nan, 1.0
    if len(lk.mass) == 1:
        return delta_lin, 1.0
    try:
        return _follow(_Chain(lk), lk, delta_lin)
    except (ValueError, RuntimeError, np.linalg.LinAlgError):  # a linkage that jams
        return math.nan, 1.0


def _follow(chain: _Chain, lk: Linkage, delta_lin: float) -> tuple[float, float]:
    """:func:`neutral_angle` of a linkage of several parts."""
    if not chain.one_dof():
        return math.nan, 1.0
    step = delta_lin / STEPS_PER_DELTA
    top = min(MAX_OVER_DELTA * delta_lin, 0.5 * math.pi)
    q = np.zeros(3 * len(lk.mass))
    t0, d0 = 0.0, chain.dv(q)
    if not d0 > 0.0:
        return math.nan, 1.0
    while t0 < top:
        t1 = min(t0 + step, top)
        q1 = chain.close(t1, q)
        if q1 is None:
            return math.nan, 1.0
        d1 = chain.dv(q1)
        if d1 <= 0.0:
            def f(th: float, qa=q) -> float:
                qq = chain.close(th, qa)
                if qq is None:
                    raise RuntimeError("the linkage does not close")
                return chain.dv(qq)

            d = brentq(f, t0, t1, xtol=1e-12 * delta_lin, rtol=1e-12)
            if abs(d - delta_lin) <= SAME * delta_lin and abs(lk.rate - 1.0) <= SAME:
                return delta_lin, 1.0
            return float(d), lk.rate
        t0, q = t1, q1
    return math.nan, 1.0


class _Chain:
    """Closure equations of a :class:`Linkage`: unknowns (x, y, φ) per part, the
    displacement of its centroid and its rotation; two equations per hinge."""

    def __init__(self, lk: Linkage) -> None:
        self.lk = lk
        self.n = 3 * len(lk.mass)
        self.fixed = 3 * lk.coordinate + 2
        self.free = np.array([i for i in range(self.n) if i != self.fixed])
        self.scale = max(float(np.ptp(np.array([h[2] for h in lk.hinges]), axis=0).max()), 1.0)

    def _point(self, q, part: int, p0) -> tuple[np.ndarray, np.ndarray]:
        """World position of the body-fixed point p0 of ``part`` and its derivatives with
        respect to (x, y, φ)."""
        if part < 0:
            return np.asarray(p0, float), np.zeros((2, 3))
        x, y, ph = q[3 * part:3 * part + 3]
        c, s = math.cos(ph), math.sin(ph)
        dx, dy = p0[0] - self.lk.centroid[part, 0], p0[1] - self.lk.centroid[part, 1]
        pos = self.lk.centroid[part] + np.array([x + c * dx - s * dy, y + s * dx + c * dy])
        jac = np.array([[1.0, 0.0, -s * dx - c * dy], [0.0, 1.0, c * dx - s * dy]])
        return pos, jac

    def residual(self, q) -> tuple[np.ndarray, np.ndarray]:
        r = np.zeros(2 * len(self.lk.hinges))
        jac = np.zeros((len(r), self.n))
        for k, (a, b, p0) in enumerate(self.lk.hinges):
            pa, ja = self._point(q, a, p0)
            pb, jb = self._point(q, b, p0)
            r[2 * k:2 * k + 2] = pa - pb
            if a >= 0:
                jac[2 * k:2 * k + 2, 3 * a:3 * a + 3] += ja
            if b >= 0:
                jac[2 * k:2 * k + 2, 3 * b:3 * b + 3] -= jb
        return r, jac

    def one_dof(self) -> bool:
        """The hinges leave exactly one degree of freedom, θ."""
        _, jac = self.residual(np.zeros(self.n))
        tol = 1e-9 * max(float(np.abs(jac).max()), 1.0)
        return np.linalg.matrix_rank(jac[:, self.free], tol) == len(self.free)

    def close(self, theta: float, q0) -> np.ndarray | None:
        """The parts' positions at θ, from the guess q0 (Newton, least squares)."""
        q = np.array(q0, float)
        q[self.fixed] = self.lk.sign * theta
        for _ in range(30):
            r, jac = self.residual(q)
            if float(np.abs(r).max()) <= 1e-13 * self.scale:
                return q
            q[self.free] -= np.linalg.lstsq(jac[:, self.free], r, rcond=None)[0]
        return None

    def dv(self, q) -> float:
        """V'(θ)/g = Σ m·ẏ of the parts, the rate at which the mechanism lifts its mass."""
        _, jac = self.residual(q)
        qd = np.zeros(self.n)
        qd[self.fixed] = self.lk.sign
        qd[self.free] = np.linalg.lstsq(jac[:, self.free], -jac[:, self.fixed] * self.lk.sign,
                                        rcond=None)[0]
        return float(np.sum(self.lk.mass * qd[1::3]))


def corner_velocity(vel, centroid, corners, body) -> np.ndarray:
    """(nj, 2, 2) velocity at both corners of every joint of the rigid motion ``vel`` of
    ``body`` (zero for the ground, body -1)."""
    body = np.asarray(body)
    on = (body >= 0)[:, None, None]
    b = np.where(body >= 0, body, 0)
    u, v, om = vel[b, 0][:, None], vel[b, 1][:, None], vel[b, 2][:, None]
    r = np.asarray(corners) - np.asarray(centroid)[b][:, None, :]
    return np.where(on, np.stack([u - om * r[..., 1], v + om * r[..., 0]], axis=-1), 0.0)
