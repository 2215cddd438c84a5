"""Exact contact solve of a structure that sticks: the rest path of the graph stepper (numba).

A structure at rest on the moving ground (a wall under a weak motion) changes nothing from
step to step but its loads, yet non-smooth Gauss–Seidel needs tens of sweeps per step to carry
each step's change of the ground's inertia force through a hyperstatic graph. The rest path
(docs/theory.md Eq. (9.7)) tries, before any sweep, the solution v⁺ = 0: every body moves with
the ground. Its impulses are the last step's Λ on the support S (the closed corner rows that
carried an impulse and the tangential rows of their joints), corrected by
the weighted least-norm increment that balances this step's loads,

    ΔΛ_S = D·J_S·(J_SᵀD·J_S)⁻¹·r,   r = −M·v_free − J_SᵀΛ_S,

D = the rows' last impulses (a row shares a load change in proportion to what it carries).
J_SᵀDJ_S (3 rows per body, banded in the body order of
:func:`rockarch.mdof.kernel_data.graph_model`) is factorised by a banded Cholesky only when S
changes, and the increment is refined against the current Jacobian. A corner whose Λ_n
turns negative leaves S; a joint whose Λ_t leaves its cone is held at its edge,
Λ_t = ±μ·(Λ_n0 + Λ_n1) (its corner rows become J_c ± μ·J_t); then again, up to
``REST_DROPS`` times. If that fails, once more from every closed corner. The result is
accepted only if it solves the step's problem (9.1)–(9.3): Λ_n ≥ 0, |Λ_t| ≤ μ·(Λ_n0 + Λ_n1)
and, at the velocities it gives, |U| ≤ ``tol_u`` on S and U_n ≥ −``tol_u`` on every other
corner; otherwise the step goes to Gauss–Seidel unchanged.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from rockarch.mdof.graph_solver import apply_impulse

#: A body's velocity after the last step (relative to g·h, rotation times the thinnest
#: joint) below which the rest path is tried: above it the structure is moving and the try
#: would only cost factorisations. Gauss–Seidel leaves a resting wall at 3e-3–9e-3·g·h (its
#: sweep tolerance), below the gate; 0.1 instead of 0.01 gives the same results on the
#: benchmarks/wall_solvers.py walls but more failed tries (10 x 4 wall at 1.5·ap,min:
#: 29 s of CPU against 22 s).
REST_V = 0.01
#: Rounds of leaving inadmissible rows out of S (each a new factorisation) before the step
#: goes to Gauss–Seidel.
REST_DROPS = 3
#: Refinements of the increment against the current Jacobian (the factor may be older).
REST_REFINE = 4
#: A Cholesky pivot below this fraction of its diagonal term: J_SᵀDJ_S is singular, S does
#: not hold every body (a mechanism): no solution with v⁺ = 0 on this S.
PIVOT_TOL = 1e-10


class RestWork(NamedTuple):
    """Work arrays of the rest path (one per run and workspace)."""

    kf: np.ndarray  # the factor of J_SᵀDJ_S (upper band, body order)
    kdiag: np.ndarray  # its diagonal before factorisation
    rs_new: np.ndarray  # S to factorise, S factorised (rows)
    rs_set: np.ndarray
    tb_new: np.ndarray  # joints held at their cone's edge (±1), to factorise / factorised
    tb_set: np.ndarray
    wt: np.ndarray  # D
    je: np.ndarray  # rows of S on bodies a and b
    rv: np.ndarray  # loads to balance / the increment (body order)
    lt: np.ndarray  # the trial impulses
    vt: np.ndarray  # the trial velocities (3, nb)
    rstate: np.ndarray  # [factor valid 1 / singular -1 / none 0, last velocity / g·h]
    lref: np.ndarray  # [thinnest joint]: rotations × lref compare with velocities


@nb.njit(cache=True)
def make_rest_work(m, scale):
    """Zeroed rest-path work of one run (empty for a banded model, which never uses it)."""
    nb3 = 0 if m.banded else 3 * m.mass.shape[0]
    n = 0 if m.banded else 3 * m.n0.shape[0]
    nj = n // 3
    return RestWork(np.zeros((nb3, m.kbody + 1)), np.zeros(nb3), np.zeros(n, dtype=np.bool_),
                    np.zeros(n, dtype=np.bool_), np.zeros(nj, dtype=np.int8),
                    np.zeros(nj, dtype=np.int8), np.zeros(n), np.zeros((n, 2, 3)),
                    np.zeros(nb3), np.zeros(n), np.zeros((3, nb3 // 3)), np.zeros(2),
                    np.array([m.thick_min * scale]))


@nb.njit(cache=True)
def band_cholesky(n, a, diag):
    """In place: the upper band a[i, d] = A[i, i + d] of the SPD matrix A becomes U, A = UᵀU
    (right-looking, row by row, contiguous updates). False if a pivot falls below
    ``PIVOT_TOL`` times its diagonal term ``diag``."""
    kd = a.shape[1] - 1
    for j in range(n):
        piv = a[j, 0]
        if piv <= PIVOT_TOL * diag[j]:
            return False
        piv = math.sqrt(piv)
        a[j, 0] = piv
        top = min(kd, n - 1 - j)
        for d in range(1, top + 1):
            a[j, d] /= piv
        for d in range(1, top + 1):
            u = a[j, d]
            if u != 0.0:
                i = j + d
                for e in range(top - d + 1):
                    a[i, e] -= u * a[j, d + e]
    return True


@nb.njit(cache=True)
def band_substitute(n, fac, x):
    """x ← A⁻¹·x with the banded factor U of :func:`band_cholesky` (Uᵀ·y = x, U·x = y)."""
    kd = fac.shape[1] - 1
    for i in range(n):
        x[i] /= fac[i, 0]
        xi = x[i]
        for d in range(1, min(kd, n - 1 - i) + 1):
            x[i + d] -= fac[i, d] * xi
    for i in range(n - 1, -1, -1):
        s = x[i]
        for d in range(1, min(kd, n - 1 - i) + 1):
            s -= fac[i, d] * x[i + d]
        x[i] = s / fac[i, 0]


@nb.njit(cache=True)
def _support(m, ws, rw, every):
    """S (rw.rs_new): closed corner rows with a last impulse (``every``: all closed corner
    rows) and the tangential rows of their joints (μ = ∞ too: no shear without a corner);
    rw.tb_new: ±1 for a joint whose last Λ_t was at ±μ·ΣΛ_n (held there), else 0. True if
    either differs from the factorised one."""
    changed = False
    for k in range(m.n0.shape[0]):
        r = 3 * k
        s0 = (every or ws.lam[r] > 0.0) and ws.bias[r] == 0.0
        s1 = (every or ws.lam[r + 1] > 0.0) and ws.bias[r + 1] == 0.0
        rw.rs_new[r] = s0
        rw.rs_new[r + 1] = s1
        rw.rs_new[r + 2] = s0 or s1
        rw.tb_new[k] = 0
        if (s0 or s1) and not math.isinf(m.mu[k]) and not every:
            bound = m.mu[k] * (ws.lam[r] + ws.lam[r + 1])
            if abs(ws.lam[r + 2]) >= (1.0 - 1e-9) * bound:
                rw.tb_new[k] = 1 if ws.lam[r + 2] > 0.0 else -1
        changed = changed or rw.tb_new[k] != rw.tb_set[k]
        for i in range(3):
            changed = changed or rw.rs_new[r + i] != rw.rs_set[r + i]
    return changed


@nb.njit(cache=True)
def _weights(m, ws, rw, every):
    """Row weights D of S from the last impulses: a corner's Λ_n (``every``: plus their mean,
    1 if none), a free tangential row's min(μ, 1)·(Λ_n0 + Λ_n1) (the mean corner weight if
    its corners carried none)."""
    tot = 0.0
    cnt = 0
    for k in range(m.n0.shape[0]):
        for c in range(2):
            r = 3 * k + c
            if rw.rs_new[r] and ws.lam[r] > 0.0:
                tot += ws.lam[r]
                cnt += 1
    mean = tot / cnt if cnt else 1.0
    for k in range(m.n0.shape[0]):
        for c in range(2):
            r = 3 * k + c
            rw.wt[r] = max(ws.lam[r], 0.0) + (mean if every else 0.0) if rw.rs_new[r] else 0.0
    mean = mean * (2.0 if every else 1.0)
    for k in range(m.n0.shape[0]):
        r = 3 * k + 2
        sn = rw.wt[r - 2] + rw.wt[r - 1]
        rw.wt[r] = min(m.mu[k], 1.0) * sn if sn > 0.0 else mean
        if not rw.rs_new[r] or rw.tb_new[k] != 0:
            rw.wt[r] = 0.0


@nb.njit(cache=True)
def _rows(m, ws, rw):
    """rw.je[r, side] = row r of S as it acts on body a (side 0) and b (side 1): a corner row
    of a joint held at its cone's edge carries its friction, J_c ± μ·J_t."""
    for k in range(m.n0.shape[0]):
        sg = rw.tb_set[k] * m.mu[k] if rw.tb_set[k] != 0 else 0.0
        for i in range(3):
            r = 3 * k + i
            f = sg if i < 2 else 0.0
            for c in range(3):
                rw.je[r, 0, c] = ws.ja[r, c] + f * ws.ja[3 * k + 2, c]
                rw.je[r, 1, c] = ws.jb[r, c] + f * ws.jb[3 * k + 2, c]


