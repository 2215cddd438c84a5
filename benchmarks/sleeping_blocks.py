"""How many blocks of the moving tall wall move with the ground at each step (docs/performance.md,
"Blocks that move with the ground").

"Sleeping islands" would take the blocks that move with the ground (at rest relative to it)
out of the contact solve and treat them as part of the support until a load wakes them. The
idea pays only if, in the steps that cost (the violent and the slow phases of the record),
many blocks do move with the ground. This script runs the 205-block wall
``ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6)`` under the first
``--seconds`` of the bundled El Centro 180° record scaled to 2·ap,min, records every step,
and counts per step the bodies whose speed relative to the ground (the largest of |v| of the
centroid and |ω|·0.2 m, a block's smaller side) reaches a threshold, and the joints that
touch such a body (the rows a solve of the moving blocks alone would keep), per phase of
the record. The engine calls a structure at rest below 10⁻⁴·g·h ≈ 3·10⁻⁶ m/s (h the time
step); larger thresholds show what a looser, no longer exact, rest test would freeze.

    .venv/bin/python benchmarks/sleeping_blocks.py          # ~6 min (21 s of the record)
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import rockarch as ra
from rockarch import mdof
from rockarch.motion.signals import GroundMotion

THRESHOLDS = (3e-6, 3e-5, 3e-4, 3e-3)  # m/s
PHASES = ((2, 6), (6, 12), (12, 15), (15, 19), (19, 21))  # s of the record


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=21.0)
    args = ap.parse_args()
    a = ra.system("mdof", wall="20,10", block="0.4,0.2", friction=0.6).assembly
    rec = ra.el_centro()
    n = int(args.seconds / (rec.t[1] - rec.t[0])) + 1
    mo = GroundMotion(rec.t[:n], rec.a[:n], name=rec.name).scaled(2.0 * a.ap_min / rec.pga)
    t0 = time.process_time()
    r = mdof.simulate(a, mo, t_free=0.0, record_every=1)
    cpu = time.process_time() - t0
    ba, bb = np.asarray(a.body_a), np.asarray(a.body_b)
    nb, nj = r.q.shape[1], len(ba)
    dq = np.abs(np.diff(r.q, axis=0))
    step = np.diff(r.t)[:, None]
    speed = np.maximum(np.hypot(dq[:, :, 0], dq[:, :, 1]), 0.2 * dq[:, :, 2]) / step
    t = r.t[1:]
    print(f"wall 20x10 (205 blocks, {nb} bodies, {nj} joints), El Centro at 2·ap,min, first "
          f"{args.seconds:g} s: {t.size} steps, {cpu:.0f} s of CPU")
    print("bodies moving relative to the ground at or above the threshold (median over the "
          "phase's steps) / joints touching one")
    print("threshold [m/s] " + "".join(f"{f'{lo}-{hi} s':>14}" for lo, hi in PHASES))
    for thr in THRESHOLDS:
        moving = speed >= thr
        rows = np.zeros((t.size, nj), bool)
        for side in (ba, bb):
            ok = side >= 0
            rows[:, ok] |= moving[:, side[ok]]
        cells = []
        for lo, hi in PHASES:
            s = (t >= lo) & (t < hi)
            cells.append(f"{np.median(moving[s].sum(axis=1)):.0f} / "
                         f"{np.median(rows[s].sum(axis=1)):.0f}" if s.any() else "-")
        print(f"{thr:<16g}" + "".join(f"{c:>14}" for c in cells))


if __name__ == "__main__":
    main()
