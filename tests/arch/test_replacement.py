"""Replacement catenary: the thickest band with free springings (theory Eqs. 7.3–7.7)."""

import numpy as np
import pytest

from rockarch.arch import analyse, catenary, circular
from rockarch.arch.band import lower_bound_band
from rockarch.arch.replacement import replacement, replacement_arch
from rockarch.paper.reference import SECT8_BAND, TABLE2


@pytest.fixture(scope="module")
def sect8():
    """The Sect. 8 arch: l = 10 m, half-angle 60°, d = 0.345 m (reference.SECT8_BAND)."""
    return replacement(circular(10.0, SECT8_BAND["rise"], SECT8_BAND["thickness"]))


def _inside(original, arch, shift, samples=801):
    """Signed margin of the band arch's intrados/extrados inside the original (m).

    Independent of the construction: the band's joint end points, shifted into the
    original's coordinates, against the original's joints found by the axis-normal offset
    on a dense independent cut of the original.
    """
    sig = np.linspace(0.0, 1.0, samples)
    bi, be = arch.joints_at(sig)
    pts = np.vstack([bi, be]) + shift
    s_o = np.linspace(0.0, 1.0, 20001)
    p, tan, d = original.axis_at(s_o)
    # nearest original joint along the axis: the point's tangential coordinate vanishes
    margin = np.inf
    for q in pts:
        k = int(np.argmin(np.hypot(*(p - q).T)))
        n = np.array([-tan[k, 1], tan[k, 0]])
        margin = min(margin, 0.5 * d[k] - abs(float(np.dot(q - p[k], n))))
    return margin


def test_sect8_lower_bound_matches_the_independent_construction(sect8):
    """d̄, l′, f′, y0, a within 1 % of the reference construction (reference.SECT8_BAND)."""
    b = sect8.band
    assert b.symmetric and b.axis == "catenary"
    assert b.thickness == pytest.approx(SECT8_BAND["d_bar"], rel=0.01)
    assert b.span == pytest.approx(SECT8_BAND["span"], rel=0.01)
    assert b.rise == pytest.approx(SECT8_BAND["band_rise"], rel=0.01)
    assert b.y0 == pytest.approx(SECT8_BAND["y0"], rel=0.01)
    assert b.a == pytest.approx(SECT8_BAND["a"], rel=0.01)
    # paper Table 2: d̄/l′ = 0.0207 (3 digits: ±0.00005 + 1 %)
    assert b.thickness / b.span == pytest.approx(TABLE2["lower-bound"]["d/l"], rel=0.01)
    # springings ~0.07 m outward along the joints, on the joint segments, at equal heights
    for pt, end in ((b.left, 0.0), (b.right, 10.0)):
        off = np.hypot(pt[0] - end, pt[1])
        assert off == pytest.approx(SECT8_BAND["springing_offset"], abs=0.005)
        assert off < 0.5 * SECT8_BAND["thickness"]
    assert b.left[0] < 0 < 10.0 < b.right[0] and b.left[1] == pytest.approx(b.right[1])
    # the replacement is catenary(l′, f′, d̄) and lies inside the original (to 1e-4 m: the
    # polyline sampling of the check itself)
    lb = sect8.lower_bound
    assert lb.arch.shape == "catenary" and lb.thickness == b.thickness
    assert _inside(circular(10.0, SECT8_BAND["rise"], 0.345), lb.arch, b.left) > -1e-4


def test_sect8_equivalent_matches_table2(sect8):
    eq = sect8.equivalent
    assert eq.ap_min == pytest.approx(sect8.original.ap_min, rel=1e-6)
    assert eq.thickness == pytest.approx(SECT8_BAND["d_equivalent"], rel=0.01)
    assert eq.p == pytest.approx(SECT8_BAND["p_equivalent"], rel=0.01)
    # c2 of both rules against Table 2: 0.10 % and 0.07 % here; 0.2 % allows the paper's
    # fourth digit and the original's ap,min (3.039 vs 3.036, +0.1 %) that d̂ inherits
    assert eq.mechanism.c2 == pytest.approx(TABLE2["equivalent"]["c2"], rel=0.002)
    assert sect8.lower_bound.mechanism.c2 == pytest.approx(TABLE2["lower-bound"]["c2"],
                                                           rel=0.002)
    # the lower bound's ap,min is Table 2's 2.163 m/s² to 1 %
    assert sect8.lower_bound.ap_min == pytest.approx(TABLE2["lower-bound"]["ap_min"],
                                                     rel=0.01)
    js = eq.to_dict()
    assert js["thickness_over_original_span"] == pytest.approx(eq.thickness / 10.0)
    assert js["thickness_over_span"] == pytest.approx(eq.thickness / eq.span)


