"""Static collapse of running-bond walls without sliding in pymunk, over load, direction and
solver iterations (docs/validation.md, general assemblies).

    PYTHONPATH=src .venv/bin/python validation/pymunk_wall_scan.py

For the 4 x 3 and 4 x 10 walls of 0.4 x 0.2 m blocks (rockarch: ap_min = 7/11 g, Eq.
(10.9) of docs/theory.md; the associative LP alone 1.5 g and 5 g; rockarch's own time
history under the same ramp: validation/wall_ramp.py) the ground
acceleration f·g is ramped in over 0.5 s and held 2 s, in both directions, with pymunk's
contact solver at 60 (the oracle's default) and 300 iterations. One line per run: stands
(largest centroid displacement below 1e-4 of the size) or collapses, and the blocks that
moved first with the load at that moment. Needs pymunk (the test extra).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from rockarch.mdof import builders as bd  # noqa: E402
from tests.validation import pymunk_oracle as po  # noqa: E402

LOADS = (0.63, 0.7, 0.8, 0.9, 0.95, 0.99, 1.01)


def run(wall, f: float, sign: float, iterations: int, dt: float = 2e-4) -> str:
    """One ramped run; sign +1: inertia to -x (rockarch's direction +1)."""
    space, bodies = po.build(wall, iterations=iterations, dt=dt)
    x0 = np.array([tuple(b.position) for b in bodies])
    names, first, d = wall.info["block_names"], None, np.zeros(len(bodies))
    for k in range(int(round(2.5 / dt))):
        load = f * min(k * dt / 0.5, 1.0)
        space.gravity = (-sign * load * wall.g, -wall.g)
        space.step(dt)
        if k % 50 == 0:
            x = np.array([tuple(b.position) for b in bodies])
            d = np.hypot(*(x - x0).T)
            if first is None and d.max() > 1e-3:
                moved = [names[i].split(" (")[1].rstrip(")") for i in np.argsort(-d)[:4]]
                first = f"first moving at {load:.3f} g: " + "; ".join(moved)
    if d.max() < 1e-4 * wall.size:
        return "stands"
    return "collapses" + (f" ({first})" if first else "")


def main() -> None:
    for cols in (3, 10):
        wall = bd.wall(4, cols, 0.4, 0.2)
        print(f"wall 4 x {cols}: rockarch ap_min = {wall.ap_min / wall.g:.4f} g")
        for iterations in (60, 300):
            for sign in (1.0, -1.0):
                for f in LOADS:
                    print(f"  iterations {iterations:3d}  direction {sign:+.0f}  {f:.2f} g  "
                          f"{run(wall, f, sign, iterations)}", flush=True)


if __name__ == "__main__":
    main()
