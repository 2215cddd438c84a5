"""Near-fault velocity pulses: the pulse indicator and pulse period of Baker (2007).

Baker, J. W. (2007). Quantitative classification of near-fault ground motions using wavelet
analysis. BSSA 97(5), 1486–1501. The method (docs/theory.md Eqs. (11.12)–(11.13)):

1. the ground velocity is projected on Daubechies-4 wavelets of every scale and position;
   the scale of the largest |coefficient| fixes the pulse period Tp (the pseudo-period of
   the wavelet, the period of its largest Fourier amplitude);
2. the pulse is the sum of 10 wavelets of that scale, each the largest projection on the
   residual left by the previous ones, sought within ±0.4·s of the first one's position
   (s the wavelet's time scale; the search window of the Shahi & Baker code): one pulse;
3. PI = 1 / (1 + exp(−23.3 + 14.6 PGV_ratio + 20.5 energy_ratio)), with the ratios of the
   residual's PGV and ∫v² to the original's; a record is pulse-like if PI > 0.85, the
   pulse is not late (it reaches 10 % of its ∫v² before the record reaches 20 % of its
   own) and PGV ≥ 30 cm/s.

The Daubechies-4 wavelet comes from PyWavelets (``pywt``): the same function as MATLAB's
``db4`` used by Baker. Our projection uses the unit-energy wavelet at each scale (an
orthogonal least-squares fit of one wavelet), which is the CWT coefficient up to a
constant factor per scale; the choice of scale maximises the coefficient as Baker's does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import fft

from rockarch.motion.intensity import uniform_samples
from rockarch.motion.signals import GroundMotion

#: Number of wavelets summed into the pulse (Baker 2007).
N_WAVELETS = 10
#: The wavelets after the first are sought within ± WINDOW·s of its position (s its time
#: scale), the search window of the Shahi & Baker code: the pulse stays one local feature.
WINDOW = 0.4
#: Logistic coefficients of the pulse indicator (Baker 2007).
PI_COEF = (-23.3, 14.6, 20.5)
#: Thresholds: pulse-like above, non-pulse below (between: ambiguous).
PI_PULSE, PI_NO_PULSE = 0.85, 0.15
#: Smallest PGV of a pulse-like record [m/s].
PGV_MIN = 0.30


@dataclass(frozen=True)
class PulseResult:
    """Baker (2007) classification of one record.

    ``tp`` [s] is the pseudo-period of the extracted pulse; ``pulse`` its velocity [m/s]
    at ``t`` [s] (uniform samples of the record).
    """

    pulse_indicator: float
    tp: float
    pgv_ratio: float
    energy_ratio: float
    late: bool
    pgv: float
    t: np.ndarray
    pulse: np.ndarray

    @property
    def pulse_like(self) -> bool:
        """PI > 0.85, not late, PGV ≥ 30 cm/s."""
        return self.pulse_indicator > PI_PULSE and not self.late and self.pgv >= PGV_MIN

    @property
    def classification(self) -> str:
        """``pulse``, ``non-pulse`` or ``ambiguous`` (Baker's three classes)."""
        if self.pulse_like:
            return "pulse"
        if self.pulse_indicator < PI_NO_PULSE or self.late or self.pgv < PGV_MIN:
            return "non-pulse"
        return "ambiguous"

    def to_dict(self) -> dict:
        return {"pulse_indicator": self.pulse_indicator, "tp": self.tp,
                "pgv_ratio": self.pgv_ratio, "energy_ratio": self.energy_ratio,
                "late": self.late, "pulse_like": self.pulse_like,
                "classification": self.classification}


def _db4():
    import pywt

    _, psi, x = pywt.Wavelet("db4").wavefun(level=10)
    return x, psi, float(pywt.central_frequency("db4"))


def _wavelet(x, psi, scale: float, dt: float) -> np.ndarray:
    """db4 at time scale ``scale`` [s], unit energy (Σ ψ² dt = 1), sampled at dt."""
    k = np.arange(int(math.floor(x[-1] * scale / dt)) + 1)
    w = np.interp(k * dt / scale, x, psi)
    return w / math.sqrt(np.sum(w * w) * dt)


def _best(v_hat: np.ndarray, n: int, w: np.ndarray, dt: float, nfft: int,
          near: tuple[int, int] | None = None) -> tuple[float, int]:
    """Largest |projection| of v (its rfft ``v_hat`` of length ``nfft``, n samples) on the
    shifted wavelet, and the wavelet's start index (< 0: partly before the record);
    ``near = (start, half)`` limits the search to starts within ``half`` samples."""
    c = np.fft.irfft(v_hat * np.fft.rfft(w[::-1], nfft), nfft)[:n + w.size - 1] * dt
    lo, hi = 0, c.size
    if near is not None:
        lo = max(near[0] - near[1] + w.size - 1, 0)
        hi = min(near[0] + near[1] + w.size, c.size)
    j = lo + int(np.argmax(np.abs(c[lo:hi])))
    return float(c[j]), j - (w.size - 1)


def _add(target: np.ndarray, w: np.ndarray, start: int, coef: float) -> None:
    lo, hi = max(start, 0), min(start + w.size, target.size)
    if hi > lo:
        target[lo:hi] += coef * w[lo - start:hi - start]


def _time_at(v: np.ndarray, frac: float, dt: float) -> float:
    cum = np.cumsum(v * v)
    return float(np.searchsorted(cum, frac * cum[-1]) * dt)


def baker_pulse(motion: GroundMotion, *, tp_min: float = 0.2, tp_max: float = 15.0,
                n_periods: int = 120, n_wavelets: int = N_WAVELETS) -> PulseResult:
    """Pulse indicator, pulse period and extracted pulse of ``motion`` (Baker 2007).

    Candidate pulse periods are ``n_periods`` log-spaced values in [tp_min, tp_max] (capped
    at the record's duration); their spacing bounds the resolution of Tp.
    """

    dt, a = uniform_samples(motion)
    v = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a[:-1] + a[1:]))])
    duration = dt * (v.size - 1)
    x, psi, fc = _db4()
    hi = min(tp_max, duration)
    if not 0 < tp_min < hi:
        raise ValueError(f"pulse periods {tp_min:g}…{tp_max:g} s do not fit a record of "
                         f"{duration:g} s")
    # one FFT length serves every scale: linear (not circular) correlation up to the
    # longest wavelet
    nfft = fft.next_fast_len(v.size + int(x[-1] * hi * fc / dt) + 1)
    v_hat = np.fft.rfft(v, nfft)
    best = (0.0, 0, 0.0)
    for tp in np.geomspace(tp_min, hi, int(n_periods)):
        scale = tp * fc  # a wavelet of time scale s has pseudo-period s / fc
        c, start = _best(v_hat, v.size, _wavelet(x, psi, scale, dt), dt, nfft)
        if abs(c) > abs(best[0]):
            best = (c, start, scale)
    scale = best[2]
    w = _wavelet(x, psi, scale, dt)
    residual = v.copy()
    pulse = np.zeros_like(v)
    near = (best[1], int(math.ceil(WINDOW * scale / dt)))
    for _ in range(int(n_wavelets)):
        c, start = _best(np.fft.rfft(residual, nfft), v.size, w, dt, nfft, near)
        _add(pulse, w, start, c)
        _add(residual, w, start, -c)
    pgv = float(np.max(np.abs(v)))
    pgv_ratio = float(np.max(np.abs(residual)) / pgv)
    energy_ratio = float(np.sum(residual**2) / np.sum(v**2))
    c0, c1, c2 = PI_COEF
    pi = 1.0 / (1.0 + math.exp(c0 + c1 * pgv_ratio + c2 * energy_ratio))
    late = _time_at(pulse, 0.10, dt) > _time_at(v, 0.20, dt)
    t = float(motion.t[0]) + np.arange(v.size) * dt
    return PulseResult(pulse_indicator=pi, tp=scale / fc, pgv_ratio=pgv_ratio,
                       energy_ratio=energy_ratio, late=bool(late), pgv=pgv, t=t, pulse=pulse)
