"""Statics of general block assemblies: the collapse acceleration ap,min by limit analysis.

One linear programme over any contact graph (docs/theory.md §10, Eqs. (10.2)–(10.5)):
unknowns are the normal force n ≥ 0 and the tangential force t at both ends (corners) of
every joint, and the load multiplier λ; every block is in equilibrium under its weight m·g
(down), a horizontal inertia load λ·m·g (the ground acceleration a_g = λ·g, direction ±1)
and its contact forces; at a joint of friction coefficient μ the friction cone
|t| ≤ μ·n is two linear constraints (exact in 2-D); μ = inf removes them (no sliding). The
largest λ is the static collapse multiplier, ap,min = λ·g. scipy's HiGHS solves it.

The cone as a yield surface is associative friction: it lets a joint that slides while it
opens be propped by shear it could not carry. By default the LP is therefore followed by the
non-associative iteration of :mod:`rockarch.mdof.nonassoc` (Eqs. (10.6)–(10.8)) and the
macro-block search of :mod:`rockarch.mdof.macroblock` (Eq. (10.9)), the smaller of both;
the associative value stays available (``friction="associative"``).

The dual solution is the collapse mechanism: a virtual velocity (u, v, ω) per block, from
which the contacts that open or slide follow (:class:`Collapse`). Its equivalent block
(Eq. (10.5)), with the neutral angle of the mechanism's finite motion (Eq. (10.5b),
:mod:`rockarch.mdof.linkage`), gives the reference frequency parameter p and neutral angle δ
of a general assembly.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import coo_matrix

from rockarch.core.constants import G
from rockarch.core.validate import show
from rockarch.mdof import macroblock as mb
from rockarch.mdof import nonassoc as na
from rockarch.mdof import statics_cache as sc
from rockarch.mdof.linkage import corner_velocity, neutral_angle

#: Largest load multiplier searched: a "mechanism" needing more than 1000 g is none.
LAMBDA_CAP = 1e3
#: Sizes [m] of the structures whose LPs are solved as given; larger or smaller ones are
#: scaled by a power of two first (exact), to O(1) numbers for HiGHS's absolute tolerances.
SIZE_RANGE = (2.0**-6, 2.0**6)
#: Joints from which the non-associative iteration shows a progress bar on a terminal (the
#: 205-block wall, 575 joints, takes a few seconds).
PROGRESS_JOINTS = 100


@dataclass(frozen=True)
class Collapse:
    """The static collapse of an assembly under a horizontal ground acceleration.

    Attributes
    ----------
    ap_min : float
        Collapse acceleration λ·g [m/s²] (inf: no mechanism below LAMBDA_CAP·g).
    lambda_ : float
        Collapse multiplier λ = ap_min / g.
    direction : int
        +1: ground accelerating to +x (inertia loads to -x); -1: mirrored.
    velocity : (nb, 3) array
        Mechanism virtual velocities (u, v, ω) of every block's centroid, scaled so that the
        largest |ω| is 1 (or the largest |(u, v)| is 1 for a purely sliding mechanism).
    opening : (nj, 2) bool array
        Joint corners that open in the mechanism.
    sliding : (nj,) bool array
        Joints that slide in the mechanism: their faces move along each other while the
        joint carries a normal force (a joint open at both corners, or carrying nothing, does
        not slide; with ``friction="associative"`` a sliding joint dilates, opens at both
        corners and is shown by ``opening``).
    normal_force, tangential_force : (nj, 2) arrays
        Corner forces at collapse, in units of g·(mass unit).
    p, delta : float
        Equivalent-block frequency parameter [1/s] and neutral angle [rad], Eqs. (10.5),
        (10.5b) (nan for a mechanism without rotation).
    converged : bool
        False if the non-associative iteration did not converge (then ap_min is the least
        λ of its iterates, and a RuntimeWarning was issued).
    iterations : int
        Tresca LPs of the non-associative iteration (0: associative LP only, or its state
        was already a fixed point and its mechanism does not slide).
    """

    ap_min: float
    lambda_: float
    direction: int
    velocity: np.ndarray
    opening: np.ndarray
    sliding: np.ndarray
    normal_force: np.ndarray
    tangential_force: np.ndarray
    p: float
    delta: float
    converged: bool = True
    iterations: int = 0

    @property
    def moving(self) -> np.ndarray:
        """(nb,) bool: the blocks that move in the mechanism."""
        v = np.abs(self.velocity)
        return v.max(axis=1) > 1e-6 * max(float(v.max()), 1e-300)


def _equilibrium(mass, centroid, corners, normal, body_a, body_b, direction):
    """A_eq (3 nb × 4 nj + 1) and b_eq of Eq. (10.2), in units of g."""
    nb_, nj = len(mass), len(normal)
    tang = np.stack([-normal[:, 1], normal[:, 0]], axis=1)
    rows, cols, vals = [], [], []
    for k in range(nj):
        for c in range(2):
            pt = corners[k, c]
            for body, sgn in ((body_b[k], 1.0), (body_a[k], -1.0)):
                if body < 0:
                    continue
                r = pt - centroid[body]
                for var, d in ((2 * k + c, normal[k]), (2 * nj + 2 * k + c, tang[k])):
                    f = sgn * d
                    rows += [3 * body, 3 * body + 1, 3 * body + 2]
                    cols += [var] * 3
                    vals += [f[0], f[1], r[0] * f[1] - r[1] * f[0]]
    for i in range(nb_):  # sum f_x = direction·λ·m  (inertia load -direction·λ·m·g)
        rows.append(3 * i)
        cols.append(4 * nj)
        vals.append(-direction * mass[i])
    a = coo_matrix((vals, (rows, cols)), shape=(3 * nb_, 4 * nj + 1)).tocsr()
    b = np.zeros(3 * nb_)
    b[1::3] = mass
    return a, b


def _friction(mu):
    """A_ub, b_ub of the friction cone |t| <= mu n (Eq. 10.3) for finite mu."""
    nj = len(mu)
    rows, cols, vals, r = [], [], [], 0
    for k in range(nj):
        if not math.isfinite(mu[k]):
            continue
        for c in range(2):
            for s in (1.0, -1.0):
                rows += [r, r]
                cols += [2 * nj + 2 * k + c, 2 * k + c]
                vals += [s, -mu[k]]
                r += 1
    return coo_matrix((vals, (rows, cols)), shape=(r, 4 * nj + 1)).tocsr(), np.zeros(r)


def _not_standing(a_eq, b_eq, bounds, a_ub, b_ub, centroid, names) -> str:
    """Who falls: the lowest moving block of the mechanism that proves gravity alone cannot
    be carried (the duals of the least-residual equilibrium, a Farkas certificate)."""
    from scipy.sparse import eye, hstack

    n, m = a_eq.shape[1], a_eq.shape[0]
    a2 = hstack([a_eq, eye(m), -eye(m)]).tocsr()
    ub2 = hstack([a_ub, coo_matrix((a_ub.shape[0], 2 * m))]).tocsr() if a_ub.shape[0] else None
    c = np.concatenate([np.zeros(n), np.ones(2 * m)])
    bnd = list(bounds[:-1]) + [(0.0, 0.0)] + [(0.0, None)] * (2 * m)
    res = linprog(c, A_ub=ub2, b_ub=b_ub if a_ub.shape[0] else None, A_eq=a2, b_eq=b_eq,
                  bounds=bnd, method="highs")
    vel = np.abs(np.asarray(res.eqlin.marginals)).reshape(-1, 3)
    moving = np.flatnonzero(vel.max(axis=1) > 1e-6 * max(vel.max(), 1e-300))
    if len(moving) == 0:
        return "no equilibrium exists"
    i = int(moving[np.argmin(centroid[moving, 1])])
    more = f" (with {len(moving) - 1} more block(s))" if len(moving) > 1 else ""
    return f"{names[i]} falls{more}: no equilibrium at rest"


def _stands(a_eq, b_eq, bounds, mu) -> bool:
    """Whether (10.2)–(10.3) have a solution at λ = 0: the structure carries its weight."""
    a_ub, b_ub = _friction(mu)
    ub = (a_ub, b_ub) if a_ub.shape[0] else (None, None)
    res = linprog(np.zeros(a_eq.shape[1]), A_ub=ub[0], b_ub=ub[1], A_eq=a_eq, b_eq=b_eq,
                  bounds=list(bounds[:-1]) + [(0.0, 0.0)], method="highs")
    return res.status == 0


def _least_friction(a_eq, b_eq, bounds, mu) -> float | None:
    """The friction coefficient, the same at every joint, from which a structure that cannot
    stand with ``mu`` stands: rounded up to 3 significant digits, where the LP at λ = 0 is
    feasible (the cone only grows with μ: it stands with every larger one). None if it
    cannot stand without sliding either (friction is not the cause); inf if it needs more
    than the largest accepted coefficient."""
    from rockarch.mdof.builders import MU_MAX  # (builders imports this module)

    if np.all(np.isinf(mu)) or not _stands(a_eq, b_eq, bounds, np.full(len(mu), np.inf)):
        return None
    lo = float(np.min(mu))  # the least coefficient given: it does not stand with that
    hi = lo
    while True:  # double up to a coefficient with which it stands
        hi = min(2.0 * hi, MU_MAX)
        if _stands(a_eq, b_eq, bounds, np.full(len(mu), hi)):
            break
        if hi >= MU_MAX:
            return math.inf
        lo = hi
    while hi - lo > 1e-4 * hi:  # then bisect, below the 3 digits shown
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _stands(a_eq, b_eq, bounds, np.full(len(mu), mid)) else (mid, hi)
    e = 10.0 ** (math.floor(math.log10(hi)) - 2)
    return math.ceil(hi / e - 1e-9) * e


def _friction_text(mu) -> str:
    """'μ = 0.1', 'μ = 0.1..0.4', with '(no sliding elsewhere)' if some joints never slide."""
    fin = mu[np.isfinite(mu)]
    lo, hi = float(fin.min()), float(fin.max())
    return (f"μ = {lo:g}" + ("" if hi == lo else f"..{hi:g}")
            + ("" if fin.size == mu.size else " (no sliding elsewhere)"))


def _cannot_stand(a_eq, b_eq, bounds, a_ub, b_ub, centroid, names, mu) -> str:
    """The one-line error of a structure whose equilibrium at rest (λ = 0) has no solution,
    saying whether its friction is the cause and from which μ it stands."""
    who = _not_standing(a_eq, b_eq, bounds, a_ub, b_ub, centroid, names)
    need = _least_friction(a_eq, b_eq, bounds, mu)
    if need is None:
        return f"the structure cannot stand under gravity: {who}"
    uniform = np.all(mu == mu[0])
    fix = ("it stands only without sliding" if math.isinf(need)
           else f"it stands with μ > {need:.3g}" + ("" if uniform else " at every joint"))
    return (f"the structure cannot stand under gravity with friction {_friction_text(mu)}: "
            f"its joints slide and {who.removesuffix(': no equilibrium at rest')}; {fix}")


def _mechanism(dual, mass, inertia, centroid, corners, normal, body_a, body_b, direction):
    vel = np.asarray(dual, dtype=float).reshape(len(mass), 3)
    if np.sum(-direction * mass * vel[:, 0]) < 0:  # the inertia load does positive work
        vel = -vel
    w = np.abs(vel[:, 2]).max()
    scale = w if w > 1e-9 * max(np.abs(vel).max(), 1e-300) else np.hypot(vel[:, 0],
                                                                           vel[:, 1]).max()
    vel = vel / scale if scale > 0 else vel
    tang = np.stack([-normal[:, 1], normal[:, 0]], axis=1)
    rel = corner_velocity(vel, centroid, corners, body_b) - corner_velocity(
        vel, centroid, corners, body_a)
    tol = 1e-6 * max(float(np.abs(rel).max()), 1e-300)
    opening = np.einsum("kcd,kd->kc", rel, normal) > tol
    slide = np.abs(np.einsum("kcd,kd->kc", rel, tang)).max(axis=1) > tol
    return vel, opening, slide


def equivalent_block(mass, inertia, velocity, g: float = G) -> tuple[float, float]:
    """(p, delta) of the block whose rocking starts like the mechanism (Eq. 10.5).

    With the mechanism coordinate θ the largest block rotation, Q = Σ m·(u, v) and
    M* = Σ m·(u² + v²) + I·ω²: p² = g·|Q| / M*, tan δ = Q_y / Q_x (for one block: Housner's
    p and α). nan if no block rotates. A rocking mechanism of several rigid parts then
    takes the neutral angle of its finite motion, :func:`rockarch.mdof.linkage.neutral_angle`,
    and p² = B_v/(A·δ) of Eq. (3.4) on the rotation of its leading part (rate |ω_l|):
    p² = g·|Q|·sin δ_lin·|ω_l|/(M*·δ) (Eq. (10.5b), in :func:`limit_analysis`).
    """
    u, v, om = velocity.T
    if np.abs(om).max() < 1e-9:
        return math.nan, math.nan
    qx, qy = float(np.sum(mass * u)), float(np.sum(mass * v))
    mstar = float(np.sum(mass * (u * u + v * v) + inertia * om * om))
    return math.sqrt(g * math.hypot(qx, qy) / mstar), math.atan2(abs(qy), abs(qx))


def _coefficients(mu, nj: int) -> np.ndarray:
    """``mu`` (a number or one per joint) as (nj,) coefficients > 0 (inf: no sliding), or a
    ValueError naming the bad one."""
    try:
        out = np.broadcast_to(np.asarray(mu, dtype=float), (nj,)).copy()
    except (TypeError, ValueError):
        raise ValueError(f"mu must be a friction coefficient or one per joint ({nj}), got "
                         f"{show(mu)}") from None
    bad = np.flatnonzero(~(out > 0))  # NaN, zero and negative
    if bad.size:
        raise ValueError(f"friction coefficients must be > 0 (inf: no sliding); joint "
                         f"{bad[0]} has {show(out[bad[0]])}")
    return out


def limit_analysis(mass, inertia, centroid, corners, normal, body_a, body_b, mu=None, *,
                   g: float = G, direction: int | None = None, names=None,
                   friction: str = "nonassociative") -> Collapse:
    """The collapse of an assembly under a horizontal ground acceleration (Eqs. 10.2–10.9).

    Parameters
    ----------
    mass, inertia : (nb,) arrays
        Block masses and polar moments about their centroids (any consistent unit).
    centroid : (nb, 2) array
    corners : (nj, 2, 2) array
        The two end points of every joint.
    normal : (nj, 2) array
        Unit normal of every joint, from body_a into body_b.
    body_a, body_b : (nj,) int arrays
        The two bodies of every joint; -1 is the ground (or a support moving with it).
    mu : (nj,) array or None
        Coulomb friction coefficient per joint (inf or None: no sliding).
    direction : +1, -1 or None
        Direction of the ground acceleration; None: the smaller of both.
    names : list of str, optional
        Block names for the error message of a structure that cannot stand.
    friction : "nonassociative" or "associative"
        Coulomb friction without dilatancy (the iteration of Eqs. 10.6–10.8 and the
        macro-blocks of Eq. 10.9, default) or the friction cone as yield surface (the single
        LP of Eq. 10.4).

    Raises
    ------
    ValueError
        If the assembly cannot stand under gravity alone (naming the block; if it stands
        without sliding, saying that its joints slide and from which μ it stands).
    """
    if friction not in ("nonassociative", "associative"):
        raise ValueError(f"friction must be 'nonassociative' or 'associative', got {friction!r}")
    mass = np.asarray(mass, float)
    mu = np.full(len(normal), np.inf) if mu is None else _coefficients(mu, len(normal))
    key = None
    if sc.root() is not None:  # the result store (the CLI): a second build reuses it
        inputs = tuple(np.asarray(v, dtype=float) for v in (
            mass, inertia, centroid, corners, normal, body_a, body_b, mu))
        key = sc.key((*inputs, float(g), direction, friction),
                     (LAMBDA_CAP, na.MAX_ITER, na.RELAX, na.TOL_LAMBDA, na.TOL_FORCE))
        hit = sc.load(key, Collapse)
        if hit is not None:
            return hit
    # HiGHS's tolerances are absolute: a structure far from metres (a file in millimetres)
    # is solved scaled by a power of two (exact), lengths by s, masses by s², then unscaled
    corners = np.asarray(corners, float)
    size = float(np.ptp(corners.reshape(-1, 2), axis=0).max())
    s = 1.0 if SIZE_RANGE[0] <= size <= SIZE_RANGE[1] else 2.0 ** -round(math.log2(size))
    out = _solve(mass * s**2, np.asarray(inertia, float) * s**4,
                 np.asarray(centroid, float) * s, corners * s, normal, body_a, body_b, mu,
                 g=g, direction=direction, names=names, friction=friction)
    if s != 1.0:
        out = _unscaled(out, s)
    if key is not None:
        sc.save(key, out)
    return out


def _unscaled(c: Collapse, s: float) -> Collapse:
    """The collapse of a structure solved with its lengths × s and masses × s²: forces / s²,
    p·√s (p² ∝ g/length), a rocking mechanism's velocities per unit rotation rate / s."""
    vel = c.velocity.copy()
    if np.abs(vel[:, 2]).max() == 1.0:  # normalised by the largest rotation rate
        vel[:, :2] /= s
    return replace(c, velocity=vel, normal_force=c.normal_force / s**2,
                   tangential_force=c.tangential_force / s**2, p=c.p * math.sqrt(s))


