"""The general MDOF stepper: any contact graph, Coulomb friction per joint (numba).

The same Moreau–Jean step as :mod:`rockarch.mdof.chain_stepper` (docs/theory.md §6, §9) for
an assembly whose joint k joins body ``ba[k]`` to body ``bb[k]`` (−1: the ground, or a
support moving with it). The normal of joint k is attached to body ``ba[k]``; its corner
points to body ``bb[k]``: the gap of corner c is the distance of b's corner from a's face
line, so a joint may slide along a's face. Per joint: two corner rows and one tangential
row at the corner in contact (the smaller gap), with the joint's Coulomb cone (μ finite) or
the no-slip constraint (μ = ∞, the chain model). Contact solve by non-smooth Gauss–Seidel
(:mod:`rockarch.mdof.graph_solver`); positions stabilised by a few Gauss–Seidel sweeps of
the chain stepper's projection (closed contacts that carried an impulse close exactly,
velocities untouched, never adding energy). Collapse, impacts and records as in the chain
stepper; in addition the largest tangential offset of any joint (``max_slip``) and the most
joints sliding at once.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from rockarch.mdof.chain_solver import EPS_REG, box_qp
from rockarch.mdof.chain_stepper import CHECK_EVERY, CHECK_FROM
from rockarch.mdof.graph_solver import NSGS_TOL, apply_impulse, joint_velocity, nsgs, solve3
from rockarch.mdof.kinematics import advance, cumint, cumint_knots

#: Gauss–Seidel sweeps of the position projection per step (a stabilisation: the remaining
#: error is corrected in the next steps).
PROJECT_SWEEPS = 3
#: Fixed-point iterations on the joints' normal impulses (chains with friction) before a
#: step counts as a failure.
MAX_OUTER = 50
#: Tolerance of that fixed point: the friction bounds in use repeat within FP_TOL of the
#: largest joint impulse.
FP_TOL = 1e-4


@nb.njit(cache=True)
def _point(j, x, y, cs, sn, r):
    """World point of the body-fixed offset r (j < 0: r is a ground point) and the offset
    turned with the body (cs, sn: cos and sin of every body's rotation)."""
    if j < 0:
        return r[0], r[1], 0.0, 0.0
    ox = cs[j] * r[0] - sn[j] * r[1]
    oy = sn[j] * r[0] + cs[j] * r[1]
    return x[j] + ox, y[j] + oy, ox, oy


@nb.njit(cache=True)
def geometry(nj, ba, bb, x, y, ph, ra, rb, n0, gap, ja, jb):
    """Gaps (nj, 3: corner 0, corner 1, tangential offset at the corner in contact) and the
    Jacobian rows (3·nj, 3) w.r.t. bodies a and b; the rows are the exact gradients of the
    gaps (lever arms from each centroid to b's corner)."""
    cs = np.cos(ph)
    sn = np.sin(ph)
    for k in range(nj):
        a = ba[k]
        b = bb[k]
        if a >= 0:
            nx = cs[a] * n0[k, 0] - sn[a] * n0[k, 1]
            ny = sn[a] * n0[k, 0] + cs[a] * n0[k, 1]
        else:
            nx = n0[k, 0]
            ny = n0[k, 1]
        tx = -ny
        ty = nx
        best = 0
        for cc in range(2):
            pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, cc])
            pbx, pby, obx, oby = _point(b, x, y, cs, sn, rb[k, cc])
            dx = pbx - pax
            dy = pby - pay
            gap[k, cc] = nx * dx + ny * dy
            if cc == 1 and gap[k, 1] < gap[k, 0]:
                best = 1
            r = 3 * k + cc
            jb[r, 0] = nx
            jb[r, 1] = ny
            jb[r, 2] = obx * ny - oby * nx
            if a >= 0:
                oax = pbx - x[a]
                oay = pby - y[a]
                ja[r, 0] = -nx
                ja[r, 1] = -ny
                ja[r, 2] = -(oax * ny - oay * nx)
        pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, best])
        pbx, pby, obx, oby = _point(b, x, y, cs, sn, rb[k, best])
        gap[k, 2] = tx * (pbx - pax) + ty * (pby - pay)
        r = 3 * k + 2
        jb[r, 0] = tx
        jb[r, 1] = ty
        jb[r, 2] = obx * ty - oby * tx
        if a >= 0:
            oax = pbx - x[a]
            oay = pby - y[a]
            ja[r, 0] = -tx
            ja[r, 1] = -ty
            ja[r, 2] = -(oax * ty - oay * tx)
        if a < 0:
            for i in range(3):
                ja[3 * k + i, 0] = 0.0
                ja[3 * k + i, 1] = 0.0
                ja[3 * k + i, 2] = 0.0
        if b < 0:
            for i in range(3):
                jb[3 * k + i, 0] = 0.0
                jb[3 * k + i, 1] = 0.0
                jb[3 * k + i, 2] = 0.0


