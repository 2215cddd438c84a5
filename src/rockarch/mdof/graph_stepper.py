"""The general MDOF stepper: any contact graph, Coulomb friction per joint (numba).

The same Moreau–Jean step as :mod:`rockarch.mdof.chain_stepper` (docs/theory.md §6, §9) for
an assembly whose joint k joins body ``ba[k]`` to body ``bb[k]`` (−1: the ground, or a
support moving with it). The normal of joint k is attached to body ``ba[k]``; its corner
points to body ``bb[k]``: the gap of corner c is the distance of b's corner from a's face
line, so a joint may slide along a's face. Per joint: two corner rows and one tangential
row at the corner in contact (the smaller gap), with the joint's Coulomb cone (μ finite) or
the no-slip constraint (μ = ∞, the chain model). Contact solve: exact, a box-constrained QP
on the banded W iterated on the friction bounds (:func:`banded_friction`; docs/theory.md
Eq. (9.4)), or, for very wide graphs, the rest path (:mod:`rockarch.mdof.rest_solver`,
Eq. (9.7)) and where it does not apply non-smooth Gauss–Seidel
(:mod:`rockarch.mdof.graph_solver`). Positions stabilised by one Gauss–Seidel sweep per step
of the chain stepper's projection (closed contacts that carried an impulse close, sticking
joints keep their slip; velocities untouched, never adding energy). Collapse, impacts and
records in :mod:`rockarch.mdof.graph_run`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from rockarch.mdof.chain_solver import box_qp
from rockarch.mdof.graph_solver import apply_impulse, joint_velocity, nsgs, solve3
from rockarch.mdof.kernel_data import SLIDE_TOL
from rockarch.mdof.rest_solver import note_velocity, rest_solve

#: Gauss–Seidel sweeps of the position projection per step (a stabilisation: the remaining
#: error is corrected in the next steps).
PROJECT_SWEEPS = 1
#: Fixed-point iterations on the joints' normal impulses (chains with friction) before a
#: step counts as a failure.
MAX_OUTER = 50
#: Tolerance of that fixed point: the friction bounds in use repeat within FP_TOL of the
#: largest joint impulse.
FP_TOL = 1e-4


@nb.njit(cache=True)
def _point(j, x, y, cs, sn, r0, r1):
    """World point of the body-fixed offset (r0, r1) (j < 0: a ground point) and the offset
    turned with the body (cs, sn: cos and sin of every body's rotation). Scalars, not a
    slice of the offsets: a view per call cost a third of :func:`geometry`."""
    if j < 0:
        return r0, r1, 0.0, 0.0
    ox = cs[j] * r0 - sn[j] * r1
    oy = sn[j] * r0 + cs[j] * r1
    return x[j] + ox, y[j] + oy, ox, oy


@nb.njit(cache=True)
def _rows(ja, jb, r, a, dx, dy, pbx, pby, obx, oby, x, y):
    """Jacobian row r of a contact direction d = (dx, dy) at B's point p_b (arm o_b from
    B's centroid); body A's arm runs from its centroid to p_b (the exact gap gradient)."""
    jb[r, 0] = dx
    jb[r, 1] = dy
    jb[r, 2] = obx * dy - oby * dx
    if a >= 0:
        oax = pbx - x[a]
        oay = pby - y[a]
        ja[r, 0] = -dx
        ja[r, 1] = -dy
        ja[r, 2] = -(oax * dy - oay * dx)


@nb.njit(cache=True, inline="always")
def _normal(k, a, cs, sn, n0):
    """Joint k's normal, turned with body a (the ground's stays)."""
    if a >= 0:
        return cs[a] * n0[k, 0] - sn[a] * n0[k, 1], sn[a] * n0[k, 0] + cs[a] * n0[k, 1]
    return n0[k, 0], n0[k, 1]


@nb.njit(cache=True, inline="always")
def _ground_rows(k, a, b, ja, jb):
    """Zero joint k's rows of the ground's side (the ground does not move)."""
    for i in range(3):
        for j in range(3):
            if a < 0:
                ja[3 * k + i, j] = 0.0
            if b < 0:
                jb[3 * k + i, j] = 0.0


#: Gap given to both corners of a joint whose faces no longer overlap [m] (open for good:
#: far above any contact tolerance, finite so that the solvers' arithmetic stays finite).
OFF_GAP = 1e6


@nb.njit(cache=True, inline="always")
def _overlap_end(r, inside, a, b, x, y, nx, ny, mx, my, bx, by, obx, oby, fax, fay, ra, rb,
                 cs, sn, gap, ja, jb):
    """One end of a sliding joint's overlap (row r = corner c): b's face end (bx, by; arm
    ob) against a's face line with a's normal n if ``inside``, else a's face end (offset
    fax, fay) against b's face line with b's normal m. The lines are taken through the
    joint's reference corner c on each body (near the contact: the ground's face ends are
    far). Returns the contact point and its arm from b's centroid."""
    k = r // 3
    c = r - 3 * k
    if inside:
        lx, ly, _, _ = _point(a, x, y, cs, sn, ra[k, c, 0], ra[k, c, 1])
        gap[k, c] = nx * (bx - lx) + ny * (by - ly)
        _rows(ja, jb, r, a, nx, ny, bx, by, obx, oby, x, y)
        return bx, by, obx, oby
    lx, ly, _, _ = _point(b, x, y, cs, sn, rb[k, c, 0], rb[k, c, 1])
    qx, qy, oqx, oqy = _point(a, x, y, cs, sn, fax, fay)
    gap[k, c] = mx * (qx - lx) + my * (qy - ly)
    _rows(jb, ja, r, b, mx, my, qx, qy, oqx, oqy, x, y)
    if b < 0:
        return qx, qy, 0.0, 0.0
    return qx, qy, qx - x[b], qy - y[b]


