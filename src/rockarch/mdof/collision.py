"""New contacts of a moving assembly: any corner that reaches any face (numba).

The joints of an assembly are the faces that touch as built (docs/theory.md §10). A block
that falls off a wall, tips off a pedestal or topples against its neighbour touches faces
that were apart: every few steps, any corner of a block that comes within a margin of a
face of another block, of a support or of the ground becomes a *point contact* (one normal
and one tangential row, Coulomb's cone on the corner, docs/theory.md Eq. (9.10)); a contact
whose corner moves away is dropped at the next search.

Broad phase: the outlines' bounding boxes, sorted by their left edges (insertion sort from
the last order: linear while the blocks move little) and swept. Narrow phase, for two convex
outlines P and Q that share no joint in use: the separating axis of least penetration — the
edge e of either outline with the greatest min over the other's corners v of n_e·(v − p_e) —
is the *reference face*; the other outline's corners within the margin of it, and over it,
are the contacts (one face per pair, as Box2D's manifolds: a corner meeting a corner gets one
normal, not two). Two blocks joined by a joint in use (one that has not handed its blocks
over, :func:`rockarch.mdof.graph_stepper.hand_over`) touch through that joint only; so does
a block and the ground it stands on. Pairs are named by ids: a block's index, nb + p for
support polygon p, nb + npoly for the ground plane y = 0.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np


@nb.njit(cache=True, inline="always")
def world(j, x, y, cs, sn, px, py):
    """World point of the body-fixed offset (px, py) of body j (j < 0: already world)."""
    if j < 0:
        return px, py
    return x[j] + cs[j] * px - sn[j] * py, y[j] + sn[j] * px + cs[j] * py


@nb.njit(cache=True)
def thin_outline(pts, keep):
    """Visvalingam's rule on a closed polygon ``pts`` (n, 2): drop the vertex whose triangle
    with its two neighbours has the least area (the first in order among equal areas) until
    ``keep`` are left; returns the mask of the vertices kept. O(n²), in the kernel: a
    voussoir's hull has ~100 vertices, and the outlines are built for every simulation
    (in Python, half the run time of a 20-voussoir arch)."""
    n = pts.shape[0]
    alive = np.ones(n, dtype=np.bool_)
    prv = np.empty(n, dtype=np.int64)
    nxt = np.empty(n, dtype=np.int64)
    area = np.empty(n)
    for i in range(n):
        prv[i] = (i - 1) % n
        nxt[i] = (i + 1) % n
    for i in range(n):
        area[i] = _triangle2(pts, prv[i], i, nxt[i])
    for _ in range(n - keep):
        best = -1
        for i in range(n):
            if alive[i] and (best < 0 or area[i] < area[best]):
                best = i
        alive[best] = False
        p = prv[best]
        q = nxt[best]
        nxt[p] = q
        prv[q] = p
        area[p] = _triangle2(pts, prv[p], p, q)
        area[q] = _triangle2(pts, p, q, nxt[q])
    return alive


@nb.njit(cache=True, inline="always")
def _triangle2(pts, p, i, q):
    """Twice the area of the triangle of vertices p, i, q."""
    return abs((pts[i, 0] - pts[p, 0]) * (pts[q, 1] - pts[p, 1])
               - (pts[q, 0] - pts[p, 0]) * (pts[i, 1] - pts[p, 1]))


@nb.njit(cache=True)
def local_normals(pptr, pv):
    """Outward unit normal of every edge (edge i: from vertex i to the next of its polygon)
    in its body's frame (a support's: the world's)."""
    nrm = np.empty_like(pv)
    for p in range(pptr.shape[0] - 1):
        i0 = pptr[p]
        m = pptr[p + 1] - i0
        for e in range(m):
            a0 = i0 + e
            a1 = i0 + (e + 1) % m
            ex = pv[a1, 0] - pv[a0, 0]
            ey = pv[a1, 1] - pv[a0, 1]
            ln = math.sqrt(ex * ex + ey * ey)
            nrm[a0, 0] = ey / ln  # counter-clockwise outline: (ey, −ex) points out
            nrm[a0, 1] = -ex / ln
    return nrm


@nb.njit(cache=True)
def boxes(pptr, pbody, pv, pn, x, y, cs, sn, wx, wy, wn, box):
    """World vertices (wx, wy) and edge normals (wn) of every polygon and its bounding box
    (x0, x1, y0, y1)."""
    for p in range(pbody.shape[0]):
        j = pbody[p]
        x0 = math.inf
        x1 = -math.inf
        y0 = math.inf
        y1 = -math.inf
        for i in range(pptr[p], pptr[p + 1]):
            px, py = world(j, x, y, cs, sn, pv[i, 0], pv[i, 1])
            wx[i] = px
            wy[i] = py
            if j >= 0:
                wn[i, 0] = cs[j] * pn[i, 0] - sn[j] * pn[i, 1]
                wn[i, 1] = sn[j] * pn[i, 0] + cs[j] * pn[i, 1]
            else:
                wn[i, 0] = pn[i, 0]
                wn[i, 1] = pn[i, 1]
            x0 = min(x0, px)
            x1 = max(x1, px)
            y0 = min(y0, py)
            y1 = max(y1, py)
        box[p, 0] = x0
        box[p, 1] = x1
        box[p, 2] = y0
        box[p, 3] = y1


