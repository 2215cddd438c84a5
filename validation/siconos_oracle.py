"""Siconos as an oracle for rockarch's MDOF engine: run with the SYSTEM python.

    /usr/bin/python3 validation/siconos_oracle.py CASE.json OUT.npz

Siconos 4.4 (Debian ``python3-siconos``) is built for /usr/bin/python3, not for rockarch's
virtual environment, so this script imports nothing from rockarch: it reads a plain JSON
case written by ``validation/siconos_compare.py`` and writes the time history to an NPZ.

The model (the standard Siconos set-up for planar rigid blocks):

- every block a ``LagrangianLinearTIDS`` with q = (x, y, theta) of its centroid and
  M = diag(m, m, I); external force (-m·a_g(t), -m·g, 0) (the ground's frame);
- every joint corner a contact: the corner of body b against the face of body a (or of the
  ground), ``LagrangianScleronomousR`` with the exact nonlinear gap
  g_N = n(theta_a)·(P_b - P_a) and tangential offset, Jacobians analytic;
  ``NewtonImpactFrictionNSL`` (e = 0, mu);
- ``MoreauJeanOSI`` (theta = 0.5), ``FrictionContact(2)`` solved by 2-D NSGS to 1e-14,
  ``TimeStepping`` with step h.

Pitfalls met on these machines (/work/shared/docs/oracles.md): relations written as Python
subclasses crash, so the gap functions are generated as C and compiled with gcc into a
plug-in; the 2-D Lemke solver can leave the cone, NSGS with a tight tolerance does not; an
activation threshold of ~1e-9·size stops round-off from releasing resting corners.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

# C source of one contact: the corner of body b (local rb) against the face of body a
# (local point ra, local normal na; a = the ground when GROUND is 1: ra, na in the ground).
_C_PAIR = """
void h_{k}(unsigned int sq, double* q, unsigned int sy, double* y, unsigned int sz, double* z)
{{
  double ca = cos(QA(2)), sa = sin(QA(2)), cb = cos(QB(2)), sb = sin(QB(2));
  double nx = ca * {nax} - sa * {nay}, ny = sa * {nax} + ca * {nay};
  double pax = QA(0) + ca * {rax} - sa * {ray}, pay = QA(1) + sa * {rax} + ca * {ray};
  double pbx = QB(0) + cb * {rbx} - sb * {rby}, pby = QB(1) + sb * {rbx} + cb * {rby};
  double dx = pbx - pax, dy = pby - pay;
  y[0] = nx * dx + ny * dy;
  y[1] = -ny * dx + nx * dy;
}}
void G_{k}(unsigned int sq, double* q, unsigned int sg, double* G, unsigned int sz, double* z)
{{
  int nr = 2;
  double ca = cos(QA(2)), sa = sin(QA(2)), cb = cos(QB(2)), sb = sin(QB(2));
  double nx = ca * {nax} - sa * {nay}, ny = sa * {nax} + ca * {nay};
  double tx = -ny, ty = nx;
  double rax = ca * {rax} - sa * {ray}, ray = sa * {rax} + ca * {ray};
  double rbx = cb * {rbx} - sb * {rby}, rby = sb * {rbx} + cb * {rby};
  double dx = QB(0) + rbx - QA(0) - rax, dy = QB(1) + rby - QA(1) - ray;
  /* column-major 2 x ndof; d(R r)/dtheta = (-r_y, r_x) */
  {gb}
  G[0 + nr * (OB + 0)] = nx;  G[1 + nr * (OB + 0)] = tx;
  G[0 + nr * (OB + 1)] = ny;  G[1 + nr * (OB + 1)] = ty;
  G[0 + nr * (OB + 2)] = nx * (-rby) + ny * rbx;
  G[1 + nr * (OB + 2)] = tx * (-rby) + ty * rbx;
  {ga}
}}
"""

_C_GA = """
  G[0] = -nx;  G[1] = -tx;  G[2] = -ny;  G[3] = -ty;
  G[4] = (tx * dx + ty * dy) - (nx * (-ray) + ny * rax);
  G[5] = (-nx * dx - ny * dy) - (tx * (-ray) + ty * rax);"""


def _source(contacts) -> str:
    out = ["#include <math.h>"]
    for k, c in enumerate(contacts):
        ground = c["a"] < 0
        macros = ("#define QA(i) (0.0)\n#define QB(i) (q[i])\n#define OB 0" if ground else
                  "#define QA(i) (q[i])\n#define QB(i) (q[3 + i])\n#define OB 3")
        body = _C_PAIR.format(k=k, nax=c["na"][0], nay=c["na"][1], rax=c["ra"][0],
                              ray=c["ra"][1], rbx=c["rb"][0], rby=c["rb"][1], gb="",
                              ga="" if ground else _C_GA)
        out += [macros, body, "#undef QA\n#undef QB\n#undef OB"]
    return "\n".join(out)


def _contacts(case):
    """Every joint corner as a contact (a, b, ra, na, rb) in the bodies' own frames."""
    cen = np.asarray(case["centroid"], float)
    out = []
    for a, b, corners, n, mu in zip(case["body_a"], case["body_b"], case["corners"],
                                    case["normal"], case["mu"], strict=True):
        n = np.asarray(n, float)
        if b < 0:  # the ground on side b: swap so that the ground is side a
            a, b, n = b, a, -n
        for p in np.asarray(corners, float):
            ra = p - (cen[a] if a >= 0 else 0.0)
            out.append({"a": int(a), "b": int(b), "ra": ra.tolist(), "na": n.tolist(),
                        "rb": (p - cen[b]).tolist(), "mu": float(mu)})
    return out


