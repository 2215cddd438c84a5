"""The plain semismooth iteration on the slowly moving tall wall's steps (docs/performance.md,
"The slow steps' plain iterations").

The 205-block wall ``ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6)``
under the bundled El Centro 180° record scaled to 2·ap,min, run by the Python version of the
run loop (``graph_run.run.py_func``) around the compiled step up to ``--to`` seconds. Every
step that starts in [``--from``, ``--to``) is kept (a deep copy of its inputs) and then
solved again from that copy: once by the solver as the run does it (its banded LU
factorisations, the steps the interior-point method solved, the rows whose states differ
between the warm start and the solution), and once by the plain semismooth Newton method
alone (``contact_solver.semismooth``) for 1, 2, ..., ``--iterations`` iterations, printing
how many rows change state at each iteration (corner rows "n", tangential rows "t") and how
many of them return to their state of two iterations before ("/k": the iteration cycles).
The solve from the copy reproduces the run's factorisations exactly (checked per step).

With ``--methods``, three textbook globalisations of Newton's method are tried on the same
copies (numpy and scipy's SuperLU; each counts its factorisations until the contact law is
met within the engine's tolerance on this wall, 100·tol_u, or gives up after
``--budget``): a primal generalised Newton method on the velocities with an exact line
search on the regularised step's energy (the friction bounds at the last iterate's
impulses); Bertsekas' projected Newton method on the impulses with an Armijo search along
the projection arc (the bounds of the friction cone held until that problem is solved,
then updated); and block principal pivoting on the rows' states from the warm start, with
Murty's single pivot (the worst violation) after three exchanges that did not reduce the
violations (Júdice and Pires). And, as a fourth, the projected Gauss–Seidel iteration of
the distinct-element and game engines (NSGS: one row at a time, from the warm start, up to
``--sweeps`` sweeps, numba). ``--soften F`` tries them again, and the engine's solve, on
the same steps with ε_n, ε_t F times larger (a check that the methods work where the
problem is not degenerate).

    .venv/bin/python benchmarks/slow_steps.py             # ~25 min (the Python loop to 16.15 s)
    .venv/bin/python benchmarks/slow_steps.py --methods   # ~5 min more
    .venv/bin/python benchmarks/slow_steps.py --methods --soften 1e7   # the same, soft too
"""

from __future__ import annotations

import argparse
import copy
import time

import numba as nb
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from qp_libraries import problem  # benchmarks/ is on sys.path when run as a script

import rockarch as ra
from rockarch.core.constants import GAP_TOL, MDOF_H_FACTOR
from rockarch.mdof import contact_solver as cs
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof.contact_solver import PROX_TOL
from rockarch.mdof.kernel_data import graph_model


def _rows(m, keep):
    """The step's rows made from a copy of its inputs: (rows, workspace, ε_n, ε_t, tol_u,
    tol_l); the workspace holds them and the warm start."""
    x, y, ph, vx, vy, om, gtol, hh, v_app, eps_n, eps_t, tol_u, tol_l, margin, ws = \
        copy.deepcopy(keep)
    nr = gs.contact_rows(m, x, y, ph, vx, vy, om, gtol, hh, v_app, margin, ws)
    return nr, ws, eps_n, eps_t, tol_u, tol_l