@nb.njit(cache=True)
def _gram(m, ws, rw, every):
    """Upper band of J_Sᵀ·D·J_S in the body order (3 rows per body), factorised in place."""
    nbod = m.mass.shape[0]
    kf = rw.kf
    kf[:] = 0.0
    _weights(m, ws, rw, every)
    for k in range(m.n0.shape[0]):
        rw.tb_set[k] = rw.tb_new[k]
        for i in range(3):
            rw.rs_set[3 * k + i] = rw.rs_new[3 * k + i]
    _rows(m, ws, rw)
    for k in range(m.n0.shape[0]):
        ends = (m.ba[k], m.bb[k])
        for i in range(3):
            r = 3 * k + i
            wr = rw.wt[r]
            if wr == 0.0:
                continue
            for p in range(2):
                if ends[p] < 0:
                    continue
                bp = 3 * m.bpos[ends[p]]
                for q in range(2):
                    if ends[q] < 0 or m.bpos[ends[q]] < m.bpos[ends[p]]:
                        continue
                    bq = 3 * m.bpos[ends[q]]
                    for s in range(3):
                        ep = wr * rw.je[r, p, s]
                        for t in range(3):
                            if bq + t >= bp + s:
                                kf[bp + s, bq + t - bp - s] += ep * rw.je[r, q, t]
    for i in range(3 * nbod):
        rw.kdiag[i] = kf[i, 0]
    return band_cholesky(3 * nbod, kf, rw.kdiag)


