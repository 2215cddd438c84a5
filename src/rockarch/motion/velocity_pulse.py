"""Near-fault velocity pulses: the pulse indicator and pulse period of Baker (2007) or of
Shahi & Baker (2014), on one ground-motion component.

Baker, J. W. (2007). Quantitative classification of near-fault ground motions using wavelet
analysis. BSSA 97(5), 1486–1501. Shahi, S. K., Baker, J. W. (2014). An efficient algorithm
to identify strong-velocity pulses in multicomponent ground motions. BSSA 104(5),
2456–2466. The method (docs/theory.md Eqs. (11.12)–(11.13)):

1. the ground velocity is projected on Daubechies-4 wavelets of every candidate scale and
   position; the scale of the largest |coefficient| fixes the pulse period Tp (the
   pseudo-period of the wavelet, the period of its largest Fourier amplitude);
2. the pulse is the sum of 10 wavelets of that scale, each the largest projection on the
   residual left by the previous ones, sought within ±0.4·s of the first one's position
   (s the wavelet's time scale). This extraction is the one of Shahi & Baker's (2014)
   code, used by both methods here (the ±0.4·s window is the 2014 code's; Baker's 2007
   extraction of the later wavelets is not reproduced);
3. the classification, by ``method``:

   * ``"2007"`` (Baker 2007): PI = 1 / (1 + exp(−23.3 + 14.6 PGV_ratio + 20.5
     energy_ratio)) with the ratios of the residual's PGV and ∫v² to the original's. The
     class is PI's alone: ``pulse`` if PI > 0.85, ``non-pulse`` if PI < 0.15, ``ambiguous``
     between. Two further criteria are separate flags: ``late`` (the pulse reaches 10 % of
     its ∫v² after the record reaches 20 % of its own) and ``low_pgv`` (PGV ≤ 30 cm/s). A
     record is *pulse-like* (Baker's records of engineering interest) if its class is
     ``pulse``, it is not late and PGV > 30 cm/s. Candidate periods 0.2–15 s (our grid).
   * ``"2014"`` (Shahi & Baker 2014): the principal component PC = 0.63 PGV_ratio + 0.777
     energy_ratio and PI = 9.384 (0.76 − PC − 0.0616 PGV)(PC + 6.914·10⁻⁴ PGV − 1.072)
     − 6.179 with PGV in cm/s; class ``pulse`` if PI > 0, else ``non-pulse``; ``late`` if
     the record has ≥ 17 % of its ∫v² by the time the pulse reaches 5 % of its own;
     pulse-like if PI > 0 and not late. Candidate periods 0.25–15 s (their code's). Their
     rotation of two components to the orientation of the strongest pulse is not
     implemented: a component is classified as given.

The Daubechies-4 wavelet comes from PyWavelets (``pywt``): the same function as MATLAB's
``db4`` used by Baker. Our projection uses the unit-energy wavelet at each scale (an
orthogonal least-squares fit of one wavelet), which is the CWT coefficient up to a
constant factor per scale; the choice of scale maximises the coefficient as Baker's does.
The energy ratio uses ∫v² (equal, by Parseval, to the sum of squared coefficients of the
full orthogonal wavelet decomposition that Shahi & Baker's code sums).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import fft

from rockarch.motion.intensity import uniform_samples
from rockarch.motion.signals import GroundMotion

#: Classification methods: Baker (2007) and Shahi & Baker (2014).
METHODS = ("2007", "2014")
#: Number of wavelets summed into the pulse (Baker 2007; Shahi & Baker 2014's code).
N_WAVELETS = 10
#: The wavelets after the first are sought within ± WINDOW·s of its position (s its time
#: scale): ``row_range = 10/25`` of Shahi & Baker's (2014) code. The pulse stays one local
#: feature.
WINDOW = 0.4
#: Candidate pulse periods [s] per method: ours for 2007, Shahi & Baker's (2014) code's
#: ``TpMin = 0.25``, ``TpMax = 15`` for 2014.
TP_RANGE = {"2007": (0.2, 15.0), "2014": (0.25, 15.0)}
#: Baker (2007): logistic pulse indicator 1/(1 + exp(c0 + c1·PGV_ratio + c2·energy_ratio)).
PI_COEF = (-23.3, 14.6, 20.5)
#: Baker (2007): classes pulse (PI above), non-pulse (PI below), ambiguous between.
PI_PULSE, PI_NO_PULSE = 0.85, 0.15
#: Baker (2007): a pulse-like record has PGV > 30 cm/s (strictly) [m/s].
PGV_MIN = 0.30
#: Baker (2007): the pulse is early if it reaches 10 % of its ∫v² before the record
#: reaches 20 % of its own.
EARLY_2007 = (0.10, 0.20)
#: Shahi & Baker (2014): PC = 0.63·PGV_ratio + 0.777·energy_ratio.
PC_COEF_2014 = (0.63, 0.777)
#: Shahi & Baker (2014): PI = k (u − PC − v·PGV)(PC + w·PGV − x) − y, PGV in cm/s, as
#: (k, u, v, w, x, y): the paper's printed form. (Their MATLAB code writes the quadratic
#: in centred variables, with coefficients of its own rounding: near PI = 0 the two
#: differ by up to 0.18 for PGV ≤ 60 cm/s, 0.7 at 150 cm/s.)
PI_COEF_2014 = (9.384, 0.76, 0.0616, 6.914e-4, 1.072, 6.179)
#: Shahi & Baker (2014): late if the record has ≥ 17 % of its ∫v² when the pulse
#: reaches 5 % of its own.
LATE_2014 = (0.05, 0.17)


@dataclass(frozen=True)
class PulseResult:
    """Velocity-pulse classification of one record (``method`` "2007" or "2014").

    ``tp`` [s] is the pseudo-period of the extracted pulse; ``pulse`` its velocity [m/s]
    at ``t`` [s] (uniform samples of the record); ``pgv`` [m/s].
    """

    method: str
    pulse_indicator: float
    tp: float
    pgv_ratio: float
    energy_ratio: float
    late: bool
    pgv: float
    t: np.ndarray
    pulse: np.ndarray

    @property
    def classification(self) -> str:
        """The class of the pulse indicator alone: ``pulse``, ``ambiguous`` or
        ``non-pulse`` (2007: PI > 0.85, between, PI < 0.15; 2014: PI > 0 or not). Lateness
        and a small PGV are the separate flags :attr:`late` and :attr:`low_pgv`."""
        if self.method == "2014":
            return "pulse" if self.pulse_indicator > 0.0 else "non-pulse"
        if self.pulse_indicator > PI_PULSE:
            return "pulse"
        return "non-pulse" if self.pulse_indicator < PI_NO_PULSE else "ambiguous"

    @property
    def low_pgv(self) -> bool:
        """PGV ≤ 30 cm/s: Baker's (2007) third criterion (the 2014 indicator contains PGV
        itself: False there)."""
        return self.method == "2007" and not self.pgv > PGV_MIN

    @property
    def pulse_like(self) -> bool:
        """The method's full criterion: 2007, class ``pulse``, not late, PGV > 30 cm/s;
        2014, PI > 0 and not late."""
        return self.classification == "pulse" and not self.late and not self.low_pgv

    def to_dict(self) -> dict:
        return {"method": self.method, "pulse_indicator": self.pulse_indicator,
                "tp": self.tp, "pgv_ratio": self.pgv_ratio,
                "energy_ratio": self.energy_ratio, "late": self.late,
                "low_pgv": self.low_pgv, "pulse_like": self.pulse_like,
                "classification": self.classification}


def pulse_indicator(pgv_ratio: float, energy_ratio: float, pgv: float,
                    method: str = "2007") -> float:
    """The pulse indicator of Baker (2007) (logistic, in [0, 1]) or of Shahi & Baker (2014)
    (quadratic in PC and PGV) from the residual's PGV and energy ratios and the PGV [m/s]."""
    if method == "2014":
        k, u, v, w, x, y = PI_COEF_2014
        pc = PC_COEF_2014[0] * pgv_ratio + PC_COEF_2014[1] * energy_ratio
        pgv_cm = 100.0 * pgv
        return k * (u - pc - v * pgv_cm) * (pc + w * pgv_cm - x) - y
    c0, c1, c2 = PI_COEF
    z = c0 + c1 * pgv_ratio + c2 * energy_ratio
    return 0.0 if z > 700.0 else 1.0 / (1.0 + math.exp(z))


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


