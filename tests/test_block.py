"""Rigid block: closed forms, exact quadratures and invariants of Housner's equation."""

import math

import numpy as np
import pytest

from rockarch.motion import signals as mo
from rockarch.motion.records import el_centro
from rockarch.rocking.block import RigidBlock, housner_restitution, simulate, simulate_batch

from .reference import free_quarter_period, step_boundary


def test_block_from_dimensions_follows_eq1():
    b = RigidBlock.from_dimensions(0.4, 2.0, g=9.81)
    r_half = 0.5 * math.hypot(0.4, 2.0)
    assert b.p == pytest.approx(math.sqrt(3 * 9.81 / (4 * r_half)), rel=1e-14)
    assert b.alpha == pytest.approx(math.atan(0.2), rel=1e-14)
    assert b.ap_min == pytest.approx(9.81 * 0.2, rel=1e-14)
    assert (b.width, b.height) == pytest.approx((0.4, 2.0), rel=1e-12)
    assert b.r == pytest.approx(1 - 1.5 * math.sin(b.alpha) ** 2)


@pytest.mark.parametrize("alpha, frac", [(0.05, 0.2), (0.2, 0.5), (0.4, 0.9)])
def test_free_rocking_quarter_period_exact(alpha, frac):
    """First impact time vs the exact energy quadrature; RK4 with p·h = 0.05 is accurate to
    ~1e-7 s here (4th order: 16x smaller per halving, checked below)."""
    b = RigidBlock(2.0, alpha)
    res = simulate(b, None, theta0=frac * alpha, t_free=3.0)
    assert res.impact_times[0] == pytest.approx(free_quarter_period(2.0, alpha, frac * alpha),
                                           abs=2e-7)


def test_free_rocking_period_linearised_for_slender_block():
    """Housner's slender-block quarter period (1/p)·arccosh(1/(1 − θ0/α)); for α = 0.01
    the linearisation error is O(α²) ≈ 1e-4 relative."""
    b = RigidBlock(3.0, 0.01)
    for frac in (0.1, 0.5, 0.9):
        res = simulate(b, None, theta0=frac * b.alpha, t_free=2.0)
        t_lin = math.acosh(1.0 / (1.0 - frac)) / b.p
        assert res.impact_times[0] == pytest.approx(t_lin, rel=1e-4)


def test_free_rocking_amplitude_decay_and_period_shrink():
    """Each half cycle the amplitude falls (r < 1) and so does the half period (Housner)."""
    b = RigidBlock(2.0, 0.2)
    res = simulate(b, None, theta0=0.8 * b.alpha, t_free=6.0)
    gaps = np.diff(res.impact_times)
    assert np.all(np.diff(gaps) < 0)


def test_rk4_converges_at_fourth_order():
    b = RigidBlock(2.0, 0.2)
    exact = free_quarter_period(2.0, 0.2, 0.1)
    errs = [abs(simulate(b, None, theta0=0.1, t_free=1.0, h_factor=h).impact_times[0] - exact)
            for h in (0.2, 0.1, 0.05)]
    # halving h divides the error by 2^4 = 16 (allow 10..22 for the pre-asymptotic range)
    assert 10 < errs[0] / errs[1] < 22 and 10 < errs[1] / errs[2] < 22


@pytest.mark.parametrize("restitution", [None, 0.9, 0.5, 1.0])
def test_velocity_ratio_at_every_impact(restitution):
    b = RigidBlock(2.5, 0.15, restitution=restitution)
    res = simulate(b, None, theta0=0.7 * b.alpha, t_free=4.0)
    i = np.flatnonzero(np.diff(res.t) == 0.0)  # impacts are stored as (before, after) pairs
    i = i[res.theta_dot[i + 1] != 0.0]  # the last one may settle the block (chatter rule)
    assert i.size >= 3
    expected = housner_restitution(0.15) if restitution is None else restitution
    assert np.allclose(res.theta_dot[i + 1] / res.theta_dot[i], expected, rtol=1e-12)


def test_restitution_zero_stops_at_first_impact():
    b = RigidBlock(2.0, 0.2, restitution=0.0)
    res = simulate(b, None, theta0=0.5 * b.alpha, t_free=5.0)
    assert res.impacts == 1 and res.t_end == pytest.approx(res.impact_times[0])


@pytest.mark.parametrize("motion", [mo.sine(1.0, 0.7), mo.square(1.0, 0.7),
                                    mo.step(1.0, 0.7)], ids=["sine", "square", "step"])
def test_nothing_moves_below_ap_min_pulses(motion):
    b = RigidBlock(2.0, 0.15)
    res = simulate(b, motion.scaled(0.9999 * b.ap_min))
    assert res.max_rotation_ratio == 0.0 and res.impacts == 0 and not res.overturned
    assert np.all(res.theta == 0.0)


def test_nothing_moves_below_ap_min_record():
    rec = el_centro()
    out = simulate_batch(RigidBlock(1.0, 0.1), rec, np.linspace(0.5, 10, 20), 0.9999)
    assert np.all(out.max_rotation_ratio == 0.0) and not out.overturned.any()


@pytest.mark.parametrize("p", [1.0, 2.0, 4.0])
def test_step_impulse_boundary_exact(p):
    """Engine vs the exact quadrature of the step impulse (tests/reference.py). t_free = 80 s
    lets the near-separatrix motion finish; agreement to 1e-6 is RK4 + event location."""
    from rockarch.spectra.oas import compute_oas
    from rockarch.systems import BlockSystem

    alpha, T = 0.2, 1.0
    ds = compute_oas(BlockSystem(alpha=alpha, t_free=80.0), mo.step(1.0, T), [p],
                     [1.0, 5.0], tol=1e-9, progress=False)
    assert ds.boundary.values[0] == pytest.approx(step_boundary(p, alpha, T), rel=1e-6)


