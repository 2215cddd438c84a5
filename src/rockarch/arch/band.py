"""The thickest catenary band inside an arch, springings free on its springing joints.

docs/theory.md Eqs. (7.3)–(7.6), paper Sects. 4 and 8. The axis family is

    y(x) = y0 − a·(cosh((x − x_m)/a) − 1)                       ("catenary", Eq. 7.3)
    y(x) = y0 − [IW(x) − IW(x_m) − W(x_m)·(x − x_m)] / (a·q̄)    ("weighted", Eq. 7.4)

(W, IW: the first and second integrals of the original's mass per horizontal length q,
q̄ its mean). The springing points P_L, P_R are where the axis crosses the original's
springing joints (intrados to extrados); the clearance h is the smallest distance from the
axis between them to the intrados and extrados polylines, negative where the axis leaves
the contour (Eq. 7.5); the band thickness is d̄ = 2·max h (Eq. 7.6, Nelder–Mead over
(y0, a) for a mirror-symmetric arch, over (y0, a, x_m) otherwise).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize
from scipy.spatial import cKDTree

from rockarch.arch.funicular import mass_per_horizontal_length
from rockarch.arch.geometry import Arch
from rockarch.arch.shapes import catenary_parameter
from rockarch.arch.weights import HorizontalWeights

AXES = ("catenary", "weighted")
_CONTOUR_SAMPLES = 4001  # joints along the original (polyline sagitta ~ 1e-7 l)
_AXIS_SAMPLES = 401  # axis points where the clearance is taken while optimising
_AXIS_SAMPLES_FINAL = 4001  # ... and for the reported thickness


@dataclass(frozen=True)
class Band:
    """The lower-bound catenary band of an arch (docs/theory.md Eqs. 7.3–7.6).

    Attributes
    ----------
    axis : "catenary" or "weighted" (the axis family).
    y0, a, x_m : crown height, parameter (m) and crown abscissa of the axis, in the
        original's coordinates (its left axis springing at (0, 0)).
    left, right : (2,) springing points P_L, P_R on the original's springing joints.
    thickness : d̄ = 2·max h [m].
    symmetric : True if the original is mirror-symmetric (x_m fixed at mid-span).
    weights : the original's mass per horizontal length (the weighted family's loads).
    """

    axis: str
    y0: float
    a: float
    x_m: float
    left: np.ndarray
    right: np.ndarray
    thickness: float
    symmetric: bool
    weights: HorizontalWeights

    @property
    def span(self) -> float:
        """l′ = x_R − x_L [m]."""
        return float(self.right[0] - self.left[0])

    @property
    def rise(self) -> float:
        """f′: crown height above the mean springing level [m]."""
        return float(self.y0 - 0.5 * (self.left[1] + self.right[1]))

    def y(self, x: np.ndarray) -> np.ndarray:
        """Axis height at x (original's coordinates)."""
        return _family(self.axis, self.weights)(np.asarray(x, dtype=float), self.y0, self.a,
                                                self.x_m)

    def dy(self, x: np.ndarray) -> np.ndarray:
        """Axis slope dy/dx at x."""
        x = np.asarray(x, dtype=float)
        if self.axis == "catenary":
            return -np.sinh((x - self.x_m) / self.a)
        w = self.weights
        qbar = w.total / (w.edges[-1] - w.edges[0])
        wm = float(w.cumulative(np.array([self.x_m]))[0])
        return -(w.cumulative(x) - wm) / (self.a * qbar)


def _family(axis: str, w: HorizontalWeights):
    if axis == "catenary":
        return lambda x, y0, a, xm: y0 - a * (np.cosh((x - xm) / a) - 1.0)
    e, q = w.edges, w.q
    h = np.diff(e)
    cw = np.concatenate([[0.0], np.cumsum(q * h)])
    ciw = np.concatenate([[0.0], np.cumsum(cw[:-1] * h + 0.5 * q * h * h)])
    qbar = w.total / (e[-1] - e[0])

    def iw(x):  # HorizontalWeights.integral_of_cumulative with the sums kept
        j = np.clip(np.searchsorted(e, x, side="right") - 1, 0, len(q) - 1)
        dx = x - e[j]
        return ciw[j] + cw[j] * dx + 0.5 * q[j] * dx * dx

    def y(x, y0, a, xm):
        w_m = float(np.interp(xm, e, cw))
        return y0 - (iw(x) - iw(xm) - w_m * (x - xm)) / (a * qbar)

    return y


def _tree(points: np.ndarray) -> cKDTree:
    """A k-d tree of a dense polyline's vertices. Its queries are exact whatever its build;
    this one (larger leaves, neither balanced nor compacted) answers the band's queries (401
    axis points at some distance from 4001 vertices) in 0.8-0.9 ms, scipy's default in 1.7."""
    return cKDTree(points, leafsize=64, compact_nodes=False, balanced_tree=False)


def _polyline_distance(tree: cKDTree, line: np.ndarray, pts: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Distance from pts to the polyline ``line`` (and the nearest vertex index)."""
    _, k = tree.query(pts)
    best = np.full(len(pts), np.inf)
    for a_idx in (np.maximum(k - 1, 0), np.minimum(k, len(line) - 2)):
        a, b = line[a_idx], line[a_idx + 1]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", pts - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
        d = np.hypot(*(pts - a - t[:, None] * ab).T)
        best = np.minimum(best, d)
    return best, k


class _Contour:
    """The original's intrados/extrados polylines, springing joints and inside test."""

    def __init__(self, arch: Arch):
        sig = np.linspace(0.0, 1.0, _CONTOUR_SAMPLES)
        self.intrados, self.extrados = arch.joints_at(sig)
        self.tree_in = _tree(self.intrados)
        self.tree_ex = _tree(self.extrados)
        mid = 0.5 * (self.intrados + self.extrados)
        dvec = self.extrados - self.intrados
        self.half = 0.5 * np.hypot(dvec[:, 0], dvec[:, 1])
        self.normal = dvec / (2 * self.half[:, None])
        self.mid = mid
        self.scale = float(np.max(self.half))
        mirrored = np.column_stack([arch.span - self.intrados[::-1, 0],
                                    self.intrados[::-1, 1]])
        self.symmetric = bool(np.max(np.abs(mirrored - self.intrados)) < 1e-9 * arch.span)

    def signed_clearance(self, pts: np.ndarray) -> float:
        """min over pts of the distance to the contour, negative outside it (Eq. 7.5).

        Exact point-to-polyline distances (the two segments at the nearest vertex); the
        inside test is the offset along the nearest joint.
        """
        di, ki = _polyline_distance(self.tree_in, self.intrados, pts)
        de, ke = _polyline_distance(self.tree_ex, self.extrados, pts)
        k = np.where(di <= de, ki, ke)
        off = np.einsum("ij,ij->i", pts - self.mid[k], self.normal[k])
        inside = np.abs(off) <= self.half[k]
        dist = np.minimum(di, de)
        return float(np.min(np.where(inside, dist, -dist)))

    def springing(self, end: int, yfun) -> tuple[np.ndarray, float]:
        """Crossing of the axis with the springing joint ``end`` (0 or -1) and a penalty.

        The crossing is sought on the joint's line; the penalty is 0 on the segment and minus
        the distance beyond its end point otherwise (a continuous guide for the optimiser).
        """
        p, q = self.intrados[end], self.extrados[end]

        def f(s: float) -> float:
            x = p[0] + s * (q[0] - p[0])
            return float(p[1] + s * (q[1] - p[1]) - yfun(np.array([x]))[0])

        grid = np.linspace(-3.0, 4.0, 29)
        gx = p[0] + grid * (q[0] - p[0])
        vals = p[1] + grid * (q[1] - p[1]) - yfun(gx)
        change = np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))
        if len(change) == 0:
            return p, -math.inf
        # the crossing nearest to the segment's middle
        j = change[np.argmin(np.abs(grid[change] + 0.125 - 0.5))]
        s = brentq(f, grid[j], grid[j + 1], xtol=1e-14)
        pt = p + s * (q - p)
        ln = float(np.hypot(*(q - p)))
        return pt, -ln * max(0.0, -s, s - 1.0)


