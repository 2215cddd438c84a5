"""SDOF mechanisms in motion: block equivalence, rocking frame, four-hinge arch dynamics."""

import math

import numpy as np
import pytest

from rockarch import systems
from rockarch.arch import catenary, circular, polyline
from rockarch.arch.fourhinge import analyse, generalized_inertia, potential
from rockarch.motion import signals as mo
from rockarch.motion.records import el_centro
from rockarch.rocking import mechanism as mc
from rockarch.rocking.block import RigidBlock, simulate, simulate_batch
from rockarch.rocking.fourhinge_motion import (
    fourhinge_mechanism,
    impact_coefficient,
    mirror_impact_coefficient,
)
from rockarch.spectra import oas as spectra


def _eq12(alpha):
    """Paper Eq. 12 applied to a block gives p² = (3g/4R)·sin(alpha)/alpha."""
    return math.sqrt(math.sin(alpha) / alpha)


def test_tabulated_block_reproduces_block_py():
    """Same physics through the table model: histories agree to the table accuracy (~1e-9)
    and the overturning maps on El Centro are identical."""
    alpha = 0.15
    b = RigidBlock(2.5, alpha)
    m = mc.from_block(2.5, alpha)
    assert m.p == pytest.approx(2.5 * _eq12(alpha), rel=1e-12)
    assert m.ap_min == pytest.approx(b.ap_min, rel=1e-12)
    rec = el_centro()
    mot = rec.scaled(1.5 * b.ap_min / rec.pga)
    r1, r2 = simulate(b, mot), mc.simulate(m, mot)
    assert r1.impacts == r2.impacts
    n = min(r1.t.size, r2.t.size, 2000)
    assert np.abs(r1.theta[:n] - r2.u[:n]).max() < 1e-7
    p = np.linspace(0.5, 10, 25)
    pp, rr = np.meshgrid(p, np.linspace(1, 5, 25), indexing="ij")
    o1 = simulate_batch(RigidBlock(1.0, alpha), rec, pp, rr).overturned
    o2 = mc.simulate_batch(m, rec, pp * _eq12(alpha), rr).overturned
    assert np.array_equal(o1, o2)


@pytest.mark.parametrize("signal", ["sine", "square", "step"])
def test_generic_mechanism_matches_block_to_order_alpha_squared(signal):
    """The equivalence form phi'' = p²(phi − 1 + a/ap,min) is the slender limit of Housner's
    equation: OAS boundaries differ by O(alpha²) (measured ≈ 0.3·alpha²)."""
    p = np.array([1.0, 2.0, 4.0, 8.0])
    ratio = np.linspace(1, 8, 29)
    m = mo.pulse(signal, period=1.0)
    dev = []
    for alpha in (0.1, 0.01):
        bb = spectra.compute_oas(systems.BlockSystem(alpha=alpha), m, p, ratio, tol=1e-6,
                                 progress=False).boundary.values
        mech = mc.generic(2.0, alpha, 9.81 * math.tan(alpha))
        bm = spectra.compute_oas(systems.MechanismSystem(mech), m, p, ratio, tol=1e-6,
                                 progress=False).boundary.values
        dev.append(np.nanmax(np.abs(bm / bb - 1)))
    assert dev[0] < 0.5 * 0.1**2 and dev[1] < 0.5 * 0.01**2


