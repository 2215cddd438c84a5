"""Benchmark: the sweep executor on a block OAS (issue 7 targets).

Run:  .venv/bin/python benchmarks/sweep.py          (about 1 min on 2 cores)

1. Throughput of 2 local worker processes vs 1 (target >= 1.8x).
2. Overhead of the Dask path (LocalCluster, 2 single-threaded worker processes on loopback)
   vs the process pool (2 workers) on a 200 x 200 block OAS (target <= 15 %).
3. For the record: numba threads in this process (the in-process path), same grid.

A 200 x 200 OAS of El Centro takes only ~1-2 s on 2 cores, too short to see an overhead
above timing noise, so the motion is El Centro 1940 played twice in a row (107 s of record,
a block that survives the first pass keeps rocking through the second) and every figure is
the best of 3 runs on an already started pool / cluster, the modes interleaved (the two
cores are shared: a burst of someone else's load then hits every mode alike); pool and
cluster start-up are timed separately. No store is used (every chunk is computed). The
maps of every mode are checked to be bit-identical.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from rockarch.core import sweep
from rockarch.motion.records import el_centro
from rockarch.motion.signals import GroundMotion
from rockarch.spectra.oas import compute_oas
from rockarch.systems import BlockSystem


def long_record(repeats: int) -> GroundMotion:
    """El Centro played ``repeats`` times back to back (uniform dt, continuous time)."""
    rec = el_centro()
    dt = float(rec.t[1] - rec.t[0])
    a = np.tile(rec.a, repeats)
    return GroundMotion(np.arange(a.size) * dt, a, f"El Centro x{repeats}")


def best_of(n: int, fn):
    times, out = [], None
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="grid size n x n (default 200)")
    ap.add_argument("--repeats", type=int, default=2, help="El Centro played this often")
    ap.add_argument("--runs", type=int, default=3, help="best of this many runs")
    args = ap.parse_args()

    motion = long_record(args.repeats)
    system = BlockSystem(alpha=0.2)
    p = np.linspace(0.5, 6.0, args.n)
    ratio = np.linspace(1.0, 6.0, args.n)
    n_sims = p.size * ratio.size
    compute_oas(system, motion, p[:2], ratio[:2], progress=False)  # JIT/cache load

    def oas(executor):
        return compute_oas(system, motion, p, ratio, progress=False, executor=executor)

    print(f"block OAS alpha=0.2, {motion.name} ({motion.duration:.0f} s), "
          f"{args.n} x {args.n} grid, 32 chunks, tol 1e-3; best of {args.runs}")
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores: > 0.5 means others "
          "are running and the figures are not clean)")
    results, starts = {}, {}
    with sweep.Executor("processes", workers=1) as one, \
            sweep.Executor("processes", workers=2) as two, \
            sweep.Executor(dask_workers=2) as dask:
        modes = {"1 process": one, "2 processes": two, "dask 2 workers": dask,
                 "in-process threads": None}
        for name, ex in modes.items():
            t0 = time.perf_counter()
            compute_oas(system, motion, p[:4], ratio[:3], progress=False, chunks=4,
                        executor=ex)  # start the pool / cluster and load the kernels
            starts[name] = time.perf_counter() - t0
        for _ in range(args.runs):  # interleaved: a burst of load hits every mode alike
            for name, ex in modes.items():
                t, ds = best_of(1, lambda ex=ex: oas(ex))
                if name not in results or t < results[name][0]:
                    results[name] = (t, ds)
    for name, (t, _) in results.items():
        start = f"; start-up {starts[name]:.2f} s" if modes[name] is not None else ""
        print(f"  {name:<22} {t:7.2f} s  ({n_sims / t:8.0f} grid sims/s{start})")
    print(f"load average after: {os.getloadavg()[0]:.2f}")

    ref = results["1 process"][1]
    for name, (_, ds) in results.items():
        assert ds.identical(ref), f"{name}: map differs"
    t1, t2, td = (results[k][0] for k in ("1 process", "2 processes", "dask 2 workers"))
    speedup = t1 / t2
    overhead = td / t2 - 1.0
    print(f"speed-up 2 processes / 1 process: {speedup:.2f}x  (target >= 1.8x) "
          f"{'OK' if speedup >= 1.8 else 'MISSED'}")
    print(f"Dask overhead vs process pool:    {100 * overhead:+.1f} %  (target <= 15 %) "
          f"{'OK' if overhead <= 0.15 else 'MISSED'}")
    print(f"in-process numba threads / 2 processes: "
          f"{results['in-process threads'][0] / t2:.2f}")
    print("all maps bit-identical")


if __name__ == "__main__":
    main()
