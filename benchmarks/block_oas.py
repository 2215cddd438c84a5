"""Benchmark: block OAS of El Centro 1940 (RSN6, 180°), rockarch vs scipy.integrate.solve_ivp.

Run:  .venv/bin/python benchmarks/block_oas.py            (≈ 3–5 min on 2 cores)
      .venv/bin/python benchmarks/block_oas.py --full --jobs 2   (solve_ivp on all 10 000
      cells, about 40 min on 2 cores)

The reference is what a user would otherwise write: Housner's exact equation integrated by
``solve_ivp`` (RK45, rtol 1e-9, atol 1e-12, max_step = record dt) with terminal events for
impact (theta = 0) and overturning (|theta| = alpha), restarted after every impact with
theta' -> r·theta', the same uplift rule and the same chatter (settling) criterion as
rockarch (without one, the reference does not finish on a record). Both run one thread per
simulation; the per-simulation times are compared on the same cells, and so are the maps.
"""

from __future__ import annotations

import argparse
import math
import resource
import time
from concurrent.futures import ProcessPoolExecutor

import numba
import numpy as np
from scipy.integrate import solve_ivp

from rockarch.core.constants import EPS_REST, T_FREE
from rockarch.core.constants import SDOF_H_FACTOR as H_FACTOR
from rockarch.motion.records import el_centro
from rockarch.rocking import kernels as rocking_kernels
from rockarch.rocking.block import RigidBlock, housner_restitution, simulate_batch
from rockarch.spectra.oas import compute_oas
from rockarch.systems import BlockSystem


def reference_simulation(t_k, a_k, p, alpha, r, t_free=T_FREE, eps_rest=EPS_REST):
    """Housner block with solve_ivp; a_k in units of g. Returns (overturned, n_impacts)."""
    amin = math.tan(alpha)
    t_end = t_k[-1] + t_free

    def ag(t):
        return np.interp(t, t_k, a_k, right=0.0)

    def rhs(t, y, s):
        x = s * alpha - y[0]
        return [y[1], -p * p * (math.sin(x) - ag(t) * math.cos(x))]

    def hit_zero(t, y, s):
        return y[0]

    def hit_alpha(t, y, s):
        return abs(y[0]) - alpha

    hit_zero.terminal = True
    hit_alpha.terminal = True
    t, th, om, s, n_imp, resting = 0.0, 0.0, 0.0, 0.0, 0, True
    while t < t_end:
        if resting:
            if t >= t_k[-1]:
                return False, n_imp
            # first knot interval after t in which |a_g| exceeds amin (a_g linear)
            k = max(int(np.searchsorted(t_k, t, side="right")) - 1, 0)
            found = False
            while k < t_k.size - 1:
                t0, t1 = max(t_k[k], t), t_k[k + 1]
                a0, a1 = ag(t0), a_k[k + 1]
                if abs(a0) > amin:
                    t, s, found = t0, math.copysign(1.0, a0), True
                    break
                if abs(a1) > amin:
                    lev = math.copysign(amin, a1)
                    t = t0 + (lev - a0) / (a1 - a0) * (t1 - t0)
                    s, found = math.copysign(1.0, a1), True
                    break
                k += 1
            if not found:
                return False, n_imp
            th, om, resting = 0.0, 0.0, False
        hit_zero.direction = -s
        sol = solve_ivp(rhs, (t, t_end), [th, om], args=(s,), method="RK45", rtol=1e-9,
                        atol=1e-12, max_step=t_k[1] - t_k[0], events=(hit_zero, hit_alpha),
                        first_step=1e-6)
        if sol.status == 1 and sol.t_events[1].size:
            return True, n_imp
        if sol.status == 1 and sol.t_events[0].size:
            t = float(sol.t_events[0][0])
            om = r * float(sol.y_events[0][0][1])
            th, s = 0.0, -s
            n_imp += 1
            x = s * alpha
            acc = -p * p * (math.sin(x) - ag(t) * math.cos(x))
            if s * acc <= 0.0 and (om * om <= 2 * eps_rest * alpha * abs(acc) or om == 0.0):
                resting, om, s = True, 0.0, 0.0
            continue
        return False, n_imp
    return False, n_imp


