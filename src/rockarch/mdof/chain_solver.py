"""Exact contact solve of the chain stepper: banded Cholesky and a primal active-set QP.

The per-step contact problem of a chain (docs/theory.md Eqs. (6.2)–(6.3)) is the strictly
convex QP  min ½ΛᵀWΛ + ΛᵀU_free, Λ_n ≥ 0, with W = J·M⁻¹·Jᵀ block-tridiagonal (half-bandwidth
``KD``). Rows come in threes per joint: the two corner (normal) rows 3k, 3k+1 and the
no-slip row 3k+2. Reach it through :mod:`rockarch.mdof.chain_stepper`.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

KD = 5  # half-bandwidth of W (3 rows per joint, neighbouring joints share one body)
_MAX_PIVOTS = 200
#: Regularisation of W (relative to its largest diagonal term): W + eps·I is positive
#: definite, so the LCP has one solution even for a statically indeterminate (closed) arch;
#: it lets a closed contact creep at U_n = −eps·Λ (≈ 1e-8·g·h: negligible).
EPS_REG = 1e-8
#: Sign tolerance of the pivoting (relative to g·h): above the solve's round-off (cond ≈ 1/EPS_REG).
TOL_LCP = 1e-7


@nb.njit(cache=True, inline="always")
def _band_solve(n, kb, rhs, lb, out, kd):
    """:func:`band_solve` for half-bandwidth kd (inlined: a constant kd is unrolled). The
    rows with a full band (i ≥ kd, all but the first kd) run loops of constant length
    (kd − d terms), which the compiler unrolls into straight code, and the arrays are
    indexed with unsigned indices (no test for a negative index wrapping around): the same
    arithmetic in the same order as the plain loops of the first rows."""
    for i in range(n):
        iu = np.uint64(i)
        for d in range(kd, -1, -1):
            j = i - d
            if j < 0:
                continue
            ju = np.uint64(j)
            s = kb[iu, np.uint64(d)]
            if i >= kd:  # a full row of the band: constant trip counts (unrolled)
                for e in range(kd - d):  # k = i − kd + e, ascending as below
                    s -= lb[iu, np.uint64(kd - e)] * lb[ju, np.uint64(kd - d - e)]
            else:
                for k in range(j):
                    s -= lb[iu, np.uint64(i - k)] * lb[ju, np.uint64(j - k)]
            if d == 0:
                if s <= 0.0:
                    return False
                lb[iu, np.uint64(0)] = math.sqrt(s)
            else:
                lb[iu, np.uint64(d)] = s / lb[ju, np.uint64(0)]
    for i in range(n):
        iu = np.uint64(i)
        s = rhs[iu]
        if i >= kd:
            for e in range(kd):
                s -= lb[iu, np.uint64(kd - e)] * out[np.uint64(i - kd + e)]
        else:
            for k in range(i):
                s -= lb[iu, np.uint64(i - k)] * out[np.uint64(k)]
        out[iu] = s / lb[iu, np.uint64(0)]
    for i in range(n - 1, -1, -1):
        iu = np.uint64(i)
        s = out[iu]
        if i + kd < n:
            for e in range(1, kd + 1):
                ku = np.uint64(i + e)
                s -= lb[ku, np.uint64(e)] * out[ku]
        else:
            for k in range(i + 1, n):
                ku = np.uint64(k)
                s -= lb[ku, np.uint64(k - i)] * out[ku]
        out[iu] = s / lb[iu, np.uint64(0)]
    return True


@nb.njit(cache=True)
def band_solve(n, kb, rhs, lb, out):
    """Cholesky of the banded SPD matrix kb (lower band, half-bandwidth kb.shape[1] − 1)
    into lb, then solve for rhs. Chains (half-bandwidth KD) run a copy with KD a
    compile-time constant, which the compiler unrolls (10 % of a chain's run time)."""
    kd = kb.shape[1] - 1
    if kd == KD:
        return _band_solve(n, kb, rhs, lb, out, KD)
    return _band_solve(n, kb, rhs, lb, out, kd)


@nb.njit(cache=True)
def masked_band(n, wb, rows, eps, kb):
    """The band of W (+ eps on the diagonal) restricted to ``rows``; the other rows and
    columns become the identity, so that one banded solve gives the subproblem."""
    for i in range(n):
        for d in range(KD + 1):
            j = i - d
            if j < 0:
                kb[i, d] = 0.0
            elif rows[i] and rows[j]:
                kb[i, d] = wb[i, d] + (eps if d == 0 else 0.0)
            else:
                kb[i, d] = 1.0 if d == 0 else 0.0


@nb.njit(cache=True, inline="always")
def wmul(n, wb, lam, i, kd):
    """(W·lam)_i from the lower band of half-bandwidth kd (inlined: a constant kd, the
    chain's KD, is unrolled by the compiler)."""
    s = wb[i, 0] * lam[i]
    for d in range(1, kd + 1):
        j = i - d
        if j >= 0:
            s += wb[i, d] * lam[j]
        j = i + d
        if j < n:
            s += wb[j, d] * lam[j]
    return s


@nb.njit(cache=True)
def lcp(n, wb, ufree, inset, free, lam, kb, lb, rhs, eps, tol_u, tol_l, sol):
    """Exact LCP by a primal active-set method on the equivalent strictly convex QP
    min ½ΛᵀWΛ + ΛᵀU_free,  Λ_n ≥ 0 (normal rows 3k, 3k+1), Λ_s free (no-slip rows 3k+2
    with ``inset``; the other rows are fixed at 0); W is a chain's band (half-bandwidth KD).

    ``free`` (warm start in, final working set out): rows not held at their bound. Starts
    from Λ = 0 (feasible); every full step strictly lowers the objective, so it cannot
    cycle. Returns the number of iterations (negative if it did not finish).
    """
    for i in range(n):
        lam[i] = 0.0
        if i % 3 == 2:
            free[i] = inset[i]
    for it in range(_MAX_PIVOTS):
        masked_band(n, wb, free, eps, kb)
        for i in range(n):
            rhs[i] = -ufree[i] if free[i] else 0.0
        if not _band_solve(n, kb, rhs, lb, sol, KD):
            return -1
        # largest feasible step towards the subproblem's solution
        alpha = 1.0
        block = -1
        for i in range(n):
            if free[i] and i % 3 != 2 and sol[i] < 0.0:
                d = sol[i] - lam[i]
                if d < 0.0:
                    a = -lam[i] / d
                    if a < alpha:
                        alpha = a
                        block = i
        for i in range(n):
            lam[i] += alpha * (sol[i] - lam[i])
        if block >= 0 and sol[block] < -tol_l:
            lam[block] = 0.0
            free[block] = False
            continue
        if block >= 0:
            for i in range(n):
                lam[i] = sol[i]
        # optimality: no held row wants to push (U_n ≥ 0 where Λ_n = 0)
        worst = -tol_u
        add = -1
        for i in range(n):
            if i % 3 == 2 or free[i]:
                continue
            u = ufree[i] + wmul(n, wb, lam, i, KD)
            if u < worst:
                worst = u
                add = i
        if add < 0:
            for i in range(n):
                if i % 3 != 2 and lam[i] < 0.0:
                    lam[i] = 0.0
            return it + 1
        free[add] = True
    return -_MAX_PIVOTS


@nb.njit(cache=True, inline="always")
def _box_qp(n, wb, q, lo, hi, st, lam, kb, lb, rhs, sol, eps, tol_u, tol_l, kd):
    for i in range(n):
        if lo[i] == hi[i]:
            st[i] = 1
        lam[i] = lo[i] if st[i] == 1 else (hi[i] if st[i] == 2 else min(max(0.0, lo[i]),
                                                                         hi[i]))
    for it in range(_MAX_PIVOTS):
        for i in range(n):
            s = -q[i]
            for d in range(kd + 1):
                j = i - d
                if j < 0:
                    kb[i, d] = 0.0
                elif st[i] == 0 and st[j] == 0:
                    kb[i, d] = wb[i, d] + (eps if d == 0 else 0.0)
                else:
                    kb[i, d] = 1.0 if d == 0 else 0.0
            if st[i] == 0:
                for d in range(1, kd + 1):  # held rows enter the free rows' right-hand side
                    j = i - d
                    if j >= 0 and st[j] != 0:
                        s -= wb[i, d] * lam[j]
                    j = i + d
                    if j < n and st[j] != 0:
                        s -= wb[j, d] * lam[j]
                rhs[i] = s
            else:
                rhs[i] = lam[i]
        if not _band_solve(n, kb, rhs, lb, sol, kd):
            return -1
        alpha = 1.0
        block = -1
        side = 0
        for i in range(n):
            if st[i] != 0:
                continue
            dl = sol[i] - lam[i]
            if sol[i] < lo[i] and dl < 0.0:
                a = (lo[i] - lam[i]) / dl
                if a < alpha:
                    alpha, block, side = a, i, 1
            elif sol[i] > hi[i] and dl > 0.0:
                a = (hi[i] - lam[i]) / dl
                if a < alpha:
                    alpha, block, side = a, i, 2
        for i in range(n):
            lam[i] += alpha * (sol[i] - lam[i])
        if block >= 0 and (sol[block] < lo[block] - tol_l or sol[block] > hi[block] + tol_l):
            lam[block] = lo[block] if side == 1 else hi[block]
            st[block] = side
            continue
        if block >= 0:
            for i in range(n):
                lam[i] = sol[i]
        worst = tol_u
        add = -1
        for i in range(n):
            if st[i] == 0 or lo[i] == hi[i]:
                continue
            u = q[i] + wmul(n, wb, lam, i, kd) + eps * lam[i]
            v = -u if st[i] == 1 else u  # held at lo: wants to go lower iff u < 0
            if v > worst:
                worst = v
                add = i
        if add < 0:
            for i in range(n):
                lam[i] = min(max(lam[i], lo[i]), hi[i])
            return it + 1
        st[add] = 0
    return -_MAX_PIVOTS


@nb.njit(cache=True)
def box_qp(n, wb, q, lo, hi, st, lam, kb, lb, rhs, sol, eps, tol_u, tol_l):
    """min ½ΛᵀWΛ + Λᵀq subject to lo ≤ Λ ≤ hi (W banded, any half-bandwidth wb.shape[1] − 1,
    eps added to its diagonal) by the same
    primal active-set method as :func:`lcp`: ``st`` (warm start in, working set out) is 0
    for a free row, 1 held at lo, 2 held at hi; a row with lo = hi is always held. Returns
    the number of banded solves (negative if it did not finish)."""
    kd = wb.shape[1] - 1
    if kd == KD:  # chains: the constant half-bandwidth, unrolled (as in band_solve)
        return _box_qp(n, wb, q, lo, hi, st, lam, kb, lb, rhs, sol, eps, tol_u, tol_l, KD)
    return _box_qp(n, wb, q, lo, hi, st, lam, kb, lb, rhs, sol, eps, tol_u, tol_l, kd)
