"""Arch geometry and voussoir discretisation (docs/theory.md §4)."""

import math

import numpy as np
import pytest

from rockarch.arch import (
    catenary,
    catenary_parameter,
    circular,
    elliptical,
    from_contour,
    horizontal_weights,
    mass_per_horizontal_length,
    pointed,
    polyline,
    voussoirs,
    weighted_catenary,
)


def test_catenary_passes_through_springings_and_crown():
    a = catenary(10.0, 3.0, 0.2)
    p, t, _ = a.axis_at(np.array([0.0, 0.5, 1.0]))
    # brentq to 1e-15 on the parameter: positions exact to rounding
    assert np.allclose(p, [[0, 0], [5, 3], [10, 0]], atol=1e-9)
    assert np.allclose(t[1], [1, 0], atol=1e-12)
    ca = catenary_parameter(10.0, 3.0)
    assert ca * (math.cosh(5.0 / ca) - 1) == pytest.approx(3.0, rel=1e-12)


def test_circular_voussoir_mass_centroid_and_inertia_are_exact_annular_sectors():
    r, d, n = 5.0, 1.0, 10
    v = voussoirs(circular(10.0, 5.0, d), n)
    half = math.pi / (2 * n)  # half angle of each voussoir
    ri, re = r - d / 2, r + d / 2
    area = half * (re**2 - ri**2)
    # centroid of an annular sector: 2 sin(b)/(3b) (re^3 - ri^3)/(re^2 - ri^2)
    rc = 2 * math.sin(half) / (3 * half) * (re**3 - ri**3) / (re**2 - ri**2)
    jo = 0.5 * half * 2 * (re**4 - ri**4) / 2  # polar moment about the centre: b (re^4-ri^4)/2
    j = jo - area * rc**2
    # 200 chords per voussoir: polygon vs true arcs differ by O((b/200)^2) ~ 1e-7 relative
    assert np.allclose(v.mass, area, rtol=1e-6)
    assert np.allclose(np.hypot(v.centroid[:, 0] - 5, v.centroid[:, 1]), rc, rtol=1e-6)
    assert np.allclose(v.inertia, j, rtol=1e-5)


def test_voussoir_centroid_shifts_outward_by_kappa_d2_over_12():
    r, d = 5.0, 0.5
    v = voussoirs(circular(10.0, 5.0, d), 400)
    shift = np.hypot(v.centroid[:, 0] - 5, v.centroid[:, 1]) - r
    # annular sector of half angle b: r_c = r + d^2/(12 r) - r b^2/6 + ...; with b = pi/800
    # the chord term r b^2/6 = 1.3e-5 m is 0.3 % of kappa d^2/12 = 4.2e-3 m: allow 0.5 %
    assert np.allclose(shift, d**2 / (12 * r), rtol=5e-3)
    # against the exact sector formula; 5 chords per voussoir arc: error ~ r (b/5)^2/3 ~ 1e-6 m
    b, ri, re = math.pi / 800, r - d / 2, r + d / 2
    rc = 2 * math.sin(b) / (3 * b) * (re**3 - ri**3) / (re**2 - ri**2)
    assert np.allclose(shift, rc - r, atol=2e-6)
    va = voussoirs(circular(10.0, 5.0, d, mass_model="axis"), 400)
    assert np.all(np.hypot(va.centroid[:, 0] - 5, va.centroid[:, 1]) < r)  # on the chord side
    assert np.allclose(va.mass.sum(), v.mass.sum(), rtol=1e-6)


def test_uniform_thickness_area_is_thickness_times_axis_length():
    for arch in (catenary(8, 2, 0.3), elliptical(8, 3, 0.3), circular(8, 2, 0.3)):
        v = voussoirs(arch, 50)
        assert v.mass.sum() == pytest.approx(0.3 * arch.length, rel=1e-6)


def test_varying_thickness_and_joints_normal_to_axis():
    a = catenary(10, 3, lambda s: 0.2 + 0.2 * np.abs(2 * s - 1))
    v = voussoirs(a, 20)
    assert v.thickness[0] == pytest.approx(0.4)
    assert v.thickness[10] == pytest.approx(0.2)
    joint = v.extrados - v.intrados
    assert np.allclose(np.sum(joint * v.tangent, axis=1), 0.0, atol=1e-12)


