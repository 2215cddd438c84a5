"""Replacement catenary arch of an arbitrary arch (paper Sect. 4, 8; physics note section 7).

The replacement is a *weighted catenary*: its axis is the gravity thrust line of the original
arch's own mass distribution (mass per unit horizontal length, carried on the axis), drawn
between the original axis' springing points. Two uniform thicknesses are defined:

* **lower bound** d̄: the largest uniform thickness whose contour (axis ± d/2 along the
  normal) fits inside the original arch's contour; the rise of the replacement axis is the
  one that maximises it;
* **equivalent** d̂: on the same axis, the thickness whose limit acceleration ap,min equals
  the original arch's.

For each, the critical optimal four-hinge mechanism gives p, ap,min, delta and the constants
c1, c2 of Eq. 14, and the equivalent slender block has R = 0.75·g/p² (Eq. 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar
from scipy.spatial import cKDTree

from rockarch._validate import positive
from rockarch.arch.cutting import voussoirs
from rockarch.arch.fourhinge import ArchMechanism, analyse
from rockarch.arch.funicular import mass_per_horizontal_length, weighted_catenary
from rockarch.arch.geometry import CONTINUOUS_BLOCKS, Arch
from rockarch.arch.thrust import limit_analysis
from rockarch.arch.weights import HorizontalWeights
from rockarch.constants import G

RULES = ("lower-bound", "equivalent")
_AXIS_SAMPLES = 801


@dataclass(frozen=True)
class ReplacementArch:
    """A replacement catenary arch and its dynamic parameters (paper Table 2).

    Attributes
    ----------
    rule : "lower-bound" or "equivalent".
    arch : the weighted catenary (span and springings of the original axis).
    thickness, rise : its uniform thickness and axis rise [m].
    mechanism : its critical optimal four-hinge mechanism (p, ap_min, delta, c1..c4).
    """

    rule: str
    arch: Arch
    thickness: float
    rise: float
    mechanism: ArchMechanism

    @property
    def p(self) -> float:
        return self.mechanism.p

    @property
    def ap_min(self) -> float:
        return self.mechanism.ap_min

    @property
    def R_block(self) -> float:  # noqa: N802 - the field's name
        """Half-diagonal of the equivalent slender block, R = 0.75·g/p² (Eq. 1) [m]."""
        return 0.75 * self.mechanism.thrust.g / self.p**2

    def to_dict(self) -> dict:
        m = self.mechanism
        return {"rule": self.rule, "thickness": self.thickness, "rise": self.rise,
                "span": self.arch.span, "p": m.p, "ap_min": m.ap_min, "delta": m.delta,
                "c1": m.c1, "c2": m.c2, "R_block": self.R_block}


def _inscribed_half_thickness(axis_arch: Arch, tree_in: cKDTree, tree_ex: cKDTree,
                              sign_fn) -> float:
    """Smallest distance from the axis to the original intrados/extrados (negative if the
    axis leaves the original contour)."""
    sig = np.linspace(0.0, 1.0, _AXIS_SAMPLES)
    pts, _, _ = axis_arch.axis_at(sig)
    di, _ = tree_in.query(pts)
    de, _ = tree_ex.query(pts)
    h = float(min(di.min(), de.min()))
    return h if sign_fn(pts) else -h


def _contour_trees(original: Arch):
    v = voussoirs(original, CONTINUOUS_BLOCKS)

    def dense(curve: np.ndarray, k: int = 8) -> np.ndarray:
        seg = np.diff(curve, axis=0)
        t = np.linspace(0.0, 1.0, k, endpoint=False)
        pts = (curve[:-1, None, :] + t[None, :, None] * seg[:, None, :]).reshape(-1, 2)
        return np.vstack([pts, curve[-1]])

    # inside test: the axis point lies on the extrados side of the intrados and vice versa,
    # judged at the nearest joint (joints are normal to the original axis)
    tree_axis = cKDTree(v.points)
    normal = np.column_stack([-v.tangent[:, 1], v.tangent[:, 0]])

    def inside(pts: np.ndarray) -> bool:
        _, k = tree_axis.query(pts)
        off = np.einsum("ij,ij->i", pts - v.points[k], normal[k])
        return bool(np.all(np.abs(off) <= 0.5 * v.thickness[k] * (1 + 1e-12)))

    return cKDTree(dense(v.intrados)), cKDTree(dense(v.extrados)), inside


def lower_bound_axis(original: Arch, weights: HorizontalWeights | None = None
                     ) -> tuple[float, float]:
    """(rise, d̄): the weighted-catenary axis rise maximising the inscribed uniform thickness.

    The axis runs between the original axis' springings and carries ``weights`` (default:
    the original's mass per horizontal length). Raises ValueError if no such axis fits.
    """
    w = weights if weights is not None else mass_per_horizontal_length(original)
    tree_in, tree_ex, inside = _contour_trees(original)
    span = original.span

    def half(rise: float) -> float:
        a = weighted_catenary(span, rise, 0.01 * span, weights=w)
        return _inscribed_half_thickness(a, tree_in, tree_ex, inside)

    f0 = original.rise
    grid = np.linspace(0.7 * f0, 1.3 * f0, 13)
    vals = np.array([half(f) for f in grid])
    k = int(np.argmax(vals))
    if vals[k] <= 0:
        raise ValueError("no weighted catenary with the arch's own mass distribution fits "
                         "inside its contour between its springings")
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    res = minimize_scalar(lambda f: -half(f), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-6 * f0})
    rise = float(res.x) if -res.fun >= vals[k] else float(grid[k])
    return rise, 2.0 * max(-float(res.fun), float(vals[k]))


def equivalent_thickness(axis_arch: Arch, ap_min: float, *, g: float = G,
                         d_lo: float | None = None) -> float:
    """Thickness d̂ on the given axis whose ap,min equals ``ap_min`` (brentq on the LP)."""
    target = positive("ap_min", ap_min)
    span = axis_arch.span

    def f(d: float) -> float:
        return limit_analysis(axis_arch.with_thickness(d), g=g).ap_min - target

    lo = d_lo if d_lo is not None else 1e-3 * span
    hi = max(2 * lo, 0.02 * span)
    while f(hi) < 0:
        lo, hi = hi, 1.6 * hi
        if hi > 0.5 * span:
            raise ValueError(f"no thickness up to {hi:.3g} m reaches ap,min = {target:.4g} "
                             "m/s² on the replacement axis")
    while f(lo) > 0:
        lo *= 0.5
        if lo < 1e-6 * span:
            raise ValueError("the replacement axis reaches the target ap,min at vanishing "
                             "thickness")
    return float(brentq(f, lo, hi, xtol=1e-7 * span, rtol=1e-10))


@dataclass(frozen=True)
class Replacement:
    """Both replacement catenary arches of an arch (paper Sect. 8, Table 2)."""

    original: ArchMechanism
    lower_bound: ReplacementArch
    equivalent: ReplacementArch

    def by_rule(self, rule: str) -> ReplacementArch:
        if rule not in RULES:
            raise ValueError(f"thickness rule must be one of {', '.join(RULES)}, got {rule!r}")
        return self.lower_bound if rule == "lower-bound" else self.equivalent


def replacement(original: Arch, *, g: float = G, rise: float | None = None) -> Replacement:
    """Replacement catenary arches of ``original`` (lower-bound and equivalent thickness).

    ``rise`` fixes the replacement axis' rise instead of fitting it (e.g. to follow a
    published geometry); the lower-bound thickness is then the largest that fits on it.
    """
    g = positive("g", g)
    orig = analyse(original, g=g)
    w = mass_per_horizontal_length(original)
    if rise is None:
        rise, d_lb = lower_bound_axis(original, w)
    else:
        rise = positive("rise", rise)
        tree_in, tree_ex, inside = _contour_trees(original)
        d_lb = 2.0 * _inscribed_half_thickness(
            weighted_catenary(original.span, rise, 0.01 * original.span, weights=w),
            tree_in, tree_ex, inside)
        if d_lb <= 0:
            raise ValueError(f"the weighted catenary of rise {rise:g} m leaves the arch")
    axis = weighted_catenary(original.span, rise, d_lb, weights=w)
    lb = ReplacementArch("lower-bound", axis, d_lb, rise, analyse(axis, g=g))
    d_eq = equivalent_thickness(axis, orig.ap_min, g=g, d_lo=0.5 * d_lb)
    eq_arch = axis.with_thickness(d_eq)
    eq = ReplacementArch("equivalent", eq_arch, d_eq, rise, analyse(eq_arch, g=g))
    if not math.isfinite(eq.p):
        raise ValueError("the equivalent replacement arch has no four-hinge mechanism")
    return Replacement(orig, lb, eq)