@nb.njit(cache=True)
def _sliding_joint(k, a, b, x, y, cs, sn, ra, rb, fa, fb, n0, nx, ny, gap, ja, jb):
    """Corner gaps and rows of a joint that may slide (μ finite, docs/theory.md §9): its
    contact runs along the overlap of the two faces. Each end of the overlap is b's face
    end against a's face line while that end lies on a's face, else a's face end against
    b's face line (the exact gradient either way). Faces that no longer overlap get
    ``OFF_GAP`` at both corners. Returns the contact points with their arms from b's
    centroid (x0, y0, ox0, oy0, x1, ...) and whether the joint is off."""
    a0x, a0y, _, _ = _point(a, x, y, cs, sn, fa[k, 0, 0], fa[k, 0, 1])
    a1x, a1y, _, _ = _point(a, x, y, cs, sn, fa[k, 1, 0], fa[k, 1, 1])
    b0x, b0y, ob0x, ob0y = _point(b, x, y, cs, sn, fb[k, 0, 0], fb[k, 0, 1])
    b1x, b1y, ob1x, ob1y = _point(b, x, y, cs, sn, fb[k, 1, 0], fb[k, 1, 1])
    ex = a0x - a1x  # along a's face, from its corner-1 end to its corner-0 end
    ey = a0y - a1y
    la = math.sqrt(ex * ex + ey * ey)
    ex /= la
    ey /= la
    u0 = ex * (b0x - a1x) + ey * (b0y - a1y)  # b's face ends on a's face, which spans [0, la]
    u1 = ex * (b1x - a1x) + ey * (b1y - a1y)
    # b's end stays the contact until it is past a's end by SLIDE_TOL of b's face (ends that
    # coincide as built stay b's: no switching on round-off)
    tol = SLIDE_TOL * math.sqrt((b0x - b1x) ** 2 + (b0y - b1y) ** 2)
    if max(0.0, u1) >= min(la, u0):
        gap[k, 0] = OFF_GAP
        gap[k, 1] = OFF_GAP
        _rows(ja, jb, 3 * k, a, nx, ny, b0x, b0y, ob0x, ob0y, x, y)
        _rows(ja, jb, 3 * k + 1, a, nx, ny, b1x, b1y, ob1x, ob1y, x, y)
        return b0x, b0y, ob0x, ob0y, b1x, b1y, ob1x, ob1y, True
    mx, my = _normal(k, b, cs, sn, n0)  # b's face normal, pointing into a: -(this)
    mx, my = -mx, -my
    p0x, p0y, o0x, o0y = _overlap_end(3 * k, u0 <= la + tol, a, b, x, y, nx, ny, mx, my, b0x,
                                      b0y, ob0x, ob0y, fa[k, 0, 0], fa[k, 0, 1], ra, rb, cs,
                                      sn, gap, ja, jb)
    p1x, p1y, o1x, o1y = _overlap_end(3 * k + 1, u1 >= -tol, a, b, x, y, nx, ny, mx, my, b1x,
                                      b1y, ob1x, ob1y, fa[k, 1, 0], fa[k, 1, 1], ra, rb, cs,
                                      sn, gap, ja, jb)
    return p0x, p0y, o0x, o0y, p1x, p1y, o1x, o1y, False