def _replay(m, keep, iterations: int) -> tuple[str, int]:
    """The step's solve and its plain iterations from a copy of its inputs."""
    nr, ws, eps_n, eps_t, tol_u, tol_l = _rows(m, keep)
    nbod = m.mass.shape[0]
    normal = ws.rows.tn0[:nr] < 0
    warm = ws.sw.st[:nr].copy()
    w = copy.deepcopy(ws)
    s0 = w.sw.state.copy()
    its = cs.solve(nbod, nr, w.rows, w.bias, w.lam, eps_n, eps_t, w.sw, tol_u, tol_l,
                   w.lref[0])
    d = w.sw.state - s0
    differ = int((w.sw.st[:nr] != warm).sum())
    states = [warm]
    for k in range(1, iterations + 1):
        w = copy.deepcopy(ws)
        cs._weights(nr, w.rows.tn0, eps_n, eps_t, 0.0, w.sw.ie)
        r = cs.semismooth(nbod, nr, w.rows, w.bias, w.lam, w.sw, tol_u, tol_l, w.lref[0], k,
                          0.0)
        states.append(w.sw.st[:nr].copy())
        if r > 0:
            break
    changes = []
    for k in range(1, len(states)):
        ch = states[k] != states[k - 1]
        back = f"/{int((ch & (states[k] == states[k - 2])).sum())}" if k >= 2 else ""
        changes.append(f"{int((ch & normal).sum())}n{int((ch & ~normal).sum())}t{back}")
    line = (f"{int(d[2]):4d} {'yes' if d[8] else 'no ':3s} {differ:5d}   "
            f"{' '.join(changes)}{'' if its >= 0 else '  (failed)'}")
    return line, int(d[2])


class _Step:
    """The step's rows in matrix form (``qp_libraries.problem``), its warm start, and the
    numpy forms of its contact law (docs/theory.md Eqs. (9.1)–(9.3) with ε)."""

    def __init__(self, m, keep):
        p = problem(m, keep)
        self.ws = _rows(m, keep)[1]  # its rows, for contact_solver.law_residual
        ws = keep[-1]
        self.eps_n, self.eps_t, self.tol = keep[9], keep[10], PROX_TOL * keep[11]
        self.j = p["j"].tocsr()
        self.jt = self.j.T.tocsr()
        self.b, self.vf, self.md, self.nr = p["b"], p["vf"], p["md"], p["nr"]
        self.normal = p["tn0"] < 0
        self.t = np.flatnonzero(~self.normal)
        self.c0, c1 = p["tn0"][self.t], p["tn1"][self.t]
        self.has1 = c1 >= 0
        self.c1 = np.where(self.has1, c1, 0)
        self.mu = p["mu"][self.t]
        self.eps = np.where(self.normal, self.eps_n, self.eps_t)
        self.w = np.asarray(self.j.multiply(self.j) @ (1.0 / self.md)).ravel()
        self.lam0 = ws.lam[:self.nr].copy()
        self.st0 = ws.sw.st[:self.nr].copy()

    def beta(self, lam):
        """The friction bounds μ·ΣΛ_n⁺ of the tangential rows."""
        ln = np.maximum(lam, 0.0)
        return self.mu * (ln[self.c0] + np.where(self.has1, ln[self.c1], 0.0))

    def velocities(self, lam):
        return self.vf + (self.jt @ lam) / self.md

    def residual(self, lam):
        """The law's natural residual at Λ and v(Λ) [m/s] (``contact_solver.law_residual``)."""
        return cs.law_residual(self.nr, self.ws.rows, self.ws.bias, lam, self.eps_n,
                               self.eps_t, self.ws.sw, self.velocities(lam))

    def impulses(self, u, bt):
        """Λ(v) of the regularised law at u = J·v + b, friction bounds bt."""
        lam = np.zeros(self.nr)
        lam[self.normal] = np.maximum(0.0, -u[self.normal] / self.eps_n)
        ut = u[self.t]
        lam[self.t] = np.where(np.abs(ut) <= self.eps_t * bt, -ut / self.eps_t,
                               -bt * np.sign(ut))
        return lam


