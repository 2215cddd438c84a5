"""One MDOF chain simulation, timed the same way at any commit (docs/performance.md, MDOF).

Run:  .venv/bin/python benchmarks/chain_one.py
      (at another commit: git worktree add /tmp/old COMMIT, then from /tmp/old
       PYTHONPATH=src NUMBA_CACHE_DIR=/tmp/nb_old /work/main/.venv/bin/python
       /work/main/benchmarks/chain_one.py)

The 20-voussoir catenary arch (l = 10 m, f = 3 m, d = 0.25 m) on the first 5 s of El Centro
at 1.5·ap,min, with history: min and median of 7 calls of ``mdof.simulate`` after one to
compile. The plain reference is the same call at an older commit, in the same session.
"""

from __future__ import annotations

import statistics
import time

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro


def main() -> None:
    rec = el_centro()
    keep = rec.t <= 5.0
    rec = motion.GroundMotion(rec.t[keep], rec.a[keep], "El Centro (first 5 s)")
    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    m = rec.scaled(1.5 * a.ap_min / rec.pga)
    mdof.simulate(a, m, t_free=0.0)
    ts = []
    for _ in range(7):
        t0 = time.perf_counter()
        mdof.simulate(a, m, t_free=0.0)
        ts.append(time.perf_counter() - t0)
    print(f"chain N = 20, 5 s of El Centro at 1.5 ap,min: min {1e3 * min(ts):.1f} ms, "
          f"median {1e3 * statistics.median(ts):.1f} ms")


if __name__ == "__main__":
    main()
