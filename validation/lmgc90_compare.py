"""rockarch's statics and one time history against LMGC90 (docs/validation.md, "LMGC90").

    .venv/bin/python validation/lmgc90_compare.py [--python .venv-lmgc90/bin/python] [--quick]

LMGC90 (the reference contact-dynamics code for masonry; compas-lmgc90 0.1.11, its own
virtual environment made by `make validate`) runs one case per process
(validation/lmgc90_oracle.py). Statics: the assembly tilted by atan(lambda) under vertical
gravity (a uniform horizontal ground acceleration lambda·g in rockarch's collapse
direction); "stands" = the largest centroid displacement stays below 1 mm over 1.5 s at
dt = 1e-3 s; bisection on lambda to 0.4 % from a bracket around rockarch's ap_min. Contact
law IQS_CLB_g0 (unilateral, inelastic, Coulomb without dilatancy). The same convex polygons
go to both codes (an arch's voussoirs as the quadrilaterals of their joint corners).
Time histories: a 0.4 x 1 m block under a one-cycle sine pulse of its ground (LMGC90: the
supports driven at the ground velocity), the largest rotation and the verdict; a thick
catenary arch of 12 voussoirs, every voussoir's rotation until rockarch's collapse.
Prints one line per case; exits 0 (a comparison, not a test).
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rockarch.arch import catenary, voussoirs
from rockarch.mdof import builders as bd
from rockarch.mdof import simulate
from rockarch.motion.signals import pulse

ORACLE = Path(__file__).with_name("lmgc90_oracle.py")
RECT = [[0, 0], [0.4, 0], [0.4, 1], [0, 1]]


def _quads_of_bridge(arch, n, pier_height, pier_width):
    b = bd.bridge(arch, n, pier_height=pier_height, pier_width=pier_width)
    v = voussoirs(arch, n)
    piers = [np.asarray(p).tolist() for p in b.polygons if len(p) <= 6]
    off = np.asarray(b.polygons[len(piers)][0]) - v.intrados[0]  # where bridge() put the arch
    return piers + _quads(v, off)


def _quads(v, offset) -> list:
    """The voussoirs ``v`` as the quadrilaterals of their joint corners, moved by
    ``offset``."""
    ip, ep = v.intrados + offset, v.extrados + offset
    return [np.array([ip[i], ip[i + 1], ep[i + 1], ep[i]]).tolist()
            for i in range(len(ip) - 1)]


def cases(quick: bool) -> list[tuple[str, list, list, float]]:
    """(name, polygons, supports, mu)."""
    out = [("block 0.4 x 1, mu 0.6", [RECT], [], 0.6),
           ("block 0.4 x 1, mu 0.3 (slides)", [RECT], [], 0.3),
           ("stack of 3 (0.6/0.45/0.3 x 0.5), mu 0.6",
            [[[-0.3, 0], [0.3, 0], [0.3, 0.5], [-0.3, 0.5]],
             [[-0.225, 0.5], [0.225, 0.5], [0.225, 1.0], [-0.225, 1.0]],
             [[-0.15, 1.0], [0.15, 1.0], [0.15, 1.5], [-0.15, 1.5]]], [], 0.6)]
    beside = [[[-0.4, 0], [0, 0], [0, 0.5], [-0.4, 0.5]]]
    out += [(f"block beside a support, mu {mu:g}", [RECT], beside, mu)
            for mu in (0.5, 2.0, 10.0)]
    wall = _polys(bd.wall(4, 3, 0.4, 0.2))
    out += [(f"wall 4 x 3, mu {mu:g}", wall, [], mu) for mu in (0.6, 2.0, 10.0)]
    if not quick:
        out.append(("arch N=10 on 3 x 1.5 m piers (quads), mu 0.6",
                    _quads_of_bridge(catenary(10.0, 3.0, 0.25), 10, 3.0, 1.5), [], 0.6))
        # cases added on 2026-11-29 after the code they check was written (a check of
        # geometries the statics had not been tuned on)
        out += [
            ("trilithon, columns 0.3 x 1.8, clear span 1.2, lintel 0.3, mu 0.6",
             _polys(bd.colonnade(2, 0.3, 1.8, 1.2, 0.3)), [], 0.6),
            ("colonnade, 3 columns of 2 drums 0.3 x 0.75, lintel 0.25, mu 0.5",
             _polys(bd.colonnade(3, 0.3, 1.5, 1.0, 0.25, drums=2)), [], 0.5),
            ("0.4 x 0.8 block on a 0.6 x 0.6 block, mu 0.2 (slides)",
             [[[-0.3, 0], [0.3, 0], [0.3, 0.6], [-0.3, 0.6]],
              [[-0.2, 0.6], [0.2, 0.6], [0.2, 1.4], [-0.2, 1.4]]], [], 0.2),
            ("trapezoid block, base 0.6, top 0.3, height 1, mu 0.6",
             [[[0, 0], [0.6, 0], [0.45, 1.0], [0.15, 1.0]]], [], 0.6),
            ("wall 3 x 2, 0.4 x 0.3 blocks, mu 0.8", _polys(bd.wall(3, 2, 0.4, 0.3)), [], 0.8),
            ("wall 5 x 4, 0.3 x 0.15 blocks, mu 0.5", _polys(bd.wall(5, 4, 0.3, 0.15)), [],
             0.5),
            ("blocks 0.3 x 1 and 0.3 x 0.8 side by side, mu 0.7",
             [[[0, 0], [0.3, 0], [0.3, 1], [0, 1]], [[0.3, 0], [0.6, 0], [0.6, 0.8], [0.3, 0.8]]],
             [], 0.7),
            # held-out walls checked 2026-11-30 (docs/assemblies.md, "Several solutions"):
            # LMGC90 stands above rockarch's end wedge already at ordinary friction
            ("wall 4 x 4, 0.25 x 0.25 blocks, mu 0.65", _polys(bd.wall(4, 4, 0.25, 0.25)), [],
             0.65),
            ("wall 3 x 3, 0.3 x 0.4 blocks, mu 0.8", _polys(bd.wall(3, 3, 0.3, 0.4)), [], 0.8)]
    return out


def _polys(a) -> list:
    return [np.asarray(p).tolist() for p in a.polygons]


def _run(python: str, case: dict) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        cin, cout = Path(tmp) / "case.json", Path(tmp) / "out.json"
        cin.write_text(json.dumps(case))
        subprocess.run([python, str(ORACLE), str(cin), str(cout)], check=True, cwd=tmp,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return json.loads(cout.read_text())


def stands(python: str, polys, supports, mu: float, lam: float) -> bool:
    """LMGC90: the assembly tilted by atan(lam) stands (centroids move < 1 mm in 1.5 s)."""
    out = _run(python, {"polygons": polys, "supports": supports, "mu": mu, "dt": 1e-3,
                        "duration": 1.5, "tilt": lam, "stop": 2e-3})
    return out["displacement"] < 1e-3


def bisect(python: str, polys, supports, mu: float, guess: float, sign: int,
           rel: float = 4e-3) -> tuple[float, float, int]:
    """Bracket [lo, hi] of LMGC90's collapse multiplier (lo stands, hi does not)."""
    lo, hi, runs = 0.8 * guess, 1.25 * guess, 0
    while not stands(python, polys, supports, mu, sign * lo):
        lo, runs = lo * 0.8, runs + 1
    while stands(python, polys, supports, mu, sign * hi):
        hi, runs = hi * 1.25, runs + 1
    runs += 2
    while hi - lo > rel * lo:
        mid = 0.5 * (lo + hi)
        runs += 1
        if stands(python, polys, supports, mu, sign * mid):
            lo = mid
        else:
            hi = mid
    return lo, hi, runs


