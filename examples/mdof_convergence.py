"""Convergence study of the MDOF model (docs/mdof.md): time step, contact tolerance, N.

Share of the cells of an OAS map (catenary f/l = 0.3, d/l = 0.025, 20 voussoirs; p = 0.5…10,
ratio 1…6) that change under refinement; sine, square and step pulses, T = 1 s.

Run:  .venv/bin/python examples/mdof_convergence.py      (≈ 2 min on 2 cores)
"""

from __future__ import annotations

import numpy as np

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.motion import signals as motion
from rockarch.rocking.fourhinge_motion import fourhinge_mechanism


def main() -> None:
    arch = catenary(1.0, 0.3, 0.025)
    fh = fourhinge_mechanism(arch)
    a20 = mdof.arch_assembly(arch, 20)
    p = np.linspace(0.5, 10.0, 20)
    ratio = np.linspace(1.0, 6.0, 26)
    pp, rr = np.meshgrid(p, ratio, indexing="ij")
    print("| signal | h·p 0.01 vs 0.005 | 0.005 vs 0.0025 | gap_tol 1e-4 vs 1e-6 | "
          "N 10 vs 20 | N 20 vs 40 | N 40 vs 80 |")
    print("|---|---|---|---|---|---|---|")
    for sig in ("sine", "square", "step"):
        m = motion.pulse(sig, period=1.0)

        def run(a=a20, m=m, **kw):
            return mdof.simulate_batch(a, m, pp, rr, ap_min=fh.ap_min, p_ref=fh.p,
                                       **kw).overturned

        h1, h2, h3 = (run(h_factor=h) for h in (0.01, 0.005, 0.0025))
        g6 = run(gap_tol=1e-6)
        ns = {n: run(mdof.arch_assembly(arch, n)) for n in (10, 40, 80)}
        ns[20] = h2

        def pct(x, y):
            return f"{100 * np.mean(x != y):.1f} %"

        print(f"| {sig} | {pct(h1, h2)} | {pct(h2, h3)} | {pct(h2, g6)} | "
              f"{pct(ns[10], ns[20])} | {pct(ns[20], ns[40])} | {pct(ns[40], ns[80])} |")


if __name__ == "__main__":
    main()
