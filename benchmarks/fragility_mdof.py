"""Benchmark: fragility of a 20-voussoir MDOF arch (issue 15 target: 50 records of ~40 s in
<= 5 min on 2 cores, linear speed-up on a Dask cluster measured with 1 and 2 workers).

Run:  .venv/bin/python benchmarks/fragility_mdof.py [--records 50] [--repeat 1]
          [--variants dask1,dask2,proc2,inproc]

A circular arch (f/l = 0.5, d/l = 0.15, span 1 m scaled to its own p) over the first
``--records`` records of rockarch.motion.synthetic.synthetic_motions(50, seed=``--seed``) (seed
1: 15-88 s, mean 43 s), scanned over ``--ratio-steps`` values of ap/ap,min from 1 to 5
with bisection to ``--tol`` (``--island-step K``: the adaptive scan). Every record is one
task (its scan and bisection). Variants: a Dask LocalCluster of 1 and of 2 single-threaded
workers, 2 local processes, and the plain in-process run (numba threads, no executor) as
the reference. Every executor is started and its workers' kernels loaded before timing
(start-up printed apart); the variants are interleaved, ``--repeat`` rounds, best wall
time kept. For each run the CPU seconds of every worker process, of this process, and of
the whole machine (other jobs included) are read from /proc, so that a speed-up lost to
other jobs on the cores shows as such. Every run's collapse points are checked to be
identical.
"""

from __future__ import annotations

import argparse
import logging
import os
import time

import numpy as np
import psutil

import rockarch as ra
from rockarch.core import sweep
from rockarch.motion.synthetic import synthetic_motions
from rockarch.risk import fragility as fr


def _warm(system, motion, p):
    """Load the kernels in a worker and hold it for 1 s (so every worker gets one)."""
    system.run(motion, np.array([p]), np.array([1.0]))
    time.sleep(1.0)
    return os.getpid()


def start(label: str, system, motion, p):
    """(executor, worker pids, start-up seconds) of a variant, its kernels loaded."""
    t0 = time.perf_counter()
    if label == "inproc":
        return None, [], 0.0
    if label == "proc2":
        ex = sweep.Executor("processes", workers=2)
        pool = ex._ensure_pool()
        pids = {f.result() for f in [pool.submit(_warm, system, motion, p)
                                     for _ in range(4)]}
    else:
        ex = sweep.Executor(dask_workers=int(label[-1]))
        pids = set(ex._ensure_client().run(_warm, system, motion, p).values())
    return ex, sorted(pids), time.perf_counter() - t0


def _busy(c) -> float:
    """CPU seconds of a process's or of the machine's cpu_times (idle and iowait out)."""
    return c.user + c.system + sum(getattr(c, f, 0.0) for f in ("nice", "irq", "softirq",
                                                                "steal"))


def timed(ex, pids, system, motions, p, ratio, tol, island_step):
    """One run: (wall, [CPU s per worker], CPU s here, CPU s of the machine, result)."""
    procs = [psutil.Process(q) for q in pids]
    me = psutil.Process()
    w0 = [_busy(q.cpu_times()) for q in procs]
    m0, s0 = _busy(me.cpu_times()), _busy(psutil.cpu_times())
    t0 = time.perf_counter()
    res = fr.ida(system, motions, p, ratio=ratio, tol=tol, executor=ex,
                 island_step=island_step)
    wall = time.perf_counter() - t0
    w = [_busy(q.cpu_times()) - a for q, a in zip(procs, w0, strict=True)]
    return (wall, w, _busy(me.cpu_times()) - m0, _busy(psutil.cpu_times()) - s0, res)


