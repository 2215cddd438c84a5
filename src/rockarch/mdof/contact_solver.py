"""Exact contact solve of one Moreau–Jean step for any contact graph (numba).

The step's contact problem (docs/theory.md Eqs. (9.1)–(9.4)): every row r is one scalar
constraint on two bodies ``rba[r]``, ``rbb[r]`` (−1: the ground) with Jacobian coefficients
``ja[r]``, ``jb[r]`` (x, y, rotation) and a bias b_r (the speculative gap / h); normal rows
(``tn0[r] < 0``) carry Λ_n ≥ 0 ⊥ u_n + ε_nΛ_n ≥ 0, tangential rows Coulomb's cone of their
joint, |Λ_t| ≤ μ·(Λ[tn0] + Λ[tn1]), sliding against their velocity, with u_t + ε_tΛ_t = 0
while they stick (u = J·v⁺ + b, v⁺ = v_free + M⁻¹·Jᵀ·Λ).

It is solved in the bodies' velocities by a semismooth Newton (active-set) method on the
rows' states (docs/theory.md Eqs. (9.7)–(9.8)): a normal row is closed (Λ_n = −u_n/ε_n) or open
(0); a tangential row sticks (Λ_t = −u_t/ε_t) or slides (Λ_t = ±μ·ΣΛ_n: the bound enters the
linear system). Eliminating the impulses leaves one linear system in the 3 velocities of
every body,

    H·v⁺ = M·v_free − Σ ε⁻¹·J_rᵀ·(bias terms),
    H = M + Σ_closed ε_n⁻¹J_nᵀJ_n + Σ_stick ε_t⁻¹J_tᵀJ_t + Σ_slide ±μ·ε_n⁻¹·J_tᵀ·ΣJ_n,

banded in a narrow body order whatever the width of the contact graph (a 210-block wall: 630
unknowns, half-bandwidth 35, where the contact-space W has 1740 rows and is singular: the
wall is hyperstatic). H is not symmetric where rows slide (non-associative friction): one
banded LU per iteration, kept from step to step while the states do not change (refined
against the moving Jacobian; a band of half-bandwidth ≤ ``REFINE_KD`` is factorised anew).
Where hundreds of joints open and close at once the plain method need not settle; it is
then globalised by the proximal point method (Eq. (9.9), :func:`solve`), in the largest
problems after an interior-point method (Eq. (9.13), :func:`interior_point`) that gets
there, or near, in a few tens of factorisations. Every step ends with the contact law met
within (tol_u, tol_l) or counts as failed.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from rockarch.core.jit_struct import JitStruct, jit_struct

#: Integer constants reach a kernel as ``_int(C)``, an int64: numba compiles a kernel once
#: per literal value it is called with (docs/performance.md, "Compile time").
_int = np.int64

#: A pivot of the banded LU below this fraction of its row's largest entry: H is singular.
PIVOT_TOL = 1e-13
#: Refinements of a solve on LU factors made for an earlier Jacobian.
REFINE_MAX = 4
#: Up to this half-bandwidth (unknowns; a chain's is 5) the LU factors are not carried into
#: a new step: a new factorisation costs about one refinement, and the step's new Jacobian
#: needs several (measured on the 20-voussoir chain: 0.8 of its 1.4 factorisations per step
#: came after a refinement that did not contract). Within a step they are kept.
REFINE_KD = 8
#: Iterations of one semismooth solve (:func:`semismooth`) within a proximal step: one that
#: has not settled by then is given up, and the step retried with more weight (half the
#: factorisations of the 205-block wall's violent steps went to such solves with 30).
SSN_MAX = 15
#: After this many iterations a μ = ∞ row that sticks keeps sticking for the step (a joint
#: whose compression comes and goes with its own shear cannot make the iteration cycle).
SSN_FREEZE = 3
#: Iterations of the plain semismooth Newton method before the proximal continuation.
SSN_FIRST = 8
#: Proximal steps of :func:`solve` (each a semismooth solve) before the step fails. The
#: violent steps of a 205-block wall under El Centro settle in 17 on the median, the hardest
#: in 210–1160, creeping at a fixed weight (docs/performance.md, "Steps that settle slowly").
PROX_MAX = 2000
#: The proximal continuation stops once the contact law's residual ρ·|Λ − Λ_k| is below
#: tol_u (docs/theory.md Eq. (9.9)), or below this many times tol_u (10⁻⁴·g·h, the speed
#: below which the engine calls a structure at rest, ``graph_run.REST_SPEED``) ...
PROX_TOL = 100.0
#: ... in a problem of more than this many rows (~330 joints: walls of ~200 blocks), whose
#: violent steps took 4.3 times the factorisations at tol_u (docs/performance.md). Smaller
#: problems keep tol_u: at 100·tol_u a slip faster than tol_u counts as sliding (a μ = 1000
#: joint slid), a wall sliding on all its bed joints is warmed up worse after a looser step
#: (27 of the 200 steps of tests/mdof/test_factor_reuse.py need the continuation, 10 at
#: tol_u), and their histories stay those of the stricter solve.
PROX_ROWS = 1000
#: Factor by which the proximal weight ρ falls after a proximal step that settled at once...
PROX_DROP = 10.0
#: ... and rises after one that did not.
PROX_UP = 3.0
#: Where the plain method does not settle in a problem of more than ``PROX_ROWS`` rows
#: without μ = ∞ rows, the interior-point method (:func:`interior_point`) is tried before
#: the proximal continuation, for at most this many iterations (one factorisation each;
#: the continuation then starts from its last iterate). On the 205-block wall's violent
#: steps 20, 30 and 45 gave 56 634, 47 324 and 49 042 factorisations over the first 3 s of
#: El Centro at 2·ap,min (docs/performance.md) ...
IP_MAX = 30
#: ... and given up after this many steps in a row shorter than ``IP_SHORT`` (it stalls).
IP_STALL = 4
IP_SHORT = 0.01
#: Fraction of the step to the boundary of the positive pairs that is taken.
IP_BOUNDARY = 0.995
#: Columns of SolverWork.ip: the variables (0 w or s₁, 1 z₁, 2 s₂, 3 z₂), the direction
#: (4 ΔΛ, 5 Δw or Δs₁, 6 Δz₁, 7 Δs₂, 8 Δz₂), the row's weight in H (9: d or q), its
#: residual (10: R_w or R_t), a tangential row's right-hand side e_t (11) and the
#: complementarity targets (12, 13).
IP_COLS = 14


@jit_struct
class Rows(JitStruct):
    """The step's rows (R of them): a joint's three (corner 0, corner 1, tangential), then a
    point contact's two (normal, tangential); passed by reference
    (:mod:`rockarch.core.jit_struct`)."""

    rba: np.ndarray  # (R,) body of the row's a side (−1: ground or support)
    rbb: np.ndarray  # (R,) body of its b side
    ja: np.ndarray  # (R, 3) the row's Jacobian on body a (x, y, rotation) ...
    jb: np.ndarray  # (R, 3) ... and on body b
    tn0: np.ndarray  # (R,) normal rows that bound a tangential row (−1: a normal row)
    tn1: np.ndarray
    tmu: np.ndarray  # (R,) friction coefficient of a tangential row


@jit_struct
class SolverWork(JitStruct):
    """Work arrays of the contact solve (one per run and stepper workspace), passed by
    reference (:mod:`rockarch.core.jit_struct`)."""

    pos: np.ndarray  # (nb,) place of every body in the band order
    vf: np.ndarray  # (3nb,) free velocities, body j at 3j..3j+2
    v: np.ndarray  # (3nb,) the velocities
    g: np.ndarray  # (3nb,) scratch
    d: np.ndarray  # (3nb,) scratch
    u: np.ndarray  # (R,) J·v + b
    mdiag: np.ndarray  # (3nb,) diagonal of M
    state: np.ndarray  # [factors valid (2), half-bandwidth, factorisations, solves,
    #                     refactorisations after refinement, semismooth solves, iterations,
    #                     steps that needed the proximal continuation, steps solved by
    #                     the interior-point method, its iterations]
    st: np.ndarray  # (R,) int8 states: normal 0 closed, −1 open; tangential 0 stick,
    #                  ±1 slide with Λ_t = ±μΣΛ_n, 2 no shear (μ = ∞ without compression)
    rhs: np.ndarray  # (3nb,) right-hand side
    x: np.ndarray  # (3nb,) band-order scratch
    lu: np.ndarray  # (3nb, 2·cap + 1) full band of H, then its LU factors
    sst: np.ndarray  # (R,) the states the LU factors were made for
    frho: np.ndarray  # [the proximal weight the LU factors were made with]
    ie: np.ndarray  # (R,) 1/(ε_r + ρ) of every row
    sst2: np.ndarray  # (R,) the states of the last proximal iterate
    bias2: np.ndarray  # (R,) b − ρ·Λ_k of the proximal steps
    lamk: np.ndarray  # (R,) Λ_k
    act: np.ndarray  # (R,) bool scratch: the rows H holds
    lurow: np.ndarray  # (cap + 1,) the pivot row of the LU
    ip: np.ndarray  # (R, IP_COLS) the interior-point method's per-row variables and scratch


@nb.njit(cache=True)
def make_solver_work(nbod, n_rows, pos, mass, inertia_scaled, kd_cap):
    """Zeroed work of :func:`solve` for ``nbod`` bodies and up to ``n_rows`` rows; the band
    holds half-bandwidths up to ``kd_cap`` (3 rows per body)."""
    n = 3 * nbod
    mdiag = np.empty(n)
    for j in range(nbod):
        mdiag[3 * j] = mass[j]
        mdiag[3 * j + 1] = mass[j]
        mdiag[3 * j + 2] = inertia_scaled[j]
    return SolverWork(pos.copy(), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
                      np.zeros(n_rows), mdiag, np.zeros(10, dtype=np.int64),
                      np.zeros(n_rows, dtype=np.int8), np.zeros(n), np.zeros(n),
                      np.zeros((n, 2 * min(kd_cap, max(n - 1, 0)) + 1)),
                      np.zeros(n_rows, dtype=np.int8), np.zeros(1), np.zeros(n_rows),
                      np.zeros(n_rows, dtype=np.int8), np.zeros(n_rows), np.zeros(n_rows),
                      np.zeros(n_rows, dtype=np.bool_),
                      np.zeros(min(kd_cap, max(n - 1, 0)) + 1), np.zeros((n_rows, IP_COLS)))


@nb.njit(cache=True, inline="always")
def row_dot(r, rba, rbb, ja, jb, v):
    """J_r·v (v: 3 entries per body). Every array is read before the branches (a ground
    side reads body 0's entries and drops them): an array used inside a branch of an
    inlined helper costs numba two atomic reference counts per call, which cost more than
    the arithmetic (the same operations in the same order either way)."""
    a = rba[r]
    b = rbb[r]
    ia = 3 * max(a, 0)
    ib = 3 * max(b, 0)
    a0 = ja[r, 0] * v[ia]
    a1 = ja[r, 1] * v[ia + 1]
    a2 = ja[r, 2] * v[ia + 2]
    b0 = jb[r, 0] * v[ib]
    b1 = jb[r, 1] * v[ib + 1]
    b2 = jb[r, 2] * v[ib + 2]
    s = 0.0
    if a >= 0:
        s += a0 + a1 + a2
    if b >= 0:
        s += b0 + b1 + b2
    return s


@nb.njit(cache=True, inline="always")
def row_add(r, rba, rbb, ja, jb, c, v):
    """v += c·J_rᵀ (arrays read before the branches: :func:`row_dot`)."""
    a = rba[r]
    b = rbb[r]
    ia = 3 * max(a, 0)
    ib = 3 * max(b, 0)
    a0 = ja[r, 0]
    a1 = ja[r, 1]
    a2 = ja[r, 2]
    b0 = jb[r, 0]
    b1 = jb[r, 1]
    b2 = jb[r, 2]
    if a >= 0:
        v[ia] += c * a0
        v[ia + 1] += c * a1
        v[ia + 2] += c * a2
    if b >= 0:
        v[ib] += c * b0
        v[ib + 1] += c * b1
        v[ib + 2] += c * b2


@nb.njit(cache=True)
def band_needed(n_rows, rba, rbb, act, pos):
    """Half-bandwidth of H for the active rows in the body order ``pos``."""
    kd = 2
    for r in range(n_rows):
        if act[r]:
            a = rba[r]
            b = rbb[r]
            if a >= 0 and b >= 0:
                kd = max(kd, 3 * abs(pos[a] - pos[b]) + 2)
    return kd


@nb.njit(cache=True)
def reorder(nbod, n_rows, rba, rbb, pos):
    """A new narrow body order (reverse Cuthill–McKee on the graph of the rows' body pairs),
    written into ``pos``; every connected part starts at a body of least degree."""
    deg = np.zeros(nbod, dtype=np.int64)
    for r in range(n_rows):
        if rba[r] >= 0 and rbb[r] >= 0:
            deg[rba[r]] += 1
            deg[rbb[r]] += 1
    ptr = np.zeros(nbod + 1, dtype=np.int64)
    for j in range(nbod):
        ptr[j + 1] = ptr[j] + deg[j]
    adj = np.empty(ptr[nbod], dtype=np.int64)
    fill = ptr[:-1].copy()
    for r in range(n_rows):
        a = rba[r]
        b = rbb[r]
        if a >= 0 and b >= 0:
            adj[fill[a]] = b
            fill[a] += 1
            adj[fill[b]] = a
            fill[b] += 1
    seen = np.zeros(nbod, dtype=np.bool_)
    order = np.empty(nbod, dtype=np.int64)
    head = 0
    tail = 0
    while tail < nbod:
        start = -1
        for j in range(nbod):
            if not seen[j] and (start < 0 or deg[j] < deg[start]):
                start = j
        seen[start] = True
        order[tail] = start
        tail += 1
        while head < tail:
            j = order[head]
            head += 1
            first = tail
            for p in range(ptr[j], ptr[j + 1]):
                k = adj[p]
                if not seen[k]:
                    seen[k] = True
                    order[tail] = k
                    tail += 1
            # neighbours by increasing degree (insertion sort: few of them)
            for i in range(first + 1, tail):
                x = order[i]
                q = i - 1
                while q >= first and deg[order[q]] > deg[x]:
                    order[q + 1] = order[q]
                    q -= 1
                order[q + 1] = x
    for i in range(nbod):
        pos[order[nbod - 1 - i]] = i


@nb.njit(cache=True, inline="always")
def _add_outer(p, q, coef, rba, rbb, ja, jb, pos, lu, kd):
    """H += coef·J_pᵀ·J_q (rows p and q on the same two bodies), full band in body order.
    The rows' coefficients are read into tuples first and the band is indexed unsigned
    (numba's reference counts and negative-index tests cost more than the arithmetic)."""
    a = rba[p]
    b = rbb[p]
    ia = 3 * pos[max(a, 0)]
    ib = 3 * pos[max(b, 0)]
    cp = (ja[p, 0], ja[p, 1], ja[p, 2], jb[p, 0], jb[p, 1], jb[p, 2])
    cq = (ja[q, 0], ja[q, 1], ja[q, 2], jb[q, 0], jb[q, 1], jb[q, 2])
    for sp in range(2):
        bp = a if sp == 0 else b
        if bp < 0:
            continue
        ip = ia if sp == 0 else ib
        for sq in range(2):
            bq = a if sq == 0 else b
            if bq < 0:
                continue
            iq = ia if sq == 0 else ib
            for x in range(3):
                f = coef * cp[3 * sp + x]
                if f == 0.0:
                    continue
                i = ip + x
                iu = np.uint64(i)
                for y in range(3):
                    lu[iu, np.uint64(kd + iq + y - i)] += f * cq[3 * sq + y]


@nb.njit(cache=True)
def _ssn_terms(r, st, tn0, tn1, tmu, mu_r):
    """How tangential row r enters H: 0 none, 1 sticking (J_tᵀJ_t), 2 sliding with sign
    st[r] on its joint's free normal rows (sμ·J_tᵀJ_n)."""
    if st[r] == 0:
        return 1
    if st[r] == 2 or math.isinf(mu_r):
        return 0
    return 2


@nb.njit(cache=True)
def _band_mass(nbod, sw, kd):
    """sw.lu ← the full band (half-bandwidth kd, body order sw.pos) of M."""
    lu = sw.lu
    pos = sw.pos
    for i in range(3 * nbod):
        for d in range(2 * kd + 1):
            lu[i, d] = 0.0
    for j in range(nbod):
        for c in range(3):
            lu[3 * pos[j] + c, kd] = sw.mdiag[3 * j + c]


@nb.njit(cache=True)
def _ssn_assemble(nbod, n_rows, rows, bias, st, ie, sw, kd):
    """The full band of H = M + ε⁻¹[Σ_closed J_nᵀJ_n + Σ_stick J_tᵀJ_t
    + Σ_slide s·μ·J_tᵀ·Σ_(closed n of its joint) J_n] (docs/theory.md Eq. (9.10)) in sw.lu,
    and its right-hand side M·v_free − ε⁻¹·(the same rows times their biases) in sw.rhs."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    lu = sw.lu
    pos = sw.pos
    _band_mass(nbod, sw, kd)
    for i in range(3 * nbod):
        sw.rhs[i] = sw.mdiag[i] * sw.vf[i]
    for r in range(n_rows):
        if tn0[r] < 0:
            if st[r] == 0:
                _add_outer(r, r, ie[r], rba, rbb, ja, jb, pos, lu, kd)
                if bias[r] != 0.0:
                    row_add(r, rba, rbb, ja, jb, -ie[r] * bias[r], sw.rhs)
            continue
        kind = _ssn_terms(r, st, tn0, tn1, tmu, tmu[r])
        if kind == 1:
            _add_outer(r, r, ie[r], rba, rbb, ja, jb, pos, lu, kd)
            if bias[r] != 0.0:
                row_add(r, rba, rbb, ja, jb, -ie[r] * bias[r], sw.rhs)
        elif kind == 2:
            for c in range(2):
                q = tn0[r] if c == 0 else tn1[r]
                if q >= 0 and st[q] == 0:
                    f = st[r] * tmu[r] * ie[q]
                    _add_outer(r, q, f, rba, rbb, ja, jb, pos, lu, kd)
                    if bias[q] != 0.0:
                        row_add(r, rba, rbb, ja, jb, -f * bias[q], sw.rhs)


@nb.njit(cache=True)
def _ssn_assemble_rhs(nbod, n_rows, rows, bias, st, ie, sw):
    """The right-hand side of :func:`_ssn_assemble` alone (kept factors)."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    for i in range(3 * nbod):
        sw.rhs[i] = sw.mdiag[i] * sw.vf[i]
    for r in range(n_rows):
        if bias[r] == 0.0 and tn0[r] < 0:
            continue
        if tn0[r] < 0:
            if st[r] == 0:
                row_add(r, rba, rbb, ja, jb, -ie[r] * bias[r], sw.rhs)
            continue
        kind = _ssn_terms(r, st, tn0, tn1, tmu, tmu[r])
        if kind == 1 and bias[r] != 0.0:
            row_add(r, rba, rbb, ja, jb, -ie[r] * bias[r], sw.rhs)
        elif kind == 2:
            for c in range(2):
                q = tn0[r] if c == 0 else tn1[r]
                if q >= 0 and st[q] == 0 and bias[q] != 0.0:
                    row_add(r, rba, rbb, ja, jb, -st[r] * tmu[r] * ie[q] * bias[q], sw.rhs)


@nb.njit(cache=True)
def band_lu(n, a, kd, row):
    """In place LU (no pivoting) of the full band a[i, kd + j − i] = A[i, j]: L unit lower
    below, U on and above the diagonal. False on a vanishing pivot. ``row`` (kd + 1) holds
    the pivot row's upper part, so that the updates read a separate array (they vectorise:
    1.5–1.7× faster, the same arithmetic). The updates index ``a`` itself, not a view of
    its row (a view costs two atomic reference counts per row: 10 % of the factorisation),
    with unsigned indices (no test for a negative index wrapping around: 1.8× faster)."""
    for j in range(n):
        piv = a[j, kd]
        if not abs(piv) > PIVOT_TOL * sw_scale(a, j, kd):
            return False
        top = min(kd, n - 1 - j)
        for e in range(1, top + 1):
            row[e] = a[j, kd + e]
        for d in range(1, top + 1):
            i = j + d
            l_ = a[i, kd - d] / piv
            a[i, kd - d] = l_
            if l_ != 0.0:
                iu = np.uint64(i)
                off = kd - d
                for e in range(1, top + 1):
                    a[iu, np.uint64(off + e)] -= l_ * row[np.uint64(e)]
    return True


@nb.njit(cache=True, inline="always")
def sw_scale(a, j, kd):
    """Largest magnitude in row j of the band of half-bandwidth kd (the pivot test's
    scale; the array may be wider, its entries beyond the band are stale)."""
    s = 0.0
    for d in range(2 * kd + 1):
        s = max(s, abs(a[j, d]))
    return s


@nb.njit(cache=True)
def band_lu_solve(n, a, kd, x):
    """x ← A⁻¹·x with the factors of :func:`band_lu`."""
    for i in range(n):
        s = x[i]
        for d in range(1, min(kd, i) + 1):
            s -= a[i, kd - d] * x[i - d]
        x[i] = s
    for i in range(n - 1, -1, -1):
        s = x[i]
        for d in range(1, min(kd, n - 1 - i) + 1):
            s -= a[i, kd + d] * x[i + d]
        x[i] = s / a[i, kd]


@nb.njit(cache=True)
def _ssn_impulses(n_rows, rows, bias, st, ie, sw, lam):
    """u = J·v + b at sw.v and the impulses of the current states: closed normal and
    sticking rows −u/ε, sliding rows s·μ·ΣΛ_n of their joint, the others 0."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    for r in range(n_rows):
        sw.u[r] = row_dot(r, rba, rbb, ja, jb, sw.v) + bias[r]
    for r in range(n_rows):
        if tn0[r] < 0:
            lam[r] = -sw.u[r] * ie[r] if st[r] == 0 else 0.0
    for r in range(n_rows):
        if tn0[r] < 0:
            continue
        kind = _ssn_terms(r, st, tn0, tn1, tmu, tmu[r])
        if kind == 1:
            lam[r] = -sw.u[r] * ie[r]
        elif kind == 2:
            s = lam[tn0[r]] + (lam[tn1[r]] if tn1[r] >= 0 else 0.0)
            lam[r] = st[r] * tmu[r] * s
        else:
            lam[r] = 0.0


@nb.njit(cache=True)
def _ssn_times(nbod, n_rows, rows, st, ie, sw, v, out):
    """out = H·v for the operator of :func:`_ssn_assemble` at the current Jacobian."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    for i in range(3 * nbod):
        out[i] = sw.mdiag[i] * v[i]
    for r in range(n_rows):
        if tn0[r] < 0:
            if st[r] == 0:
                row_add(r, rba, rbb, ja, jb, ie[r] * row_dot(r, rba, rbb, ja, jb, v), out)
            continue
        kind = _ssn_terms(r, st, tn0, tn1, tmu, tmu[r])
        if kind == 1:
            row_add(r, rba, rbb, ja, jb, ie[r] * row_dot(r, rba, rbb, ja, jb, v), out)
        elif kind == 2:
            s = 0.0
            for c in range(2):
                q = tn0[r] if c == 0 else tn1[r]
                if q >= 0 and st[q] == 0:
                    s += ie[q] * row_dot(q, rba, rbb, ja, jb, v)
            row_add(r, rba, rbb, ja, jb, st[r] * tmu[r] * s, out)


@nb.njit(cache=True)
def _fit_band(nbod, n_rows, rows, sw):
    """The half-bandwidth of H for the rows marked in sw.act, in the body order sw.pos; where
    it exceeds the band's room, a new order (:func:`reorder`; the kept factors are then
    void). −1 if it still does (sw.state[0] = 0)."""
    rba, rbb = rows.rba, rows.rbb
    kd = band_needed(n_rows, rba, rbb, sw.act, sw.pos)
    if 2 * kd + 1 > sw.lu.shape[1]:
        sw.state[0] = 0
        reorder(nbod, n_rows, rba, rbb, sw.pos)
        kd = band_needed(n_rows, rba, rbb, sw.act, sw.pos)
        if 2 * kd + 1 > sw.lu.shape[1]:
            return -1
    return kd


@nb.njit(cache=True)
def _ssn_solve(nbod, n_rows, rows, bias, st, ie, sw, lref, tol, key):
    """sw.v = H⁻¹·rhs for the states ``st``: on the kept LU factors if they were made for
    the same states (refined against the current Jacobian), else on new ones. False if H
    cannot be factorised in the band."""
    tn0, tmu = rows.tn0, rows.tmu
    n = 3 * nbod
    same = sw.state[0] == 2 and sw.frho[0] == key
    if same:
        for r in range(n_rows):
            if sw.sst[r] != st[r]:
                same = False
                break
    if not same:
        act = sw.act
        for r in range(n_rows):
            act[r] = st[r] == 0 or (tn0[r] >= 0 and st[r] != 2 and not math.isinf(tmu[r]))
        kd = _fit_band(nbod, n_rows, rows, sw)
        if kd < 0:
            return False
        _ssn_assemble(nbod, n_rows, rows, bias, st, ie, sw, kd)
        sw.state[2] += 1
        if not band_lu(n, sw.lu, kd, sw.lurow):
            sw.state[0] = 0
            return False
        sw.state[0] = 2
        sw.state[1] = kd
        sw.frho[0] = key
        for r in range(n_rows):
            sw.sst[r] = st[r]
        for j in range(nbod):
            for c in range(3):
                sw.x[3 * sw.pos[j] + c] = sw.rhs[3 * j + c]
        band_lu_solve(n, sw.lu, kd, sw.x)
        for j in range(nbod):
            for c in range(3):
                sw.v[3 * j + c] = sw.x[3 * sw.pos[j] + c]
        sw.state[3] += 1
        return True
    # the kept factors: refine against this Jacobian and right-hand side
    kd = sw.state[1]
    _ssn_assemble_rhs(nbod, n_rows, rows, bias, st, ie, sw)
    prev = math.inf
    for _ in range(REFINE_MAX + 1):
        _ssn_times(nbod, n_rows, rows, st, ie, sw, sw.v, sw.d)
        for j in range(nbod):
            for c in range(3):
                sw.x[3 * sw.pos[j] + c] = sw.rhs[3 * j + c] - sw.d[3 * j + c]
        band_lu_solve(n, sw.lu, kd, sw.x)
        sw.state[3] += 1
        err = 0.0
        for j in range(nbod):
            for c in range(3):
                e = sw.x[3 * sw.pos[j] + c]
                sw.v[3 * j + c] += e
                err = max(err, abs(e) * (lref if c == 2 else 1.0))
        if err <= tol:
            return True
        if err > 0.1 * prev:
            break
        prev = err
    sw.state[0] = 0
    sw.state[4] += 1
    return _ssn_solve(nbod, n_rows, rows, bias, st, ie, sw, lref, tol, key)


@nb.njit(cache=True)
def _ssn_classify(n_rows, st, rows, lam, sw, tol_u, tol_l, it, prox):
    """New states from the impulses and velocities (with hysteresis: a state changes only
    when it is violated by more than the tolerance). In a proximal step (``prox``) a
    sliding row's direction is that of its proximal velocity u + (ε + ρ)·Λ_t (docs/theory.md
    Eq. (9.9)). Returns whether any changed."""
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    changed = False
    ie = sw.ie
    for r in range(n_rows):
        if tn0[r] < 0:
            s = st[r]
            if s == 0 and lam[r] < -tol_l:
                s = -1
            elif s != 0 and sw.u[r] < -tol_u:
                s = 0
            if s != st[r]:
                st[r] = s
                changed = True
    for r in range(n_rows):
        if tn0[r] < 0:
            continue
        q0 = tn0[r]
        q1 = tn1[r]
        sn = (lam[q0] if st[q0] == 0 else 0.0) + (lam[q1] if q1 >= 0 and st[q1] == 0 else 0.0)
        s = st[r]
        if math.isinf(tmu[r]):
            if s == 0 and sn <= 0.0 and it < SSN_FREEZE:
                s = 2
            elif s != 0 and sn > tol_l:
                s = 0
        else:
            b = tmu[r] * max(sn, 0.0)
            if s == 0:
                if lam[r] > b + tol_l:
                    s = 1
                elif lam[r] < -b - tol_l:
                    s = -1
            elif s == 2:
                s = 0
            elif s * (sw.u[r] + (lam[r] / ie[r] if prox else 0.0)) > tol_u:
                s = 0
        if s != st[r]:
            st[r] = s
            changed = True
    return changed


@nb.njit(cache=True, inline="always")
def _wrr(r, rba, rbb, ja, jb, sw):
    """W_rr = J_r·M⁻¹·J_rᵀ (arrays read before the branches: :func:`row_dot`)."""
    a = rba[r]
    b = rbb[r]
    md = sw.mdiag
    ia = 3 * max(a, 0)
    ib = 3 * max(b, 0)
    wa = (ja[r, 0] ** 2 + ja[r, 1] ** 2) / md[ia] + ja[r, 2] ** 2 / md[ia + 2]
    wb = (jb[r, 0] ** 2 + jb[r, 1] ** 2) / md[ib] + jb[r, 2] ** 2 / md[ib + 2]
    w = 0.0
    if a >= 0:
        w += wa
    if b >= 0:
        w += wb
    return w



@nb.njit(cache=True)
def semismooth(nbod, n_rows, rows, bias, lam, sw, tol_u, tol_l, lref, max_it, key):
    """The semismooth Newton method on the rows' states (module docstring; docs/theory.md
    Eq. (9.8)) with the rows' 1/ε in sw.ie: states change where violated by more than
    (tol_u, tol_l) (a closed row in tension, an open one that moves in, a sticking row beyond
    its cone, a sliding one that moves with its friction force); it stops when none changes.
    ``sw.st`` and ``lam`` hold the warm start (the last step's states and impulses); ``key``
    names the proximal weight of sw.ie (LU factors are reused only under the same key).
    Returns the iterations (negative: not settled within ``max_it``)."""
    rba, rbb, ja, jb, tn0, tmu = rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0, rows.tmu
    n = 3 * nbod
    st = sw.st
    # u at the warm start v = v_free + M⁻¹·Jᵀ·Λ
    for i in range(n):
        sw.g[i] = 0.0
    for r in range(n_rows):
        if lam[r] != 0.0:
            row_add(r, rba, rbb, ja, jb, lam[r], sw.g)
    for i in range(n):
        sw.v[i] = sw.vf[i] + sw.g[i] / sw.mdiag[i]
    for r in range(n_rows):
        sw.u[r] = row_dot(r, rba, rbb, ja, jb, sw.v) + bias[r]
        if tn0[r] >= 0 and st[r] == -1 and math.isinf(tmu[r]):
            st[r] = 2
    tol_sol = 1e-3 * tol_u
    sw.state[5] += 1
    for it in range(max_it):
        sw.state[6] += 1
        changed = _ssn_classify(n_rows, st, rows, lam, sw, tol_u, tol_l,
                                it if key == 0.0 else SSN_FREEZE, key != 0.0)
        if it > 0 and not changed:
            return it
        if not _ssn_solve(nbod, n_rows, rows, bias, st, sw.ie, sw, lref, tol_sol, key):
            return -1 - it
        _ssn_impulses(n_rows, rows, bias, st, sw.ie, sw, lam)
    return -max_it


@nb.njit(cache=True)
def _any_inf(n_rows, rows):
    """Whether a tangential row has μ = ∞."""
    tn0, tmu = rows.tn0, rows.tmu
    for r in range(n_rows):
        if tn0[r] >= 0 and math.isinf(tmu[r]):
            return True
    return False


@nb.njit(cache=True)
def _weights(n_rows, tn0, eps_n, eps_t, rho, ie):
    """1/(ε + ρ) of every row (ε_n for normal rows, ε_t for tangential ones)."""
    for r in range(n_rows):
        ie[r] = 1.0 / ((eps_n if tn0[r] < 0 else eps_t) + rho)


@nb.njit(cache=True)
def solve(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, tol_u, tol_l, lref):
    """The step's contact problem (module docstring): v⁺ in sw.v from the free velocities
    in sw.vf, the impulses in ``lam`` (their last values on entry: the warm start).

    First the plain semismooth Newton method (``SSN_FIRST`` iterations). Where it does not
    settle (hundreds of joints opening and closing at once), the proximal point method
    (docs/theory.md Eq. (9.9); Siconos' and LMGC90's PROX): the problems with ε' = ε + ρ
    and b' = b − ρ·Λ_k, whose solution is the impulse closest to the last one Λ_k in the
    weight ρ. For ρ of the order of W's diagonal they are diagonally dominant and settle in a
    few iterations; Λ_k ← Λ, and ρ falls by ``PROX_DROP`` after a proximal step that settled
    at once (rises by ``PROX_UP`` after one that did not), until ρ·|Λ − Λ_k| ≤ tol_u (≤
    ``PROX_TOL``·tol_u in a problem of more than ``PROX_ROWS`` rows): the proximal term, the
    residual of the original contact law in the rows' velocities, is then below that
    tolerance and Λ solves the original problem to it.
    In a problem of more than ``PROX_ROWS`` rows without μ = ∞ rows, the interior-point
    method (:func:`interior_point`, docs/theory.md Eq. (9.13)) comes first, for at most
    ``IP_MAX`` iterations; where it does not get there, the continuation starts from its
    last iterate.
    Returns the iterations, semismooth and interior-point (negative: failed)."""
    rba, rbb, ja, jb, tn0 = rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0
    if sw.state[1] <= REFINE_KD:
        sw.state[0] = 0  # a narrow band: refactorised at the step's Jacobian (REFINE_KD)
    lamk = sw.lamk
    st = sw.st  # the work arrays named once: a field read in a loop's branch costs
    sst2 = sw.sst2  # numba atomic reference counts per row
    bias2 = sw.bias2
    for r in range(n_rows):
        lamk[r] = lam[r]  # the warm start, kept for the proximal steps
        sst2[r] = st[r]
    _weights(n_rows, tn0, eps_n, eps_t, 0.0, sw.ie)
    its = semismooth(nbod, n_rows, rows, bias, lam, sw, tol_u, tol_l, lref, _int(SSN_FIRST),
                     0.0)
    if its >= 0:
        return its
    total = SSN_FIRST
    sw.state[7] += 1
    if n_rows > PROX_ROWS and not _any_inf(n_rows, rows):
        ip_its = interior_point(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw,
                                PROX_TOL * tol_u, lamk)
        if ip_its > 0:
            sw.state[8] += 1
            return total + ip_its
        if ip_its < 0:  # the continuation starts from the method's last iterate
            total -= ip_its
            for r in range(n_rows):
                lamk[r] = lam[r]
                sst2[r] = st[r]
    rho = 0.0
    for r in range(n_rows):
        rho = max(rho, _wrr(r, rba, rbb, ja, jb, sw))
        lam[r] = lamk[r]
        st[r] = sst2[r]
    tol_prox = (PROX_TOL if n_rows > PROX_ROWS else 1.0) * tol_u
    for _ in range(PROX_MAX):
        for r in range(n_rows):
            bias2[r] = bias[r] - rho * lamk[r]
        _weights(n_rows, tn0, eps_n, eps_t, rho, sw.ie)
        its = semismooth(nbod, n_rows, rows, sw.bias2, lam, sw, tol_u, tol_l, lref,
                         _int(SSN_MAX), rho)
        if its < 0:
            total += SSN_MAX
            for r in range(n_rows):  # back to the last proximal iterate, more weight on it
                lam[r] = lamk[r]
                st[r] = sst2[r]
            rho *= PROX_UP
            continue
        total += its
        # the original problem's KKT conditions hold but for ρ·(Λ − Λ_k): within tol_u?
        dev = 0.0
        for r in range(n_rows):
            dev = max(dev, rho * abs(lam[r] - lamk[r]))
            lamk[r] = lam[r]
            sst2[r] = st[r]
        if dev <= tol_prox:
            return total
        if its <= 4:
            rho /= PROX_DROP
    # not settled: the step keeps the last proximal iterate (the solution of a nearby
    # problem, its velocities v_free + M⁻¹·Jᵀ·Λ_k) and counts as failed
    for r in range(n_rows):
        lam[r] = lamk[r]
        st[r] = sst2[r]
    for i in range(3 * nbod):
        sw.g[i] = 0.0
    for r in range(n_rows):
        if lam[r] != 0.0:
            row_add(r, rba, rbb, ja, jb, lam[r], sw.g)
    for i in range(3 * nbod):
        sw.v[i] = sw.vf[i] + sw.g[i] / sw.mdiag[i]
    return -1 - total


@nb.njit(cache=True, inline="always")
def _ip_pair(lam, r, tn0, tn1):
    """Σ of the normal impulses bounding tangential row r (its joint's corners)."""
    q1 = tn1[r]
    v1 = lam[max(q1, 0)]
    s = lam[tn0[r]]
    if q1 >= 0:
        s += v1
    return s


@nb.njit(cache=True, inline="always")
def _ip_pair_x(x, c, r, tn0, tn1):
    """Σ of column c of x over the normal rows bounding tangential row r."""
    q1 = tn1[r]
    v1 = x[max(q1, 0), c]
    s = x[tn0[r], c]
    if q1 >= 0:
        s += v1
    return s


@nb.njit(cache=True)
def _rows_dot(n_rows, rows, v, out):
    """out[r] = J_r·v for every row (one pass, the interior-point method's: a single inlined
    :func:`row_dot` keeps its compile time down)."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    for r in range(n_rows):
        out[r] = row_dot(r, rba, rbb, ja, jb, v)


@nb.njit(cache=True)
def _rows_add(n_rows, rows, c, scale, out, which):
    """out += Σ_r scale·c[r]·J_rᵀ over the normal rows (``which`` 1), the tangential ones
    (2) or all (0), in row order."""
    rba, rbb, ja, jb, tn0 = rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0
    for r in range(n_rows):
        if which == 0 or (which == 1) == (tn0[r] < 0):
            row_add(r, rba, rbb, ja, jb, scale * c[r], out)


@nb.njit(cache=True, inline="always")
def _ip_cone(x, r, lam, tn0, tn1, tmu):
    """Tangential row r's distances to its cone's edges s₁, s₂, the ratios z₁/s₁, z₂/s₂ and
    the residuals s₁ − β − Λ_t, s₂ − β + Λ_t (β = μ·ΣΛ_n)."""
    s1 = x[r, 0]
    s2 = x[r, 2]
    beta = tmu[r] * _ip_pair(lam, r, tn0, tn1)
    return s1, s2, x[r, 1] / s1, x[r, 3] / s2, s1 - beta - lam[r], s2 - beta + lam[r]


@nb.njit(cache=True)
def _ip_velocities(nbod, n_rows, rows, lam, sw, out):
    """out = v_free + M⁻¹·Jᵀ·Λ (sw.g: scratch)."""
    for i in range(3 * nbod):
        sw.g[i] = 0.0
    _rows_add(n_rows, rows, lam, 1.0, sw.g, _int(0))
    for i in range(3 * nbod):
        out[i] = sw.vf[i] + sw.g[i] / sw.mdiag[i]


@nb.njit(cache=True)
def _ip_residuals(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw):
    """u = J·v + b in sw.u, the momentum residual M·(v − v_f) − Jᵀ·Λ in sw.g, the rows'
    residuals in sw.ip[:, 10] (normal: R_w = w − u − ε_nΛ; tangential: R_t = u + ε_tΛ_t −
    z₁ + z₂). Returns the mean complementarity product."""
    tn0 = rows.tn0
    x = sw.ip
    for i in range(3 * nbod):
        sw.g[i] = sw.mdiag[i] * (sw.v[i] - sw.vf[i])
    _rows_add(n_rows, rows, lam, -1.0, sw.g, _int(0))
    _rows_dot(n_rows, rows, sw.v, sw.u)
    gap = 0.0
    for r in range(n_rows):
        u = sw.u[r] + bias[r]
        sw.u[r] = u
        if tn0[r] < 0:
            x[r, 10] = x[r, 0] - u - eps_n * lam[r]
            gap += lam[r] * x[r, 0]
        else:
            x[r, 10] = u + eps_t * lam[r] - x[r, 1] + x[r, 3]
            gap += x[r, 0] * x[r, 1] + x[r, 2] * x[r, 3]
    return gap / n_rows


@nb.njit(cache=True)
def _ip_direction(nbod, n_rows, rows, lam, eps_n, eps_t, sw, kd):
    """The Newton direction of the perturbed law for the complementarity targets in sw.ip[:,
    12:14] (docs/theory.md Eq. (9.13)), on the factors of H in sw.lu: into sw.ip[:, 4:9]
    (ΔΛ, Δw or Δs₁, Δz₁, Δs₂, Δz₂) and sw.d (Δv)."""
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    x = sw.ip
    c = sw.bias2  # scratch (R,): the rows' right-hand side terms, then J·Δv
    n = 3 * nbod
    for i in range(n):
        sw.rhs[i] = -sw.g[i]
    for r in range(n_rows):  # normal rows: ΔΛ = g − d·J·Δv, g in column 4 for now
        if tn0[r] < 0:
            den = x[r, 0] + eps_n * lam[r]
            x[r, 4] = (x[r, 12] + lam[r] * x[r, 10]) / den
            c[r] = x[r, 4]
    _rows_add(n_rows, rows, c, 1.0, sw.rhs, _int(1))
    for r in range(n_rows):  # tangential rows: ΔΛ_t = f − q·(J_t·Δv + (a₁ − a₂)·μ·ΣΔΛ_n)
        if tn0[r] >= 0:
            s1, s2, a1, a2, rs1, rs2 = _ip_cone(x, r, lam, tn0, tn1, tmu)
            e = -x[r, 10] + x[r, 12] / s1 - x[r, 13] / s2 + a1 * rs1 - a2 * rs2
            x[r, 11] = e
            c[r] = (e - (a1 - a2) * tmu[r] * _ip_pair_x(x, 4, r, tn0, tn1)) / (eps_t + a1 + a2)
    _rows_add(n_rows, rows, c, 1.0, sw.rhs, _int(2))
    pos = sw.pos
    for j in range(nbod):
        for k in range(3):
            sw.x[3 * pos[j] + k] = sw.rhs[3 * j + k]
    band_lu_solve(n, sw.lu, kd, sw.x)
    sw.state[3] += 1
    for j in range(nbod):
        for k in range(3):
            sw.d[3 * j + k] = sw.x[3 * pos[j] + k]
    _rows_dot(n_rows, rows, sw.d, c)
    for r in range(n_rows):
        if tn0[r] < 0:
            jdv = c[r]
            dl = x[r, 4] - x[r, 9] * jdv
            x[r, 4] = dl
            x[r, 5] = jdv + eps_n * dl - x[r, 10]
    for r in range(n_rows):
        if tn0[r] >= 0:
            s1, s2, a1, a2, rs1, rs2 = _ip_cone(x, r, lam, tn0, tn1, tmu)
            jdv = c[r]
            dbeta = tmu[r] * _ip_pair_x(x, 4, r, tn0, tn1)
            dl = (x[r, 11] - jdv - (a1 - a2) * dbeta) / (eps_t + a1 + a2)
            x[r, 4] = dl
            ds1 = dbeta + dl - rs1
            ds2 = dbeta - dl - rs2
            x[r, 5] = ds1
            x[r, 6] = (x[r, 12] - x[r, 1] * ds1) / s1
            x[r, 7] = ds2
            x[r, 8] = (x[r, 13] - x[r, 3] * ds2) / s2


@nb.njit(cache=True, inline="always")
def _ip_ratio(a, da, alpha):
    """The largest step ≤ alpha keeping a + step·da ≥ 0."""
    if da < 0.0:
        alpha = min(alpha, -a / da)
    return alpha


@nb.njit(cache=True)
def _ip_step_length(n_rows, tn0, lam, x):
    """The largest step in [0, 1] along the direction keeping every pair nonnegative."""
    alpha = 1.0
    for r in range(n_rows):
        if tn0[r] < 0:
            alpha = _ip_ratio(lam[r], x[r, 4], alpha)
            alpha = _ip_ratio(x[r, 0], x[r, 5], alpha)
        else:
            for c in range(4):
                alpha = _ip_ratio(x[r, c], x[r, 5 + c], alpha)
    return alpha


@nb.njit(cache=True)
def _ip_assemble(nbod, n_rows, rows, lam, eps_n, eps_t, sw, kd):
    """The full band of the interior-point method's H = M + Jᵀ·K·J (docs/theory.md
    Eq. (9.13)) in sw.lu, its weights in sw.ip[:, 9]: the normal rows' d = Λ_n/(w + ε_nΛ_n)
    first, then every tangential row's q = 1/(ε_t + z₁/s₁ + z₂/s₂) and its couplings
    −q·(z₁/s₁ − z₂/s₂)·μ·d to its joint's normal rows (one :func:`_add_outer` site: each
    inlined copy costs compile time)."""
    rba, rbb, ja, jb, tn0, tn1, tmu = (rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0,
                                       rows.tn1, rows.tmu)
    x = sw.ip
    lu = sw.lu
    pos = sw.pos
    _band_mass(nbod, sw, kd)
    for r in range(n_rows):
        if tn0[r] < 0:
            x[r, 9] = lam[r] / (x[r, 0] + eps_n * lam[r])
    for phase in range(2):
        for r in range(n_rows):
            if (phase == 0) != (tn0[r] < 0):
                continue
            for k in range(3 if phase == 1 else 1):
                if phase == 0:
                    q, coef = r, x[r, 9]
                elif k == 0:
                    a1 = x[r, 1] / x[r, 0]
                    a2 = x[r, 3] / x[r, 2]
                    x[r, 9] = 1.0 / (eps_t + a1 + a2)
                    q, coef = r, x[r, 9]
                else:
                    q = tn0[r] if k == 1 else tn1[r]
                    if q < 0:
                        continue
                    coef = -x[r, 9] * (x[r, 1] / x[r, 0] - x[r, 3] / x[r, 2]) * tmu[r] * x[q, 9]
                _add_outer(r, q, coef, rba, rbb, ja, jb, pos, lu, kd)


@nb.njit(cache=True)
def interior_point(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, tol, lamw):
    """The step's contact law (docs/theory.md Eqs. (9.1)–(9.3)) by Mehrotra's
    predictor–corrector interior-point method (Eq. (9.13)): every pair (Λ_n, w = u_n + ε_nΛ_n)
    and, on a tangential row, (s₁ = β + Λ_t, z₁), (s₂ = β − Λ_t, z₂) with u_t + ε_tΛ_t = z₁ −
    z₂ is kept positive with products driven to 0; each iteration is one banded LU of
    H = M + Jᵀ·K·J, whose weights K join the states' 1/ε (a closed or sticking row) and 0
    (an open one) continuously, and whose couplings are those of (9.7). Started from the
    step's warm start ``lamw``; stops when the law's natural residual at Λ and v_free +
    M⁻¹·Jᵀ·Λ (:func:`law_residual`) is within ``tol``: Λ in ``lam``, v⁺ in sw.v and the
    rows' states from them in sw.st. Returns the iterations; negative: not converged within
    ``IP_MAX`` or stalled (``IP_STALL`` steps shorter than ``IP_SHORT``), with the last
    iterate in ``lam``, sw.v and sw.st as above; 0: not tried (H with every row is wider
    than the band)."""
    rba, rbb, ja, jb, tn0, tn1, tmu = (rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0,
                                       rows.tn1, rows.tmu)
    n = 3 * nbod
    x = sw.ip
    act = sw.act
    for r in range(n_rows):
        act[r] = True
    kd = _fit_band(nbod, n_rows, rows, sw)
    if kd < 0:
        return 0
    sw.state[0] = 0  # the LU below is the method's own: no factors kept for the states
    # the start: the warm start's impulses moved into the interior
    vs = 1e3 * tol
    c = sw.bias2  # scratch (R,)
    _rows_dot(n_rows, rows, sw.vf, c)
    for r in range(n_rows):
        vs = max(vs, abs(c[r] + bias[r]))
    for r in range(n_rows):
        if tn0[r] < 0:
            lam[r] = max(lamw[r], 0.0) + vs / _wrr(r, rba, rbb, ja, jb, sw)
    for r in range(n_rows):
        if tn0[r] >= 0:
            beta = tmu[r] * _ip_pair(lam, r, tn0, tn1)
            lam[r] = min(max(lamw[r], -0.9 * beta), 0.9 * beta)
            x[r, 0] = beta + lam[r]
            x[r, 1] = vs
            x[r, 2] = beta - lam[r]
            x[r, 3] = vs
    _ip_velocities(nbod, n_rows, rows, lam, sw, sw.v)
    _rows_dot(n_rows, rows, sw.v, c)
    for r in range(n_rows):
        if tn0[r] < 0:
            x[r, 0] = max(c[r] + bias[r] + eps_n * lam[r], 0.0) + vs
    short = 0
    for it in range(IP_MAX):
        gap = _ip_residuals(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw)
        _ip_assemble(nbod, n_rows, rows, lam, eps_n, eps_t, sw, kd)
        sw.state[2] += 1
        sw.state[9] += 1
        if not band_lu(n, sw.lu, kd, sw.lurow):
            return _ip_give_up(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, it)
        # predictor: the targets 0
        for r in range(n_rows):
            if tn0[r] < 0:
                x[r, 12] = -lam[r] * x[r, 0]
            else:
                x[r, 12] = -x[r, 0] * x[r, 1]
                x[r, 13] = -x[r, 2] * x[r, 3]
        _ip_direction(nbod, n_rows, rows, lam, eps_n, eps_t, sw, kd)
        alpha = _ip_step_length(n_rows, tn0, lam, x)
        aff = 0.0
        for r in range(n_rows):
            if tn0[r] < 0:
                aff += (lam[r] + alpha * x[r, 4]) * (x[r, 0] + alpha * x[r, 5])
            else:
                aff += ((x[r, 0] + alpha * x[r, 5]) * (x[r, 1] + alpha * x[r, 6])
                        + (x[r, 2] + alpha * x[r, 7]) * (x[r, 3] + alpha * x[r, 8]))
        sigma = (aff / n_rows / gap) ** 3
        # corrector: the centred targets with the predictor's second-order terms
        for r in range(n_rows):
            if tn0[r] < 0:
                x[r, 12] = sigma * gap - lam[r] * x[r, 0] - x[r, 4] * x[r, 5]
            else:
                x[r, 12] = sigma * gap - x[r, 0] * x[r, 1] - x[r, 5] * x[r, 6]
                x[r, 13] = sigma * gap - x[r, 2] * x[r, 3] - x[r, 7] * x[r, 8]
        _ip_direction(nbod, n_rows, rows, lam, eps_n, eps_t, sw, kd)
        alpha = min(1.0, IP_BOUNDARY * _ip_step_length(n_rows, tn0, lam, x))
        for i in range(n):
            sw.v[i] += alpha * sw.d[i]
        for r in range(n_rows):
            lam[r] += alpha * x[r, 4]
            x[r, 0] += alpha * x[r, 5]
            if tn0[r] >= 0:
                x[r, 1] += alpha * x[r, 6]
                x[r, 2] += alpha * x[r, 7]
                x[r, 3] += alpha * x[r, 8]
        short = short + 1 if alpha < IP_SHORT else 0
        if short >= IP_STALL:
            return _ip_give_up(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, it + 1)
        # converged? the law at Λ and the velocities of its momentum balance
        _ip_velocities(nbod, n_rows, rows, lam, sw, sw.d)
        if law_residual(n_rows, rows, bias, lam, eps_n, eps_t, sw, sw.d) <= tol:
            for i in range(n):
                sw.v[i] = sw.d[i]
            _ip_states(n_rows, rows, bias, lam, eps_n, eps_t, sw)
            return it + 1
    return _ip_give_up(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, _int(IP_MAX))


@nb.njit(cache=True)
def _ip_give_up(nbod, n_rows, rows, bias, lam, eps_n, eps_t, sw, its):
    """The last iterate as a warm start: v⁺ = v_free + M⁻¹·Jᵀ·Λ in sw.v, its states in
    sw.st. Returns −its (at least 1)."""
    _ip_velocities(nbod, n_rows, rows, lam, sw, sw.v)
    _ip_states(n_rows, rows, bias, lam, eps_n, eps_t, sw)
    return -max(its, 1)


@nb.njit(cache=True)
def _ip_states(n_rows, rows, bias, lam, eps_n, eps_t, sw):
    """The rows' states of the interior point's solution (the next step's warm start): a
    normal row closed where W_rr·Λ_n exceeds u_n + ε_nΛ_n, a tangential row sliding where
    its trial impulse Λ_t − (u_t + ε_tΛ_t)/W_rr leaves its cone (in that direction)."""
    rba, rbb, ja, jb, tn0, tn1, tmu = (rows.rba, rows.rbb, rows.ja, rows.jb, rows.tn0,
                                       rows.tn1, rows.tmu)
    st = sw.st
    _rows_dot(n_rows, rows, sw.v, sw.u)
    for r in range(n_rows):
        sw.u[r] += bias[r]
        if tn0[r] < 0:
            w = _wrr(r, rba, rbb, ja, jb, sw)
            st[r] = 0 if w * lam[r] > sw.u[r] + eps_n * lam[r] else -1
    for r in range(n_rows):
        if tn0[r] >= 0:
            q0 = tn0[r]
            q1 = tn1[r]
            sn = (lam[q0] if st[q0] == 0 else 0.0) + (lam[q1] if q1 >= 0 and st[q1] == 0
                                                      else 0.0)
            beta = tmu[r] * max(sn, 0.0)
            trial = lam[r] - (sw.u[r] + eps_t * lam[r]) / _wrr(r, rba, rbb, ja, jb, sw)
            st[r] = 1 if trial > beta else (-1 if trial < -beta else 0)


@nb.njit(cache=True)
def law_residual(n_rows, rows, bias, lam, eps_n, eps_t, sw, v):
    """The largest natural residual of the step's contact law (docs/theory.md Eqs.
    (9.1)–(9.3) with the regularisation ε) at the impulses ``lam`` and velocities ``v`` [m/s]:
    |min(W_rr·Λ_n, u_n + ε_n·Λ_n)| on a corner row, W_rr·|Λ_t − proj_[−β, β](Λ_t − (u_t +
    ε_t·Λ_t)/W_rr)| on a tangential one, β = μ·ΣΛ_n⁺ (u = J·v + b; μ = ∞ rows skipped). A
    diagnostic of the solve (tests, benchmarks/hard_steps.py), not used by it."""
    rba, rbb, ja, jb = rows.rba, rows.rbb, rows.ja, rows.jb
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    worst = 0.0
    for r in range(n_rows):
        u = row_dot(r, rba, rbb, ja, jb, v) + bias[r]
        w = _wrr(r, rba, rbb, ja, jb, sw)
        if tn0[r] < 0:
            res = abs(min(w * lam[r], u + eps_n * lam[r]))
        elif math.isinf(tmu[r]):
            continue
        else:
            q1 = tn1[r]
            sn = max(lam[tn0[r]], 0.0) + (max(lam[q1], 0.0) if q1 >= 0 else 0.0)
            beta = tmu[r] * sn
            trial = lam[r] - (u + eps_t * lam[r]) / w
            res = w * abs(lam[r] - min(max(trial, -beta), beta))
        worst = max(worst, res)
    return worst


@nb.njit(cache=True, inline="always")
def _bound(c0, c1, lo, hi):
    """Intersect [lo, hi] with {a : c0 + a·c1 ≥ 0}."""
    if c1 > 0.0:
        lo = max(lo, -c0 / c1)
    elif c1 < 0.0:
        hi = min(hi, -c0 / c1)
    elif c0 < 0.0:
        hi = -math.inf
    return lo, hi


@nb.njit(cache=True)
def rest_interval(nbod, n_rows, rows, bias, eps_n, eps_t, sw, tol_u, tol_l, lref, h, g, v_rest,
                  lam0, lam1):
    """The mean ground accelerations ā of a step for which a structure at rest stays at
    rest (docs/theory.md Eq. (9.11)): with v = 0 before the step and the rows' present
    states, the step's solution (9.7) and its impulses are affine in ā, Λ = Λ₀ + ā·Λ₁
    (``lam0``, ``lam1``), and these states solve the step within (tol_u, tol_l) while every
    closed row stays in compression, every open one does not move in, every sticking one
    stays in its cone, every sliding one (a slip slower than tol_u: a joint at its cone's
    edge) does not turn back, and every body moves slower than ``v_rest`` (the creep of
    the regularised rows stays below it; a motion that starts under an unbalanced
    acceleration a exceeds it after one step once a > v_rest/h). Returns (lo, hi); lo > hi:
    the states do not hold."""
    tn0, tn1, tmu = rows.tn0, rows.tn1, rows.tmu
    lo, hi = -math.inf, math.inf
    for r in range(n_rows):
        if tn0[r] < 0:
            continue
        if sw.st[r] == 2 and not math.isinf(tmu[r]):
            return 1.0, -1.0
    _weights(n_rows, tn0, eps_n, eps_t, 0.0, sw.ie)
    tol_sol = 1e-3 * tol_u
    for case in range(2):  # ā = 0, then ā = 1
        for j in range(nbod):
            sw.vf[3 * j] = -h * case
            sw.vf[3 * j + 1] = -h * g
            sw.vf[3 * j + 2] = 0.0
        if not _ssn_solve(nbod, n_rows, rows, bias, sw.st, sw.ie, sw, lref, tol_sol, 0.0):
            return 1.0, -1.0
        _ssn_impulses(n_rows, rows, bias, sw.st, sw.ie, sw, lam0 if case == 0 else lam1)
        if case == 0:
            for i in range(3 * nbod):
                sw.g[i] = sw.v[i]
            for r in range(n_rows):
                sw.bias2[r] = sw.u[r]
    for i in range(3 * nbod):  # the bodies' speeds: creep only
        w = lref if i % 3 == 2 else 1.0
        v1 = (sw.v[i] - sw.g[i]) * w
        lo, hi = _bound(v_rest - sw.g[i] * w, -v1, lo, hi)
        lo, hi = _bound(v_rest + sw.g[i] * w, v1, lo, hi)
    for r in range(n_rows):
        lam1[r] -= lam0[r]
        if tn0[r] < 0:
            if sw.st[r] == 0:
                lo, hi = _bound(lam0[r] + tol_l, lam1[r], lo, hi)
            else:
                lo, hi = _bound(sw.bias2[r] + tol_u, sw.u[r] - sw.bias2[r], lo, hi)
            continue
        s0 = 0.0
        s1 = 0.0
        for c in range(2):
            q = tn0[r] if c == 0 else tn1[r]
            if q >= 0 and sw.st[q] == 0:
                s0 += lam0[q]
                s1 += lam1[q]
        if sw.st[r] == 2:  # μ = ∞ without compression: no shear while none comes
            lo, hi = _bound(tol_l - s0, -s1, lo, hi)
        else:
            lo, hi = _bound(s0, s1, lo, hi)
            if st_slides(sw.st[r]):  # slips slower than tol_u (the bodies' speeds): keeps on
                s = sw.st[r]
                lo, hi = _bound(tol_u - s * sw.bias2[r], -s * (sw.u[r] - sw.bias2[r]), lo, hi)
            elif not math.isinf(tmu[r]):
                mu = tmu[r]
                lo, hi = _bound(mu * s0 + tol_l - lam0[r], mu * s1 - lam1[r], lo, hi)
                lo, hi = _bound(mu * s0 + tol_l + lam0[r], mu * s1 + lam1[r], lo, hi)
        if lo > hi:
            break
    return lo, hi


@nb.njit(cache=True, inline="always")
def st_slides(s):
    """A tangential row's state slides (±1)."""
    return s == 1 or s == -1
