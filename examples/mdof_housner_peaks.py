"""Moreau–Jean's extra dissipation at impacts on one rocking block (docs/mdof.md, "Housner's
r for one block").

The block of tests/mdof/test_mdof.py (p = 2 1/s, α = 0.2), a step pulse of 2·ap,min for
0.3 s, then 4 s of free rocking: the MDOF engine at three steps against ``block.py``
(Housner's equation, exact impacts). Prints, per step, the impacts and the change of the
peak of each excursion after an impact [%] (cumulative over the impacts before it).

Run:  .venv/bin/python examples/mdof_housner_peaks.py      (≈ 10 s)
"""

from __future__ import annotations

import numpy as np

from rockarch import mdof
from rockarch.motion import signals as motion
from rockarch.rocking import block


def main() -> None:
    alpha, p = 0.2, 2.0
    a = mdof.block_from_p_alpha(p, alpha)
    m = motion.step(2.0 * a.ap_min, 0.3)
    b = block.simulate(block.RigidBlock(p, alpha), m, t_free=4.0)
    edges = np.concatenate([b.impact_times, [b.t[-1]]])
    for hf in (0.01, 0.002, 0.0005):
        r = mdof.simulate(a, m, t_free=4.0, h_factor=hf)
        change = []
        for t0, t1 in zip(edges[:-1], edges[1:], strict=True):
            pk_b = np.abs(b.theta[(b.t > t0) & (b.t < t1)]).max()
            pk_r = np.abs(r.q[(r.t > t0) & (r.t < t1), 0, 2]).max()
            change.append(f"{100 * (pk_r / pk_b - 1):+.2f}")
        print(f"h·p = {hf:g}: {r.impacts} impacts; peaks after them: {', '.join(change)} %")


if __name__ == "__main__":
    main()