@nb.njit(cache=True)
def joint_blocks(nj, ba, bb, ja, jb, im, ii, eps, wl):
    """The 3×3 diagonal blocks W_kk = J_k·M⁻¹·J_kᵀ (+ eps·I) of every joint."""
    for k in range(nj):
        a = ba[k]
        b = bb[k]
        for i in range(3):
            ri = 3 * k + i
            for j in range(3):
                rj = 3 * k + j
                s = eps if i == j else 0.0
                if a >= 0:
                    s += (ja[ri, 0] * ja[rj, 0] + ja[ri, 1] * ja[rj, 1]) * im[a] \
                        + ja[ri, 2] * ja[rj, 2] * ii[a]
                if b >= 0:
                    s += (jb[ri, 0] * jb[rj, 0] + jb[ri, 1] * jb[rj, 1]) * im[b] \
                        + jb[ri, 2] * jb[rj, 2] * ii[b]
                wl[k, i, j] = s


@nb.njit(cache=True)
def band_w(m, ja, jb, im, ii, wb):
    """Lower band of W = J·M⁻¹·Jᵀ, wb[i, d] = W[i, i − d] (d ≤ wb.shape[1] − 1, which the
    joint ordering of :func:`rockarch.mdof.kernel_data.graph_model` guarantees): every body
    adds the products of the rows of the joints it takes part in."""
    wb[:] = 0.0
    for j in range(m.mass.shape[0]):
        for p in range(m.inc_ptr[j], m.inc_ptr[j + 1]):
            kp = m.inc_joint[p]
            jp = ja if m.inc_side[p] == 0 else jb
            for q in range(m.inc_ptr[j], m.inc_ptr[j + 1]):
                kq = m.inc_joint[q]
                if kq > kp:
                    continue
                jq = ja if m.inc_side[q] == 0 else jb
                for a in range(3):
                    i = 3 * kp + a
                    for b in range(3):
                        r = 3 * kq + b
                        if r <= i:
                            wb[i, i - r] += (jp[i, 0] * jq[r, 0] + jp[i, 1] * jq[r, 1]) * im[j] \
                                + jp[i, 2] * jq[r, 2] * ii[j]


@nb.njit(cache=True)
def banded_friction(m, ws, eps, tol_u, tol_l):
    """Exact contact solve with friction (docs/theory.md §9): box-constrained QPs
    (|Λ_t| ≤ μ·s_k, Λ_n ≥ 0) by the banded active-set method, iterated on the joints'
    normal sums s_k until the bounds in use repeat and every sticking joint lies inside its
    cone, within ``FP_TOL`` of the largest joint impulse (then Λ solves the Coulomb problem
    to that tolerance). Returns the number of banded solves (negative: failed)."""
    nj = m.n0.shape[0]
    total = 0
    for _outer in range(MAX_OUTER):
        for k in range(nj):
            for c in range(2):
                ws.lo[3 * k + c] = 0.0
                ws.hi[3 * k + c] = np.inf
            if math.isinf(m.mu[k]):
                ws.lo[3 * k + 2] = -np.inf
                ws.hi[3 * k + 2] = np.inf
            else:
                b = m.mu[k] * max(ws.lam[3 * k] + ws.lam[3 * k + 1], 0.0)
                if _outer >= 3:  # damped: the plain iteration may oscillate
                    b = 0.5 * (b + ws.hi[3 * k + 2])
                ws.lo[3 * k + 2] = -b
                ws.hi[3 * k + 2] = b
        its = box_qp(3 * nj, ws.wb, ws.q, ws.lo, ws.hi, ws.st, ws.lam, ws.kb, ws.lb, ws.rhs,
                     ws.sol, eps, tol_u, tol_l)
        if its < 0:
            return -1 - total
        total += its
        # converged when no bound in use moved and every sticking joint is inside its cone
        diff = 0.0
        smax = 0.0
        for k in range(nj):
            smax = max(smax, ws.lam[3 * k] + ws.lam[3 * k + 1])
        for k in range(nj):
            if not math.isinf(m.mu[k]):
                b = m.mu[k] * (ws.lam[3 * k] + ws.lam[3 * k + 1])
                if ws.st[3 * k + 2] != 0:
                    diff = max(diff, abs(b - ws.hi[3 * k + 2]))
                else:
                    diff = max(diff, abs(ws.lam[3 * k + 2]) - b)
        if diff <= max(tol_l, FP_TOL * smax):
            return total
    return -1 - total


