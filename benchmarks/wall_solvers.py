"""Benchmark: the wide-graph contact solve (rest path + Gauss–Seidel) on running-bond walls.

Run:  .venv/bin/python benchmarks/wall_solvers.py          (≈ 3–6 min on 2 cores)

1. accuracy: a 42-block wall (4 x 10, mu = 0.6, half-bandwidth 38) under sine pulses
   (T = 0.5 s) of 1.5…4·ap,min plus 1 s of free motion, on the default solver of wide graphs
   (the rest path of docs/theory.md Eq. (9.7), Gauss–Seidel where it does not apply) and on
   the exact banded solve (Eq. (9.4)) forced on the same model: largest slip, largest
   rotation / delta, verdict, failed steps, steps on the rest path, run time;
2. cost: the 205-block wall (10 x 20) on the first 5 s of El Centro at 0.5, 0.75 and 1·ap,min
   (the default solver): run time, steps, steps on the rest path, failed steps, and the chain
   stepper's 20-voussoir arch on the same record in the same run as the plain reference;
3. where no solver is accurate: a tall 45-block wall (10 x 4) rocking and sliding under
   El Centro at 1.5·ap,min (+ 1 s free) on the default solver and on the banded solve, with
   CPU times (``python benchmarks/wall_solvers.py tall`` runs only this part).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.mdof import builders as bd
from rockarch.mdof import graph_run
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro


def run(model, a, m, t_end):
    """One graph_run.run of the model on motion m (m/s²): summary and wall time."""
    h = 0.005 / a.p_ref
    t0 = time.perf_counter()
    out = graph_run.run(model, 1.0, m.t, m.a, 1.0, h, t_end, m.duration, 1e-4, 0, np.zeros(0),
                        np.zeros((0, 1, 3)), np.zeros((0, 1), np.int8), np.zeros(0))
    return out, time.perf_counter() - t0


def accuracy() -> None:
    a = bd.wall(4, 10, 0.4, 0.2, mu=0.6)
    wide = graph_model(a)
    exact = wide._replace(banded=True)
    print(f"1. {a.name}: {a.n_blocks} blocks, kd = {wide.kd}; sine T = 0.5 s + 1 s free")
    print("| PGA / ap,min | solver | max slip [m] | max rot / delta | collapse | failed steps "
          "| rest-path steps | steps | run [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for ratio in (1.5, 2.0, 3.0, 4.0):
        m = motion.sine(ratio * a.ap_min, 0.5)
        for name, model in (("rest + Gauss–Seidel", wide), ("banded (exact)", exact)):
            run(model, a, m, 0.01)  # JIT / cache load
            out, wall = run(model, a, m, m.duration + 1.0)
            print(f"| {ratio:g} | {name} | {out[8]:.5g} | {out[2]:.4g} | {bool(out[0])} | "
                  f"{out[7]} | {out[10]} | {out[6]} | {wall:.2f} |")


def el_centro_5s() -> motion.GroundMotion:
    rec = el_centro()
    keep = rec.t <= 5.0
    return motion.GroundMotion(rec.t[keep], rec.a[keep], "El Centro (first 5 s)")


def cost() -> None:
    rec = el_centro_5s()
    a = bd.wall(10, 20, 0.4, 0.2, mu=0.6)
    model = graph_model(a)
    arch = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    mdof.simulate(arch, rec.scaled(0.5), t_free=0.0)  # JIT
    t0 = time.perf_counter()
    mdof.simulate(arch, rec.scaled(1.5 * arch.ap_min / rec.pga), t_free=0.0)
    ref = time.perf_counter() - t0
    print(f"2. {a.name}: {a.n_blocks} blocks, {a.n_joints} joints, 5 s of El Centro; "
          f"load average {os.getloadavg()[0]:.2f}; reference: 20-voussoir arch "
          f"(chain stepper, 1.5·ap,min) {1e3 * ref:.1f} ms")
    print("| PGA / ap,min | run [s] | steps | rest-path steps | failed steps | max slip [m] "
          "| max rot / delta | collapse |")
    print("|---|---|---|---|---|---|---|---|")
    run(model, a, rec.scaled(0.01), 0.01)  # JIT / cache load
    for ratio in (0.5, 0.75, 1.0):
        m = rec.scaled(ratio * a.ap_min / rec.pga)
        out, wall = run(model, a, m, m.duration)
        print(f"| {ratio:g} | {wall:.2f} | {out[6]} | {out[10]} | {out[7]} | {out[8]:.3g} | "
              f"{out[2]:.3g} | {bool(out[0])} |")


def tall() -> None:
    rec = el_centro_5s()
    a = bd.wall(10, 4, 0.4, 0.2, mu=0.6)
    m = rec.scaled(1.5 * a.ap_min / rec.pga)
    print(f"3. {a.name}: {a.n_blocks} blocks, El Centro at 1.5·ap,min + 1 s free")
    print("| solver | CPU [s] | steps | failed steps | rest-path steps | max slip [m] "
          "| max rot / delta |")
    print("|---|---|---|---|---|---|---|")
    for name, banded in (("rest + Gauss–Seidel", False), ("banded (exact)", True)):
        model = graph_model(a)._replace(banded=banded)
        run(model, a, m, 0.01)  # JIT / cache load
        c0 = time.process_time()
        out, _ = run(model, a, m, m.duration + 1.0)
        print(f"| {name} | {time.process_time() - c0:.1f} | {out[6]} | {out[7]} | {out[10]} | "
              f"{out[8]:.4g} | {out[2]:.4g} |")


if __name__ == "__main__":
    if sys.argv[1:] == ["tall"]:
        tall()
    else:
        accuracy()
        cost()
        tall()