def test_step_impulse_boundary_linearised_closed_form():
    """Linearised slender block, step impulse of duration T (derivation in docs/block.md):
    overturning iff ap/ap,min ≥ 1/(1 − exp(−p·T)). The exact engine deviates by O(α²):
    below 1e-4 relative for α = 0.01, and 100x more for α = 0.1."""
    from rockarch.spectra.oas import compute_oas
    from rockarch.systems import BlockSystem

    ps = np.array([0.7, 1.5, 3.0])
    T = 0.8
    closed = 1.0 / (1.0 - np.exp(-ps * T))
    devs = []
    for alpha in (0.01, 0.1):
        ds = compute_oas(BlockSystem(alpha=alpha, t_free=80.0), mo.step(1.0, T), ps,
                         [1.0, 20.0], tol=1e-9, progress=False)
        devs.append(np.abs(ds.boundary.values / closed - 1).max())
    assert devs[0] < 1e-4
    assert 30 < devs[1] / devs[0] < 300  # ∝ α²: (0.1/0.01)² = 100


@pytest.mark.parametrize("motion", [mo.sine(1.0, 0.6), el_centro()], ids=["sine", "record"])
def test_sign_symmetry(motion):
    """Mirroring the excitation mirrors the response exactly (the equation is odd)."""
    b = RigidBlock(3.0, 0.12)
    m = motion.scaled(1.8 * b.ap_min / motion.pga)
    a, c = simulate(b, m), simulate(b, m.scaled(-1.0))
    assert np.array_equal(a.t, c.t)
    assert np.array_equal(a.theta, -c.theta)
    assert a.overturned == c.overturned and a.impacts == c.impacts


def test_convergence_under_step_refinement_on_a_record():
    """Overturning time and peak rotation on El Centro converge as h = c/p shrinks."""
    b = RigidBlock(2.5, 0.1)
    rec = el_centro()
    m = rec.scaled(1.4 * b.ap_min / rec.pga)
    res = [simulate(b, m, h_factor=h) for h in (0.1, 0.05, 0.025)]
    assert all(r.overturned for r in res)
    t = [r.t_overturn for r in res]
    assert abs(t[1] - t[2]) < 1e-5 and abs(t[0] - t[2]) < 1e-4
    safe = [simulate(b, rec.scaled(1.1 * b.ap_min / rec.pga), h_factor=h) for h in (0.05, 0.025)]
    assert safe[0].max_rotation_ratio == pytest.approx(safe[1].max_rotation_ratio,
                                                         rel=1e-5)


def test_batch_matches_single_simulations():
    rec = el_centro()
    ps = np.array([1.0, 2.0, 3.5, 6.0])
    ratios = np.array([1.2, 1.6, 2.5, 1.05])
    out = simulate_batch(RigidBlock(1.0, 0.1), rec, ps, ratios)
    for i in range(ps.size):
        b = RigidBlock(ps[i], 0.1)
        single = simulate(b, rec.scaled(ratios[i] * b.ap_min / rec.pga))
        assert out.overturned[i] == single.overturned
        assert out.impacts[i] == single.impacts
        assert out.max_rotation_ratio[i] == pytest.approx(single.max_rotation_ratio,
                                                            rel=1e-12)


def test_chatter_is_settled_in_bounded_work():
    """Free rocking decays to rest in finite work (Zeno sequence cut by the criterion)."""
    b = RigidBlock(4.0, 0.05)
    res = simulate(b, None, theta0=0.9 * b.alpha, t_free=1000.0)
    assert res.t_end < 1000.0  # came to rest
    # amplitude ratio per impact is r² in energy; reaching eps_rest = 1e-6 needs
    # ln(1e6) / (-2 ln r) ≈ 1.8e3 impacts for alpha = 0.05
    assert res.impacts < 3000


@pytest.mark.parametrize(
    "call, msg",
    [
        (lambda: RigidBlock(0.0, 0.1), "p must"),
        (lambda: RigidBlock(1.0, 0.0), "alpha must lie in"),
        (lambda: RigidBlock(1.0, 1.6), "alpha must lie in"),
        (lambda: RigidBlock(1.0, 0.1, restitution=1.2), "restitution must lie in"),
        (lambda: RigidBlock.from_dimensions(-1.0, 2.0), "width B"),
        (lambda: simulate(RigidBlock(1.0, 0.1), None, theta0=0.2), "theta0"),
        (lambda: simulate(RigidBlock(1.0, 0.1), None, t_free=-1), "t_free"),
        (lambda: simulate_batch(RigidBlock(1.0, 0.1), mo.sine(1, 1), [1.0, -1.0], 2.0),
         "p must"),
    ],
)
def test_bad_input(call, msg):
    with pytest.raises(ValueError, match=msg):
        call()


def test_history_buffer_growth_gives_the_same_history():
    """A too-small history buffer is enlarged and the run repeated: same result."""
    from rockarch.rocking import kernels as k

    b = RigidBlock(2.0, 0.15)
    rec = el_centro()
    m = rec.scaled(1.2 * b.ap_min / rec.pga)
    tk, ak, _, _ = k.motion_arrays(m, b.g, "")  # as simulate passes them (read-only)
    args = (tk, ak, 1.0,
            *b.kernel_args()[:1], b.p**2, b.p, *b.kernel_args()[1:], 10.0, 0.05, 1e-6,
            0.0, 0.0)
    small = k.run_recorded(*args, 8)
    big = k.run_recorded(*args, 10**6)
    assert small[0] == big[0] and np.array_equal(small[4], big[4])
    assert np.array_equal(small[5], big[5]) and np.array_equal(small[7], big[7])
