"""Arch geometry: an axis, a thickness normal to it, a mass model (docs/theory.md Sect. 4).

An :class:`Arch` is an axis running from the left springing (x = 0, y = 0) to the right springing
(x = span, y = 0) plus a thickness measured normal to the axis (uniform, or varying along the
arc), or an intrados/extrados pair. :func:`rockarch.arch.cutting.voussoirs` cuts it into N
voussoirs; the axis shapes live in :mod:`rockarch.arch.shapes`, the weighted catenary in
:mod:`rockarch.arch.funicular`.

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

import importlib
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from rockarch.arch.shapes import (
    SHAPES,
    AxisFn,
    _catenary_axis,
    _circular_axis,
    _elliptical_axis,
    _pointed_centre,
    _polyline_axis,
    _segments_cross,
    _two_centred,
)
from rockarch.arch.weights import HorizontalWeights
from rockarch.core.validate import finite_array, number, positive

__all__ = ["CONTINUOUS_BLOCKS", "MASS_MODELS", "SHAPES", "Arch", "catenary", "circular",
           "elliptical", "from_contour", "make_arch", "pointed", "polyline"]

#: Names that lived in this module before it was split: still importable from here.
_MOVED = {"voussoirs": "cutting", "Voussoirs": "cutting", "polygons_props": "cutting",
          "weighted_catenary": "funicular", "mass_per_horizontal_length": "funicular",
          "horizontal_weights": "weights", "catenary_parameter": "shapes"}


def __getattr__(name: str):
    if name in _MOVED:
        return getattr(importlib.import_module(f"rockarch.arch.{_MOVED[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


MASS_MODELS = ("voussoir", "axis", "weights")
CONTINUOUS_BLOCKS = 2000  # voussoirs of the "continuous" (critical optimal) model
_DENSE = 8192  # samples of the parametric axis used to build the arc-length map


@dataclass(frozen=True)
class Arch:
    """An arch: an axis from (0, 0) to (span, 0) and a thickness normal to it (docs/theory.md §4).

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


#: Spans an arch may have [m] (sizes beyond overflow the masses and the LP's scaling).
SPAN_RANGE = (1e-3, 1e5)
#: Rise over span of an arch axis (flatter: a beam; higher: a tower).
RISE_OVER_SPAN = (1e-3, 10.0)
#: Smallest thickness over span (the minimum-thickness search starts there).
MIN_THICKNESS_OVER_SPAN = 1e-6


def _span_rise(span, rise) -> tuple[float, float]:
    """span and rise [m] within :data:`SPAN_RANGE` and :data:`RISE_OVER_SPAN`."""
    span, rise = positive("span", span), positive("rise", rise)
    lo, hi = SPAN_RANGE
    if not lo <= span <= hi:
        raise ValueError(f"span must lie in [{lo:g}, {hi:g}] m, got {span:g} m")
    lo, hi = RISE_OVER_SPAN
    if not lo <= rise / span <= hi:
        raise ValueError(f"rise/span must lie in [{lo:g}, {hi:g}], got rise = {rise:g} m for "
                         f"span = {span:g} m (rise/span = {rise / span:.3g})")
    return span, rise


def _thickness_arg(thickness, span: float | None = None) -> float | Callable:
    if callable(thickness):
        return thickness
    if isinstance(thickness, (bool, np.bool_, str, bytes)) or thickness is None:
        number("thickness", thickness)  # the TypeError naming it
    arr = np.asarray(thickness, dtype=float)
    if arr.ndim == 0:
        d = positive("thickness", float(arr))
        if span is not None and d < MIN_THICKNESS_OVER_SPAN * span:
            raise ValueError(f"thickness must be at least {MIN_THICKNESS_OVER_SPAN:g} x span "
                             f"= {MIN_THICKNESS_OVER_SPAN * span:.3g} m, got {d:g} m")
        return d
    vals = finite_array("thickness", arr, min_len=2)
    if np.any(vals <= 0):
        raise ValueError("thickness must be > 0 everywhere along the axis")
    grid = np.linspace(0.0, 1.0, len(vals))
    return lambda sigma: np.interp(sigma, grid, vals)


