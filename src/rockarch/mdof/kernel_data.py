"""Typed inputs of the MDOF kernels, built from an :class:`~rockarch.mdof.assembly.Assembly`.

The kernels take one record instead of a long positional argument list:
:func:`chain_model` (a small named tuple, passed by value) for the banded chain stepper,
:func:`graph_model` (a record passed by reference, :mod:`rockarch.core.jit_struct`) for
the general contact-graph stepper with friction.
"""

from __future__ import annotations

from typing import NamedTuple

import numba as nb
import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.spatial import ConvexHull

from rockarch.core.jit_struct import JitStruct, jit_struct
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.collision import thin_outline

#: The fraction of a face a joint's contact end may pass the other face's end before the
#: overlap's end moves to it (docs/theory.md §9; :mod:`rockarch.mdof.graph_stepper`).
SLIDE_TOL = 1e-3


class ChainModel(NamedTuple):
    """A chain assembly for :mod:`rockarch.mdof.chain_stepper` (unit scale)."""

    mass: np.ndarray  # (nb,)
    inertia: np.ndarray  # (nb,) about the centroid
    c0: np.ndarray  # (nb, 2) reference centroids
    rl: np.ndarray  # (nj, 2, 2) corners relative to the left/lower body (absolute: ground)
    rr: np.ndarray  # (nj, 2, 2) corners relative to the right/upper body
    n0: np.ndarray  # (nj, 2) reference normals
    thick_min: float  # thinnest joint (contact tolerance scale)
    delta_ref: float  # reference rotation of max_rotation_ratio
    g: float


def _f(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float)


def chain_model(assembly: Assembly) -> ChainModel:
    """The chain stepper's input (joint k between body k−1 and body k)."""
    nb_, nj = assembly.n_blocks, assembly.n_joints
    rl = np.empty((nj, 2, 2))
    rr = np.empty((nj, 2, 2))
    for k in range(nj):
        rl[k] = assembly.corners[k] - (assembly.centroid[k - 1] if k >= 1 else 0.0)
        rr[k] = assembly.corners[k] - (assembly.centroid[k] if k < nb_ else 0.0)
    return ChainModel(_f(assembly.mass), _f(assembly.inertia), _f(assembly.centroid), rl, rr,
                      _f(assembly.normal), float(assembly.thickness.min()),
                      float(assembly.delta_ref), float(assembly.g))


@jit_struct
class GraphModel(JitStruct):
    """Any assembly for :mod:`rockarch.mdof.graph_run` (unit scale), passed by reference
    (:mod:`rockarch.core.jit_struct`)."""

    mass: np.ndarray  # (nb,)
    inertia: np.ndarray  # (nb,)
    c0: np.ndarray  # (nb, 2)
    ba: np.ndarray  # (nj,) body on the tail side of the normal (-1: ground)
    bb: np.ndarray  # (nj,) body the normal points into (-1: ground)
    ra: np.ndarray  # (nj, 2, 2) corners relative to body a (absolute for the ground)
    rb: np.ndarray  # (nj, 2, 2) corners relative to body b (absolute for the ground)
    n0: np.ndarray  # (nj, 2) reference normals (turn with body a)
    mu: np.ndarray  # (nj,) friction coefficients (inf: no sliding)
    fa: np.ndarray  # (nj, 2, 2) ends of body a's face on the corner 0 / 1 side (as ra)
    fb: np.ndarray  # (nj, 2, 2) ends of body b's face (as rb)
    ftol: np.ndarray  # (nj,) slip below which a sliding joint keeps its corners as built
    inc_ptr: np.ndarray  # (nb + 1,) body j takes part in joints inc_joint[inc_ptr[j]:inc_ptr[j+1]]
    inc_joint: np.ndarray
    inc_side: np.ndarray  # 0: as body a, 1: as body b
    bpos: np.ndarray  # (nb,) place of every body in a narrow-band body order (Newton solve)
    kbody: int  # half-bandwidth of JᵀJ in that order (3 rows a body)
    kd_cap: int  # half-bandwidth the solver's band has room for (new contacts widen it)
    pv: np.ndarray  # (nv, 2) outline vertices for new contacts, relative to their body's
    #                 centroid (a support's: absolute), counter-clockwise
    pptr: np.ndarray  # (npoly + 1,) polygon p has the vertices pptr[p]:pptr[p + 1]
    pbody: np.ndarray  # (npoly,) body of every polygon (-1: a support)
    vpoly: np.ndarray  # (nv,) polygon of every vertex
    pkeys: np.ndarray  # sorted keys of the pairs of ids (a block, nb + a support polygon,
    #                    nb + npoly the ground) that share joints ...
    pptr_j: np.ndarray  # ... their joints pjoint[pptr_j[q]:pptr_j[q + 1]]
    pjoint: np.ndarray
    ground_y: float  # height of the ground plane of new contacts
    mu_contact: float  # friction coefficient of new contacts
    contact_cap: int  # most point contacts at once
    thick_min: float
    delta_ref: float
    g: float


