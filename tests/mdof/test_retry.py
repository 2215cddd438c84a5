"""A step whose contact problem does not settle runs again as substeps (docs/theory.md §9).

No small structure has such a step (the 205-block wall's record has a handful), so the
run loop is executed as Python (``graph_run.run.py_func``) around the compiled step, and
the step is told that its solve did not settle. The loop must then go back to the step's
start (velocities and ground-motion index as they were), run it as ``kin.REFINE``
substeps of h/REFINE, and count as failed only the substeps that do not settle either."""

from __future__ import annotations

import numpy as np
import pytest

from rockarch import mdof
from rockarch.core.constants import GAP_TOL
from rockarch.mdof import builders as bd
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof import kinematics as kin
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion import signals as motion

EMPTY = (np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8), np.zeros(0))


def _run(assembly, ground, h, t_end, unsettled, monkeypatch):
    """Run the loop as Python; the solves numbered in ``unsettled`` (0-based calls of the
    contact step) report "not settled" after solving. Returns the run's outputs and, per
    call, (step length, vy, om) as passed in."""
    m = graph_model(assembly)
    step = gs.contact_step
    calls = []

    def told(*args):
        calls.append((args[8], args[5].copy(), args[6].copy()))
        its = step(*args)
        return -1 if len(calls) - 1 in unsettled else its

    monkeypatch.setattr(gr, "contact_step", told)
    out = gr.run.py_func(m, 1.0, ground.t, ground.a, 1.0, h, t_end, ground.duration, GAP_TOL,
                         0, *EMPTY, False, False)
    return out, calls


@pytest.fixture(scope="module")
def column():
    # two stacked drums with friction: the general stepper (not the frictionless chain)
    drum = np.array([[-0.15, 0.0], [0.15, 0.0], [0.15, 0.9], [-0.15, 0.9]])
    return bd.from_polygons([drum, drum + [0.0, 0.9]], mu=0.6)


def test_an_unsettled_step_runs_again_as_substeps_from_its_start(column, monkeypatch):
    # a pulse below ap,min: the column rests, every step is one step of h, so the substeps
    # seen after the told step are the retry's own
    ground = motion.pulse("sine", period=0.5, ap=0.5 * column.ap_min)
    h = 2e-3
    k = 20
    out, calls = _run(column, ground, h, 0.1, {k}, monkeypatch)
    lengths = [c[0] for c in calls]
    assert lengths[:k + 1] == [h] * (k + 1)
    # the same step again as REFINE substeps, then steps of h
    assert lengths[k + 1:k + 1 + kin.REFINE] == pytest.approx([h / kin.REFINE] * kin.REFINE,
                                                             rel=1e-12)
    assert lengths[k + 1 + kin.REFINE] == h
    # from the step's start: gravity applied over h/REFINE instead of h to the velocities
    # saved before the told step (vy), the rotation rates as they were (om); exact up to
    # rounding
    _, vy_told, om_told = calls[k]
    _, vy_again, om_again = calls[k + 1]
    g = column.g
    np.testing.assert_allclose(vy_again, vy_told + h * g - h / kin.REFINE * g, rtol=0,
                               atol=1e-12)
    np.testing.assert_array_equal(om_again, om_told)
    # the substeps settled: no failed step; the whole record's steps were run
    assert out[7] == 0
    assert out[6] == int(np.ceil(0.1 / h))
    assert out[0] == 0  # at rest, as without the retry


def test_substeps_that_do_not_settle_count_as_failed_and_the_run_goes_on(column, monkeypatch):
    # the told step and its substeps: each substep counts, none is retried again
    ground = motion.pulse("sine", period=0.5, ap=0.5 * column.ap_min)
    h = 2e-3
    k = 20
    told = {k, *range(k + 1, k + 1 + kin.REFINE)}
    out, calls = _run(column, ground, h, 0.1, told, monkeypatch)
    lengths = [c[0] for c in calls]
    assert lengths[k + 1 + kin.REFINE] == h  # no retry of a substep
    assert out[7] == kin.REFINE
    assert out[6] == int(np.ceil(0.1 / h))


def test_a_retried_step_keeps_the_history_of_a_rocking_column(column, monkeypatch):
    # the column rocks under a sine of 1.3 ap,min (as in validation/siconos_compare.py); one
    # step in the strong motion told unsettled runs as three substeps: a change of the step
    # over one step of ~300, whose effect on the history is of the order of Moreau-Jean's
    # O(h) error: the largest rotation / delta within 5 % of the run without it (the same
    # band as the comparison with Siconos at equal steps), the verdict the same
    ground = motion.pulse("sine", period=0.7, ap=1.3 * column.ap_min)
    h = mdof.simulate(column, ground, t_free=0.0).h
    plain, calls0 = _run(column, ground, h, ground.duration, set(), monkeypatch)
    k = len(calls0) // 2
    retried, calls = _run(column, ground, h, ground.duration, {k}, monkeypatch)
    assert calls[k + 1][0] == pytest.approx(h / kin.REFINE, rel=1e-12)
    # in motion, the step's start restored: om as it was (exact), vy with gravity over
    # h/REFINE instead of h, up to the turn of the centroid velocity with its body over the
    # half step to the midpoint (kin.advance: at most |om|·h/2·|v|)
    (_, vy_told, om_told), (_, vy_again, om_again) = calls[k], calls[k + 1]
    assert np.abs(om_told).max() > 0.01
    np.testing.assert_array_equal(om_again, om_told)
    turn = np.abs(om_told).max() * h / 2 * (np.abs(vy_told).max() + column.g * h)
    np.testing.assert_allclose(vy_again, vy_told + h * column.g * (1 - 1 / kin.REFINE),
                               rtol=0, atol=2 * turn)
    assert turn < 0.01 * np.abs(vy_told).max()  # a bound that still tells a wrong start
    assert retried[7] == 0 and plain[7] == 0
    assert retried[0] == plain[0]
    assert plain[2] > 0.05  # it rocks
    assert retried[2] == pytest.approx(plain[2], rel=0.05)
