"""Macro-block mechanisms: one rigid cluster of blocks rocking about one corner, every joint
around it unloaded (docs/theory.md §10, Eq. 10.9).

Non-associative limit analysis can have several solutions, and the iteration of
:mod:`rockarch.mdof.nonassoc` finds one. A cluster S of blocks rotating rigidly about a
corner P, with every other joint on its boundary opening (and free to slide: it carries
nothing), is another solution wherever the rest of the structure can stand: S's moment
balance about P fixes λ_S, and the LP of Eq. (10.4) with S's boundary forces set to zero
(except at P) confirms a Coulomb-admissible force field. These are the crack patterns of
the kinematic (macro-element) approach to masonry, e.g. the stepped corner wedge of a
running-bond wall. :func:`lowest` returns the least confirmed one below a given λ.
"""

from __future__ import annotations

import hashlib
import threading

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import breadth_first_order

from rockarch.mdof.nonassoc import Iterate


def _drags(pivot, omega: float, kin, tol: float) -> csr_matrix:
    """The directed graph "i rotating about ``pivot`` drags j along" (node nb: the ground):
    at a joint with i inside and j outside, a corner of j would be penetrated (its normal
    relative velocity below -tol), so j must join the cluster."""
    centroid, corners, normal, body_a, body_b = kin
    nb_ = len(centroid)
    r = corners - pivot  # (nj, 2, 2)
    dn = omega * np.einsum("kcd,kd->kc", np.stack([-r[..., 1], r[..., 0]], axis=-1), normal)
    a, b = np.where(body_a < 0, nb_, body_a), np.where(body_b < 0, nb_, body_b)
    b_in = (dn < -tol).any(axis=1)  # b inside, a outside: b's motion w.r.t. a penetrates
    a_in = (dn > tol).any(axis=1)   # a inside, b outside: the same, mirrored
    src = np.r_[b[b_in], a[a_in]]
    dst = np.r_[a[b_in], b[a_in]]
    return csr_matrix((np.ones(len(src)), (src, dst)), shape=(nb_ + 1, nb_ + 1))


def _reach(graph: csr_matrix, start: int, nb_: int):
    """The cluster of ``start`` in the drag graph: every block it reaches (an (nb,) bool
    mask), or None if it reaches the ground."""
    seen = breadth_first_order(graph, start, directed=True, return_predecessors=False)
    if (seen == nb_).any():
        return None
    ins = np.zeros(nb_, dtype=bool)
    ins[seen] = True
    return ins


#: Clusters of recent geometries (both load directions and both friction analyses of one
#: build share them: the enumeration is a second on a 205-block wall).
_CACHE: dict = {}
_CACHE_LOCK = threading.Lock()


def clusters(kin, size: float) -> list:
    """Every distinct (S, k, c, ω) of Eq. (10.9): cluster S (an (nb,) bool mask) grown from
    a block of joint k rotating at rate ω about corner c of k. Geometry only (no load
    direction, no friction); cached for the last few geometries."""
    key = hashlib.sha1(b"".join(np.ascontiguousarray(v).tobytes() for v in kin)
                       + np.float64(size).tobytes()).hexdigest()
    with _CACHE_LOCK:  # held throughout: the other direction's thread waits and reuses
        if key not in _CACHE:
            if len(_CACHE) >= 4:
                _CACHE.pop(next(iter(_CACHE)))
            _CACHE[key] = _enumerate(kin, size)
        return _CACHE[key]


def _enumerate(kin, size: float) -> list:
    centroid, corners, normal, body_a, body_b = kin
    nj, nb_, tol = len(normal), len(centroid), 1e-9 * size
    seen, out, graphs = set(), [], {}
    for k in range(nj):
        for c in range(2):
            pivot = corners[k, c]
            for start in (body_a[k], body_b[k]):
                for omega in (1.0, -1.0):
                    if start < 0:
                        continue
                    gkey = (pivot.tobytes(), omega)  # joints share corners: one graph each
                    if gkey not in graphs:
                        graphs[gkey] = _drags(pivot, omega, kin, tol)
                    s = _reach(graphs[gkey], int(start), nb_)
                    if s is None:  # the whole structure is a cluster too: a block
                        continue   # jammed against a support by self-stress rocks away
                    key_s = (s.tobytes(), k, c, omega)
                    if key_s not in seen:
                        seen.add(key_s)
                        out.append((s, k, c, omega))
    return out


def lowest(kin, mass, direction: int, lp, below: float, size: float):
    """The least macro-block solution with λ < ``below`` (Eq. 10.9), or None.

    ``kin`` = (centroid, corners, normal, body_a, body_b); ``lp(zero)`` solves Eq. (10.4)
    with the corner forces of the (nj, 2) mask ``zero`` set to 0 and returns scipy's result.
    Returns an :class:`Iterate` whose ``duals`` are the cluster's rotation.
    """
    centroid, corners = kin[0], kin[1]
    body_a, body_b = kin[3], kin[4]
    cands = []
    for s, k, c, omega in clusters(kin, size):
        r = centroid[s] - corners[k, c]
        m_in = direction * float(np.sum(mass[s] * r[:, 1]))
        if omega * m_in <= 0:  # inertia must drive the rotation
            continue
        lam = float(np.sum(mass[s] * r[:, 0])) / m_in
        if 0 <= lam < below * (1 - 1e-9):
            cands.append((lam, s, k, c, omega))
    for lam, s, k, c, omega in sorted(cands, key=lambda t: t[0]):
        zero = np.repeat((np.append(s, False)[body_a] ^ np.append(s, False)[body_b])[:, None],
                         2, axis=1)
        zero[k, c] = False
        res = lp(zero)
        if res.status != 0 or abs(res.x[-1] - lam) > 1e-6 * max(1.0, lam):
            continue
        r = centroid - corners[k, c]
        vel = np.where(s[:, None], omega * np.stack([-r[:, 1], r[:, 0], np.ones(len(s))],
                                                    axis=1), 0.0)
        return Iterate(float(res.x[-1]), res.x, vel.reshape(-1))
    return None


def solve_zeroed(cost, a_ub, b_ub, a_eq, b_eq, bounds, zero):
    """Eq. (10.4) with the corner forces (N and T) flagged in ``zero`` fixed at 0."""
    nj = zero.shape[0]
    bnd = list(bounds)
    for i in np.flatnonzero(zero.reshape(-1)):
        bnd[i] = (0.0, 0.0)
        bnd[2 * nj + i] = (0.0, 0.0)
    return linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=b_eq, bounds=bnd,
                   method="highs")
