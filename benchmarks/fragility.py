"""Benchmark: fragility of a block at one p over a synthetic suite (issue 15 target: 50
records of ~40 s in <= 10 s on 2 cores).

Run:  .venv/bin/python benchmarks/fragility.py [--records 50] [--p 2] [--workers 2]

The suite is rockarch.motion.synthetic.synthetic_motions(N, seed=0) (Rezaeian & Der Kiureghian
model; durations 13-84 s, mean ~37 s). Timed in the same run, best of ``--repeat``:

* reference: the plain loop a user writes without rockarch.risk.fragility: one
  ``rockarch.oas(block, record, p=[p], ratio=grid)`` per record (grid + bisection), then
  the lognormal fit;
* ``fragility`` in-process (numba threads on every core), the same simulations;
* ``fragility`` on a pool of ``--workers`` local processes (records in chunks, each
  bisection round of every record in parallel); pool start-up timed separately.

Every variant's collapse points are checked to be bit-identical to the reference's. No
store is used.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import rockarch as ra
from rockarch.core import sweep
from rockarch.motion.synthetic import synthetic_motions
from rockarch.risk import fragility as fr

GRID = np.round(np.linspace(1.0, 5.0, 81), 12)


def reference(sys_, motions, p):
    """One OAS per record at p (the plain loop), then the fit."""
    b = np.array([ra.oas(sys_, m, p=[p], ratio=GRID)["boundary"].values[0] for m in motions])
    ok = np.isfinite(b)
    fit = fr.fit_lognormal(b[ok] * sys_.ap_min, np.full((~ok).sum(), GRID[-1] * sys_.ap_min))
    return b, fit


def best_of(n, fn):
    """(best wall time, CPU time of this process in that run, result)."""
    best, out = None, None
    for _ in range(n):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        run = (time.perf_counter() - t0, time.process_time() - c0)
        best = run if best is None or run[0] < best[0] else best
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--records", type=int, default=50)
    ap.add_argument("--p", type=float, default=2.0)
    ap.add_argument("--alpha", type=float, default=0.1)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    motions = synthetic_motions(args.records, seed=0)
    dur = np.array([m.duration for m in motions])
    sys_ = ra.system("block", alpha=args.alpha)
    print(f"{len(motions)} synthetic records, duration {dur.min():.0f}-{dur.max():.0f} s "
          f"(mean {dur.mean():.1f} s); block alpha={args.alpha:g} at p={args.p:g}; "
          f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")
    fr.ida(sys_, motions[:1], args.p, ratio=GRID[:3])  # compile / load numba caches

    def ours(executor=None):
        return fr.fragility(sys_, motions, args.p, ratio=GRID, executor=executor,
                            n_bootstrap=200)

    t_ref, (b_ref, fit_ref) = best_of(args.repeat, lambda: reference(sys_, motions, args.p))
    t_in, f_in = best_of(args.repeat, ours)
    t0 = time.perf_counter()
    with sweep.Executor("processes", workers=args.workers) as ex:
        ex._ensure_pool().submit(int).result()
        t_start = time.perf_counter() - t0
        t_pool, f_pool = best_of(args.repeat, lambda: ours(ex))
    for f in (f_in, f_pool):
        assert np.array_equal(f.ida.ratio_collapse, b_ref, equal_nan=True)
    print(f"collapse points bit-identical; median {f_in.fit.median:.4g} m/s2, beta "
          f"{f_in.fit.beta:.3f} ({f_in.fit.n_censored} censored; reference fit "
          f"{fit_ref.median:.4g}, {fit_ref.beta:.3f})")
    print(f"{'variant':<44}{'wall [s]':>9}{'vs reference':>14}{'CPU here [s]':>14}")
    for name, (t, cpu) in (("reference: oas() per record", t_ref),
                           ("fragility, in-process (numba threads)", t_in),
                           (f"fragility, {args.workers} worker processes", t_pool)):
        print(f"{name:<44}{t:>9.2f}{t_ref[0] / t:>13.2f}x{cpu:>14.2f}")
    print(f"(pool start-up {t_start:.2f} s, not included; bootstrap 200 resamples included; "
          "CPU of the worker processes is not counted in 'CPU here')")


if __name__ == "__main__":
    main()
