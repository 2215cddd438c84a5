"""Hypothesis 1 (paper Fig. 15) and the SDOF equivalence, with the figure and tables.

OAS of the critical optimal four-hinge mechanisms of catenary arches (f/l = 0.2, 0.3, 0.4;
d/l = 0.0125, 0.025, 0.05, the arches of Table 1) for the sine, square and step signals of
Fig. 14 (period T = 1 s; pulse OAS depend on p·T only), with the OAS of a slender block
(alpha = 0.01) overlaid. Then the equivalence of ref. [13]: the four-hinge catenary
(f/l = 0.3) against a block with the same p and ap,min as d/l → 0.

Run:  .venv/bin/python examples/hypothesis1.py --out docs/img      (≈ 20 s on 2 cores)
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rockarch import motion, spectra  # noqa: E402
from rockarch.arch import catenary  # noqa: E402
from rockarch.arch.dynamics import fourhinge_mechanism  # noqa: E402
from rockarch.plot import save_figure  # noqa: E402

SIGNALS = ("sine", "square", "step")
RISES = (0.2, 0.3, 0.4)
THICK = (0.0125, 0.025, 0.05)
COLORS = {0.0125: "tab:blue", 0.025: "tab:orange", 0.05: "tab:green"}


def boundary(system, signal, p, ratio):
    return spectra.compute_oas(system, motion.pulse(signal, 1.0, 1.0), p, ratio,
                               progress=False).boundary.values


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    ap.add_argument("--n", type=int, default=40, help="p values (0.5…10 1/s)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    p = np.linspace(0.5, 10.0, args.n)
    ratio = np.linspace(1.0, 8.0, 71)
    block = spectra.BlockSystem(alpha=0.01)

    fig, axes = plt.subplots(3, 3, figsize=(13, 11), sharex=True, sharey=True)
    rows = ["| signal | f/l | d/l | e (impact) | p where the d/l = 0.0125 arch is on the safe "
            "side of this one | p where the block is on the safe side |", "|---|---|---|---|"
            "---|---|"]
    for i, sig in enumerate(SIGNALS):
        bb = boundary(block, sig, p, ratio)
        for j, rise in enumerate(RISES):
            ax = axes[i, j]
            slender = None
            for d in THICK:
                mech = fourhinge_mechanism(catenary(1.0, rise, d))
                b = boundary(spectra.MechanismSystem(mech), sig, p, ratio)
                if slender is None:
                    slender = b
                ax.plot(p, b, color=COLORS[d], lw=1.5, label=f"arch d/l = {d}")
                ok = np.isfinite(b) | np.isnan(slender)
                lhs = np.where(np.isfinite(slender), slender, np.inf)
                rhs = np.where(np.isfinite(b), b, np.inf)
                frac_arch = np.mean((lhs <= rhs * (1 + 1e-3)) & ok)
                frac_blk = np.mean(np.where(np.isfinite(bb), bb, np.inf) <= rhs * (1 + 1e-3))
                rows.append(f"| {sig} | {rise} | {d} | {mech.plus.e_close:.3f} | "
                            f"{100 * frac_arch:.0f} % | {100 * frac_blk:.0f} % |")
            ax.plot(p, bb, "k--", lw=1.5, label="slender block (alpha = 0.01)")
            ax.set_title(f"{sig}, T = 1 s, catenary f/l = {rise}", fontsize=9)
            if i == 2:
                ax.set_xlabel("p [1/s]")
            if j == 0:
                ax.set_ylabel(r"lowest overturning $a_p/a_{p,\min}$")
            ax.set_ylim(1, 8)
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Hypothesis 1 (paper Fig. 15): OAS of critical optimal four-hinge mechanisms "
                 "of catenary arches", fontsize=11)
    fig.tight_layout()
    save_figure(fig, args.out / "hypothesis1.png")
    print("\n".join(rows))

    # equivalence: four-hinge catenary f/l = 0.3 vs the block with the same p and ap,min
    print("\n| signal | d/l | e (impact) | max rel. deviation of the boundary | mean | "
          "p where the block is on the safe side |\n|---|---|---|---|---|---|")
    pe = np.linspace(1.0, 10.0, 19)
    ratio_e = np.linspace(1.0, 8.0, 57)
    for sig in SIGNALS:
        for d in (0.05, 0.025, 0.0125, 0.005, 0.0025):
            mech = fourhinge_mechanism(catenary(1.0, 0.3, d))
            blk = spectra.BlockSystem(alpha=math.atan(mech.ap_min / mech.g))
            bf = boundary(spectra.MechanismSystem(mech), sig, pe, ratio_e)
            bk = boundary(blk, sig, pe, ratio_e)
            rel = (bf - bk) / bk
            print(f"| {sig} | {d} | {mech.plus.e_close:.3f} | {np.nanmax(np.abs(rel)):.4f} | "
                  f"{np.nanmean(rel):+.4f} | {100 * np.nanmean(rel >= -1e-3):.0f} % |")
    print(f"\nwrote {args.out / 'hypothesis1.png'}")


if __name__ == "__main__":
    main()
