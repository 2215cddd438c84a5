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
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rockarch import mdof, motion, spectra  # noqa: E402
from rockarch.arch import catenary  # noqa: E402
from rockarch.arch.dynamics import fourhinge_mechanism  # noqa: E402
from rockarch.plot import save_figure  # noqa: E402

SIGNALS = ("sine", "square", "step")
GEOMETRIES = ((0.2, 0.025), (0.3, 0.025), (0.4, 0.025))


def boundary(system, signal, p, ratio):
    return spectra.compute_oas(system, motion.pulse(signal, 1.0, 1.0), p, ratio,
                               progress=False).boundary.values


def compare(ref, other):
    """(share of p where `other` is at or below `ref` (safe side), mean relative gap)."""
    r = np.where(np.isfinite(ref), ref, np.inf)
    o = np.where(np.isfinite(other), other, np.inf)
    both = np.isfinite(r) & np.isfinite(o)
    safe = np.mean(o <= r * (1 + 2e-3))
    rel = np.nanmean((o[both] - r[both]) / r[both]) if both.any() else math.nan
    return safe, rel


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    ap.add_argument("--n", type=int, default=30, help="p values (0.5…10 1/s)")
    ap.add_argument("--blocks", type=int, default=20, help="voussoirs of the MDOF arch")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    p = np.linspace(0.5, 10.0, args.n)
    ratio = np.linspace(1.0, 8.0, 57)

    figs = {h: plt.subplots(3, 3, figsize=(13, 11), sharex=True, sharey=True)
            for h in (2, 3)}
    rows = ["| signal | f/l | d/l | ap,min(N)/ap,min(opt) | H2: p where four-hinge is safe | "
            "four-hinge vs MDOF (mean rel.) | H3: p where block is safe | block vs MDOF "
            "(mean rel.) | MDOF open joints (max) |", "|---|---|---|---|---|---|---|---|---|"]
    for j, (rise, d) in enumerate(GEOMETRIES):
        arch = catenary(1.0, rise, d)
        fh = fourhinge_mechanism(arch)
        asm = mdof.arch_assembly(arch, args.blocks)
        sys_m = mdof.MDOFSystem(asm, ap_min=fh.ap_min, p_ref=fh.p)
        sys_f = spectra.MechanismSystem(fh)
        sys_b = spectra.BlockSystem(alpha=math.atan(fh.ap_min / fh.g))
        for i, sig in enumerate(SIGNALS):
            bm = boundary(sys_m, sig, p, ratio)
            bf = boundary(sys_f, sig, p, ratio)
            bb = boundary(sys_b, sig, p, ratio)
            pp, rr = np.meshgrid(p, [1.5], indexing="ij")
            nopen = mdof.simulate_batch(asm, motion.pulse(sig, 1.0, 1.0), pp, rr,
                                        ap_min=fh.ap_min, p_ref=fh.p).open_joints_max.max()
            s2, r2 = compare(bm, bf)
            s3, r3 = compare(bm, bb)
            rows.append(f"| {sig} | {rise} | {d} | {asm.ap_min / fh.ap_min:.3f} | "
                        f"{100 * s2:.0f} % | {r2:+.3f} | {100 * s3:.0f} % | {r3:+.3f} | "
                        f"{nopen} |")
            for h, other, lab in ((2, bf, "critical optimal four-hinge"),
                                  (3, bb, "block, same p and ap,min")):
                ax = figs[h][1][i, j]
                ax.plot(p, bm, color="tab:red", lw=1.8, label=f"MDOF arch, N = {args.blocks}")
                ax.plot(p, other, "k--", lw=1.5, label=lab)
                ax.set_title(f"{sig}, T = 1 s, catenary f/l = {rise}, d/l = {d}", fontsize=9)
                if i == 2:
                    ax.set_xlabel("p [1/s] (optimal four-hinge mechanism)")
                if j == 0:
                    ax.set_ylabel(r"lowest overturning $a_p/a_{p,\min}$")
                ax.set_ylim(1, 8)
                ax.grid(alpha=0.3)
    for h, title in ((2, "Hypothesis 2 (paper Fig. 16): MDOF catenary arch vs its critical "
                      "optimal four-hinge mechanism"),
                     (3, "Hypothesis 3 (paper Fig. 17): MDOF catenary arch vs the block with "
                      "the same p and ap,min")):
        fig, axes = figs[h]
        axes[0, 0].legend(fontsize=8)
        fig.suptitle(title, fontsize=11)
        fig.tight_layout()
        save_figure(fig, args.out / f"hypothesis{h}.png")
    print("\n".join(rows))
    print(f"\nwrote {args.out / 'hypothesis2.png'} and {args.out / 'hypothesis3.png'}")


if __name__ == "__main__":
    main()
