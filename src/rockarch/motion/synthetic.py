"""Seeded synthetic ground motions: the modulated, time-varying filtered white-noise model
of Rezaeian & Der Kiureghian (2008, 2010), for tests and demos of suites of 50+ records.

The model (docs/theory.md Eqs. (11.8)–(11.11)):

* a unit-variance process: white noise through a linear filter whose frequency ω_f(τ) =
  ω_mid + ω'(τ − t_mid) drifts in time and whose damping ζ_f is constant, normalised by its
  standard deviation at each t;
* times a gamma-shaped modulating function q(t) = α1 t^(α2−1) e^(−α3 t), whose three
  parameters follow from the expected Arias intensity Ia, the significant duration D5–95
  and the time t_mid at which 45 % of Ia is reached (for this q the Husid function is a
  gamma distribution function, so the mapping is exact);
* a critically damped high-pass oscillator (corner f_c) that removes the residual velocity
  and displacement (Rezaeian & Der Kiureghian 2010).

:func:`generate` draws one record for given model parameters; :func:`synthetic_suite` draws
``n`` records whose parameters are themselves random: from the marginal distributions that
Rezaeian & Der Kiureghian (2010) fitted to the parameters identified on their NGA set
(:data:`MARGINALS`), joined by a Gaussian copula with their correlation matrix
(:data:`CORRELATION`); both are reproducible from ``seed``.

References: Rezaeian, S., Der Kiureghian, A. (2008). A stochastic ground motion model with
separable temporal and spectral nonstationarities. EESD 37(13), 1565–1584. Rezaeian, S.,
Der Kiureghian, A. (2010). Simulation of synthetic ground motions for specified earthquake
and site characteristics. EESD 39(10), 1155–1180 (RDK 2010 below).
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import asdict, dataclass

import numba as nb
import numpy as np
from scipy import optimize, special

from rockarch.core import limits
from rockarch.core.constants import G_STANDARD, G
from rockarch.core.paths import check_output_dir, write_text
from rockarch.core.validate import in_range, integer, positive
from rockarch.motion.intensity import pgv
from rockarch.motion.signals import GroundMotion
from rockarch.motion.suite import from_motions, write_at2

#: Default time step of synthetic records [s] (our choice).
DT = 0.01
#: Default corner of the critically damped high-pass oscillator [Hz]. The oscillator is RDK
#: 2010's post-processing; the 0.2 Hz default is our choice, not a value from their paper.
F_CORNER = 0.2
#: Lowest filter frequency [Hz] (our choice, not RDK's): ω_f(τ) = ω_mid + ω'(τ − t_mid) is
#: clipped here where the drift ω' would make it smaller (or negative).
F_FLOOR = 0.3
#: Truncation of the filter's impulse response (ours): exp(−ζ_f ω_f s) below this is dropped.
IRF_CUTOFF = 1e-6
#: Quantile of the Husid (gamma) function at which a record ends (ours).
END_QUANTILE = 0.9995


@dataclass(frozen=True)
class RDKParameters:
    """Parameters of one record of the Rezaeian–Der Kiureghian model (SI units).

    arias : expected Arias intensity Ia [m/s]; d5_95 : significant duration [s];
    t_mid : time at 45 % of Ia [s]; f_mid : filter frequency at t_mid [Hz];
    f_slope : its rate of change [Hz/s]; zeta_f : filter damping ratio.
    """

    arias: float
    d5_95: float
    t_mid: float
    f_mid: float
    f_slope: float
    zeta_f: float

    def __post_init__(self) -> None:
        for name, value in (("Arias intensity", self.arias), ("D5-95", self.d5_95),
                            ("t_mid", self.t_mid), ("f_mid", self.f_mid)):
            positive(name, value)
        in_range("f_slope", self.f_slope, -5.0, 5.0)
        in_range("zeta_f", self.zeta_f, 0.0, 1.0, lo_open=True, hi_open=True)

    def to_dict(self) -> dict:
        return asdict(self)


def _quantile_ratio(k: float) -> float:
    q = special.gammaincinv(k, [0.05, 0.45, 0.95])  # Gamma(k, 1) quantiles
    return float((q[2] - q[0]) / q[1])


#: Shape range of the gamma Husid function that :func:`modulation` can represent (ours).
_K_RANGE = (0.3, 2000.0)


@functools.cache
def ratio_bounds() -> tuple[float, float]:
    """The open interval of D5–95/t_mid that :func:`modulation` can represent (the ratio
    of the gamma shapes :data:`_K_RANGE`)."""
    return _quantile_ratio(_K_RANGE[1]), _quantile_ratio(_K_RANGE[0])


def modulation(p: RDKParameters, g: float = G) -> tuple[float, float, float]:
    """(α1, α2, α3) of RDK 2008's gamma modulating function q(t) = α1 t^(α2−1) e^(−α3 t)
    with the expected Ia, D5–95 and t_mid.

    q² ∝ t^(k−1) e^(−λt) with k = 2α2 − 1 and λ = 2α3 is a gamma density, so the Husid
    function is the gamma distribution function: D5–95/t_mid fixes k, then λ =
    G⁻¹(0.45; k)/t_mid, and α1 follows from Ia = π/(2g) α1² Γ(k)/λ^k (Eq. (11.9)).
    """
    target = p.d5_95 / p.t_mid
    lo, hi = ratio_bounds()
    if not lo < target < hi:
        raise ValueError(f"D5-95/t_mid = {target:.3g} cannot be represented by the gamma "
                         f"modulating function (need {lo:.3g} < D5-95/t_mid < {hi:.3g})")
    log_k = optimize.brentq(lambda x: _quantile_ratio(math.exp(x)) - target,
                            math.log(_K_RANGE[0]), math.log(_K_RANGE[1]), xtol=1e-12)
    k = math.exp(log_k)
    lam = float(special.gammaincinv(k, 0.45)) / p.t_mid
    log_a1_sq = math.log(p.arias * 2.0 * g / math.pi) + k * math.log(lam) - special.gammaln(k)
    return math.exp(0.5 * log_a1_sq), (k + 1.0) / 2.0, lam / 2.0


@nb.njit(cache=True)
def _filtered_noise(u, dt, omega, zeta, cutoff):
    """Σ_i h(t_k − t_i, ω_i) u_i / sqrt(Σ_i h²) at every t_k: RDK 2008's normalised
    time-varying filter of white noise (docs/theory.md Eq. (11.8)).

    The impulse response of pulse i is h(s) = ω_i/√(1−ζ²) e^(−ζω_i s) sin(ω_i √(1−ζ²) s),
    marched by one complex rotation per step and dropped once e^(−ζω_i s) < ``cutoff``.
    """
    n = u.shape[0]
    num = np.zeros(n)
    den = np.zeros(n)
    sq = math.sqrt(1.0 - zeta * zeta)
    for i in range(n - 1):
        w = omega[i]
        decay = math.exp(-zeta * w * dt)
        c = math.cos(w * sq * dt) * decay
        s = math.sin(w * sq * dt) * decay
        m = min(n - 1 - i, int(math.ceil(-math.log(cutoff) / (zeta * w * dt))))
        zr = 1.0  # e^((−ζ + i√(1−ζ²)) ω s) at s = 0
        zi = 0.0
        amp = w / sq
        for j in range(1, m + 1):
            zr, zi = zr * c - zi * s, zr * s + zi * c
            h = amp * zi
            num[i + j] += h * u[i]
            den[i + j] += h * h
    out = np.zeros(n)
    for k in range(n):
        if den[k] > 0.0:
            out[k] = num[k] / math.sqrt(den[k])
    return out


@nb.njit(cache=True)
def _high_pass(a, dt, omega_c):
    """ü of ü + 2ω_c u̇ + ω_c² u = a (critically damped, from rest), by the average
    acceleration (trapezoidal) rule: unconditionally stable, second order (Eq. (11.11))."""
    n = a.shape[0]
    out = np.empty(n)
    u = 0.0
    v = 0.0
    acc = a[0]
    out[0] = acc
    c = 2.0 * omega_c
    k = omega_c * omega_c
    for i in range(1, n):
        # solve for acc_new: acc_new + c v_new + k u_new = a[i] with trapezoidal updates
        v_pred = v + 0.5 * dt * acc
        u_pred = u + dt * v + 0.25 * dt * dt * acc
        acc_new = (a[i] - c * v_pred - k * u_pred) / (1.0 + 0.5 * dt * c + 0.25 * dt * dt * k)
        v = v_pred + 0.5 * dt * acc_new
        u = u_pred + 0.25 * dt * dt * acc_new
        acc = acc_new
        out[i] = acc
    return out


def generate(params: RDKParameters, seed: int | np.random.Generator | None = None, *,
             dt: float = DT, f_corner: float = F_CORNER, g: float = G,
             name: str | None = None) -> GroundMotion:
    """One synthetic record of the RDK model with ``params`` [m/s²], reproducible from
    ``seed``. The record lasts until the Husid function reaches :data:`END_QUANTILE`."""
    rng = np.random.default_rng(seed)
    dt = positive("dt", dt)
    a1, a2, a3 = modulation(params, g)
    k, lam = 2.0 * a2 - 1.0, 2.0 * a3
    t_end = float(special.gammaincinv(k, END_QUANTILE)) / lam
    n = int(math.ceil(t_end / dt)) + 1
    if n > 200_000:
        raise ValueError(f"the record would need {n} samples (t_end = {t_end:.4g} s at dt = "
                         f"{dt:g} s): shorten D5-95/t_mid or enlarge dt")
    t = np.arange(n) * dt
    omega = 2 * math.pi * np.maximum(params.f_mid + params.f_slope * (t - params.t_mid),
                                     F_FLOOR)
    if 2 * math.pi * params.f_mid * dt > 0.5 * math.pi:
        raise ValueError(f"f_mid = {params.f_mid:g} Hz is above a quarter of the sampling "
                         f"rate 1/dt = {1 / dt:g} Hz: use a smaller dt")
    noise = _filtered_noise(rng.standard_normal(n), dt, omega, params.zeta_f, IRF_CUTOFF)
    q = np.zeros(n)  # the filtered noise is 0 at t = 0, so is the record
    q[1:] = a1 * np.exp((a2 - 1.0) * np.log(t[1:]) - a3 * t[1:])
    acc = q * noise
    if f_corner > 0:
        acc = _high_pass(acc, dt, 2 * math.pi * positive("f_corner", f_corner))
    meta = {"format": "synthetic", "model": "Rezaeian & Der Kiureghian 2008",
            "dt": dt, "npts": n, **params.to_dict(), "f_corner": f_corner}
    return GroundMotion(t, acc, name or "RDK synthetic", meta)


@dataclass(frozen=True)
class MPPulse:
    """Near-fault velocity pulse of Mavroeidis & Papageorgiou (2003), Eq. (11.14):
    v = (A/2)[1 + cos(2π(t − t0)/(γ Tp))] cos(2π(t − t0)/Tp + ν) for |t − t0| ≤ γTp/2.

    tp : pulse period [s]; amplitude : A [m/s]; gamma : oscillatory character γ > 1;
    nu : phase ν [rad]; t0 : centre of the pulse [s].
    """

    tp: float
    amplitude: float
    gamma: float
    nu: float
    t0: float

    def __post_init__(self) -> None:
        positive("pulse period", self.tp)
        positive("pulse amplitude", self.amplitude)
        in_range("pulse gamma", self.gamma, 1.0, 10.0, lo_open=True)
        in_range("pulse t0", self.t0, 0.0, math.inf)

    @property
    def start(self) -> float:
        """First instant of the pulse [s]."""
        return self.t0 - 0.5 * self.gamma * self.tp

    @property
    def end(self) -> float:
        """Last instant of the pulse [s]."""
        return self.t0 + 0.5 * self.gamma * self.tp

    def velocity(self, t) -> np.ndarray:
        """Ground velocity of the pulse [m/s]."""
        tau = np.asarray(t, dtype=float) - self.t0
        k = 2 * math.pi / self.tp
        v = 0.5 * self.amplitude * (1 + np.cos(k * tau / self.gamma)) * np.cos(k * tau + self.nu)
        return np.where(np.abs(tau) <= 0.5 * self.gamma * self.tp, v, 0.0)

    def acceleration(self, t) -> np.ndarray:
        """Ground acceleration of the pulse [m/s²] (the derivative of :meth:`velocity`)."""
        tau = np.asarray(t, dtype=float) - self.t0
        k = 2 * math.pi / self.tp
        a = -0.5 * self.amplitude * k * (np.sin(k * tau / self.gamma) * np.cos(k * tau + self.nu)
                                         / self.gamma
                                         + (1 + np.cos(k * tau / self.gamma))
                                         * np.sin(k * tau + self.nu))
        return np.where(np.abs(tau) <= 0.5 * self.gamma * self.tp, a, 0.0)


def add_pulse(motion: GroundMotion, pulse: MPPulse) -> GroundMotion:
    """The motion (uniformly sampled from t = 0) plus the pulse's acceleration, extended
    with zeros if the pulse ends after it; the pulse's parameters go to ``meta``."""
    t = np.asarray(motion.t)
    dt = float(t[1] - t[0])
    if pulse.start < t[0]:
        raise ValueError(f"the pulse starts at {pulse.start:.3g} s, before the record")
    n = max(t.size, int(math.ceil(pulse.end / dt)) + 2)
    tt = t[0] + np.arange(n) * dt
    acc = np.zeros(n)
    acc[:t.size] = motion.a
    meta = {**motion.meta, **{f"pulse_{k}": v for k, v in asdict(pulse).items()}}
    return GroundMotion(tt, acc + pulse.acceleration(tt), motion.name, meta)