@nb.njit(cache=True)
def contact_step(m, x, y, ph, vx, vy, om, gtol, hh, eps, tol_u, tol_l, ws):
    """Geometry at (x, y, ph), contact impulses for the free velocities (vx, vy, om), which
    are turned into v⁺ in place. Warm start: ws.lam, ws.case, ws.st. Exact banded solve
    (:func:`banded_friction`), or Gauss–Seidel sweeps if the model says so. Returns the solver's
    iteration count (negative: failed)."""
    nj = m.n0.shape[0]
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, m.n0, ws.gap, ws.ja, ws.jb)
    for k in range(nj):
        for c in range(3):
            r = 3 * k + c
            ws.bias[r] = ws.gap[k, c] / hh if c < 2 and ws.gap[k, c] > gtol else 0.0
    d = np.empty(3)
    if m.banded:
        band_w(m, ws.ja, ws.jb, ws.im, ws.ii, ws.wb)
        for k in range(nj):
            joint_velocity(k, m.ba, m.bb, ws.ja, ws.jb, ws.bias, vx, vy, om, d)
            for i in range(3):
                ws.q[3 * k + i] = d[i]
        its = banded_friction(m, ws, eps, tol_u, tol_l)
    else:
        joint_blocks(nj, m.ba, m.bb, ws.ja, ws.jb, ws.im, ws.ii, eps, ws.wl)
    for k in range(nj):
        for i in range(3):
            d[i] = ws.lam[3 * k + i]
        apply_impulse(k, m.ba, m.bb, ws.ja, ws.jb, d, ws.im, ws.ii, vx, vy, om)
    if m.banded:
        return its
    return nsgs(nj, m.ba, m.bb, ws.ja, ws.jb, ws.wl, ws.bias, m.mu, ws.im, ws.ii, vx, vy, om,
                ws.lam, ws.case, tol_u, tol_l)


