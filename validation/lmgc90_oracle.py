"""One LMGC90 run of a planar block assembly, in LMGC90's own virtual environment.

    .venv-lmgc90/bin/python validation/lmgc90_oracle.py CASE.json OUT.json

LMGC90 keeps one simulation per process (its Fortran state is global), so
validation/lmgc90_compare.py starts this script once per run and exchanges JSON. The case:
``polygons`` (blocks, 2-D, metres), ``supports`` (fixed polygons), ``mu`` (Coulomb friction
of the contact law IQS_CLB_g0: unilateral, inelastic, no dilatancy), ``dt``, ``duration``,
and either ``tilt`` (a static test: the whole assembly rotated by atan(lambda), gravity
vertical: a uniform horizontal ground acceleration lambda·g) or ``ground`` (times and
velocities [m/s] of the ground and supports, along x: a time history). Every 2-D polygon is
extruded to a prism of unit depth along y; the 2-D y axis is LMGC90's z (gravity -z). The
ground is a fixed slab under y = 0. Written: ``displacement`` (the largest centroid
displacement of a block over the run [m]), ``max_rotation`` (the largest |rotation| of a
block about y [rad]) and the history (time, block 0's centroid x and z, then every block's
rotation in the 2-D sense, counter-clockwise positive) every ``record`` steps.
"""

from __future__ import annotations

import json
import math
import sys

import numpy as np


def _prism(poly, depth: float = 1.0) -> dict:
    """Vertices and outward faces of the prism of a convex 2-D polygon (x, y) -> (x, 0..d, y)."""
    p = np.asarray(poly, dtype=float)
    if np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]) < 0:
        p = p[::-1]  # counter-clockwise in (x, y)
    n = len(p)
    front = [[x, 0.0, y] for x, y in p]
    back = [[x, depth, y] for x, y in p]
    # (x, y) counter-clockwise seen from +z... in 3-D (x, z) seen from -y is counter-clockwise
    faces = [list(range(n)), list(range(2 * n - 1, n - 1, -1))]
    faces += [[i, n + i, n + (i + 1) % n, (i + 1) % n] for i in range(n)]
    return {"vertices": front + back, "faces": faces}


def _rotate(poly, angle: float):
    c, s = math.cos(angle), math.sin(angle)
    return [[c * x - s * y, s * x + c * y] for x, y in poly]


def main() -> None:
    case = json.load(open(sys.argv[1]))
    from compas_lmgc90.solver import Solver

    blocks, supports = case["polygons"], case["supports"]
    pts = np.concatenate([np.asarray(b, float) for b in blocks + supports])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    size = float(max(hi - lo))
    slab = [[lo[0] - 2 * size, -0.5 * size], [hi[0] + 2 * size, -0.5 * size],
            [hi[0] + 2 * size, 0.0], [lo[0] - 2 * size, 0.0]]
    fixed = supports + [slab]
    angle = math.atan(case.get("tilt", 0.0))
    geo = [_prism(_rotate(p, angle)) for p in blocks + fixed]
    # the prism's own vertex order is (x, 0/1, y): front face normal is -y if the polygon is
    # counter-clockwise in (x, z) seen from +y; fix the winding by checking the volume sign
    for g in geo:
        v = np.asarray(g["vertices"])
        c = v.mean(axis=0)
        f0 = g["faces"][0]
        a, b, d = v[f0[0]], v[f0[1]], v[f0[2]]
        if np.dot(np.cross(b - a, d - a), a - c) < 0:
            g["faces"] = [list(reversed(f)) for f in g["faces"]]
    solver = Solver(dt=case["dt"], theta=0.5, density=case.get("density", 2000.0))
    solver.geometry_from_v_f(geo)
    nb = len(blocks)
    ground = case.get("ground")
    for i in range(nb, len(geo)):  # supports: every degree of freedom driven
        for comp in ("Vx", "Vy", "Vz", "Rx", "Ry", "Rz"):
            if ground is not None and comp == "Vx":
                solver.apply_velocity(i, comp, np.array([ground["t"], ground["v"]]))
            else:
                solver.apply_velocity(i, comp, 0.0)
    solver.contact_law("IQS_CLB_g0", float(case["mu"]), alert=case.get("alert", 1e-3))
    solver.preprocess()
    c0 = np.array([np.array(c, float) for c in solver.init_coor[:nb]])
    f0 = [np.array(f, float).copy() for f in solver.init_frame[:nb]]
    steps = int(round(case["duration"] / case["dt"]))
    record = int(case.get("record", 10))
    disp, rot, hist = 0.0, 0.0, []
    for k in range(steps):
        solver.run(nb_steps=1)
        res = solver.last_result
        c = np.array([np.array(res.bodies[i], float) for i in range(nb)])
        d = np.linalg.norm(c - c0, axis=1)
        angles = []
        for i in range(nb):
            fr = np.array(res.body_frames[i], float).reshape(3, 3)
            r = fr.T @ f0[i]
            angles.append(-math.atan2(r[0, 2], r[0, 0]))  # about -y: the 2-D sense
        disp, rot = max(disp, float(d.max())), max(rot, float(np.max(np.abs(angles))))
        if k % record == 0:
            hist.append([(k + 1) * case["dt"], float(c[0, 0] - c0[0, 0]),
                         float(c[0, 2] - c0[0, 2]), *angles])
        if disp > case.get("stop", math.inf):
            break
    json.dump({"displacement": disp, "max_rotation": rot, "history": hist,
               "steps": k + 1}, open(sys.argv[2], "w"))


if __name__ == "__main__":
    main()