@nb.njit(cache=True)
def _slid_joints(nj, ba, bb, x, y, cs, sn, ra, rb, fa, fb, ftol, n0, mu, gap, ja, jb):
    """The joints of :func:`geometry` that slipped more than ``ftol``: corners at the ends
    of the faces' overlap (:func:`_sliding_joint`), the tangential row at the one in
    contact. Returns the number of joints whose faces no longer overlap."""
    n_off = 0
    for k in range(nj):
        if math.isinf(mu[k]) or abs(gap[k, 2]) <= ftol[k]:
            continue
        a = ba[k]
        b = bb[k]
        nx, ny = _normal(k, a, cs, sn, n0)
        p0x, p0y, o0x, o0y, p1x, p1y, o1x, o1y, off = _sliding_joint(
            k, a, b, x, y, cs, sn, ra, rb, fa, fb, n0, nx, ny, gap, ja, jb)
        n_off += off
        best = 1 if gap[k, 1] < gap[k, 0] else 0
        pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, best, 0], ra[k, best, 1])
        pbx, pby, _, _ = _point(b, x, y, cs, sn, rb[k, best, 0], rb[k, best, 1])
        gap[k, 2] = -ny * (pbx - pax) + nx * (pby - pay)
        px, py, obx, oby = (p1x, p1y, o1x, o1y) if best == 1 else (p0x, p0y, o0x, o0y)
        _rows(ja, jb, 3 * k + 2, a, -ny, nx, px, py, obx, oby, x, y)
        _ground_rows(k, a, b, ja, jb)
    return n_off


@nb.njit(cache=True)
def geometry(nj, ba, bb, x, y, ph, ra, rb, fa, fb, ftol, n0, mu, gap, ja, jb):
    """Gaps (nj, 3: corner 0, corner 1, tangential offset at the corner in contact) and the
    Jacobian rows (3·nj, 3) w.r.t. bodies a and b; the rows are the exact gradients of the
    gaps (lever arms from each centroid to b's corner). A joint with finite μ takes its
    corners at the ends of the faces' overlap (:func:`_sliding_joint`), its tangential row
    at the one in contact; its offset stays that of the reference corners (the slip). While
    it slips less than ``ftol`` (SLIDE_TOL of its face) it keeps the corners as built: the
    overlap's ends are within ``ftol`` of them, and a corner's gap measured from either
    face is the same to first order (the arithmetic and the cost of a no-slip joint).
    Returns the number of joints whose faces no longer overlap."""
    cs = np.cos(ph)
    sn = np.sin(ph)
    for k in range(nj):
        a = ba[k]
        b = bb[k]
        nx, ny = _normal(k, a, cs, sn, n0)
        tx = -ny
        ty = nx
        # the corners as built (every joint; redone below for one that slid)
        best = 0
        for cc in range(2):
            pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, cc, 0], ra[k, cc, 1])
            pbx, pby, obx, oby = _point(b, x, y, cs, sn, rb[k, cc, 0], rb[k, cc, 1])
            dx = pbx - pax
            dy = pby - pay
            gap[k, cc] = nx * dx + ny * dy
            if cc == 1 and gap[k, 1] < gap[k, 0]:
                best = 1
            _rows(ja, jb, 3 * k + cc, a, nx, ny, pbx, pby, obx, oby, x, y)
        pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, best, 0], ra[k, best, 1])
        pbx, pby, obx, oby = _point(b, x, y, cs, sn, rb[k, best, 0], rb[k, best, 1])
        gap[k, 2] = tx * (pbx - pax) + ty * (pby - pay)
        _rows(ja, jb, 3 * k + 2, a, tx, ty, pbx, pby, obx, oby, x, y)
        _ground_rows(k, a, b, ja, jb)
    # the joints that slid, in a second pass: the loop above stays that of a no-slip joint
    for k in range(nj):
        if not math.isinf(mu[k]) and abs(gap[k, 2]) > ftol[k]:
            return _slid_joints(nj, ba, bb, x, y, cs, sn, ra, rb, fa, fb, ftol, n0, mu, gap,
                                ja, jb)
    return 0


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
                # no slip while the joint is compressed, no shear when it is not (μ → ∞);
                # after three iterations a joint once freed stays free (the set only grows)
                b = np.inf if ws.lam[3 * k] + ws.lam[3 * k + 1] > 0.0 or (
                    _outer >= 3 and ws.hi[3 * k + 2] > 0.0) else 0.0
                ws.lo[3 * k + 2] = -b
                ws.hi[3 * k + 2] = b
                if b > 0.0:
                    ws.st[3 * k + 2] = 0  # an infinite bound is never held
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
            if math.isinf(m.mu[k]):
                loaded = ws.lam[3 * k] + ws.lam[3 * k + 1] > 0.0
                if (ws.hi[3 * k + 2] > 0.0) != loaded and (loaded or _outer < 3):
                    diff = np.inf
            else:
                b = m.mu[k] * (ws.lam[3 * k] + ws.lam[3 * k + 1])
                if ws.st[3 * k + 2] != 0:
                    diff = max(diff, abs(b - ws.hi[3 * k + 2]))
                else:
                    diff = max(diff, abs(ws.lam[3 * k + 2]) - b)
        if diff <= max(tol_l, FP_TOL * smax):
            return total
    return -1 - total