def test_rocking_frame():
    alpha, pc = 0.12, 2.0
    # gamma = 0: two independent blocks
    f0 = mc.rocking_frame(alpha, pc, 0.0)
    b0 = mc.from_block(pc, alpha)
    assert f0.p == pytest.approx(b0.p, rel=1e-12)
    assert f0.plus.e_close == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-12)
    gamma = 0.7
    f = mc.rocking_frame(alpha, pc, gamma)
    # Makris & Vassiliou: p² = (3g/4R)(1+2γ)/(1+3γ), times sin(α)/α of Eq. 12
    assert f.p == pytest.approx(pc * math.sqrt((1 + 2 * gamma) / (1 + 3 * gamma))
                                * _eq12(alpha), rel=1e-12)
    assert f.ap_min == pytest.approx(9.81 * math.tan(alpha), rel=1e-12)
    # impact coefficient against an explicit projection of the velocity fields (per unit
    # column mass; R = 1): columns spin about the closing/opening corners, lintel translates
    c, s = math.cos(alpha), math.sin(alpha)
    mass = np.array([1, 1, 1, 1, 2 * gamma, 2 * gamma])  # column L, R (x, y), then lintel
    inertia = 1.0 / 3.0
    j_old = np.array([-c, s, -c, s, -2 * c, 2 * s])
    j_new = np.array([c, s, c, s, 2 * c, 2 * s])
    spin_old, spin_new = np.array([1.0, 1.0]), np.array([-1.0, -1.0])
    cross = mass @ (j_old * j_new) + inertia * spin_old @ spin_new
    norm = mass @ (j_new * j_new) + inertia * spin_new @ spin_new
    assert f.plus.e_close == pytest.approx(-cross / norm, rel=1e-12)


@pytest.fixture(scope="module")
def arch_mech():
    return fourhinge_mechanism(catenary(10.0, 3.0, 0.25))


def test_fourhinge_parameters_match_statics(arch_mech):
    res = analyse(catenary(10.0, 3.0, 0.25))
    assert arch_mech.p == pytest.approx(res.p, rel=1e-9)
    assert arch_mech.ap_min == pytest.approx(res.ap_min, rel=1e-7)  # LP vs virtual work
    assert arch_mech.delta == pytest.approx(res.delta, rel=1e-12)
    assert arch_mech.info["symmetric"] == 1


def test_fourhinge_conserves_energy_between_impacts(arch_mech):
    """Free motion from u0 = 0.6·delta: E = ½A(u)u'² + V(u) from the exact kinematics is
    constant until the first impact (RK4 + table interpolation: drift < 1e-7 of the energy
    released)."""
    mech_exact = analyse(catenary(10.0, 3.0, 0.25)).mechanism
    u0 = 0.6 * arch_mech.delta
    r = mc.simulate(arch_mech, None, u0=u0, t_free=5.0)
    assert r.impacts >= 1
    k = int(np.searchsorted(r.t, r.impact_times[0]))  # samples before the first impact
    u, ud = r.u[:k + 1], r.u_dot[:k + 1]
    energy = 0.5 * generalized_inertia(mech_exact, u) * ud**2 + potential(mech_exact, u)
    released = float(potential(mech_exact, 0.0)[0] - potential(mech_exact, u0)[0])
    assert np.abs(energy - energy[0]).max() < 1e-7 * abs(released)


def test_fourhinge_nothing_moves_below_ap_min(arch_mech):
    for m in (mo.sine(1, 0.8), mo.square(1, 0.8), el_centro()):
        r = mc.simulate(arch_mech, m.scaled(0.999 * arch_mech.ap_min / m.pga))
        assert r.max_rotation_ratio == 0.0 and r.impacts == 0 and not r.overturned


def test_fourhinge_mirrored_excitation_mirrored_response(arch_mech):
    rec = el_centro()
    m = rec.scaled(1.3 * arch_mech.ap_min / rec.pga)
    a, b = mc.simulate(arch_mech, m, p=4.0), mc.simulate(arch_mech, m.scaled(-1), p=4.0)
    assert np.array_equal(a.t, b.t) and np.array_equal(a.u, -b.u)
    assert a.overturned == b.overturned and a.impacts == b.impacts


def test_size_scaling_p_inverse_sqrt_span():
    """The same shape at 4x the span has half the p, and its response at that p is the
    reference mechanism's response at that p (p ∝ 1/sqrt(l), the kernel's time scaling)."""
    small = fourhinge_mechanism(catenary(2.5, 0.75, 0.0625))
    big = fourhinge_mechanism(catenary(10.0, 3.0, 0.25))
    assert small.p == pytest.approx(2 * big.p, rel=1e-9)
    m = mo.sine(1.0, 1.0).scaled(1.8 * big.ap_min)
    a, b = mc.simulate(big, m), mc.simulate(small, m, p=big.p)
    assert a.overturned == b.overturned and a.impacts == b.impacts
    assert a.max_rotation_ratio == pytest.approx(b.max_rotation_ratio, rel=1e-6)


