"""Contact solve with Coulomb friction for any contact graph: non-smooth Gauss–Seidel.

The per-step problem (docs/theory.md Eqs. (9.1)–(9.3)): for every joint k, corner rows
3k, 3k+1 (normal impulses Λ_n ≥ 0 ⊥ U_n ≥ 0) and one tangential row 3k+2 with the 2-D
(two-sided, hence exactly linear) Coulomb cone of the joint

    |Λ_t| ≤ μ·(Λ_n0 + Λ_n1),   U_t ≠ 0  ⇒  Λ_t = −μ·(Λ_n0 + Λ_n1)·sign(U_t),

or, for μ = ∞, the no-slip row U_t = 0 (Λ_t free) while a corner carries an impulse and
Λ_t = 0 when neither does (the limit μ → ∞ of the cone: no shear without compression).
It is solved by non-smooth (block) Gauss–Seidel, the method of Jean and Moreau's NSCD
(LMGC90, Siconos): joint after joint, the joint's 3×3 problem is solved *exactly* with the
others' impulses fixed, by enumerating its 4 (μ = ∞) or 12 contact states (each corner
closed/open × stick/slip+/slip−), each a 3×3 linear solve; sweeps alternate direction and
are warm-started from the previous step.
The sweeps stop when a sweep changes no joint's relative velocity by more than
``SWEEP_TOL``·g·h, the tolerance of the local solves' sign conditions too; a step that does
not converge within ``NSGS_MAX_SWEEPS`` sweeps counts as a failure (``lcp_failures``).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

#: Sign tolerance of the banded solve (graph_run), relative to g·h.
NSGS_TOL = 1e-6
#: Convergence of the Gauss–Seidel sweeps: largest change of a contact velocity in a sweep,
#: relative to g·h. Gauss–Seidel converges slowly on a hyperstatic graph (a wall), so the
#: sweeps stop at 1e-3·g·h: on a 42-block wall under sine pulses up to 4·ap,min the largest
#: slip agrees with the exact banded solve within 0.1 % (docs/performance.md), at a tenth
#: of the cost of 1e-4 and 1/50 of 1e-6.
SWEEP_TOL = 1e-3
#: Sweeps before a step counts as a failure.
NSGS_MAX_SWEEPS = 2000


@nb.njit(cache=True, inline="always")
def solve3(a, r, out):
    """Solve the 3×3 system a·out = r (Gaussian elimination, partial pivoting; a, r are
    overwritten). Returns False if a is (numerically) singular."""
    for c in range(3):
        p = c
        for i in range(c + 1, 3):
            if abs(a[i, c]) > abs(a[p, c]):
                p = i
        if abs(a[p, c]) < 1e-300:
            return False
        if p != c:
            for j in range(3):
                tmp = a[c, j]
                a[c, j] = a[p, j]
                a[p, j] = tmp
            tmp = r[c]
            r[c] = r[p]
            r[p] = tmp
        for i in range(c + 1, 3):
            f = a[i, c] / a[c, c]
            if f != 0.0:
                for j in range(c, 3):
                    a[i, j] -= f * a[c, j]
                r[i] -= f * r[c]
    for i in range(2, -1, -1):
        s = r[i]
        for j in range(i + 1, 3):
            s -= a[i, j] * out[j]
        out[i] = s / a[i, i]
    return True


@nb.njit(cache=True)
def _case_system(w, q, mu, case, a, r):
    """The linear system of one contact state: case % 4 = open corners (bit 0: corner 0,
    bit 1: corner 1), case // 4 = 0 stick, 1 slip with U_t > 0, 2 slip with U_t < 0."""
    sn = case % 4
    st = case // 4
    for c in range(2):
        if (sn >> c) & 1:
            a[c, 0] = 0.0
            a[c, 1] = 0.0
            a[c, 2] = 0.0
            a[c, c] = 1.0
            r[c] = 0.0
        else:
            a[c, 0] = w[c, 0]
            a[c, 1] = w[c, 1]
            a[c, 2] = w[c, 2]
            r[c] = -q[c]
    if sn == 3 and math.isinf(mu):
        # both corners open: no normal impulse, so no shear either (μ → ∞ limit of Coulomb)
        a[2, 0] = 0.0
        a[2, 1] = 0.0
        a[2, 2] = 1.0
        r[2] = 0.0
    elif st == 0:
        a[2, 0] = w[2, 0]
        a[2, 1] = w[2, 1]
        a[2, 2] = w[2, 2]
        r[2] = -q[2]
    else:
        s = mu if st == 1 else -mu
        a[2, 0] = s
        a[2, 1] = s
        a[2, 2] = 1.0
        r[2] = 0.0


