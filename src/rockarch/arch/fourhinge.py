"""The four-hinge mechanism of an arch: exact linkage kinematics, Bv, Bh, A, delta, p.

Theory: docs/theory.md §3 (SDOF mechanisms) and §5 (the four-hinge mechanism).

Hinges H1 < H2 < H3 < H4 (left to right, from the limit analysis); rigid parts 1 = H1–H2,
2 = H2–H3, 3 = H3–H4; the voussoirs outside H1–H4 stay on the ground. The coordinate u is the
rotation of part 1 about H1, signed so that u > 0 opens the mechanism in its collapse direction:
part 1 turns counter-clockwise by ``sigma*u`` (sigma = +1 for an arch falling to the left,
direction = +1, i.e. a ground acceleration to the right). Part 3 turns by v(u) about H4 so that
|H3(v) - H2(u)| = |H3 - H2| (closed form, branch through v(0) = 0); part 2 follows as the
rigid motion carrying (H2, H3) to (H2(u), H3(v)).

With these kinematics (docs/theory.md §3):

    A(u) = sum_j m_j (x_j'^2 + y_j'^2) + I_j phi_j'^2        (' = d/du)
    V(u) = g sum_j m_j y_j(u)
    Bv = V'(0) (gravity's generalised moment, includes g),
    Bh = -direction * g * sum_j m_j x_j'(0) (the same for horizontal loads m*g, i.e. a ground
    acceleration of g in the collapse direction),  ap_min = g Bv / Bh
    delta: V'(delta) = 0,  p = sqrt(Bv / (A(0) delta))       (paper Eq. 12–13)

and Lagrange's equation  A u'' + A'(u) u'^2 / 2 = -V'(u) - a_g sum_j m_j x_j'(u).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from rockarch.arch.cutting import Voussoirs
from rockarch.arch.geometry import Arch
from rockarch.arch.thrust import Hinge, ThrustResult, limit_analysis
from rockarch.core.constants import G
from rockarch.core.validate import positive


def _perp(p: np.ndarray) -> np.ndarray:
    return np.stack([-p[..., 1], p[..., 0]], axis=-1)


def _rot(th: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Rotate the vector(s) p by angle(s) th (broadcast: th (n,), p (2,) or (n, 2))."""
    c, s = np.cos(th), np.sin(th)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]], axis=-1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@dataclass(frozen=True)
class FourHinge:
    """A four-hinge mechanism: hinge points and the three rigid parts (Sect. 5).

    Attributes
    ----------
    hinges : (4, 2) hinge points H1..H4 (undeformed), left to right.
    sides : the four hinge sides ("intrados" / "extrados").
    joints : the four joint indices in the discretisation.
    mass : (3,) part masses (unit density, per unit depth).
    centroid : (3, 2) part centres of mass (undeformed).
    inertia : (3,) part polar moments about their centres of mass.
    direction : +1 (ground acceleration to the right, falls to the left) or -1.
    sigma : +1 or -1: part 1 rotates counter-clockwise by sigma*u.
    g : gravity, m/s².
    """

    hinges: np.ndarray
    sides: tuple[str, ...]
    joints: tuple[int, ...]
    mass: np.ndarray
    centroid: np.ndarray
    inertia: np.ndarray
    direction: int
    sigma: int
    g: float = G


@dataclass(frozen=True)
class Kinematics:
    """Positions, rotations and their u-derivatives of the three parts (Sect. 5).

    Arrays have shape (3, n) for n values of u (part index first); ``v`` has shape (n,).
    ``x, y`` are the parts' centres of mass, ``phi`` their rotations (counter-clockwise),
    ``dx, dy, dphi`` the first derivatives w.r.t. u and ``d2x, d2y, d2phi`` the second
    derivatives (None unless requested; central differences of the exact first derivatives,
    relative accuracy ~1e-8). ``h2, h3`` (n, 2) are the moving inner hinges.
    ``valid`` (n,) is False where the linkage cannot close (u beyond its range).
    """

    u: np.ndarray
    v: np.ndarray
    x: np.ndarray
    y: np.ndarray
    phi: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    dphi: np.ndarray
    h2: np.ndarray
    h3: np.ndarray
    valid: np.ndarray
    d2x: np.ndarray | None = None
    d2y: np.ndarray | None = None
    d2phi: np.ndarray | None = None


