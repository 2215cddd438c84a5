"""Intensity measures of a ground motion: PGA, PGV, PGD, Arias intensity, significant
duration D5–95, mean period Tm and 5 %-damped pseudo-spectral acceleration Sa(T).

A :class:`rockarch.motion.signals.GroundMotion` is piecewise linear between its knots, and every
measure here is computed for that function: velocity, displacement and Arias intensity
are exact integrals of it (docs/theory.md Eqs. (11.1)–(11.5)), Sa(T) uses the exact recurrence of a
linear oscillator under piecewise-linear excitation (Nigam & Jennings 1969; Eq. (11.6)).
Why not eqsig or pyrotd: docs/sites.md, "Intensity measures".

Units: SI (m/s², m/s, m, s); Arias intensity in m/s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

from rockarch.core.constants import G
from rockarch.core.jit_cache import kernel_array
from rockarch.core.validate import finite_array, in_range, positive
from rockarch.motion.signals import GroundMotion

#: Default damping ratio of Sa(T): the 5 % of design spectra (a convention, not a fit).
DAMPING = 0.05
#: Default periods of Sa(T) [s] (``rockarch records info``).
PERIODS = (0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0)
#: Sub-steps per oscillator period in the Sa recurrence. The recurrence is exact at the
#: steps; the peak between steps is missed by at most 1 − cos(π/N) ≈ (π/N)²/2 = 2e-4
#: relative at N = 150.
POINTS_PER_PERIOD = 150
#: Frequency band of the mean period Tm [Hz]: 0.25–20 Hz, the band of the definition of
#: Rathje, Abrahamson & Bray (1998, JGGE 124(2)), kept by Rathje et al. (2004).
TM_BAND = (0.25, 20.0)
#: Largest and smallest number of samples a non-uniformly sampled motion is resampled to.
MAX_SAMPLES = 2_000_000
MIN_SAMPLES = 4000
#: Intensity measures proportional to the scale factor of the motion (used by IDA).
LINEAR_IMS = ("pga", "pgv", "pgd", "sa")


def pga(motion: GroundMotion) -> float:
    """Peak ground acceleration max |a_g| [m/s²] (Eq. (11.1))."""
    return motion.pga


def _steps(motion: GroundMotion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t, a = np.asarray(motion.t), np.asarray(motion.a)
    return t, a, np.diff(t)


def velocity(motion: GroundMotion) -> tuple[np.ndarray, np.ndarray]:
    """Ground velocity at the knots [m/s], exact for piecewise-linear a_g, from rest
    (Eq. (11.2)). Returns ``(t, v)``."""
    t, a, h = _steps(motion)
    v = np.concatenate([[0.0], np.cumsum(0.5 * h * (a[:-1] + a[1:]))])
    return t, v


def pgv(motion: GroundMotion) -> float:
    """Peak ground velocity max |v| [m/s] (exact: v is piecewise quadratic, its extremes
    lie at knots or where a_g changes sign inside a step)."""
    t, a, h = _steps(motion)
    _, v = velocity(motion)
    peak = float(np.max(np.abs(v)))
    a0, a1 = a[:-1], a[1:]
    cross = (a0 * a1 < 0.0) & (h > 0.0)
    if np.any(cross):
        s = a0[cross] / (a0[cross] - a1[cross])  # fraction of the step where a = 0
        v_ext = v[:-1][cross] + 0.5 * a0[cross] * s * h[cross]
        peak = max(peak, float(np.max(np.abs(v_ext))))
    return peak


def displacement(motion: GroundMotion, order: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Baseline-corrected ground displacement at the knots [m] (Eq. (11.3)).

    The velocity (exact) is corrected by removing its least-squares polynomial of degree
    ``order`` in time (order 1: a constant acceleration offset and an initial velocity, the
    usual zero-line drift of an accelerogram; 0: only a velocity offset; -1: none), fitted
    in time (trapezoid weights); the
    displacement is its exact integral (Simpson's rule on each step is exact for the
    piecewise-quadratic raw velocity; the polynomial is integrated exactly too).
    """
    order = int(order)
    if order < -1 or order > 5:
        raise ValueError(f"baseline order must lie in -1…5, got {order}")
    t, a, h = _steps(motion)
    _, v = velocity(motion)
    # exact integral of the piecewise-quadratic v over each step
    u = np.concatenate([[0.0], np.cumsum(h * (v[:-1] + h * (2 * a[:-1] + a[1:]) / 6.0))])
    if order >= 0:
        tau = (t - t[0]) / (t[-1] - t[0])
        # least squares in time (trapezoid weights), not per sample: end samples and
        # repeated knots get their share of time, no more
        wts = np.concatenate([[0.0], h]) / 2 + np.concatenate([h, [0.0]]) / 2
        coef = np.polynomial.polynomial.polyfit(tau, v, order, w=np.sqrt(wts))
        # integral of the fitted polynomial in real time: ∫ P(τ) dt = T ∫ P(τ) dτ
        integ = np.polynomial.polynomial.polyint(coef) * (t[-1] - t[0])
        u = u - np.polynomial.polynomial.polyval(tau, integ)
    return t, u