@nb.njit(cache=True)
def local_solve(w, q, mu, case0, lam, a, r, sol, tol_u, tol_l):
    """Exact solution of one joint's contact problem U = w·Λ + q (module docstring).

    Tries the contact states starting from ``case0`` (the joint's last one); the first whose
    solution satisfies every sign condition within (tol_u, tol_l) is written to ``lam``.
    Returns its state, or −1 − (least-violating state) if none does (that one is written).
    """
    ncase = 4 if math.isinf(mu) else 12
    best = -1
    best_v = math.inf
    b0 = 0.0
    b1 = 0.0
    b2 = 0.0
    for idx in range(ncase):
        case = (case0 + idx) % ncase
        _case_system(w, q, mu, case, a, r)
        if not solve3(a, r, sol):
            continue
        sn = case % 4
        st = case // 4
        viol = 0.0
        for c in range(2):
            if (sn >> c) & 1:
                u = q[c] + w[c, 0] * sol[0] + w[c, 1] * sol[1] + w[c, 2] * sol[2]
                viol = max(viol, -u / tol_u)
            else:
                viol = max(viol, -sol[c] / tol_l)
        if ncase == 12:
            ut = q[2] + w[2, 0] * sol[0] + w[2, 1] * sol[1] + w[2, 2] * sol[2]
            if st == 0:
                viol = max(viol, (abs(sol[2]) - mu * (sol[0] + sol[1])) / tol_l)
            elif st == 1:
                viol = max(viol, -ut / tol_u)
            else:
                viol = max(viol, ut / tol_u)
        if viol <= 1.0:
            lam[0] = sol[0]
            lam[1] = sol[1]
            lam[2] = sol[2]
            return case
        if viol < best_v:
            best_v = viol
            best = case
            b0 = sol[0]
            b1 = sol[1]
            b2 = sol[2]
    lam[0] = b0
    lam[1] = b1
    lam[2] = b2
    return -1 - max(best, 0)


@nb.njit(cache=True, inline="always")
def joint_velocity(k, ba, bb, ja, jb, bias, vx, vy, om, u):
    """Relative velocities (3 rows of joint k, bias included) at the bodies' velocities."""
    a = ba[k]
    b = bb[k]
    for i in range(3):
        r = 3 * k + i
        s = bias[r]
        if a >= 0:
            s += ja[r, 0] * vx[a] + ja[r, 1] * vy[a] + ja[r, 2] * om[a]
        if b >= 0:
            s += jb[r, 0] * vx[b] + jb[r, 1] * vy[b] + jb[r, 2] * om[b]
        u[i] = s


@nb.njit(cache=True, inline="always")
def apply_impulse(k, ba, bb, ja, jb, d, im, ii, vx, vy, om):
    """Velocities += M⁻¹·J_kᵀ·d (d: impulse increments of the 3 rows of joint k)."""
    a = ba[k]
    b = bb[k]
    for i in range(3):
        if d[i] == 0.0:
            continue
        r = 3 * k + i
        if a >= 0:
            vx[a] += ja[r, 0] * d[i] * im[a]
            vy[a] += ja[r, 1] * d[i] * im[a]
            om[a] += ja[r, 2] * d[i] * ii[a]
        if b >= 0:
            vx[b] += jb[r, 0] * d[i] * im[b]
            vy[b] += jb[r, 1] * d[i] * im[b]
            om[b] += jb[r, 2] * d[i] * ii[b]


@nb.njit(cache=True)
def nsgs(nj, ba, bb, ja, jb, wl, bias, mu, im, ii, vx, vy, om, lam, case, tol_u, tol_l):
    """Gauss–Seidel sweeps until converged (module docstring). (vx, vy, om) must already
    include M⁻¹·Jᵀ·lam (the warm start); ``case`` holds every joint's last contact state.
    Returns the number of sweeps (negative: not converged)."""
    u = np.empty(3)
    q = np.empty(3)
    ln = np.empty(3)
    d = np.empty(3)
    a = np.empty((3, 3))
    r = np.empty(3)
    sol = np.empty(3)
    su = tol_u * (SWEEP_TOL / NSGS_TOL)
    sl = tol_l * (SWEEP_TOL / NSGS_TOL)
    for sweep in range(NSGS_MAX_SWEEPS):
        worst = 0.0
        for kk in range(nj):
            k = kk if sweep % 2 == 0 else nj - 1 - kk
            w = wl[k]
            joint_velocity(k, ba, bb, ja, jb, bias, vx, vy, om, u)
            for i in range(3):
                q[i] = u[i] - (w[i, 0] * lam[3 * k] + w[i, 1] * lam[3 * k + 1]
                               + w[i, 2] * lam[3 * k + 2])
            c = local_solve(w, q, mu[k], max(case[k], 0), ln, a, r, sol, su, sl)
            case[k] = c if c >= 0 else -1 - c
            for i in range(3):
                d[i] = ln[i] - lam[3 * k + i]
            for i in range(3):
                du = abs(w[i, 0] * d[0] + w[i, 1] * d[1] + w[i, 2] * d[2])
                if du > worst:
                    worst = du
                lam[3 * k + i] = ln[i]
            apply_impulse(k, ba, bb, ja, jb, d, im, ii, vx, vy, om)
        if worst <= su:
            return sweep + 1
    return -NSGS_MAX_SWEEPS
