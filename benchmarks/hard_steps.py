"""The contact solve's work on the violent steps of the tall wall (docs/performance.md,
"The proximal continuation's tolerance").

The 205-block wall ``ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6)``
under the first ``--seconds`` of the bundled El Centro 180° record scaled to 2·ap,min: its
steps are run by the Python version of the run loop (``graph_run.run.py_func``) around the
compiled step, so that every step's banded LU factorisations (the solver's counter) and CPU
time are read. Prints the steps solved, those that needed the proximal continuation
(docs/theory.md Eq. (9.9)), the factorisations and how they spread over the steps, the
steps that the interior-point method (Eq. (9.13)) solved and its iterations, the failed
steps, the residual of the contact law at the impulses of the steps that needed the
continuation (``contact_solver.law_residual``: the natural residual of Eqs. (9.1)–(9.3)
with ε, in velocity, against the continuation's tolerance) and the CPU seconds of the
solved steps. To compare with an earlier version of the solver, run the same command from
a git worktree of that commit (``PYTHONPATH`` set to its ``src``).

    .venv/bin/python benchmarks/hard_steps.py       # ~1 min
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import rockarch as ra
from rockarch.core.constants import GAP_TOL, MDOF_H_FACTOR
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof.contact_solver import PROX_TOL, law_residual
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion.signals import GroundMotion


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=2.5, help="seconds of the record")
    ap.add_argument("--ratio", type=float, default=2.0, help="PGA / ap,min")
    args = ap.parse_args()
    a = ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6).assembly
    m = graph_model(a)
    rec = ra.el_centro()
    n = int(args.seconds / (rec.t[1] - rec.t[0])) + 1
    mo = GroundMotion(rec.t[:n], rec.a[:n], name=rec.name).scaled(args.ratio * a.ap_min
                                                                  / rec.pga)
    step = gs.contact_step
    log = []
    residuals = []
    ipc = []

    def counted(*args_):
        ws = args_[-1]
        f0, p0 = ws.sw.state[2], ws.sw.state[7]
        i0, j0 = ws.sw.state[8], ws.sw.state[9]
        t0 = time.process_time()
        its = step(*args_)
        ipc.append((ws.sw.state[8] - i0, ws.sw.state[9] - j0))
        log.append((its, ws.sw.state[2] - f0, ws.sw.state[7] - p0, time.process_time() - t0))
        if ws.sw.state[7] > p0:  # the law's residual where the continuation ran
            nr = 3 * m.n0.shape[0] + 2 * ws.cnt[0]
            v = np.column_stack([args_[4], args_[5], args_[6]]).ravel()
            res = law_residual(nr, ws.rows, ws.bias, ws.lam, args_[10], args_[11], ws.sw, v)
            residuals.append((its < 0, res / args_[12]))
        return its

    h = MDOF_H_FACTOR / a.p_ref
    empty = (np.zeros(0), np.zeros((0, 1, 3)), np.zeros((0, 1), dtype=np.int8), np.zeros(0))
    gr.run.py_func(m, 1.0, mo.t, mo.a, 1.0, h, 2 * h, 2 * h, GAP_TOL, 0, *empty, False,
                   True)  # compiles the step's kernels before the count
    gr.contact_step = counted  # the compiled steps, counted one by one
    try:
        out = gr.run.py_func(m, 1.0, mo.t, mo.a, 1.0, h, mo.duration, mo.duration, GAP_TOL, 0,
                             *empty, False, True)
    finally:
        gr.contact_step = step
    arr = np.array(log)
    nf = arr[:, 1]
    prox = arr[:, 2] > 0
    print(f"wall 20x10 (205 blocks), first {args.seconds:g} s of El Centro at "
          f"{args.ratio:g}·ap,min: {out[6]} steps, {out[11]} at rest, {len(arr)} solved, "
          f"{int(prox.sum())} with the proximal continuation, {int((arr[:, 0] < 0).sum())} "
          f"failed; {out[3]} impacts, up to {out[4]} joints open")
    print(f"factorisations: {int(nf.sum())} ({nf.sum() / max(prox.sum(), 1):.0f} per step "
          f"with the proximal continuation); the 10 % costliest steps take "
          f"{np.sort(nf)[::-1][:max(len(nf) // 10, 1)].sum() / max(nf.sum(), 1):.0%}; "
          f"CPU {arr[:, 3].sum():.1f} s in the solved steps "
          f"({1e3 * arr[:, 3].sum() / max(nf.sum(), 1):.2f} ms per factorisation)")
    ipa = np.array(ipc)
    print(f"interior point: {int(ipa[:, 0].sum())} steps solved by it, {int(ipa[:, 1].sum())} "
          f"of its iterations (each a factorisation)")
    res = np.array(residuals).reshape(-1, 2)
    for label, sel in (("solved", res[:, 0] == 0), ("failed", res[:, 0] == 1)):
        if sel.any():
            r = res[sel, 1]
            print(f"the contact law's residual at the impulses of the {int(sel.sum())} {label} "
                  f"steps with the continuation: median {np.median(r):.3g}, largest "
                  f"{r.max():.3g} times tol_u, above {PROX_TOL:g} times tol_u (the "
                  f"continuation's tolerance on this wall) in {int((r > PROX_TOL).sum())}")


if __name__ == "__main__":
    main()