#: Demo distribution of pulse parameters (our choice): Tp lognormal (median 2 s, σ_ln 0.5)
#: clipped to 0.5…8 s, γ uniform 1.5…2.5, ν uniform 0…2π, centre t_mid ± 2 s, amplitude
#: 1.5…3 × the PGV of the record it is added to and at least 0.35 m/s.
PULSE_RANGES = {"tp": ("lognormal", 2.0, 0.5), "gamma": ("uniform", 1.5, 2.5),
                "amplitude_over_pgv": ("uniform", 1.5, 3.0), "amplitude_min": 0.35}


def draw_pulse(rng: np.random.Generator, motion: GroundMotion, t_mid: float) -> MPPulse:
    """A pulse from :data:`PULSE_RANGES` for ``motion`` (whose PGV sets its amplitude)."""

    r = PULSE_RANGES
    tp = min(max(r["tp"][1] * math.exp(r["tp"][2] * rng.standard_normal()), 0.5), 8.0)
    gamma = float(rng.uniform(*r["gamma"][1:]))
    nu = float(rng.uniform(0.0, 2 * math.pi))
    t0 = max(t_mid + float(rng.uniform(-2.0, 2.0)), 0.5 * gamma * tp)
    amp = max(float(rng.uniform(*r["amplitude_over_pgv"][1:])) * pgv(motion),
              r["amplitude_min"])
    return MPPulse(tp=tp, amplitude=amp, gamma=gamma, nu=nu, t0=t0)