def _closure(mech: FourHinge, th1: np.ndarray):
    """The moved hinge H2(u), H2(u) - H4 and the cosine of the right part's angle at H4 that
    closes the linkage (it closes where that cosine lies in [-1, 1])."""
    h1, h2, h3, h4 = mech.hinges
    a, w0 = h3 - h4, h3 - h2
    h2u = h1 + _rot(th1, h2 - h1)
    q = h2u - h4
    aa = float(a @ a)
    qq = np.sum(q * q, axis=-1)
    return h2u, q, (aa + qq - float(w0 @ w0)) / (2 * math.sqrt(aa) * np.sqrt(qq))


def _first(mech: FourHinge, u: np.ndarray):
    h1, h2, h3, h4 = mech.hinges
    c1, c2, c3 = mech.centroid
    a = h3 - h4
    w0 = h3 - h2
    th1 = mech.sigma * u
    h2u, q, cosarg = _closure(mech, th1)
    valid = np.abs(cosarg) <= 1.0
    # branch through v(0) = 0
    q0 = h2 - h4
    d0 = math.atan2(float(_cross(a, q0)), float(a @ q0))
    s = -1.0 if d0 > 0 else 1.0
    delta_aq = np.arctan2(_cross(a, q), np.sum(q * a, axis=-1))
    v = delta_aq + s * np.arccos(np.clip(cosarg, -1.0, 1.0))
    h3v = h4 + _rot(v, a)
    w = h3v - h2u
    phi2 = np.arctan2(_cross(w0, w), np.sum(w * w0, axis=-1))
    dh2 = mech.sigma * _perp(h2u - h1)
    pv = _perp(h3v - h4)
    with np.errstate(divide="ignore", invalid="ignore"):
        dv = np.sum(w * dh2, axis=-1) / np.sum(w * pv, axis=-1)
        dh3 = pv * dv[..., None]
        dw = dh3 - dh2
        dphi2 = _cross(w, dw) / np.sum(w * w, axis=-1)
    p1 = h1 + _rot(th1, c1 - h1)
    p3 = h4 + _rot(v, c3 - h4)
    p2 = h2u + _rot(phi2, c2 - h2)
    d1 = mech.sigma * _perp(p1 - h1)
    d3 = _perp(p3 - h4) * dv[..., None]
    d2 = dh2 + _perp(p2 - h2u) * dphi2[..., None]
    pos = np.stack([p1, p2, p3])  # (3, n, 2)
    vel = np.stack([d1, d2, d3])
    phi = np.stack([th1, phi2, v])
    dphi = np.stack([np.full_like(u, float(mech.sigma)), dphi2, dv])
    return v, pos, vel, phi, dphi, h2u, h3v, valid


def kinematics(mech: FourHinge, u, *, second: bool = False) -> Kinematics:
    """Exact kinematics of the three parts at rotation(s) u of the left part (Sect. 5).

    Parameters
    ----------
    mech : FourHinge
    u : float or array
        Rotation of part 1 about H1 (rad), > 0 opening the mechanism.
    second : bool
        Also return the second derivatives (d2x, d2y, d2phi).
    """
    u = np.atleast_1d(np.asarray(u, dtype=float))
    v, pos, vel, phi, dphi, h2u, h3v, valid = _first(mech, u)
    extra = {}
    if second:
        h = 1e-5
        _, _, vp, _, dpp, _, _, _ = _first(mech, u + h)
        _, _, vm, _, dpm, _, _, _ = _first(mech, u - h)
        acc = (vp - vm) / (2 * h)
        extra = {"d2x": acc[..., 0], "d2y": acc[..., 1], "d2phi": (dpp - dpm) / (2 * h)}
    return Kinematics(u=u, v=v, x=pos[..., 0], y=pos[..., 1], phi=phi, dx=vel[..., 0],
                      dy=vel[..., 1], dphi=dphi, h2=h2u, h3=h3v, valid=valid, **extra)


