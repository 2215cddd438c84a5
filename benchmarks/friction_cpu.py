"""Friction against no sliding on the 20-voussoir chain, on CPU time (docs/performance.md).

Run:  .venv/bin/python benchmarks/friction_cpu.py

The case of benchmarks/mdof.py part 5 (catenary l = 10 m, f = 3 m, d = 0.25 m, N = 20, first
5 s of El Centro, ratios 1.0…2.0 in 6 steps): the chain stepper (no sliding, the plain
reference) and the general stepper with mu = 0.5 at every joint, each the best of 5 passes
over the 6 ratios on ``time.process_time``, alternated three times.
"""

from __future__ import annotations

import time

import numpy as np

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.mdof import builders as bd
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro


def cpu(asm, rec, ap_min, ratios) -> float:
    best = np.inf
    for _ in range(5):
        t0 = time.process_time()
        for r in ratios:
            mdof.simulate(asm, rec.scaled(r * ap_min / rec.pga), t_free=0.0)
        best = min(best, time.process_time() - t0)
    return best


def main() -> None:
    rec = el_centro()
    keep = rec.t <= 5.0
    rec = motion.GroundMotion(rec.t[keep], rec.a[keep], "El Centro (first 5 s)")
    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    af = bd.with_friction(a, 0.5)
    ratios = np.linspace(1.0, 2.0, 6)
    cpu(a, rec, a.ap_min, ratios)  # compile
    cpu(af, rec, a.ap_min, ratios)
    for _ in range(3):
        c, f = cpu(a, rec, a.ap_min, ratios), cpu(af, rec, a.ap_min, ratios)
        print(f"chain (no sliding) {1e3 * c:.0f} ms, friction mu = 0.5 {1e3 * f:.0f} ms: "
              f"{f / c:.2f}x", flush=True)


if __name__ == "__main__":
    main()
