"""A general assembly's reference values follow its mechanism's finite motion (Eq. (10.5b)):
an arch's p and δ are those of its four-hinge mechanism (docs/theory.md §5), computed by an
independent code (rockarch.arch.fourhinge: closed-form closure of the four-bar linkage)."""

import math

import numpy as np
import pytest

from rockarch import mdof
from rockarch.arch import catenary, circular, pointed
from rockarch.arch.fourhinge import analyse
from rockarch.mdof import builders as bd
from rockarch.mdof.linkage import linkage
from rockarch.mdof.statics import equivalent_block, limit_analysis


def _general(a):
    """The chain's blocks and joints through the general limit analysis (Eqs. 10.4, 10.5b)."""
    return limit_analysis(a.mass, a.inertia, a.centroid, a.corners, a.normal, a.body_a,
                          a.body_b, None, g=a.g)


@pytest.mark.parametrize("arch, n", [
    (catenary(10.0, 3.0, 0.25), 20),   # the README's arch
    (catenary(10.0, 2.0, 0.5), 12),    # thick and flat: u(θ) far from linear
    (catenary(10.0, 3.0, 0.05), 20),   # thin: δ = 0.012
    (circular(6.0, 3.0, 0.4), 9),      # semicircular
    (pointed(10.0, 6.0, 0.5), 14),
])
def test_an_arch_through_the_general_statics_has_its_four_hinge_p_and_delta(arch, n):
    chain = mdof.arch_assembly(arch, n)   # p_ref, delta_ref from rockarch.arch.fourhinge
    c = _general(chain)
    assert c.lambda_ == pytest.approx(chain.ap_min / chain.g, rel=1e-9)
    # both are root finds of V'(u) = 0 to ~1e-12 on the same hinges; 1e-8 leaves room for
    # the LP's duals (1e-9) and a machine's last bits
    assert c.delta == pytest.approx(chain.delta_ref, rel=1e-8)
    assert c.p == pytest.approx(chain.p_ref, rel=1e-8)
    # Eq. (10.5) alone, the initial estimate tan δ = ap,min/g, is far from it
    p_lin, delta_lin = equivalent_block(chain.mass, chain.inertia, c.velocity, chain.g)
    assert delta_lin == pytest.approx(math.atan(c.lambda_), rel=1e-6)
    assert delta_lin > 1.1 * c.delta


def _semicircle(n=9, ri=2.8, re=3.2):
    ang = np.pi * (1 - np.arange(n + 1) / n)
    return [[[ri * np.cos(a), ri * np.sin(a)], [re * np.cos(a), re * np.sin(a)],
             [re * np.cos(b), re * np.sin(b)], [ri * np.cos(b), ri * np.sin(b)]]
            for a, b in zip(ang[:-1], ang[1:], strict=True)]


def test_an_arch_given_as_polygons_has_the_built_in_arch_s_p_and_delta():
    poly = bd.from_polygons(_semicircle())
    four = analyse(circular(6.0, 3.0, 0.4), 9)
    # the polygons' straight intrados and extrados change the voussoirs' masses by ~1-2 %
    # (ap,min 1.8 % apart); p and δ follow within 2 % (measured 0.4 % and 1.9 %). Before
    # Eq. (10.5b): p 2.615 (-26 %), δ 0.099 (+84 %)
    assert poly.ap_min == pytest.approx(four.ap_min, rel=0.02)
    assert poly.p_ref == pytest.approx(four.p, rel=0.02)
    assert poly.delta_ref == pytest.approx(four.delta, rel=0.02)


@pytest.mark.parametrize("make", [
    lambda: bd.from_polygons([[[0, 0], [0.4, 0], [0.4, 1.2], [0, 1.2]]]),   # one block
    lambda: bd.wall(4, 3, 0.4, 0.2),                                        # a wedge
    lambda: bd.colonnade(2, 0.3, 1.8, 1.2, 0.3),                            # a trilithon
    lambda: bd.colonnade(3, 0.3, 1.5, 1.0, 0.25, drums=2),                  # rocking frame
])
def test_one_rigid_part_and_rocking_frames_keep_eq_10_5_exactly(make):
    a = make()
    c = _general(a)
    p_lin, delta_lin = equivalent_block(a.mass, a.inertia, c.velocity, a.g)
    # their neutral angle is tan δ = Q_y/Q_x itself: Housner's α for a block, the columns'
    # for a frame (docs/theory.md Eq. 10.5), bit for bit
    assert (c.p, c.delta) == (p_lin, delta_lin)


def test_the_leading_part_of_an_arch_on_piers_is_the_pier_on_the_side_it_falls_to():
    b = bd.bridge(catenary(10.0, 3.0, 0.25), 10, pier_height=3.0, pier_width=1.5)
    c = _general(b)
    lk = linkage(b.mass, b.centroid, b.corners, b.body_a, b.body_b, c.velocity, c.direction)
    assert len(lk.mass) == 3 and len(lk.hinges) == 4   # a four-hinge linkage with a pier
    lead = [h for h in lk.hinges if lk.coordinate in h[:2] and -1 in h[:2]]
    x_lead = lead[0][2][0]
    xs = [h[2][0] for h in lk.hinges if -1 in h[:2]]
    assert c.direction * x_lead == min(c.direction * x for x in xs)
    # its neutral angle is smaller than the initial estimate, and p larger
    p_lin, delta_lin = equivalent_block(b.mass, b.inertia, c.velocity, b.g)
    assert c.delta < delta_lin and c.p > p_lin
