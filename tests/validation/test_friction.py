"""Coulomb friction in the MDOF engine (docs/theory.md §9): closed forms (Newmark's sliding
block, the rock / slide / slide-rock onset), energy, and the no-sliding limit mu → large."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rockarch import mdof
from rockarch.core.constants import GAP_TOL, G
from rockarch.mdof import builders as bd
from rockarch.motion import signals as motion


def onset_mu(a: float, lam: float) -> float:
    """Smallest mu for pure rocking of a block (lambda = B/H) from rest under a constant
    ground acceleration a·g ≥ lambda·g (docs/theory.md Eq. (9.6))."""
    return (a * (1 + 4 * lam**2) + 3 * lam) / (4 + lam**2 + 3 * lam * a)


def newmark_slip(a: float, mu: float, t: float) -> float:
    """Total slip of a block that can only slide (Eq. (9.5)): step pulse a [m/s²], t [s]."""
    v = (a - mu * G) * t
    return 0.5 * (a - mu * G) * t**2 + v**2 / (2 * mu * G)


def test_newmark_sliding_block():
    # B/H = 1 > a/g = 0.5 > mu = 0.1: the block only slides (issue value: 0.392 m)
    assert newmark_slip(0.5 * G, 0.1, 0.2) == pytest.approx(0.392, abs=5e-4)
    blk = bd.with_friction(mdof.single_block(1.0, 1.0), 0.1)
    r = mdof.simulate(blk, motion.step(0.5 * G, 0.2), t_free=2.0)
    # Moreau–Jean is exact for piecewise-constant accelerations except at the two stick/
    # slip transitions, each inside one step: an O(h·v) error, h·v ≈ 1.2 mm·... = 1e-3
    # relative at h·p = 0.005 (measured: 6e-4)
    assert r.max_slip == pytest.approx(newmark_slip(0.5 * G, 0.1, 0.2), rel=2e-3)
    assert r.max_rotation_ratio < 1e-9 and not r.overturned
    assert r.sliding_contacts_max == 1 and r.lcp_failures == 0
    # it comes to rest when the slip ends: v / (mu·g) = 0.8 s after the pulse
    assert r.t_end == pytest.approx(1.0, abs=0.01)
    d = r.to_dict()
    assert d["max_slip"] == r.max_slip and d["sliding_contacts_max"] == 1
    # the slip history (MDOFResponse.slip, at the joint's midpoint): 0 as built, growing
    # while the block slides one way, its end Newmark's slip; the kernel's max_slip is the
    # same offset at every step (1e-6: the midpoint and the corners of a joint that does
    # not turn slide together, to rounding of the recorded positions)
    s = r.slip()
    assert s[0] == 0.0 and np.all(np.diff(s) >= -1e-12)
    assert s.max() == pytest.approx(r.max_slip, rel=1e-6)


def _on_a_base(density: float, top: list, mu: float):
    """A light block ``top`` on a 2 x 1 m base block of ``density`` (the top's is 1), the
    base on the ground with mu = 0.9 (it never slides here)."""
    return bd.from_polygons([[[0, 0], [2, 0], [2, 1], [0, 1]], top], density=[density, 1.0],
                            contacts=[(0, -1, 0.9), (1, 0, mu)])


@pytest.mark.parametrize("density", [1.0, 1e3])
def test_a_light_block_on_a_heavy_one_slides_and_rocks_as_on_the_ground(density):
    # the position projection returns what the regularised contacts took by creeping; that
    # return was charged to the kinetic energy of every block, and under a base 1000 times
    # heavier it stopped the top block (0.3 mm of slip instead of Newmark's 0.276 m, and a
    # slender block that should fall stood)
    slide = _on_a_base(density, [[0.7, 1], [1.3, 1], [1.3, 2], [0.7, 2]], 0.4)
    r = mdof.simulate(slide, motion.step(0.45 * G, 1.0), t_free=2.0)
    # Moreau–Jean is exact for a constant acceleration but at the two stick/slip
    # transitions (an O(h·v) error: 1e-3 relative, as in test_newmark_sliding_block)
    assert r.max_slip == pytest.approx(newmark_slip(0.45 * G, 0.4, 1.0), rel=2e-3)
    rock = _on_a_base(density, [[0.9, 1], [1.1, 1], [1.1, 2], [0.9, 2]], 0.9)
    r = mdof.simulate(rock, motion.step(1.5 * rock.ap_min, 1.0), t_free=1.0)
    # B/H = 0.2 < mu: it rocks from 0.2 g and falls under 0.3 g for 1 s, as a block on the
    # ground (the closed form of the rigid block: docs/theory.md Eq. (1.4)), whatever its
    # base's mass: t_overturn to 1 %, the base's own recoil under the top's impacts
    blk = mdof.simulate(bd.with_friction(mdof.single_block(0.2, 1.0), 0.9),
                        motion.step(1.5 * rock.ap_min, 1.0), t_free=1.0)
    assert r.overturned and blk.overturned
    assert r.t_overturn == pytest.approx(blk.t_overturn, rel=1e-2)


def _mode(lam: float, a: float, mu: float) -> str:
    """What a block (B/H = lam) does in its first 0.05 s under a constant a·g."""
    blk = bd.with_friction(mdof.single_block(lam, 1.0), mu)
    r = mdof.simulate(blk, motion.step(a * G, 0.05), t_free=0.0)
    assert r.lcp_failures == 0
    # thresholds: every mode below moves by > 2e-5 m or 1e-3·alpha in 0.05 s at the
    # chosen distances (0.002) from the boundaries; the engine's solve is exact to ~1e-12
    slides = r.max_slip > 1e-6
    rocks = r.max_rotation_ratio > 1e-6
    return {(False, False): "rest", (True, False): "slide", (False, True): "rock",
            (True, True): "slide-rock"}[(slides, rocks)]


def test_onset_formula_values():
    # the values for lambda = 0.25
    assert onset_mu(0.3, 0.25) == pytest.approx(0.2624, abs=5e-5)
    assert onset_mu(0.5, 0.25) == pytest.approx(0.3099, abs=5e-5)
    assert onset_mu(0.25, 0.25) == pytest.approx(0.25)  # continuous with mu = lambda


@pytest.mark.parametrize("a", [0.3, 0.4, 0.5, 0.8])
def test_rock_slide_rock_boundary(a):
    lam = 0.25
    mu0 = onset_mu(a, lam)
    assert _mode(lam, a, mu0 + 0.002) == "rock"
    assert _mode(lam, a, mu0 - 0.002) == "slide-rock"


def test_rest_and_pure_sliding():
    lam = 0.25
    assert _mode(lam, 0.2, 0.3) == "rest"  # a < min(mu, lambda)
    assert _mode(lam, 0.24, 0.5) == "rest"
    assert _mode(lam, 0.3, 0.2) == "slide"  # mu < lambda, a > mu
    assert _mode(lam, 0.8, 0.2) == "slide"  # mu < lambda: never rocks, whatever a


@pytest.mark.parametrize("mu, assembly, amp", [
    (0.26, mdof.single_block(0.3, 1.2), 0.8),
    (0.26, mdof.column([(0.3, 1.0), (0.25, 0.8)]), 0.8),
    (0.22, mdof.column([(0.3, 1.0), (0.25, 0.8)]), 0.6),
])
def test_energy_never_increases_with_friction_and_impacts(mu, assembly, amp):
    # blocks that rock, slide and impact during a sine pulse (T = 0.3 s); in the free motion
    # after it the energy may only drop (friction, impacts). Bound: a corner counts as
    # touching within GAP_TOL·d (d: thinnest joint), so closing such a gap can return at
    # most M·g·GAP_TOL·d; the no-friction chain stepper shows the same (measured ≤ 3e-5 of
    # M·g·d with and without friction)
    a = bd.with_friction(assembly, mu)
    r = mdof.simulate(a, motion.sine(1.0, 0.3).scaled_to_pga(amp * G), t_free=2.0)
    assert r.lcp_failures == 0 and not r.overturned
    assert r.sliding_contacts_max >= 1 and r.impacts >= 3 and r.max_slip > 1e-3
    e = r.energy[r.t >= 0.3]
    assert e[0] - e[-1] > 0.3 * abs(e[0])  # friction and impacts did dissipate
    gain = np.max(e[1:] - np.minimum.accumulate(e)[:-1])
    assert gain <= GAP_TOL * a.mass.sum() * G * a.thickness.min()


def _maps(assembly, signal, p, ratio):
    m = motion.pulse(signal, period=1.0)
    ref = mdof.simulate_batch(assembly, m, p, ratio)
    fr = mdof.simulate_batch(bd.with_friction(assembly, 1e3), m, p, ratio)
    assert fr.extras["lcp_failures"].sum() == 0
    return ref, fr


@pytest.mark.parametrize("signal", ["sine", "step"])
def test_large_mu_reproduces_no_sliding_maps(signal):
    # mu = 1000: no joint can slide (the friction cone holds any shear the structure can
    # carry), so the collapse maps equal those of the no-sliding chain stepper cell for cell
    pp, rr = np.meshgrid(np.linspace(1.0, 6.0, 4), np.linspace(1.0, 4.0, 6), indexing="ij")
    for assembly in (mdof.block_from_p_alpha(2.0, 0.2), mdof.column([(0.3, 1.0), (0.2, 0.8)])):
        ref, fr = _maps(assembly, signal, pp, rr)
        assert ref.overturned.any() and not ref.overturned.all()
        np.testing.assert_array_equal(fr.overturned, ref.overturned)
        assert np.all(fr.extras["sliding_contacts_max"] == 0)


def _two_blocks_on_the_ground(mu: float) -> mdof.Assembly:
    """Two separate unit blocks on the ground: a contact graph that is not a chain."""
    one = mdof.single_block(1.0, 1.0)
    shift = np.array([2.0, 0.0])
    return mdof.Assembly(
        name="two blocks", kind="assembly", mass=np.repeat(one.mass, 2),
        inertia=np.repeat(one.inertia, 2), centroid=np.vstack([one.centroid, one.centroid + shift]),
        corners=np.stack([one.corners[0], one.corners[0] + shift]),
        normal=np.repeat(one.normal, 2, axis=0),
        polygons=(one.polygons[0], one.polygons[0] + shift), ap_min=mu * G, p_ref=one.p_ref,
        delta_ref=one.delta_ref, size=one.size, body_a=[-1, -1], body_b=[0, 1], mu=[mu, mu])


def test_newmark_on_the_general_stepper():
    # the sliding block of test_newmark_sliding_block, twice, in a non-chain assembly (the
    # Gauss–Seidel solve): each block slides exactly as alone
    a = _two_blocks_on_the_ground(0.1)
    assert not a.is_chain
    r = mdof.simulate(a, motion.step(0.5 * G, 0.2), t_free=2.0)
    assert r.lcp_failures == 0
    assert r.max_slip == pytest.approx(newmark_slip(0.5 * G, 0.1, 0.2), rel=2e-3)
    assert r.sliding_contacts_max == 2
    assert math.isclose(r.max_rotation_ratio, 0.0, abs_tol=1e-9)
    assert np.allclose(r.q[:, 1, 0] - r.q[:, 0, 0], 2.0, atol=1e-9)


@pytest.mark.parametrize("mu", [0.5, math.inf])
def test_fully_open_joint_separates(mu):
    # a block 1 mm above the ground moving sideways at 1 m/s, one contact solve: the open
    # joint carries no impulse at all, the velocity is untouched; with friction and without
    # (mu = inf is the limit of Coulomb's cone: no shear without compression,
    # docs/theory.md §9)
    from rockarch.mdof import graph_stepper as gs
    from rockarch.mdof.kernel_data import graph_model

    blk = mdof.single_block(0.5, 1.0)
    m = graph_model(dataclasses.replace(blk, mu=np.array([mu])))
    ws = gs.make_work(m, 1.0, m.contact_cap)
    x, y, ph = m.c0[:, 0].copy(), m.c0[:, 1] + 1e-3, np.zeros(1)
    vx, vy, om = np.array([1.0]), np.zeros(1), np.zeros(1)
    h = 1e-3  # the gap (1 mm) is not closed within the step: no speculative contact
    its = gs.contact_step(m, x, y, ph, vx, vy, om, 1e-4 * 0.5, h, 1.5 * G * h, 1e-12, 1e-12,
                          1e-9, 1e-12, 1e-4 * 0.5, ws)
    assert its >= 0
    assert (vx[0], vy[0], om[0]) == (1.0, 0.0, 0.0) and np.all(ws.lam == 0.0)


def test_no_sliding_joint_holds_while_compressed():
    # the other half of the mu = inf limit: a block standing on the ground pushed sideways
    # (free velocity 0.01 m/s at its centre, gravity's step -g·h) does not slide: its base
    # keeps U_t = 0 (asserted to 1e-6 m/s, a thousand times the solve's 1e-9 sign
    # tolerance) and the impulse is compressive
    from rockarch.mdof import graph_stepper as gs
    from rockarch.mdof.kernel_data import graph_model

    blk = mdof.single_block(0.5, 1.0)
    m = graph_model(blk)
    ws = gs.make_work(m, 1.0, m.contact_cap)
    x, y, ph = m.c0[:, 0].copy(), m.c0[:, 1].copy(), np.zeros(1)
    h = 1e-3
    vx, vy, om = np.array([0.01]), np.array([-G * h]), np.zeros(1)
    its = gs.contact_step(m, x, y, ph, vx, vy, om, 1e-4 * 0.5, h, 1.5 * G * h, 1e-12, 1e-12,
                          1e-9, 1e-12, 1e-4 * 0.5, ws)
    assert its >= 0
    assert ws.lam[0] + ws.lam[1] > 0.0
    assert abs(vx[0] + 0.5 * om[0]) < 1e-6  # the base (r_y = -H/2) does not slide


def test_wide_wall_at_rest():
    # a 42-block running-bond wall (a hyperstatic graph: 108 joints, 324 rows for 126
    # velocities) on still ground stays at rest: no failed step, no rotation or slip above
    # round-off
    a = bd.wall(4, 10, 0.4, 0.2, mu=0.6)
    assert a.n_blocks == 42
    r = mdof.simulate(a, motion.step(1e-9 * G, 0.2), t_free=1.0)
    assert r.lcp_failures == 0 and not r.overturned
    assert r.max_rotation_ratio < 1e-6 and r.max_slip < 1e-6
    assert np.abs(r.q[-1] - r.q[0]).max() < 1e-6


def test_slender_wall_collapses_as_one_block():
    # a slender wall (one block wide, 1.2 m tall, ap,min = g/3) under a 0.9 g step pulse of
    # 0.3 s rocks about its base as one body and collapses at the time of the rigid block
    # of the same outline (Housner's equation, rockarch.rocking: exact); the MDOF engine's
    # midpoint steps of h·p = 0.005 put it within 1 % (a step is 0.1 % of that time)
    from rockarch.rocking.block import RigidBlock
    from rockarch.rocking.block import simulate as housner

    a = bd.wall(6, 1, 0.4, 0.2, mu=0.8)
    assert a.ap_min == pytest.approx(G / 3, rel=1e-6)
    step = motion.step(0.9 * G, 0.3)
    r = mdof.simulate(a, step, t_free=2.0)
    ref = housner(RigidBlock.from_dimensions(0.4, 1.2), step)
    assert r.lcp_failures == 0 and r.overturned and ref.overturned
    assert r.t_overturn == pytest.approx(ref.t_overturn, rel=1e-2)


def _on_pedestal(width: float) -> mdof.Assembly:
    """A block 0.4 × 0.2 m, mu = 0.1, on a rigid pedestal 1 m high whose top, ``width``
    wide, ends flush with the block's right face (the block slides to -x under +a)."""
    return bd.from_polygons([[[0, 1], [0.4, 1], [0.4, 1.2], [0, 1.2]]], mu=0.1,
                            supports=[[[0.4 - width, 0], [0.4, 0], [0.4, 1],
                                       [0.4 - width, 1]]])


@pytest.mark.parametrize("duration", [0.1, 0.15, 0.2])
def test_block_slides_off_a_pedestal_edge(duration):
    # a sliding joint's contact runs along the overlap of the two faces (docs/theory.md
    # §9): on a pedestal as wide as the block it slips as Newmark says while its centroid
    # stays on the pedestal (slip < B/2 = 0.2 m), and it tips over the edge once the slip
    # passes B/2 (Newmark: 0.098, 0.221, 0.392 m for the three pulses); on a 2 m wide
    # pedestal it slips the whole Newmark distance and stays (rel 2e-3: the closed-form
    # test above)
    step = motion.step(0.5 * G, duration)
    slip = newmark_slip(0.5 * G, 0.1, duration)
    narrow = mdof.simulate(_on_pedestal(0.4), step, t_free=2.0)
    wide = mdof.simulate(_on_pedestal(2.0), step, t_free=2.0)
    assert narrow.lcp_failures == 0 and wide.lcp_failures == 0
    assert not wide.overturned and wide.max_slip == pytest.approx(slip, rel=2e-3)
    assert narrow.overturned == (slip > 0.2)
    if slip < 0.2:
        assert narrow.max_slip == pytest.approx(slip, rel=2e-3)


def test_sliding_joint_contact_is_the_overlap_of_the_faces():
    # the block of _on_pedestal(0.4) shifted by -0.3 m, flat on the pedestal: the joint's
    # contact is the overlap [0, 0.1] of the two faces (the pedestal's corner and the
    # block's), so the rows' lever arms from the block's centroid (x = -0.1) are 0.1 and
    # 0.2 m, the gaps 0 and the offset the shift; shifted by -0.5 m the faces no longer
    # overlap and both corners are open by OFF_GAP (exact arithmetic on these values)
    from rockarch.mdof import graph_stepper as gs
    from rockarch.mdof.kernel_data import graph_model

    m = graph_model(_on_pedestal(0.4))
    ws = gs.make_work(m, 1.0, m.contact_cap)
    for shift in (-0.3, -0.5):
        x, y, ph = m.c0[:, 0] + shift, m.c0[:, 1].copy(), np.zeros(1)
        off = gs.geometry(1, m.ba, m.bb, x, y, ph, ws.ra, ws.rb, ws.fa, ws.fb, ws.ftol, m.n0, m.mu,
                          ws.gap, ws.rows.ja, ws.rows.jb)
        jrows = ws.rows.ja if m.ba[0] == 0 else ws.rows.jb
        if shift == -0.3:
            assert off == 0
            assert np.allclose(ws.gap[0, :2], 0.0, atol=1e-12)
            assert abs(ws.gap[0, 2]) == pytest.approx(0.3)
            assert sorted(abs(jrows[:2, 2])) == pytest.approx([0.1, 0.2])
            assert np.allclose(abs(jrows[:2, 1]), 1.0) and np.allclose(jrows[:2, 0], 0.0)
        else:
            assert off == 1 and np.all(ws.gap[0, :2] == gs.OFF_GAP)


def test_energy_never_increases_while_a_block_overhangs():
    # a block 0.6 × 0.3 m (mu = 0.2) on a base 1 × 0.5 m that does not slide: a 0.9 g sine
    # pulse of 0.8 s slides it 0.48 m, past the base's edge (0.2 m away) but not past its
    # own centroid, so the contact's end moves to the base's corner and stays there; in the
    # free motion the energy may only drop (bound of the test above: measured gain 4e-8 J
    # against 4e-4 J)
    a = bd.from_polygons([[[0, 0], [1.0, 0], [1.0, 0.5], [0, 0.5]],
                          [[0.2, 0.5], [0.8, 0.5], [0.8, 0.8], [0.2, 0.8]]],
                         contacts=[(0, -1, None), (1, 0, 0.2)])
    r = mdof.simulate(a, motion.sine(1.0, 0.8).scaled_to_pga(0.9 * G), t_free=2.0)
    assert r.lcp_failures == 0 and not r.overturned
    assert 0.2 < r.max_slip < 0.5  # past the base's edge, centroid still on the base
    e = r.energy[r.t >= 0.8]
    assert e[0] - e[-1] > 0.3 * abs(e[0])
    gain = np.max(e[1:] - np.minimum.accumulate(e)[:-1])
    assert gain <= GAP_TOL * a.mass.sum() * G * a.thickness.min()