def _primal(s: _Step, budget: int) -> int | None:
    """Generalised Newton on the step's energy in v, ½|v − v_free|²_M + Σ penalties of
    u = J·v + b, with an exact line search (regula falsi on its slope)."""
    v = s.velocities(s.lam0)
    for k in range(budget):
        u = s.j @ v + s.b
        lam0 = s.impulses(u, s.beta(np.maximum(0.0, -u / s.eps_n)))
        bt = s.beta(lam0)
        lam = s.impulses(u, bt)
        if s.residual(lam) <= s.tol:
            return k
        grad = s.md * (v - s.vf) - s.jt @ lam
        d = np.where(s.normal, (u < 0) / s.eps_n, 0.0)
        d[s.t] = (np.abs(u[s.t]) <= s.eps_t * bt) / s.eps_t
        dv = spl.splu((sp.diags(s.md) + s.jt @ sp.diags(d) @ s.j).tocsc()).solve(-grad)
        jd = s.j @ dv

        def slope(a, u=u, v=v, dv=dv, jd=jd, bt=bt):
            return dv @ (s.md * (v + a * dv - s.vf)) - jd @ s.impulses(u + a * jd, bt)

        a, f1 = 1.0, slope(1.0)
        if f1 > 0.0:
            lo, hi, flo, fhi = 0.0, 1.0, slope(0.0), f1
            for _ in range(40):
                a = min(max(lo - flo * (hi - lo) / (fhi - flo), lo + 1e-3 * (hi - lo)),
                        hi - 1e-3 * (hi - lo))
                fa = slope(a)
                lo, flo, hi, fhi = (a, fa, hi, fhi) if fa <= 0.0 else (lo, flo, a, fa)
                if hi - lo < 1e-12:
                    break
        v = v + a * dv
    return None


def _projected(s: _Step, budget: int) -> int | None:
    """Bertsekas' projected Newton on the impulses: min ½ΛᵀWΛ + cᵀΛ over the box of the
    current friction bounds (W = J·M⁻¹·Jᵀ + ε, c = J·v_free + b), Armijo on the arc."""
    c = s.j @ s.vf + s.b

    def box(lam):
        lo = np.where(s.normal, 0.0, -np.inf)
        hi = np.full(s.nr, np.inf)
        lo[s.t], hi[s.t] = -s.beta(lam), s.beta(lam)
        return lo, hi

    def q(lam):
        return 0.5 * lam @ (s.j @ ((s.jt @ lam) / s.md) + s.eps * lam) + c @ lam

    lo, hi = box(s.lam0)
    lam = np.clip(s.lam0, lo, hi)
    wd = s.w + s.eps
    for k in range(budget):
        if s.residual(lam) <= s.tol:
            return k
        grad = s.j @ ((s.jt @ lam) / s.md) + s.eps * lam + c
        pg = wd * (lam - np.clip(lam - grad / wd, lo, hi))
        if np.abs(pg).max() <= s.tol:  # this box solved: the cone's bounds of its impulses
            lo, hi = box(lam)
            lam = np.clip(lam, lo, hi)
            grad = s.j @ ((s.jt @ lam) / s.md) + s.eps * lam + c
            pg = wd * (lam - np.clip(lam - grad / wd, lo, hi))
        delta = min(np.abs(pg / wd).max(), 1e-3 * max(np.abs(lam).max(), 1e-12))
        fixed = (((lam <= lo + delta) & (grad > 0)) | ((lam >= hi - delta) & (grad < 0))
                 | (hi <= lo))
        ei = np.where(fixed, 0.0, 1.0 / s.eps)
        gf = np.where(fixed, 0.0, grad)
        y = spl.splu((sp.diags(s.md) + s.jt @ sp.diags(ei) @ s.j).tocsc()).solve(
            s.jt @ (ei * gf))
        d = ei * (s.j @ y) - ei * gf  # W_FF⁻¹ by Woodbury on the body-space matrix
        d[fixed] = -grad[fixed] / wd[fixed]
        q0, a = q(lam), 1.0
        while True:
            new = np.clip(lam + a * d, lo, hi)
            if q0 - q(new) >= 1e-4 * (-a * (gf @ d) + grad[fixed] @ (lam - new)[fixed]) \
                    or a < 1e-10:
                break
            a *= 0.5
        lam = new
    return None


