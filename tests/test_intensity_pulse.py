"""Baker (2007) pulse indicator and period (rockarch.motion.velocity_pulse)."""

import numpy as np
import pytest

from rockarch.motion import synthetic as sy
from rockarch.motion import velocity_pulse as vp
from rockarch.motion.signals import GroundMotion

DT = 0.01
# candidate periods: 120 log-spaced in [0.2, 15] s, neighbours 3.7 % apart
GRID_STEP = (15.0 / 0.2) ** (1 / 119) - 1


def _from_velocity(v):
    return GroundMotion(np.arange(v.size) * DT, np.gradient(v, DT))


def test_a_velocity_that_is_a_db4_wavelet_is_a_pulse_of_its_pseudo_period():
    x, psi, fc = vp._db4()
    tp = 1.5
    w = vp._wavelet(x, psi, tp * fc, DT)
    v = np.zeros(4000)
    v[500:500 + w.size] = 0.5 * w / np.abs(w).max()  # PGV 0.5 m/s
    res = vp.baker_pulse(_from_velocity(v))
    assert res.pulse_like and res.classification == "pulse"
    assert res.tp == pytest.approx(tp, rel=GRID_STEP)
    assert res.energy_ratio < 1e-3  # the pulse is the whole record


def test_a_one_cycle_sine_velocity_pulse_is_found_near_its_period():
    # db4 is not a sine: its best-fitting pseudo-period is ~10 % longer (measured 2.19 s)
    t = np.arange(0, 30, DT)
    period = 2.0
    v = np.where((t > 3) & (t < 3 + period), 0.6 * np.sin(2 * np.pi * (t - 3) / period), 0.0)
    res = vp.baker_pulse(_from_velocity(v))
    assert res.pulse_like
    assert res.tp == pytest.approx(period, rel=0.15)


def test_stationary_filtered_noise_is_not_pulse_like():
    p = sy.RDKParameters(arias=2.0, d5_95=30.0, t_mid=20.0, f_mid=3.0, f_slope=0.0,
                         zeta_f=0.3)
    for seed in range(3):
        res = vp.baker_pulse(sy.generate(p, seed))
        assert res.pulse_indicator < vp.PI_PULSE and not res.pulse_like


def test_a_pulse_at_the_end_of_a_record_is_late():
    x, psi, fc = vp._db4()
    w = vp._wavelet(x, psi, 1.0 * fc, DT)
    rng = np.random.default_rng(0)
    v = np.convolve(rng.standard_normal(6000), np.ones(20) / 20, mode="same") * 0.2
    v[-800:-800 + w.size] += 0.8 * w / np.abs(w).max()
    res = vp.baker_pulse(_from_velocity(v))
    assert res.late and not res.pulse_like
    assert res.pulse_indicator > vp.PI_PULSE  # a clear pulse, but after most of the motion
