"""The general MDOF stepper: any contact graph, Coulomb friction, new contacts (numba).

The same Moreau–Jean step as :mod:`rockarch.mdof.chain_stepper` (docs/theory.md §6, §9) for
an assembly whose joint k joins body ``ba[k]`` to body ``bb[k]`` (−1: the ground, or a
support moving with it). The normal of joint k is attached to body ``ba[k]``; its corner
points to body ``bb[k]``: the gap of corner c is the distance of b's corner from a's face
line, so a joint may slide along a's face. Per joint: two corner rows and one tangential
row at the corner in contact (the smaller gap), with the joint's Coulomb cone (μ finite) or
the no-slip constraint (μ = ∞, the chain model). After the joints, the point contacts of
corners that reached a face they did not touch as built (:mod:`rockarch.mdof.collision`):
one normal and one tangential row each. Contact solve: exact, the Newton method in the
bodies' velocities iterated on the friction bounds (:mod:`rockarch.mdof.contact_solver`,
docs/theory.md Eqs. (9.7)–(9.9)). Positions stabilised by one Gauss–Seidel sweep per step
of the chain stepper's projection (closed contacts that carried an impulse close, sticking
joints keep their slip; velocities untouched, never adding energy). Collapse, impacts and
records in :mod:`rockarch.mdof.graph_run`.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from rockarch.core.jit_struct import JitStruct, jit_struct
from rockarch.mdof.collision import detect, local_normals, world
from rockarch.mdof.contact_solver import Rows, SolverWork, make_solver_work, row_dot, solve
from rockarch.mdof.kernel_data import SLIDE_TOL
from rockarch.mdof.kinematics import normal_bias, strikes

#: Gauss–Seidel sweeps of the position projection per step (a stabilisation: the remaining
#: error is corrected in the next steps).
PROJECT_SWEEPS = 1


@nb.njit(cache=True)
def _point(j, x, y, cs, sn, r0, r1):
    """World point of the body-fixed offset (r0, r1) (j < 0: a ground point) and the offset
    turned with the body (cs, sn: cos and sin of every body's rotation). Scalars, not a
    slice of the offsets: a view per call cost a third of :func:`geometry`. The arrays are
    read before the branch (the ground reads body 0 and drops it): an array read inside a
    branch costs numba two atomic reference counts per call, more than the arithmetic."""
    i = max(j, 0)
    c = cs[i]
    s = sn[i]
    xj = x[i]
    yj = y[i]
    if j < 0:
        return r0, r1, 0.0, 0.0
    ox = c * r0 - s * r1
    oy = s * r0 + c * r1
    return xj + ox, yj + oy, ox, oy


@nb.njit(cache=True)
def _rows(ja, jb, r, a, dx, dy, pbx, pby, obx, oby, x, y):
    """Jacobian row r of a contact direction d = (dx, dy) at B's point p_b (arm o_b from
    B's centroid); body A's arm runs from its centroid to p_b (the exact gap gradient).
    (x, y read before the branch: :func:`_point`.)"""
    jb[r, 0] = dx
    jb[r, 1] = dy
    jb[r, 2] = obx * dy - oby * dx
    xa = x[max(a, 0)]
    ya = y[max(a, 0)]
    if a >= 0:
        oax = pbx - xa
        oay = pby - ya
        ja[r, 0] = -dx
        ja[r, 1] = -dy
        ja[r, 2] = -(oax * dy - oay * dx)


@nb.njit(cache=True, inline="always")
def _normal(k, a, cs, sn, n0):
    """Joint k's normal, turned with body a (the ground's stays; arrays read before the
    branch: :func:`_point`)."""
    c = cs[max(a, 0)]
    s = sn[max(a, 0)]
    n0x = n0[k, 0]
    n0y = n0[k, 1]
    if a >= 0:
        return c * n0x - s * n0y, s * n0x + c * n0y
    return n0x, n0y


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


#: A joint's corner that projects beyond the other block's face by more than this fraction
#: of the face is off it (the faces turned apart); generous, as it only has to catch blocks
#: that tipped over an edge (a sliding joint's corners follow the faces' overlap, §9).
OFF_FACE = 0.05


@nb.njit(cache=True, inline="always")
def _outside(ex0, ey0, ex1, ey1, px, py):
    """True if (px, py) projects beyond the segment from (ex1, ey1) to (ex0, ey0) by more
    than ``OFF_FACE`` of its length."""
    ux = ex0 - ex1
    uy = ey0 - ey1
    ll = ux * ux + uy * uy
    s = (ux * (px - ex1) + uy * (py - ey1)) / ll
    return s < -OFF_FACE or s > 1.0 + OFF_FACE


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
        # the world ends of the joint's faces (in this function: a helper taking the arrays
        # costs numba atomic reference counts per call, a fifth of this function)
        a0x, a0y, _, _ = _point(a, x, y, cs, sn, fa[k, 0, 0], fa[k, 0, 1])
        a1x, a1y, _, _ = _point(a, x, y, cs, sn, fa[k, 1, 0], fa[k, 1, 1])
        b0x, b0y, _, _ = _point(b, x, y, cs, sn, fb[k, 0, 0], fb[k, 0, 1])
        b1x, b1y, _, _ = _point(b, x, y, cs, sn, fb[k, 1, 0], fb[k, 1, 1])
        # the corners as built (every joint; redone below for one that slid)
        best = 0
        for cc in range(2):
            pax, pay, _, _ = _point(a, x, y, cs, sn, ra[k, cc, 0], ra[k, cc, 1])
            pbx, pby, obx, oby = _point(b, x, y, cs, sn, rb[k, cc, 0], rb[k, cc, 1])
            dx = pbx - pax
            dy = pby - pay
            gap[k, cc] = nx * dx + ny * dy
            # a corner no longer over the other block's face: b's point beyond the ends of
            # a's face or a's beyond b's (the faces have turned apart: a block tipped over
            # an edge; a sliding joint's corners, the ends of the faces' overlap, never are)
            if _outside(a0x, a0y, a1x, a1y, pbx, pby) or _outside(b0x, b0y, b1x, b1y, pax, pay):
                gap[k, cc] = OFF_GAP
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


@nb.njit(cache=True, inline="always")
def solve3(a, r, out):
    """Solve the 3×3 system a·out = r (Gaussian elimination, partial pivoting; a, r are
    overwritten). Returns False if a is (numerically) singular."""
    for c in range(3):
        p = c
        for i in range(c + 1, 3):
            if abs(a[i, c]) > abs(a[p, c]):
                p = i
        if abs(a[p, c]) < 1e-300:
            return False
        if p != c:
            for j in range(3):
                tmp = a[c, j]
                a[c, j] = a[p, j]
                a[p, j] = tmp
            tmp = r[c]
            r[c] = r[p]
            r[p] = tmp
        for i in range(c + 1, 3):
            f = a[i, c] / a[c, c]
            if f != 0.0:
                for j in range(c, 3):
                    a[i, j] -= f * a[c, j]
                r[i] -= f * r[c]
    for i in range(2, -1, -1):
        s = r[i]
        for j in range(i + 1, 3):
            s -= a[i, j] * out[j]
        out[i] = s / a[i, i]
    return True


@nb.njit(cache=True, inline="always")
def apply_impulse(k, ba, bb, ja, jb, d, im, ii, vx, vy, om):
    """Velocities += M⁻¹·J_kᵀ·d (d: impulse increments of the 3 rows of joint k). No array
    is read or written inside a branch (numba's atomic reference counts per call cost more
    than the arithmetic): a side without a body, or a zero increment, writes back the
    velocities it read (body 0's for the ground: unchanged)."""
    a = ba[k]
    b = bb[k]
    ia = max(a, 0)
    ib = max(b, 0)
    ima = im[ia]
    iia = ii[ia]
    imb = im[ib]
    iib = ii[ib]
    for i in range(3):
        r = 3 * k + i
        di = d[i]
        cf = (ja[r, 0], ja[r, 1], ja[r, 2], jb[r, 0], jb[r, 1], jb[r, 2])
        for s in range(2):  # body a, then body b
            j = ia if s == 0 else ib
            on = di != 0.0 and (a if s == 0 else b) >= 0
            imj = ima if s == 0 else imb
            iij = iia if s == 0 else iib
            ux = vx[j]
            uy = vy[j]
            uo = om[j]
            vx[j] = ux + cf[3 * s] * di * imj if on else ux
            vy[j] = uy + cf[3 * s + 1] * di * imj if on else uy
            om[j] = uo + cf[3 * s + 2] * di * iij if on else uo


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
def point_rows(m, ws, x, y, cs, sn, i):
    """Gap and rows of point contact i (face edge ws.cedge[i], corner ws.cvert[i]) at the
    configuration (x, y, cs, sn): normal row 3·nj + 2i, tangential row 3·nj + 2i + 1, the
    face's normal attached to its body a (the ground's: +y), the corner on body b; arms
    from both centroids to the corner (the exact gradient of the gap, docs/theory.md
    Eq. (9.10))."""
    rba, rbb, ja, jb = ws.rows.rba, ws.rows.rbb, ws.rows.ja, ws.rows.jb
    nv = m.pv.shape[0]
    v = ws.cvert[i]
    e = ws.cedge[i]
    b = m.pbody[m.vpoly[v]]
    pbx, pby = world(b, x, y, cs, sn, ws.pv[v, 0], ws.pv[v, 1])
    obx, oby = (pbx - x[b], pby - y[b]) if b >= 0 else (0.0, 0.0)
    if e == nv:
        a = -1
        nx, ny = 0.0, 1.0
        gap = pby - ws.gy[0]
    else:
        a = m.pbody[m.vpoly[e]]
        e1 = e + 1 if e + 1 < m.pptr[m.vpoly[e] + 1] else m.pptr[m.vpoly[e]]
        p0x, p0y = world(a, x, y, cs, sn, ws.pv[e, 0], ws.pv[e, 1])
        p1x, p1y = world(a, x, y, cs, sn, ws.pv[e1, 0], ws.pv[e1, 1])
        ex = p1x - p0x
        ey = p1y - p0y
        ln = math.sqrt(ex * ex + ey * ey)
        nx = ey / ln
        ny = -ex / ln
        gap = nx * (pbx - p0x) + ny * (pby - p0y)
    r = 3 * m.n0.shape[0] + 2 * i
    rba[r] = a
    rbb[r] = b
    rba[r + 1] = a
    rbb[r + 1] = b
    for c in range(3):
        ja[r, c] = 0.0
        jb[r, c] = 0.0
        ja[r + 1, c] = 0.0
        jb[r + 1, c] = 0.0
    _rows(ja, jb, r, a, nx, ny, pbx, pby, obx, oby, x, y)
    _rows(ja, jb, r + 1, a, -ny, nx, pbx, pby, obx, oby, x, y)
    if b < 0:
        for c in range(3):
            jb[r, c] = 0.0
            jb[r + 1, c] = 0.0
    ws.cgap[i] = gap


#: A joint whose two blocks have turned apart by more than this [rad] hands their contact
#: over to the point contacts: its corner rows assume a face lying on the other block's face
#: (its normal), which a block that tipped over an edge no longer does.
TURN_OFF = 0.25 * math.pi


@nb.njit(cache=True)
def hand_over(m, ph, gap, jon):
    """Joints in use (``jon``): those whose blocks have not turned apart by more than
    ``TURN_OFF``; the others are open (their corners' gaps ``OFF_GAP``) and their corners
    and faces become point contacts (:mod:`rockarch.mdof.collision`). Returns whether a
    joint changed hands this step."""
    changed = False
    for k in range(m.n0.shape[0]):
        a = m.ba[k]
        b = m.bb[k]
        rel = (ph[b] if b >= 0 else 0.0) - (ph[a] if a >= 0 else 0.0)
        on = abs(rel) <= TURN_OFF
        if on != jon[k]:
            changed = True
            jon[k] = on
        if not on:
            gap[k, 0] = OFF_GAP
            gap[k, 1] = OFF_GAP
    return changed


@nb.njit(cache=True)
def find_contacts(m, ws, x, y, ph, margin):
    """The point contacts of this configuration (:func:`rockarch.mdof.collision.detect`)
    with their rows; each keeps its last impulses if it was a contact the step before (the
    warm start). ``margin`` < 0: the contacts of the last search, at this configuration.
    Returns the number of new ones (absent the step before)."""
    nv = m.pv.shape[0]
    cs = np.cos(ph)
    sn = np.sin(ph)
    if margin < 0.0:
        for i in range(ws.cnt[0]):
            point_rows(m, ws, x, y, cs, sn, i)
        return 0
    n = detect(m.pptr, m.pbody, ws.pv, ws.pn, x, y, cs, sn, m.pkeys, m.pptr_j, m.pjoint,
               ws.jon, margin, ws.gy[0], ws.wx, ws.wy, ws.wn, ws.box, ws.order, ws.found)
    if n > ws.found.shape[0]:
        ws.cnt[1] = n  # more than there is room for: the run widens it
        n = ws.found.shape[0]
    old = ws.cnt[0]
    okey = ws.okey
    olam = ws.olam
    nj3 = 3 * m.n0.shape[0]
    st = ws.sw.st
    for i in range(old):
        okey[i] = ws.ckey[i]
        olam[i, 0] = ws.lam[nj3 + 2 * i]
        olam[i, 1] = ws.lam[nj3 + 2 * i + 1]
        ws.ost[i, 0] = st[nj3 + 2 * i]
        ws.ost[i, 1] = st[nj3 + 2 * i + 1]
    srt = np.argsort(okey[:old])
    fresh = 0
    for i in range(n):
        e = ws.found[i, 0]
        v = ws.found[i, 1]
        key = v * (nv + 1) + e
        ws.cedge[i] = e
        ws.cvert[i] = v
        ws.ckey[i] = key
        r = nj3 + 2 * i
        lo = 0
        hi = old
        while lo < hi:
            mid = (lo + hi) // 2
            if okey[srt[mid]] < key:
                lo = mid + 1
            else:
                hi = mid
        if lo < old and okey[srt[lo]] == key:
            ws.lam[r] = olam[srt[lo], 0]
            ws.lam[r + 1] = olam[srt[lo], 1]
            st[r] = ws.ost[srt[lo], 0]
            st[r + 1] = ws.ost[srt[lo], 1]
        else:  # a new contact starts open (its tangential row carries nothing)
            ws.lam[r] = 0.0
            ws.lam[r + 1] = 0.0
            st[r] = -1
            st[r + 1] = 2 if math.isinf(m.mu_contact) else 1
            fresh += 1
        point_rows(m, ws, x, y, cs, sn, i)
    ws.cnt[0] = n
    return fresh


@nb.njit(cache=True)
def contact_rows(m, x, y, ph, vx, vy, om, gtol, hh, v_app, margin, ws):
    """The rows of the step's contact problem: geometry at (x, y, ph) (the joints and the
    point contacts within ``margin``), the free velocities (vx, vy, om) in ws.sw.vf and the
    rows' biases (docs/theory.md Eq. (6.3a)) in ws.bias. Returns the number of rows."""
    rba, rbb, ja, jb = ws.rows.rba, ws.rows.rbb, ws.rows.ja, ws.rows.jb
    nj = m.n0.shape[0]
    nbod = m.mass.shape[0]
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, ws.fa, ws.fb, ws.ftol, m.n0, m.mu, ws.gap,
             ja, jb)
    handed = hand_over(m, ph, ws.gap, ws.jon)
    if handed and margin < 0.0:
        margin = gtol  # a joint just handed its blocks over: search now
    find_contacts(m, ws, x, y, ph, margin)
    nrows = 3 * nj + 2 * ws.cnt[0]
    sw = ws.sw
    for j in range(nbod):
        sw.vf[3 * j] = vx[j]
        sw.vf[3 * j + 1] = vy[j]
        sw.vf[3 * j + 2] = om[j]
    bias = ws.bias  # the work arrays named once (a field read in a branch of the loop
    strike = ws.strike  # costs numba atomic reference counts per row)
    vf = sw.vf
    for k in range(nj):
        for c in range(3):
            r = 3 * k + c
            bias[r] = 0.0
            strike[r] = False
            if c < 2:
                u = row_dot(r, rba, rbb, ja, jb, vf)
                bias[r] = normal_bias(ws.gap[k, c], u, gtol, hh, v_app)
                strike[r] = strikes(u, bias[r], v_app)
    for i in range(ws.cnt[0]):
        r = 3 * nj + 2 * i
        u = row_dot(r, rba, rbb, ja, jb, sw.vf)
        ws.bias[r] = normal_bias(ws.cgap[i], u, gtol, hh, v_app)
        ws.strike[r] = strikes(u, ws.bias[r], v_app)
        ws.bias[r + 1] = 0.0
        ws.strike[r + 1] = False
    return nrows