def is_late(v: np.ndarray, pulse: np.ndarray, dt: float, method: str = "2007") -> bool:
    """Whether the pulse arrives late in the record: 2007 (Baker), the pulse reaches 10 %
    of its ∫v² after the record reaches 20 % of its own; 2014 (Shahi & Baker), the record
    has ≥ 17 % of its ∫v² at the last sample where the pulse has ≤ 5 % of its own."""
    if method == "2014":
        frac_pulse, frac_record = LATE_2014
        cum_p, cum_v = np.cumsum(pulse * pulse), np.cumsum(v * v)
        k = max(int(np.searchsorted(cum_p, frac_pulse * cum_p[-1], side="right")) - 1, 0)
        return bool(cum_v[k] >= frac_record * cum_v[-1])
    frac_pulse, frac_record = EARLY_2007
    return _time_at(pulse, frac_pulse, dt) > _time_at(v, frac_record, dt)


def check_method(method) -> str:
    """``method`` as one of :data:`METHODS` (2007 or 2014, given as str or int)."""
    m = str(method).strip()
    if m not in METHODS:
        raise ValueError(f"pulse method must be one of {', '.join(METHODS)}, got {method!r}")
    return m


def baker_pulse(motion: GroundMotion, *, method: str = "2007", tp_min: float | None = None,
                tp_max: float | None = None, n_periods: int = 120,
                n_wavelets: int = N_WAVELETS) -> PulseResult:
    """Pulse indicator, pulse period and extracted pulse of ``motion``: ``method`` "2007"
    (Baker 2007) or "2014" (Shahi & Baker 2014), see the module docstring.

    Candidate pulse periods are ``n_periods`` log-spaced values in [tp_min, tp_max]
    (default :data:`TP_RANGE` of the method; capped at the record's duration); their
    spacing bounds the resolution of Tp.
    """

    method = check_method(method)
    lo, hi_default = TP_RANGE[method]
    tp_min = lo if tp_min is None else tp_min
    tp_max = hi_default if tp_max is None else tp_max
    dt, a = uniform_samples(motion)
    v = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a[:-1] + a[1:]))])
    duration = dt * (v.size - 1)
    x, psi, fc = _db4()
    hi = min(tp_max, duration)
    if not 0 < tp_min < hi:
        raise ValueError(f"pulse periods {tp_min:g}…{tp_max:g} s do not fit a record of "
                         f"{duration:g} s")
    pgv = float(np.max(np.abs(v)))
    if not pgv > 0:
        raise ValueError("the record has no ground velocity (PGV = 0): no pulse to classify")
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
    pgv_ratio = float(np.max(np.abs(residual)) / pgv)
    energy_ratio = float(np.sum(residual**2) / np.sum(v**2))
    pi = pulse_indicator(pgv_ratio, energy_ratio, pgv, method)
    t = float(motion.t[0]) + np.arange(v.size) * dt
    return PulseResult(method=method, pulse_indicator=pi, tp=scale / fc, pgv_ratio=pgv_ratio,
                       energy_ratio=energy_ratio, late=is_late(v, pulse, dt, method),
                       pgv=pgv, t=t, pulse=pulse)
