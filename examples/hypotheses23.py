"""Hypotheses 2 and 3 (paper Figs. 16 and 17): MDOF catenary arches against their critical
optimal four-hinge mechanism and against the slender block with the same p and ap,min.

Three catenary geometries (f/l = 0.2, 0.3, 0.4 at d/l = 0.025) cut into N voussoirs
(default 20), the sine, square and step signals of Fig. 14 (T = 1 s). Every curve is on the
axes of the critical optimal four-hinge mechanism of the continuous arch: p of that
mechanism at the arch's size, ap / its ap,min. The N-voussoir arch is a little stronger
(its hinges must sit at joints): the ratio ap,min(N)/ap,min(optimal) is printed.

A model is a *safe* approximation of the MDOF arch at a p where its boundary (lowest
overturning ratio) is at or below the MDOF boundary.

Run:  .venv/bin/python examples/hypotheses23.py --out docs/img      (≈ 3–5 min on 2 cores)
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rockarch.paper import results as paper


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    ap.add_argument("--n", type=int, default=30, help="p values (0.5…10 1/s)")
    ap.add_argument("--blocks", type=int, default=20, help="voussoirs of the MDOF arch")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    rows = paper.fig16_17(args.out, n_p=args.n, blocks=args.blocks)
    print("| signal | f/l | d/l | ap,min(N)/ap,min(opt) | H2: p where four-hinge is safe | "
          "four-hinge vs MDOF (mean rel.) | H3: p where block is safe | block vs MDOF "
          "(mean rel.) | MDOF open joints (max) |\n|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['signal']} | {r['f/l']} | {r['d/l']} | {r['ap_min_ratio']:.3f} | "
              f"{100 * r['fourhinge_safe']:.0f} % | {r['fourhinge_rel']:+.3f} | "
              f"{100 * r['block_safe']:.0f} % | {r['block_rel']:+.3f} | "
              f"{r['open_joints_max']} |")
    print(f"\nwrote {args.out / 'hypothesis2.png'} and {args.out / 'hypothesis3.png'}")


if __name__ == "__main__":
    main()
