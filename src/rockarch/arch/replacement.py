"""Replacement catenary arch of an arbitrary arch (paper Sects. 4, 8; docs/theory.md §7).

The replacement's axis is the axis of the thickest uniform catenary band inside the
original's contour, its springings free on the original's springing joints
(:func:`rockarch.arch.band.lower_bound_band`, Eqs. 7.3–7.6). It has its own span l′ and
rise f′. Two uniform thicknesses are defined on it:

* **lower bound** d̄: the band's thickness (Eq. 7.6);
* **equivalent** d̂: the thickness whose limit acceleration ap,min equals the original arch's
  (root finding on the LP, Eq. 7.7).

By default the replacement carries its own uniform mass (``mass="own"``, the voussoir model
of ``catenary(l′, f′, d)``); ``mass="original"`` puts the original's mass per horizontal
length on its axis instead. For each thickness the critical optimal four-hinge mechanism
gives p, ap,min, delta and c1, c2 (Eq. 5.2), and the equivalent slender block has
R = 0.75·g/p² (Eq. 7.1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from rockarch.arch.band import AXES, Band, lower_bound_band
from rockarch.arch.fourhinge import ArchMechanism, analyse
from rockarch.arch.geometry import Arch, catenary
from rockarch.arch.thrust import limit_analysis
from rockarch.arch.weights import HorizontalWeights
from rockarch.core.constants import G
from rockarch.core.validate import positive

RULES = ("lower-bound", "equivalent")
MASSES = ("own", "original")


@dataclass(frozen=True)
class ReplacementArch:
    """A replacement catenary arch and its dynamic parameters (paper Table 2).

    Attributes
    ----------
    rule : "lower-bound" or "equivalent".
    arch : the replacement (its own coordinates: left springing at (0, 0), span l′).
    thickness, rise, span : its uniform thickness, axis rise f′ and span l′ [m].
    springings : (2, 2) P_L, P_R in the original's coordinates.
    original_span : the original's span l [m].
    mechanism : its critical optimal four-hinge mechanism (p, ap_min, delta, c1..c4).
    """

    rule: str
    arch: Arch
    thickness: float
    rise: float
    span: float
    springings: np.ndarray
    original_span: float
    mechanism: ArchMechanism

    p = property(lambda self: self.mechanism.p, doc="Frequency parameter p [rad/s].")
    ap_min = property(lambda self: self.mechanism.ap_min, doc="ap,min [m/s²].")

    @property
    def R_block(self) -> float:  # noqa: N802 - the field's name
        """Half-diagonal of the equivalent slender block, R = 0.75·g/p² [m] (Eq. 7.1: Housner's
        1963 p² = 3g/(4R) of a rectangular block, solved for R)."""
        return 0.75 * self.mechanism.thrust.g / self.p**2

    def to_dict(self) -> dict:
        """The ``replacement`` object of ``rockarch design --json``.

        Thickness and span are given per the replacement's own span l′ (as the paper's
        0.0207) and per the original's span l (as the paper's 0.0293).
        """
        m = self.mechanism
        return {"rule": self.rule, "thickness": self.thickness, "span": self.span,
                "rise": self.rise, "p": m.p, "ap_min": m.ap_min,
                "thickness_over_span": self.thickness / self.span,
                "thickness_over_original_span": self.thickness / self.original_span,
                "span_over_original_span": self.span / self.original_span,
                "rise_over_span": self.rise / self.span,
                "springings": self.springings.tolist(),
                "delta": m.delta_end, "delta_u": m.delta, "c1": m.c1, "c2": m.c2,
                "R_block": self.R_block}


def _shifted_weights(w: HorizontalWeights, band: Band) -> HorizontalWeights:
    """The original's q(x) in the replacement's coordinates, covering [0, l′]."""
    edges = w.edges - band.left[0]
    edges[0] = min(edges[0], 0.0)
    edges[-1] = max(edges[-1], band.span)
    return HorizontalWeights(edges=edges, q=w.q)


def replacement_arch(band: Band, thickness: float, *, mass: str = "own") -> Arch:
    """The replacement arch on the band's axis with a given uniform thickness (Eq. 7.3/7.4).

    A symmetric catenary band gives ``catenary(l′, f′, d)``; otherwise the axis is the band's
    curve between P_L and P_R, shifted so that P_L is at (0, 0).
    """
    if mass not in MASSES:
        raise ValueError(f"replacement mass must be one of {', '.join(MASSES)}, got {mass!r}")
    d = positive("thickness", thickness)
    span, rise = band.span, band.rise
    if band.axis == "catenary" and band.symmetric:
        arch = catenary(span, rise, d)
    else:
        x_l, y_l = float(band.left[0]), float(band.left[1])

        def axis_fn(t):
            x = x_l + np.asarray(t, dtype=float) * span
            return (x - x_l, band.y(x) - y_l, np.full_like(x, span), band.dy(x) * span)

        name = "catenary" if band.axis == "catenary" else "weighted catenary"
        arch = Arch(name, span, rise, d, axis_fn)
    if mass == "original":
        arch = arch.with_mass_model("weights", _shifted_weights(band.weights, band))
    return arch


def equivalent_thickness(axis_arch: Arch, ap_min: float, *, g: float = G,
                         d_lo: float | None = None) -> float:
    """Thickness d̂ on the given axis whose ap,min equals ``ap_min`` (Eq. 7.7, brentq on the LP)."""
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
    band: Band
    mass: str
    lower_bound: ReplacementArch
    equivalent: ReplacementArch

    def by_rule(self, rule: str) -> ReplacementArch:
        if rule not in RULES:
            raise ValueError(f"thickness rule must be one of {', '.join(RULES)}, got {rule!r}")
        return self.lower_bound if rule == "lower-bound" else self.equivalent


def replacement(original: Arch, *, g: float = G, axis: str = "catenary",
                mass: str = "own") -> Replacement:
    """Replacement catenary arches of ``original`` (lower-bound and equivalent thickness).

    Parameters
    ----------
    axis : "catenary" (default; uniform-mass catenary family) or "weighted" (the funicular
        of the original's mass per horizontal length).
    mass : "own" (default; the replacement's own uniform mass: fits Table 2's c2 to 0.1 %)
        or "original" (the original's mass per horizontal length on the replacement's axis).
    """
    g = positive("g", g)
    if axis not in AXES:
        raise ValueError(f"replacement axis must be one of {', '.join(AXES)}, got {axis!r}")
    if mass not in MASSES:
        raise ValueError(f"replacement mass must be one of {', '.join(MASSES)}, got {mass!r}")
    orig = analyse(original, g=g)
    band = lower_bound_band(original, axis=axis)
    springs = np.stack([band.left, band.right])

    def make(rule: str, arch: Arch) -> ReplacementArch:
        return ReplacementArch(rule, arch, float(arch.uniform_thickness), band.rise,
                               band.span, springs, original.span, analyse(arch, g=g))

    lb_arch = replacement_arch(band, band.thickness, mass=mass)
    lb = make("lower-bound", lb_arch)
    d_eq = equivalent_thickness(lb_arch, orig.ap_min, g=g, d_lo=0.5 * band.thickness)
    eq = make("equivalent", lb_arch.with_thickness(d_eq))
    if not math.isfinite(eq.p):
        raise ValueError("the equivalent replacement arch has no four-hinge mechanism")
    return Replacement(orig, band, mass, lb, eq)
