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

    .venv/bin/python benchmarks/slow_steps.py        # ~25 min (the Python loop to 16.15 s)
"""

from __future__ import annotations

import argparse
import copy
import time

import numpy as np

import rockarch as ra
from rockarch.core.constants import GAP_TOL, MDOF_H_FACTOR
from rockarch.mdof import contact_solver as cs
from rockarch.mdof import graph_run as gr
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof.kernel_data import graph_model


def _replay(m, keep, iterations: int) -> tuple[str, int]:
    """The step's solve and its plain iterations from a copy of its inputs."""
    x, y, ph, vx, vy, om, gtol, hh, v_app, eps_n, eps_t, tol_u, tol_l, margin, ws = \
        copy.deepcopy(keep)
    nbod = m.mass.shape[0]
    nr = gs.contact_rows(m, x, y, ph, vx, vy, om, gtol, hh, v_app, margin, ws)
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--from", dest="t0", type=float, default=16.0, help="first second kept")
    ap.add_argument("--to", dest="t1", type=float, default=16.15, help="last second kept")
    ap.add_argument("--ratio", type=float, default=2.0, help="PGA / ap,min")
    ap.add_argument("--iterations", type=int, default=12, help="plain iterations traced")
    args = ap.parse_args()
    rec = ra.el_centro()
    if not 0.0 <= args.t0 < args.t1 <= rec.duration:
        ap.error(f"need 0 <= --from < --to <= {rec.duration:g} s (the record)")
    if args.iterations < 1 or args.ratio <= 0.0:
        ap.error("--iterations must be >= 1 and --ratio > 0")
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


if __name__ == "__main__":
    main()