@dataclass(frozen=True)
class TwoSidedExponential:
    """The two-sided exponential distribution RDK 2010 fitted to f' [Hz/s]: density
    ∝ c·e^(b x) on [lo, 0) and c·e^(−a x) on [0, hi] (a, b, c > 0).

    The published constants integrate to 1 − 1.1·10⁻⁵ over [lo, hi]; the density is
    divided by that mass (:attr:`mass`) so that it integrates to 1. Methods are named as
    those of scipy.stats' frozen distributions (``pdf``, ``cdf``, ``ppf``, ``mean``,
    ``std``) so that it stands beside them in :data:`MARGINALS`.
    """

    a: float
    b: float
    c: float
    lo: float
    hi: float

    def __post_init__(self) -> None:
        for name in ("a", "b", "c"):
            positive(f"two-sided exponential {name}", getattr(self, name))
        if not self.lo < 0.0 < self.hi:
            raise ValueError(f"two-sided exponential needs lo < 0 < hi, got [{self.lo:g}, "
                             f"{self.hi:g}]")

    def _raw(self, k: int, x0: float, x1: float, s: float) -> float:
        """c ∫ x^k e^(s x) dx over [x0, x1] in closed form: the antiderivative is
        e^(s x) Σ_j (−1)^j k!/(k − j)! x^(k−j) / s^(j+1)."""
        def anti(x):
            return math.exp(s * x) * sum((-1) ** j * math.perm(k, j) * x ** (k - j)
                                         / s ** (j + 1) for j in range(k + 1))
        return self.c * (anti(x1) - anti(x0))

    @property
    def mass(self) -> float:
        """∫ of the published (unnormalised) density over [lo, hi]."""
        return self._raw(0, self.lo, 0.0, self.b) + self._raw(0, 0.0, self.hi, -self.a)

    def moment(self, k: int) -> float:
        """E[x^k] of the normalised density (as scipy's ``moment(order)``)."""
        return (self._raw(k, self.lo, 0.0, self.b)
                + self._raw(k, 0.0, self.hi, -self.a)) / self.mass

    def pdf(self, x):
        x = np.asarray(x, dtype=float)
        inside = (x >= self.lo) & (x <= self.hi)
        dens = self.c * np.exp(np.where(x < 0, self.b * x, -self.a * x)) / self.mass
        return np.where(inside, dens, 0.0)

    def cdf(self, x):
        x = np.clip(np.asarray(x, dtype=float), self.lo, self.hi)
        f0 = self._raw(0, self.lo, 0.0, self.b)
        neg = self.c / self.b * (np.exp(self.b * np.minimum(x, 0.0)) - math.exp(self.b * self.lo))
        pos = f0 + self.c / self.a * -np.expm1(-self.a * np.maximum(x, 0.0))
        return np.where(x < 0, neg, pos) / self.mass

    def ppf(self, u):
        """Inverse of :meth:`cdf`, both branches in closed form."""
        w = np.clip(np.asarray(u, dtype=float), 0.0, 1.0) * self.mass  # unnormalised
        f0 = self._raw(0, self.lo, 0.0, self.b)
        with np.errstate(divide="ignore", invalid="ignore"):
            neg = np.log(w * self.b / self.c + math.exp(self.b * self.lo)) / self.b
            pos = -np.log1p(-(w - f0) * self.a / self.c) / self.a
        return np.clip(np.where(w < f0, neg, pos), self.lo, self.hi)

    def mean(self) -> float:
        return self.moment(1)

    def std(self) -> float:
        return math.sqrt(self.moment(2) - self.moment(1) ** 2)