def _timed_reference(job):
    t1 = time.perf_counter()
    ov, _ = reference_simulation(*job)
    return ov, time.perf_counter() - t1


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100, help="grid size n x n (default 100)")
    ap.add_argument("--sample", type=int, default=150,
                    help="cells simulated with solve_ivp (default 150)")
    ap.add_argument("--full", action="store_true", help="solve_ivp on every cell")
    ap.add_argument("--alpha", type=float, default=0.1)
    ap.add_argument("--jobs", type=int, default=1,
                    help="processes for the solve_ivp reference (timings stay per process)")
    args = ap.parse_args()

    rec = el_centro()
    unit = rec.normalized()
    alpha = args.alpha
    r = housner_restitution(alpha)
    p = np.linspace(0.5, 10.0, args.n)
    ratio = np.linspace(1.0, 5.0, args.n)
    system = BlockSystem(alpha=alpha)
    print(f"record: {rec.name}, {rec.duration:.1f} s + {T_FREE:.0f} s free rocking")
    print(f"cores: {numba.config.NUMBA_NUM_THREADS}, grid {args.n} x {args.n}, alpha={alpha}")

    compute_oas(system, rec, p[:2], ratio[:2], progress=False)  # JIT warm-up
    t0 = time.perf_counter()
    ds = compute_oas(system, rec, p, ratio, progress=False)
    wall = time.perf_counter() - t0
    print(f"rockarch {args.n}x{args.n} OAS (+boundary bisection): {wall:.2f} s wall")
    p2 = np.linspace(0.5, 10.0, 200)
    r2 = np.linspace(1.0, 5.0, 200)
    t0 = time.perf_counter()
    compute_oas(system, rec, p2, r2, progress=False)
    wall2 = time.perf_counter() - t0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"rockarch 200x200 OAS: {wall2:.2f} s wall (target <= 20 s); "
          f"peak RSS of this process so far {rss:.0f} MB (target < 500 MB)")

    # single-thread time per simulation, cell by cell
    tk, ak = np.ascontiguousarray(unit.t), np.ascontiguousarray(unit.a)
    d = np.zeros(1)
    model, prm, tab, amin, level, e = RigidBlock(1.0, alpha).kernel_args()
    pp, rr = np.meshgrid(p, ratio, indexing="ij")
    cells = np.arange(pp.size)
    if not args.full:
        cells = np.random.default_rng(1).choice(pp.size, size=min(args.sample, pp.size),
                                                replace=False)
    fast_t, full_len = [], []
    for c in range(pp.size):
        best = math.inf
        for _ in range(3):  # best of 3: the OS adds ms-scale jitter to single runs
            t1 = time.perf_counter()
            steps = 2 * int(rocking_kernels.check_steps(tk, T_FREE, pp.flat[c], H_FACTOR)) + 1000
            st, _, _, _, _, t_end, _ = rocking_kernels.run(
                tk, ak, rr.flat[c] * math.tan(alpha), model, pp.flat[c] ** 2, pp.flat[c],
                prm, tab, amin, level, e, T_FREE, H_FACTOR, EPS_REST, 0.0, 0.0, False,
                steps, d, d, d, d)
            best = min(best, time.perf_counter() - t1)
        fast_t.append(best)
        if st == 0 and t_end >= rec.duration:
            full_len.append(best)
    fast_t = np.array(fast_t)
    print(f"rockarch per simulation (1 thread, best of 3, all {pp.size} cells): median "
          f"{np.median(fast_t) * 1e3:.3f} ms, p99 {np.percentile(fast_t, 99) * 1e3:.3f} ms, "
          f"max {fast_t.max() * 1e3:.3f} ms")
    if full_len:
        fl = np.array(full_len)
        print(f"  runs that last the whole {rec.duration:.0f} s record (+ free rocking): "
              f"{fl.size}, median {np.median(fl) * 1e3:.3f} ms (target <= 1 ms), max/median "
              f"{fl.max() / np.median(fl):.1f}")
    imps = simulate_batch(RigidBlock(1.0, alpha), rec, pp, rr).impacts
    print(f"  impacts per simulation: median {int(np.median(imps))}, max {int(imps.max())}")

    a_g = np.ascontiguousarray(unit.a)
    jobs = [(tk, a_g * rr.flat[c] * math.tan(alpha), pp.flat[c], alpha, r) for c in cells]
    ref_t, ref_ov = [], []
    t_start = time.perf_counter()
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for j, (ov, dt) in enumerate(pool.map(_timed_reference, jobs, chunksize=4)):
            ref_t.append(dt)
            ref_ov.append(ov)
            if (j + 1) % 250 == 0 or j + 1 == len(jobs):
                print(f"  solve_ivp: {j + 1}/{cells.size} cells, "
                      f"{time.perf_counter() - t_start:.0f} s", flush=True)
    agree = np.array(ref_ov) == ds.overturned.values.flat[cells]
    ref_t = np.array(ref_t)
    sub = fast_t[cells]
    print(f"solve_ivp per simulation ({cells.size} cells): median "
          f"{np.median(ref_t) * 1e3:.1f} ms, mean {ref_t.mean() * 1e3:.1f} ms")
    print(f"same cells, rockarch: median {np.median(sub) * 1e3:.3f} ms, "
          f"mean {sub.mean() * 1e3:.3f} ms")
    print(f"speed-up: median/median {np.median(ref_t) / np.median(sub):.0f}x, "
          f"total/total {ref_t.sum() / sub.sum():.0f}x (target >= 500x)")
    print(f"same overturning verdict in {100 * np.mean(agree):.2f} % of the "
          f"{cells.size} cells (target >= 99 %)")


if __name__ == "__main__":
    main()
