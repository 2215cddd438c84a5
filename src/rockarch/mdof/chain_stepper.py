"""The chain stepper of the MDOF model (frictionless chains; reach it through :mod:`rockarch.mdof`).

Moreau–Jean time stepping (midpoint form) of a *chain* of planar rigid bodies: joint k
lies between body k−1 (its "left/lower" side L) and body k (its "right/upper" side R);
body −1 and body nb are the rigid ground (supports), so an arch (nj = nb + 1), a column
(nj = nb) and a single block (nb = nj = 1) share one kernel. Everything is written in the
frame that moves with the ground (inertia load −m·a_g on every body, supports fixed).

Each joint has two corner contacts (normal, unilateral, restitution 0) and one no-slip
constraint along the joint line (transmits any shear while the joint touches). One step:

1. q_m = q ⊕ (h/2)·v (exact rigid screw motion: a point with zero velocity does not move);
2. contact geometry at q_m; index set = corners with gap ≤ g_tol;
3. v_free = v + h·M⁻¹·f̄ (f̄ = gravity + the exact mean of a_g over the step);
4. impulses Λ from the LCP  U = W·Λ + U_free, 0 ≤ U_n ⊥ Λ_n ≥ 0, U_s = 0, with
   W = J·M⁻¹·Jᵀ (block-tridiagonal, half-bandwidth 5) + ε·I, solved *exactly* as the
   equivalent strictly convex QP by a primal active-set method (finite, no cycling) with
   banded Cholesky solves, warm-started from the previous step's working set; every corner
   is a speculative contact (it may close its current gap by the next midpoint, no more);
5. v⁺ = v_free + M⁻¹·Jᵀ·Λ;  q⁺ = q_m ⊕ (h/2)·v⁺.

Step 4 is the kinetic-energy projection of v_free onto the admissible velocities
(Gauss's principle): it can only remove energy; with restitution 0 it is the inelastic
impact law, docs/theory.md Eq. (5.3) (for a block, Housner's r, Eq. (1.6)).

Collapse (status 1): the structure has passed its neutral configuration, tested on the
frozen configuration: starting from rest at q⁺ under gravity alone, the structure moves
*away* from its initial configuration (the mass-weighted distance D grows). For a block
this is |theta| ≥ alpha exactly; for a four-hinge mechanism it is u ≥ delta. The test
runs every ``CHECK_EVERY`` steps once some block has rotated by more than 0.1·delta_ref.
Safety net: any block rotated by more than π/2.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from rockarch.core.response import thread_map
from rockarch.mdof.chain_solver import EPS_REG, KD, TOL_LCP, band_solve, lcp, masked_band
from rockarch.mdof.kinematics import (
    APPROACH_SPEED,
    IMPACT_HORIZON,
    IMPACT_SPEED,
    advance,
    at_rest,
    cap_projection_energy,
    creep_energy,
    energy,
    impact_ahead,
    kinetic,
    moves_away,
    normal_bias,
    predict,
    record,
    rest_under_gravity,
    step_end,
    step_start,
    strikes,
    tally,
    triple,
)

CHECK_EVERY = 4
#: The collapse test runs once a block has rotated by CHECK_FROM·delta_ref.
CHECK_FROM = 0.5


@nb.njit(cache=True)
def _arm(b, moving, c, s, r0, r1, x, y):
    """Arm (rotated body-frame point r) and position of a contact corner on body b; a
    corner on the ground (``moving`` false) has no arm and stays at r."""
    if moving:
        ax = c * r0 - s * r1
        ay = s * r0 + c * r1
        return ax, ay, x[b] + ax, y[b] + ay
    return 0.0, 0.0, r0, r1


@nb.njit(cache=True)
def _rows(jl, jr, r, dx, dy, ax, ay, bx, by):
    """Jacobian row r of a contact direction d = (dx, dy) with arms a (L body) and b (R)."""
    jl[r, 0] = -dx
    jl[r, 1] = -dy
    jl[r, 2] = -(ax * dy - ay * dx)
    jr[r, 0] = dx
    jr[r, 1] = dy
    jr[r, 2] = bx * dy - by * dx


@nb.njit(cache=True)
def _geometry(nbod, nj, x, y, ph, rl, rr, n0, gap, jl, jr):
    """Gaps (nj, 3: corner 0, corner 1, tangential offset) and Jacobian rows (3·nj, 3)
    w.r.t. the L and R bodies at (x, y, ph)."""
    for k in range(nj):
        lb = k - 1
        rb = k
        if lb >= 0:
            cl = math.cos(ph[lb])
            sl = math.sin(ph[lb])
            nx = cl * n0[k, 0] - sl * n0[k, 1]
            ny = sl * n0[k, 0] + cl * n0[k, 1]
        else:
            cl = 1.0
            sl = 0.0
            nx = n0[k, 0]
            ny = n0[k, 1]
        if rb < nbod:
            cr = math.cos(ph[rb])
            sr = math.sin(ph[rb])
        else:
            cr = 1.0
            sr = 0.0
        best = 0
        bax = 0.0
        bay = 0.0
        bbx = 0.0
        bby = 0.0
        bdx = 0.0
        bdy = 0.0
        for c in range(2):
            ax, ay, plx, ply = _arm(lb, lb >= 0, cl, sl, rl[k, c, 0], rl[k, c, 1], x, y)
            bx, by, prx, pry = _arm(rb, rb < nbod, cr, sr, rr[k, c, 0], rr[k, c, 1], x, y)
            gap[k, c] = nx * (prx - plx) + ny * (pry - ply)
            _rows(jl, jr, 3 * k + c, nx, ny, ax, ay, bx, by)
            if c == 0 or gap[k, 1] < gap[k, 0]:
                best = c
                bax = ax
                bay = ay
                bbx = bx
                bby = by
                bdx = prx - plx
                bdy = pry - ply
        # no-slip row along the joint line s = (-ny, nx), at the corner in contact
        sx = -ny
        sy = nx
        gap[k, 2] = sx * bdx + sy * bdy  # tangential offset of the corners in contact
        r = 3 * k + 2
        _rows(jl, jr, r, sx, sy, bax, bay, bbx, bby)
        if lb < 0:
            jl[3 * k, :] = 0.0
            jl[3 * k + 1, :] = 0.0
            jl[r, :] = 0.0
        if rb >= nbod:
            jr[3 * k, :] = 0.0
            jr[3 * k + 1, :] = 0.0
            jr[r, :] = 0.0
        _ = best


@nb.njit(cache=True)
def _assemble_w(nbod, nj, jl, jr, im, ii, wb):
    """Lower band of W = J M⁻¹ Jᵀ: wb[i, d] = W[i, i − d], d = 0..KD."""
    n = 3 * nj
    for i in range(n):
        ki = i // 3
        for d in range(KD + 1):
            j = i - d
            if j < 0:
                wb[i, d] = 0.0
                continue
            kj = j // 3
            s = 0.0
            if ki == kj:
                lb = ki - 1
                if lb >= 0:
                    s += (jl[i, 0] * jl[j, 0] + jl[i, 1] * jl[j, 1]) * im[lb] \
                        + jl[i, 2] * jl[j, 2] * ii[lb]
                if ki < nbod:
                    s += (jr[i, 0] * jr[j, 0] + jr[i, 1] * jr[j, 1]) * im[ki] \
                        + jr[i, 2] * jr[j, 2] * ii[ki]
            elif ki == kj + 1:
                b = kj  # R of joint kj, L of joint ki
                s = (jl[i, 0] * jr[j, 0] + jl[i, 1] * jr[j, 1]) * im[b] \
                    + jl[i, 2] * jr[j, 2] * ii[b]
            wb[i, d] = s


@nb.njit(cache=True)
def _apply(nbod, n, jl, jr, lam, im, ii, ux, uy, uphi):
    """u += M⁻¹ Jᵀ λ over the contact rows (λ: impulses on velocities, or position
    corrections on positions); joint k acts on bodies k − 1 (L) and k (R)."""
    for r in range(n):
        if lam[r] == 0.0:
            continue
        k = r // 3
        if k - 1 >= 0:
            b = k - 1
            ux[b] += jl[r, 0] * lam[r] * im[b]
            uy[b] += jl[r, 1] * lam[r] * im[b]
            uphi[b] += jl[r, 2] * lam[r] * ii[b]
        if k < nbod:
            ux[k] += jr[r, 0] * lam[r] * im[k]
            uy[k] += jr[r, 1] * lam[r] * im[k]
            uphi[k] += jr[r, 2] * lam[r] * ii[k]


@nb.njit(cache=True)
def _contact_step(nbod, nj, x, y, ph, vfx, vfy, vfo, rl, rr, n0, im, ii, gtol, hh, v_app,
                  bias, strike, eps, tol_u, tol_l, gap, jl, jr, wb, kb, lb, rhs, lam, ufree, inset,
                  free, sol, vx, vy, om):
    """Geometry at (x, y, ph), LCP for v_free, v⁺ into (vx, vy, om). Returns LCP iterations."""
    n = 3 * nj
    _geometry(nbod, nj, x, y, ph, rl, rr, n0, gap, jl, jr)
    for r in range(n):
        k = r // 3
        u = 0.0
        lb_ = k - 1
        if lb_ >= 0:
            u += jl[r, 0] * vfx[lb_] + jl[r, 1] * vfy[lb_] + jl[r, 2] * vfo[lb_]
        if k < nbod:
            u += jr[r, 0] * vfx[k] + jr[r, 1] * vfy[k] + jr[r, 2] * vfo[k]
        c = r - 3 * k
        # a corner in contact, striking or speculative (Eq. 6.3a)
        bias[r] = normal_bias(gap[k, c], u, gtol, hh, v_app) if c < 2 else 0.0
        strike[r] = c < 2 and strikes(u, bias[r], v_app)
        ufree[r] = u + bias[r]
    # every corner is a (speculative) contact; the no-slip row is bilateral and always on
    # (the model has no sliding: an open joint stays hinged at its corner)
    for r in range(n):
        inset[r] = True
        if r % 3 == 2:
            free[r] = True
    _assemble_w(nbod, nj, jl, jr, im, ii, wb)
    its = lcp(n, wb, ufree, inset, free, lam, kb, lb, rhs, eps, tol_u, tol_l, sol)
    for j in range(nbod):
        vx[j] = vfx[j]
        vy[j] = vfy[j]
        om[j] = vfo[j]
    _apply(nbod, n, jl, jr, lam, im, ii, vx, vy, om)
    return its


@nb.njit(cache=True)
def _project(nbod, nj, x, y, ph, rl, rr, n0, im, ii, eps, keep, gap, jl, jr, wb, kb, lb, rhs,
             mu, slip_tol):
    """Post-stabilisation: move the bodies (minimum mass-weighted norm, velocities untouched)
    so that the contacts that carried an impulse this step close exactly (gap = 0, no
    tangential offset). Removes the O(h²) drift of interior hinges."""
    n = 3 * nj
    _geometry(nbod, nj, x, y, ph, rl, rr, n0, gap, jl, jr)
    _assemble_w(nbod, nj, jl, jr, im, ii, wb)
    masked_band(n, wb, keep, eps, kb)
    for i in range(n):
        # normal rows: close the gap; no-slip rows: undo a drift-sized tangential offset
        # (a larger one, left by a separation, is kept: pulling it back would add energy)
        if keep[i] and (i % 3 != 2 or abs(gap[i // 3, 2]) <= slip_tol):
            rhs[i] = -gap[i // 3, i % 3]
        else:
            rhs[i] = 0.0
    if not band_solve(n, kb, rhs, lb, mu):
        return
    _apply(nbod, n, jl, jr, mu, im, ii, x, y, ph)


@nb.njit(cache=True, nogil=True)
def run(model, scale, tk, ak, amp, h, t_end, t_motion, gtol_rel, rec_every, out_t, out_q,
        out_state, out_e):
    """Simulate one assembly (``model``: a :class:`rockarch.mdof.kernel_data.ChainModel`),
    scaled by ``scale`` (lengths), on amp·a(t) [m/s²].

    Returns (status, t_collapse, max_rot_over_delta, impacts, open_max, n_rec, steps,
    lcp_failures). status 1: collapsed, 0: safe. Records every ``rec_every`` steps
    (0: no record) into out_* while they have room.
    """
    mass = model.mass
    inertia = model.inertia
    c0 = model.c0
    rl0 = model.rl
    rr0 = model.rr
    n0 = model.n0
    g = model.g
    thick_min = model.thick_min
    delta_ref = model.delta_ref
    nbod = mass.shape[0]
    nj = n0.shape[0]
    n = 3 * nj
    # scaled geometry
    cx0 = c0[:, 0] * scale
    cy0 = c0[:, 1] * scale
    rl = rl0 * scale
    rr = rr0 * scale
    im = 1.0 / mass
    ii = 1.0 / (inertia * scale * scale)
    gtol = gtol_rel * thick_min * scale
    mtot = mass.sum()
    # work arrays
    x, y, ph, vx, vy, om = at_rest(cx0, cy0)
    xm, ym, phm = triple(nbod)
    vfx, vfy, vfo = triple(nbod)
    tvx, tvy, tom = triple(nbod)
    gap = np.zeros((nj, 3))
    jl = np.zeros((n, 3))
    jr = np.zeros((n, 3))
    wb = np.zeros((n, KD + 1))
    kb = np.zeros((n, KD + 1))
    lb = np.zeros((n, KD + 1))
    rhs = np.zeros(n)
    sol = np.zeros(n)
    lam = np.zeros(n)
    ufree = np.zeros(n)
    bias = np.zeros(n)
    strike = np.zeros(n, dtype=np.bool_)
    inset = np.zeros(n, dtype=np.bool_)
    free = np.zeros(n, dtype=np.bool_)
    t_inset = np.zeros(n, dtype=np.bool_)
    t_free_ = np.zeros(n, dtype=np.bool_)
    t_lam = np.zeros(n)
    was_open = np.zeros((nj, 2), dtype=np.bool_)
    keep = np.zeros(n, dtype=np.bool_)
    mu = np.zeros(n)
    gmid = np.zeros((nj, 2))
    # ground-motion integral
    m = tk.shape[0]
    ck = np.zeros(m)
    for i in range(1, m):
        ck[i] = ck[i - 1] + 0.5 * (ak[i] + ak[i - 1]) * (tk[i] - tk[i - 1])
    # W scale for the regularisation and tolerances
    wmax = 0.0
    for j in range(nbod):
        if im[j] > wmax:
            wmax = im[j]
    eps = EPS_REG * wmax
    tol_u = TOL_LCP * g * h
    tol_l = TOL_LCP * g * h / wmax
    e_scale = mtot * g * thick_min * scale
    status, t_col, mx, fails = 0, np.nan, 0.0, 0
    # counters passed to kernels start as int64, not literals: numba would otherwise
    # compile those kernels once more for the literal while it types the loop
    impacts, open_max, n_rec = np.int64(0), np.int64(0), np.int64(0)
    t, step, i_prev = 0.0, np.int64(0), 0.0
    n_steps = int(math.ceil(t_end / h))
    no_free = np.zeros(0, dtype=np.bool_)  # a chain's joints never slide
    # a step in which a corner is about to strike runs as REFINE substeps (Eq. 6.5)
    gprev = np.zeros((nj, 2))
    ahead = np.bool_(False)
    nsub, sub, t_step, hc = np.int64(1), np.int64(0), 0.0, h
    v_imp = IMPACT_SPEED * g * h
    v_app = APPROACH_SPEED * g * h
    reach = IMPACT_HORIZON * h
    screw = np.ones(nbod, dtype=np.bool_)  # a chain's blocks turn about their hinges
    while step < n_steps:
        nsub, t_step, hc = step_start(sub, ahead, t, t_step, nsub, h, hc, lam)
        i_prev, agbar = predict(x, y, ph, vx, vy, om, hc, xm, ym, phm, t, i_prev, tk, ak, ck,
                                amp, screw)
        for j in range(nbod):
            vfx[j] = vx[j] - hc * agbar
            vfy[j] = vy[j] - hc * g
            vfo[j] = om[j]
        its = _contact_step(nbod, nj, xm, ym, phm, vfx, vfy, vfo, rl, rr, n0, im, ii, gtol,
                            hc, v_app, bias, strike, eps, tol_u, tol_l * hc / h, gap, jl, jr,
                            wb, kb, lb, rhs, lam, ufree, inset, free, sol, vx, vy, om)
        if its < 0:
            fails += 1
        advance(xm, ym, phm, vx, vy, om, 0.5 * hc, x, y, ph, screw)
        any_keep = False
        struck = False
        for r in range(n):
            k = r // 3
            c = r - 3 * k
            if c < 2:  # corners in contact that carried an impulse (not speculative ones)
                keep[r] = lam[r] > 0.0 and bias[r] == 0.0
                struck = struck or (keep[r] and strike[r])
            else:
                keep[r] = True
            any_keep = any_keep or keep[r]
        # record the midpoint gaps (joint states, impacts) before the projection
        for k in range(nj):
            for c in range(2):
                gmid[k, c] = gap[k, c]
        if any_keep:
            v0 = 0.0
            for j in range(nbod):
                v0 += mass[j] * y[j]
            _project(nbod, nj, x, y, ph, rl, rr, n0, im, ii, eps, keep, gap, jl, jr, wb, kb,
                     lb, rhs, mu, 100.0 * gtol)
            if not struck:  # a strike's projection undoes a passage through (Eq. 6.3a)
                cap_projection_energy(mass, ii, vx, vy, om, y, v0, g,
                                      creep_energy(lam, keep, eps, eps, no_free))
        sub, t, step = step_end(sub, nsub, t_step, h, step)
        # joints, impacts
        impacts, open_max, mx, n_open, rho = tally(gmid, gtol, was_open, lam, ph, delta_ref,
                                                   impacts, open_max, mx)
        ahead = impact_ahead(gmid, gprev, gtol, hc, reach, v_imp)
        if sub == 0 and rec_every > 0 and step % rec_every == 0 and n_rec < out_t.shape[0]:
            record(n_rec, t, x, y, ph, gmid, gtol, out_t, out_q, out_state)
            out_e[n_rec] = energy(mass, ii, vx, vy, om, y, cy0, g)
            n_rec += 1
        if rho > 0.5 * math.pi:
            status = 1
            t_col = t
            break
        if sub > 0:  # the rest of this step's substeps
            continue
        if rho > CHECK_FROM * delta_ref and step % CHECK_EVERY == 0:
            # frozen-configuration test: from rest at q under gravity alone
            rest_under_gravity(tvx, tvy, tom, h, g)
            for r in range(n):
                t_inset[r] = inset[r]
                t_free_[r] = free[r]
            _contact_step(nbod, nj, x, y, ph, tvx, tvy, tom, rl, rr, n0, im, ii, gtol,
                          0.5 * h, v_app, bias, strike, eps, tol_u, tol_l, gap, jl, jr, wb, kb, lb,
                          rhs, t_lam, ufree, t_inset, t_free_, sol, tvx, tvy, tom)
            if moves_away(mass, ii, x, y, ph, cx0, cy0, tvx, tvy, tom):
                status = 1
                t_col = t
                break
        if t >= t_motion:
            # at rest: every joint closed and (numerically) no kinetic energy
            if n_open == 0 and kinetic(mass, ii, vx, vy, om) < 1e-12 * e_scale:
                break
    return status, t_col, mx, impacts, open_max, n_rec, step, fails


def run_batch(model, scales, tk, ak, amps, hs, t_end, t_motion, gtol_rel):
    """Many (scale, amplitude, step) triples side by side on numba's threads
    (:func:`rockarch.core.response.thread_map`); summaries only: (status, t_collapse,
    max ratio, impacts, most open joints, failed solves) arrays."""
    def one(i):
        return run(model, scales[i], tk, ak, amps[i], hs[i], t_end, t_motion, gtol_rel, 0,
                   np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8),
                   np.zeros(0))

    res = thread_map(one, scales.shape[0])
    cols = ((0, np.int8), (1, float), (2, float), (3, np.int64), (4, np.int64), (7, np.int64))
    return tuple(np.array([r[c] for r in res], dtype=t) for c, t in cols)