# the parameters of MARGINALS (RDK 2010, as coded in SCECcode/bbp rzz2015_gmpe.py)
_LN_ARIAS = (-4.8255, 1.4318)  # (mean, sd) of ln(Ia [s·g])
_D5_95 = (1.1314, 2.4474, 5.0, 40.0)  # Beta(a, b), then loc + scale·x [s]
_T_MID = (1.5792, 3.6405, 0.5, 39.5)  # Beta(a, b), then loc + scale·x [s]
_F_MID = (4.0982, 1.4330)  # Gamma(shape, scale) [Hz]
_ZETA_F = (1.4250, 5.7208, 0.02, 0.98)  # Beta(a, b), then loc + scale·x

#: Marginal distributions of the six parameters of a record: those RDK 2010 fitted to the
#: parameters identified on their NGA set of far-field records on firm ground. The digits
#: are read from the SCEC Broadband Platform, which implements them (SCECcode/bbp,
#: bbp/comps/rzz2015_gmpe.py, ``RZZ2015GMPE.calculate_mean_values``), not re-checked
#: against the printed paper here:
#:
#: * ``ln_arias``: ln(Ia [s·g]) ~ N(−4.8255, 1.4318) (Ia lognormal; 1 s·g = g·1 s, so
#:   Ia [m/s] = 9.80665·Ia [s·g]; median 0.079 m/s);
#: * ``d5_95`` [s] = 5 + 40·Beta(1.1314, 2.4474) (mean 17.6 s);
#: * ``t_mid`` [s] = 0.5 + 39.5·Beta(1.5792, 3.6405) (mean 12.45 s);
#: * ``f_mid`` [Hz] ~ Gamma(shape 4.0982, scale 1.4330) (mean 5.87 Hz, sd 2.90 Hz);
#: * ``f_slope`` f' [Hz/s]: two-sided exponential on [−2, 0.5], density 4.8512·e^(6.7729 x)
#:   for x < 0 and 4.8512·e^(−17.095 x) for x ≥ 0 (mean −0.089, sd 0.159);
#: * ``zeta_f`` = 0.02 + 0.98·Beta(1.4250, 5.7208) (mean 0.215).
#:
#: (Built on first use: scipy.stats takes half a second to import, which every command of
#: the command line would otherwise pay.)
MARGINALS: dict