def body_order(assembly: Assembly) -> tuple[np.ndarray, int]:
    """The place of every body in a narrow-band body order and the half-bandwidth of JᵀJ in
    it (3 rows per body): the narrowest of reverse Cuthill–McKee on the bodies-sharing-a-
    joint graph and the bodies sorted by abscissa or by height."""
    body_a, body_b = np.asarray(assembly.body_a), np.asarray(assembly.body_b)
    nb_ = assembly.n_blocks
    both = (body_a >= 0) & (body_b >= 0)
    p = np.column_stack([body_a[both], body_b[both]])
    if not p.size:
        return np.arange(nb_, dtype=np.int64), 2
    adj = csr_matrix((np.ones(len(p)), (p[:, 0], p[:, 1])), shape=(nb_, nb_))
    cen = np.asarray(assembly.centroid, dtype=float)
    # rounded to a millionth of the size: the blocks of a course sort by abscissa, not by
    # the round-off of their heights
    q = np.round(cen / (1e-6 * max(float(np.ptp(cen, axis=0).max()), 1e-300)))
    best = None
    for o in (reverse_cuthill_mckee(adj + adj.T, symmetric_mode=True),
              np.lexsort((q[:, 1], q[:, 0])), np.lexsort((q[:, 0], q[:, 1]))):
        pos = np.empty(nb_, dtype=np.int64)
        pos[np.asarray(o)] = np.arange(nb_)
        kb = int(3 * np.abs(pos[p[:, 0]] - pos[p[:, 1]]).max() + 2)
        if best is None or kb < best[1]:
            best = (pos, kb)
    return best


#: Half-length of the ground's face [m]: the ground is a plane (its ends are never reached).
GROUND_FACE = 1e6


def face_ends(assembly: Assembly, body: np.ndarray, corners: np.ndarray,
              normal: np.ndarray) -> np.ndarray:
    """The ends of every joint's face on ``body``'s side (nj, 2, 2; end c on corner c's
    side): the extreme vertices on the joint line of the body's outline (of the support's,
    for a support given to :func:`rockarch.mdof.builders.from_polygons`), along which a
    sliding joint's contact may run (docs/theory.md §9). The ground y = 0 is a plane
    (±``GROUND_FACE``); any other support's face ends at the joint's corners."""
    outlines: dict[int, list] = {}
    for i, p in enumerate(assembly.polygons):
        outlines.setdefault(assembly.body_of_polygon(i), []).append(np.asarray(p, float))
    supports = [np.asarray(p, float) for p in assembly.info.get("supports", ())]
    ends = corners.copy()
    for k in range(corners.shape[0]):
        c0, c1 = corners[k]
        length = float(np.hypot(*(c1 - c0)))
        t = (c1 - c0) / length
        tol = 1e-6 * max(length, float(np.abs(corners).max()))
        lo, hi = 0.0, length
        if body[k] < 0 and abs(c0[1]) <= tol and abs(c1[1]) <= tol:
            lo, hi = -GROUND_FACE, length + GROUND_FACE
        else:
            for v in (outlines.get(int(body[k]), []) if body[k] >= 0 else supports):
                on = np.abs((v - c0) @ normal[k]) <= tol
                u = (v[on] - c0) @ t
                if on.sum() >= 2 and u.min() <= tol and u.max() >= length - tol:
                    lo, hi = min(lo, float(u.min())), max(hi, float(u.max()))
        ends[k, 0] = c0 + lo * t if lo < -tol else c0  # a face end at the corner: the corner
        ends[k, 1] = c0 + hi * t if hi > length + tol else c1
    return ends


#: Most vertices of a block's outline for new contacts: a curved voussoir's convex hull is
#: thinned to its corners and the arc points that matter most (Visvalingam's area rule).
OUTLINE_VERTICES = 12


def collision_outline(points: np.ndarray) -> np.ndarray:
    """The outline of a block for new contacts (:mod:`rockarch.mdof.collision`): its convex
    hull, counter-clockwise, thinned to ``OUTLINE_VERTICES`` by repeatedly dropping the
    vertex whose triangle with its neighbours has the least area (a concave intrados becomes
    its chord; flat faces and corners stay; :func:`rockarch.mdof.collision.thin_outline`)."""
    hull = np.asarray(points, float)[ConvexHull(np.asarray(points, float)).vertices]
    return hull[thin_outline(np.ascontiguousarray(hull), OUTLINE_VERTICES)]


