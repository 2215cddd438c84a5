"""Voussoir cutting: joints normal to the axis, mass, centroid, inertia (docs/theory.md Sect. 4)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockarch.arch.geometry import Arch
from rockarch.core import limits
from rockarch.core.validate import integer

_MIN_SUB = 2000  # minimum number of sub-segments along the whole arch in a discretisation


@dataclass(frozen=True)
class Voussoirs:
    """An arch cut into N voussoirs by N + 1 joints normal to the axis (docs/theory.md Sect. 4).

    Attributes (per unit depth, unit density)
    ----------
    arch : Arch
    sigma : (N+1,) normalised arc length of the joints (0 = left springing).
    points : (N+1, 2) axis point of each joint (midpoint of the joint).
    tangent : (N+1, 2) unit axis tangent at each joint (left to right).
    thickness : (N+1,) joint length.
    intrados, extrados : (N+1, 2) joint end points.
    mass : (N,) voussoir mass (= area for the voussoir model).
    centroid : (N, 2) centre of mass.
    inertia : (N,) polar moment about the centre of mass.
    """

    arch: Arch
    sigma: np.ndarray
    points: np.ndarray
    tangent: np.ndarray
    thickness: np.ndarray
    intrados: np.ndarray
    extrados: np.ndarray
    mass: np.ndarray
    centroid: np.ndarray
    inertia: np.ndarray
    sub: int = 1

    @property
    def n(self) -> int:
        """Number of voussoirs."""
        return len(self.mass)

    @property
    def normal(self) -> np.ndarray:
        """(N+1, 2) unit normal of each joint, pointing to the extrados."""
        return np.stack([-self.tangent[:, 1], self.tangent[:, 0]], axis=-1)

    def polygons(self) -> list[np.ndarray]:
        """Voussoir outlines (for plots): list of (2*sub + 2, 2) arrays."""
        sig = np.linspace(0.0, 1.0, self.n * self.sub + 1)
        ip, ep = self.arch.joints_at(sig)
        k = self.sub
        return [np.concatenate([ip[j * k:(j + 1) * k + 1], ep[j * k:(j + 1) * k + 1][::-1]])
                for j in range(self.n)]


def polygons_props(v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Area, centroid, polar moment about the centroid of polygons v (N, K, 2), vectorised."""
    o = v.mean(axis=1, keepdims=True)
    p = v - o
    x, y = p[..., 0], p[..., 1]
    x1, y1 = np.roll(x, -1, axis=1), np.roll(y, -1, axis=1)
    cr = x * y1 - x1 * y
    a = 0.5 * cr.sum(axis=1)
    cx = ((x + x1) * cr).sum(axis=1) / (6 * a)
    cy = ((y + y1) * cr).sum(axis=1) / (6 * a)
    j0 = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * cr).sum(axis=1) / 12
    j = j0 - a * (cx * cx + cy * cy)
    return a, np.stack([cx, cy], axis=-1) + o[:, 0, :], j


def voussoirs(arch: Arch, n: int) -> Voussoirs:
    """Cut ``arch`` into ``n`` voussoirs of equal axis arc length, joints normal to the axis.

    Each voussoir outline follows the intrados and extrados with enough sub-segments that the
    whole arch has at least ~2000 of them (exact areas/centroids to O(1e-7) for curved arches).
    Mass, centroid and polar moment follow ``arch.mass_model`` (see :mod:`rockarch.arch.geometry`).
    """
    n = integer("number of voussoirs (blocks)", n)
    if n < 4:
        raise ValueError(f"at least 4 voussoirs are needed for a four-hinge mechanism, got {n}")
    limits.check_count("the arch", n, "voussoirs", "use fewer --blocks")
    sub = max(1, math.ceil(_MIN_SUB / n))
    sig = np.linspace(0.0, 1.0, n * sub + 1)
    ip, ep = arch.joints_at(sig)
    if arch.contour is None:
        pts, tan, dd = arch.axis_at(sig)
    else:
        pts = 0.5 * (ip + ep)
        dvec = ep - ip
        dd = np.hypot(dvec[:, 0], dvec[:, 1])
        nn = dvec / dd[:, None]
        tan = np.stack([nn[:, 1], -nn[:, 0]], axis=-1)
    # polygons: intrados forward, extrados backward
    idx = np.arange(n)[:, None] * sub + np.arange(sub + 1)[None, :]
    poly = np.concatenate([ip[idx], ep[idx][:, ::-1]], axis=1)
    area, cen, jp = polygons_props(poly)
    if np.any(area <= 0):
        raise ValueError("voussoir outlines overlap or turn inside out: thickness too large for "
                         "this axis")
    jo = np.arange(0, n * sub + 1, sub)
    if arch.mass_model == "voussoir":
        mass, centroid, inertia = area, cen, jp
    else:
        # line mass on the axis: sub-segment masses at their midpoints
        mid = 0.5 * (pts[:-1] + pts[1:])
        if arch.mass_model == "axis":
            ds = np.hypot(*np.diff(pts, axis=0).T)
            ms = ds * 0.5 * (dd[:-1] + dd[1:])
        else:
            ms = np.diff(arch.weights.cumulative(pts[:, 0]))
            if np.any(ms < 0):
                raise ValueError("mass_model='weights' needs an axis that advances in x")
            ds = np.hypot(*np.diff(pts, axis=0).T)
        ms = ms.reshape(n, sub)
        mid = mid.reshape(n, sub, 2)
        ds = ds.reshape(n, sub)
        mass = ms.sum(axis=1)
        centroid = np.einsum("ns,nsk->nk", ms, mid) / mass[:, None]
        r2 = np.sum((mid - centroid[:, None, :]) ** 2, axis=2)
        inertia = np.sum(ms * (r2 + ds * ds / 12.0), axis=1)
    return Voussoirs(arch=arch, sigma=sig[jo], points=pts[jo], tangent=tan[jo],
                     thickness=dd[jo], intrados=ip[jo], extrados=ep[jo], mass=mass,
                     centroid=centroid, inertia=inertia, sub=sub)