@functools.cache
def _marginals() -> dict:
    from scipy import stats

    return {
        "ln_arias": stats.norm(*_LN_ARIAS),
        "d5_95": stats.beta(*_D5_95[:2], loc=_D5_95[2], scale=_D5_95[3]),
        "t_mid": stats.beta(*_T_MID[:2], loc=_T_MID[2], scale=_T_MID[3]),
        "f_mid": stats.gamma(_F_MID[0], scale=_F_MID[1]),
        "f_slope": _F_SLOPE,
        "zeta_f": stats.beta(*_ZETA_F[:2], loc=_ZETA_F[2], scale=_ZETA_F[3]),
    }


def __getattr__(name: str):
    if name == "MARGINALS":
        return _marginals()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


_F_SLOPE = TwoSidedExponential(a=17.095, b=6.7729, c=4.8512, lo=-2.0, hi=0.5)

#: Correlation of the six parameters (order of :data:`MARGINALS`) in standard normal space,
#: ν_i = Φ⁻¹(F_i(θ_i)): the correlation matrix of the total errors of RDK 2010's regression
#: of ν on fault type, magnitude, distance and Vs30 (the four-digit values are
#: ``rho_totalerror`` of the SCEC Broadband Platform's bbp/comps/rzz2015_gmpe.py, which
#: cites RDK 2010). It is the correlation *given* the earthquake and site; we
#: use it as the copula of the unconditional marginals above (the part of the correlation
#: that the predictors explain is not published): our approximation.
CORRELATION = np.array([
    [1.0000, -0.3555, 0.0066, -0.1545, 0.1341, -0.0078],
    [-0.3555, 1.0000, 0.6729, -0.1303, -0.1576, -0.1958],
    [0.0066, 0.6729, 1.0000, -0.2761, -0.1977, -0.2188],
    [-0.1545, -0.1303, -0.2761, 1.0000, -0.2034, 0.2814],
    [0.1341, -0.1576, -0.1977, -0.2034, 1.0000, -0.0137],
    [-0.0078, -0.1958, -0.2188, 0.2814, -0.0137, 1.0000],
])
_CHOLESKY = np.linalg.cholesky(CORRELATION)
#: Draws :func:`draw_parameters` makes before giving up (a draw is redrawn only where the
#: model cannot represent it: about 2 in 100 000 at the default dt).
MAX_DRAWS = 1000