def _pivoting(s: _Step, budget: int) -> int | None:
    """Block principal pivoting on the rows' states from the warm start's, with Murty's
    single pivot after three exchanges that did not reduce the violations."""
    n, t = s.normal, s.t
    st = np.where(n, np.where(s.st0 == 0, 0, 1), np.where(s.st0 == 2, 1, s.st0)).astype(float)
    best, stalled = None, 0
    for k in range(budget):
        rows, cols, vals = [], [], []
        for r in np.flatnonzero(st == 0):  # closed corners and sticking rows: Λ = −u/ε
            rows.append(r), cols.append(r), vals.append(-1.0 / s.eps[r])
        for i, r in enumerate(t):  # sliding rows: Λ_t = ±μ·ΣΛ_n of their closed corners
            if st[r] != 0:
                for qn in (s.c0[i], s.c1[i] if s.has1[i] else -1):
                    if qn >= 0 and st[qn] == 0:
                        rows.append(r), cols.append(qn), vals.append(-st[r] * s.mu[i] / s.eps_n)
        kmat = sp.csr_matrix((vals, (rows, cols)), shape=(s.nr, s.nr))
        v = spl.splu((sp.diags(s.md) - s.jt @ kmat @ s.j).tocsc()).solve(
            s.md * s.vf + s.jt @ (kmat @ s.b))
        u = s.j @ v + s.b
        lam = kmat @ u
        if s.residual(lam) <= s.tol:
            return k + 1
        bt = np.zeros(s.nr)
        bt[t] = s.beta(np.where(n, lam, 0.0))
        tol = s.tol
        while True:  # the states violated by more than tol (tighter while none is: the law's
            new, sev = st.copy(), np.zeros(s.nr)  # residual counts a little more than these)
            for mask, to, how in (
                    (n & (st == 0) & (s.w * lam < -tol), 1.0, -s.w * lam),
                    (n & (st == 1) & (u < -tol), 0.0, -u),
                    (~n & (st == 0) & (s.w * (np.abs(lam) - bt) > tol), np.sign(lam),
                     s.w * (np.abs(lam) - bt)),
                    (~n & (st != 0) & (st * (u + s.eps * lam) > tol), 0.0,
                     st * (u + s.eps * lam))):
                new[mask] = to[mask] if isinstance(to, np.ndarray) else to
                sev[mask] = how[mask]
            bad = np.flatnonzero(new != st)
            if len(bad) or tol < 1e-3 * s.tol:
                break
            tol *= 0.5
        if len(bad) == 0:  # no state to change, the law not met: stuck
            return None
        if best is None or len(bad) < best:
            best, stalled, st = len(bad), 0, new
        elif stalled < 3:
            stalled, st = stalled + 1, new
        else:
            r = bad[np.argmax(sev[bad])]
            st[r] = new[r]
    return None