def test_impact_law_slender_arches_lose_little():
    """Projection impact law: energy kept e² → 1 as d/l → 0 (paper Sect. 4); the mirror
    computation equals the general one with the LP's opposite mechanism (energy ratio is
    coordinate-free)."""
    kept = []
    for d in (0.05, 0.025, 0.0125, 0.005):
        plus = analyse(catenary(1.0, 0.3, d), direction=1)
        minus = analyse(catenary(1.0, 0.3, d), direction=-1)
        e_m = mirror_impact_coefficient(plus)
        e_g = impact_coefficient(plus, minus)
        # e_g is on the linkages' own coordinates (part 1's rotation); minus.A is reported
        # on its part 3's (docs/theory.md Eq. 5.6)
        a_minus = float(generalized_inertia(minus.mechanism, 0.0)[0])
        assert e_g**2 * a_minus / plus.A == pytest.approx(e_m**2, rel=1e-9)
        kept.append(e_m**2)
    assert np.all(np.diff(kept) > 0) and kept[-1] > 0.99 and kept[0] < 0.5


def test_non_symmetric_arch_uses_both_lp_mechanisms():
    x = np.linspace(0.0, 10.0, 41)
    y = 3.0 * (1 - ((x - 4.0) / np.where(x < 4.0, 4.0, 6.0)) ** 2)
    mech = fourhinge_mechanism(polyline(np.column_stack([x, y]), 0.5))
    assert mech.info["symmetric"] == 0
    assert mech.plus.ap_min != pytest.approx(mech.minus.ap_min, rel=1e-3)
    assert mech.ap_min == min(mech.plus.ap_min, mech.minus.ap_min)
    # energy kept by the impact is the same in both directions (coordinate-free)
    e_pm = mech.plus.e_close**2 * mech.minus.A0 / mech.plus.A0
    e_mp = mech.minus.e_close**2 * mech.plus.A0 / mech.minus.A0
    assert e_pm == pytest.approx(e_mp, rel=1e-9) and e_pm <= 1.0


@pytest.mark.parametrize("signal", ["sine", "square", "step"])
def test_slender_fourhinge_oas_tends_to_block_oas(signal):
    """DeJong–Dimitrakopoulos equivalence: the four-hinge catenary's OAS approaches the
    block's with the same p and ap,min as d/l → 0 (measured: max deviation 5.4 % at
    d/l = 0.0125, 0.9 % at 0.0025, for pT = 1…10)."""
    p = np.linspace(1, 10, 10)
    ratio = np.linspace(1, 8, 57)
    m = mo.pulse(signal, period=1.0)
    devs = []
    for d in (0.0125, 0.0025):
        mech = fourhinge_mechanism(catenary(1.0, 0.3, d))
        blk = systems.BlockSystem(alpha=math.atan(mech.ap_min / 9.81))
        bf = spectra.compute_oas(systems.MechanismSystem(mech), m, p, ratio,
                                 progress=False).boundary.values
        bb = spectra.compute_oas(blk, m, p, ratio, progress=False).boundary.values
        devs.append(np.nanmax(np.abs(bf / bb - 1)))
    assert devs[1] < 0.02 and devs[1] < devs[0]


def test_bad_mechanism_input():
    with pytest.raises(ValueError, match="delta"):
        mc.generic(1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="ap_min"):
        mc.generic(1.0, 0.1, -1.0)
    with pytest.raises(ValueError, match="mass_ratio"):
        mc.rocking_frame(0.1, 1.0, -0.5)
    with pytest.raises(ValueError, match="restitution"):
        mc.generic(1.0, 0.1, 1.0, restitution=2.0)
    with pytest.raises(ValueError, match="no four-hinge mechanism.*cannot carry"):
        fourhinge_mechanism(circular(1.0, 0.5, 0.01))  # semicircle below t/R = 0.1075
