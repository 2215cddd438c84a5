"""Kinematics and ground-motion helpers shared by the MDOF steppers (numba).

``advance`` moves rigid bodies exactly with a constant spatial twist (docs/theory.md
Eq. (6.1)'s midpoint rule); ``cumint`` is the exact integral of a piecewise-linear record,
so that the step mean of a_g is exact whatever the record's sampling.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

#: Substeps of a step in which a corner is about to strike (docs/theory.md Eq. (6.5)):
#: Moreau–Jean places an impact only to within its step, a first-order error that the
#: many impacts of a multi-block collapse accumulate; these steps are divided by this.
REFINE = 3
#: A corner strikes if it closes faster than this fraction of g·h (slower closings, such
#: as the head joints of a resting wall as the ground acceleration turns, transfer no
#: momentum worth resolving) ...
IMPACT_SPEED = 1.0
#: ... within this many steps at its present closing speed.
IMPACT_HORIZON = 2.0
#: A corner approaches if its free normal velocity closes faster than this multiple of
#: g·h (docs/theory.md Eq. (6.3a)); slower ones keep the tolerance. A corner resting on
#: the ground closes at g·h in the free velocity (one step of gravity): 1.5 leaves it
#: alone and catches the slow strikes of small rocking (a block's corner at a few cm/s).
APPROACH_SPEED = 1.5


@nb.njit(cache=True)
def normal_bias(gap, u, gtol, hh, v_app):
    """Bias b of a normal row, U_n + b ≥ 0 (docs/theory.md Eq. (6.3a)), for the corner's gap
    [m] at the step's midpoint and its free normal velocity ``u`` [m/s] (negative:
    closing), step ``hh`` [s], approach speed ``v_app`` [m/s].

    A corner that approaches and would strike within the half step left after the
    midpoint is in contact now (b = 0: the impact of this step); one that approaches but
    would not may close at most its gap by the step's end (b = 2·gap/hh), so no partial
    impulse acts before the strike. Other corners: closed within the tolerance ``gtol``
    (b = 0), or speculative beyond it (b = gap/hh, closed by the next midpoint).
    """
    if gap <= 0.0:
        return 0.0
    if u < -v_app:
        return 0.0 if gap <= -0.5 * u * hh else 2.0 * gap / hh
    return gap / hh if gap > gtol else 0.0


@nb.njit(cache=True, inline="always")
def strikes(u, bias, v_app):
    """Whether a corner strikes in this step (docs/theory.md Eq. (6.3a)): it approaches
    faster than ``v_app`` and its bias (:func:`normal_bias`) puts it in contact now."""
    return u < -v_app and bias == 0.0


@nb.njit(cache=True)
def advance(x, y, ph, vx, vy, om, dt, xo, yo, pho, screw):
    """Exact rigid motion over dt. A body in contact (``screw[j]``: it took an impulse in
    the last solve) moves with a constant spatial twist (rotation about the fixed
    instantaneous centre, exact for a block turning about a corner) and (vx, vy) are turned
    in place to the centroid's new velocity; a free body (in flight) keeps its centroid's
    velocity and turns about its centroid (docs/theory.md §6)."""
    for j in range(x.shape[0]):
        a = om[j] * dt
        if a == 0.0 or not screw[j]:
            xo[j] = x[j] + vx[j] * dt
            yo[j] = y[j] + vy[j] * dt
        else:
            sa = math.sin(a) / a
            ca = 2.0 * math.sin(0.5 * a) ** 2 / a
            xo[j] = x[j] + dt * (sa * vx[j] - ca * vy[j])
            yo[j] = y[j] + dt * (sa * vy[j] + ca * vx[j])
            # constant *spatial* twist: the centroid velocity turns with the body
            c = math.cos(a)
            s = math.sin(a)
            u = vx[j]
            vx[j] = c * u - s * vy[j]
            vy[j] = s * u + c * vy[j]
        pho[j] = ph[j] + a


@nb.njit(cache=True)
def cumint(t, tk, ak, ck):
    """∫_0^t a_g (piecewise linear through the knots, zero outside them)."""
    m = tk.shape[0]
    if t <= tk[0]:
        return 0.0
    if t >= tk[m - 1]:
        return ck[m - 1]
    lo = 0
    hi = m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tk[mid] <= t:
            lo = mid
        else:
            hi = mid
    dt = t - tk[lo]
    slope = (ak[lo + 1] - ak[lo]) / (tk[lo + 1] - tk[lo])
    return ck[lo] + dt * (ak[lo] + 0.5 * dt * slope)


@nb.njit(cache=True)
def cumint_knots(tk, ak):
    """Running integral of a_g at the knots (the table ``cumint`` interpolates)."""
    m = tk.shape[0]
    ck = np.zeros(m)
    for i in range(1, m):
        ck[i] = ck[i - 1] + 0.5 * (ak[i] + ak[i - 1]) * (tk[i] - tk[i - 1])
    return ck


@nb.njit(cache=True)
def cap_projection_energy(mass, ii, vx, vy, om, y, v0, g, creep):
    """After a position projection: a gain of potential energy (O(h²) drift, not physics,
    ``v0`` = Σ m·y before it) is taken from the kinetic energy, so the projection never
    adds energy (docs/mdof.md, step 6); not called in a step where a corner struck (Eq.
    (6.3a)). ``ii`` holds inverse moments of inertia. ``creep``
    (:func:`creep_energy`): what the step's regularised contacts took by creeping, which
    the projection gives back, is not charged (a heavy block resting on the ground would
    otherwise stop a light one sliding or rocking on it)."""
    dv = -g * v0 - creep
    ke = 0.0
    for j in range(mass.shape[0]):
        dv += g * mass[j] * y[j]
        ke += 0.5 * (mass[j] * (vx[j] ** 2 + vy[j] ** 2) + om[j] ** 2 / ii[j])
    if dv > 0.0 and ke > 0.0:
        f = math.sqrt(max(0.0, 1.0 - dv / ke))
        for j in range(mass.shape[0]):
            vx[j] *= f
            vy[j] *= f
            om[j] *= f


@nb.njit(cache=True)
def creep_energy(lam, keep, eps_n, eps_t, free_t):
    """Σ ε·Λ² over the kept rows (3 per joint: two corners with ε_n, the tangential row with
    ε_t unless its joint is in ``free_t``, sliding or open; an empty ``free_t``: none is):
    the energy the regularised law's creep u = −ε·Λ took in the step, which the position
    projection returns (:func:`cap_projection_energy`)."""
    e = 0.0
    for r in range(keep.shape[0]):
        if not keep[r]:
            continue
        if r % 3 < 2:
            e += eps_n * lam[r] ** 2
        elif free_t.shape[0] == 0 or not free_t[r // 3]:
            e += eps_t * lam[r] ** 2
    return e


@nb.njit(cache=True)
def count_joints(gmid, gtol, was_open, lam):
    """Impacts (a corner that was open taking a compressive impulse) and open joints of one
    step; updates ``was_open`` (a corner back within the tolerance stays open until it
    strikes: an approaching corner keeps its bias, Eq. (6.3a)). Returns (impacts, open
    joints)."""
    impacts = 0
    n_open = 0
    for k in range(gmid.shape[0]):
        op = False
        for c in range(2):
            o = gmid[k, c] > gtol
            hit = lam[3 * k + c] > 0.0
            if not o and was_open[k, c] and hit:
                impacts += 1
            was_open[k, c] = o or (was_open[k, c] and not hit)
            op = op or o
        if op:
            n_open += 1
    return impacts, n_open


@nb.njit(cache=True)
def moves_away(mass, ii, x, y, ph, cx0, cy0, tvx, tvy, tom):
    """Frozen-configuration collapse test (docs/theory.md §6): does the velocity (tvx, tvy,
    tom) that gravity alone gives the structure at rest in its current configuration point
    further away from the initial configuration (cx0, cy0, 0) in the kinetic metric?"""
    dd = 0.0
    dn = 0.0
    vn = 0.0
    for j in range(mass.shape[0]):
        ddx = x[j] - cx0[j]
        ddy = y[j] - cy0[j]
        dd += mass[j] * (ddx * tvx[j] + ddy * tvy[j]) + ph[j] * tom[j] / ii[j]
        dn += mass[j] * (ddx * ddx + ddy * ddy) + ph[j] * ph[j] / ii[j]
        vn += mass[j] * (tvx[j] ** 2 + tvy[j] ** 2) + tom[j] ** 2 / ii[j]
    return dd > 1e-6 * math.sqrt(dn * vn)


@nb.njit(cache=True)
def record(n_rec, t, x, y, ph, gmid, gtol, out_t, out_q, out_state):
    """Store the time, block positions and joint states (0 closed, 1 pivot on corner 0,
    2 pivot on corner 1, 3 open) of one step in row ``n_rec`` of the history."""
    out_t[n_rec] = t
    for j in range(out_q.shape[1]):
        out_q[n_rec, j, 0] = x[j]
        out_q[n_rec, j, 1] = y[j]
        out_q[n_rec, j, 2] = ph[j]
    for k in range(gmid.shape[0]):
        o0 = gmid[k, 0] > gtol
        o1 = gmid[k, 1] > gtol
        out_state[n_rec, k] = 3 if o0 and o1 else (1 if o1 else (2 if o0 else 0))


@nb.njit(cache=True)
def kinetic(mass, ii, vx, vy, om):
    """Kinetic energy of the blocks, Σ ½(m v² + ω²/i) with ``ii`` the inverse inertia [J]."""
    ke = 0.0
    for j in range(mass.shape[0]):
        ke += 0.5 * (mass[j] * (vx[j] ** 2 + vy[j] ** 2) + om[j] ** 2 / ii[j])
    return ke


@nb.njit(cache=True)
def energy(mass, ii, vx, vy, om, y, cy0, g):
    """Mechanical energy above the initial configuration: kinetic + Σ m g (y − y0) [J]."""
    pe = 0.0
    for j in range(mass.shape[0]):
        pe += mass[j] * g * (y[j] - cy0[j])
    return kinetic(mass, ii, vx, vy, om) + pe


@nb.njit(cache=True)
def predict(x, y, ph, vx, vy, om, h, xm, ym, phm, t, i_prev, tk, ak, ck, amp, screw):
    """Start of a Moreau–Jean step (docs/theory.md §6): the midpoint configuration
    (xm, ym, phm) half a step ahead (:func:`advance`), and the ground's velocity integral at
    t + h with the mean ground acceleration over the step. Returns (integral, mean)."""
    advance(x, y, ph, vx, vy, om, 0.5 * h, xm, ym, phm, screw)
    return ground_increment(t, h, i_prev, tk, ak, ck, amp)


@nb.njit(cache=True)
def tally(gmid, gtol, was_open, lam, ph, delta_ref, impacts, open_max, mx):
    """End-of-step counts: impacts and open joints (:func:`count_joints`), the largest
    rotation rho and the peak rho/delta_ref. Returns (impacts, open_max, mx, n_open, rho)."""
    di, n_open = count_joints(gmid, gtol, was_open, lam)
    rho = largest_rotation(ph)
    return impacts + di, max(open_max, n_open), max(mx, rho / delta_ref), n_open, rho


@nb.njit(cache=True)
def ground_increment(t, h, i_prev, tk, ak, ck, amp):
    """The ground's velocity integral at t + h and the mean ground acceleration over the
    step [t, t + h] (amp · Δ∫a_g / h, docs/theory.md §6). Returns (integral, mean)."""
    i_new = cumint(t + h, tk, ak, ck)
    return i_new, amp * (i_new - i_prev) / h


@nb.njit(cache=True)
def impact_ahead(gmid, gprev, gtol, hc, reach, v_imp):
    """True if an open corner is about to strike (docs/theory.md Eq. (6.5)): its gap at the
    step's midpoint fell by more than ``v_imp``·hc since the last (sub)step of length
    ``hc`` [s], and at that closing speed it closes within ``reach`` [s]. Updates
    ``gprev`` (the gaps of the last (sub)step) to ``gmid``."""
    ahead = False
    for k in range(gmid.shape[0]):
        for c in range(2):
            gn = gmid[k, c]
            closing = gprev[k, c] - gn
            if gn > 0.0 and closing > v_imp * hc and gn <= closing / hc * reach:
                ahead = True
            gprev[k, c] = gn
    return ahead


@nb.njit(cache=True)
def step_start(sub, ahead, t, t_step, nsub, h, hc_last, lam):
    """Start of a (sub)step of the step h (Eq. 6.5): at a step's start (``sub`` 0) it is
    divided into REFINE substeps if a corner is about to strike (``ahead``). The warm
    start's impulses ``lam`` are scaled to the new length. Returns (nsub, t_step, hc)."""
    if sub == 0:
        nsub = REFINE if ahead else 1
        t_step = t
    hc = h / nsub
    if hc != hc_last:
        for r in range(lam.shape[0]):
            lam[r] *= hc / hc_last
    return nsub, t_step, hc