def pgd(motion: GroundMotion, order: int = 1) -> float:
    """Peak ground displacement [m] of the baseline-corrected displacement (Eq. (11.3))."""
    return float(np.max(np.abs(displacement(motion, order)[1])))


def arias(motion: GroundMotion, g: float = G) -> float:
    """Arias intensity Ia = π/(2g) ∫ a_g² dt [m/s] (Arias 1970; Eq. (11.4)), exact for
    piecewise-linear a_g."""
    return float(husid_integral(motion)[-1] * math.pi / (2.0 * positive("g", g)))


def husid_integral(motion: GroundMotion) -> np.ndarray:
    """∫_0^t a_g² dt at the knots (exact for piecewise-linear a_g) [m²/s³]."""
    _, a, h = _steps(motion)
    a0, a1 = a[:-1], a[1:]
    return np.concatenate([[0.0], np.cumsum(h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0)])


def significant_duration(motion: GroundMotion, lo: float = 0.05, hi: float = 0.95
                         ) -> float:
    """Significant duration D_lo–hi [s]: time between the instants where the Husid
    function (normalised Arias intensity) reaches ``lo`` and ``hi`` (Eq. (11.5); Trifunac &
    Brady 1975). Linear interpolation between knots of the exact Husid integral."""
    lo = in_range("lower fraction", lo, 0.0, 1.0)
    hi = in_range("upper fraction", hi, 0.0, 1.0)
    if not lo < hi:
        raise ValueError(f"need lower fraction < upper fraction, got {lo} and {hi}")
    cum = husid_integral(motion)
    frac = cum / cum[-1]
    t = np.asarray(motion.t)
    return float(np.interp(hi, frac, t) - np.interp(lo, frac, t))


def uniform_samples(motion: GroundMotion) -> tuple[float, np.ndarray]:
    """``(dt, a)`` on a uniform grid: the knots themselves when they are uniform (records),
    else the motion resampled at its smallest knot spacing, or finer so that it has at
    least :data:`MIN_SAMPLES` samples (pulses; a jump is then spread over one step)."""
    t, a, h = _steps(motion)
    dt = (t[-1] - t[0]) / (t.size - 1)
    if np.all(np.abs(h - dt) <= 1e-6 * dt):
        return float(dt), kernel_array(a)
    pos = h[h > 0.0]
    # at least MIN_SAMPLES over the motion: a pulse of few knots (a square pulse has 4)
    # keeps its shape, a jump is spread over a small fraction of it
    step = max(min(float(pos.min()), (t[-1] - t[0]) / MIN_SAMPLES),
               (t[-1] - t[0]) / MAX_SAMPLES)
    n = int(math.ceil((t[-1] - t[0]) / step)) + 1
    grid = t[0] + np.arange(n) * ((t[-1] - t[0]) / (n - 1))
    return float(grid[1] - grid[0]), kernel_array(motion(grid))


