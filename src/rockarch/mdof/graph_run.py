"""The run loop of the general MDOF stepper (any contact graph, friction; numba).

One Moreau–Jean step per iteration (the pieces: :mod:`rockarch.mdof.graph_stepper`);
collapse test, impacts, joint states and records exactly as in
:mod:`rockarch.mdof.chain_stepper`, plus ``max_slip``, the most joints sliding at once and
the point contacts of new contacts (:mod:`rockarch.mdof.collision`).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from rockarch.core.response import thread_map
from rockarch.mdof import kinematics as kin
from rockarch.mdof.chain_solver import EPS_REG
from rockarch.mdof.chain_stepper import CHECK_EVERY, CHECK_FROM
from rockarch.mdof.contact_solver import rest_interval
from rockarch.mdof.graph_stepper import OFF_GAP, contact_step, make_work, project

#: Regularisation ε_n of the normal rows, relative to the largest inverse mass
#: (docs/theory.md Eq. (9.4)): a closed corner carrying Λ moves in at ε_nΛ, which the
#: position projection takes back. It decides how a hyperstatic structure shares its load
#: between redundant contacts, and with it the conditioning of the step ...
EPS_N = EPS_REG
#: ... and ε_t of the tangential rows: a sticking joint creeps at ε_tΛ_t, which nothing
#: takes back, so it stays that of the chain stepper.
EPS_T = EPS_REG
#: Impulse tolerance of the friction fixed point, as a fraction of g·h over the largest
#: inverse mass (the sign tolerance of the contact law).
LAM_TOL = 1e-6
#: New contacts are searched every this many steps (sooner if the blocks speed up), within
#: the distance two corners can close meanwhile: the contacts found are kept (as speculative
#: rows, inactive while they do not close) until the next search.
DETECT_EVERY = 8
#: A structure whose every point moves slower than this fraction of g·h is at rest (docs/theory.md
#: Eq. (9.11)): above the creep of the regularised rows of a 20-course wall (7e-6·g·h), and
#: reached within one step by any motion driven by an unbalanced acceleration above 1e-4·g.
REST_SPEED = 1e-4


@nb.njit(cache=True)
def _vmax(vx, vy, om, rad):
    """Largest speed of any block point [m/s]."""
    vmax = 0.0
    for j in range(vx.shape[0]):
        vmax = max(vmax, math.sqrt(vx[j] ** 2 + vy[j] ** 2) + abs(om[j]) * rad[j])
    return vmax


@nb.njit(cache=True)
def _radii(m, scale):
    """Largest distance of an outline vertex from its body's centroid (scaled)."""
    rad = np.zeros(m.mass.shape[0])
    for v in range(m.pv.shape[0]):
        j = m.pbody[m.vpoly[v]]
        if j >= 0:
            rad[j] = max(rad[j], math.hypot(m.pv[v, 0], m.pv[v, 1]) * scale)
    return rad


@nb.njit(cache=True)
def _point_impacts(m, ws, was_closed):
    """Point contacts that carry a compressive impulse now and did not the step before
    (``was_closed`` holds the keys that did; updated)."""
    nj3 = 3 * m.n0.shape[0]
    imp = 0
    n = ws.cnt[0]
    for i in range(n):
        if ws.lam[nj3 + 2 * i] > 0.0:
            key = ws.ckey[i]
            found = False
            for q in range(was_closed.shape[0]):
                if was_closed[q] == key:
                    found = True
                    break
            if not found:
                imp += 1
    k = 0
    for i in range(n):
        if ws.lam[nj3 + 2 * i] > 0.0 and k < was_closed.shape[0]:
            was_closed[k] = ws.ckey[i]
            k += 1
    for q in range(k, was_closed.shape[0]):
        was_closed[q] = -1
    return imp


@nb.njit(cache=True)
def _sliding(m, ws, vx, vy, om, tol_u, free_t):
    """Number of joints with finite μ that carry a normal impulse and slide (|U_t| > tol_u);
    ``free_t``: those joints and the joints without a normal impulse."""
    ja, jb = ws.rows.ja, ws.rows.jb
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
            u += ja[r, 0] * vx[a] + ja[r, 1] * vy[a] + ja[r, 2] * om[a]
        if b >= 0:
            u += jb[r, 0] * vx[b] + jb[r, 1] * vy[b] + jb[r, 2] * om[b]
        if abs(u) > tol_u:
            n_sl += 1
            free_t[k] = True
    return n_sl