@nb.njit(cache=True)
def step_end(sub, nsub, t_step, h, step):
    """End of a (sub)step: returns (sub, t, step), ``sub`` 0 and ``step`` + 1 when the
    step h is complete."""
    sub += 1
    if sub == nsub:
        return 0, t_step + h, step + 1
    return sub, t_step + sub * (h / nsub), step


@nb.njit(cache=True)
def largest_rotation(ph):
    """max_j |φ_j| of the blocks [rad]."""
    rho = 0.0
    for j in range(ph.shape[0]):
        a = abs(ph[j])
        if a > rho:
            rho = a
    return rho


@nb.njit(cache=True)
def rest_under_gravity(tvx, tvy, tom, h, g):
    """Free velocities of the frozen-configuration test: at rest, then one step of gravity."""
    for j in range(tvx.shape[0]):
        tvx[j] = 0.0
        tvy[j] = -h * g
        tom[j] = 0.0


@nb.njit(cache=True)
def at_rest(cx0, cy0):
    """Positions and velocities (x, y, φ, vx, vy, ω) of blocks at rest with their centres
    at (cx0, cy0)."""
    n = cx0.shape[0]
    return cx0.copy(), cy0.copy(), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)


@nb.njit(cache=True)
def triple(n):
    """Three work vectors (x, y, φ or vx, vy, ω) for n blocks."""
    return np.empty(n), np.empty(n), np.empty(n)
