"""Baker (2007) and Shahi & Baker (2014) pulse indicators and period
(rockarch.motion.velocity_pulse)."""

import math

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
    assert res.classification == "pulse"  # the class is the indicator's; late is a flag
    res14 = vp.baker_pulse(_from_velocity(v), method="2014")
    assert res14.late and res14.classification == "pulse" and not res14.pulse_like


def _result(**kw):
    base = {"method": "2007", "pulse_indicator": 0.9, "tp": 1.0, "pgv_ratio": 0.1,
            "energy_ratio": 0.1, "late": False, "pgv": 0.5, "t": np.zeros(1),
            "pulse": np.zeros(1)}
    return vp.PulseResult(**{**base, **kw})


def test_2007_class_is_the_indicator_alone_and_pgv_must_exceed_30_cm_s():
    assert [_result(pulse_indicator=x).classification for x in (0.9, 0.5, 0.1)] == \
        ["pulse", "ambiguous", "non-pulse"]
    at_limit = _result(pgv=0.30)  # Baker (2007): PGV > 30 cm/s, strictly
    assert at_limit.low_pgv and at_limit.classification == "pulse" and not at_limit.pulse_like
    assert _result(pgv=0.3001).pulse_like
    late = _result(late=True)
    assert late.classification == "pulse" and not late.pulse_like and not late.low_pgv
    assert _result(pulse_indicator=0.5).pulse_like is False  # ambiguous is not pulse-like
    d = _result(pgv=0.2).to_dict()
    assert d["classification"] == "pulse" and d["low_pgv"] and not d["pulse_like"]
    # 2014: two classes by the sign of PI; PGV enters PI, no separate PGV flag
    assert _result(method="2014", pulse_indicator=0.3, pgv=0.2).pulse_like
    assert _result(method="2014", pulse_indicator=-0.3).classification == "non-pulse"


def test_late_rules_of_2007_and_2014():
    v = np.ones(100)  # the record's ∫v² grows uniformly: 1 % per sample
    early, late = np.zeros(100), np.zeros(100)
    early[10:20] = 1.0
    late[25:35] = 1.0
    # 2007: the pulse's 10 % (sample 10 / 25) against the record's 20 % (sample 19)
    assert not vp.is_late(v, early, 0.01, "2007") and vp.is_late(v, late, 0.01, "2007")
    # 2014: the record's share where the pulse last has <= 5 %: 11 % and 26 % against 17 %
    assert not vp.is_late(v, early, 0.01, "2014") and vp.is_late(v, late, 0.01, "2014")


def test_pulse_indicators_of_the_papers():
    # Baker (2007): a residual of nothing is a sure pulse, of everything a sure non-pulse
    assert vp.pulse_indicator(0.0, 0.0, 1.0) == pytest.approx(1.0, abs=1e-9)
    assert vp.pulse_indicator(1.0, 1.0, 1.0) < 1e-5
    # on the line 14.6 r_pgv + 20.5 r_e = 23.3 + ln(1/0.85 − 1) the indicator is 0.85
    r_e = 0.3
    r_pgv = (23.3 + math.log(1 / 0.85 - 1) - 20.5 * r_e) / 14.6
    assert vp.pulse_indicator(r_pgv, r_e, 1.0) == pytest.approx(0.85, abs=1e-12)

    # Shahi & Baker (2014): the printed form against the centred quadratic of the authors'
    # MATLAB code (an independent rounding of the same fit): within 0.18 near PI = 0 for
    # PGV <= 60 cm/s (the two roundings differ by up to 0.175 there, measured)
    def matlab(pc, pgv_cm):
        p, q = (pc - 1.208421) / 0.2462717, (pgv_cm - 11.58861) / 18.88015
        return (-7.817 - 0.5679 * p**2 - 0.1516 * q**2 - 3.0253 * p - 1.7396 * q
                - 2.7156 * p * q)

    for pc in np.linspace(0.2, 1.2, 21):
        for pgv_cm in np.linspace(0.0, 60.0, 21):
            ours = vp.pulse_indicator(pc / 0.63, 0.0, pgv_cm / 100, "2014")
            if abs(ours) < 2:
                assert ours == pytest.approx(matlab(pc, pgv_cm), abs=0.18)


def test_2014_method_on_a_wavelet_and_on_noise():
    x, psi, fc = vp._db4()
    w = vp._wavelet(x, psi, 1.5 * fc, DT)
    v = np.zeros(4000)
    v[500:500 + w.size] = 0.5 * w / np.abs(w).max()
    res = vp.baker_pulse(_from_velocity(v), method="2014")
    assert res.method == "2014" and res.pulse_like and res.pulse_indicator > 0
    grid_step = (15.0 / 0.25) ** (1 / 119) - 1  # 2014's candidate periods: 0.25-15 s
    assert res.tp == pytest.approx(1.5, rel=grid_step)
    p = sy.RDKParameters(arias=2.0, d5_95=30.0, t_mid=20.0, f_mid=3.0, f_slope=0.0,
                         zeta_f=0.3)
    for seed in range(2):
        assert not vp.baker_pulse(sy.generate(p, seed), method="2014").pulse_like
    with pytest.raises(ValueError, match="pulse method"):
        vp.baker_pulse(_from_velocity(v), method="2010")
