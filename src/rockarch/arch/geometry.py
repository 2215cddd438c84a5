"""Arch geometry: axis shapes, thickness, and the voussoir discretisation (physics note Sect. 4).

An :class:`Arch` is an axis running from the left springing (x = 0, y = 0) to the right springing
(x = span, y = 0) plus a thickness measured normal to the axis (uniform, or varying along the
arc), or an intrados/extrados pair. :func:`voussoirs` cuts it into N voussoirs with joints
normal to the axis and returns the mass, centroid and polar moment of each one.

Conventions: x to the right, y up; the axis is oriented from the left springing to the right
one, with unit tangent ``t`` and unit normal ``n = (-t_y, t_x)`` pointing to the extrados.
Everything is per unit depth with unit density (all results scale out).

Mass models (``Arch.mass_model``):

* ``"voussoir"`` (default): the true voussoir polygons with uniform density. With a uniform
  thickness normal to a curved axis the mass per unit arc length is exactly ``d`` but each
  centroid lies ``kappa*d**2/12`` outside the axis (kappa = axis curvature).
* ``"axis"``: the same mass (``d`` per unit arc length) lumped on the axis as a line mass. A
  uniform-thickness catenary then has its gravity thrust line exactly on the axis (Heyman's
  model of the semicircular arch, t/R = 0.106, uses this).
* ``"weights"``: a prescribed weight per unit *horizontal* length q(x), lumped on the axis
  (weighted catenaries, the replacement arch of paper Sect. 4/8).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import brentq

from rockarch._validate import finite_array, positive

SHAPES = ("catenary", "circular", "pointed", "elliptical")
MASS_MODELS = ("voussoir", "axis", "weights")
CONTINUOUS_BLOCKS = 2000  # voussoirs of the "continuous" (critical optimal) model
_DENSE = 8192  # samples of the parametric axis used to build the arc-length map
_MIN_SUB = 2000  # minimum number of sub-segments along the whole arch in a discretisation


# --------------------------------------------------------------------------------------------
# parametric axes: t in [0, 1] -> (x, y, dx/dt, dy/dt)
# --------------------------------------------------------------------------------------------
AxisFn = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]


def catenary_parameter(span: float, rise: float) -> float:
    """Return a with a*(cosh(span/(2a)) - 1) = rise: the catenary y = f + a - a*cosh(x'/a)."""
    span = positive("span", span)
    rise = positive("rise", rise)
    r = rise / span

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


# --------------------------------------------------------------------------------------------
# weights per unit horizontal length (histogram over x) for weighted catenaries
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class HorizontalWeights:
    """Weight per unit horizontal length as a histogram: ``q[j]`` on ``[edges[j], edges[j+1]]``.

    Used both to shape a weighted catenary (its axis is the funicular of these loads) and as
    the ``"weights"`` mass model of an arch. Unit density, per unit depth: the values are
    areas (m²/m) as for the voussoir model, so that arches of either model are comparable.
    """

    edges: np.ndarray
    q: np.ndarray

    def cumulative(self, x: np.ndarray) -> np.ndarray:
        """W(x) = integral of q from edges[0] to x (piecewise linear, exact)."""
        cw = np.concatenate([[0.0], np.cumsum(self.q * np.diff(self.edges))])
        return np.interp(x, self.edges, cw)

    def integral_of_cumulative(self, x: np.ndarray) -> np.ndarray:
        """IW(x) = integral of W from edges[0] to x (piecewise quadratic, exact)."""
        e, q = self.edges, self.q
        h = np.diff(e)
        cw = np.concatenate([[0.0], np.cumsum(q * h)])
        ciw = np.concatenate([[0.0], np.cumsum(cw[:-1] * h + 0.5 * q * h * h)])
        x = np.asarray(x, dtype=float)
        j = np.clip(np.searchsorted(e, x, side="right") - 1, 0, len(q) - 1)
        dx = x - e[j]
        return ciw[j] + cw[j] * dx + 0.5 * q[j] * dx * dx

    @property
    def total(self) -> float:
        return float(np.sum(self.q * np.diff(self.edges)))


def horizontal_weights(x, q=None, *, span: float | None = None, n: int = 4000
                       ) -> HorizontalWeights:
    """Build a :class:`HorizontalWeights` histogram (paper Sect. 4, weighted catenary loads).

    Parameters
    ----------
    x : callable or array
        Either a callable ``q(x)`` (weight per unit horizontal length, vectorised), sampled at
        ``n`` bin midpoints over ``[0, span]``; or the ``M + 1`` bin edges, with ``q`` the ``M``
        bin values; or, when ``q`` has the same length as ``x``, point samples of q(x)
        (interpolated to bins between consecutive samples).
    """
    if callable(x):
        span = positive("span", span)
        edges = np.linspace(0.0, span, int(n) + 1)
        vals = np.asarray(x(0.5 * (edges[:-1] + edges[1:])), dtype=float)
        vals = np.broadcast_to(vals, (len(edges) - 1,)).astype(float)
    else:
        edges = finite_array("weight x", x, min_len=2)
        vals = finite_array("weights", q, min_len=1)
        if len(vals) == len(edges):
            vals = 0.5 * (vals[:-1] + vals[1:])
        elif len(vals) != len(edges) - 1:
            raise ValueError("weights must have one value per bin (len(edges) - 1) or one per "
                             f"sample (len(x)), got {len(vals)} for {len(edges)} x values")
    if np.any(np.diff(edges) <= 0):
        raise ValueError("weight x positions must increase strictly")
    if np.any(vals < 0) or not np.any(vals > 0):
        raise ValueError("weights must be >= 0 and not all zero")
    if not np.all(np.isfinite(vals)):
        raise ValueError("weights contain a non-finite value")
    return HorizontalWeights(edges=edges, q=vals)


# --------------------------------------------------------------------------------------------
# the Arch
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Arch:
    """An arch: an axis from (0, 0) to (span, 0) and a thickness normal to it (Sect. 4).

    Build one with :func:`catenary`, :func:`weighted_catenary`, :func:`circular`,
    :func:`pointed`, :func:`elliptical`, :func:`polyline` or :func:`from_contour`.

    Attributes
    ----------
    shape : str
        Name of the axis shape.
    span, rise : float
        Span of the axis (springing to springing) and rise of the axis, m.
    thickness : float or callable
        Uniform thickness d (m), or ``d(sigma)`` with sigma in [0, 1] the normalised arc length.
    mass_model : str
        ``"voussoir"``, ``"axis"`` or ``"weights"`` (see the module docstring).
    weights : HorizontalWeights or None
        Weight per unit horizontal length for ``mass_model="weights"``.
    """

    shape: str
    span: float
    rise: float
    thickness: float | Callable[[np.ndarray], np.ndarray]
    axis_fn: AxisFn = field(repr=False)
    mass_model: str = "voussoir"
    weights: HorizontalWeights | None = field(default=None, repr=False)
    contour: tuple[AxisFn, AxisFn] | None = field(default=None, repr=False)
    _table: tuple = field(default=(), repr=False, compare=False)

    def __post_init__(self):
        if self.mass_model not in MASS_MODELS:
            raise ValueError(f"mass_model must be one of {', '.join(MASS_MODELS)}, "
                             f"got {self.mass_model!r}")
        if self.mass_model == "weights" and self.weights is None:
            raise ValueError("mass_model='weights' needs the weights (weight per unit "
                             "horizontal length)")
        if not self._table:
            t = np.linspace(0.0, 1.0, _DENSE + 1)
            x, y, _, _ = self.axis_fn(t)
            s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
            object.__setattr__(self, "_table", (t, s))
        if self.contour is None:
            _check_thickness(self)

    @property
    def length(self) -> float:
        """Arc length of the axis, m."""
        return float(self._table[1][-1])

    @property
    def uniform_thickness(self) -> float | None:
        """The thickness if it is uniform, else None."""
        if callable(self.thickness) or (self.contour is not None and self.shape != "pointed"):
            return None
        return float(self.thickness)

    def with_thickness(self, d: float) -> Arch:
        """The same axis with another uniform thickness."""
        if self.shape == "pointed":
            return pointed(self.span, self.rise, d, mass_model=self.mass_model)
        if self.contour is not None:
            raise ValueError("an arch given by its intrados/extrados has no adjustable "
                             "thickness")
        return replace(self, thickness=positive("thickness", d), _table=self._table)

    def with_mass_model(self, mass_model: str, weights: HorizontalWeights | None = None
                        ) -> Arch:
        """The same geometry with another mass model."""
        return replace(self, mass_model=mass_model, weights=weights or self.weights,
                       _table=self._table)

    def axis_at(self, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Axis points (k, 2), unit tangents (k, 2) and thickness (k,) at arc fractions sigma."""
        sigma = np.asarray(sigma, dtype=float)
        t_tab, s_tab = self._table
        t = np.interp(sigma * s_tab[-1], s_tab, t_tab)
        x, y, dx, dy = self.axis_fn(t)
        nrm = np.hypot(dx, dy)
        tan = np.stack([dx / nrm, dy / nrm], axis=-1)
        d = self.thickness(sigma) if callable(self.thickness) else np.full(sigma.shape,
                                                                            self.thickness)
        return np.stack([x, y], axis=-1), tan, np.asarray(d, dtype=float)

    def joints_at(self, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Intrados and extrados end points (k, 2) of the joints at arc fractions sigma."""
        if self.contour is not None:
            return _contour_points(self, sigma)
        p, tan, d = self.axis_at(sigma)
        n = np.stack([-tan[:, 1], tan[:, 0]], axis=-1)
        return p - 0.5 * d[:, None] * n, p + 0.5 * d[:, None] * n


def _contour_points(arch: Arch, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    out = []
    for fn in arch.contour:
        t = np.linspace(0.0, 1.0, _DENSE + 1)
        x, y, _, _ = fn(t)
        s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
        tt = np.interp(sigma * s[-1], s, t)
        xx, yy, _, _ = fn(tt)
        out.append(np.stack([xx, yy], axis=-1))
    return out[0], out[1]


def _check_thickness(arch: Arch) -> None:
    """Reject thicknesses the axis cannot hold: offset curves that fold (intrados radius <= 0)."""
    sig = np.linspace(0.0, 1.0, 4001)
    p, tan, d = arch.axis_at(sig)
    if np.any(~np.isfinite(d)) or np.any(d <= 0):
        raise ValueError("thickness must be a finite number > 0 everywhere along the axis")
    n = np.stack([-tan[:, 1], tan[:, 0]], axis=-1)
    for side in (-0.5, 0.5):
        c = p + side * d[:, None] * n
        seg = np.diff(c, axis=0)
        ahead = np.sum(seg * 0.5 * (tan[:-1] + tan[1:]), axis=1)
        if np.any(ahead <= 0):
            kappa = _max_curvature(p)
            raise ValueError(
                f"thickness {float(np.max(d)):g} m is too large for this axis: the "
                f"{'intrados' if side < 0 else 'extrados'} folds on itself (the thickness must "
                f"stay below 2 x the smallest radius of curvature, {2 / kappa:g} m)")


def _max_curvature(p: np.ndarray) -> float:
    d1 = np.gradient(p, axis=0)
    d2 = np.gradient(d1, axis=0)
    k = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(d1[:, 0], d1[:, 1]) ** 3
    return float(np.max(k))


def _thickness_arg(thickness) -> float | Callable:
    if callable(thickness):
        return thickness
    arr = np.asarray(thickness, dtype=float)
    if arr.ndim == 0:
        return positive("thickness", float(arr))
    vals = finite_array("thickness", arr, min_len=2)
    if np.any(vals <= 0):
        raise ValueError("thickness must be > 0 everywhere along the axis")
    grid = np.linspace(0.0, 1.0, len(vals))
    return lambda sigma: np.interp(sigma, grid, vals)


def catenary(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Catenary arch, mass uniform along the arc: y = f + a - a*cosh((x - l/2)/a) (Sect. 4)."""
    span, rise = positive("span", span), positive("rise", rise)
    return Arch("catenary", span, rise, _thickness_arg(thickness), _catenary_axis(span, rise),
                mass_model=mass_model)


def circular(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Circular (segmental up to semicircular) arch from span and rise of the axis (Sect. 8)."""
    span, rise = positive("span", span), positive("rise", rise)
    return Arch("circular", span, rise, _thickness_arg(thickness), _circular_axis(span, rise),
                mass_model=mass_model)


def pointed(span: float, rise: float, thickness: float, *, mass_model: str = "voussoir"
            ) -> Arch:
    """Pointed two-centred arch: both centres on the springing line, rise > span/2.

    Intrados and extrados are the concentric arcs of radius R -/+ d/2 meeting on the crown
    line, so the crown joint is vertical; joints join points at equal fractions of the
    intrados and extrados arc lengths (radial away from the crown, i.e. normal to the axis).
    """
    span, rise = positive("span", span), positive("rise", rise)
    d = positive("thickness", thickness)
    xc = _pointed_centre(span, rise)
    if d >= min(span, 2 * xc):
        raise ValueError(f"thickness {d:g} m is too large for this pointed arch (the intrados "
                         f"must still meet on the crown line: thickness < {min(span, 2 * xc):g} m)")
    return Arch("pointed", span, rise, d, _two_centred(span, xc, xc), mass_model=mass_model,
                contour=(_two_centred(span, xc, xc - 0.5 * d),
                         _two_centred(span, xc, xc + 0.5 * d)))


def elliptical(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Semi-elliptical arch: semi-axes span/2 (horizontal) and rise (vertical)."""
    span, rise = positive("span", span), positive("rise", rise)
    return Arch("elliptical", span, rise, _thickness_arg(thickness),
                _elliptical_axis(span, rise), mass_model=mass_model)


def make_arch(shape: str, span: float, rise: float, thickness, *,
              mass_model: str = "voussoir") -> Arch:
    """Build an arch of one of :data:`SHAPES` by name."""
    builders = {"catenary": catenary, "circular": circular, "pointed": pointed,
                "elliptical": elliptical}
    if shape not in builders:
        raise ValueError(f"shape must be one of {', '.join(SHAPES)}, got {shape!r}")
    return builders[shape](span, rise, thickness, mass_model=mass_model)


def _check_polyline(name: str, points) -> np.ndarray:
    pts = finite_array(name, points, ndim=2, min_len=2)
    if pts.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got {pts.shape}")
    seg = np.diff(pts, axis=0)
    if np.any(np.hypot(seg[:, 0], seg[:, 1]) <= 0):
        raise ValueError(f"{name} has repeated consecutive points")
    if _segments_cross(pts):
        raise ValueError(f"{name} intersects itself")
    return pts


def polyline(points, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Arch with an arbitrary polyline axis (points left to right, springings at both ends).

    The points are shifted so that the left springing is at (0, 0); both springings must be at
    the same level. Joints at the vertices bisect the adjacent segments.
    """
    pts = _check_polyline("axis polyline", points)
    pts = pts - pts[0]
    if pts[-1, 0] <= 0:
        raise ValueError("the axis polyline must run from the left springing to the right one")
    if abs(pts[-1, 1]) > 1e-9 * pts[-1, 0]:
        raise ValueError("both springings of the axis polyline must be at the same level")
    span, rise = float(pts[-1, 0]), float(np.max(pts[:, 1]))
    if rise <= 0:
        raise ValueError("the axis polyline must rise above its springings")
    return Arch("polyline", span, rise, _thickness_arg(thickness), _polyline_axis(pts),
                mass_model=mass_model)


def from_contour(intrados, extrados, *, mass_model: str = "voussoir") -> Arch:
    """Arch given by its intrados and extrados polylines (each left to right).

    Joint k joins the intrados and extrados points at the same fraction of their arc lengths;
    the axis is the line of the joints' midpoints. The springing line is that of the midpoint
    of the first joint.
    """
    ia = _check_polyline("intrados", intrados)
    ea = _check_polyline("extrados", extrados)
    origin = 0.5 * (ia[0] + ea[0])
    ia, ea = ia - origin, ea - origin
    fi, fe = _polyline_axis(ia), _polyline_axis(ea)
    t = np.linspace(0, 1, 2001)
    xi, yi, _, _ = fi(t)
    xe, ye, _, _ = fe(t)
    mid = np.stack([(xi + xe) / 2, (yi + ye) / 2], axis=-1)
    if np.any(np.hypot(xe - xi, ye - yi) <= 0):
        raise ValueError("intrados and extrados touch")
    return Arch("contour", float(mid[-1, 0]), float(np.max(mid[:, 1])),
                0.0, _polyline_axis(mid), mass_model=mass_model, contour=(fi, fe))


# --------------------------------------------------------------------------------------------
# weighted catenary
# --------------------------------------------------------------------------------------------
def _funicular_axis(span: float, rise: float, w: HorizontalWeights) -> AxisFn:
    """Axis y(x) with H*y'' = -q(x), y(0) = y(span) = 0, max y = rise (exact for histograms)."""
    c = float(w.integral_of_cumulative(np.array([span]))[0]) / span  # Y(l) = 0
    xs = np.linspace(0.0, span, 20001)
    ys = c * xs - w.integral_of_cumulative(xs)
    i = int(np.argmax(ys))
    # refine the crown: Y'(x) = c - W(x) = 0
    lo, hi = xs[max(i - 1, 0)], xs[min(i + 1, len(xs) - 1)]
    if c - w.cumulative(np.array([lo]))[0] > 0 > c - w.cumulative(np.array([hi]))[0]:
        xm = brentq(lambda x: c - float(w.cumulative(np.array([x]))[0]), lo, hi, xtol=1e-14)
    else:
        xm = xs[i]
    ymax = c * xm - float(w.integral_of_cumulative(np.array([xm]))[0])
    scale = rise / ymax

    def axis(t):
        x = np.asarray(t, dtype=float) * span
        y = scale * (c * x - w.integral_of_cumulative(x))
        dy = scale * (c - w.cumulative(x)) * span
        return x, y, np.full_like(x, span), dy

    return axis


def weighted_catenary(span: float, rise: float, thickness, *, weights=None,
                      weights_per_arc: Callable[[np.ndarray], np.ndarray] | None = None,
                      tol: float = 1e-12, max_iter: int = 200, n: int = 4000) -> Arch:
    """Weighted catenary: the axis is the gravity thrust line of a given mass (paper Sect. 4).

    Give exactly one of

    * ``weights``: weight per unit horizontal length, as a :class:`HorizontalWeights`, a
      callable q(x) on [0, span], or ``(x, q)`` arrays (see :func:`horizontal_weights`); e.g.
      the mass distribution of another arch from :func:`mass_per_horizontal_length`. The axis
      is then found directly (H*y'' = -q).
    * ``weights_per_arc``: weight per unit arc length mu(sigma), sigma the normalised arc
      length of the *new* axis. The axis depends on its own arc length: fixed point
      geometry -> q(x) = mu*ds/dx -> axis, iterated until the axis moves less than tol*span.
      ``mu = const`` gives the ordinary catenary.

    The arch gets ``mass_model="weights"`` with those loads on the axis, so its gravity thrust
    line lies on the axis; the thickness only sets the contour (where the hinges form).
    """
    span, rise = positive("span", span), positive("rise", rise)
    if (weights is None) == (weights_per_arc is None):
        raise ValueError("give exactly one of weights (per horizontal length) and "
                         "weights_per_arc")
    if weights is not None:
        if isinstance(weights, HorizontalWeights):
            w = weights
        elif callable(weights):
            w = horizontal_weights(weights, span=span, n=n)
        else:
            w = horizontal_weights(*weights)
        if abs(w.edges[0]) > 1e-9 * span or abs(w.edges[-1] - span) > 1e-9 * span:
            raise ValueError(f"weights must cover [0, span] = [0, {span:g}], got "
                             f"[{w.edges[0]:g}, {w.edges[-1]:g}]")
    else:
        edges = np.linspace(0.0, span, n + 1)
        xm = 0.5 * (edges[:-1] + edges[1:])
        y = 4 * rise * xm * (span - xm) / span**2  # parabola as first guess
        w = None
        for _ in range(max_iter):
            if w is None:
                ax = lambda t: (t * span, 4 * rise * t * (1 - t),  # noqa: E731
                                np.full_like(t, span), 4 * rise * (1 - 2 * t))
            else:
                ax = _funicular_axis(span, rise, w)
            xe, ye, _, _ = ax(edges / span)
            ds = np.hypot(np.diff(xe), np.diff(ye))
            sig = np.concatenate([[0.0], np.cumsum(ds)])
            sig /= sig[-1]
            mu = np.asarray(weights_per_arc(0.5 * (sig[:-1] + sig[1:])), dtype=float)
            mu = np.broadcast_to(mu, ds.shape)
            if np.any(~np.isfinite(mu)) or np.any(mu < 0) or not np.any(mu > 0):
                raise ValueError("weights_per_arc must be finite, >= 0 and not all zero")
            w = HorizontalWeights(edges=edges, q=mu * ds / np.diff(edges))
            _, ynew, _, _ = _funicular_axis(span, rise, w)(xm / span)
            step = float(np.max(np.abs(ynew - y)))
            y = ynew
            if step < tol * span:
                break
        else:
            raise ValueError(f"weighted catenary fixed point did not converge in {max_iter} "
                             "iterations")
    return Arch("weighted catenary", span, rise, _thickness_arg(thickness),
                _funicular_axis(span, rise, w), mass_model="weights", weights=w)


def mass_per_horizontal_length(arch: Arch, n: int = 4000) -> HorizontalWeights:
    """The arch's mass (unit density) per unit horizontal length, as a histogram over x.

    Each of ``n`` fine voussoirs spreads its mass uniformly over the x-range of its axis chord.
    Pass the result as ``weights=`` to :func:`weighted_catenary` for a replacement arch with
    the same mass distribution (paper Sect. 4 and 8).
    """
    v = voussoirs(arch, n)
    x = v.points[:, 0]
    order_ok = np.all(np.diff(x) > 0)
    if not order_ok:
        raise ValueError("the arch axis is not a function of x (it turns back): no weight per "
                         "horizontal length")
    return HorizontalWeights(edges=x - x[0], q=v.mass / np.diff(x))


# --------------------------------------------------------------------------------------------
# voussoirs
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Voussoirs:
    """An arch cut into N voussoirs by N + 1 joints normal to the axis (physics note Sect. 4).

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


def _polygon_props(v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
    Mass, centroid and polar moment follow ``arch.mass_model`` (module docstring, Sect. 4).
    """
    try:
        n = int(n)
    except (TypeError, ValueError):
        raise ValueError(f"number of voussoirs must be an integer, got {n!r}") from None
    if n < 4:
        raise ValueError(f"at least 4 voussoirs are needed for a four-hinge mechanism, got {n}")
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
    area, cen, jp = _polygon_props(poly)
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