@nb.njit(cache=True)
def _residual(m, ws, rw, vx, vy, om):
    """rw.rv = −M·v_free − J_SᵀΛ (body order); returns its largest velocity, M⁻¹·rv,
    relative to one unit of rw.rv's scale (translation, rotation × thick_min)."""
    nbod = m.mass.shape[0]
    for j in range(nbod):
        p = 3 * m.bpos[j]
        rw.rv[p] = -vx[j] / ws.im[j]
        rw.rv[p + 1] = -vy[j] / ws.im[j]
        rw.rv[p + 2] = -om[j] / ws.ii[j]
    for k in range(m.n0.shape[0]):
        for i in range(3):
            r = 3 * k + i
            lam = rw.lt[r]
            if lam == 0.0:
                continue
            if m.ba[k] >= 0:
                p = 3 * m.bpos[m.ba[k]]
                for c in range(3):
                    rw.rv[p + c] -= ws.ja[r, c] * lam
            if m.bb[k] >= 0:
                p = 3 * m.bpos[m.bb[k]]
                for c in range(3):
                    rw.rv[p + c] -= ws.jb[r, c] * lam
    dv = 0.0
    for j in range(nbod):
        p = 3 * m.bpos[j]
        dv = max(dv, abs(rw.rv[p]) * ws.im[j], abs(rw.rv[p + 1]) * ws.im[j],
                 abs(rw.rv[p + 2]) * ws.ii[j] * rw.lref[0])
    return dv