def _ground_velocity(gm, t_free: float) -> dict:
    """The ground's velocity [m/s] at the pulse's knots (the integral of its acceleration),
    held for ``t_free`` after it."""
    t = np.asarray(gm.t, float)
    acc = np.asarray(gm.a, float)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * np.diff(t))])
    return {"t": np.concatenate([t, [t[-1] + t_free]]).tolist(),
            "v": np.concatenate([v, [v[-1]]]).tolist()}


def thick_arch() -> tuple[list, list]:
    """The thick catenary arch of ``validation/siconos_compare.py --more`` (l = 8, f = 3,
    d = 0.3 m, N = 12) with quadrilateral voussoirs (LMGC90 takes convex polygons), 0.6 m
    up on two fixed supports under its springings: (voussoirs, supports)."""
    v = voussoirs(catenary(8.0, 3.0, 0.3), 12)
    ip, ep = v.intrados + [0.0, 0.6], v.extrados + [0.0, 0.6]
    left = [ep[0], [ep[0][0], 0.0], [ip[0][0], 0.0], ip[0]]
    right = [ip[-1], [ip[-1][0], 0.0], [ep[-1][0], 0.0], ep[-1]]
    return _quads(v, [0.0, 0.6]), [np.asarray(q).tolist() for q in (left, right)]


