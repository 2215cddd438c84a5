"""Parametric arch axes t in [0, 1] -> (x, y, dx/dt, dy/dt) (docs/theory.md Sect. 4).

The axis shapes of :data:`SHAPES` (catenary, circular, pointed two-centred, elliptical) and the
polyline axis, plus the self-intersection test used to validate user polylines. Each builder
returns an :data:`AxisFn`; :mod:`rockarch.arch.geometry` wraps it into an :class:`Arch`.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from rockarch.core.validate import positive

SHAPES = ("catenary", "circular", "pointed", "elliptical")

#: Range of rise/span of a catenary axis (its parameter a/l lies in [1e-4, 1e6] there).
CATENARY_RISE_OVER_SPAN = (1e-6, 100.0)

AxisFn = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]


def catenary_parameter(span: float, rise: float) -> float:
    """Return a with a*(cosh(span/(2a)) - 1) = rise: the catenary y = f + a - a*cosh(x'/a)."""
    span = positive("span", span)
    rise = positive("rise", rise)
    r = rise / span
    lo, hi = CATENARY_RISE_OVER_SPAN
    if not lo <= r <= hi:
        raise ValueError(f"a catenary arch needs {lo:g} <= rise/span <= {hi:g}, got rise = "
                         f"{rise:g} m for span = {span:g} m (rise/span = {r:.3g})")

    def g(la: float) -> float:  # a*(cosh(1/(2a)) - 1) - f/l, decreasing in la = log(a/l)
        a = math.exp(la)
        x = 0.5 / a
        return (700.0 - r) if x > 700 else a * (math.cosh(x) - 1.0) - r

    return span * math.exp(brentq(g, math.log(1e-4), math.log(1e6), xtol=1e-15, rtol=1e-15))


def _catenary_axis(span: float, rise: float) -> AxisFn:
    a = catenary_parameter(span, rise)

    def axis(t):
        xp = (t - 0.5) * span
        x = t * span
        y = rise + a - a * np.cosh(xp / a)
        return x, y, np.full_like(t, span), -span * np.sinh(xp / a)

    return axis


def _circular_axis(span: float, rise: float) -> AxisFn:
    if rise > 0.5 * span * (1 + 1e-12):
        raise ValueError(f"a circular arch needs rise <= span/2 (semicircle), got rise={rise:g} "
                         f"for span={span:g}")
    rise = min(rise, 0.5 * span)
    radius = (0.25 * span**2 + rise**2) / (2 * rise)
    half = math.asin(min(1.0, 0.5 * span / radius))
    if rise > radius:  # cannot happen for rise <= span/2
        half = math.pi - half
    yc = rise - radius

    def axis(t):
        th = math.pi / 2 + half - 2 * half * t  # from the left springing to the right one
        x = 0.5 * span + radius * np.cos(th)
        y = yc + radius * np.sin(th)
        return x, y, 2 * half * radius * np.sin(th), -2 * half * radius * np.cos(th)

    return axis


def _two_centred(span: float, xc: float, radius: float) -> AxisFn:
    """Two arcs of the given radius, centres (xc, 0) and (span - xc, 0), meeting on x = span/2."""
    th_top = math.acos((0.5 * span - xc) / radius)  # angle of the crown seen from the left centre

    def axis(t):
        t = np.asarray(t, dtype=float)
        left = t <= 0.5
        tt = np.where(left, 2 * t, 2 * (1 - t))  # 0 at the springing, 1 at the crown
        th = math.pi + (th_top - math.pi) * tt
        dth = 2 * (th_top - math.pi)
        xl = xc + radius * np.cos(th)
        y = radius * np.sin(th)
        dxl = -radius * np.sin(th) * dth
        dy = radius * np.cos(th) * dth
        return np.where(left, xl, span - xl), y, dxl, np.where(left, dy, -dy)

    return axis


def _pointed_centre(span: float, rise: float) -> float:
    xc = (0.25 * span**2 + rise**2) / span  # centre of the left arc, measured from x = 0
    if xc <= 0.5 * span * (1 + 1e-12):
        raise ValueError(f"a pointed (two-centred) arch needs rise > span/2, got rise={rise:g} "
                         f"for span={span:g} (use the circular shape)")
    return xc


def _elliptical_axis(span: float, rise: float) -> AxisFn:
    a = 0.5 * span

    def axis(t):
        th = math.pi * (1 - t)
        return (a + a * np.cos(th), rise * np.sin(th), math.pi * a * np.sin(th),
                -math.pi * rise * np.cos(th))

    return axis


def _polyline_axis(points: np.ndarray) -> AxisFn:
    seg = np.diff(points, axis=0)
    ln = np.hypot(seg[:, 0], seg[:, 1])
    s = np.concatenate([[0.0], np.cumsum(ln)])
    total = s[-1]
    u = seg / ln[:, None]
    vt = np.empty_like(points)  # vertex tangents: bisectors of the adjacent segments
    vt[0], vt[-1] = u[0], u[-1]
    mid = u[:-1] + u[1:]
    vt[1:-1] = mid / np.hypot(mid[:, 0], mid[:, 1])[:, None]
    sn = s / total

    def axis(t):
        t = np.asarray(t, dtype=float)
        x = np.interp(t, sn, points[:, 0])
        y = np.interp(t, sn, points[:, 1])
        tx = np.interp(t, sn, vt[:, 0])
        ty = np.interp(t, sn, vt[:, 1])
        nrm = np.hypot(tx, ty)
        return x, y, tx / nrm * total, ty / nrm * total

    return axis


def _segments_cross(p: np.ndarray) -> bool:
    """True if a polyline (M+1, 2) intersects itself (non-adjacent segments cross).

    Vectorised over all later segments for chunks of 256 segments (memory O(256 M)).
    """
    a, d = p[:-1], np.diff(p, axis=0)
    m = len(a)
    for i0 in range(0, max(m - 2, 0), 256):
        i = np.arange(i0, min(i0 + 256, m - 2))[:, None]
        j = np.arange(m)[None, :]
        pair = j >= i + 2
        r, s = d[i[:, 0]][:, None, :], d[None, :, :]
        qp = a[None, :, :] - a[i[:, 0]][:, None, :]
        den = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            tt = (qp[..., 0] * s[..., 1] - qp[..., 1] * s[..., 0]) / den
            uu = (qp[..., 0] * r[..., 1] - qp[..., 1] * r[..., 0]) / den
        hit = pair & (np.abs(den) > 1e-300) & (tt >= 0) & (tt <= 1) & (uu >= 0) & (uu <= 1)
        if np.any(hit):
            return True
    return False