def mean_period(motion: GroundMotion, band: tuple[float, float] = TM_BAND) -> float:
    """Mean period Tm = Σ C_i²/f_i / Σ C_i² over the Fourier amplitudes C_i of a_g with
    ``band[0] ≤ f_i ≤ band[1]`` Hz [s] (Eq. (11.7); Rathje et al. 1998, 2004)."""
    f_lo, f_hi = (positive("band start", band[0]), positive("band end", band[1]))
    if not f_lo < f_hi:
        raise ValueError(f"the Tm band needs start < end, got {band}")
    dt, a = uniform_samples(motion)
    amp = np.abs(np.fft.rfft(a))
    f = np.fft.rfftfreq(a.size, dt)
    sel = (f >= f_lo) & (f <= f_hi)
    c2 = amp[sel] ** 2
    if not np.any(c2 > 0.0):
        raise ValueError(f"{motion.name}: no Fourier amplitude in {f_lo:g}…{f_hi:g} Hz "
                         "(record too short or band above its Nyquist frequency)")
    return float(np.sum(c2 / f[sel]) / np.sum(c2))


def _oscillator_step(omega: float, zeta: float, h: float, u0: float, v0: float, a0: float,
                     slope: float) -> tuple[float, float]:
    """(u, u') after h of u'' + 2ζωu' + ω²u = −(a0 + slope·τ), in closed form: the
    particular solution −(a0 + slope·τ)/ω² + 2ζ·slope/ω³ plus damped free vibration."""
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    w2 = omega * omega
    up0 = -a0 / w2 + 2.0 * zeta * slope / (w2 * omega)
    c1 = u0 - up0
    c2 = (v0 + slope / w2 + zeta * omega * c1) / wd
    e, c, s = math.exp(-zeta * omega * h), math.cos(wd * h), math.sin(wd * h)
    u = up0 - slope * h / w2 + e * (c1 * c + c2 * s)
    v = -slope / w2 + e * ((wd * c2 - zeta * omega * c1) * c - (zeta * omega * c2 + wd * c1) * s)
    return u, v


def _oscillator_coefficients(omega: float, zeta: float, h: float) -> np.ndarray:
    """Exact one-step coefficients of u'' + 2ζωu' + ω²u = −a_g, a_g linear over h
    (Eq. (11.6); the step is linear in u, u', a_g and its change, so unit inputs give the
    coefficients). The last two multiply the change of a_g over the step."""
    unit = [(1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0),
            (0.0, 0.0, 0.0, 1.0 / h)]
    (uu, vu), (uv, vv), (ua, va), (us, vs) = (_oscillator_step(omega, zeta, h, *x)
                                              for x in unit)
    return np.array([uu, uv, vu, vv, ua, va, us, vs])


#: Periods of Sa(T) accepted [s]: shorter ones need dt·N/T sub-steps per sample (1e-3 s:
#: 1500 at dt = 0.01 s), longer ones a free vibration of T/2 after the motion.
PERIOD_RANGE = (1e-3, 100.0)
#: Most periods of one call (each is a pass over the record).
MAX_PERIODS = 1000


def _check_periods(periods) -> np.ndarray:
    per = finite_array("periods", np.atleast_1d(periods))
    lo, hi = PERIOD_RANGE
    bad = per[(per < lo) | (per > hi)]
    if bad.size:
        raise ValueError(f"periods of Sa(T) must lie in [{lo:g}, {hi:g}] s, got {bad[0]:g}")
    if per.size > MAX_PERIODS:
        raise ValueError(f"at most {MAX_PERIODS} periods of Sa(T), got {per.size}")
    return per


def _substeps(dt: float, period: float, points_per_period: int) -> tuple[int, float]:
    sub = max(1, int(math.ceil(dt * points_per_period / period)))
    return sub, dt / sub