def arch_history(python: str) -> None:
    """Every voussoir's rotation of the thick arch (:func:`thick_arch`, mu 0.5) under a
    sine pulse of 1.3 ap,min, T = 0.8 s, until rockarch's collapse: rockarch at its default
    step against LMGC90 at dt = 1e-3 and 5e-4 s."""
    quads, sups = thick_arch()
    a = bd.from_polygons(quads, supports=sups, mu=0.5)
    gm = pulse("sine", period=0.8, ap=1.3 * a.ap_min)
    r = simulate(a, gm, t_free=2.0)
    t_end = float(r.t[-1])
    rot = r.q[:, :, 2]
    for dt in (1e-3, 5e-4):
        ground = _ground_velocity(gm, max(t_end - float(gm.t[-1]), 0.0) + 0.1)
        out = _run(python, {"polygons": quads, "supports": sups, "mu": 0.5, "dt": dt,
                            "duration": t_end, "record": round(5e-3 / dt), "ground": ground})
        hist = np.asarray(out["history"])
        t, lm = hist[:, 0], hist[:, 3:]
        keep = t <= t_end
        ours = np.stack([np.interp(t[keep], r.t, rot[:, i]) for i in range(rot.shape[1])], 1)
        dev = np.abs(ours - lm[keep]).max(axis=1) / np.abs(ours).max()
        k = min(int(np.searchsorted(t[keep], 0.8)), int(keep.sum()) - 1)  # at 0.8 s [mrad]
        split = [1e3 * (th[k, 3] - th[k, 2]) for th in (ours, lm[keep])] + [
            1e3 * (th[k, 4] - th[k, 3]) for th in (ours, lm[keep])]
        print(f"thick arch (quadrilateral voussoirs, mu 0.5), sine 1.3 ap,min T = 0.8 s "
              f"(rockarch {'collapses' if r.overturned else 'stands'}, h = {r.h:.3g} s): "
              f"largest difference of a voussoir's rotation from LMGC90 at dt = {dt:g} s, "
              f"relative to the largest rotation ({np.abs(ours).max():.4f} rad): "
              f"{100 * dev[t[keep] <= 1.0].max():.2f} % until t = 1 s, "
              f"{100 * dev.max():.2f} % until t = {t_end:.3f} s; at t = 0.8 s joints 3 and 4 "
              f"opened by {split[0]:.1f} and {split[2]:.1f} mrad (LMGC90 {split[1]:.1f} and "
              f"{split[3]:.1f})", flush=True)


def time_history(python: str) -> None:
    """A 0.4 x 1 m block (mu 0.6) under a one-cycle sine pulse of 1.5 B/H·g, T = 0.5 s."""
    a = bd.from_polygons([RECT], mu=0.6)
    for ratio in (1.5, 3.0):
        gm = pulse("sine", period=0.5, ap=ratio * a.ap_min)
        r = simulate(a, gm, t_free=1.5)
        th = np.abs(r.q[:, 0, 2]).max()
        ground = _ground_velocity(gm, 1.5)
        out = _run(python, {"polygons": [RECT], "supports": [], "mu": 0.6, "dt": 1e-3,
                            "duration": ground["t"][-1], "record": 10, "ground": ground})
        alpha = math.atan(0.4)
        lm_over = out["max_rotation"] > 2 * alpha
        print(f"time history: block 0.4 x 1, sine T = 0.5 s, 1 cycle, {ratio:g} B/H g: "
              f"rockarch max |theta| = {min(th, 9.99):.4f} rad, "
              f"{'overturns' if r.overturned else 'stands'}; LMGC90 max |theta| = "
              f"{min(out['max_rotation'], 9.99):.4f} rad, "
              f"{'overturns' if lm_over else 'stands'} (alpha = {alpha:.4f} rad)",
              flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--python", default=".venv-lmgc90/bin/python",
                    help="the interpreter with compas-lmgc90")
    ap.add_argument("--quick", action="store_true", help="small structures only")
    args = ap.parse_args()
    if "/" in args.python:  # the runs start in temporary folders
        args.python = str(Path(args.python).absolute())
    check = subprocess.run([args.python, "-c", "import compas_lmgc90.solver"],
                           capture_output=True)
    if check.returncode != 0:
        print(f"lmgc90: {args.python} cannot import compas_lmgc90; skipped "
              "(make validate installs it)")
        return
    for name, polys, supports, mu in cases(args.quick):
        t0 = time.perf_counter()
        a = bd.from_polygons(polys, supports=supports, mu=mu)
        lam, sign = a.ap_min / a.g, int(a.info["collapse_direction"])
        lo, hi, runs = bisect(args.python, polys, supports, mu, lam, sign)
        mid = 0.5 * (lo + hi)
        print(f"{name}: rockarch {lam:.4f} g, LMGC90 {lo:.4f}..{hi:.4f} g "
              f"({100 * (mid / lam - 1):+.1f} %; {runs} runs, "
              f"{time.perf_counter() - t0:.0f} s)", flush=True)
    time_history(args.python)
    if not args.quick:
        arch_history(args.python)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
