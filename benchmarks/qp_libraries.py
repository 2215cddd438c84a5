"""Convex-optimisation libraries on the tall wall's violent steps, against rockarch's exact
contact solve (docs/performance.md, "Library QP solvers on the violent steps").

The 205-block wall ``ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6)``
under the first ``--seconds`` of the bundled El Centro 180° record at 2·ap,min: the steps
whose exact solve needs the proximal continuation (docs/theory.md Eq. (9.9)) are captured
(every ``--every``-th, at most ``--steps``), and each is solved again from the same state:

- by rockarch's exact solve (:func:`rockarch.mdof.graph_stepper.contact_step`, Coulomb's
  law without dilatancy, Eqs. (9.1)–(9.3));
- as the Anitescu-type convex step (the quadratic programme in the bodies' velocities
  ``min ½(v − v_f)ᵀM(v − v_f)`` subject to ``u_n ± μ·u_t ≥ 0`` at every corner of a joint or
  point contact, u = J·v + b: Coulomb's cone with an associated flow, so that a sliding
  corner separates at μ·|u_t|) by Clarabel (interior point), OSQP (ADMM) and ProxQP
  (proxsuite, a proximal augmented Lagrangian);
- as a sequence of such programmes with the friction bounds β = μ·ΣΛ_n frozen at the last
  solution (Tresca's law, no dilatancy) by Clarabel, until β holds: the library route to the
  law rockarch solves.

The rows, the biases (docs/theory.md Eq. (6.3a)) and the free velocities are those of the
exact solve (:func:`rockarch.mdof.graph_stepper.contact_rows`); the libraries run without
rockarch's regularisation ε (they do not need it) to the tolerance of the exact solve on this
wall, 10⁻⁴·g·h in velocity. Prints, per solver, the CPU time per step, the largest difference
of the bodies' velocities from the exact solve (rotations times the thinnest joint), the
largest penetration velocity and the largest opening velocity of a compressed corner of a
sliding joint (the dilatancy). The libraries are installed by ``make bench``; one that is
missing is skipped.

    .venv/bin/python benchmarks/qp_libraries.py       # ~2 min
"""

from __future__ import annotations

import argparse
import copy
import importlib
import time

import numpy as np
import scipy.sparse as sp

import rockarch as ra
from rockarch.core.constants import GAP_TOL, MDOF_H_FACTOR
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion.signals import GroundMotion

#: Stand-in for μ = ∞ in the cone constraints (no joint of this wall has it).
MU_INF = 1e3


def capture(seconds: float, ratio: float, every: int, most: int):
    """The wall, its model and copies of the inputs of the steps that need the
    proximal continuation."""
    a = ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6).assembly
    m = graph_model(a)
    rec = ra.el_centro()
    n = int(seconds / (rec.t[1] - rec.t[0])) + 1
    mo = GroundMotion(rec.t[:n], rec.a[:n], name=rec.name).scaled(ratio * a.ap_min / rec.pga)
    step = gs.contact_step
    kept, seen = [], [0]

    def counted(*args):
        ws = args[-1]
        before = copy.deepcopy(args[1:])
        p0 = ws.sw.state[7]
        its = step(*args)
        if ws.sw.state[7] > p0:
            seen[0] += 1
            if seen[0] % every == 0 and len(kept) < most:
                kept.append(before)
        return its

    h = MDOF_H_FACTOR / a.p_ref
    empty = (np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8), np.zeros(0))
    gr.contact_step = counted
    try:
        gr.run.py_func(m, 1.0, mo.t, mo.a, 1.0, h, mo.duration, mo.duration, GAP_TOL, 0,
                       *empty, False, True)
    finally:
        gr.contact_step = step
    return a, m, kept, seen[0]


