"""Ground motions: base acceleration a_g(t) of the ground, in m/s², positive to the right.

A :class:`GroundMotion` is a piecewise-linear function given by knots ``(t, a)``: the base
acceleration is linear between knots and zero before the first and after the last knot
(docs/theory.md Sect. 8, paper Fig. 14). Records have uniformly spaced knots (one per
sample); pulses may repeat a knot time to represent a jump exactly (the square and step
signals), so no signal is smeared over a sampling interval.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import numpy as np

from rockarch.core import limits
from rockarch.core.validate import finite_array, integer, number, positive

#: Knots per period used to sample smooth pulses (sine, half-sine, harmonic, Ricker).
#: Linear interpolation of a sine with N knots per period has a peak error of
#: (pi/N)²/2 ≈ 5e-6 relative at N = 1000, far below the OAS tolerance (1e-3).
KNOTS_PER_PERIOD = 1000

SIGNALS = ("sine", "square", "step", "halfsine", "harmonic", "ricker")


@dataclass(frozen=True, repr=False)
class GroundMotion:
    """Base acceleration a_g(t) [m/s²], linear between knots, zero outside them.

    Parameters
    ----------
    t : array
        Knot times [s], non-decreasing; a repeated time is a jump.
    a : array
        Base acceleration at the knots [m/s²], positive to the right.
    name : str
        Human-readable description (record name or pulse parameters).
    """

    t: np.ndarray
    a: np.ndarray
    name: str = "ground motion"
    meta: dict = field(default_factory=dict, compare=False)

    def __repr__(self) -> str:
        """One line: the name, the number of knots, the duration and the peak (not the
        samples, which ``t`` and ``a`` hold)."""
        return (f"GroundMotion({self.name!r}, {self.t.size} knots, {self.duration:.4g} s, "
                f"PGA {self.pga:.4g} m/s²)")

    def __post_init__(self) -> None:
        t = finite_array("time", self.t, min_len=2)
        a = finite_array("acceleration", self.a, min_len=2)
        if t.shape != a.shape:
            raise ValueError(f"time and acceleration differ in length ({t.size} vs {a.size})")
        if np.any(np.diff(t) < 0):
            k = int(np.flatnonzero(np.diff(t) < 0)[0])
            raise ValueError(f"time must be non-decreasing (t[{k + 1}] < t[{k}])")
        if t[-1] <= t[0]:
            raise ValueError("a ground motion needs a positive duration")
        if not np.any(a != 0.0):
            raise ValueError("the ground motion is zero everywhere")
        t.setflags(write=False)
        a.setflags(write=False)
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "a", a)

    @property
    def duration(self) -> float:
        """Time of the last knot [s] (the motion is zero afterwards)."""
        return float(self.t[-1])

    @property
    def pga(self) -> float:
        """Peak ground acceleration max |a_g| [m/s²]."""
        return float(np.max(np.abs(self.a)))

    def __call__(self, time) -> np.ndarray:
        """Evaluate a_g at ``time`` (linear between knots, zero outside them)."""
        return np.interp(time, self.t, self.a, left=0.0, right=0.0)

    def scaled(self, factor: float) -> GroundMotion:
        """Return the motion multiplied by ``factor`` (any sign: -1 mirrors it)."""
        f = number("factor", factor)
        if not math.isfinite(f):
            raise ValueError(f"scale factor must be finite, got {factor!r}")
        return GroundMotion(self.t, self.a * f, self.name, dict(self.meta))

    def scaled_to_pga(self, pga: float) -> GroundMotion:
        """Return the motion scaled so that its peak ground acceleration is ``pga`` [m/s²]."""
        return self.scaled(positive("target PGA", pga) / self.pga)

    def normalized(self) -> GroundMotion:
        """Return the motion scaled to unit peak (|a_g| ≤ 1): the *shape* used by an OAS."""
        return self.scaled(1.0 / self.pga)

    def fingerprint(self) -> str:
        """SHA-256 of the knots: identifies the exact motion (for caches and provenance)."""
        h = hashlib.sha256()
        h.update(np.ascontiguousarray(self.t).tobytes())
        h.update(np.ascontiguousarray(self.a).tobytes())
        return h.hexdigest()

    def shape_fingerprint(self) -> str:
        """SHA-256 of the time axis and of the samples over the PGA to 6 decimals: the same
        record whatever its units or scale (a suite scales every record to its own PGA)."""
        h = hashlib.sha256()
        h.update(np.ascontiguousarray(np.round(self.t, 9)).tobytes())
        pga = float(np.max(np.abs(self.a)))
        h.update(np.ascontiguousarray(np.round(self.a / pga, 6) + 0.0).tobytes()
                 if pga > 0 else b"")
        return h.hexdigest()


def _smooth(ap: float, period: float, duration: float, func, name: str, n=None) -> GroundMotion:
    if n is None:
        need = max(math.ceil(duration / period * KNOTS_PER_PERIOD), 2)
        if need + 1 > limits.max_samples():  # docs/theory.md Eq. (8.4), before allocating
            raise limits.too_many(f"{name} ({KNOTS_PER_PERIOD} knots per period)", need + 1,
                                  "samples", limits.max_samples(), "use fewer --cycles")
    n_knots = max(int(math.ceil(duration / period * KNOTS_PER_PERIOD)), 2) if n is None else n
    t = np.linspace(0.0, duration, n_knots + 1)
    return GroundMotion(t, ap * func(t), name, {"signal": name.split()[0], "period": period})


def sine(ap: float, period: float) -> GroundMotion:
    """Full-cycle sine pulse a = ap·sin(2πt/T) for 0 ≤ t ≤ T (paper Fig. 14a)."""
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    return _smooth(ap, period, period, lambda t: np.sin(2 * np.pi * t / period),
                   f"sine T={period:g} s")


def halfsine(ap: float, period: float) -> GroundMotion:
    """Half-sine pulse a = ap·sin(2πt/T) for 0 ≤ t ≤ T/2 (one positive lobe)."""
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    return _smooth(ap, period, period / 2, lambda t: np.sin(2 * np.pi * t / period),
                   f"halfsine T={period:g} s")


def harmonic(ap: float, period: float, cycles: int = 3) -> GroundMotion:
    """n-cycle harmonic a = ap·sin(2πt/T) for 0 ≤ t ≤ n·T."""
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    if int(cycles) != cycles or cycles < 1:
        raise ValueError(f"cycles must be a positive integer, got {cycles!r}")
    return _smooth(ap, period, period * int(cycles), lambda t: np.sin(2 * np.pi * t / period),
                   f"harmonic T={period:g} s x{int(cycles)}")


def ricker(ap: float, period: float) -> GroundMotion:
    """Ricker (1953) wavelet of peak ap and dominant period T = 1/f_p, centred at t0 = 1.5·T.

    a = ap·(1 − 2π²f_p²τ²)·exp(−π²f_p²τ²), τ = t − t0, on [0, 3T] (the tails beyond are
    below 1e-8·ap).
    """
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    fp = 1.0 / period

    def shape(t):
        x = (np.pi * fp * (t - 1.5 * period)) ** 2
        return (1.0 - 2.0 * x) * np.exp(-x)

    return _smooth(ap, period, 3 * period, shape, f"ricker T={period:g} s")


def square(ap: float, period: float) -> GroundMotion:
    """Square signal: +ap on [0, T/2), −ap on [T/2, T] (paper Fig. 14b); exact jumps."""
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    h = period / 2
    t = np.array([0.0, h, h, period])
    a = np.array([ap, ap, -ap, -ap])
    return GroundMotion(t, a, f"square T={period:g} s", {"signal": "square", "period": period})


def step(ap: float, period: float) -> GroundMotion:
    """Step impulse: +ap on [0, T] (paper Fig. 14c), then zero."""
    ap, period = positive("amplitude ap", ap), positive("period T", period)
    t = np.array([0.0, period])
    a = np.array([ap, ap])
    return GroundMotion(t, a, f"step T={period:g} s", {"signal": "step", "period": period})


def pulse(signal: str, *, period: float, ap: float = 1.0, cycles: int | None = None
          ) -> GroundMotion:
    """A pulse of the paper's family by name (Fig. 14; docs/theory.md Eqs. 8.1–8.3).

    Parameters
    ----------
    signal : str
        One of :data:`SIGNALS`.
    period : float
        Period of the pulse [s] (of one cycle for ``harmonic``).
    ap : float, optional
        Peak acceleration [m/s²]; 1 by default (``oas`` and ``simulate`` scale the shape).
    cycles : int, optional
        Number of cycles of ``harmonic`` (default 3; the other signals refuse it).
    """
    makers = {"sine": sine, "square": square, "step": step, "halfsine": halfsine,
              "ricker": ricker}
    if not isinstance(signal, str):
        raise TypeError(f"signal must be one of {', '.join(SIGNALS)} (a string), got "
                        f"{type(signal).__name__}")
    if signal not in makers and signal != "harmonic":
        raise ValueError(f"unknown signal {signal!r}: choose one of {', '.join(SIGNALS)}")
    period, ap = number("period", period), number("ap", ap)
    if signal == "harmonic":
        return harmonic(ap, period, 3 if cycles is None else integer("cycles", cycles))
    if cycles is not None:
        raise ValueError(f"cycles (--cycles) goes with the harmonic signal, not {signal}")
    return makers[signal](ap, period)