def generalized_inertia(mech: FourHinge, u) -> np.ndarray:
    """A(u) = sum m (x'^2 + y'^2) + I phi'^2 (docs/theory.md Eq. 3.2; paper Eqs. 12–13)."""
    k = kinematics(mech, u)
    m, i = mech.mass[:, None], mech.inertia[:, None]
    return np.sum(m * (k.dx**2 + k.dy**2) + i * k.dphi**2, axis=0)


def generalized_inertia_du(mech: FourHinge, u) -> np.ndarray:
    """A'(u) = 2 sum m (x' x'' + y' y'') + 2 I phi' phi''.

    The u-derivative of docs/theory.md Eq. 3.2."""
    k = kinematics(mech, u, second=True)
    m, i = mech.mass[:, None], mech.inertia[:, None]
    return 2 * np.sum(m * (k.dx * k.d2x + k.dy * k.d2y) + i * k.dphi * k.d2phi, axis=0)


def potential(mech: FourHinge, u) -> np.ndarray:
    """V(u) = g sum m y(u), relative to u = 0 (docs/theory.md Eq. 3.2)."""
    k = kinematics(mech, u)
    return mech.g * np.sum(mech.mass[:, None] * (k.y - mech.centroid[:, 1:2]), axis=0)


def potential_du(mech: FourHinge, u) -> np.ndarray:
    """dV/du = g sum m y'(u): gravity's resisting generalised moment.

    B_v of docs/theory.md Eq. 3.3 at u = 0."""
    k = kinematics(mech, u)
    return mech.g * np.sum(mech.mass[:, None] * k.dy, axis=0)


def driving_moment(mech: FourHinge, u) -> np.ndarray:
    """-direction * sum m x'(u): generalised force per unit ground acceleration (Sect. 3)."""
    k = kinematics(mech, u)
    return -mech.direction * np.sum(mech.mass[:, None] * k.dx, axis=0)


def _closes(mech: FourHinge, u: float) -> bool:
    """``kinematics(mech, u).valid[0]`` without the parts' motion."""
    return bool(np.abs(_closure(mech, mech.sigma * np.atleast_1d(float(u)))[2][0]) <= 1.0)


def closure_limit(mech: FourHinge, u_max: float = math.pi / 2) -> float:
    """Largest u in (0, u_max] up to which the linkage closes (bisection on validity)."""
    if _closes(mech, u_max):
        return u_max
    lo, hi = 0.0, u_max
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _closes(mech, mid):
            lo = mid
        else:
            hi = mid
    return lo


def neutral_position(mech: FourHinge) -> float:
    """delta: the first root u > 0 of dV/du = 0 on the exact kinematics (paper Fig. 10)."""
    lim = closure_limit(mech)
    u = np.linspace(0.0, lim, 801)[1:]
    dv = potential_du(mech, u)
    bad = np.flatnonzero(dv <= 0)
    if len(bad) == 0:
        raise ValueError("the four-hinge mechanism has no neutral position within its range "
                         f"of motion (u <= {lim:.4g} rad): its parts lock before they could "
                         "overturn, as in a ring too thick for its span (give a thinner ring)")
    j = int(bad[0])
    if j == 0:
        lo = 0.0
    else:
        lo = float(u[j - 1])
    return brentq(lambda t: float(potential_du(mech, t)[0]), max(lo, 1e-15), float(u[j]),
                  xtol=1e-14, rtol=1e-12)