def test_original_mass_option_moves_c2_by_a_few_tenths_of_a_percent(sect8):
    """The original's mass on the replacement axis: c2 0.3–0.4 % above the own-mass value
    (issue's verified figure), same band."""
    arch = circular(10.0, SECT8_BAND["rise"], SECT8_BAND["thickness"])
    r = replacement(arch, mass="original")
    assert r.band.thickness == pytest.approx(sect8.band.thickness, rel=1e-12)
    rel = r.equivalent.mechanism.c2 / sect8.equivalent.mechanism.c2 - 1
    assert 0.001 < rel < 0.006
    assert r.lower_bound.arch.mass_model == "weights"


def test_replacement_of_a_catenary_is_itself():
    """A uniform catenary's best band is its own axis: springings at the axis springings,
    d̄ = d (to the optimiser's 1e-4 relative and the contour sampling)."""
    b = lower_bound_band(catenary(10.0, 3.0, 0.25))
    assert b.thickness == pytest.approx(0.25, rel=1e-3)
    assert b.span == pytest.approx(10.0, rel=1e-4)
    assert b.rise == pytest.approx(3.0, rel=1e-4)
    assert np.allclose(b.left, [0, 0], atol=1e-3) and np.allclose(b.right, [10, 0], atol=1e-3)


@pytest.fixture(scope="module")
def tapered():
    """Thickness growing left to right: not mirror-symmetric."""
    arch = circular(10.0, 2.89, lambda s: 0.30 + 0.15 * np.asarray(s))
    return arch, lower_bound_band(arch)


def test_non_symmetric_arch(tapered):
    """x_m and the springing heights are free; the band lies inside the original and the
    replacement runs from P_L to P_R."""
    arch, b = tapered
    assert not b.symmetric
    assert abs(b.x_m - 5.0) > 1e-3 and abs(b.left[1] - b.right[1]) > 1e-4
    rep = replacement_arch(b, b.thickness)
    assert _inside(arch, rep, b.left) > -1e-4
    # the replacement's own springings are its ends: P_R − P_L in its coordinates
    end = rep.axis_at(np.array([1.0]))[0][0]
    assert np.allclose(end, b.right - b.left, atol=1e-9)


def test_non_symmetric_band_is_bracketed_by_the_uniform_ones(tapered):
    """The contours are nested (0.30 ⊂ tapered ⊂ 0.45), so are the best bands."""
    _, b = tapered
    thin = lower_bound_band(circular(10.0, 2.89, 0.30)).thickness
    thick = lower_bound_band(circular(10.0, 2.89, 0.45)).thickness
    assert thin < b.thickness < thick


def test_weighted_axis_option():
    """The funicular of the original's mass also fits; for a catenary original it is the same
    axis (the mass per horizontal length of a uniform catenary is its own funicular's)."""
    b = lower_bound_band(catenary(10.0, 3.0, 0.25), axis="weighted")
    assert b.thickness == pytest.approx(0.25, rel=2e-3)
    with pytest.raises(ValueError, match="replacement axis must be one of"):
        lower_bound_band(catenary(10.0, 3.0, 0.25), axis="parabola")


def test_too_thin_for_any_catenary_band():
    """The circle deviates 0.068 m from its best catenary (Chebyshev): d = 0.134 m stands
    (minimum thickness 0.132 m) but holds no catenary band."""
    arch = circular(10.0, 2.89, 0.134)
    assert analyse(arch).ap_min > 0
    with pytest.raises(ValueError, match="no catenary band fits inside this arch .* leaves "
                                         "the contour by 0.00"):
        replacement(arch)