def parameters_from_normal(z) -> RDKParameters:
    """The parameters whose normal scores ν = Φ⁻¹(F(θ)) are ``z`` (6 values, the order of
    :data:`MARGINALS`): θ_i = F_i⁻¹(Φ(z_i)), Ia converted from s·g to m/s. (The inverse
    distribution functions of :data:`MARGINALS`, evaluated by scipy.special directly:
    scipy.stats' frozen ``ppf`` costs 0.2 ms a call.)"""
    z = np.asarray(z, dtype=float)
    u = special.ndtr(z)

    def beta(ui, a, b, loc, scale):
        return loc + scale * float(special.betaincinv(a, b, ui))

    return RDKParameters(
        arias=math.exp(_LN_ARIAS[0] + _LN_ARIAS[1] * float(z[0])) * G_STANDARD,
        d5_95=beta(u[1], *_D5_95), t_mid=beta(u[2], *_T_MID),
        f_mid=_F_MID[1] * float(special.gammaincinv(_F_MID[0], u[3])),
        f_slope=float(_F_SLOPE.ppf(u[4])), zeta_f=beta(u[5], *_ZETA_F))


def draw_parameters(rng: np.random.Generator, *, f_max: float = math.inf) -> RDKParameters:
    """One parameter set from RDK 2010's fitted distributions (:data:`MARGINALS`, joined by
    the Gaussian copula :data:`CORRELATION`).

    A draw the model cannot represent is redrawn: D5–95/t_mid outside
    :func:`ratio_bounds` (:func:`modulation` refuses it; 1.8·10⁻⁵ of draws) or f_mid ≥
    ``f_max`` (:func:`generate` refuses f_mid above a quarter of the sampling rate: at
    dt = 0.01 s, f_max = 25 Hz, 2·10⁻⁵ of draws). The accepted draws follow the published
    distribution truncated by these conditions.
    """
    lo, hi = ratio_bounds()
    for _ in range(MAX_DRAWS):
        try:
            p = parameters_from_normal(_CHOLESKY @ rng.standard_normal(6))
        except ValueError:  # a draw on the open end of a range (zeta_f = 1, ...)
            continue
        if lo < p.d5_95 / p.t_mid < hi and p.f_mid < f_max:
            return p
    raise ValueError(f"no representable RDK parameter set in {MAX_DRAWS} draws "
                     f"(f_max = {f_max:g} Hz)")


