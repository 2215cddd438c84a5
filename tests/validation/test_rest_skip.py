"""The rest shortcut of the general stepper (docs/theory.md Eq. (9.11)): steps where a
structure at rest stays at rest are not solved again, and the histories are those of the
engine that solves every step (``skip_rest=False``) within the solver's tolerances."""

from __future__ import annotations

import numpy as np
import pytest

import rockarch as ra
from rockarch import mdof

G = 9.81
MU = 0.6


def _motion(seconds: float, pga: float) -> ra.GroundMotion:
    m = ra.el_centro()
    k = m.t <= seconds
    return ra.GroundMotion(m.t[k], m.a[k], "El Centro").scaled(pga / m.pga)


def _newmark(motion: ra.GroundMotion, mu: float, dt: float = 1e-5) -> float:
    """Newmark's rigid sliding block (docs/theory.md Eq. (9.5) stepped finely): its final
    slip relative to the ground [m] (positive: +x)."""
    t = np.arange(0.0, motion.duration, dt)
    ag = np.interp(t, motion.t, motion.a)
    v = x = 0.0
    for a in ag:
        if v == 0.0:
            if abs(a) > mu * G:
                v = -np.sign(a) * (abs(a) - mu * G) * dt
        else:
            nv = v + (-a - np.sign(v) * mu * G) * dt
            v = 0.0 if nv * v < 0.0 else nv
        x += v * dt
    return x


def _assembly(**kw):
    s = ra.system("mdof", friction=MU, **kw)
    return s.assembly


@pytest.mark.parametrize("kw", [{"column": [[4.0, 0.8]]},
                                {"wall": [2, 3], "block": [0.4, 0.2]}],
                         ids=["squat block", "wall 2x3"])
def test_sliding_with_rest_shortcut_is_newmark(kw):
    """A block and a two-course wall that can only slide (B/H far above μ) under 6 s of El
    Centro at 1.5·μg: with the shortcut, most steps are at rest, and the final slip is the
    engine's without it (measured: equal to 1e-4 m, the tolerance is ten times that) and
    Newmark's (within 1 %, the O(h) error of the step's sliding onsets: measured 0.2 %)."""
    a = _assembly(**kw)
    m = _motion(6.0, 1.5 * MU * G)
    fast = mdof.simulate(a, m, t_free=0.0)
    ref = mdof.simulate(a, m, t_free=0.0, skip_rest=False)
    assert ref.steps_at_rest == 0
    assert fast.steps_at_rest > 0.5 * fast.steps
    dx_fast = fast.q[-1, :, 0] - fast.q[0, :, 0]
    dx_ref = ref.q[-1, :, 0] - ref.q[0, :, 0]
    assert np.ptp(dx_fast) < 1e-5  # slides as one body
    assert abs(dx_fast.mean() - dx_ref.mean()) < 1e-3
    slip = _newmark(m, MU)
    assert slip > 0.005
    assert dx_fast.mean() == pytest.approx(slip, rel=0.01)


def test_below_ap_min_nothing_is_solved_after_the_first_steps():
    """The trilithon under El Centro scaled to 0.9·ap,min: at rest throughout, so all but a
    few steps (the first, and one at each change of the contact states as the ground
    acceleration changes sign) are skipped, and no block turns (its rest is exact: the
    engine's own creep, below 1e-6 of δ)."""
    a = _assembly(colonnade=2, block=[0.3, 2.0], bay=1.0, lintel=0.4)
    r = mdof.simulate(a, _motion(10.0, 0.9 * a.ap_min))
    assert not r.overturned and r.impacts == 0
    assert r.max_rotation_ratio < 1e-6
    assert r.steps_at_rest > 0.9 * r.steps
