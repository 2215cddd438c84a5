"""Paper Sect. 8, Table 2 and Sect. 9: the circular arch and its replacement catenary arches.

Prints paper vs computed side by side (a) with the replacement rockarch constructs (the
thickest catenary band inside the arch, springings free on its springing joints,
docs/theory.md Eqs. 7.3–7.7; own mass, then the original's mass) and (b) with the paper's
printed geometry (l = 10 m, f = 2.924 m, d/l = 0.0207 and 0.0293), and draws Fig. 19: the OAS
of the arch's four-hinge mechanism and MDOF model and of the two equivalent blocks for the
three signals of Fig. 14.

Run:  .venv/bin/python examples/table2.py --out docs/img        (≈ 1 min, Fig. 19's MDOF arch)
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rockarch.core.constants import G
from rockarch.paper import results as paper
from rockarch.paper.reference import SECT8, SECT9, TABLE2


def dev(a: float, b: float) -> str:
    return f"{100 * (a / b - 1):+.1f} %"


def row(name: str, ref: dict, ours: dict) -> str:
    own = ours.get("d/l'")
    cells = [name, f"{ref['d/l']} / {ours['d/l']:.4f}"
             + (f" (per l′: {own:.4f})" if own is not None else "")]
    if "span" in ours:
        cells.append(f"{ours['span']:.3f} / {ours['rise']:.3f}")
    elif "rise" in ours:
        cells.append(f"10 / {ours['rise']:.3f}")
    else:
        cells.append("10 / 2.89")
    cells += [f"{ref[k]} / {ours[k]:.4f} ({dev(ours[k], ref[k])})"
              for k in ("c1", "c2", "ap_min")]
    if "R/l" in ref:
        cells += [f"{ref['R/l']} / {ours['R/l']:.4f}",
                  f"{ref['p']:.3f} / {ours['p']:.3f} ({dev(ours['p'], ref['p'])})"]
    else:
        cells += ["–", f"– / {ours['p']:.3f}"]
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    t2 = paper.table2_rows()
    head = ("| model | d/l paper / ours | l′ / f′ [m] | c1 | c2 | ap,min [m/s²] | block R/l | "
            "p [1/s] |\n|---|---|---|---|---|---|---|---|")
    arch_ref = {"d/l": 0.0345, **{k: SECT8[k] for k in ("c1", "c2", "ap_min")}}
    for title, key in (("(a) rockarch's replacement: the thickest catenary band, own mass",
                        "fitted"),
                       ("(a') the same band carrying the original's mass per horizontal "
                        "length", "fitted_original_mass")):
        print(title + "\n")
        print(head)
        print(row("circular arch", arch_ref, {"d/l": SECT8["d_over_l"], **t2["original"]}))
        for rule in ("equivalent", "lower-bound"):
            print(row(f"replacement, {rule}", TABLE2[rule], t2[key][rule]))
        print()
    print("(b) the paper's replacement geometry: l = 10 m, f = 2.924 m, d/l as in Table 2\n")
    print(head)
    for rule in ("equivalent", "lower-bound"):
        print(row(f"replacement, {rule}", TABLE2[rule], t2["paper_geometry"][rule]))
    eq = t2["fitted"]["equivalent"]
    print(f"\nSect. 9 with this arch (d/l = 0.0346; Sect. 9 quotes d = 0.35 m with the same "
          f"ap,min): equivalent replacement d = {eq['thickness']:.3f} m (paper 0.293), "
          f"p = {eq['p']:.3f} 1/s (paper 3.705), ap,min = {eq['ap_min']:.3f} m/s² (paper "
          f"3.036); with the paper's site ratio {SECT9['ratio']} the safe PGA would be "
          f"{SECT9['ratio'] * eq['ap_min']:.3f} m/s² = {SECT9['ratio'] * eq['ap_min'] / G:.3f} g "
          f"(paper {SECT9['pga_safe']} m/s² = {SECT9['pga_safe_g']} g)")
    rows = paper.fig19(args.out / "fig19.png", rep=t2["replacement"])
    print("\nFig. 19: share of p where each curve is at or below the MDOF arch's (within 0.2 %)"
          " and the mean relative gap")
    for r in rows:
        print(f"  {r['signal']:6s} {r['curve']:45s} {100 * r['safe']:4.0f} %  "
              f"{100 * r['mean_rel']:+.1f} %")
    print(f"\nwrote {args.out / 'fig19.png'}")


if __name__ == "__main__":
    main()