def neutral_position_linear(mech: FourHinge) -> float:
    """delta from linearised kinematics: -V'(0)/V''(0) (first-order expansion of dV/du)."""
    h = 1e-5
    v2 = float((potential_du(mech, h)[0] - potential_du(mech, -h)[0]) / (2 * h))
    if v2 >= 0:
        raise ValueError("gravity does not weaken the mechanism to first order (V''(0) >= 0)")
    return -float(potential_du(mech, 0.0)[0]) / v2


def mechanism_from_hinges(v: Voussoirs, hinges, *, direction: int = 1, g: float = G
                          ) -> FourHinge:
    """Build the mechanism from 4 hinges (Hinge objects or joint indices + sides) (Sect. 5).

    The parts are the voussoirs between consecutive hinge joints; their mass, centre of mass
    and polar moment come from the voussoirs (parallel-axis theorem).
    """
    g = positive("g", g)
    hs = list(hinges)
    if len(hs) != 4:
        raise ValueError(f"a four-hinge mechanism needs 4 hinges, got {len(hs)}")
    joints = tuple(int(h.joint) for h in hs)
    if any(b <= a for a, b in zip(joints, joints[1:], strict=False)):
        raise ValueError(f"hinge joints must increase strictly left to right, got {joints}")
    if joints[0] < 0 or joints[-1] > v.n:
        raise ValueError(f"hinge joints must lie in 0..{v.n}, got {joints}")
    pts = np.array([[h.x, h.y] for h in hs], dtype=float)
    mass, cen, ine = [], [], []
    for a, b in zip(joints[:-1], joints[1:], strict=False):
        m = v.mass[a:b]
        mt = float(m.sum())
        c = (m[:, None] * v.centroid[a:b]).sum(axis=0) / mt
        i = float(np.sum(v.inertia[a:b] + m * np.sum((v.centroid[a:b] - c) ** 2, axis=1)))
        mass.append(mt)
        cen.append(c)
        ine.append(i)
    proto = FourHinge(hinges=pts, sides=tuple(h.side for h in hs), joints=joints,
                      mass=np.array(mass), centroid=np.array(cen), inertia=np.array(ine),
                      direction=int(direction), sigma=1, g=g)
    dx0 = float(np.sum(proto.mass * kinematics(proto, 0.0).dx[:, 0]))
    if dx0 == 0.0:
        raise ValueError("degenerate mechanism: it does not move the mass horizontally")
    sigma = 1 if -direction * dx0 > 0 else -1
    return FourHinge(hinges=pts, sides=proto.sides, joints=joints, mass=proto.mass,
                     centroid=proto.centroid, inertia=proto.inertia, direction=int(direction),
                     sigma=sigma, g=g)