@nb.njit(cache=True)
def _increment(m, rw):
    """rw.lt += D·J_S·(J_SᵀDJ_S)⁻¹·rw.rv (the factor in rw.kf, the rows in rw.je)."""
    band_substitute(rw.rv.shape[0], rw.kf, rw.rv)
    for k in range(m.n0.shape[0]):
        ends = (m.ba[k], m.bb[k])
        for i in range(3):
            r = 3 * k + i
            if rw.wt[r] == 0.0:
                continue
            u = 0.0
            for p in range(2):
                if ends[p] >= 0:
                    q = 3 * m.bpos[ends[p]]
                    u += rw.je[r, p, 0] * rw.rv[q] + rw.je[r, p, 1] * rw.rv[q + 1] \
                        + rw.je[r, p, 2] * rw.rv[q + 2]
            rw.lt[r] += rw.wt[r] * u
    _held(m, rw)


@nb.njit(cache=True)
def _held(m, rw):
    """Λ_t of the joints held at their cone's edge: ±μ·(Λ_n0 + Λ_n1)."""
    for k in range(m.n0.shape[0]):
        if rw.tb_set[k] != 0:
            rw.lt[3 * k + 2] = rw.tb_set[k] * m.mu[k] * (rw.lt[3 * k] + rw.lt[3 * k + 1])


@nb.njit(cache=True)
def _balance(m, ws, rw, vx, vy, om, tol_v):
    """Λ on S balancing the loads (rw.lt), refined to tol_v. False if it does not converge."""
    for r in range(rw.lt.shape[0]):
        rw.lt[r] = ws.lam[r] if rw.rs_set[r] else 0.0
    _held(m, rw)
    _rows(m, ws, rw)
    for _ in range(REST_REFINE):
        if _residual(m, ws, rw, vx, vy, om) <= tol_v:
            return True
        _increment(m, rw)
    return _residual(m, ws, rw, vx, vy, om) <= tol_v


@nb.njit(cache=True)
def _admissible(m, rw, tol_l):
    """Λ_n ≥ 0 and |Λ_t| ≤ μ·(Λ_n0 + Λ_n1) within tol_l (Eq. (9.2)). Where not, the next S
    (rw.rs_new, rw.tb_new) leaves out the corner (and a joint's tangential row with its last
    corner) or holds the joint at its cone's edge. Returns the number of changes."""
    out = 0
    for k in range(m.n0.shape[0]):
        r = 3 * k
        rw.tb_new[k] = rw.tb_set[k]
        for i in range(3):
            rw.rs_new[r + i] = rw.rs_set[r + i]
        for c in range(2):
            if rw.lt[r + c] < -tol_l:
                rw.rs_new[r + c] = False
                out += 1
        if not (rw.rs_new[r] or rw.rs_new[r + 1]):
            out += rw.rs_new[r + 2]
            rw.rs_new[r + 2] = False
            rw.tb_new[k] = 0
        elif rw.tb_set[k] == 0 and not math.isinf(m.mu[k]) and \
                abs(rw.lt[r + 2]) > m.mu[k] * (rw.lt[r] + rw.lt[r + 1]) + tol_l:
            rw.tb_new[k] = 1 if rw.lt[r + 2] > 0.0 else -1
            out += 1
    return out


