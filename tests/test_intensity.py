"""Intensity measures against closed forms (rockarch.motion.intensity; docs/theory.md
Sect. 11.1)."""

import math

import numpy as np
import pytest

import rockarch as ra
from rockarch.core.constants import G
from rockarch.motion import intensity as im
from rockarch.motion.records import el_centro
from rockarch.motion.signals import GroundMotion

# Peak sampling error of the Sa recurrence: the recurrence is exact at its sub-steps, a
# peak between them is missed by at most 1 - cos(pi/N) <= (pi/N)^2/2 = 2.2e-4 (N = 150).
SA_RTOL = 3e-4


def _sine(amp, period, cycles, knots_per_period=1000):
    n = int(cycles * knots_per_period)
    t = np.linspace(0.0, cycles * period, n + 1)
    return GroundMotion(t, amp * np.sin(2 * np.pi * t / period))


def test_sa_of_a_step_is_the_dynamic_amplification_closed_form():
    # constant a0 from t = 0: first peak u = a0/w^2 (1 + exp(-zeta pi / sqrt(1 - zeta^2)))
    zeta, a0 = 0.05, 1.7
    m = GroundMotion(np.array([0.0, 0.0, 30.0]), np.array([0.0, a0, a0]))
    sa = im.spectral_acceleration(m, [0.2, 1.0, 3.0], zeta)
    exact = a0 * (1 + math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2)))
    np.testing.assert_allclose(sa, exact, rtol=SA_RTOL)


@pytest.mark.parametrize("r", [0.6, 1.0, 1.4])
def test_oscillator_reaches_the_steady_state_amplitude_under_a_sine(r):
    # u0 = (A/w^2) / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = forcing / natural frequency;
    # the transient decays as exp(-zeta w t) = exp(-0.05 * 2 pi * 100) ~ 1e-14 by t = 100 s
    period, zeta, amp = 1.0, 0.05, 2.0
    w = 2 * math.pi / period
    m = _sine(amp, period / r, cycles=int(150 * r), knots_per_period=400)
    t, u = im.oscillator_history(m, period, zeta)
    u0 = amp / w**2 / math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
    assert np.max(np.abs(u[t > 100.0])) == pytest.approx(u0, rel=SA_RTOL)


def test_recurrence_coefficients_equal_nigam_jennings_closed_form():
    # the homogeneous block of exp(K h): Nigam & Jennings (1969) A matrix, written out
    w, z, h = 2 * math.pi / 0.7, 0.05, 0.004
    wd = w * math.sqrt(1 - z * z)
    e, s, c = math.exp(-z * w * h), math.sin(wd * h), math.cos(wd * h)
    q = z / math.sqrt(1 - z * z)
    a = [e * (q * s + c), e * s / wd, -w / math.sqrt(1 - z * z) * e * s, e * (c - q * s)]
    coef = im._oscillator_coefficients(w, z, h)
    np.testing.assert_allclose(coef[:4], a, rtol=1e-12, atol=1e-15)
    # constant a_g over h (no slope): u(h) = -(a/w^2)(1 - e (c + q s)) from rest
    np.testing.assert_allclose(coef[4], -(1 - e * (c + q * s)) / w**2, rtol=1e-9)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.5])
def test_recurrence_coefficients_equal_the_matrix_exponential(zeta):
    # independent route: exp(K h) of the augmented state [u, u', a_g, a_g'] (theory Eq. 11.6)
    from scipy.linalg import expm

    w, h = 2 * math.pi / 0.3, 0.002
    k = np.array([[0, 1, 0, 0], [-w * w, -2 * zeta * w, -1, 0], [0, 0, 0, 1], [0, 0, 0, 0]])
    phi = expm(k * h)
    ref = [phi[0, 0], phi[0, 1], phi[1, 0], phi[1, 1], phi[0, 2], phi[1, 2],
           phi[0, 3] / h, phi[1, 3] / h]
    scale = np.array([1, h, w * w * h, 1, h * h, h, h * h, h])  # size of each coefficient
    np.testing.assert_allclose(im._oscillator_coefficients(w, zeta, h) / scale,
                               np.array(ref) / scale, rtol=0, atol=1e-9)


def test_sa_tends_to_pga_for_a_rigid_oscillator():
    # T = 0.01 s is 4x shorter than the shortest period the PEER filter keeps (25 Hz
    # corner): the oscillator follows the ground, Sa = PGA within 1 %
    m = el_centro()
    assert im.spectral_acceleration(m, 0.01)[0] == pytest.approx(m.pga, rel=0.01)


def test_sa_pgv_pgd_scale_linearly_and_arias_quadratically():
    m = el_centro(270)
    k = 2.5
    m2 = m.scaled(k)
    np.testing.assert_allclose(im.spectral_acceleration(m2, [0.3, 1.0]),
                               k * im.spectral_acceleration(m, [0.3, 1.0]), rtol=1e-12)
    assert im.pgv(m2) == pytest.approx(k * im.pgv(m), rel=1e-12)
    assert im.pgd(m2) == pytest.approx(k * im.pgd(m), rel=1e-12)
    assert im.arias(m2) == pytest.approx(k * k * im.arias(m), rel=1e-12)
    assert im.significant_duration(m2) == pytest.approx(im.significant_duration(m), abs=1e-9)