@nb.njit(cache=True)
def contact_step(m, x, y, ph, vx, vy, om, gtol, hh, v_app, eps_n, eps_t, tol_u, tol_l, margin, ws):
    """The rows of the step (:func:`contact_rows`), then the exact contact solve of the step
    (:func:`rockarch.mdof.contact_solver.solve`) for the free velocities (vx, vy, om), which
    are turned into v⁺ in place. Warm start: the last impulses in ws.lam. Returns the
    solver's Newton iterations (negative: failed)."""
    nbod = m.mass.shape[0]
    nrows = contact_rows(m, x, y, ph, vx, vy, om, gtol, hh, v_app, margin, ws)
    sw = ws.sw
    its = solve(nbod, nrows, ws.rows, ws.bias, ws.lam, eps_n, eps_t, sw, tol_u, tol_l, ws.lref[0])
    for j in range(nbod):
        vx[j] = sw.v[3 * j]
        vy[j] = sw.v[3 * j + 1]
        om[j] = sw.v[3 * j + 2]
    return its


@nb.njit(cache=True)
def project(m, x, y, ph, eps, keep, slip_tol, free_t, anchor, ws, cws):
    """Position stabilisation: Gauss–Seidel on W·μ = −gap over the kept rows (closed
    corners that carried an impulse, and their joint's tangential row; point contacts that
    carried one), then q += M⁻¹·Jᵀ·μ (velocities untouched). Tangential targets: 0 for
    μ = ∞ joints while the offset is drift-sized; ``anchor`` (the offset when the joint
    last slid or was open) for a sticking joint; the current offset for a joint in
    ``free_t`` (sliding or open), whose anchor it becomes. ``cws``: the step's workspace,
    whose point contacts (and their impulses) are projected here at this configuration."""
    rba, rbb, ja, jb = ws.rows.rba, ws.rows.rbb, ws.rows.ja, ws.rows.jb
    nj = m.n0.shape[0]
    nbod = m.mass.shape[0]
    geometry(nj, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, ws.fa, ws.fb, ws.ftol, m.n0, m.mu, ws.gap,
             ja, jb)
    joint_blocks(nj, m.ba, m.bb, ja, jb, ws.im, ws.ii, eps, ws.wl)
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
                    s += ja[r, 0] * dx[a] + ja[r, 1] * dy[a] + ja[r, 2] * dp[a]
                if b >= 0:
                    s += jb[r, 0] * dx[b] + jb[r, 1] * dy[b] + jb[r, 2] * dp[b]
                u[i] = s
            for i in range(3):
                for j in range(3):
                    kept = keep[3 * k + i] and keep[3 * k + j]
                    a3[i, j] = ws.wl[k, i, j] if kept else (1.0 if i == j else 0.0)
                r3[i] = -u[i] if keep[3 * k + i] else 0.0
            if solve3(a3, r3, d):
                apply_impulse(k, m.ba, m.bb, ja, jb, d, ws.im, ws.ii, dx, dy, dp)
    # point contacts that carried an impulse: their normal rows, one by one
    cs = np.cos(ph)
    sn = np.sin(ph)
    for i in range(cws.cnt[0]):
        r = 3 * nj + 2 * i
        if cws.lam[r] <= 0.0:
            continue
        ws.cvert[i] = cws.cvert[i]
        ws.cedge[i] = cws.cedge[i]
        point_rows(m, ws, x, y, cs, sn, i)
        if ws.cgap[i] > 0.0:
            continue
        a = rba[r]
        b = rbb[r]
        s = ws.cgap[i]
        w = eps
        if a >= 0:
            s += ja[r, 0] * dx[a] + ja[r, 1] * dy[a] + ja[r, 2] * dp[a]
            w += (ja[r, 0] ** 2 + ja[r, 1] ** 2) * ws.im[a] + ja[r, 2] ** 2 * ws.ii[a]
        if b >= 0:
            s += jb[r, 0] * dx[b] + jb[r, 1] * dy[b] + jb[r, 2] * dp[b]
            w += (jb[r, 0] ** 2 + jb[r, 1] ** 2) * ws.im[b] + jb[r, 2] ** 2 * ws.ii[b]
        mu_ = -s / w
        if a >= 0:
            dx[a] += ja[r, 0] * mu_ * ws.im[a]
            dy[a] += ja[r, 1] * mu_ * ws.im[a]
            dp[a] += ja[r, 2] * mu_ * ws.ii[a]
        if b >= 0:
            dx[b] += jb[r, 0] * mu_ * ws.im[b]
            dy[b] += jb[r, 1] * mu_ * ws.im[b]
            dp[b] += jb[r, 2] * mu_ * ws.ii[b]
    for j in range(nbod):
        x[j] += dx[j]
        y[j] += dy[j]
        ph[j] += dp[j]


