"""Convex polygon blocks: validation, mass properties and coincident-face contacts.

The geometric half of a general assembly (docs/theory.md §10): every block is a convex
polygon; two blocks are in contact where an edge of one lies on an edge of the other with
opposite outward normals (a *coincident face*, Eq. (10.1)); a block rests on the ground where
one of its edges lies on y = 0 with an outward normal pointing down. All functions are pure
and raise ValueError with a one-line message naming the block.
"""

from __future__ import annotations

import math

import numpy as np

from rockarch.arch.cutting import polygons_props

#: Relative tolerance (of the assembly's size) for coincident points, faces and overlaps.
REL_TOL = 1e-7


def polygon_props(poly: np.ndarray) -> tuple[float, np.ndarray, float]:
    """Area, centroid (2,) and polar moment about the centroid of one polygon (unit density)."""
    a, c, j = polygons_props(np.asarray(poly, dtype=float)[None])
    return float(a[0]), c[0], float(j[0])


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


#: Largest |coordinate| of a block [m] (masses and inertias ~ size⁴ stay finite).
MAX_COORDINATE = 1e5


def convex_polygon(points, name: str = "block") -> np.ndarray:
    """``points`` as a (K, 2) counter-clockwise convex polygon, or ValueError.

    Either orientation is accepted; collinear vertices are dropped. A polygon whose edges turn
    both ways is non-convex; one that turns one way but winds more than once (a star) is
    self-intersecting.
    """
    try:
        p = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: a polygon is a list of [x, y] points") from None
    if p.ndim != 2 or p.shape[1] != 2 or p.shape[0] < 3:
        raise ValueError(f"{name}: a polygon needs at least 3 [x, y] points")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name}: polygon coordinates must be finite numbers")
    if np.abs(p).max() > MAX_COORDINATE:
        raise ValueError(f"{name}: polygon coordinates must lie within ±{MAX_COORDINATE:g} m "
                         f"(metres), got {np.abs(p).max():.3g}")
    size = float(np.ptp(p, axis=0).max())
    if size <= 0:
        raise ValueError(f"{name}: the polygon has no area")
    tol = REL_TOL * size
    # drop repeated points (incl. a closing copy of the first)
    keep = np.hypot(*(p - np.roll(p, 1, axis=0)).T) > tol
    p = p[keep]
    if len(p) < 3:
        raise ValueError(f"{name}: a polygon needs at least 3 distinct points")
    e = np.roll(p, -1, axis=0) - p
    turn = _cross(np.roll(e, 1, axis=0), e)  # turn at each vertex
    lens = np.hypot(*e.T)
    straight = np.abs(turn) <= 1e-9 * np.roll(lens, 1) * lens
    p, turn = p[~straight], turn[~straight]
    if len(p) < 3:
        raise ValueError(f"{name}: the polygon has no area (all points on a line)")
    if np.any(turn > 0) and np.any(turn < 0):
        raise ValueError(f"{name}: the polygon is not convex (or its edges cross)")
    if turn[0] < 0:
        p = p[::-1]
    e = np.roll(p, -1, axis=0) - p
    ang = np.arctan2(_cross(np.roll(e, 1, axis=0), e),
                     np.sum(np.roll(e, 1, axis=0) * e, axis=1))
    if abs(ang.sum() - 2 * math.pi) > 1e-6:
        raise ValueError(f"{name}: the polygon is self-intersecting (it winds "
                         f"{ang.sum() / (2 * math.pi):.0f} times)")
    return np.ascontiguousarray(p)


def _project(p: np.ndarray, axis: np.ndarray) -> tuple[float, float]:
    s = p @ axis
    return float(s.min()), float(s.max())


def _edge_normals(p: np.ndarray) -> np.ndarray:
    e = np.roll(p, -1, axis=0) - p
    n = np.stack([e[:, 1], -e[:, 0]], axis=1)  # outward for a counter-clockwise polygon
    return n / np.hypot(*n.T)[:, None]


def overlap_depth(p: np.ndarray, q: np.ndarray) -> float:
    """Penetration depth of two convex polygons (separating axes): <= 0 if they are apart
    or only touch, > 0 if their interiors overlap."""
    depth = math.inf
    for axis in np.concatenate([_edge_normals(p), _edge_normals(q)]):
        a0, a1 = _project(p, axis)
        b0, b1 = _project(q, axis)
        depth = min(depth, min(a1, b1) - max(a0, b0))
        if depth <= 0:
            return depth
    return depth


def shared_face(p: np.ndarray, q: np.ndarray, tol: float):
    """The coincident face of convex polygons p and q (Eq. 10.1): (end0, end1, normal) with
    the unit normal pointing from p into q, or None. Faces shorter than ``tol`` are points
    (corner-to-corner touches carry no face)."""
    np_, nq = _edge_normals(p), _edge_normals(q)
    for i in range(len(p)):
        a0, a1 = p[i], p[(i + 1) % len(p)]
        n = np_[i]
        for j in range(len(q)):
            if n @ nq[j] > -1 + 1e-9:
                continue
            b0, b1 = q[j], q[(j + 1) % len(q)]
            if abs((b0 - a0) @ n) > tol or abs((b1 - a0) @ n) > tol:
                continue
            t = (a1 - a0) / np.hypot(*(a1 - a0))
            lo = max(0.0, min((b0 - a0) @ t, (b1 - a0) @ t))
            hi = min(float((a1 - a0) @ t), max((b0 - a0) @ t, (b1 - a0) @ t))
            if hi - lo > tol:
                return a0 + lo * t, a0 + hi * t, n.copy()
    return None


def ground_face(p: np.ndarray, tol: float, level: float = 0.0):
    """The edge of p lying on the ground y = level (end0, end1) with the upward normal, or
    None."""
    on = np.abs(p[:, 1] - level) <= tol
    k = len(p)
    for i in range(k):
        j = (i + 1) % k
        if on[i] and on[j] and p[j, 0] > p[i, 0] + tol:  # bottom edge of a CCW polygon
            return (np.array([p[i, 0], level]), np.array([p[j, 0], level]),
                    np.array([0.0, 1.0]))
    return None
