"""Benchmark: fragility of a 20-voussoir MDOF arch (issue 15 target: 50 records of ~40 s in
<= 5 min on 2 cores, linear speed-up on a Dask cluster measured with 1 and 2 workers).

Run:  .venv/bin/python benchmarks/fragility_mdof.py [--records 10] [--ratio-steps 17]

A circular arch (f/l = 0.5, d/l = 0.15, span 1 m scaled to its own p) over the first
``--records`` records of rockarch.synthetic.synthetic_motions(50, seed=0), scanned over
``--ratio-steps`` values of ap/ap,min from 1 to 5 with bisection to ``--tol``; timed on
a local Dask cluster of 1 and of 2 single-threaded workers and on 2 local processes; the
time for 50 records is extrapolated linearly (records are independent chunks). Every run's
collapse points are checked to be identical.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import rockarch as ra
from rockarch import fragility as fr
from rockarch import sweep
from rockarch.synthetic import synthetic_motions


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--records", type=int, default=10)
    ap.add_argument("--blocks", type=int, default=20)
    ap.add_argument("--ratio-steps", type=int, default=17)
    ap.add_argument("--tol", type=float, default=0.01)
    args = ap.parse_args()
    motions = synthetic_motions(50, seed=0)[:args.records]
    sys_ = ra.system("mdof", shape="circular", rise_over_span=0.5, thickness_over_span=0.15,
                     blocks=args.blocks)
    p = sys_.p_ref
    ratio = np.round(np.linspace(1.0, 5.0, args.ratio_steps), 12)
    dur = np.mean([m.duration for m in motions])
    print(f"{sys_.name} at its p = {p:.3f} 1/s; {len(motions)} synthetic records (mean "
          f"{dur:.1f} s); {ratio.size} ratios + bisection to {args.tol:g}; "
          f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")
    fr.ida(sys_, motions[:1], p, ratio=[1.0, 2.0], tol=0.5)  # compile / load numba caches
    runs = {}
    for label, make in (("2 local processes", lambda: sweep.Executor("processes",
                                                                       workers=2)),
                        ("Dask, 1 worker", lambda: sweep.Executor(dask_workers=1)),
                        ("Dask, 2 workers", lambda: sweep.Executor(dask_workers=2))):
        with make() as ex:
            # start the pool / cluster and load the kernels in every worker (4 chunks)
            fr.ida(sys_, motions[:4], p, ratio=[1.0, 1.5], tol=0.0, executor=ex)
            t0 = time.perf_counter()
            res = fr.ida(sys_, motions, p, ratio=ratio, tol=args.tol, executor=ex)
            runs[label] = (time.perf_counter() - t0, res)
    first = next(iter(runs.values()))[1]
    for _, res in runs.values():
        assert np.array_equal(res.ratio_collapse, first.ratio_collapse, equal_nan=True)
    print(f"collapse points identical in every run; {int(first.censored.sum())} censored")
    print(f"{'executor':<20}{'wall [s]':>10}{'per record [s]':>16}{'50 records [min]':>18}")
    for label, (t, _) in runs.items():
        print(f"{label:<20}{t:>10.1f}{t / len(motions):>16.2f}"
              f"{t / len(motions) * 50 / 60:>18.1f}")
    t1, t2 = runs["Dask, 1 worker"][0], runs["Dask, 2 workers"][0]
    print(f"Dask speed-up 1 -> 2 workers: {t1 / t2:.2f}x (linear: 2)")


if __name__ == "__main__":
    main()