NAMES = {"dask1": "Dask, 1 worker", "dask2": "Dask, 2 workers",
         "proc2": "2 local processes", "inproc": "in-process (reference)"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--records", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--blocks", type=int, default=20)
    ap.add_argument("--ratio-steps", type=int, default=17)
    ap.add_argument("--tol", type=float, default=0.01)
    ap.add_argument("--island-step", type=int, default=1,
                    help="1: every ratio; K > 1: the adaptive scan (fragility.ida)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--variants", default="dask1,dask2,proc2,inproc")
    args = ap.parse_args()
    # several LocalClusters in one process: the first to close would restore distributed's
    # INFO logging while the others still run (silence_logs is per cluster)
    logging.getLogger("distributed").setLevel(logging.ERROR)
    variants = args.variants.split(",")
    motions = synthetic_motions(50, seed=args.seed)[:args.records]
    sys_ = ra.system("mdof", shape="circular", rise_over_span=0.5, thickness_over_span=0.15,
                     blocks=args.blocks)
    p = sys_.p_ref
    ratio = np.round(np.linspace(1.0, 5.0, args.ratio_steps), 12)
    dur = np.array([m.duration for m in motions])
    print(f"{sys_.name} at its p = {p:.3f} 1/s; {len(motions)} synthetic records (seed "
          f"{args.seed}), {dur.min():.0f}-{dur.max():.0f} s, mean {dur.mean():.1f} s; "
          f"{ratio.size} ratios (island step {args.island_step}) + bisection to "
          f"{args.tol:g}; {os.cpu_count()} cores; "
          f"load average before: {os.getloadavg()[0]:.2f}")
    fr.ida(sys_, motions[:1], p, ratio=[1.0, 2.0], tol=0.5)  # compile / load numba caches
    started = {v: start(v, sys_, motions[0], p) for v in variants}
    runs: dict = {}
    try:
        for rnd in range(args.repeat):
            for v in variants:  # interleaved
                ex, pids = started[v][:2]
                run = timed(ex, pids, sys_, motions, p, ratio, args.tol, args.island_step)
                print(f"  round {rnd + 1} {NAMES[v]:<24} {run[0]:7.1f} s wall, workers "
                      + " ".join(f"{c:.1f}" for c in run[1]) + f" CPU s, here {run[2]:.1f},"
                      f" machine {run[3]:.1f} of {2 * run[0]:.1f} CPU s; load "
                      f"{os.getloadavg()[0]:.2f}", flush=True)
                if v not in runs or run[0] < runs[v][0]:
                    runs[v] = run
    finally:
        for ex, _, _ in started.values():
            if ex is not None:
                ex.close()
    first = next(iter(runs.values()))[4]
    for run in runs.values():
        assert np.array_equal(run[4].ratio_collapse, first.ratio_collapse, equal_nan=True)
        assert np.array_equal(run[4].overturned, first.overturned)
    print(f"collapse points identical in every run; {int(first.censored.sum())} censored; "
          f"load average after: {os.getloadavg()[0]:.2f}")
    print(f"best of {args.repeat}:")
    print("| variant | start-up [s] | wall [s] | CPU per worker [s] | CPU here [s] | "
          "machine busy / 2 cores x wall | min for 50 records |")
    print("|---|---|---|---|---|---|---|")
    for v, (wall, w, here, machine, _) in runs.items():
        print(f"| {NAMES[v]} | {started[v][2]:.1f} | {wall:.1f} | "
              f"{' / '.join(f'{c:.1f}' for c in w) or '-'} | {here:.1f} | "
              f"{machine / (2 * wall):.2f} | {wall / len(motions) * 50 / 60:.1f} |")
    if "dask1" in runs and "dask2" in runs:
        w1, w2 = runs["dask1"], runs["dask2"]
        print(f"Dask speed-up 1 -> 2 workers: wall {w1[0] / w2[0]:.2f}x (linear: 2); "
              f"CPU of the work {sum(w1[1]):.1f} s -> {sum(w2[1]):.1f} s; on free cores "
              f"(1 worker's CPU / the busiest of 2 workers' CPU) "
              f"{sum(w1[1]) / max(w2[1]):.2f}x")


if __name__ == "__main__":
    main()
