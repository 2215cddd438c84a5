"""Benchmark: the MDOF model against its targets and a plain reference.

Run:  .venv/bin/python benchmarks/mdof.py                 (≈ 5–8 min on 2 cores)
      .venv/bin/python benchmarks/mdof.py friction graphs (only parts 5 and 6; "chain": 1)

1. one simulation of a 20-voussoir catenary arch (l = 10 m, f = 3 m, d = 0.25 m) on the first
   5 s of El Centro 1940 (PGA = ratio·ap,min, ratio 1.0…2.0, no free time), with history:
   median per simulation (target ≤ 50 ms);
2. a 50 × 50 MDOF OAS of that arch under a sine pulse (T = 1 s) with boundary bisection,
   wall time on all cores (target ≤ 3 min);
3. cost scaling with N = 10, 20, 40, 80 voussoirs (the case of 1);
4. reference: the single block (p = 2, alpha = 0.2) on the same 5 s by the MDOF kernel and
   by scipy's solve_ivp on Housner's equation with events (benchmarks/block_oas.py), same
   runs, same verdicts;
5. friction: the case of 1 with mu = 0.5 (and mu = 1000, no joint can slide) against the
   frictionless chain stepper in the same run (target: ≤ 2x);
6. general contact graphs, El Centro at 0.5·ap,min (the structure stays up): a two-span
   bridge on piers and walls of 14, 42 and 205 blocks over 5 s (target for 200 blocks: 5 s
   in ≤ 2 s), as run (steps at rest not solved again, docs/theory.md Eq. (9.11)) and with
   every step solved (the plain reference); µs per solved step and per step and block, against
   pymunk (the test oracle's model, tests/validation/pymunk_oracle.py: dt = 2e-4 s,
   60 iterations) on the same structures over 0.5 s. Every graph runs on the exact contact
   solve (docs/theory.md Eqs. (9.7)–(9.9)); "band" is its half-bandwidth in bodies.
"""

from __future__ import annotations

import math
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from rockarch import mdof, systems
from rockarch.arch import catenary
from rockarch.mdof import builders as bd
from rockarch.mdof.kernel_data import graph_model
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro
from rockarch.rocking.block import housner_restitution
from rockarch.spectra import oas as spectra

sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(1, str(Path(__file__).parent.parent))
from block_oas import reference_simulation  # noqa: E402


def first_seconds(rec, seconds):
    keep = rec.t <= seconds
    return motion.GroundMotion(rec.t[keep], rec.a[keep], f"{rec.name} (first {seconds:g} s)")


def time_runs(assembly, rec, ratios, reps=3):
    times, steps, over = [], [], []
    for r in ratios:
        m = rec.scaled(r * assembly.ap_min / rec.pga)
        best = math.inf
        for _ in range(reps):
            t0 = time.perf_counter()
            res = mdof.simulate(assembly, m, t_free=0.0)
            best = min(best, time.perf_counter() - t0)
        times.append(best)
        steps.append(res.steps)
        over.append(res.overturned)
    return np.array(times), np.array(steps), np.array(over)


def friction(rec, arch) -> None:
    a20 = mdof.arch_assembly(arch, 20)
    ratios = np.linspace(1.0, 2.0, 6)
    mdof.simulate(bd.with_friction(a20, 0.5), rec.scaled(0.5), t_free=0.0)  # JIT
    t0, st0, _ = time_runs(a20, rec, ratios)
    print("5. friction, the case of 1 (ratios 1.0…2.0, best of 3, same run):")
    print("| joints | median per simulation [ms] | µs per step | vs no friction |")
    print("|---|---|---|---|")
    print(f"| no sliding (chain stepper) | {1e3 * np.median(t0):.1f} | "
          f"{1e6 * np.sum(t0) / np.sum(st0):.1f} | 1 |")
    for mu in (1e3, 0.5):
        a = bd.with_friction(a20, mu)
        a = replace(a, ap_min=a20.ap_min)  # the same motions as the reference
        t, st, _ = time_runs(a, rec, ratios)
        print(f"| mu = {mu:g} | {1e3 * np.median(t):.1f} | {1e6 * np.sum(t) / np.sum(st):.1f}"
              f" | {np.median(t / t0):.2f}x |")


def pymunk_us_per_step(a, seconds=0.5):
    try:
        from tests.validation import pymunk_oracle as po
    except ImportError:  # pymunk is a test-only dependency
        return math.nan
    dt = 2e-4
    t0 = time.perf_counter()
    po.run(a, lambda t: 0.5 * a.ap_min * math.sin(2 * math.pi * t), seconds, dt=dt)
    return 1e6 * (time.perf_counter() - t0) / round(seconds / dt)