@nb.njit(cache=False)
def _nsgs_sweeps(ptr, col, val, b, vf, md, tn0, tn1, mu, eps, w, lam, sweeps, tol):
    """Projected Gauss–Seidel on the rows (alternating order), the law's natural residual
    checked every 10 sweeps; the sweeps it took (−sweeps: not within tol)."""
    nr = len(b)
    v = vf.copy()
    for r in range(nr):
        for k in range(ptr[r], ptr[r + 1]):
            v[col[k]] += val[k] * lam[r] / md[col[k]]
    for s in range(sweeps):
        for i in range(nr):
            r = i if s % 2 == 0 else nr - 1 - i
            u = b[r]
            for k in range(ptr[r], ptr[r + 1]):
                u += val[k] * v[col[k]]
            new = lam[r] - (u + eps[r] * lam[r]) / (w[r] + eps[r])
            if tn0[r] < 0:
                new = max(new, 0.0)
            else:
                bt = mu[r] * (max(lam[tn0[r]], 0.0) + (max(lam[tn1[r]], 0.0) if tn1[r] >= 0
                                                       else 0.0))
                new = min(max(new, -bt), bt)
            for k in range(ptr[r], ptr[r + 1]):
                v[col[k]] += val[k] * (new - lam[r]) / md[col[k]]
            lam[r] = new
        if (s + 1) % 10 == 0:
            worst = 0.0
            for r in range(nr):
                u = b[r]
                for k in range(ptr[r], ptr[r + 1]):
                    u += val[k] * v[col[k]]
                if tn0[r] < 0:
                    res = abs(min(w[r] * lam[r], u + eps[r] * lam[r]))
                else:
                    bt = mu[r] * (max(lam[tn0[r]], 0.0) + (max(lam[tn1[r]], 0.0)
                                                           if tn1[r] >= 0 else 0.0))
                    trial = lam[r] - (u + eps[r] * lam[r]) / w[r]
                    res = w[r] * abs(lam[r] - min(max(trial, -bt), bt))
                worst = max(worst, res)
            if worst <= tol:
                return s + 1
    return -sweeps


def _gauss_seidel(s: _Step, sweeps: int) -> int | None:
    """NSGS from the warm start: the sweeps it takes to meet the law, or None."""
    tn1 = np.full(s.nr, -1)
    tn0 = np.full(s.nr, -1)
    mu = np.zeros(s.nr)
    tn0[s.t], tn1[s.t], mu[s.t] = s.c0, np.where(s.has1, s.c1, -1), s.mu
    k = _nsgs_sweeps(s.j.indptr, s.j.indices, s.j.data, s.b, s.vf, s.md, tn0, tn1, mu, s.eps,
                     s.w, s.lam0.copy(), sweeps, s.tol)
    return k if k > 0 else None


def _softened(keep, factor: float):
    """A copy of the step's inputs with its regularisation ε_n, ε_t times ``factor``."""
    k = list(copy.deepcopy(keep))
    k[9] *= factor
    k[10] *= factor
    return tuple(k)


def _engine_factorisations(m, keep) -> int:
    """The factorisations of the engine's solve of the step from a copy of its inputs."""
    nr, ws, eps_n, eps_t, tol_u, tol_l = _rows(m, keep)
    f0 = int(ws.sw.state[2])
    cs.solve(m.mass.shape[0], nr, ws.rows, ws.bias, ws.lam, eps_n, eps_t, ws.sw, tol_u, tol_l,
             ws.lref[0])
    return int(ws.sw.state[2]) - f0