def test_arias_of_a_sine_is_pi_a2_l_over_4g():
    # Ia = pi/(2g) * A^2 L / 2 over whole cycles; piecewise-linear sampling with 1000 knots
    # a period changes the mean square by ~(pi/1000)^2/3 ~ 3e-6 relative
    amp, period, cycles = 3.0, 0.4, 25
    m = _sine(amp, period, cycles)
    exact = math.pi / (2 * G) * amp**2 * cycles * period / 2
    assert im.arias(m) == pytest.approx(exact, rel=1e-5)


def test_pgv_of_a_sine_pulse_and_of_a_ramp_through_zero():
    amp, period = 2.0, 0.8
    m = _sine(amp, period, 1)
    # v(T/2) = A T / pi; the chords of a sine with 1000 knots a period lose ~(pi/1000)^2/3
    assert im.pgv(m) == pytest.approx(amp * period / math.pi, rel=1e-5)
    # a = 1 -> -1 linearly over 1 s: v peaks mid-step (no knot there) at 1/4 m/s
    ramp = GroundMotion(np.array([0.0, 1.0]), np.array([1.0, -1.0]))
    assert im.pgv(ramp) == pytest.approx(0.25, rel=1e-12)


def test_pgd_of_a_harmonic_displacement_after_baseline_correction():
    # a = -A w^2 sin(wt) from rest: v = A w (cos wt - 1), u = A sin wt - A w t. The order-1
    # baseline removes the constant velocity offset (the drift A w t): u = A sin wt, PGD = A.
    amp, period, cycles = 0.05, 0.5, 20
    w = 2 * math.pi / period
    t = np.linspace(0.0, cycles * period, cycles * 1000 + 1)
    m = GroundMotion(t, -amp * w * w * np.sin(w * t))
    assert im.pgd(m) == pytest.approx(amp, rel=1e-4)  # ∫cos·t over whole cycles = 0
    assert im.pgd(m, order=-1) > 10 * amp  # uncorrected: the drift dominates


def test_significant_duration_of_a_stationary_sine_is_90_percent_of_it():
    # Husid function of a constant-amplitude sine rises linearly up to a ripple of T/(4 pi)
    period, cycles = 0.25, 80
    m = _sine(1.0, period, cycles)
    assert im.significant_duration(m) == pytest.approx(0.9 * cycles * period,
                                                       abs=period / 4)


def test_mean_period_of_a_sine_of_whole_cycles_is_its_period():
    # N samples spanning exactly k cycles: all Fourier amplitude lies in bin k, Tm = 1/f
    dt, period, cycles = 0.01, 0.5, 40
    n = int(round(cycles * period / dt))
    t = np.arange(n) * dt
    m = GroundMotion(t, np.sin(2 * np.pi * t / period))
    assert im.mean_period(m) == pytest.approx(period, rel=1e-9)


def test_measures_of_el_centro_and_im_value():
    m = el_centro()
    x = im.measures(m, periods=[0.5, 1.0])
    d = x.to_dict()
    assert set(d) >= {"pga", "pgv", "pgd", "arias", "d5_95", "tm", "periods", "sa"}
    assert d["pga"] == pytest.approx(0.281 * 9.80665, rel=1e-3)  # PEER: 0.281 g
    assert im.im_value(m, "sa", period=1.0) == pytest.approx(d["sa"][1], rel=1e-12)
    assert im.im_value(m, "PGV") == pytest.approx(d["pgv"])
    assert 0.1 < d["tm"] < 2.0 and 5.0 < d["d5_95"] < m.duration


@pytest.mark.parametrize("call, match", [
    (lambda m: im.im_value(m, "sa"), "needs a period"),
    (lambda m: im.im_value(m, "cav"), "unknown intensity measure"),
    (lambda m: im.spectral_acceleration(m, [0.0]), "periods of Sa.T. must lie in"),
    (lambda m: im.spectral_acceleration(m, [1.0], damping=1.0), "damping"),
    (lambda m: im.significant_duration(m, 0.9, 0.1), "lower fraction < upper"),
    (lambda m: im.pgd(m, order=9), "baseline order"),
])
def test_bad_arguments_give_one_clear_error(call, match):
    with pytest.raises(ValueError, match=match):
        call(el_centro())


def test_sa_of_a_square_pulse_keeps_its_jumps():
    # square pulse of 4 knots (+a for T/2, -a for T/2) resampled for the recurrence. An
    # oscillator 50x faster settles at +a/w² by T/2 (transient e^(-zeta w T/2) = 4e-4); the
    # jump to -a then is a step of -2a from rest: peak a/w² (1 + 2 e^(-zeta pi/sqrt(1-z²)))
    zeta = 0.05
    m = ra.pulse("square", period=0.5)
    sa = im.spectral_acceleration(m, [0.01], zeta)[0]
    exact = 1 + 2 * math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    assert m.t.size == 4
    assert sa == pytest.approx(exact, rel=2e-3)  # transient 4e-4 x 2, jump spread 1e-4 T
