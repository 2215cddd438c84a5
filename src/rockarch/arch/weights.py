"""Weight per unit horizontal length and its funicular axis (docs/theory.md Sect. 4).

:class:`HorizontalWeights` is a histogram q(x) over x; :func:`funicular_axis` is the axis
y(x) with H*y'' = -q(x) through both springings (exact for histograms). Both feed the
weighted catenary (:mod:`rockarch.arch.funicular`) and the ``"weights"`` mass model.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from rockarch.arch.shapes import AxisFn
from rockarch.core.validate import finite_array, positive


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


def funicular_axis(span: float, rise: float, w: HorizontalWeights) -> AxisFn:
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