@nb.njit(cache=True, inline="always")
def pair_key(i, j, nid):
    """Key of the unordered pair of ids i, j (ids < nid)."""
    return min(i, j) * nid + max(i, j)


@nb.njit(cache=True)
def joined(i, j, nid, pkeys, pptr, pjoint, jon):
    """True if ids i and j share a joint in use."""
    key = pair_key(i, j, nid)
    q = np.searchsorted(pkeys, key)
    if q < pkeys.shape[0] and pkeys[q] == key:
        for t in range(pptr[q], pptr[q + 1]):
            if jon[pjoint[t]]:
                return True
    return False


@nb.njit(cache=True, inline="always")
def _separation(pa, pb, pptr, wx, wy, wn):
    """Greatest over the edges e of polygon pa of the least n_e·(v − p_e) over the corners v
    of polygon pb, and that edge."""
    best = -math.inf
    be = np.int64(-1)  # int64, not a literal: _manifold is compiled once
    for a0 in range(pptr[pa], pptr[pa + 1]):
        worst = math.inf
        for v in range(pptr[pb], pptr[pb + 1]):
            s = wn[a0, 0] * (wx[v] - wx[a0]) + wn[a0, 1] * (wy[v] - wy[a0])
            worst = min(worst, s)
        if worst > best:
            best = worst
            be = a0
    return best, be


@nb.njit(cache=True)
def _manifold(pa, pb, e, pptr, wx, wy, wn, margin, out, n, cap):
    """Corners of polygon pb within ``margin`` of reference edge e of polygon pa and over it
    (their projection within the edge, the margin either side): rows (e, corner) of
    ``out`` from row n. Returns the new count (counted beyond ``cap``, not stored)."""
    i0 = pptr[pa]
    m = pptr[pa + 1] - i0
    a1 = i0 + (e - i0 + 1) % m
    tx = wx[a1] - wx[e]
    ty = wy[a1] - wy[e]
    ln = math.sqrt(tx * tx + ty * ty)
    tx /= ln
    ty /= ln
    for v in range(pptr[pb], pptr[pb + 1]):
        dx = wx[v] - wx[e]
        dy = wy[v] - wy[e]
        s = wn[e, 0] * dx + wn[e, 1] * dy
        u = tx * dx + ty * dy
        if s <= margin and -margin <= u <= ln + margin:
            if n < cap:
                out[n, 0] = e
                out[n, 1] = v
            n += 1
    return n


@nb.njit(cache=True)
def detect(pptr, pbody, pv, pn, x, y, cs, sn, pkeys, pptr_j, pjoint, jon, margin, ground_y,
           wx, wy, wn, box, order, found):
    """Every (reference face, corner) pair within ``margin`` (module docstring): rows of
    ``found`` (edge id: the global index of the edge's first vertex, or nv for the ground
    plane y = ``ground_y``; vertex id). ``pkeys``/``pptr_j``/``pjoint``: the joints of every pair of
    ids (sorted keys, CSR), ``jon`` the joints in use. Returns the number found (more than
    found.shape[0]: that many did not fit)."""
    npoly = pbody.shape[0]
    nv = pv.shape[0]
    nbod = x.shape[0]
    nid = nbod + npoly + 1
    cap = found.shape[0]
    boxes(pptr, pbody, pv, pn, x, y, cs, sn, wx, wy, wn, box)
    for i in range(1, npoly):
        p = order[i]
        k = i - 1
        while k >= 0 and box[order[k], 0] > box[p, 0]:
            order[k + 1] = order[k]
            k -= 1
        order[k + 1] = p
    n = np.int64(0)
    for ii in range(npoly):
        p = order[ii]
        for jj in range(ii + 1, npoly):
            q = order[jj]
            if box[q, 0] > box[p, 1] + margin:
                break
            bp = pbody[p]
            bq = pbody[q]
            if bp == bq:
                continue  # one body, or two supports
            if box[q, 2] > box[p, 3] + margin or box[p, 2] > box[q, 3] + margin:
                continue
            ip = bp if bp >= 0 else nbod + p
            iq = bq if bq >= 0 else nbod + q
            if joined(ip, iq, nid, pkeys, pptr_j, pjoint, jon):
                continue
            sp, ep = _separation(p, q, pptr, wx, wy, wn)
            sq, eq = _separation(q, p, pptr, wx, wy, wn)
            if max(sp, sq) > margin:
                continue
            if sp >= sq:
                n = _manifold(p, q, ep, pptr, wx, wy, wn, margin, found, n, cap)
            else:
                n = _manifold(q, p, eq, pptr, wx, wy, wn, margin, found, n, cap)
    # the ground plane y = 0 (normal +y) against every block's corners
    for p in range(npoly):
        j = pbody[p]
        if j < 0 or box[p, 2] > ground_y + margin or joined(j, nid - 1, nid, pkeys, pptr_j,
                                                             pjoint, jon):
            continue
        for v in range(pptr[p], pptr[p + 1]):
            if wy[v] <= ground_y + margin:
                if n < cap:
                    found[n, 0] = nv
                    found[n, 1] = v
                n += 1
    return n