def graphs(rec) -> None:
    cases = [("2-span bridge on piers (N = 10 per span)", 5.0,
              bd.bridge(catenary(10.0, 3.0, 0.25), 10, spans=2, pier_height=3.0,
                        pier_width=1.0)),
             ("wall 4 x 3 (mu = 0.6)", 5.0, bd.wall(4, 3, 0.4, 0.2, mu=0.6)),
             ("wall 4 x 10 (mu = 0.6)", 5.0, bd.wall(4, 10, 0.4, 0.2, mu=0.6)),
             ("wall 10 x 20 (mu = 0.6)", 5.0, bd.wall(10, 20, 0.4, 0.2, mu=0.6))]
    print("6. general contact graphs, El Centro at 0.5·ap,min (one run each; load average "
          f"{os.getloadavg()[0]:.2f}):")
    print("| structure | blocks | joints | solver | seconds of motion | run [s] | steps | "
          "steps at rest | every step solved [s] | µs per solved step | "
          "µs per solved step and block | pymunk µs per step | pymunk µs per step and block | "
          "failed steps |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, seconds, a in cases:
        m = first_seconds(rec, seconds).scaled(0.5 * a.ap_min / rec.pga)
        mdof.simulate(a, first_seconds(rec, 0.01), t_free=0.0)  # JIT
        t0 = time.perf_counter()
        r = mdof.simulate(a, m, t_free=0.0)
        wall = time.perf_counter() - t0
        t0 = time.perf_counter()
        r0 = mdof.simulate(a, m, t_free=0.0, skip_rest=False)  # the plain reference
        wall0 = time.perf_counter() - t0
        us = 1e6 * wall0 / r0.steps
        pm = pymunk_us_per_step(a)
        solver = f"Newton, band {graph_model(a).kbody}"
        print(f"| {name} | {a.n_blocks} | {a.n_joints} | {solver} | {seconds:g} | {wall:.2f} "
              f"| {r.steps} | {r.steps_at_rest} | {wall0:.2f} "
              f"| {us:.0f} | {us / a.n_blocks:.1f} | {pm:.0f} | {pm / a.n_blocks:.1f} | "
              f"{r.lcp_failures} |")


def chain(rec, arch) -> None:
    """Part 1: the 20-voussoir chain, one simulation with history."""
    ratios = np.linspace(1.0, 2.0, 11)
    a20 = mdof.arch_assembly(arch, 20)
    mdof.simulate(a20, rec.scaled(0.5), t_free=0.0)  # JIT / cache load
    t, st, ov = time_runs(a20, rec, ratios)
    print(f"{a20.name}: p = {a20.p_ref:.4f} 1/s, ap,min = {a20.ap_min:.4f} m/s²")
    print(f"1. one simulation, 5 s of El Centro, ratio 1.0…2.0 (with history, best of 3): "
          f"median {1e3 * np.median(t):.1f} ms, max {1e3 * t.max():.1f} ms "
          f"(target <= 50 ms median); {ov.sum()}/{ov.size} collapse; "
          f"{1e6 * np.sum(t) / np.sum(st):.1f} µs per step")


def main() -> None:
    rec = first_seconds(el_centro(), 5.0)
    arch = catenary(10.0, 3.0, 0.25)
    only = set(sys.argv[1:])
    if only:
        if "chain" in only:
            chain(rec, arch)
        if "friction" in only:
            friction(rec, arch)
        if "graphs" in only:
            graphs(rec)
        return
    chain(rec, arch)
    ratios = np.linspace(1.0, 2.0, 11)

    sysm = systems.MDOFSystem(mdof.arch_assembly(catenary(1.0, 0.3, 0.025), 20))
    p = np.linspace(0.5, 10.0, 50)
    rr = np.linspace(1.0, 8.0, 50)
    t0 = time.perf_counter()
    ds = spectra.compute_oas(sysm, motion.sine(1.0, 1.0), p, rr, progress=False)
    wall = time.perf_counter() - t0
    print(f"2. 50 x 50 MDOF OAS (f/l = 0.3, d/l = 0.025, N = 20), sine T = 1 s, + bisection: "
          f"{wall:.1f} s wall (target <= 180 s); {int(ds.overturned.sum())} of 2500 cells "
          "collapse")

    print("3. scaling with N (case 1, median over the ratios):")
    print("| N | median per simulation [ms] | µs per step | µs per step and joint |")
    print("|---|---|---|---|")
    for n in (10, 20, 40, 80):
        an = mdof.arch_assembly(arch, n)
        t, st, _ = time_runs(an, rec, ratios, reps=2)
        us = 1e6 * np.sum(t) / np.sum(st)
        print(f"| {n} | {1e3 * np.median(t):.1f} | {us:.1f} | {us / (n + 1):.2f} |")

    blk = mdof.block_from_p_alpha(2.0, 0.2)
    r = housner_restitution(0.2)
    ratios_b = np.linspace(1.5, 4.0, 6)
    t_m, t_r, agree = [], [], 0
    for ratio in ratios_b:
        m = rec.scaled(ratio * blk.ap_min / rec.pga)
        t0 = time.perf_counter()
        res = mdof.simulate(blk, m, t_free=0.0)
        t_m.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        ov_ref, _ = reference_simulation(m.t, m.a / 9.81, 2.0, 0.2, r, t_free=0.0)
        t_r.append(time.perf_counter() - t0)
        agree += ov_ref == res.overturned
    t_m, t_r = np.median(t_m), np.median(t_r)
    print(f"4. single block (p = 2, alpha = 0.2), 5 s of El Centro, {ratios_b.size} ratios: "
          f"MDOF kernel {1e3 * t_m:.2f} ms, solve_ivp reference {1e3 * t_r:.1f} ms "
          f"(median): {t_r / t_m:.0f}x; same verdict in {agree}/{ratios_b.size}")
    friction(rec, arch)
    graphs(rec)


if __name__ == "__main__":
    main()