def run(case: dict) -> dict:
    import siconos.kernel as sk
    import siconos.numerics as sn

    contacts = _contacts(case)
    work = tempfile.mkdtemp(prefix="rockarch-siconos-")
    src = os.path.join(work, "contacts.c")
    lib = os.path.join(work, "contacts.so")
    with open(src, "w") as f:
        f.write(_source(contacts))
    subprocess.run(["gcc", "-O2", "-shared", "-fPIC", "-o", lib, src, "-lm"], check=True)
    return _simulate(case, contacts, sk, sn, os.path.join(work, "contacts"))


def _simulate(case, contacts, sk, sn, plugin: str):
    mass = np.asarray(case["mass"], float)
    inertia = np.asarray(case["inertia"], float)
    cen = np.asarray(case["centroid"], float)
    g, h, t_end = float(case["g"]), float(case["h"]), float(case["t_end"])
    tg, ag = np.asarray(case["t_ground"], float), np.asarray(case["a_ground"], float)
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    dss, fext = [], []
    for i in range(len(mass)):
        m = np.diag([mass[i], mass[i], inertia[i]])
        ds = sk.LagrangianLinearTIDS([cen[i, 0], cen[i, 1], 0.0], [0.0, 0.0, 0.0], m)
        f = sk.SiconosVector(3)
        ds.setFExtPtr(f)
        nsds.insertDynamicalSystem(ds)
        dss.append(ds)
        fext.append(f)
    for k, c in enumerate(contacts):
        mu = c["mu"] if np.isfinite(c["mu"]) else float(case.get("mu_no_slip", 100.0))
        law = sk.NewtonImpactFrictionNSL(0.0, 0.0, mu, 2)
        rel = sk.LagrangianScleronomousR(f"{plugin}:h_{k}", f"{plugin}:G_{k}")
        inter = sk.Interaction(law, rel)
        if c["a"] < 0:
            nsds.link(inter, dss[c["b"]])
        else:
            nsds.link(inter, dss[c["a"]], dss[c["b"]])
    osi = sk.MoreauJeanOSI(0.5)
    osi.setConstraintActivationThreshold(1e-9 * float(case["size"]))
    osnspb = sk.FrictionContact(2, sn.SICONOS_FRICTION_2D_NSGS)
    so = osnspb.numericsSolverOptions()
    so.dparam[sn.SICONOS_DPARAM_TOL] = float(os.environ.get("SICONOS_TOL", "1e-14"))
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
    td = sk.TimeDiscretisation(0.0, h)
    sim = sk.TimeStepping(nsds, td, osi, osnspb)
    ts, qs = [0.0], [np.c_[cen, np.zeros(len(mass))]]
    t = 0.0
    while sim.hasNextEvent() and t < t_end - 0.5 * h:
        t_next = t + h
        a = float(np.interp(t_next, tg, ag, right=0.0))
        for i, f in enumerate(fext):
            f.setValue(0, -mass[i] * a)
            f.setValue(1, -mass[i] * g)
            f.setValue(2, 0.0)
        sim.computeOneStep()
        sim.nextStep()
        t = t_next
        ts.append(t)
        qs.append(np.array([np.asarray(ds.q()).ravel()[:3] for ds in dss]))
    return {"t": np.array(ts), "q": np.array(qs)}


def main(argv) -> int:
    if len(argv) != 3:
        print(__doc__.splitlines()[2].strip(), file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        case = json.load(f)
    res = run(case)
    np.savez(argv[2], **res)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