@dataclass(frozen=True)
class ArchMechanism:
    """Critical (optimal) four-hinge mechanism of an arch and its dynamic parameters.

    Paper Eqs. 12–14; docs/theory.md Eqs. (3.3)–(3.5) and (5.2).

    Attributes
    ----------
    thrust : ThrustResult
        The limit analysis (ap_min, thrust line, hinges).
    mechanism : FourHinge
    continuous : bool
        True for the critical optimal mechanism (fine "continuous" discretisation).
    ap_min, lambda_ : from the LP.
    ap_min_vw : g*Bv/Bh from virtual work on the mechanism (must equal ap_min).
    Bv, Bh, A : generalised gravity moment, driving moment per unit acceleration, inertia.
    delta : neutral value of the mechanism coordinate u (exact kinematics) — the dynamics'
        delta; delta_linear: linearised. u is the rotation of the end part on the side the
        arch falls towards: part 1 about H1 for direction +1, part 3 about H4 for −1 (the
        mirror image: a symmetric arch has the same p, delta, Bv, Bh and A both ways,
        docs/theory.md Eq. 5.6). ``mechanism``'s own kinematics take part 1's rotation,
        whose neutral value is ``delta_linkage`` (= delta for direction +1).
    delta_end, end_part : Table 1's delta: the rotation, at the neutral configuration, of the
        end part next to the extrados inner hinge (``end_part`` 1 = H1–H2 or 3 = H3–H4),
        docs/theory.md Eq. (5.4).
    p : sqrt(Bv/(A*delta)), 1/s (on the coordinate u).
    c1..c4, c3p : constants of paper Eq. 14 / Table 1 (see :func:`analyse`); c4 in Table 1's
        convention (delta_end), c4_u = d/(delta*l) on the coordinate u.
    """

    thrust: ThrustResult
    mechanism: FourHinge
    continuous: bool
    ap_min: float
    lambda_: float
    ap_min_vw: float
    Bv: float
    Bh: float
    A: float
    delta: float
    delta_linear: float
    p: float
    c1: float
    c2: float
    c3: float
    c3p: float
    c4: float
    delta_end: float = float("nan")
    end_part: int = 0
    c4_u: float = float("nan")
    delta_linkage: float = float("nan")

    @property
    def hinges(self) -> tuple[Hinge, ...]:
        return self.thrust.hinges

    def to_dict(self) -> dict:
        """The CLI's JSON contract (joint is None for the continuous mechanism).

        ``delta`` and ``c4`` are Table 1's (the end part next to the extrados inner hinge,
        ``delta_part``); ``delta_u`` and ``c4_u`` are on the dynamics' coordinate u.
        """
        return {"ap_min": self.ap_min, "lambda": self.lambda_, "p": self.p,
                "delta": self.delta_end, "delta_part": self.end_part, "delta_u": self.delta,
                "Bv": self.Bv, "Bh": self.Bh, "A": self.A,
                "hinges": [h.to_dict(joint=not self.continuous) for h in self.hinges],
                "c1": self.c1, "c2": self.c2, "c3": self.c3, "c3p": self.c3p, "c4": self.c4,
                "c4_u": self.c4_u}


def _on_part3(mech: FourHinge, bv: float, bh: float, a0: float, dlin: float, delta_u: float
              ) -> tuple[float, float, float, float, float]:
    """Bv, Bh, A, the linearised and the exact neutral angle on w, part 3's rotation about H4
    (docs/theory.md Eq. 5.6): w' = r u' at u = 0 with r = |v'(0)|, so Bv and Bh divide by r,
    A by r², and the neutral configuration is the same one, w = |v(delta_u)|."""
    r = abs(float(kinematics(mech, 0.0).dphi[2, 0]))
    delta_w = abs(float(kinematics(mech, delta_u).phi[2, 0]))
    return bv / r, bh / r, a0 / (r * r), dlin * r, delta_w


class NoFourHingeMechanism(ValueError):
    """The thrust line at ap,min does not give a four-bar linkage (a very thick ring): its
    ``ap_min`` [m/s²] is valid, the four-hinge p and delta do not exist."""

    def __init__(self, message: str, ap_min: float):
        super().__init__(message)
        self.ap_min = ap_min


def _check_four_bar(res: ThrustResult) -> None:
    """A four-bar mechanism opens four hinges on alternate faces (e, i, e, i or i, e, i, e).

    A very thick ring's thrust line grazes one face at two neighbouring joints instead (a
    semicircle of thickness 0.45 x span, for one), or touches the ring at 3 or 5 points (a
    catenary of rise 0.3 and thickness 0.3 x span: the ring lifts off an abutment): its
    ap,min is the LP's, but no four-bar linkage, whose parts could move, passes through
    those points. Raises :class:`NoFourHingeMechanism`."""
    sides = [h.side for h in res.hinges]
    if len(sides) == 4 and all(a != b for a, b in zip(sides[:-1], sides[1:], strict=True)):
        return
    where = "not on alternate faces" if len(sides) == 4 else f"at {len(sides)} points"
    raise NoFourHingeMechanism(
        f"no four-hinge mechanism: ap,min = {res.ap_min:.4g} m/s² ({res.lambda_:.3g} g), but "
        f"there the thrust line touches the ring at {', '.join(s[0] for s in sides)} "
        f"(e: extrados, i: intrados; joints {', '.join(str(h.joint) for h in res.hinges)}), "
        f"{where}: the ring is too thick for a four-hinge mechanism, so its p and delta do "
        "not exist (give a thinner ring; the multi-block engine, --system mdof or "
        "`rockarch simulate mdof`, takes any mechanism)", res.ap_min)