def spectral_acceleration(motion: GroundMotion, periods: Sequence[float] | float = PERIODS,
                          damping: float = DAMPING,
                          points_per_period: int = POINTS_PER_PERIOD) -> np.ndarray:
    """Pseudo-spectral acceleration Sa(T) = ω² max|u| [m/s²] of a linear oscillator at rest
    (Eq. (11.6)), for each period in ``periods``.

    The oscillator is followed over the motion and half a period of free vibration after it
    (where a later peak can occur).
    """
    from rockarch.motion.intensity_kernels import march

    per = _check_periods(periods)
    zeta = in_range("damping", damping, 0.0, 1.0, hi_open=True)
    dt, a = uniform_samples(motion)
    out = np.empty(per.size)
    for j, period in enumerate(per):
        omega = 2.0 * math.pi / period
        sub, h = _substeps(dt, period, int(points_per_period))
        coef = _oscillator_coefficients(omega, zeta, h)
        n_free = int(math.ceil(0.5 * period / h)) + 1
        out[j] = omega * omega * march(a, sub, coef, n_free, np.empty(0))
    return out


def oscillator_history(motion: GroundMotion, period: float, damping: float = DAMPING,
                       points_per_period: int = POINTS_PER_PERIOD
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Relative displacement u(t) [m] of the oscillator behind Sa(T): ``(t, u)`` at every
    sub-step of the recurrence."""
    from rockarch.motion.intensity_kernels import march

    period = positive("period", period)
    zeta = in_range("damping", damping, 0.0, 1.0, hi_open=True)
    dt, a = uniform_samples(motion)
    sub, h = _substeps(dt, period, int(points_per_period))
    u = np.zeros((a.size - 1) * sub + 1)
    march(a, sub, _oscillator_coefficients(2 * math.pi / period, zeta, h), 0, u)
    return float(motion.t[0]) + np.arange(u.size) * h, u


@dataclass(frozen=True)
class IntensityMeasures:
    """The intensity measures of one record (SI units; ``sa`` at ``periods``)."""

    pga: float
    pgv: float
    pgd: float
    arias: float
    d5_95: float
    tm: float
    periods: tuple[float, ...]
    sa: tuple[float, ...]
    damping: float = DAMPING

    def to_dict(self) -> dict:
        """Plain dict (``sa`` as a list aligned with ``periods``)."""
        d = asdict(self)
        d["periods"], d["sa"] = list(self.periods), list(self.sa)
        return d


def measures(motion: GroundMotion, periods: Sequence[float] = PERIODS,
             damping: float = DAMPING, g: float = G) -> IntensityMeasures:
    """Every intensity measure of ``motion`` (Eqs. (11.1)–(11.7)); ``tm`` is NaN where no
    Fourier amplitude lies in its band (a constant or very short motion)."""
    per = _check_periods(periods)
    sa = spectral_acceleration(motion, per, damping)
    try:
        tm = mean_period(motion)
    except ValueError:  # no Fourier amplitude in the band (a constant or very short motion)
        tm = math.nan
    return IntensityMeasures(pga=pga(motion), pgv=pgv(motion), pgd=pgd(motion),
                             arias=arias(motion, g), d5_95=significant_duration(motion),
                             tm=tm, periods=tuple(float(x) for x in per),
                             sa=tuple(float(x) for x in sa), damping=float(damping))


def im_value(motion: GroundMotion, name: str, *, period: float | None = None,
             damping: float = DAMPING) -> float:
    """One intensity measure by name: pga, pgv, pgd, arias, d5_95, tm, or sa (which needs
    ``period``). Used by fragility analyses (``--im``)."""
    key = name.strip().lower()
    simple = {"pga": pga, "pgv": pgv, "pgd": pgd, "arias": arias,
              "d5_95": significant_duration, "tm": mean_period}
    if key in simple:
        return float(simple[key](motion))
    if key == "sa":
        if period is None:
            raise ValueError("the intensity measure sa needs a period T [s]")
        return float(spectral_acceleration(motion, [period], damping)[0])
    raise ValueError(f"unknown intensity measure {name!r}: use one of "
                     f"{', '.join([*simple, 'sa'])}")