@jit_struct
class Work(JitStruct):
    """Scaled geometry and work arrays of one run: the joints' rows first (3 per joint:
    corner 0, corner 1, tangential), then up to ``cap`` point contacts (2 rows each);
    passed by reference (:mod:`rockarch.core.jit_struct`)."""

    ra: np.ndarray
    rb: np.ndarray
    fa: np.ndarray
    fb: np.ndarray
    ftol: np.ndarray
    im: np.ndarray
    ii: np.ndarray
    gap: np.ndarray  # (nj, 3)
    rows: Rows  # the rows' bodies and Jacobian (R rows), and their friction law
    wl: np.ndarray  # (nj, 3, 3) the joints' diagonal blocks of W (projection)
    bias: np.ndarray  # (R,)
    strike: np.ndarray  # (R,) normal rows of corners striking this step (Eq. 6.3a)
    lam: np.ndarray
    pv: np.ndarray  # (nv, 2) the polygons' vertices, scaled
    wx: np.ndarray  # (nv,) their world positions
    wy: np.ndarray
    pn: np.ndarray  # (nv, 2) outward edge normals in the bodies' frames
    wn: np.ndarray  # (nv, 2) the same in the world
    box: np.ndarray  # (npoly, 4)
    order: np.ndarray  # (npoly,)
    found: np.ndarray  # (cap, 3)
    cnt: np.ndarray  # [point contacts in use, contacts found beyond the room (0: none)]
    jon: np.ndarray  # (nj,) joints in use (:func:`hand_over`)
    cedge: np.ndarray  # (cap,) face (edge id) and corner (vertex id) of every point contact
    cvert: np.ndarray
    ckey: np.ndarray
    cgap: np.ndarray
    okey: np.ndarray  # the last step's keys, impulses and states (warm start)
    olam: np.ndarray
    ost: np.ndarray
    lref: np.ndarray  # [thinnest joint, scaled]
    gy: np.ndarray  # [height of the ground plane, scaled]
    sw: SolverWork