@nb.njit(cache=True)
def project(m, x, y, ph, eps, keep, slip_tol, free_t, anchor, ws):
    """Position stabilisation: Gauss–Seidel on W·μ = −gap over the kept rows (closed
    corners that carried an impulse, and their joint's tangential row), then
    q += M⁻¹·Jᵀ·μ (velocities untouched). Tangential targets: 0 for μ = ∞ joints while
    the offset is drift-sized; ``anchor`` (the offset when the joint last slid or was
    open) for a sticking joint; the current offset for a joint in ``free_t`` (sliding or
    open), whose anchor it becomes."""
    nj = m.n0.shape[0]
    nbod = m.mass.shape[0]
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, m.n0, ws.gap, ws.ja, ws.jb)
    joint_blocks(nj, m.ba, m.bb, ws.ja, ws.jb, ws.im, ws.ii, eps, ws.wl)
    for k in range(nj):
        if free_t[k]:
            anchor[k] = ws.gap[k, 2]
    dx = np.zeros(nbod)
    dy = np.zeros(nbod)
    dp = np.zeros(nbod)
    u = np.empty(3)
    a3 = np.empty((3, 3))
    r3 = np.empty(3)
    d = np.empty(3)
    for sweep in range(PROJECT_SWEEPS):
        for kk in range(nj):
            k = kk if sweep % 2 == 0 else nj - 1 - kk
            if not (keep[3 * k] or keep[3 * k + 1] or keep[3 * k + 2]):
                continue
            a = m.ba[k]
            b = m.bb[k]
            for i in range(3):
                r = 3 * k + i
                s = ws.gap[k, i]
                if i == 2:
                    if not math.isinf(m.mu[k]):
                        s -= anchor[k]
                    elif abs(s) > slip_tol:
                        s = 0.0
                if a >= 0:
                    s += ws.ja[r, 0] * dx[a] + ws.ja[r, 1] * dy[a] + ws.ja[r, 2] * dp[a]
                if b >= 0:
                    s += ws.jb[r, 0] * dx[b] + ws.jb[r, 1] * dy[b] + ws.jb[r, 2] * dp[b]
                u[i] = s
            for i in range(3):
                for j in range(3):
                    kept = keep[3 * k + i] and keep[3 * k + j]
                    a3[i, j] = ws.wl[k, i, j] if kept else (1.0 if i == j else 0.0)
                r3[i] = -u[i] if keep[3 * k + i] else 0.0
            if solve3(a3, r3, d):
                apply_impulse(k, m.ba, m.bb, ws.ja, ws.jb, d, ws.im, ws.ii, dx, dy, dp)
    for j in range(nbod):
        x[j] += dx[j]
        y[j] += dy[j]
        ph[j] += dp[j]


class Work(NamedTuple):
    """Scaled geometry and work arrays of one run."""

    ra: np.ndarray
    rb: np.ndarray
    im: np.ndarray
    ii: np.ndarray
    gap: np.ndarray
    ja: np.ndarray
    jb: np.ndarray
    wl: np.ndarray
    bias: np.ndarray
    lam: np.ndarray
    case: np.ndarray
    wb: np.ndarray  # banded solve of chains: W, its factor, the matrix solved
    lb: np.ndarray
    kb: np.ndarray
    q: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    rhs: np.ndarray
    sol: np.ndarray
    st: np.ndarray