@nb.njit(cache=True)
def contact_step(m, x, y, ph, vx, vy, om, gtol, hh, eps, tol_u, tol_l, ws, rw):
    """Geometry at (x, y, ph), contact impulses for the free velocities (vx, vy, om), which
    are turned into v⁺ in place. Warm start: ws.lam, ws.case, ws.st; rw: the rest path's
    work (:func:`rockarch.mdof.rest_solver.make_rest_work`). Exact banded solve
    (:func:`banded_friction`), or, if the model says so, the rest path
    (:func:`rockarch.mdof.rest_solver.rest_solve`: returns 0) and else Gauss–Seidel sweeps.
    Returns the solver's iteration count (negative: failed)."""
    nj = m.n0.shape[0]
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, ws.fa, ws.fb, ws.ftol, m.n0, m.mu, ws.gap,
             ws.ja, ws.jb)
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
        if rest_solve(m, ws, rw, vx, vy, om, tol_u, tol_l):
            note_velocity(m, rw, vx, vy, om, m.g * hh)
            return 0
        joint_blocks(nj, m.ba, m.bb, ws.ja, ws.jb, ws.im, ws.ii, eps, ws.wl)
    for k in range(nj):
        for i in range(3):
            d[i] = ws.lam[3 * k + i]
        apply_impulse(k, m.ba, m.bb, ws.ja, ws.jb, d, ws.im, ws.ii, vx, vy, om)
    if m.banded:
        return its
    sweeps = nsgs(nj, m.ba, m.bb, ws.ja, ws.jb, ws.wl, ws.bias, m.mu, ws.im, ws.ii, vx, vy, om,
                  ws.lam, ws.case, tol_u, tol_l)
    note_velocity(m, rw, vx, vy, om, m.g * hh)
    return sweeps


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
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, ws.fa, ws.fb, ws.ftol, m.n0, m.mu, ws.gap,
             ws.ja, ws.jb)
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
    fa: np.ndarray
    fb: np.ndarray
    ftol: np.ndarray
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
def make_work(m, scale, lam, case):
    """Scaled geometry and zeroed work arrays of one run (lam, case: the warm start)."""
    nj = m.n0.shape[0]
    n = 3 * nj
    kd = m.kd if m.banded else 0
    return Work(m.ra * scale, m.rb * scale, m.fa * scale, m.fb * scale, m.ftol * scale,
                1.0 / m.mass,
                1.0 / (m.inertia * scale * scale),
                np.zeros((nj, 3)), np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((nj, 3, 3)),
                np.zeros(n), lam, case, np.zeros((n, kd + 1)), np.zeros((n, kd + 1)),
                np.zeros((n, kd + 1)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
                np.zeros(n), np.zeros(n, dtype=np.int8))