#: Time steps of a synthetic suite [s]: the filter frequency (up to 12 Hz) stays below a
#: quarter of the sampling rate, and a record below 2e5 samples.
DT_RANGE = (1e-4, 0.02)
#: Largest high-pass corner [Hz]: above it the filter removes the records' own content
#: (f_mid >= 1 Hz, F_FLOOR).
F_CORNER_MAX = 1.0


def _suite_args(n, seed, dt, f_corner, pulse_fraction) -> tuple:
    """(n, seed, dt, f_corner, pulse fraction) checked before any record is drawn."""
    n = integer("n (number of records)", n)
    if n < 1:
        raise ValueError(f"need at least one synthetic record, got n = {n}")
    limits.check_count("the synthetic suite", n, "records", "ask for fewer records (--n)")
    seed = integer("seed", seed)
    if seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed}")
    dt = in_range("dt (time step) [s]", dt, *DT_RANGE)
    f_corner = in_range("f_corner (high-pass corner) [Hz]", f_corner, 0.0, F_CORNER_MAX)
    return n, seed, dt, f_corner, in_range("pulse fraction", pulse_fraction, 0.0, 1.0)


def record_name(seed: int, k: int) -> str:
    """The name of the k-th synthetic record of ``seed`` (its .AT2 file's stem)."""
    return f"rdk-s{seed}-{k:03d}"


def iter_synthetic(n: int, seed: int = 0, *, dt: float = DT, f_corner: float = F_CORNER,
                   pulse_fraction: float = 0.0):
    """The records of :func:`synthetic_motions`, drawn one at a time (a suite written to
    files holds one record in memory)."""
    n, seed, dt, f_corner, fraction = _suite_args(n, seed, dt, f_corner, pulse_fraction)
    for k, child in enumerate(np.random.SeedSequence(seed).spawn(n)):
        rng = np.random.default_rng(child)
        params = draw_parameters(rng, f_max=0.25 / dt)  # generate's limit on f_mid
        m = generate(params, rng, dt=dt, f_corner=f_corner, name=record_name(seed, k))
        if rng.uniform() < fraction:
            m = add_pulse(m, draw_pulse(rng, m, params.t_mid))
        yield m


