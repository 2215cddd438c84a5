"""New contacts (docs/theory.md Eq. (9.10), rockarch.mdof.collision): blocks that touch faces
they did not touch as built, against pymunk (an independent engine whose contacts are found
anew every step) and against geometry."""

from __future__ import annotations

import numpy as np
import pytest

from rockarch import mdof
from rockarch.core.constants import G
from rockarch.mdof import builders as bd
from rockarch.motion import signals as motion
from tests.validation import pymunk_oracle as po


def _pushed(assembly, accel: float, duration: float, t_free: float = 3.0):
    """rockarch (through the collapse) and pymunk under a step of ground acceleration
    -accel·g for ``duration`` s (inertia to +x): their final (x, y, rotation) per block."""
    m = motion.step(accel * G, duration).scaled(-1.0)
    r = mdof.simulate(assembly, m, t_free=t_free, through_collapse=True)
    ref = po.final_state(assembly, lambda t: float(m(t)) if t <= m.duration else 0.0,
                         m.duration + t_free)
    return r, ref


def test_a_toppling_column_comes_to_rest_on_its_neighbour_as_in_pymunk():
    # column A (0.2 × 1 m) topples to +x onto column B (0.4 × 1 m, 0.4 m away) and rests
    # leaning on it; B stays. Where A comes to rest is set by geometry (its top corner on B's
    # face, its foot on the ground) and friction: rockarch and pymunk agree within 2 %
    # (measured: 0.03 %); the as-built joints cannot do this (A and B share none).
    a = bd.from_polygons([[[0, 0], [0.2, 0], [0.2, 1], [0, 1]],
                          [[0.6, 0], [1.0, 0], [1.0, 1], [0.6, 1]]], mu=0.6)
    r, ref = _pushed(a, 0.3, 0.4)
    assert r.lcp_failures == 0 and r.overturned  # A's collapse, followed to rest
    assert r.new_contacts_max >= 1
    final = r.q[-1]
    np.testing.assert_allclose(final[0], ref[0], rtol=0.02)
    assert final[0, 2] == pytest.approx(-0.404, abs=0.01)  # leaning, not lying
    np.testing.assert_allclose(final[1], [0.8, 0.5, 0.0], atol=1e-3)  # B did not move
    # A's top corner touches B's face at rest: the contact holds it (geometry)
    x, y, ph = final[0]
    corner = np.array([x, y]) + np.array([[np.cos(ph), -np.sin(ph)],
                                          [np.sin(ph), np.cos(ph)]]) @ np.array([0.1, 0.5])
    assert corner[0] == pytest.approx(0.6, abs=1e-3)


def test_a_collapse_followed_through_reports_the_summary_of_the_collapse():
    # animate follows the fall (through_collapse); its summary keys must mean what they mean
    # in simulate, read at the first collapse, not after the fall (before: the toppling
    # column's max_rotation_ratio 5.15 and 5 impacts where simulate gives ~1 and 0). Same
    # engine, same steps up to the collapse: equal to the last bit.
    a = bd.from_polygons([[[0, 0], [0.2, 0], [0.2, 1], [0, 1]],
                          [[0.6, 0], [1.0, 0], [1.0, 1], [0.6, 1]]], mu=0.6)
    m = motion.step(0.3 * G, 0.4).scaled(-1.0)
    stop = mdof.simulate(a, m, t_free=3.0)
    fall = mdof.simulate(a, m, t_free=3.0, through_collapse=True)
    assert stop.overturned and fall.overturned and fall.t_end > stop.t_end
    for key in ("t_overturn", "max_rotation_ratio", "impacts", "open_joints_max",
                "max_slip", "sliding_contacts_max"):
        assert getattr(fall, key) == getattr(stop, key), key


def test_a_block_tipping_off_a_pedestal_lands_on_the_ground_as_in_pymunk():
    # a block 0.2 × 0.6 m on a pedestal 0.4 × 0.05 m (a support), 3 cm from its edge, tips
    # over the edge and comes to rest across it, one end on the ground; rockarch and pymunk
    # agree on where it rests within 2 % (measured: 1.2 % in x, 0.01 % in y and rotation).
    # Its joint with the pedestal hands it over to point contacts once the two have turned
    # apart by 45°, and the ground, which it never touched, catches it.
    blk = [[0.17, 0.05], [0.37, 0.05], [0.37, 0.65], [0.17, 0.65]]
    a = bd.from_polygons([blk], supports=[[[0, 0], [0.4, 0], [0.4, 0.05], [0, 0.05]]],
                         mu=1.0)
    r, ref = _pushed(a, 0.5, 0.3)
    assert r.lcp_failures == 0 and r.overturned and r.new_contacts_max >= 1
    np.testing.assert_allclose(r.q[-1, 0], ref[0], rtol=0.02)
    # at rest: its lowest corner on the ground (y = 0 within the contact tolerance)
    x, y, ph = r.q[-1, 0]
    rot = np.array([[np.cos(ph), -np.sin(ph)], [np.sin(ph), np.cos(ph)]])
    corners = np.array([x, y]) + (rot @ (np.array(blk) - [0.27, 0.35]).T).T
    assert corners[:, 1].min() == pytest.approx(0.0, abs=1e-4)
    assert r.q[-1, 0] == pytest.approx(r.q[-40, 0], abs=1e-6)  # it has stopped


def test_an_intact_wall_makes_no_new_contact():
    # blocks that only rock and slide on the faces they were built on touch through their
    # joints: a running-bond wall under a strong pulse has no point contact at all (the
    # corners where four blocks meet belong to the joints), so its results are those of
    # the joints alone
    a = bd.wall(3, 3, 0.4, 0.2, mu=0.6)
    r = mdof.simulate(a, motion.pulse("sine", period=0.5).scaled(0.8 * a.ap_min), t_free=1.0)
    assert r.lcp_failures == 0 and r.new_contacts_max == 0


def _visvalingam(pts: np.ndarray, keep: int) -> np.ndarray:
    """Visvalingam's rule as written: drop the first vertex of least triangle area, again
    and again (O(n²) numpy passes)."""
    pts = [tuple(p) for p in pts]
    while len(pts) > keep:
        a = np.array(pts)
        prv, nxt = np.roll(a, 1, axis=0), np.roll(a, -1, axis=0)
        area = np.abs((a[:, 0] - prv[:, 0]) * (nxt[:, 1] - prv[:, 1])
                      - (nxt[:, 0] - prv[:, 0]) * (a[:, 1] - prv[:, 1]))
        del pts[int(np.argmin(area))]
    return np.array(pts)


def test_outline_thinning_is_visvalingams_rule_vertex_for_vertex():
    # the kernel's thinning against the rule written out, on a 20-voussoir arch's curved
    # voussoirs (~100 hull vertices each), regular polygons (every area equal: ties are
    # broken by order) and random hulls: the same vertices, bit for bit (same arithmetic)
    from scipy.spatial import ConvexHull

    from rockarch.arch import catenary
    from rockarch.mdof.kernel_data import OUTLINE_VERTICES, collision_outline
    rng = np.random.default_rng(0)
    polys = list(mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20).polygons)
    polys += [np.c_[np.cos(t), np.sin(t)] for t in
              (np.linspace(0, 2 * np.pi, k, endpoint=False) for k in (13, 40, 101))]
    polys += [rng.normal(size=(k, 2)) for k in (8, 30, 200)]
    for p in polys:
        hull = np.asarray(p, float)[ConvexHull(np.asarray(p, float)).vertices]
        assert np.array_equal(collision_outline(p), _visvalingam(hull, OUTLINE_VERTICES))