def _methods(m, keeps, args, label: str) -> None:
    """The four textbook methods on the kept steps: how many each solves, and at what cost."""
    print(f"textbook methods{label}, at most {args.budget} factorisations each (scipy "
          "SuperLU; the law within 100·tol_u):")
    for name, method in (("primal Newton, exact line search", _primal),
                         ("projected Newton on the impulses", _projected),
                         ("block principal pivoting + Murty", _pivoting)):
        t_cpu = time.process_time()
        got = [method(_Step(m, keep), args.budget) for keep in keeps]
        ok = [g for g in got if g is not None]
        print(f"  {name}: {len(ok)} of {len(got)} steps solved"
              + (f", median {np.median(ok):.0f} factorisations" if ok else "")
              + f" ({time.process_time() - t_cpu:.0f} s)")
    t_cpu = time.process_time()
    got = [_gauss_seidel(_Step(m, keep), args.sweeps) for keep in keeps]
    ok = [g for g in got if g is not None]
    print(f"  projected Gauss–Seidel (NSGS), at most {args.sweeps} sweeps: {len(ok)} of "
          f"{len(got)} steps solved" + (f", median {np.median(ok):.0f} sweeps" if ok else "")
          + f" ({time.process_time() - t_cpu:.0f} s)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--from", dest="t0", type=float, default=16.0, help="first second kept")
    ap.add_argument("--to", dest="t1", type=float, default=16.15, help="last second kept")
    ap.add_argument("--ratio", type=float, default=2.0, help="PGA / ap,min")
    ap.add_argument("--iterations", type=int, default=12, help="plain iterations traced")
    ap.add_argument("--methods", action="store_true",
                    help="also try three textbook globalisations on the kept steps")
    ap.add_argument("--budget", type=int, default=100,
                    help="factorisations a textbook method gets per step")
    ap.add_argument("--sweeps", type=int, default=5000,
                    help="Gauss–Seidel sweeps per step (--methods)")
    ap.add_argument("--soften", type=float, default=1.0,
                    help="--methods again on the steps with eps this many times larger")
    args = ap.parse_args()
    rec = ra.el_centro()
    if not 0.0 <= args.t0 < args.t1 <= rec.duration:
        ap.error(f"need 0 <= --from < --to <= {rec.duration:g} s (the record)")
    if min(args.iterations, args.budget, args.sweeps) < 1 or min(args.ratio, args.soften) <= 0:
        ap.error("--iterations, --budget and --sweeps must be >= 1, --ratio and --soften > 0")
    a = ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6).assembly
    m = graph_model(a)
    mo = rec.scaled(args.ratio * a.ap_min / rec.pga)
    step, predict = gs.contact_step, gr.kin.predict
    now = [0.0]
    kept = []

    def timed(*a_):  # kin.predict(..., t, ...): the time of the step being run
        now[0] = a_[10]
        return predict(*a_)

    class Done(Exception):
        pass

    def counted(*a_):
        if now[0] >= args.t1:
            raise Done
        keep = copy.deepcopy(a_[1:]) if now[0] >= args.t0 else None
        f0 = int(a_[-1].sw.state[2])
        its = step(*a_)
        if keep is not None:
            kept.append((now[0], int(a_[-1].sw.state[2]) - f0, keep))
        return its

    h = MDOF_H_FACTOR / a.p_ref
    empty = (np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8), np.zeros(0))
    t_cpu = time.process_time()
    gr.contact_step, gr.kin.predict = counted, timed
    try:
        gr.run.py_func(m, 1.0, mo.t, mo.a, 1.0, h, mo.duration, mo.duration, GAP_TOL, 0,
                       *empty, False, True)
    except Done:
        pass
    finally:
        gr.contact_step, gr.kin.predict = step, predict
    print(f"wall 20x10 (205 blocks), El Centro at {args.ratio:g}·ap,min: {len(kept)} steps "
          f"kept in [{args.t0:g}, {args.t1:g}) s ({time.process_time() - t_cpu:.0f} s of CPU "
          "to get there)")
    if not kept:
        print("no step solved in that window (the wall rested through it)")
        return
    print("   t [s]  fact  ip  differ   rows changed per plain iteration (n corner, "
          "t tangential, /back to two iterations before)")
    facts = []
    for t, fact, keep in kept:
        line, f = _replay(m, keep, args.iterations)
        assert f == fact, f"the replay took {f} factorisations, the run {fact}"
        facts.append(f)
        print(f"{t:8.4f}  {line}")
    print(f"factorisations per step: median {np.median(facts):.0f}, mean {np.mean(facts):.0f},"
          f" largest {max(facts)}")
    if not args.methods:
        return
    _methods(m, [keep for _, _, keep in kept], args, "")
    if args.soften != 1.0:
        soft = [_softened(keep, args.soften) for _, _, keep in kept]
        facts = [_engine_factorisations(m, keep) for keep in soft]
        print(f"the same steps with eps_n, eps_t {args.soften:g} times larger: the engine's "
              f"solve {np.median(facts):.0f} factorisations (median), largest {max(facts)}")
        _methods(m, soft, args, f" (eps x {args.soften:g})")

if __name__ == "__main__":
    main()