def synthetic_motions(n: int, seed: int = 0, *, dt: float = DT, f_corner: float = F_CORNER,
                      pulse_fraction: float = 0.0) -> list[GroundMotion]:
    """``n`` synthetic records named ``rdk-s{seed}-{k:03d}``, parameters drawn by
    :func:`draw_parameters` (RDK 2010's fitted distributions); the same (n, seed) gives the
    same records, and the first m of a larger n are the records of n = m (at the same dt).
    Each record gets a Mavroeidis–Papageorgiou pulse
    (:data:`PULSE_RANGES`) with probability ``pulse_fraction`` (0: none, 1: every one);
    the noise part of record k does not depend on ``pulse_fraction``. At most
    :func:`rockarch.core.limits.max_records` records, and
    :func:`rockarch.core.limits.max_suite_samples` samples in all."""
    out, total = [], 0
    for m in iter_synthetic(n, seed, dt=dt, f_corner=f_corner,
                            pulse_fraction=pulse_fraction):
        total += m.t.size
        if total > limits.max_suite_samples():
            raise limits.too_many(f"a synthetic suite of {n} records", total, "suite_samples",
                                  limits.max_suite_samples(),
                                  "ask for fewer records (write them with `rockarch records "
                                  "synth`, which holds one at a time)")
        out.append(m)
    return out


def synthetic_suite(n: int, seed: int = 0, *, dt: float = DT, f_corner: float = F_CORNER,
                    pulse_fraction: float = 0.0):
    """A :class:`rockarch.motion.suite.Suite` of ``n`` synthetic records (see
    :func:`synthetic_motions`); each record's model parameters are in ``motion.meta``."""

    return from_motions(synthetic_motions(n, seed, dt=dt, f_corner=f_corner,
                                          pulse_fraction=pulse_fraction))


#: File listing the model parameters of a written synthetic suite (not read as a record).
PARAMETERS_FILE = "_synthetic_parameters.csv"


def write_suite(directory, n: int, seed: int = 0, *, dt: float = DT,
                f_corner: float = F_CORNER, pulse_fraction: float = 0.0) -> list:
    """Write ``n`` synthetic records as ``.AT2`` files ``rdk-s{seed}-{k:03d}.AT2`` into
    ``directory`` (created with its missing parents), with their model parameters in
    :data:`PARAMETERS_FILE`. Returns the record paths."""
    from pathlib import Path

    directory = Path(directory)
    check_output_dir(directory)
    if directory.is_dir():  # a suite is a folder: others' records would join it unseen
        from rockarch.motion.suite import _is_record_file

        ours = {f"{record_name(seed, k)}.AT2" for k in range(int(n))}
        other = sorted(q.name for q in directory.iterdir()
                       if q.is_file() and _is_record_file(q) and q.name not in ours)
        if other:
            raise ValueError(f"{directory} already holds {len(other)} other record file(s) "
                             f"(e.g. {other[0]}), which a suite read from it would include: "
                             "give a new or empty folder")
    # the arguments and the first record first: a bad n, dt or pulse fraction leaves no
    # folder behind; then one record at a time in memory
    motions = iter_synthetic(n, seed, dt=dt, f_corner=f_corner, pulse_fraction=pulse_fraction)
    first = next(motions)
    directory.mkdir(parents=True, exist_ok=True)
    paths, lines = [], []
    keys = list(RDKParameters.__dataclass_fields__)
    pulse_keys = [f"pulse_{k}" for k in MPPulse.__dataclass_fields__]
    for m in itertools.chain([first], motions):
        path = write_at2(directory / f"{m.name}.AT2", m,
                         event=f"Synthetic RDK08 seed {int(seed)}", station=m.name,
                         component="H")
        paths.append(path)
        lines.append(",".join([path.name, *(f"{m.meta[k]:.10g}" for k in keys),
                               *(f"{m.meta[k]:.10g}" if k in m.meta else ""
                                 for k in pulse_keys)]))
    write_text(directory / PARAMETERS_FILE,
               "\n".join([",".join(["file", *keys, *pulse_keys]), *lines]) + "\n")
    return paths
