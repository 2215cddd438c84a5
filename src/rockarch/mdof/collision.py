"""New contacts of a moving assembly: any corner that reaches any face (numba).

The joints of an assembly are the faces that touch as built (docs/theory.md §10). A block
that falls off a wall, tips off a pedestal or topples against its neighbour touches faces
that were apart: every step, any corner of a block that comes within a margin of a face of
another block, of a support or of the ground becomes a *point contact* (one normal and one
tangential row, Coulomb's cone on the corner, docs/theory.md Eq. (9.9)); a contact whose
corner moves away is dropped the next step. Broad phase: the blocks' bounding boxes, sorted
by their left edge and swept; narrow phase: for convex polygons P and Q, a corner v of Q is
in contact with the edge of P of greatest signed distance s_e(v) = n_e·(v − p_e) (the
separating axis of least penetration) when that distance is within the margin. A corner and
a face that form a joint as built (the corner lay on the joint's line) are the joint's: they
are never a point contact, and neither is a corner whose nearest face is such a joint face.
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
def _excluded(excl, key):
    i = np.searchsorted(excl, key)
    return i < excl.shape[0] and excl[i] == key


@nb.njit(cache=True)
def _corners_on(pa, pb, pptr, wx, wy, wn, excl, nv, margin, tie, out, n, cap):
    """Corners of polygon ``pb`` within ``margin`` of polygon ``pa`` (face owner): appended to
    ``out`` as (edge id, vertex id) rows from row n. Returns the new count (capped)."""
    i0 = pptr[pa]
    i1 = pptr[pa + 1]
    for v in range(pptr[pb], pptr[pb + 1]):
        vx = wx[v]
        vy = wy[v]
        best = -math.inf
        be = -1
        for a0 in range(i0, i1):
            s = wn[a0, 0] * (vx - wx[a0]) + wn[a0, 1] * (vy - wy[a0])
            if s > margin:
                be = -1
                break
            if s > best:
                best = s
                be = a0
        if be < 0:
            continue
        # the joint's face wins a tie (a corner shared by a joint's face and another face)
        key0 = v * (nv + 1)
        joint = False
        for a0 in range(i0, i1):
            s = wn[a0, 0] * (vx - wx[a0]) + wn[a0, 1] * (vy - wy[a0])
            if s >= best - tie and _excluded(excl, key0 + a0):
                joint = True
                break
        if joint:
            continue
        if n < cap:
            out[n, 0] = be
            out[n, 1] = v
            n += 1
        else:
            n += 1  # counted: the caller widens its room
    return n


@nb.njit(cache=True)
def detect(pptr, pbody, pv, pn, x, y, cs, sn, excl, margin, tie, wx, wy, wn, box, order,
           found):
    """Every (face, corner) pair within ``margin`` (module docstring): rows of ``found``
    (edge id: the global index of the edge's first vertex, or nv for the ground plane y = 0;
    vertex id). A joint's face within ``tie`` (the contact tolerance) of the nearest face
    wins: corners shared by a joint's face and another face of the block (four blocks
    meeting in a running-bond wall, a voussoir's corner) stay the joint's. ``order`` keeps
    the polygons sorted by the left edge of their boxes from call to call (insertion sort:
    linear while the blocks move little). Returns the number found (more than
    found.shape[0]: that many did not fit)."""
    npoly = pbody.shape[0]
    nv = pv.shape[0]
    cap = found.shape[0]
    boxes(pptr, pbody, pv, pn, x, y, cs, sn, wx, wy, wn, box)
    for i in range(1, npoly):
        p = order[i]
        k = i - 1
        while k >= 0 and box[order[k], 0] > box[p, 0]:
            order[k + 1] = order[k]
            k -= 1
        order[k + 1] = p
    n = 0
    for ii in range(npoly):
        p = order[ii]
        for jj in range(ii + 1, npoly):
            q = order[jj]
            if box[q, 0] > box[p, 1] + margin:
                break
            if pbody[p] == pbody[q]:
                continue  # one body, or two supports
            if box[q, 2] > box[p, 3] + margin or box[p, 2] > box[q, 3] + margin:
                continue
            n = _corners_on(p, q, pptr, wx, wy, wn, excl, nv, margin, tie, found, n, cap)
            n = _corners_on(q, p, pptr, wx, wy, wn, excl, nv, margin, tie, found, n, cap)
    # the ground plane y = 0 (normal +y) against every block's corners
    for p in range(npoly):
        if pbody[p] < 0 or box[p, 2] > margin:
            continue
        for v in range(pptr[p], pptr[p + 1]):
            if wy[v] <= margin and not _excluded(excl, v * (nv + 1) + nv):
                if n < cap:
                    found[n, 0] = nv
                    found[n, 1] = v
                n += 1
    return n