@nb.njit(cache=True)
def _complementary(m, ws, rw, tol_u):
    """At ws.v (the velocities Λ gives): |U| ≤ tol_u on S, U_n ≥ −tol_u on the other rows
    (Eq. (9.1)); finite-μ tangential rows outside S carry no impulse, any U_t will do."""
    for k in range(m.n0.shape[0]):
        a = m.ba[k]
        b = m.bb[k]
        for i in range(3):
            r = 3 * k + i
            u = ws.bias[r]
            if a >= 0:
                u += ws.ja[r, 0] * rw.vt[0, a] + ws.ja[r, 1] * rw.vt[1, a] \
                    + ws.ja[r, 2] * rw.vt[2, a]
            if b >= 0:
                u += ws.jb[r, 0] * rw.vt[0, b] + ws.jb[r, 1] * rw.vt[1, b] \
                    + ws.jb[r, 2] * rw.vt[2, b]
            if rw.rs_set[r]:
                if abs(u) > tol_u:
                    return False
            elif i < 2 and u < -tol_u:
                return False
    return True


@nb.njit(cache=True)
def _stick(m, ws, rw, vx, vy, om, tol_u, tol_l, every):
    """Admissible Λ (rw.lt) that stops every body, starting from the last impulses on S
    (``every``: on every closed corner), leaving inadmissible rows out up to ``REST_DROPS``
    times."""
    changed = _support(m, ws, rw, every) or every
    for _ in range(REST_DROPS + 1):
        if changed or rw.rstate[0] == 0.0:
            rw.rstate[0] = 1.0 if _gram(m, ws, rw, every) else -1.0
        if rw.rstate[0] < 0.0:
            return False
        if not _balance(m, ws, rw, vx, vy, om, 0.1 * tol_u):
            if changed:
                return False
            rw.rstate[0] = 1.0 if _gram(m, ws, rw, False) else -1.0  # the factor was too old
            if rw.rstate[0] < 0.0 or not _balance(m, ws, rw, vx, vy, om, 0.1 * tol_u):
                return False
        if _admissible(m, rw, tol_l) == 0:
            return True
        changed = True
    return False


@nb.njit(cache=True)
def rest_solve(m, ws, rw, vx, vy, om, tol_u, tol_l):
    """The rest path (module docstring) for the free velocities (vx, vy, om), turned into
    v⁺ in place and ws.lam into Λ if it solves the step (docs/theory.md Eq. (9.7)). Needs
    the step's geometry and bias in ws. Returns True if it did."""
    nbod = m.mass.shape[0]
    if rw.rstate[1] > REST_V:
        return False
    for every in (False, True):
        if _stick(m, ws, rw, vx, vy, om, tol_u, tol_l, every):
            break
        if every:
            return False
    tx, ty, to = rw.vt[0], rw.vt[1], rw.vt[2]
    for j in range(nbod):
        tx[j] = vx[j]
        ty[j] = vy[j]
        to[j] = om[j]
    d = np.empty(3)
    for k in range(m.n0.shape[0]):
        for i in range(3):
            d[i] = rw.lt[3 * k + i]
        apply_impulse(k, m.ba, m.bb, ws.ja, ws.jb, d, ws.im, ws.ii, tx, ty, to)
    if not _complementary(m, ws, rw, tol_u):
        return False
    for j in range(nbod):
        vx[j] = tx[j]
        vy[j] = ty[j]
        om[j] = to[j]
    for r in range(rw.lt.shape[0]):
        ws.lam[r] = rw.lt[r]
    return True


@nb.njit(cache=True)
def note_velocity(m, rw, vx, vy, om, gh):
    """Store the step's largest body velocity relative to g·h (the gate ``REST_V``)."""
    v = 0.0
    for j in range(m.mass.shape[0]):
        v = max(v, abs(vx[j]), abs(vy[j]), abs(om[j]) * rw.lref[0])
    rw.rstate[1] = v / gh