def analyse(arch: Arch, blocks: int | None = None, *, g: float = G, direction: int = 1
            ) -> ArchMechanism:
    """Limit analysis + four-hinge mechanism + p, delta, ap_min and paper Eq. 14 constants.

    Parameters
    ----------
    arch : Arch
    blocks : int, optional
        Number of voussoirs (critical mechanism, hinges at joints). None: the continuous
        limit (critical optimal mechanism, 2000 voussoirs).
    g : float
    direction : {+1, -1}
        +1: ground acceleration to the right (the arch falls to the left).

    Notes
    -----
    Paper Eq. 14 (docs/theory.md Eq. 5.2): c1 = g/(p² f), c2 = ap_min f²/(g d l), c4 = d/(delta l),
    with l the span, f the rise of the axis and d the thickness (the mean joint length if it
    varies). c4 uses Table 1's delta, the rotation of the end part next to the extrados inner
    hinge at the neutral configuration (Eq. 5.4); c4_u uses the coordinate u's delta. c3 and c3p are
    the positions of the two inner hinges, each measured from its near springing (H2 from the
    left, H3 from the right) as a fraction of the span: c3 for the inner hinge on the
    **extrados**, c3p for the one on the intrados (this matches Table 1, where c3 < c3').
    """
    res = limit_analysis(arch, blocks, g=g, direction=direction)
    _check_four_bar(res)
    mech = mechanism_from_hinges(res.voussoirs, res.hinges, direction=direction, g=g)
    bv = float(potential_du(mech, 0.0)[0])
    bh = g * float(driving_moment(mech, 0.0)[0])  # moment of horizontal loads m*g
    a0 = float(generalized_inertia(mech, 0.0)[0])
    if bv <= 0:
        raise ValueError("gravity does not resist the four-hinge mechanism (Bv <= 0)")
    delta = neutral_position(mech)
    try:
        dlin = neutral_position_linear(mech)
    except ValueError:
        dlin = float("nan")
    u_neutral = delta
    if direction < 0:  # on the mirror image of side +'s coordinate (Eq. 5.6)
        bv, bh, a0, dlin, delta = _on_part3(mech, bv, bh, a0, dlin, delta)
    p = math.sqrt(bv / (a0 * delta))
    span, rise = arch.span, arch.rise
    d = arch.uniform_thickness
    if d is None:
        d = float(np.mean(res.voussoirs.thickness))
    h2, h3 = res.hinges[1], res.hinges[2]
    pts = res.voussoirs.points
    pos2 = (pts[h2.joint, 0] - pts[0, 0]) / span
    pos3 = (pts[-1, 0] - pts[h3.joint, 0]) / span
    if h2.side == "extrados":
        c3, c3p = pos2, pos3
    else:
        c3, c3p = pos3, pos2
    end_part = 1 if h2.side == "extrados" else 3
    delta_end = abs(float(kinematics(mech, u_neutral).phi[end_part - 1, 0]))
    return ArchMechanism(
        thrust=res, mechanism=mech, continuous=blocks is None, ap_min=res.ap_min,
        lambda_=res.lambda_, ap_min_vw=g * bv / bh, Bv=bv, Bh=bh, A=a0, delta=delta,
        delta_linear=dlin, p=p, c1=g / (p * p * rise), c2=res.ap_min * rise**2 / (g * d * span),
        c3=c3, c3p=c3p, c4=d / (delta_end * span), delta_end=delta_end, end_part=end_part,
        c4_u=d / (delta * span), delta_linkage=u_neutral)
