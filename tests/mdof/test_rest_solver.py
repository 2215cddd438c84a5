"""The rest path of wide contact graphs (docs/theory.md Eq. (9.7)): exact where it applies,
refused where the structure must move."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rockarch import mdof
from rockarch.core.constants import G
from rockarch.mdof import builders as bd
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof import rest_solver as rs
from rockarch.mdof.chain_solver import EPS_REG
from rockarch.mdof.graph_solver import NSGS_TOL, SWEEP_TOL
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro


def test_band_cholesky_solves_like_numpy():
    # a random banded SPD matrix (diagonally dominant: cond < 10, so round-off ~1e-15 and
    # 1e-12 is a safe bound) solved by the banded factor against numpy's dense solve
    rng = np.random.default_rng(1)
    n, kd = 30, 6
    a = np.zeros((n, n))
    for i in range(n):
        for j in range(i, min(n, i + kd + 1)):
            a[i, j] = a[j, i] = rng.uniform(-1.0, 1.0)
        a[i, i] = 2.0 * kd + 3.0
    band = np.array([[a[i, i + d] if i + d < n else 0.0 for d in range(kd + 1)]
                     for i in range(n)])
    assert rs.band_cholesky(n, band, np.diag(a).copy())
    b = rng.normal(size=n)
    x = b.copy()
    rs.band_substitute(n, band, x)
    assert np.allclose(x, np.linalg.solve(a, b), rtol=0.0, atol=1e-12)
    # a body held by nothing: a zero row is refused (the pivot test), not divided by
    a[3, :] = a[:, 3] = 0.0
    band = np.array([[a[i, i + d] if i + d < n else 0.0 for d in range(kd + 1)]
                     for i in range(n)])
    assert not rs.band_cholesky(n, band, np.maximum(np.diag(a), 1.0))


def _one_step(a, ag, force_gs=False):
    """One contact solve of the assembly at rest in its reference configuration under
    gravity and a horizontal ground acceleration ag, on the wide-graph solver (forced for a
    narrow graph): (iterations, v⁺, Λ, model, ws, h)."""
    m = graph_model(a)._replace(banded=False)
    nj, nbod = m.n0.shape[0], m.mass.shape[0]
    ws = gs.make_work(m, 1.0, np.zeros(3 * nj), np.zeros(nj, dtype=np.int64))
    rw = rs.make_rest_work(m, 1.0)
    if force_gs:
        rw.rstate[1] = math.inf  # the gate: as if the structure were moving
    h = 0.005 / a.p_ref
    wmax = max(ws.im.max(), (ws.ii * m.thick_min ** 2).max())
    tol_u = NSGS_TOL * G * h
    x, y, ph = m.c0[:, 0].copy(), m.c0[:, 1].copy(), np.zeros(nbod)
    vx, vy, om = np.full(nbod, -h * ag), np.full(nbod, -h * G), np.zeros(nbod)
    its = gs.contact_step(m, x, y, ph, vx, vy, om, 1e-4 * m.thick_min, h, EPS_REG * wmax,
                          tol_u, tol_u / wmax, ws, rw)
    return its, np.column_stack([vx, vy, om * m.thick_min]), ws.lam.copy(), m, ws, h


def _ground_reaction(m, ws, lam):
    """Total impulse the ground joints give the structure (x, y)."""
    f = np.zeros(2)
    for k in range(m.n0.shape[0]):
        for i in range(3):
            r = 3 * k + i
            if m.ba[k] < 0:
                f += ws.jb[r, :2] * lam[r]
            elif m.bb[k] < 0:
                f += ws.ja[r, :2] * lam[r]
    return f


def test_rest_path_solves_a_resting_wall_exactly():
    # a 42-block running-bond wall (mu = 0.6, ap,min = 0.6 g) at rest under 0.3 g: every
    # block moves with the ground. The rest path takes the step (0 sweeps) from a cold
    # start, leaves velocities at its balance tolerance (1e-7·g·h) and impulses inside the
    # cones, and the ground's reaction equals the wall's inertia and weight, M·h·(a, g)
    # (statics; 1e-9 of it is round-off over 108 joints)
    a = bd.wall(4, 10, 0.4, 0.2, mu=0.6)
    assert not graph_model(a).banded
    its, v, lam, m, ws, h = _one_step(a, 0.3 * G)
    assert its == 0
    assert np.abs(v).max() <= 0.1 * NSGS_TOL * G * h
    ln = lam.reshape(-1, 3)
    assert ln[:, :2].min() >= 0.0
    assert np.all(np.abs(ln[:, 2]) <= m.mu * ln[:, :2].sum(axis=1) * (1 + 1e-12))
    total = m.mass.sum() * h * np.array([0.3 * G, G])
    assert np.allclose(_ground_reaction(m, ws, lam), total, rtol=1e-9)
    # Gauss–Seidel (forced) on the same step needs tens of sweeps and stops on the change
    # per sweep (SWEEP_TOL·g·h), not on the residual: it leaves velocities far above the rest
    # path's, and its reaction differs from the exact one by the momentum M·v⁺ they carry
    its_gs, v_gs, lam_gs, *_ = _one_step(a, 0.3 * G, force_gs=True)
    assert its_gs > 10 and np.abs(v_gs).max() > 100 * np.abs(v).max()
    assert np.allclose(_ground_reaction(m, ws, lam_gs), total, rtol=0.0,
                       atol=m.mass.sum() * np.abs(v_gs).max())


def test_rest_path_refuses_a_sliding_block():
    # one block (B/H = 0.5, mu = 0.1) under 0.5 g must slide: the rest path has no
    # admissible impulse (it would need |Λ_t| = 0.5·m·g·h > 0.1·m·g·h) and the step goes
    # to Gauss–Seidel, whose one Moreau–Jean step is Newmark's: the block slides at
    # h·(a − μ·g) relative to the ground (to the sweep tolerance)
    a = dataclasses.replace(mdof.single_block(0.5, 1.0), mu=np.array([0.1]))
    its, v, lam, m, ws, h = _one_step(a, 0.5 * G)
    assert its > 0
    assert v[0, 0] == pytest.approx(-h * (0.5 - 0.1) * G, abs=SWEEP_TOL * G * h)


def test_wall_on_a_weak_record_rests_on_the_rest_path():
    # the 42-block wall on El Centro at 0.5·ap,min (0.3 g < mu·g and < B/H·g of any block or
    # course): nothing can slide or rock, the exact solution is rest. Almost every step
    # takes the rest path, no step fails, and the slip stays at round-off and projection
    # drift (1e-6 m; Gauss–Seidel alone drifted 6e-5 m here at its sweep tolerance)
    from rockarch.mdof import graph_run

    a = bd.wall(4, 10, 0.4, 0.2, mu=0.6)
    rec = el_centro()
    keep = rec.t <= 5.0
    m = motion.GroundMotion(rec.t[keep], rec.a[keep], "El Centro").scaled(
        0.5 * a.ap_min / rec.pga)
    out = graph_run.run(graph_model(a), 1.0, m.t, m.a, 1.0, 0.005 / a.p_ref, m.duration,
                        m.duration, 1e-4, 0, np.zeros(0), np.zeros((0, 1, 3)),
                        np.zeros((0, 1), np.int8), np.zeros(0))
    status, steps, fails, max_slip, rest = out[0], out[6], out[7], out[8], out[10]
    assert status == 0 and fails == 0
    assert rest >= 0.95 * steps
    assert max_slip < 1e-6
