"""Reproduce the paper's Table 1 (catenary arches) and the Sect. 8 circular arch, side by side.

Usage::

    .venv/bin/python examples/table1.py            # the comparison table
    .venv/bin/python examples/table1.py --variants # plus the mass-model / delta investigation

Paper: c1..c4 of Eq. 14 for the critical optimal four-hinge mechanism (continuous arch,
hinges at the maximum eccentricities). Ours: rockarch.arch.analyse with the default choices
(true voussoir polygons, exact kinematics, ground acceleration to the right). "c4" uses
Table 1's delta (the rotation of the end part next to the extrados inner hinge at the
neutral configuration, docs/theory.md Eq. 5.4); "c4_u" the dynamics' coordinate u (rotation
of the left part). See docs/validation.md.
"""

from __future__ import annotations

import argparse
import time

from rockarch.arch import analyse, catenary, circular
from rockarch.core.constants import G
from rockarch.paper import results as paper
from rockarch.paper.reference import SECT8, TABLE1, TABLE2


def pct(ours: float, paper: float) -> str:
    return f"{100 * (ours / paper - 1):+5.1f}%"


def table1() -> dict:
    print("Table 1, catenary arches (span l = 1; paper / ours / deviation)")
    head = (f"{'f/l':>4} {'d/l':>6} | {'c1 paper':>8} {'ours':>6} {'dev':>6} | "
            f"{'c2 paper':>8} {'ours':>6} {'dev':>6} | {'c3/c3p paper':>12} {'ours':>11} | "
            f"{'c4 paper':>8} {'ours':>6} {'dev':>6} {'c4_u':>6} {'dev':>6}")
    print(head)
    print("-" * len(head))
    worst = {"c1": 0.0, "c2": 0.0, "c3": 0.0, "c4": 0.0, "c4m": 0.0}
    for (fl, dl), (c1, c2, c3, c3p, c4) in TABLE1.items():
        r = analyse(catenary(1.0, fl, dl), g=G)
        worst["c1"] = max(worst["c1"], abs(r.c1 / c1 - 1))
        worst["c2"] = max(worst["c2"], abs(r.c2 / c2 - 1))
        worst["c3"] = max(worst["c3"], abs(r.c3 - c3), abs(r.c3p - c3p))
        worst["c4"] = max(worst["c4"], abs(r.c4 / c4 - 1))
        worst["c4m"] = max(worst["c4m"], abs(r.c4_u / c4 - 1))
        print(f"{fl:4.1f} {dl:6.4f} | {c1:8.3f} {r.c1:6.3f} {pct(r.c1, c1)} | "
              f"{c2:8.3f} {r.c2:6.3f} {pct(r.c2, c2)} | {c3:5.2f}/{c3p:<6.2f} "
              f"{r.c3:5.3f}/{r.c3p:5.3f} | {c4:8.2f} {r.c4:6.3f} {pct(r.c4, c4)} "
              f"{r.c4_u:6.3f} {pct(r.c4_u, c4)}")
    print(f"max |deviation|: c1 {100 * worst['c1']:.1f}%, c2 {100 * worst['c2']:.2f}%, "
          f"c3/c3' {worst['c3']:.3f} (absolute), c4 {100 * worst['c4']:.0f}% "
          f"(c4_u {100 * worst['c4m']:.0f}%)")
    return worst


def sect8() -> None:
    print("\nSect. 8 circular arch, l = 10 m, f/l = 0.289 (paper: ap,min = 3.036 m/s², "
          "Table 2: c1 = 0.242, c2 = 0.768)")
    for dl in (0.0346, 0.0345):
        r = analyse(circular(10.0, 2.89, 10.0 * dl), g=G)
        c2_own = SECT8["ap_min"] * 0.289**2 / (G * dl)
        print(f"  d/l = {dl}: ap,min = {r.ap_min:.3f} m/s² ({pct(r.ap_min, SECT8['ap_min'])}), "
              f"c1 = {r.c1:.3f} ({pct(r.c1, 0.242)}), c2 = {r.c2:.3f} ({pct(r.c2, 0.768)}; "
              f"the paper's ap,min implies c2 = {c2_own:.3f}), p = {r.p:.3f} 1/s, "
              f"delta = {r.delta_end:.4f} rad (part {r.end_part}), hinges at x = "
              + ", ".join(f"{h.x:.2f}" for h in r.hinges))


def table2() -> None:
    print("\nTable 2 / Sect. 9: replacement weighted catenaries carrying the circular arch's mass "
          "(l = 10 m, rise 2.924 m as in Sect. 9)")
    given = paper.table2_rows(G)["paper_geometry"]
    for name, ref in TABLE2.items():
        r = given[name]
        print(f"  {name:11s} d/l = {ref['d/l']}: ap,min = {r['ap_min']:.3f} ({ref['ap_min']}, "
              f"{pct(r['ap_min'], ref['ap_min'])}), c1 = {r['c1']:.4f} ({ref['c1']}, "
              f"{pct(r['c1'], ref['c1'])}), c2 = {r['c2']:.4f} ({ref['c2']}, "
              f"{pct(r['c2'], ref['c2'])}), p = {r['p']:.3f} 1/s")


def variants() -> None:
    print("\nVariants (f/l = 0.3): mass model, definition of delta, and Eq. 12's delta-free "
          "product c1*c4 = g*A*d/(Bv*f*l) (A, Bv on the coordinate of Table 1's delta)")
    print(f"{'d/l':>6} | {'c1 vous':>7} {'c1 axis':>7} {'c2 vous':>7} {'c2 axis':>7} | "
          f"{'c4':>6} {'c4 lin':>7} {'c4_u':>6} | {'Eq. 12':>7} {'paper':>6} {'ratio':>5}")
    rows = {(r["f/l"], r["d/l"]): r for r in paper.table1_rows(G)}
    for dl in (0.001, 0.0125, 0.025, 0.05, 0.1):
        rv = analyse(catenary(1.0, 0.3, dl), g=G)
        ra = analyse(catenary(1.0, 0.3, dl, mass_model="axis"), g=G)
        ref = TABLE1.get((0.3, dl))
        row = rows.get((0.3, dl))
        prod = (f"{ref[0] * ref[4]:6.4f} {row['paper_c1c4_ratio']:5.2f}" if ref
                else "   -      -")
        eq12 = f"{row['ours']['c1c4_eq12']:7.4f}" if row else "    -  "
        print(f"{dl:6.4f} | {rv.c1:7.4f} {ra.c1:7.4f} {rv.c2:7.4f} {ra.c2:7.4f} | "
              f"{rv.c4:6.4f} {dl / rv.delta_linear:7.4f} {rv.c4_u:6.4f} | {eq12} {prod}")
    print("paper c1*c4 / Eq. 12 over all of Table 1: "
          + ", ".join(f"{k[0]}/{k[1]}: {r['paper_c1c4_ratio']:.2f}" for k, r in rows.items()))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variants", action="store_true", help="also print the investigation")
    args = ap.parse_args()
    t0 = time.perf_counter()
    table1()
    sect8()
    table2()
    if args.variants:
        variants()
    print(f"\n({time.perf_counter() - t0:.1f} s)")


if __name__ == "__main__":
    main()