def problem(m, inputs):
    """The step's rows from a copy of its inputs: J (sparse), b, the free velocities, M's
    diagonal, the cone constraints G·v ≥ −c and their rows, and the exact solution."""
    x, y, ph, vx, vy, om, gtol, hh, v_app, eps_n, eps_t, tol_u, tol_l, margin, ws = \
        copy.deepcopy(inputs)
    nr = gs.contact_rows(m, x, y, ph, vx, vy, om, gtol, hh, v_app, margin, ws)
    sw = ws.sw
    nb = m.mass.shape[0]
    rows, cols, vals = [], [], []
    wr = ws.rows
    for r in range(nr):
        for body, jac in ((wr.rba[r], wr.ja[r]), (wr.rbb[r], wr.jb[r])):
            if body >= 0:
                rows += [r] * 3
                cols += [3 * body, 3 * body + 1, 3 * body + 2]
                vals += list(jac)
    jmat = sp.csr_matrix((vals, (rows, cols)), shape=(nr, 3 * nb))
    b = ws.bias[:nr].copy()
    tn0, tn1, tmu = wr.tn0[:nr], wr.tn1[:nr], wr.tmu[:nr]
    cone = []  # (normal row, tangential row, ±1)
    for t in range(nr):
        if tn0[t] >= 0:
            for q in (tn0[t], tn1[t]):
                if q >= 0:
                    cone += [(q, t, 1.0), (q, t, -1.0)]
    mu = np.minimum(tmu, MU_INF)
    qn = np.array([c[0] for c in cone])
    tt = np.array([c[1] for c in cone])
    sg = np.array([c[2] for c in cone])
    g = jmat[qn] + sp.diags(sg * mu[tt]) @ jmat[tt]
    c = b[qn]
    # the exact solve from the same state
    ex = copy.deepcopy(inputs)
    t0 = time.process_time()
    its = gs.contact_step(m, *ex)
    t_exact = time.process_time() - t0
    v_exact = np.column_stack([ex[3], ex[4], ex[5]]).ravel()
    lam_exact = np.where(tn0 < 0, ex[-1].lam[:nr], 0.0)
    return dict(j=jmat, b=b, vf=sw.vf.copy(), md=sw.mdiag.copy(), g=g.tocsc(), c=c,
                tn0=tn0.copy(), tn1=tn1.copy(), mu=mu, lref=ws.lref[0], tol=100 * tol_u,
                v_exact=v_exact, lam_exact=lam_exact, t_exact=t_exact, failed=its < 0,
                its_exact=abs(its), nr=nr, cone_q=qn)


