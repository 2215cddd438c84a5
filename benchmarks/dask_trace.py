"""Diagnosis: where the time of an MDOF IDA goes on a Dask LocalCluster (task stream per
worker, CPU seconds per worker process, of this process and of the whole machine).

Run:  .venv/bin/python benchmarks/dask_trace.py [--records 6] [--seed 0] [--workers 1,2]

The 20-voussoir circular arch of benchmarks/fragility_mdof.py at its p over the first
``--records`` synthetic records, 17 ratios and bisection to 0.01, on a LocalCluster of each
``--workers`` count (kernels loaded in every worker first). For each worker: its tasks as
"start+duration" in seconds from the first task (distributed.get_task_stream), the time
it spent in tasks, and its CPU seconds; a worker whose CPU seconds fall short of its time
in tasks was waiting for a core (other jobs), a worker whose time in tasks falls short of
the wall time was idle (barriers, imbalance).
"""

from __future__ import annotations

import argparse
import logging
import os
import time

import numpy as np
import psutil
from distributed import get_task_stream

import rockarch as ra
from rockarch.core import sweep
from rockarch.motion.synthetic import synthetic_motions
from rockarch.risk import fragility as fr


def _load(system, motion, p):
    system.run(motion, np.array([p]), np.array([1.0]))
    return os.getpid()


def _cpu(c) -> float:
    return c.user + c.system + sum(getattr(c, f, 0.0) for f in ("nice", "irq", "softirq",
                                                                "steal"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--records", type=int, default=6)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--workers", default="1,2")
    args = ap.parse_args()
    # several LocalClusters in one process: the first to close would restore distributed's
    # INFO logging while the others still run (silence_logs is per cluster)
    logging.getLogger("distributed").setLevel(logging.ERROR)
    motions = synthetic_motions(50, seed=args.seed)[:args.records]
    arch = ra.system("mdof", shape="circular", rise_over_span=0.5, thickness_over_span=0.15,
                     blocks=20)
    p, ratio = arch.p_ref, np.round(np.linspace(1.0, 5.0, 17), 12)
    fr.ida(arch, motions[:1], p, ratio=[1.0, 2.0], tol=0.5)
    for n in (int(w) for w in args.workers.split(",")):
        with sweep.Executor(dask_workers=n) as ex:
            client = ex._ensure_client()
            pids = client.run(_load, arch, motions[0], p)
            procs = {a: psutil.Process(q) for a, q in pids.items()}
            cpu0 = {a: _cpu(q.cpu_times()) for a, q in procs.items()}
            here0, m0 = _cpu(psutil.Process().cpu_times()), _cpu(psutil.cpu_times())
            with get_task_stream(client) as ts:
                t0 = time.perf_counter()
                fr.ida(arch, motions, p, ratio=ratio, tol=0.01, executor=ex)
                wall = time.perf_counter() - t0
            here = _cpu(psutil.Process().cpu_times()) - here0
            machine = _cpu(psutil.cpu_times()) - m0
            print(f"== {n} worker(s): wall {wall:.1f} s; CPU here {here:.1f} s; machine "
                  f"{machine:.1f} of {(os.cpu_count() or 1) * wall:.1f} CPU s; load "
                  f"{os.getloadavg()[0]:.2f}")
            spans = [(d["worker"], s["start"], s["stop"]) for d in ts.data
                     for s in d["startstops"] if s["action"] == "compute"]
            start = min(s for _, s, _ in spans)
            for a, q in procs.items():
                mine = sorted((s - start, e - s) for w, s, e in spans if w == a)
                busy = sum(d for _, d in mine)
                print(f"  worker {a}: {len(mine)} tasks, {busy:.1f} s in tasks, CPU "
                      f"{_cpu(q.cpu_times()) - cpu0[a]:.1f} s: "
                      + " ".join(f"{s:.1f}+{d:.2f}" for s, d in mine))


if __name__ == "__main__":
    main()