def test_pointed_arch_has_vertical_crown_joint_and_symmetry():
    v = voussoirs(pointed(10, 7, 0.5), 20)
    assert v.intrados[10, 0] == pytest.approx(5.0)
    assert v.extrados[10, 0] == pytest.approx(5.0)
    assert np.allclose(v.mass, v.mass[::-1], rtol=1e-9)


def test_contour_arch_matches_uniform_arch():
    a = circular(10, 5, 0.5)
    sig = np.linspace(0, 1, 3001)
    ip, ep = a.joints_at(sig)
    b = from_contour(ip, ep)
    va, vb = voussoirs(a, 30), voussoirs(b, 30)
    # polylines of 3000 chords: areas agree to ~1e-6
    assert vb.mass.sum() == pytest.approx(va.mass.sum(), rel=1e-5)


@pytest.mark.parametrize("call, msg", [
    (lambda: catenary(0, 3, 0.2), "span"),
    (lambda: catenary(10, -3, 0.2), "rise"),
    (lambda: catenary(10, 3, 0), "thickness"),
    (lambda: circular(10, 2, 30), "too large"),
    (lambda: circular(10, 6, 0.2), "rise <= span/2"),
    (lambda: pointed(10, 4, 0.2), "rise > span/2"),
    (lambda: polyline([[0, 0], [2, 2], [1, 2], [1.5, 0.5], [3, 0]], 0.1), "intersects itself"),
    (lambda: voussoirs(catenary(10, 3, 0.2), 3), "at least 4"),
])
def test_bad_geometry_raises_one_clear_valueerror(call, msg):
    with pytest.raises(ValueError, match=msg):
        call()


def test_weighted_catenary_with_uniform_arc_weight_is_the_catenary():
    w = weighted_catenary(10, 3, 0.2, weights_per_arc=lambda s: np.ones_like(s))
    c = catenary(10, 3, 0.2)
    x = np.linspace(0, 1, 101)
    # 4000-bin histogram of the weight: axis error O(h^2) ~ 1e-7 of the span
    assert np.allclose(w.axis_at(x)[0], c.axis_at(x)[0], atol=1e-6 * 10)


def test_weighted_catenary_with_uniform_horizontal_weight_is_a_parabola():
    w = weighted_catenary(10, 3, 0.2, weights=lambda x: np.ones_like(x))
    x = np.linspace(0, 10, 11)
    _, y, _, _ = w.axis_fn(x / 10)
    assert np.allclose(y, 4 * 3 * x * (10 - x) / 100, atol=1e-12)


def test_weighted_catenary_from_another_arch_keeps_its_mass():
    circ = circular(10, 2.89, 0.346)
    q = mass_per_horizontal_length(circ)
    rep = weighted_catenary(10, 2.89, 0.293, weights=q)
    v = voussoirs(rep, 100)
    # both are polygon sums (4000 vs 2000 chords): equal to ~1e-7
    assert v.mass.sum() == pytest.approx(voussoirs(circ, 100).mass.sum(), rel=1e-6)
    assert rep.mass_model == "weights"


def test_horizontal_weights_rejects_bad_input():
    with pytest.raises(ValueError, match="increase"):
        horizontal_weights([0, 2, 1], [1, 1])
    with pytest.raises(ValueError, match=">= 0"):
        horizontal_weights([0, 1, 2], [1, -1])


def test_an_arch_in_millimetres_is_warned_about():
    # 10 000 m read from sizes in mm runs as a 10 km arch (p = 0.116 1/s) with nothing said;
    # blocks and assembly files warn already (docs/assemblies.md)
    import warnings

    from rockarch.arch.geometry import make_arch
    from rockarch.motion.records import UnitsWarning

    with pytest.warns(UnitsWarning, match="spans 1e\\+04 m: sizes are in metres"):
        make_arch("circular", 10000, 2890, 350)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        make_arch("circular", 10, 2.89, 0.35)  # the Sect. 9 arch: quiet
