"""The tall running-bond wall under the whole El Centro record: at rest, moving, and pymunk.

Issue 23's measurement (docs/performance.md, "Walls at real scale"): the 205-block wall
``ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6)`` (20 courses of 10
blocks, 4 m tall) under the bundled El Centro 180° record (53.7 s) and 2 s of free motion,
at 0.5·ap,min (it rests on the moving ground) and at 2·ap,min (it rocks and slides), timed
in CPU seconds in one process; pymunk on the same wall, at its 2e-4 s step, for the first
``--pymunk-seconds`` of the moving record (its per-step cost times the steps of the whole
record is the reference: a full pymunk run takes minutes).

    .venv/bin/python benchmarks/walls.py --ratios 0.5    # ~1 min: the wall at rest
    .venv/bin/python benchmarks/walls.py                 # > 45 min: the moving run too
    .venv/bin/python benchmarks/walls.py --ratios 2      # the moving run only
    .venv/bin/python benchmarks/walls.py --wall 4,10 --ratios 0.5,1.5,3,5 --every-step
                                                         # ~2 min: the rest shortcut

``--every-step`` also runs each ratio with every step solved (``skip_rest=False``: the
plain reference of the rest shortcut, docs/theory.md Eq. (9.11)) and prints the ratio.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

import rockarch as ra
from rockarch import mdof

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def _cpu(fn):
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


def pymunk_cpu_per_step(assembly, motion, seconds: float, dt: float = 2e-4) -> float:
    """pymunk's CPU seconds per step on the assembly under the first ``seconds`` of the
    motion (tests/validation/pymunk_oracle.py builds the same blocks)."""
    from tests.validation import pymunk_oracle as po

    space, _ = po.build(assembly, dt=dt)
    n = int(round(seconds / dt))
    t0 = time.process_time()
    for k in range(n):
        space.gravity = (-float(motion(k * dt)), -assembly.g)
        space.step(dt)
    return (time.process_time() - t0) / n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ratios", default="0.5,2", help="PGA / ap,min of the runs")
    ap.add_argument("--t-free", type=float, default=2.0)
    ap.add_argument("--pymunk-seconds", type=float, default=1.0)
    ap.add_argument("--wall", default="20,10", help="courses,blocks per course")
    ap.add_argument("--every-step", action="store_true",
                    help="also solve every step (no rest shortcut) and print the ratio")
    args = ap.parse_args()
    sysobj, build = _cpu(lambda: ra.system("mdof", wall=args.wall, block="0.4,0.2",
                                           friction=0.6))
    a = sysobj.assembly
    rec = ra.el_centro()
    print(f"wall {args.wall.replace(',', 'x')} blocks 0.4x0.2 m, mu = 0.6: {a.n_blocks} blocks, "
          f"{a.n_joints} joints, "
          f"ap,min = {a.ap_min / a.g:.4f} g, p = {a.p_ref:.4f} 1/s; statics {build:.1f} s CPU")
    mdof.simulate(a, rec.scaled(0.01), t_free=0.0, record_every=1000)  # compiled once
    runs = {}
    for ratio in map(float, args.ratios.split(",")):
        m = rec.scaled(ratio * a.ap_min / rec.pga)
        r, cpu = _cpu(lambda m=m: mdof.simulate(a, m, t_free=args.t_free, record_every=100))
        runs[ratio] = (r, cpu)
        print(f"ratio {ratio:g}: {cpu:.1f} s CPU, {r.steps} steps ({1e3 * cpu / r.steps:.2f} ms "
              f"each), failed steps {r.lcp_failures}, overturned {r.overturned}, impacts "
              f"{r.impacts}, most joints open {r.open_joints_max}, largest slip "
              f"{r.max_slip:.4g} m, new contacts {r.new_contacts_max}, steps at rest "
              f"{r.steps_at_rest}", flush=True)
        if args.every_step:
            r0, cpu0 = _cpu(lambda m=m: mdof.simulate(a, m, t_free=args.t_free,
                                                      record_every=100, skip_rest=False))
            print(f"  every step solved: {cpu0:.1f} s CPU ({1e3 * cpu0 / r0.steps:.2f} ms each),"
                  f" overturned {r0.overturned}, largest slip {r0.max_slip:.4g} m; the rest "
                  f"shortcut is {cpu0 / cpu:.1f}x faster", flush=True)
    if len(runs) >= 2:
        (lo, (_, c_lo)), (hi, (_, c_hi)) = min(runs.items()), max(runs.items())
        print(f"moving ({hi:g}) / at rest ({lo:g}): {c_hi / c_lo:.2f}x")
    hi = max(runs)
    m = rec.scaled(hi * a.ap_min / rec.pga)
    per = pymunk_cpu_per_step(a, m, args.pymunk_seconds)
    full = per * (rec.duration + args.t_free) / 2e-4
    print(f"pymunk: {1e3 * per:.2f} ms CPU per 2e-4 s step over the first "
          f"{args.pymunk_seconds:g} s at ratio {hi:g}: {full:.0f} s for the whole record; "
          f"rockarch {full / runs[hi][1]:.1f}x faster")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