def _outlines(assembly: Assembly):
    """Collision outlines of the blocks and supports: vertices (relative to the body's
    centroid; a support's absolute), polygon pointers, polygon bodies, vertex polygons, and
    the sorted keys of the (corner, face) pairs that touch as built (the joints'; a corner
    on the ground y = 0 against the ground, face id nv)."""
    cen = np.asarray(assembly.centroid, dtype=float)
    polys = [(assembly.body_of_polygon(i), collision_outline(p))
             for i, p in enumerate(assembly.polygons)]
    polys += [(-1, collision_outline(p)) for p in assembly.info.get("supports", ())]
    world = [p for _, p in polys]
    size = float(np.ptp(np.concatenate(world), axis=0).max())
    tol = 1e-6 * size
    ptr = np.cumsum([0] + [len(p) for p in world])
    allv = np.concatenate(world)
    vpoly = np.repeat(np.arange(len(world)), [len(p) for p in world])
    pbody = np.array([b for b, _ in polys], dtype=np.int64)
    # the joints of every pair of ids (a block's index, nb + p for support polygon p, the
    # ground plane nb + npoly): two blocks joined by a joint in use touch through it only
    nb_ = assembly.n_blocks
    npoly = len(polys)
    nid = nb_ + npoly + 1
    corners = np.asarray(assembly.corners, dtype=float)
    normal = np.asarray(assembly.normal, dtype=float)
    pairs: dict[int, list[int]] = {}
    for k, (a, b) in enumerate(zip(assembly.body_a, assembly.body_b, strict=True)):
        a, b = int(a), int(b)
        if a >= 0 and b >= 0:
            ids = (a, b)
        else:
            body = b if a < 0 else a
            c0, c1 = corners[k]
            if max(abs(c0[1]), abs(c1[1])) <= tol and abs(abs(normal[k, 1]) - 1.0) <= 1e-9:
                other = nid - 1
            else:
                other = next((nb_ + p for p, (bp, pw) in enumerate(polys) if bp < 0 and any(
                    max(abs((c0 - pw[e]) @ normal[k]), abs((c1 - pw[e]) @ normal[k])) <= tol
                    for e in range(len(pw)))), -1)
            if other < 0:
                continue  # an abutment without an outline: nothing to collide with
            ids = (body, other)
        pairs.setdefault(min(ids) * nid + max(ids), []).append(k)
    keys = np.array(sorted(pairs), dtype=np.int64)
    pptr_j = np.cumsum([0] + [len(pairs[q]) for q in keys]).astype(np.int64)
    pjoint = np.array([k for q in keys for k in pairs[q]], dtype=np.int64)
    rel = allv - np.where(pbody[vpoly][:, None] >= 0, cen[np.maximum(pbody[vpoly], 0)], 0.0)
    # the ground plane: y = 0, or just below the lowest corner as built if that is lower (an
    # arch springs from inclined abutments below its springing line: none touches the plane)
    low = float(allv[pbody[vpoly] >= 0, 1].min())
    ground_y = 0.0 if low >= -tol else low - 1e-3 * size
    return (_f(rel), np.asarray(ptr, dtype=np.int64), pbody, np.asarray(vpoly, dtype=np.int64),
            keys, pptr_j, pjoint, ground_y)


def graph_model(assembly: Assembly) -> GraphModel:
    """The general stepper's input: the contact graph (body_a, body_b), mu per joint and
    the blocks' outlines for new contacts."""
    ba = np.ascontiguousarray(np.asarray(assembly.body_a, dtype=np.int64))
    bb = np.ascontiguousarray(np.asarray(assembly.body_b, dtype=np.int64))
    cen = np.asarray(assembly.centroid, dtype=float)
    corners = np.asarray(assembly.corners, dtype=float)
    inc = sorted([(int(b), k, 0) for k, b in enumerate(ba) if b >= 0]
                 + [(int(b), k, 1) for k, b in enumerate(bb) if b >= 0])
    ptr = np.searchsorted([i[0] for i in inc], np.arange(assembly.n_blocks + 1))
    normal = _f(assembly.normal)

    def rel(bodies, pts):
        return np.ascontiguousarray(pts - np.where(bodies[:, None, None] >= 0,
                                                   cen[bodies][:, None, :], 0.0))

    fa, fb = face_ends(assembly, ba, corners, normal), face_ends(assembly, bb, corners, normal)
    span = np.hypot(*(corners[:, 1] - corners[:, 0]).T)
    bpos, kbody = body_order(assembly)
    pv, pptr, pbody, vpoly, pkeys, pptr_j, pjoint, ground_y = _outlines(assembly)
    mu = np.asarray(assembly.mu, dtype=float)
    return _new_graph_model((_f(assembly.mass), _f(assembly.inertia), _f(cen), ba, bb,
                             rel(ba, corners), rel(bb, corners), normal, _f(mu), rel(ba, fa),
                             rel(bb, fb), _f(SLIDE_TOL * span),
                             np.ascontiguousarray(ptr, dtype=np.int64),
                             np.array([i[1] for i in inc], dtype=np.int64),
                             np.array([i[2] for i in inc], dtype=np.int64),
                             bpos, kbody,
                             min(3 * assembly.n_blocks - 1, max(2 * kbody, kbody + 30)),
                             pv, pptr, pbody, vpoly, pkeys, pptr_j, pjoint, ground_y,
                             float(mu.min()), 2 * pv.shape[0] + 16,
                             float(assembly.thickness.min()), float(assembly.delta_ref),
                             float(assembly.g)))


@nb.njit(cache=True)
def _new_graph_model(fields):
    """A :class:`GraphModel` of its fields (built here: from Python, numba would compile
    its constructor anew in every process)."""
    return GraphModel(*fields)