@nb.njit(cache=True)
def make_work(m, scale, cap):
    """Scaled geometry and zeroed work arrays of one run, room for ``cap`` point contacts."""
    nj = m.n0.shape[0]
    nbod = m.mass.shape[0]
    n = 3 * nj + 2 * cap
    rba = np.empty(n, dtype=np.int64)
    rbb = np.empty(n, dtype=np.int64)
    tn0 = np.full(n, -1, dtype=np.int64)
    tn1 = np.full(n, -1, dtype=np.int64)
    tmu = np.zeros(n)
    for k in range(nj):
        for c in range(3):
            rba[3 * k + c] = m.ba[k]
            rbb[3 * k + c] = m.bb[k]
        tn0[3 * k + 2] = 3 * k
        tn1[3 * k + 2] = 3 * k + 1
        tmu[3 * k + 2] = m.mu[k]
    for i in range(cap):
        r = 3 * nj + 2 * i
        tn0[r + 1] = r
        tmu[r + 1] = m.mu_contact
    inertia = m.inertia * scale * scale
    npoly = m.pbody.shape[0]
    nv = m.pv.shape[0]
    pv = m.pv.copy()
    for v in range(nv):  # supports' vertices are absolute: scaled too
        pv[v, 0] *= scale
        pv[v, 1] *= scale
    return Work(m.ra * scale, m.rb * scale, m.fa * scale, m.fb * scale, m.ftol * scale,
                1.0 / m.mass, 1.0 / inertia,
                np.zeros((nj, 3)),
                Rows(rba, rbb, np.zeros((n, 3)), np.zeros((n, 3)), tn0, tn1, tmu),
                np.zeros((nj, 3, 3)), np.zeros(n), np.zeros(n, dtype=np.bool_), np.zeros(n), pv,
                np.zeros(nv), np.zeros(nv), local_normals(m.pptr, pv),
                np.zeros((nv, 2)), np.zeros((npoly, 4)),
                np.arange(npoly), np.zeros((cap, 2), dtype=np.int64),
                np.zeros(2, dtype=np.int64), np.ones(nj, dtype=np.bool_),
                np.zeros(cap, dtype=np.int64),
                np.zeros(cap, dtype=np.int64), np.zeros(cap, dtype=np.int64), np.zeros(cap),
                np.zeros(cap, dtype=np.int64), np.zeros((cap, 2)),
                np.zeros((cap, 2), dtype=np.int8), np.array([m.thick_min * scale]),
                np.array([m.ground_y * scale]),
                make_solver_work(nbod, n, m.bpos, m.mass, inertia, m.kd_cap))