@nb.njit(cache=True)
def _work(m, scale, lam, case):
    nj = m.n0.shape[0]
    n = 3 * nj
    kd = m.kd if m.banded else 0
    return Work(m.ra * scale, m.rb * scale, 1.0 / m.mass, 1.0 / (m.inertia * scale * scale),
                np.zeros((nj, 3)), np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((nj, 3, 3)),
                np.zeros(n), lam, case, np.zeros((n, kd + 1)), np.zeros((n, kd + 1)),
                np.zeros((n, kd + 1)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
                np.zeros(n), np.zeros(n, dtype=np.int8))


@nb.njit(cache=True)
def _kinetic(mass, ii, vx, vy, om):
    ke = 0.0
    for j in range(mass.shape[0]):
        ke += 0.5 * (mass[j] * (vx[j] ** 2 + vy[j] ** 2) + om[j] ** 2 / ii[j])
    return ke


@nb.njit(cache=True)
def _sliding(m, ws, vx, vy, om, tol_u, free_t):
    """Number of joints with finite μ that carry a normal impulse and slide (|U_t| > tol_u);
    ``free_t``: those joints and the joints without a normal impulse."""
    n_sl = 0
    for k in range(m.n0.shape[0]):
        free_t[k] = ws.lam[3 * k] + ws.lam[3 * k + 1] <= 0.0
        if math.isinf(m.mu[k]) or free_t[k]:
            continue
        a = m.ba[k]
        b = m.bb[k]
        r = 3 * k + 2
        u = 0.0
        if a >= 0:
            u += ws.ja[r, 0] * vx[a] + ws.ja[r, 1] * vy[a] + ws.ja[r, 2] * om[a]
        if b >= 0:
            u += ws.jb[r, 0] * vx[b] + ws.jb[r, 1] * vy[b] + ws.jb[r, 2] * om[b]
        if abs(u) > tol_u:
            n_sl += 1
            free_t[k] = True
    return n_sl


@nb.njit(cache=True)
def run(m, scale, tk, ak, amp, h, t_end, t_motion, gtol_rel, rec_every, out_t, out_q,
        out_state, out_e):
    """Simulate one assembly (``m``: a :class:`rockarch.mdof.kernel_data.GraphModel`) scaled
    by ``scale`` (lengths) on amp·a(t) [m/s²]. Returns (status, t_collapse,
    max_rot_over_delta, impacts, open_max, n_rec, steps, failures, max_slip, sliding_max)."""
    mass = m.mass
    g = m.g
    nbod = mass.shape[0]
    nj = m.n0.shape[0]
    n = 3 * nj
    ws = _work(m, scale, np.zeros(n), np.zeros(nj, dtype=np.int64))
    tws = _work(m, scale, np.zeros(n), np.zeros(nj, dtype=np.int64))
    cx0 = m.c0[:, 0] * scale
    cy0 = m.c0[:, 1] * scale
    gtol = gtol_rel * m.thick_min * scale
    x = cx0.copy()
    y = cy0.copy()
    ph = np.zeros(nbod)
    vx = np.zeros(nbod)
    vy = np.zeros(nbod)
    om = np.zeros(nbod)
    xm = np.empty(nbod)
    ym = np.empty(nbod)
    phm = np.empty(nbod)
    tvx = np.empty(nbod)
    tvy = np.empty(nbod)
    tom = np.empty(nbod)
    was_open = np.zeros((nj, 2), dtype=np.bool_)
    keep = np.zeros(n, dtype=np.bool_)
    free_t = np.zeros(nj, dtype=np.bool_)
    anchor = np.zeros(nj)
    gmid = np.zeros((nj, 3))
    ck = cumint_knots(tk, ak)
    wmax = 0.0
    for j in range(nbod):
        wmax = max(wmax, ws.im[j], ws.ii[j] * (m.thick_min * scale) ** 2)
    eps = EPS_REG * wmax
    tol_u = NSGS_TOL * g * h
    tol_l = NSGS_TOL * g * h / wmax
    e_scale = mass.sum() * g * m.thick_min * scale
    status = 0
    t_col = np.nan
    mx = 0.0
    impacts = 0
    open_max = 0
    slide_max = 0
    max_slip = 0.0
    n_rec = 0
    fails = 0
    t = 0.0
    step = 0
    i_prev = 0.0
    n_steps = int(math.ceil(t_end / h))
    cap = out_t.shape[0]
    while step < n_steps:
        advance(x, y, ph, vx, vy, om, 0.5 * h, xm, ym, phm)
        i_new = cumint(t + h, tk, ak, ck)
        agbar = amp * (i_new - i_prev) / h
        i_prev = i_new
        for j in range(nbod):
            vx[j] -= h * agbar
            vy[j] -= h * g
        if contact_step(m, xm, ym, phm, vx, vy, om, gtol, h, eps, tol_u, tol_l, ws) < 0:
            fails += 1
        n_sl = _sliding(m, ws, vx, vy, om, tol_u, free_t)
        slide_max = max(slide_max, n_sl)
        advance(xm, ym, phm, vx, vy, om, 0.5 * h, x, y, ph)
        any_keep = False
        for r in range(n):
            k = r // 3
            c = r - 3 * k
            if c < 2:
                keep[r] = ws.lam[r] > 0.0 and ws.gap[k, c] <= gtol
            else:
                keep[r] = keep[r - 1] or keep[r - 2]
            any_keep = any_keep or keep[r]
        for k in range(nj):
            for c in range(3):
                gmid[k, c] = ws.gap[k, c]
            max_slip = max(max_slip, abs(ws.gap[k, 2]))
        if not any_keep:
            for k in range(nj):
                anchor[k] = ws.gap[k, 2]
        else:
            v0 = 0.0
            for j in range(nbod):
                v0 += mass[j] * y[j]
            project(m, x, y, ph, eps, keep, 100.0 * gtol, free_t, anchor, tws)
            dv = -g * v0
            for j in range(nbod):
                dv += g * mass[j] * y[j]
            ke = _kinetic(mass, ws.ii, vx, vy, om)
            if dv > 0.0 and ke > 0.0:
                f = math.sqrt(max(0.0, 1.0 - dv / ke))
                for j in range(nbod):
                    vx[j] *= f
                    vy[j] *= f
                    om[j] *= f
        t += h
        step += 1
        n_open = 0
        for k in range(nj):
            op = False
            for c in range(2):
                o = gmid[k, c] > gtol
                if not o and was_open[k, c] and ws.lam[3 * k + c] > 0.0:
                    impacts += 1
                was_open[k, c] = o
                op = op or o
            if op:
                n_open += 1
        open_max = max(open_max, n_open)
        rho = 0.0
        for j in range(nbod):
            rho = max(rho, abs(ph[j]))
        mx = max(mx, rho / m.delta_ref)
        if rec_every > 0 and step % rec_every == 0 and n_rec < cap:
            out_t[n_rec] = t
            pe = 0.0
            for j in range(nbod):
                out_q[n_rec, j, 0] = x[j]
                out_q[n_rec, j, 1] = y[j]
                out_q[n_rec, j, 2] = ph[j]
                pe += mass[j] * g * (y[j] - cy0[j])
            out_e[n_rec] = _kinetic(mass, ws.ii, vx, vy, om) + pe
            for k in range(nj):
                o0 = gmid[k, 0] > gtol
                o1 = gmid[k, 1] > gtol
                out_state[n_rec, k] = 3 if o0 and o1 else (1 if o1 else (2 if o0 else 0))
            n_rec += 1
        if rho > 0.5 * math.pi:
            status = 1
            t_col = t
            break
        if rho > CHECK_FROM * m.delta_ref and step % CHECK_EVERY == 0:
            # frozen-configuration test: from rest at q under gravity alone
            for j in range(nbod):
                tvx[j] = 0.0
                tvy[j] = -h * g
                tom[j] = 0.0
            for r in range(n):
                tws.lam[r] = 0.5 * ws.lam[r]
            for k in range(nj):
                tws.case[k] = ws.case[k]
            for r in range(n):
                tws.st[r] = ws.st[r]
            contact_step(m, x, y, ph, tvx, tvy, tom, gtol, 0.5 * h, eps, tol_u, tol_l, tws)
            dd = 0.0
            dn = 0.0
            vn = 0.0
            for j in range(nbod):
                ddx = x[j] - cx0[j]
                ddy = y[j] - cy0[j]
                dd += mass[j] * (ddx * tvx[j] + ddy * tvy[j]) + ph[j] * tom[j] / ws.ii[j]
                dn += mass[j] * (ddx * ddx + ddy * ddy) + ph[j] * ph[j] / ws.ii[j]
                vn += mass[j] * (tvx[j] ** 2 + tvy[j] ** 2) + tom[j] ** 2 / ws.ii[j]
            if dd > 1e-6 * math.sqrt(dn * vn):
                status = 1
                t_col = t
                break
        if t >= t_motion and n_open == 0 and n_sl == 0:
            if _kinetic(mass, ws.ii, vx, vy, om) < 1e-12 * e_scale:
                break
    return status, t_col, mx, impacts, open_max, n_rec, step, fails, max_slip, slide_max


@nb.njit(cache=True, parallel=True)
def run_batch(m, scales, tk, ak, amps, hs, t_end, t_motion, gtol_rel):
    """Many (scale, amplitude, step) triples in parallel; summaries only."""
    k = scales.shape[0]
    status = np.zeros(k, dtype=np.int8)
    t_col = np.full(k, np.nan)
    mx = np.zeros(k)
    nimp = np.zeros(k, dtype=np.int64)
    nopen = np.zeros(k, dtype=np.int64)
    fails = np.zeros(k, dtype=np.int64)
    slip = np.zeros(k)
    nslide = np.zeros(k, dtype=np.int64)
    for i in nb.prange(k):
        dt = np.zeros(0)
        dq = np.zeros((0, 1, 3))
        ds = np.zeros((0, 1), dtype=np.int8)
        res = run(m, scales[i], tk, ak, amps[i], hs[i], t_end, t_motion, gtol_rel, 0, dt, dq,
                  ds, dt)
        status[i] = res[0]
        t_col[i] = res[1]
        mx[i] = res[2]
        nimp[i] = res[3]
        nopen[i] = res[4]
        fails[i] = res[7]
        slip[i] = res[8]
        nslide[i] = res[9]
    return status, t_col, mx, nimp, nopen, fails, slip, nslide