def _solve(mass, inertia, centroid, corners, normal, body_a, body_b, mu, *, g: float,
           direction: int | None, names, friction: str) -> Collapse:
    """:func:`limit_analysis` itself (no store)."""
    nb_, nj = len(mass), len(normal)
    if direction is None:  # both directions at once: HiGHS releases the GIL
        with ThreadPoolExecutor(max_workers=2) as pool:
            both = list(pool.map(lambda d: limit_analysis(
                mass, inertia, centroid, corners, normal, body_a, body_b, mu, g=g,
                direction=d, names=names, friction=friction), (1, -1)))
        return min(both, key=lambda c: c.lambda_)
    a_ub, b_ub = _friction(mu)
    a_eq, b_eq = _equilibrium(mass, np.asarray(centroid, float), np.asarray(corners, float),
                              np.asarray(normal, float), body_a, body_b, direction)
    bounds = [(0.0, None)] * (2 * nj) + [(None, None)] * (2 * nj) + [(0.0, LAMBDA_CAP)]
    cost = np.zeros(4 * nj + 1)
    cost[-1] = -1.0
    ub = (a_ub, b_ub) if a_ub.shape[0] else (None, None)
    res = linprog(cost, A_ub=ub[0], b_ub=ub[1], A_eq=a_eq, b_eq=b_eq, bounds=bounds,
                  method="highs")
    if res.status == 2:
        names = names if names is not None else [f"block {i}" for i in range(nb_)]
        raise ValueError(_cannot_stand(a_eq, b_eq, bounds, a_ub, b_ub,
                                       np.asarray(centroid, float), names, mu))
    if res.status != 0:
        raise ValueError(f"the collapse LP failed: {res.message}")
    geom = (mass, np.asarray(inertia, float), np.asarray(centroid, float),
            np.asarray(corners, float), np.asarray(normal, float), body_a, body_b, direction)
    state = na.Iterate(float(res.x[-1]), res.x, np.asarray(res.eqlin.marginals))
    converged, iterations = True, 0
    if friction == "nonassociative":
        out = na.iterate(a_eq, b_eq, mu, state, float(mass.sum()),
                         lambda duals: _mechanism(duals, *geom)[2], LAMBDA_CAP,
                         desc=(f"limit analysis of {nb_} blocks, {'+' if direction > 0 else '-'}x"
                               if nj >= PROGRESS_JOINTS else None),
                         position=0 if direction > 0 else 1)
        if out.iterations == 0:  # not even the first capacities (10.6) carry gravity
            raise ValueError("the structure cannot stand under gravity: it hangs on shear "
                             "at joints without normal force (non-associative friction, "
                             "docs/theory.md §10)")
        start = state.lambda_
        # the LP's state is kept where it is a fixed point of the iteration and its
        # mechanism does not slide; a sliding one is the cone's dilatant flow, and the
        # Tresca LP's mechanism at that fixed point slides without opening (Eq. 10.6)
        if not (out.converged and out.iterations == 1
                and not _mechanism(state.duals, *geom)[2].any()):
            state, converged, iterations = out.state, out.converged, out.iterations
        # macro-blocks below the converged solution; without one, below the associative
        # bound (an unconverged iterate is no solution: a wedge that is one wins)
        size = float(np.ptp(geom[3].reshape(-1, 2), axis=0).max())
        wedge = mb.lowest(geom[2:7], mass, direction, lambda zero: mb.solve_zeroed(
            cost, ub[0], ub[1], a_eq, b_eq, bounds, zero),
            state.lambda_ if converged else start, size)
        if wedge is not None:  # a macro-block solution below the iteration's (Eq. 10.9)
            state, converged = wedge, True
        elif not converged:
            na.warn_unconverged(out, direction)
    return _collapse(state, geom, g, converged, iterations)


