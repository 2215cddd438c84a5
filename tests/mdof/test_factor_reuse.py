"""The contact solve keeps its LU factors from step to step (docs/theory.md Eq. (9.12)):
the reuse happens on a sliding wall, and gives the solve on fresh factors. The steps of
that wall that need the proximal continuation (Eq. (9.9)) end with the contact law met
within its tolerance."""

from __future__ import annotations

import numpy as np

from rockarch.mdof import builders as bd
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof import kinematics as kin
from rockarch.mdof.contact_solver import law_residual
from rockarch.mdof.kernel_data import graph_model

G = 9.81


def test_sliding_wall_reuses_the_factors_and_solves_as_fresh_ones():
    # the 42-block running-bond wall (mu = 0.6, ap,min = 0.6 g) under a constant ground
    # acceleration of 0.8 g for 0.15 s, then -0.8 g for 0.05 s, h = 1e-3 s: it slides as one
    # body. Every step is solved twice from the same configuration, warm start and free
    # velocities: with the factors kept from the last step (the engine) and with them
    # discarded (every step factorises anew). Both end with the contact law met within the
    # solver's tolerance tol_u at the current Jacobian, so their velocities agree within tol_u
    # (measured: 0.08·tol_u), while the kept factors save most factorisations (measured: 122
    # against 494 in 200 steps; asserted: fewer than half, and fewer than one per step)
    m = graph_model(bd.wall(4, 10, 0.4, 0.2, mu=0.6))
    h = 1e-3
    keep = gs.make_work(m, 1.0, m.contact_cap)
    fresh = gs.make_work(m, 1.0, m.contact_cap)
    wmax = max(keep.im.max(), (keep.ii * m.thick_min ** 2).max())
    eps = gr.EPS_T * wmax
    tol_u = gr.LAM_TOL * G * h
    tol_l = tol_u / wmax
    gtol = 1e-4 * m.thick_min
    x, y, ph, vx, vy, om = kin.at_rest(m.c0[:, 0].copy(), m.c0[:, 1].copy())
    xm, ym, phm = kin.triple(x.shape[0])
    screw = np.ones(x.shape[0], dtype=bool)  # every block on its contacts (kin.advance)
    n_steps, dv, worst, prox_steps = 200, 0.0, 0.0, 0
    for step in range(n_steps):
        ag = 0.8 * G if step < 150 else -0.8 * G
        kin.advance(x, y, ph, vx, vy, om, 0.5 * h, xm, ym, phm, screw)
        vx -= h * ag
        vy -= h * G
        vf = (vx.copy(), vy.copy(), om.copy())
        before = keep.sw.state[7]
        fresh.lam[:] = keep.lam
        fresh.sw.st[:] = keep.sw.st
        fresh.sw.state[0] = 0  # no valid factors: the solve factorises anew
        assert gs.contact_step(m, xm, ym, phm, vx, vy, om, gtol, h, 1.5 * G * h, eps, eps, tol_u,
                               tol_l, -1.0, keep) >= 0
        assert gs.contact_step(m, xm, ym, phm, *vf, gtol, h, 1.5 * G * h, eps, eps, tol_u, tol_l,
                               -1.0, fresh) >= 0
        dv = max(dv, np.abs(vx - vf[0]).max(), np.abs(vy - vf[1]).max(),
                 (np.abs(om - vf[2]) * m.thick_min).max())
        if keep.sw.state[7] > before:  # this step needed the proximal continuation
            prox_steps += 1
            v = np.column_stack([vx, vy, om]).ravel()
            n_rows = 3 * m.n0.shape[0] + 2 * keep.cnt[0]  # joints' rows, point contacts' rows
            worst = max(worst, law_residual(n_rows, keep.rows, keep.bias, keep.lam, eps, eps,
                                            keep.sw, v))
        kin.advance(xm, ym, phm, vx, vy, om, 0.5 * h, x, y, ph, screw)
    slide = np.abs(x - m.c0[:, 0])
    assert slide.min() > 0.01 and np.ptp(x - m.c0[:, 0]) < 1e-6  # slides as one body
    assert np.abs(ph).max() < 1e-6  # without turning: J moves by round-off only
    assert dv <= tol_u
    factorisations, fresh_factorisations = keep.sw.state[2], fresh.sw.state[2]
    assert fresh_factorisations >= n_steps
    assert factorisations < min(0.5 * fresh_factorisations, n_steps)
    # the continuation stops at rho·|Λ − Λ_k| <= tol_u and the states change only where
    # violated by more than tol_u (tol_l): the law's natural residual is tol_u plus that
    # hysteresis, asserted within 2·tol_u (measured: 0.22·tol_u over the 2 such steps;
    # 1.2e7·tol_u, 0.1 m/s, over 10 such steps before a proximal step tested a sliding row
    # on its proximal velocity u + (ε + ρ)·Λ_t, docs/theory.md Eq. (9.9): such a row could
    # slide along its friction force)
    assert prox_steps >= 1  # the check is not empty (measured: 2 steps of 200)
    assert worst <= 2.0 * tol_u
