"""Paper Sect. 8, Table 2 and Sect. 9: the circular arch and its replacement catenary arches.

Prints paper vs computed side by side (a) with the replacement geometry rockarch constructs
(rise fitted to the thickest inscribed weighted catenary) and (b) with the paper's stated
geometry (f = 2.924 m, d/l = 0.0207 and 0.0293), and draws Fig. 19: the OAS of the arch's
four-hinge mechanism and of the two equivalent blocks for the three signals of Fig. 14.

Run:  .venv/bin/python examples/table2.py --out docs/img        (≈ 10 s)
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
from rockarch.arch import analyse, circular, mass_per_horizontal_length  # noqa: E402
from rockarch.arch import weighted_catenary as wcat  # noqa: E402
from rockarch.arch.dynamics import fourhinge_mechanism  # noqa: E402
from rockarch.arch.replacement import replacement  # noqa: E402
from rockarch.plot import save_figure  # noqa: E402

L, F, D = 10.0, 2.89, 0.346
PAPER = {  # Table 2 and Sect. 8-9
    "arch": {"d/l": 0.0345, "c1": 0.242, "c2": 0.768, "ap_min": 3.036},
    "equivalent": {"d/l": 0.0293, "c1": 0.2473, "c2": 0.8914, "ap_min": 3.036,
                   "R/l": 0.0536, "p": 3.705, "f": 2.924},
    "lower-bound": {"d/l": 0.0207, "c1": 0.2437, "c2": 0.8896, "ap_min": 2.163,
                    "R/l": 0.0528, "p": 11.82 / math.sqrt(10.0)},
}


def dev(a: float, b: float) -> str:
    return f"{100 * (a / b - 1):+.1f} %"


def row(name, paper, d_l, c1, c2, ap, r_l, p) -> str:
    cells = [name,
             f"{paper['d/l']} / {d_l:.4f}",
             f"{paper['c1']} / {c1:.4f} ({dev(c1, paper['c1'])})",
             f"{paper['c2']} / {c2:.4f} ({dev(c2, paper['c2'])})",
             f"{paper['ap_min']} / {ap:.3f} ({dev(ap, paper['ap_min'])})"]
    if "R/l" in paper:
        cells += [f"{paper['R/l']} / {r_l:.4f}", f"{paper['p']:.3f} / {p:.3f} "
                  f"({dev(p, paper['p'])})"]
    else:
        cells += ["–", f"– / {p:.3f}"]
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    g = 9.81
    arch = circular(L, F, D)
    rep = replacement(arch)
    o = rep.original
    head = ("| model | d/l paper / ours | c1 | c2 | ap,min [m/s²] | block R/l | p [1/s] |\n"
            "|---|---|---|---|---|---|---|")
    print("(a) rockarch's replacement geometry: axis rise fitted, f = "
          f"{rep.equivalent.rise:.4f} m (paper 2.924 m)\n")
    print(head)
    print(row("circular arch", PAPER["arch"], D / L, o.c1, o.c2, o.ap_min, 0, o.p))
    for r in (rep.equivalent, rep.lower_bound):
        m = r.mechanism
        print(row(f"replacement, {r.rule}", PAPER[r.rule], r.thickness / L, m.c1, m.c2,
                  m.ap_min, r.R_block / L, m.p))
    print("\n(b) the paper's replacement geometry: f = 2.924 m, d/l as in Table 2\n")
    print(head)
    w = mass_per_horizontal_length(arch)
    fixed = {}
    for rule in ("equivalent", "lower-bound"):
        d = PAPER[rule]["d/l"] * L
        m = analyse(wcat(L, 2.924, d, weights=w))
        fixed[rule] = m
        print(row(f"replacement, {rule}", PAPER[rule], d / L, m.c1, m.c2, m.ap_min,
                  0.75 * g / m.p**2 / L, m.p))
    eq = rep.equivalent
    print(f"\nSect. 9 with this arch (d/l = 0.0346; Sect. 9 quotes d = 0.35 m with the same "
          f"ap,min): equivalent replacement d = {eq.thickness:.3f} m (paper "
          f"0.293), p = {eq.p:.3f} 1/s (paper 3.705), ap,min = {eq.ap_min:.3f} m/s² (paper "
          "3.036); with the paper's site ratio 1.351 the safe PGA would be "
          f"{1.351 * eq.ap_min:.3f} m/s² = {1.351 * eq.ap_min / g:.3f} g (paper 4.102 m/s² = "
          "0.418 g)")

    # Fig. 19: OAS of the arch (four-hinge mechanism) and of both replacement blocks
    p = np.linspace(1.0, 10.0, 37)
    ratio = np.linspace(1.0, 8.0, 57)
    fh = spectra.MechanismSystem(fourhinge_mechanism(arch))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), sharey=True)
    for ax, sig in zip(axes, ("sine", "square", "step"), strict=True):
        m = motion.pulse(sig, 1.0, 1.0)
        ax.plot(p, spectra.compute_oas(fh, m, p, ratio, progress=False).boundary.values, "k-",
                lw=1.6, label="circular arch, four-hinge mechanism")
        for r, style in ((rep.equivalent, "--"), (rep.lower_bound, ":")):
            blk = spectra.BlockSystem(alpha=math.atan(r.ap_min / g))
            b = spectra.compute_oas(blk, m, p, ratio, progress=False).boundary.values
            ax.plot(p, b, "b" + style, lw=1.4, label=f"block of the {r.rule} replacement")
        ax.set_title(f"{sig}, T = 1 s", fontsize=9)
        ax.set_xlabel("p [1/s]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(r"lowest overturning $a_p/a_{p,\min}$")
    axes[0].legend(fontsize=8)
    fig.suptitle("Paper Fig. 19: OAS of the circular arch (f/l = 0.289, d/l = 0.0346) and of "
                 "its replacement blocks", fontsize=10)
    fig.tight_layout()
    save_figure(fig, args.out / "fig19.png")
    print(f"\nwrote {args.out / 'fig19.png'}")


if __name__ == "__main__":
    main()
