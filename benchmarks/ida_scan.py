"""Benchmark: the adaptive IDA scan (``fragility.ida(..., island_step=K)``) against the full
scan: simulations and CPU saved, safe islands missed, collapse points (must be identical).

Run:  .venv/bin/python benchmarks/ida_scan.py [--steps 2,4,8] [--mdof-records 10]

* blocks (alpha, p) = (0.1, 2), (0.2, 1), (0.15, 3) over the 50 synthetic records of
  seed 1 and both El Centro components, the default grid (81 ratios 1 ... 5, tol 1e-3),
  the grid alone (no search below its first collapse: ``search_step=0``);
* the 20-voussoir circular arch of benchmarks/fragility_mdof.py at its p over every 5th of
  the 50 synthetic records of seed 1, 17 ratios 1 ... 5, tol 0.01.

In this process (numba threads); CPU seconds of this process (all its threads) per scan.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import rockarch as ra
from rockarch.motion.synthetic import synthetic_motions
from rockarch.risk import fragility as fr


def compare(label, system, motions, p, steps, **kw):
    """Full scan, then each island step: identical collapse points, what it saves."""
    c0 = time.process_time()
    full = fr.ida(system, motions, p, **kw)
    cpu_full = time.process_time() - c0
    print(f"{label}: full scan {full.evaluated.sum()} grid simulations, "
          f"{cpu_full:.1f} CPU s, {full.resurrections.sum()} safe islands "
          f"({(full.resurrections > 0).sum()} of {len(motions)} records)")
    for k in steps:
        c0 = time.process_time()
        res = fr.ida(system, motions, p, island_step=k, **kw)
        cpu = time.process_time() - c0
        assert np.array_equal(res.ratio_collapse, full.ratio_collapse, equal_nan=True)
        ev = res.evaluated
        assert np.array_equal(res.overturned[ev], full.overturned[ev])
        print(f"  island step {k}: {ev.sum()} grid simulations ({ev.sum() / ev.size:.0%}), "
              f"CPU {cpu / cpu_full:.2f} of the full scan; islands found "
              f"{res.resurrections.sum()} of {full.resurrections.sum()} (records missing "
              f"one: {(res.resurrections < full.resurrections).sum()}); collapse points "
              "identical", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", default="2,4,8")
    ap.add_argument("--mdof-records", type=int, default=10)
    ap.add_argument("--no-block", action="store_true")
    args = ap.parse_args()
    steps = [int(k) for k in args.steps.split(",")]
    suite = synthetic_motions(50, seed=1)
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    if not args.no_block:
        motions = suite + [ra.el_centro(180), ra.el_centro(270)]
        for alpha, p in ((0.1, 2.0), (0.2, 1.0), (0.15, 3.0)):
            compare(f"block alpha={alpha:g} p={p:g}, {len(motions)} records",
                    ra.system("block", alpha=alpha), motions, p, steps, search_step=0)
    if args.mdof_records:
        arch = ra.system("mdof", shape="circular", rise_over_span=0.5,
                         thickness_over_span=0.15, blocks=20)
        motions = suite[::5][:args.mdof_records]
        fr.ida(arch, motions[:1], arch.p_ref, ratio=[1.0, 2.0], tol=0.5)  # load kernels
        compare(f"{arch.name} p={arch.p_ref:.3f}, {len(motions)} records", arch, motions,
                arch.p_ref, steps, ratio=np.round(np.linspace(1.0, 5.0, 17), 12), tol=0.01)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