@nb.njit(cache=True)
def _touched(ws, n_rows, screw):
    """``screw[j]``: body j took an impulse in the step's solve (it moves about a contact,
    :func:`rockarch.mdof.kinematics.advance`); the others are in flight."""
    rba, rbb, lam = ws.rows.rba, ws.rows.rbb, ws.lam
    screw[:] = False
    for r in range(n_rows):
        if lam[r] != 0.0:
            a = rba[r]
            b = rbb[r]
            if a >= 0:
                screw[a] = True
            if b >= 0:
                screw[b] = True


@nb.njit(cache=True)
def _fallen(m, gap):
    """True if some block has slid off everything that carried it: every joint of the block
    has faces that no longer overlap (a block falling free: collapse)."""
    for j in range(m.mass.shape[0]):
        off = True
        for p in range(m.inc_ptr[j], m.inc_ptr[j + 1]):
            if gap[m.inc_joint[p], 0] < OFF_GAP:
                off = False
                break
        if off:
            return True
    return False


@nb.njit(cache=True, nogil=True)
def run(m, scale, tk, ak, amp, h, t_end, t_motion, gtol_rel, rec_every, out_t, out_q,
        out_state, out_e, through, skip_rest=True):
    """Simulate one assembly (``m``: a :class:`rockarch.mdof.kernel_data.GraphModel`) scaled
    by ``scale`` (lengths) on amp·a(t) [m/s²]; ``through``: go on after a collapse (until
    rest or t_end) instead of stopping there. Returns (status, t_collapse,
    max_rot_over_delta, impacts, open_max, n_rec, steps, failures, max_slip, sliding_max,
    most new contacts carrying an impulse at once, steps skipped at rest); after a
    collapse, the five from max_rot_over_delta to sliding_max are those reached at the
    collapse, also when ``through`` follows the fall (the other four cover the whole run).

    A step whose contact problem does not settle (docs/theory.md §9) runs again as
    ``REFINE`` substeps warm-started from its last proximal iterate; ``failures`` counts the
    (sub)steps that do not settle even so.

    A structure at rest stays at rest while the step's mean ground acceleration stays in
    the interval where its contact forces remain admissible (docs/theory.md Eq. (9.11),
    :func:`rockarch.mdof.contact_solver.rest_interval`): those steps are not solved again,
    only counted and recorded (``skip_rest`` False: every step is solved, the reference of
    the shortcut's tests and benchmarks)."""
    mass = m.mass
    g = m.g
    nbod = mass.shape[0]
    nj = m.n0.shape[0]
    n = 3 * nj
    ws = make_work(m, scale, m.contact_cap)
    tws = make_work(m, scale, m.contact_cap)
    rad = _radii(m, scale)
    was_closed = np.full(m.contact_cap, -1, dtype=np.int64)
    cx0 = m.c0[:, 0] * scale
    cy0 = m.c0[:, 1] * scale
    gtol = gtol_rel * m.thick_min * scale
    x, y, ph, vx, vy, om = kin.at_rest(cx0, cy0)
    xm, ym, phm = kin.triple(nbod)
    tvx, tvy, tom = kin.triple(nbod)
    svx, svy, som = kin.triple(nbod)
    was_open = np.zeros((nj, 2), dtype=np.bool_)
    keep = np.zeros(n, dtype=np.bool_)
    free_t = np.zeros(nj, dtype=np.bool_)
    anchor = np.zeros(nj)
    gmid = np.zeros((nj, 3))
    ck = kin.cumint_knots(tk, ak)
    can_slide = not np.all(np.isinf(m.mu))
    wmax = 0.0
    for j in range(nbod):
        wmax = max(wmax, ws.im[j], ws.ii[j] * (m.thick_min * scale) ** 2)
    eps = EPS_T * wmax
    eps_n = EPS_N * wmax
    tol_u = LAM_TOL * g * h
    v_rest = REST_SPEED * g * h
    tol_l = LAM_TOL * g * h / wmax
    e_scale = mass.sum() * g * m.thick_min * scale
    status, t_col, mx, fails = 0, np.nan, 0.0, 0
    # counters passed to kernels start as int64, not literals: numba would otherwise
    # compile those kernels once more for the literal while it types the loop
    impacts, open_max, n_rec = np.int64(0), np.int64(0), np.int64(0)
    slide_max, max_slip, points_max = 0, 0.0, 0
    at_col = (mx, impacts, open_max, max_slip, np.int64(slide_max))
    t, step, i_prev = 0.0, np.int64(0), 0.0
    n_steps = int(math.ceil(t_end / h))
    next_search, v_search, next_rest, rest_wait = 0, 0.0, 0, 1
    a_max = 0.0
    lam0 = np.zeros(ws.lam.shape[0])
    lam1 = np.zeros(ws.lam.shape[0])
    skipped = 0
    for i in range(ak.shape[0]):
        a_max = max(a_max, abs(amp * ak[i]))
    # a step in which a corner is about to strike runs as REFINE substeps (Eq. 6.5)
    gprev = np.zeros((nj, 2))
    ahead = np.bool_(False)
    nsub, sub, t_step, hc = np.int64(1), np.int64(0), 0.0, h
    v_imp = kin.IMPACT_SPEED * g * h
    v_app = kin.APPROACH_SPEED * g * h
    reach = kin.IMPACT_HORIZON * h
    retry = False
    i_step = i_prev
    screw = np.ones(nbod, dtype=np.bool_)  # bodies in contact (kin.advance)
    while step < n_steps:
        nsub, t_step, hc = kin.step_start(sub, ahead or retry, t, t_step, nsub, h, hc, ws.lam)
        retry = False
        if sub == 0:
            i_step = i_prev
            for j in range(nbod):
                svx[j] = vx[j]
                svy[j] = vy[j]
                som[j] = om[j]
        i_prev, agbar = kin.predict(x, y, ph, vx, vy, om, hc, xm, ym, phm, t, i_prev, tk, ak,
                                    ck, amp, screw)
        for j in range(nbod):
            vx[j] -= hc * agbar
            vy[j] -= hc * g
        vnow = _vmax(vx, vy, om, rad)
        margin = -1.0
        if step >= next_search or vnow > 2.0 * v_search + g * h:
            # two corners close at most at 2·(vmax + the speed they gain) meanwhile
            dt = DETECT_EVERY * h
            margin = gtol + 2.0 * dt * (2.0 * vnow + dt * (g + a_max))
            next_search = step + DETECT_EVERY
            v_search = vnow
        its = contact_step(m, xm, ym, phm, vx, vy, om, gtol, hc, v_app, eps_n, eps, tol_u,
                           tol_l * hc / h, margin, ws)
        if its < 0 and nsub == 1 and ws.cnt[1] == 0:
            # not settled: the step again as REFINE substeps (Eq. 6.5), warm-started from
            # the last proximal iterate
            i_prev = i_step
            for j in range(nbod):
                vx[j] = svx[j]
                vy[j] = svy[j]
                om[j] = som[j]
            retry = True
            continue
        if its < 0 or ws.cnt[1] > 0:  # not solved, or more new contacts than room
            fails += 1
            ws.cnt[1] = 0
        n_touch = 0
        for i in range(ws.cnt[0]):
            if ws.lam[n + 2 * i] > 0.0:
                n_touch += 1
        points_max = max(points_max, n_touch)
        n_sl = _sliding(m, ws, vx, vy, om, tol_u, free_t)
        slide_max = max(slide_max, n_sl)
        _touched(ws, n + 2 * ws.cnt[0], screw)
        kin.advance(xm, ym, phm, vx, vy, om, 0.5 * hc, x, y, ph, screw)
        any_keep = False
        struck = False
        for r in range(n):
            k = r // 3
            c = r - 3 * k
            if c < 2:
                keep[r] = ws.lam[r] > 0.0 and ws.bias[r] == 0.0
                struck = struck or (keep[r] and ws.strike[r])
            else:
                keep[r] = keep[r - 1] or keep[r - 2]
            any_keep = any_keep or keep[r]
        for k in range(nj):
            for c in range(3):
                gmid[k, c] = ws.gap[k, c]
            if ws.gap[k, 0] <= gtol or ws.gap[k, 1] <= gtol:  # a separated joint does not slip
                max_slip = max(max_slip, abs(ws.gap[k, 2]))
        if not any_keep:
            for k in range(nj):
                anchor[k] = ws.gap[k, 2]
        else:
            v0 = 0.0
            for j in range(nbod):
                v0 += mass[j] * y[j]
            project(m, x, y, ph, eps, keep, 100.0 * gtol, free_t, anchor, tws, ws)
            if not struck:  # a strike's projection undoes a passage through (Eq. 6.3a)
                kin.cap_projection_energy(mass, ws.ii, vx, vy, om, y, v0, g,
                                          kin.creep_energy(ws.lam, keep, eps_n, eps, free_t))
        sub, t, step = kin.step_end(sub, nsub, t_step, h, step)
        impacts, open_max, mx, n_open, rho = kin.tally(gmid, gtol, was_open, ws.lam, ph,
                                                   m.delta_ref, impacts, open_max, mx)
        impacts += _point_impacts(m, ws, was_closed)
        ahead = kin.impact_ahead(gmid, gprev, gtol, hc, reach, v_imp)
        if sub == 0 and rec_every > 0 and step % rec_every == 0 and n_rec < out_t.shape[0]:
            kin.record(n_rec, t, x, y, ph, gmid, gtol, out_t, out_q, out_state)
            out_e[n_rec] = kin.energy(mass, ws.ii, vx, vy, om, y, cy0, g)
            n_rec += 1
        if status == 0 and (rho > 0.5 * math.pi or (can_slide and _fallen(m, gmid))):
            status = 1
            t_col = t
            at_col = (mx, impacts, open_max, max_slip, slide_max)
            if not through:
                break
        if sub > 0:  # the rest of this step's substeps
            continue
        if status == 0 and rho > CHECK_FROM * m.delta_ref and step % CHECK_EVERY == 0:
            # frozen-configuration test: from rest at q under gravity alone
            kin.rest_under_gravity(tvx, tvy, tom, h, g)
            for r in range(n):
                tws.lam[r] = 0.5 * ws.lam[r]
                tws.sw.st[r] = ws.sw.st[r]
            tws.cnt[0] = 0
            tws.sw.state[0] = 0
            contact_step(m, x, y, ph, tvx, tvy, tom, gtol, 0.5 * h, v_app, eps_n, eps, tol_u, tol_l,
                         gtol, tws)
            if kin.moves_away(mass, ws.ii, x, y, ph, cx0, cy0, tvx, tvy, tom):
                status = 1
                t_col = t
                at_col = (mx, impacts, open_max, max_slip, slide_max)
                if not through:
                    break
        if t >= t_motion and n_open == 0 and n_sl == 0:
            if kin.kinetic(mass, ws.ii, vx, vy, om) < 1e-12 * e_scale:
                break
        if not skip_rest or its < 0 or n_sl > 0 or step >= n_steps or step < next_rest \
                or _vmax(vx, vy, om, rad) > v_rest:
            continue
        # at rest: skip the steps whose mean ground acceleration keeps it at rest (Eq. 9.11)
        lo, hi = rest_interval(nbod, 3 * nj + 2 * ws.cnt[0], ws.rows, ws.bias, eps_n, eps, ws.sw,
                               tol_u, tol_l, ws.lref[0], h, g, v_rest, lam0, lam1)
        a_last = math.nan
        if lo <= hi:
            rest_wait = 1
        else:  # these states do not rest: look again later, twice as late every time
            next_rest = step + rest_wait
            rest_wait = min(2 * rest_wait, 64)
        while lo <= hi and step < n_steps:
            i_new, agbar = kin.ground_increment(t, h, i_prev, tk, ak, ck, amp)
            if not lo <= agbar <= hi:
                break
            if math.isnan(a_last):
                for j in range(nbod):
                    vx[j] = 0.0
                    vy[j] = 0.0
                    om[j] = 0.0
            i_prev = i_new
            a_last = agbar
            t += h
            step += 1
            skipped += 1
            if rec_every > 0 and step % rec_every == 0 and n_rec < out_t.shape[0]:
                kin.record(n_rec, t, x, y, ph, gmid, gtol, out_t, out_q, out_state)
                out_e[n_rec] = kin.energy(mass, ws.ii, vx, vy, om, y, cy0, g)
                n_rec += 1
            if t >= t_motion and n_open == 0:
                break
        if not math.isnan(a_last):
            for r in range(3 * nj + 2 * ws.cnt[0]):
                ws.lam[r] = lam0[r] + a_last * lam1[r]
            hc = h
            next_search = step
            if t >= t_motion and n_open == 0:
                break
    if status == 1:  # the summary of the first collapse, also when followed through
        mx, impacts, open_max, max_slip, slide_max = at_col
    return (status, t_col, mx, impacts, open_max, n_rec, step, fails, max_slip, slide_max,
            points_max, skipped)


def run_batch(m, scales, tk, ak, amps, hs, t_end, t_motion, gtol_rel):
    """Many (scale, amplitude, step) triples side by side on numba's threads
    (:func:`rockarch.core.response.thread_map`); summaries only: (status, t_collapse,
    max ratio, impacts, most open joints, failed steps, largest slip, most sliding joints)
    arrays."""
    def one(i):
        return run(m, scales[i], tk, ak, amps[i], hs[i], t_end, t_motion, gtol_rel, 0,
                   np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8),
                   np.zeros(0), False, True)

    res = thread_map(one, scales.shape[0])
    cols = ((0, np.int8), (1, float), (2, float), (3, np.int64), (4, np.int64), (7, np.int64),
            (8, float), (9, np.int64))
    return tuple(np.array([r[c] for r in res], dtype=t) for c, t in cols)
