"""Typed inputs of the MDOF kernels, built from an :class:`~rockarch.mdof.assembly.Assembly`.

The kernels take one small named tuple (numba passes it as a record) instead of a long
positional argument list: :func:`chain_model` for the banded chain stepper,
:func:`graph_model` for the general contact-graph stepper with friction.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import reverse_cuthill_mckee

from rockarch.mdof.assembly import Assembly

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


class GraphModel(NamedTuple):
    """Any assembly for :mod:`rockarch.mdof.graph_run` (unit scale)."""

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
    banded: bool  # exact banded contact solve (else rest path, Gauss–Seidel)
    kd: int  # half-bandwidth of W in this joint order
    inc_ptr: np.ndarray  # (nb + 1,) body j takes part in joints inc_joint[inc_ptr[j]:inc_ptr[j+1]]
    inc_joint: np.ndarray
    inc_side: np.ndarray  # 0: as body a, 1: as body b
    order: np.ndarray  # (nj,) model joint i is the assembly's joint order[i]
    bpos: np.ndarray  # (nb,) place of every body in a narrow-band body order (rest path)
    kbody: int  # half-bandwidth of JᵀJ in that order (3 rows a body)
    thick_min: float
    delta_ref: float
    g: float


#: Largest half-bandwidth of W solved by the banded exact solve (cost n·kd² per
#: factorisation, one per pivot, and a cold start pivots once per opening row); wider
#: graphs use the rest path and Gauss–Seidel (rest_solver, graph_solver). At kd = 38–47
#: (40-block walls) the banded solve is already 5–12× slower than those and fails steps on
#: its pivot limit; the 14-block wall (kd = 32) and every chain and bridge of the tests stay
#: banded.
KD_MAX = 32


def _half_band(order: np.ndarray, pairs: np.ndarray) -> int:
    pos = np.empty(order.size, dtype=np.int64)
    pos[order] = np.arange(order.size)
    return int(3 * np.abs(pos[pairs[:, 0]] - pos[pairs[:, 1]]).max() + 2)


def joint_order(assembly: Assembly) -> tuple[np.ndarray, int]:
    """A joint order with a narrow band and the half-bandwidth of W in it (3 rows per
    joint): chains keep theirs; other graphs take the narrowest of reverse Cuthill–McKee
    on the joints-sharing-a-body graph and the joints sorted by height or by abscissa."""
    body_a, body_b = np.asarray(assembly.body_a), np.asarray(assembly.body_b)
    nj = body_a.size
    pairs = []
    for j in range(assembly.n_blocks):
        ks = np.flatnonzero((body_a == j) | (body_b == j))
        pairs += [(a, b) for a in ks for b in ks if a != b]
    if not pairs:
        return np.arange(nj), 2
    p = np.array(pairs)
    if assembly.is_chain:
        return np.arange(nj), _half_band(np.arange(nj), p)
    adj = csr_matrix((np.ones(len(p)), (p[:, 0], p[:, 1])), shape=(nj, nj))
    mid = np.asarray(assembly.corners, dtype=float).mean(axis=1)
    cands = [np.asarray(reverse_cuthill_mckee(adj, symmetric_mode=True), dtype=np.int64),
             np.lexsort((mid[:, 0], mid[:, 1])), np.lexsort((mid[:, 1], mid[:, 0]))]
    return min(((o, _half_band(o, p)) for o in cands), key=lambda c: c[1])


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
    best = None
    for o in (reverse_cuthill_mckee(adj + adj.T, symmetric_mode=True),
              np.lexsort((cen[:, 1], cen[:, 0])), np.lexsort((cen[:, 0], cen[:, 1]))):
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


def graph_model(assembly: Assembly) -> GraphModel:
    """The general stepper's input: the contact graph (body_a, body_b) and mu per joint."""
    order, kd = joint_order(assembly)
    ba = np.ascontiguousarray(np.asarray(assembly.body_a, dtype=np.int64)[order])
    bb = np.ascontiguousarray(np.asarray(assembly.body_b, dtype=np.int64)[order])
    cen = np.asarray(assembly.centroid, dtype=float)
    corners = np.asarray(assembly.corners, dtype=float)[order]
    inc = sorted([(int(b), k, 0) for k, b in enumerate(ba) if b >= 0]
                 + [(int(b), k, 1) for k, b in enumerate(bb) if b >= 0])
    ptr = np.searchsorted([i[0] for i in inc], np.arange(assembly.n_blocks + 1))

    normal = _f(np.asarray(assembly.normal)[order])

    def rel(bodies, pts):
        return np.ascontiguousarray(pts - np.where(bodies[:, None, None] >= 0,
                                                   cen[bodies][:, None, :], 0.0))

    fa, fb = face_ends(assembly, ba, corners, normal), face_ends(assembly, bb, corners, normal)
    span = np.hypot(*(corners[:, 1] - corners[:, 0]).T)
    return GraphModel(_f(assembly.mass), _f(assembly.inertia), _f(cen), ba, bb,
                      rel(ba, corners), rel(bb, corners), normal,
                      _f(np.asarray(assembly.mu)[order]), rel(ba, fa), rel(bb, fb),
                      _f(SLIDE_TOL * span), kd <= KD_MAX, kd,
                      np.ascontiguousarray(ptr, dtype=np.int64),
                      np.array([i[1] for i in inc], dtype=np.int64),
                      np.array([i[2] for i in inc], dtype=np.int64), order,
                      *body_order(assembly),
                      float(assembly.thickness.min()), float(assembly.delta_ref),
                      float(assembly.g))