def _collapse(state, geom, g: float, converged: bool, iterations: int) -> Collapse:
    """The :class:`Collapse` of one solved LP state (forces, λ, duals)."""
    mass, inertia, direction, nj = geom[0], geom[1], geom[-1], len(geom[4])
    lam = state.lambda_
    vel, opening, slide = _mechanism(state.duals, *geom)
    if lam >= LAMBDA_CAP * (1 - 1e-9):
        lam = math.inf
    p, delta = equivalent_block(mass, inertia, vel, g)
    if math.isfinite(lam) and not slide.any():  # a rocking mechanism: its finite δ (10.5b)
        d, rate = neutral_angle(mass, geom[2], geom[3], geom[5], geom[6], vel, direction,
                                delta)
        if math.isfinite(d) and d != delta:  # Eq. (3.4) on the leading part's rotation
            p, delta = p * math.sqrt(math.sin(delta) * rate / d), d
    x = state.x
    normal = x[:2 * nj].reshape(nj, 2)
    # sliding (the attribute): a joint that moves along its face while it carries a normal
    # force (friction at its capacity). A joint that opens at both corners separates, and
    # one that carries nothing is free: neither slides, though its faces move along each
    # other (a head joint beside a rotating wedge); `slide` above, any tangential motion,
    # decides only whether the mechanism is a linkage of hinges (the finite δ)
    carries = normal.sum(axis=1) > 1e-9 * max(float(normal.max()), 1e-300)
    slide = slide & ~opening.all(axis=1) & carries
    return Collapse(ap_min=lam * g, lambda_=lam, direction=direction, velocity=vel,
                    opening=opening, sliding=slide, normal_force=normal,
                    tangential_force=x[2 * nj:4 * nj].reshape(nj, 2), p=p, delta=delta,
                    converged=converged, iterations=iterations)


def collapse(assembly, *, mu=None, direction: int | None = None,
             friction: str = "nonassociative") -> Collapse:
    """:func:`limit_analysis` (Eqs. 10.4–10.9) of an
    :class:`~rockarch.mdof.assembly.Assembly` (its own friction coefficients unless ``mu``
    is given)."""
    a = assembly
    return limit_analysis(a.mass, a.inertia, a.centroid, a.corners, a.normal, a.body_a,
                          a.body_b, a.mu if mu is None else mu, g=a.g, direction=direction,
                          names=a.info.get("block_names"), friction=friction)