def quality(p, v, lam_n):
    """Largest velocity difference from the exact solve, largest penetration velocity, and
    the dilatancy: the largest opening velocity of a compressed corner (Λ_n·max(1/m) above
    the tolerance) of a sliding joint (|u_t| above it)."""
    scale = np.tile([1.0, 1.0, p["lref"]], len(v) // 3)
    dv = np.max(np.abs((v - p["v_exact"]) * scale))
    u = p["j"] @ v + p["b"]
    normal = p["tn0"] < 0
    pen = max(0.0, -u[normal].min())
    pressed = np.abs(lam_n) * np.max(1.0 / p["md"]) > p["tol"]
    dil = 0.0
    for t in np.flatnonzero(~normal):
        if abs(u[t]) > p["tol"]:
            for q in (p["tn0"][t], p["tn1"][t]):
                if q >= 0 and pressed[q]:
                    dil = max(dil, u[q])
    return dv, pen, dil


def cone_impulses(p, mult):
    """Λ_n of every normal row: the sum of the multipliers of its corner's cone
    constraints."""
    lam_n = np.zeros(p["nr"])
    np.add.at(lam_n, p["cone_q"], np.abs(mult))
    return lam_n


def clarabel_qp(p, beta=None):
    """min ½vᵀMv − (Mv_f)ᵀv s.t. G·v + c ≥ 0 (``beta`` None: the cone) or, with the bounds
    β frozen, J_n·v + b ≥ 0 and s_t ≥ |J_t·v| at the cost β·s_t. Returns v, the iterations
    and the normal rows' impulses (the constraints' multipliers)."""
    import clarabel

    n, nr = len(p["vf"]), p["nr"]
    normal = np.flatnonzero(p["tn0"] < 0)
    lam_n = np.zeros(nr)
    if beta is None:
        pm = sp.diags(p["md"]).tocsc()
        q = -p["md"] * p["vf"]
        a, bb = -p["g"], p["c"]
    else:
        jm = p["j"]
        tang = np.flatnonzero(p["tn0"] >= 0)
        nt = len(tang)
        pm = sp.block_diag([sp.diags(p["md"]), sp.csc_matrix((nt, nt))]).tocsc()
        q = np.concatenate([-p["md"] * p["vf"], beta])
        eye = sp.identity(nt)
        a = sp.vstack([sp.hstack([-jm[normal], sp.csc_matrix((len(normal), nt))]),
                       sp.hstack([jm[tang], -eye]), sp.hstack([-jm[tang], -eye])]).tocsc()
        bb = np.concatenate([p["b"][normal], np.zeros(2 * nt)])
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.tol_feas = settings.tol_gap_abs = 1e-10
    settings.tol_gap_rel = 1e-9
    sol = clarabel.DefaultSolver(pm, q, a, bb, [clarabel.NonnegativeConeT(a.shape[0])],
                                 settings)
    res = sol.solve()
    z = np.asarray(res.z)
    if beta is None:
        lam_n = cone_impulses(p, z)
    else:
        lam_n[normal] = z[:len(normal)]
    return np.asarray(res.x)[:n], res.iterations, lam_n


def tresca(p):
    """Clarabel on the programmes with the bounds frozen at the last normal impulses (from
    the cone's solution first), until the velocities change by less than the tolerance
    between two programmes (at most 30; the normal impulses of a hyperstatic wall are not
    unique without rockarch's regularisation ε, its velocities are). Returns v, the
    programmes solved and the normal impulses."""
    tang = np.flatnonzero(p["tn0"] >= 0)
    scale = np.tile([1.0, 1.0, p["lref"]], len(p["vf"]) // 3)
    v, _, lam_n = clarabel_qp(p)
    solved = 1
    while solved <= 30:
        beta = np.array([p["mu"][t] * (lam_n[p["tn0"][t]]
                                        + (lam_n[p["tn1"][t]] if p["tn1"][t] >= 0 else 0.0))
                         for t in tang])
        v_new, _, lam_n = clarabel_qp(p, beta)
        solved += 1
        change = np.max(np.abs((v_new - v) * scale))
        v = v_new
        if change <= p["tol"]:
            break
    return v, solved, lam_n


def run_osqp(p):
    import osqp

    prob = osqp.OSQP()
    prob.setup(sp.diags(p["md"]).tocsc(), -p["md"] * p["vf"], p["g"], -p["c"],
               np.full(len(p["c"]), np.inf), eps_abs=p["tol"], eps_rel=0.0, max_iter=200000,
               verbose=False, polishing=True)
    res = prob.solve()
    return np.asarray(res.x), res.info.iter, cone_impulses(p, res.y)


def run_proxqp(p):
    import proxsuite

    n, nc = len(p["vf"]), len(p["c"])
    qp = proxsuite.proxqp.sparse.QP(n, 0, nc)
    qp.settings.eps_abs = p["tol"]
    qp.settings.eps_rel = 0.0
    qp.settings.max_iter = 10000
    qp.init(sp.diags(p["md"]).tocsc(), -p["md"] * p["vf"], None, None, p["g"], -p["c"],
            np.full(nc, 1e20))
    qp.solve()
    return np.asarray(qp.results.x), qp.results.info.iter, cone_impulses(p, qp.results.z)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=2.5, help="seconds of the record")
    ap.add_argument("--ratio", type=float, default=2.0, help="PGA / ap,min")
    ap.add_argument("--every", type=int, default=10, help="keep every n-th violent step")
    ap.add_argument("--steps", type=int, default=20, help="at most this many steps")
    args = ap.parse_args()
    if args.every < 1 or args.steps < 1 or args.seconds <= 0 or args.ratio <= 0:
        ap.error("--every and --steps need at least 1, --seconds and --ratio a positive value")
    a, m, kept, seen = capture(args.seconds, args.ratio, args.every, args.steps)
    if not kept:
        raise SystemExit(f"error: no step of the first {args.seconds:g} s needed the proximal "
                         f"continuation ({seen} seen): give more --seconds or a larger --ratio")
    probs = [problem(m, k) for k in kept]
    p0 = probs[0]
    print(f"wall 20x10 (205 blocks), first {args.seconds:g} s of El Centro at "
          f"{args.ratio:g}·ap,min: {seen} steps need the proximal continuation; "
          f"{len(probs)} of them solved again ({p0['nr']} rows, {len(p0['vf'])} velocities, "
          f"{len(p0['c'])} cone constraints in the first)")
    solvers = {"rockarch exact solve (no dilatancy)": None,
               "Clarabel, Anitescu cone (dilatant)": ("clarabel", clarabel_qp),
               "OSQP, Anitescu cone (dilatant)": ("osqp", run_osqp),
               "ProxQP, Anitescu cone (dilatant; the first 3 steps only)":
                   ("proxsuite", run_proxqp, 3),
               "Clarabel, frozen bounds until they hold (no dilatancy)": ("clarabel", None)}
    print("| solver | CPU per step, median [ms] | mean | largest | iterations (median) "
          "| largest velocity difference from the exact solve [m/s] "
          "| penetration [m/s] | dilatancy [m/s] |")
    print("|---|---|---|---|---|---|---|---|")
    for name, spec in solvers.items():
        if spec is not None:
            try:
                importlib.import_module(spec[0])
            except ImportError:
                print(f"| {name} | not installed (make bench installs it) | | | | | | |")
                continue
        times, iters, dvs, pens, dils = [], [], [], [], []
        for p in probs[:spec[2] if spec is not None and len(spec) > 2 else None]:
            if spec is None:
                times.append(p["t_exact"])
                v, it, lam_n = p["v_exact"], p["its_exact"], p["lam_exact"]
            else:
                t0 = time.process_time()
                v, it, lam_n = (tresca if spec[1] is None else spec[1])(p)
                times.append(time.process_time() - t0)
            dv, pen, dil = quality(p, v, lam_n)
            iters.append(it)
            dvs.append(dv)
            pens.append(pen)
            dils.append(dil)
        print(f"| {name} | {1e3 * np.median(times):.1f} | {1e3 * np.mean(times):.1f} | "
              f"{1e3 * max(times):.1f} | "
              f"{np.median(iters):.0f} | {max(dvs):.2e} | {max(pens):.2e} | {max(dils):.2e} |",
              flush=True)
    print(f"(the exact solve failed in {sum(p['failed'] for p in probs)} of these steps; "
          f"the tolerance 10⁻⁴·g·h = {p0['tol']:.2e} m/s; iterations: rockarch's semismooth "
          f"iterations, the libraries' own, the programmes solved for the frozen bounds)")


if __name__ == "__main__":
    main()
