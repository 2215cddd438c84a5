"""Benchmark of the statics of general assemblies: associative LP (Eq. 10.4 of
docs/theory.md) against the non-associative analysis (Eqs. 10.6-10.9), per structure.

Usage::

    .venv/bin/python benchmarks/assembly_statics.py

Prints the load average, then per structure the median wall time (3 runs) of
``mdof.collapse(a, friction="associative")`` (the plain reference) and of
``mdof.collapse(a)`` (both directions each), with the ap_min of both; then the whole build
of the two 205-block walls with mu = 0.6 (``ra.system``: the analyses with and without
sliding, both directions, one run each: wall time and CPU time of this process, converged
or not), without the statics store.

``--breakdown`` then runs the tall wall's four analyses once more, one after the other,
under cProfile with the process CPU clock: CPU seconds per analysis and the LPs it took,
and over all four the time inside HiGHS' warm-started solves (highspy), inside scipy's
``linprog`` (the associative LPs and the macro-block checks); and, before them and
without the profiler (whose overhead per Python call would inflate it), the cluster
enumeration of Eq. (10.9) that they share.
"""

from __future__ import annotations

import cProfile
import os
import pstats
import statistics
import sys
import time
import warnings

import numpy as np

import rockarch as ra
from rockarch import mdof
from rockarch.arch import catenary
from rockarch.mdof import builders as bd
from rockarch.mdof import macroblock, statics


def median_time(fn, repeat: int = 3) -> tuple[float, object]:
    out = fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def main() -> None:
    print("load average (1, 5, 15 min): {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    cases = {
        "block against a support, mu 0.5": bd.from_polygons(
            [[[0, 0], [0.4, 0], [0.4, 1], [0, 1]]],
            supports=[[[0.4, 0], [1.4, 0], [1.4, 2], [0.4, 2]]], mu=0.5),
        "arch N=10 on 3 x 1.5 m piers": bd.bridge(catenary(10.0, 3.0, 0.25), 10,
                                                   pier_height=3.0, pier_width=1.5),
        "wall 4 x 3, no sliding": bd.wall(4, 3, 0.4, 0.2),
        "wall 4 x 10, no sliding": bd.wall(4, 10, 0.4, 0.2),
    }
    for name, a in cases.items():
        t_a, ca = median_time(lambda a=a: mdof.collapse(a, friction="associative"))
        t_n, cn = median_time(lambda a=a: mdof.collapse(a))
        print(f"{name:34s} associative {t_a * 1e3:8.1f} ms ({ca.ap_min / a.g:.4f} g)   "
              f"non-associative {t_n * 1e3:8.1f} ms ({cn.ap_min / a.g:.4f} g)")
    for wall in ("10,20", "20,10"):
        t0, c0 = time.perf_counter(), time.process_time()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            a = ra.system("mdof", wall=wall, block="0.4,0.2", friction=0.6).assembly
        wall_s, cpu_s = time.perf_counter() - t0, time.process_time() - c0
        conv = "not converged" if caught else "converged"
        print(f"wall {wall} ({a.n_blocks} blocks), mu 0.6: build {wall_s:.1f} s "
              f"({cpu_s:.1f} s CPU), ap_min {a.ap_min / a.g:.4f} g, without sliding "
              f"{a.info['ap_min_no_sliding'] / a.g:.4f} g, {conv}", flush=True)
    if "--breakdown" in sys.argv[1:]:  # the last wall built: the tall one
        breakdown(a)


def breakdown(a) -> None:
    """Where the statics of assembly ``a`` spend their CPU time (see the module text)."""
    args = (a.mass, a.inertia, a.centroid, a.corners, a.normal, a.body_a, a.body_b)
    macroblock._CACHE.clear()  # the build filled it: enumerate again, without the profiler
    c0 = time.process_time()
    macroblock.clusters(args[2:7], float(np.ptp(a.corners.reshape(-1, 2), axis=0).max()))
    total = clusters = time.process_time() - c0  # the analyses below reuse them
    prof = cProfile.Profile(time.process_time)
    for mu in (a.mu, None):
        for d in (1, -1):
            c0 = time.process_time()
            prof.enable()
            c = statics.limit_analysis(*args, mu, g=a.g, direction=d)
            prof.disable()
            cpu = time.process_time() - c0
            total += cpu
            print(f"  {'mu 0.6' if mu is not None else 'no sliding'}, direction {d:+d}: "
                  f"{cpu:.2f} s CPU, {c.iterations} LPs, ap_min {c.lambda_:.4f} g")
    stats = pstats.Stats(prof).stats  # {(file, line, name): (cc, nc, tottime, cumtime, ..)}

    def own(name: str) -> float:  # time inside a built-in
        return sum(v[2] for k, v in stats.items() if k[2] == name)

    print(f"  all {total:.2f} s CPU (profiled): HiGHS warm-started "
          f"{own('<built-in method highspy._core.run>'):.2f} s, scipy linprog "
          f"{own('<built-in method scipy.optimize._highspy._core.run>'):.2f} s, "
          f"clusters of Eq. (10.9) {clusters:.2f} s (not profiled)")


if __name__ == "__main__":
    main()
