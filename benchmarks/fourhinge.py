"""Benchmark: the four-hinge arch in motion (issue 4 targets), against solve_ivp.

Run:  .venv/bin/python benchmarks/fourhinge.py          (≈ 2–3 min: the reference is slow)

Arch: catenary l = 10 m, f = 3 m, d = 0.25 m (f/l = 0.3, d/l = 0.025), critical optimal
four-hinge mechanism. Motion: the first 10 s of El Centro 1940 (PEER RSN6, 180°) scaled to
PGA = ratio·ap,min. The reference integrates the same Lagrange equation with
``scipy.integrate.solve_ivp`` (RK45, rtol 1e-9, atol 1e-12) calling the exact kinematics of
``rockarch.arch.fourhinge`` at every evaluation (what a user would write from the physics
note), with the same events, impact coefficient and settling rule.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from rockarch import systems
from rockarch.arch import catenary
from rockarch.arch.fourhinge import (
    analyse,
    driving_moment,
    generalized_inertia,
    generalized_inertia_du,
    potential_du,
)
from rockarch.core.constants import EPS_REST, T_FREE
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro
from rockarch.rocking import mechanism as mc
from rockarch.rocking.fourhinge_motion import fourhinge_mechanism
from rockarch.spectra import oas as spectra


def reference(res, e, motion_, t_free=T_FREE):
    """solve_ivp on A u'' + ½A'u'² = −V'(u) + s·a_g·Q(u) (symmetric arch: both sides alike);
    returns (collapsed, impacts)."""
    mech, delta, amin = res.mechanism, res.delta, res.ap_min
    t_k, a_k = motion_.t, motion_.a
    t_end = t_k[-1] + t_free

    def ag(t):
        return float(np.interp(t, t_k, a_k, right=0.0))

    def qdd(q, qd, s, a):
        return float((-potential_du(mech, q)[0] + s * a * driving_moment(mech, q)[0]
                      - 0.5 * generalized_inertia_du(mech, q)[0] * qd * qd)
                     / generalized_inertia(mech, q)[0])

    def rhs(t, y, s):  # y = (theta, theta'), theta = s·q
        return [y[1], s * qdd(s * y[0], s * y[1], s, ag(t))]

    def zero(t, y, s):
        return y[0]

    def top(t, y, s):
        return abs(y[0]) - delta

    zero.terminal = top.terminal = True
    t, th, om, s, n_imp, resting = 0.0, 0.0, 0.0, 0.0, 0, True
    while t < t_end:
        if resting:
            idx = np.flatnonzero((np.abs(a_k) > amin) & (t_k >= t))
            if idx.size == 0:
                return False, n_imp
            k = int(idx[0])
            t0 = max(t_k[max(k - 1, 0)], t)
            a0, a1 = ag(t0), a_k[k]
            if abs(a0) > amin:
                t = t0
            else:
                lev = math.copysign(amin, a1)
                t = t0 + (lev - a0) / (a1 - a0) * (t_k[k] - t0)
            s, th, om, resting = math.copysign(1.0, a1), 0.0, 0.0, False
        zero.direction = -s
        sol = solve_ivp(rhs, (t, t_end), [th, om], args=(s,), rtol=1e-9, atol=1e-12,
                        max_step=t_k[1] - t_k[0], events=(zero, top), first_step=1e-6)
        if sol.status == 1 and sol.t_events[1].size:
            return True, n_imp
        if sol.status == 1 and sol.t_events[0].size:
            t = float(sol.t_events[0][0])
            om, th, s = e * float(sol.y_events[0][0][1]), 0.0, -s
            n_imp += 1
            acc = s * qdd(0.0, 0.0, s, ag(t))
            if s * acc <= 0 and (om * om <= 2 * EPS_REST * delta * abs(acc) or om == 0.0):
                resting, om, s = True, 0.0, 0.0
            continue
        return False, n_imp
    return False, n_imp


def main() -> None:
    arch = catenary(10.0, 3.0, 0.25)
    t0 = time.perf_counter()
    mech = fourhinge_mechanism(arch)
    t_build = time.perf_counter() - t0
    res = analyse(arch)
    rec = el_centro()
    k = int(np.searchsorted(rec.t, 10.0)) + 1
    ten = motion.GroundMotion(rec.t[:k], rec.a[:k], "El Centro 0-10 s")
    print(f"{mech.name}: p = {mech.p:.4f} 1/s, delta = {mech.delta:.5f} rad, ap,min = "
          f"{mech.ap_min:.4f} m/s², e = {mech.plus.e_close:.4f}; built in {t_build * 1e3:.0f} ms")

    mc.simulate(mech, ten.scaled(1.5 * mech.ap_min / ten.pga))  # JIT warm-up
    ratios = np.linspace(1.05, 3.0, 40)
    times, verdicts = [], []
    for r in ratios:
        m = ten.scaled(r * mech.ap_min / ten.pga)
        best = math.inf
        for _ in range(3):
            t1 = time.perf_counter()
            out = mc.simulate(mech, m)
            best = min(best, time.perf_counter() - t1)
        times.append(best)
        verdicts.append(out.overturned)
    times = np.array(times)
    print(f"one simulation, 10 s record + {T_FREE:.0f} s free (with history, 40 ratios, best of "
          f"3): median {np.median(times) * 1e3:.3f} ms, max {times.max() * 1e3:.3f} ms "
          f"(target <= 5 ms median)")

    ref_t, agree = [], []
    for r, v in zip(ratios[::8], verdicts[::8], strict=True):
        m = ten.scaled(r * mech.ap_min / ten.pga)
        t1 = time.perf_counter()
        ov, _ = reference(res, mech.plus.e_close, m)
        ref_t.append(time.perf_counter() - t1)
        agree.append(ov == v)
        print(f"  solve_ivp reference: {len(ref_t)}/{len(ratios[::8])} runs", flush=True)
    sub = times[::8]
    print(f"solve_ivp reference ({len(ref_t)} runs): median {np.median(ref_t) * 1e3:.0f} ms; "
          f"rockarch on the same runs {np.median(sub) * 1e3:.3f} ms: "
          f"{np.median(ref_t) / np.median(sub):.0f}x; same verdict in {sum(agree)}/"
          f"{len(agree)}")

    system = systems.MechanismSystem(mech)
    sine = motion.sine(1.0, 1.0)
    spectra.compute_oas(system, sine, [1.0, 2.0], [1.0, 2.0], progress=False)
    t1 = time.perf_counter()
    ds = spectra.compute_oas(system, sine, np.linspace(0.5, 10, 100), np.linspace(1, 8, 100),
                             progress=False)
    wall = time.perf_counter() - t1
    print(f"100 x 100 four-hinge OAS, sine T = 1 s (+ boundary bisection): {wall:.2f} s wall "
          f"(target <= 60 s); {int(ds.overturned.sum())} of 10000 cells collapse")


if __name__ == "__main__":
    main()
