"""Static collapse of running-bond walls in rockarch's own time history, under the load
ramp of the pymunk scan (docs/validation.md, general assemblies).

    PYTHONPATH=src .venv/bin/python validation/wall_ramp.py

For the 4 x 3 and 4 x 10 walls of 0.4 x 0.2 m blocks without sliding (mu = inf, the limit
of Coulomb's cone: no shear without compression, docs/theory.md §9) the ground acceleration
f·g is ramped in over 0.5 s and held 2 s, in both directions, exactly as
validation/pymunk_wall_scan.py does in pymunk. One line per run: the largest centroid
displacement, stands (below 1e-4 of the wall's size, the pymunk scan's criterion) or moves,
and whether it collapses. The statics (Eq. 10.9) gives ap_min = 7/11 g for both walls.
"""

from __future__ import annotations

import numpy as np

from rockarch.mdof import builders as bd
from rockarch.mdof import simulate
from rockarch.motion.signals import GroundMotion

LOADS = (0.63, 0.7, 0.8, 0.85, 0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.45)


def run(wall, f: float, sign: float) -> tuple[float, bool]:
    """Largest centroid displacement [m] and collapse of one ramped run; sign +1: inertia to
    -x (ground acceleration +f·g)."""
    t = np.linspace(0.0, 2.5, 2501)
    acc = sign * f * wall.g * np.clip(t / 0.5, 0.0, 1.0)
    r = simulate(wall, GroundMotion(t, acc, f"ramp {f:g} g"), t_free=0.0)
    d = np.hypot(r.q[:, :, 0] - r.q[0, :, 0], r.q[:, :, 1] - r.q[0, :, 1]).max()
    return float(d), bool(r.overturned)


def main() -> None:
    for cols in (3, 10):
        wall = bd.wall(4, cols, 0.4, 0.2)
        print(f"wall 4 x {cols}: rockarch ap_min = {wall.ap_min / wall.g:.4f} g")
        for sign in (1.0, -1.0):
            for f in LOADS:
                d, collapsed = run(wall, f, sign)
                verdict = "collapses" if collapsed else (
                    "stands" if d < 1e-4 * wall.size else "moves, stops")
                print(f"  direction {sign:+.0f}  {f:.2f} g  largest displacement {d:.2e} m  "
                      f"{verdict}", flush=True)


if __name__ == "__main__":
    main()