def catenary(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Catenary arch, mass uniform along the arc: y = f + a - a*cosh((x - l/2)/a) (Eq. (4.4))."""
    span, rise = _span_rise(span, rise)
    return Arch("catenary", span, rise, _thickness_arg(thickness, span),
                _catenary_axis(span, rise),
                mass_model=mass_model)


def circular(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Circular (segmental up to semicircular) arch from span and rise of the axis.

    The arch of the paper's Sect. 8 is one.
    """
    span, rise = _span_rise(span, rise)
    return Arch("circular", span, rise, _thickness_arg(thickness, span),
                _circular_axis(span, rise),
                mass_model=mass_model)


def pointed(span: float, rise: float, thickness: float, *, mass_model: str = "voussoir"
            ) -> Arch:
    """Pointed two-centred arch: both centres on the springing line, rise > span/2.

    Intrados and extrados are the concentric arcs of radius R -/+ d/2 meeting on the crown
    line, so the crown joint is vertical; joints join points at equal fractions of the
    intrados and extrados arc lengths (radial away from the crown, i.e. normal to the axis).
    """
    span, rise = _span_rise(span, rise)
    d = _thickness_arg(thickness, span)
    if not isinstance(d, float):
        raise TypeError("a pointed arch takes one uniform thickness (a number)")
    xc = _pointed_centre(span, rise)
    if d >= min(span, 2 * xc):
        raise ValueError(f"thickness {d:g} m is too large for this pointed arch (the intrados "
                         f"must still meet on the crown line: thickness < {min(span, 2 * xc):g} m)")
    return Arch("pointed", span, rise, d, _two_centred(span, xc, xc), mass_model=mass_model,
                contour=(_two_centred(span, xc, xc - 0.5 * d),
                         _two_centred(span, xc, xc + 0.5 * d)))


def elliptical(span: float, rise: float, thickness, *, mass_model: str = "voussoir") -> Arch:
    """Semi-elliptical arch: semi-axes span/2 (horizontal) and rise (vertical)."""
    span, rise = _span_rise(span, rise)
    return Arch("elliptical", span, rise, _thickness_arg(thickness, span),
                _elliptical_axis(span, rise), mass_model=mass_model)


#: Spans above this [m] are read as a units mistake and warned about (the longest masonry
#: arches span about 120 m).
PLAUSIBLE_SPAN = 300.0


def make_arch(shape: str, span: float, rise: float, thickness, *,
              mass_model: str = "voussoir") -> Arch:
    """Build an arch of one of :data:`SHAPES` by name, from the span and rise of its axis.

    The arch for :func:`rockarch.system` ``("fourhinge"|"mdof", ...)`` and the arch
    functions (limit analysis, replacement catenary, design); geometry in docs/theory.md §4
    and docs/arch.md.

    Parameters
    ----------
    shape : str
        ``"catenary"`` (:func:`catenary`), ``"circular"`` (segmental up to semicircular,
        :func:`circular`), ``"pointed"`` (two-centred, rise > span/2, :func:`pointed`) or
        ``"elliptical"`` (semi-elliptical, :func:`elliptical`).
    span : float
        Span of the axis, springing to springing [m].
    rise : float
        Rise of the axis above the springings [m]; rise/span within
        :data:`RISE_OVER_SPAN` and the shape's own limits.
    thickness : float, array-like or callable
        Thickness normal to the axis [m]: a number (uniform), values spaced evenly along
        the axis from springing to springing, or a function of the normalised arc length
        sigma in [0, 1] (a pointed arch takes a number only).
    mass_model : str
        ``"voussoir"`` (default: the true voussoir polygons, uniform density) or ``"axis"``
        (the same mass lumped on the axis as a line mass); see
        :mod:`rockarch.arch.geometry`. (``"weights"`` needs weights: use
        :func:`rockarch.arch.funicular.weighted_catenary`.)

    Returns
    -------
    Arch
        Axis from (0, 0) to (span, 0), thickness, mass model.

    Raises
    ------
    TypeError
        If ``shape`` is not a string, or a number is of the wrong type.
    ValueError
        If ``shape`` is not one of :data:`SHAPES`, span, rise or thickness is out of range,
        or the thickness does not fit the shape.

    Warns
    -----
    UnitsWarning
        If the span exceeds :data:`PLAUSIBLE_SPAN` (sizes in millimetres?).

    Examples
    --------
    >>> import rockarch as ra
    >>> arch = ra.make_arch("circular", span=10.0, rise=2.89, thickness=0.35)
    >>> arch.shape, arch.span, arch.uniform_thickness
    ('circular', 10.0, 0.35)
    """
    builders = {"catenary": catenary, "circular": circular, "pointed": pointed,
                "elliptical": elliptical}
    if not isinstance(shape, str):
        raise TypeError(f"shape must be one of {', '.join(SHAPES)} (a string), got "
                        f"{type(shape).__name__} {shape!r}"[:200])
    if shape not in builders:
        raise ValueError(f"shape must be one of {', '.join(SHAPES)}, got {shape!r}")
    arch = builders[shape](span, rise, thickness, mass_model=mass_model)
    if arch.span > PLAUSIBLE_SPAN:
        from rockarch.motion.records import UnitsWarning

        warnings.warn(UnitsWarning(
            f"the arch spans {arch.span:.4g} m: sizes are in metres (millimetres? divide "
            "them by 1000)"), stacklevel=2)
    return arch


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
