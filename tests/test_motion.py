"""Ground motions: pulse shapes (paper Fig. 14), interpolation and scaling."""

import numpy as np
import pytest

from rockarch.motion import signals as mo


def test_sine_full_cycle_shape():
    m = mo.sine(2.0, 0.8)
    # linear interpolation of 1000 knots per period: peak error (pi/1000)^2/2 ≈ 5e-6
    assert m(0.2) == pytest.approx(2.0, rel=1e-5)
    assert m(0.6) == pytest.approx(-2.0, rel=1e-5)
    assert m(0.8 + 1e-9) == 0.0 and m(5.0) == 0.0
    assert m.duration == pytest.approx(0.8)
    assert m.pga == pytest.approx(2.0, rel=1e-5)


@pytest.mark.unperturbed  # the pulse is its amplitude exactly, on every machine
def test_square_and_step_have_exact_jumps():
    sq = mo.square(1.5, 1.0)
    assert sq(0.4999999) == 1.5 and sq(0.5000001) == -1.5
    assert sq(1.0000001) == 0.0
    st = mo.step(3.0, 2.0)
    assert st(0.0) == 3.0 and st(1.999999) == 3.0 and st(2.000001) == 0.0


def test_halfsine_harmonic_ricker():
    h = mo.halfsine(1.0, 1.0)
    assert h.duration == pytest.approx(0.5) and h(0.25) == pytest.approx(1.0, rel=1e-5)
    hm = mo.harmonic(1.0, 0.5, cycles=4)
    assert hm.duration == pytest.approx(2.0)
    assert hm(1.625) == pytest.approx(1.0, rel=1e-5)
    r = mo.ricker(2.0, 1.0)
    assert r(1.5) == pytest.approx(2.0, rel=1e-9)  # knot at the centre: exact peak
    assert abs(r(0.0)) < 1e-8 * 2.0  # truncated tails below 1e-8·ap


def test_scaling_to_pga_and_mirroring():
    m = mo.sine(1.0, 1.0).scaled_to_pga(4.0)
    assert m.pga == pytest.approx(4.0)
    assert m.scaled(-1.0)(0.25) == pytest.approx(-4.0, rel=1e-5)
    assert m.normalized().pga == pytest.approx(1.0)
    assert m.fingerprint() != m.scaled(-1).fingerprint()


@pytest.mark.parametrize(
    "call, msg",
    [
        (lambda: mo.sine(1.0, 0.0), "period T must be a finite number > 0"),
        (lambda: mo.sine(-1.0, 1.0), "amplitude ap"),
        (lambda: mo.harmonic(1.0, 1.0, cycles=0), "cycles"),
        (lambda: mo.pulse("sawtooth", period=1.0), "unknown signal"),
        (lambda: mo.GroundMotion([0.0], [1.0]), "at least 2"),
        (lambda: mo.GroundMotion([0.0, 1.0], [np.nan, 1.0]), "non-finite"),
        (lambda: mo.GroundMotion([0.0, 1.0, 0.5], [1.0, 1.0, 1.0]), "non-decreasing"),
        (lambda: mo.GroundMotion([0.0, 1.0], [0.0, 0.0]), "zero everywhere"),
        (lambda: mo.sine(1.0, 1.0).scaled_to_pga(0.0), "target PGA"),
    ],
)
def test_bad_input_is_a_clear_valueerror(call, msg):
    with pytest.raises(ValueError, match=msg):
        call()


def test_repr_is_one_line_without_the_samples():
    # a record's repr printed its 5372 samples (a long screen of numbers in a notebook)
    from rockarch.motion.records import el_centro

    r = repr(el_centro())
    assert "\n" not in r and len(r) < 200
    assert "5372 knots, 53.71 s, PGA 2.754 m/s²" in r