def _evaluate(contour: _Contour, yfun, params, samples: int = _AXIS_SAMPLES
              ) -> tuple[float, np.ndarray, np.ndarray]:
    y0, a, xm = params
    if not a > 0:
        return -10.0 * contour.scale, contour.intrados[0], contour.intrados[-1]

    def yx(x):
        return yfun(x, y0, a, xm)

    left, pen_l = contour.springing(0, yx)
    right, pen_r = contour.springing(-1, yx)
    if not (math.isfinite(pen_l) and math.isfinite(pen_r)) or right[0] <= left[0]:
        return -10.0 * contour.scale, left, right
    x = np.linspace(left[0], right[0], samples)
    h = contour.signed_clearance(np.column_stack([x, yx(x)]))
    return min(h, h + pen_l + pen_r), left, right


def _start(arch: Arch, axis: str, yfun) -> tuple[float, float]:
    """(y0, a) of the family's axis through both springings with the arch's rise."""
    span, rise = arch.span, arch.rise
    xm = 0.5 * span
    if axis == "catenary":
        return rise, catenary_parameter(span, rise)
    return rise, float(rise - yfun(np.array([0.0]), rise, 1.0, xm)[0]) / rise


def lower_bound_band(original: Arch, *, axis: str = "catenary",
                     weights: HorizontalWeights | None = None) -> Band:
    """The thickest uniform catenary band inside ``original`` (docs/theory.md Eq. 7.6).

    Parameters
    ----------
    original : the arch to replace.
    axis : "catenary" (uniform mass, Eq. 7.3) or "weighted" (the funicular of the original's
        mass per horizontal length, Eq. 7.4).
    weights : the original's mass per horizontal length (computed when None).

    Raises
    ------
    ValueError
        If no axis of the family fits inside the contour with both springings on the
        springing joints (the arch is too thin or too far from a catenary).
    """
    if axis not in AXES:
        raise ValueError(f"replacement axis must be one of {', '.join(AXES)}, got {axis!r}")
    w = weights if weights is not None else mass_per_horizontal_length(original)
    contour = _Contour(original)
    yfun = _family(axis, w)
    y00, a0 = _start(original, axis, yfun)
    d0 = 2 * contour.scale
    xm0 = 0.5 * (contour.mid[0, 0] + contour.mid[-1, 0])
    # coarse grid for a start inside the contour, then Nelder–Mead on the clearance
    best = (-math.inf, (y00, a0, xm0))
    for y0 in y00 + d0 * np.linspace(-0.5, 1.0, 7):
        for a in a0 * np.linspace(0.8, 1.25, 7):
            h = _evaluate(contour, yfun, (y0, a, xm0))[0]
            if h > best[0]:
                best = (h, (y0, a, xm0))
    h0, (y0s, as_, _) = best
    if contour.symmetric:
        obj = lambda z: -_evaluate(contour, yfun, (z[0], z[1], xm0))[0]  # noqa: E731
        z0, simplex_steps = [y0s, as_], [0.1 * d0, 0.02 * as_]
    else:
        obj = lambda z: -_evaluate(contour, yfun, tuple(z))[0]  # noqa: E731
        z0, simplex_steps = [y0s, as_, xm0], [0.1 * d0, 0.02 * as_, 0.01 * original.span]
    simplex = np.array([z0] + [np.array(z0) + np.eye(len(z0))[k] * simplex_steps[k]
                               for k in range(len(z0))])
    res = minimize(obj, z0, method="Nelder-Mead",
                   options={"initial_simplex": simplex, "xatol": 1e-7 * original.span,
                            "fatol": 1e-9 * original.span, "maxiter": 4000})
    z = res.x if -res.fun >= h0 else np.array(z0)
    params = (z[0], z[1], xm0 if contour.symmetric else z[2])
    h, left, right = _evaluate(contour, yfun, params, _AXIS_SAMPLES_FINAL)
    if h <= 0:
        raise ValueError(
            f"no {axis} band fits inside this arch with its springings on the springing "
            f"joints: the best {axis} axis leaves the contour by {-h:.3g} m (the arch is too "
            "thin, or too far from a catenary, to contain a replacement catenary)")
    return Band(axis=axis, y0=float(params[0]), a=float(params[1]), x_m=float(params[2]),
                left=left, right=right, thickness=2.0 * h, symmetric=contour.symmetric,
                weights=w)
