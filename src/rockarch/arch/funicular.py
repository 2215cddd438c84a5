"""Weighted catenary: the axis is the gravity thrust line of a given mass (docs/theory.md Sect. 4).

:func:`weighted_catenary` solves for the axis directly (weights per horizontal length) or by a
fixed point (weights per arc length); :func:`mass_per_horizontal_length` gives an arch's own
mass as such weights (the replacement arch of paper Sect. 4 and 8).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rockarch.arch.cutting import voussoirs
from rockarch.arch.geometry import Arch, _thickness_arg
from rockarch.arch.weights import HorizontalWeights, funicular_axis, horizontal_weights
from rockarch.core.validate import positive


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
                ax = funicular_axis(span, rise, w)
            xe, ye, _, _ = ax(edges / span)
            ds = np.hypot(np.diff(xe), np.diff(ye))
            sig = np.concatenate([[0.0], np.cumsum(ds)])
            sig /= sig[-1]
            mu = np.asarray(weights_per_arc(0.5 * (sig[:-1] + sig[1:])), dtype=float)
            mu = np.broadcast_to(mu, ds.shape)
            if np.any(~np.isfinite(mu)) or np.any(mu < 0) or not np.any(mu > 0):
                raise ValueError("weights_per_arc must be finite, >= 0 and not all zero")
            w = HorizontalWeights(edges=edges, q=mu * ds / np.diff(edges))
            _, ynew, _, _ = funicular_axis(span, rise, w)(xm / span)
            step = float(np.max(np.abs(ynew - y)))
            y = ynew
            if step < tol * span:
                break
        else:
            raise ValueError(f"weighted catenary fixed point did not converge in {max_iter} "
                             "iterations")
    return Arch("weighted catenary", span, rise, _thickness_arg(thickness),
                funicular_axis(span, rise, w), mass_model="weights", weights=w)


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
