"""The demo job (`make demo`): the paper's Sect. 9 design check on bundled data.

1. the OAS of a slender block for the bundled El Centro 1940 record and the paper's pulses;
2. a site OAS from the two bundled El Centro components;
3. the design check of the Sect. 9 circular arch (l = 10 m, f/l = 0.289, d = 0.35 m):
   replacement catenary arch, p and ap,min, the largest safe PGA, an HTML report.

Run:  .venv/bin/python examples/demo.py --out demo-output
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from rockarch import systems
from rockarch.arch import analyse, circular
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro
from rockarch.output.arch_plots import plot_mechanism
from rockarch.output.figures import plot_oas, plot_response, save_figure, subplots
from rockarch.paper import results as paper
from rockarch.rocking.block import RigidBlock, simulate
from rockarch.spectra import oas as spectra

ALPHA = 0.1  # slender block (B/H ≈ 0.1): the OAS of slender blocks hardly depend on alpha


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("demo-output"))
    ap.add_argument("--n", type=int, default=100, help="grid points per axis")
    args = ap.parse_args()
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# rockarch demo report", "",
             f"Command: `python examples/demo.py --out {out} --n {args.n}`", ""]

    rec = el_centro()
    system = systems.BlockSystem(alpha=ALPHA)
    p = np.linspace(0.5, 10.0, args.n)
    ratio = np.linspace(1.0, 5.0, args.n)
    t0 = time.perf_counter()
    ds = spectra.compute_oas(system, rec, p, ratio)
    dt = time.perf_counter() - t0
    spectra.save(ds, out / "oas_elcentro.nc")
    ax = plot_oas(ds, title=f"OAS, slender block (alpha = {ALPHA} rad), El Centro 1940 180° "
                  "(PEER RSN6)")
    save_figure(ax.figure, out / "oas_elcentro.png")
    lines += ["## OAS of a slender block, El Centro 1940 (PEER NGA-West2 RSN6, 180°)", "",
              f"{args.n} x {args.n} grid, p = 0.5…10 1/s, ap/ap,min = 1…5, computed in "
              f"{dt:.1f} s. Files: `oas_elcentro.png`, `oas_elcentro.nc`.", "",
              "| p [1/s] | lowest overturning ap/ap,min |", "|---|---|"]
    for pv in (1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0):
        i = int(np.argmin(np.abs(p - pv)))
        b = ds.boundary.values[i]
        lines.append(f"| {p[i]:.2f} | {b:.3f} |" if np.isfinite(b) else
                     f"| {p[i]:.2f} | > {ratio[-1]:g} |")
    lines.append("")

    fig, axes = subplots(1, 3, figsize=(15, 4.4))
    lines += ["## OAS for the paper's pulses (Fig. 14), T = 1 s", "",
              "File: `oas_pulses.png`.", ""]
    for axi, sig in zip(axes, ("sine", "square", "step"), strict=True):
        dsp = spectra.compute_oas(system, motion.pulse(sig, period=1.0),
                                  np.linspace(0.5, 10.0, args.n // 2),
                                  np.linspace(1.0, 8.0, args.n))
        plot_oas(dsp, ax=axi, title=f"{sig}, T = 1 s, alpha = {ALPHA}")
    save_figure(fig, out / "oas_pulses.png")

    blk = RigidBlock.from_dimensions(0.25, 2.5)
    mot = rec.scaled_to_pga(1.6 * blk.ap_min)
    resp = simulate(blk, mot)
    save_figure(plot_response(resp, mot), out / "block_elcentro.png")
    s = resp.to_dict()
    lines += ["## One time history", "",
              f"Block B = 0.25 m, H = 2.5 m (p = {blk.p:.3f} 1/s, alpha = {blk.alpha:.4f} rad,"
              f" ap,min = {blk.ap_min:.3f} m/s²), El Centro scaled to PGA = 1.6 ap,min: "
              + (f"overturns at t = {s['t_overturn']:.2f} s" if s["overturned"] else
                 f"safe, max |theta|/alpha = {s['max_theta_over_alpha']:.3f}")
              + f", {s['impacts']} impacts. File: `block_elcentro.png`.", ""]
    # site OAS of the bundled records and the Sect. 9 design check
    plot_mechanism(analyse(circular(10.0, 2.89, 0.35)), out / "arch_sect9.png")
    d = paper.sect9(out, n_p=args.n)
    lines += ["## Design check of the paper's Sect. 9 arch", "",
              "Circular arch l = 10 m, f = 2.89 m (f/l = 0.289), d = 0.35 m; site OAS of the two "
              "bundled El Centro 1940 components (slender block, alpha = 0.05), envelope.", "",
              f"- replacement catenary (equivalent thickness): d = {d['thickness']:.3f} m, "
              f"f = {d['rise']:.3f} m, p = {d['p']:.3f} 1/s, ap,min = {d['ap_min']:.3f} m/s² "
              "(paper: d = 0.293 m, f = 2.924 m, p = 3.705 1/s, ap,min = 3.036 m/s²)",
              f"- site envelope at p: ap/ap,min = {d['ratio']:.3f}"
              + (f" (the records' first collapses at p, collapse islands searched; the site "
                 f"OAS grid reads {d['ratio_grid']:.3f})" if d["ratio"] < d["ratio_grid"]
                 else ""),
              f"- **largest safe PGA: {d['pga_safe']:.3f} m/s² = {d['pga_safe_g']:.3f} g** "
              "(the paper's unspecified site gave 0.418 g)", "",
              "Files: `site.nc`, `arch_sect9.png`, `design_report.html` (self-contained).", "",
              f"Rerun the check alone: `{d['command']}`", ""]
    (out / "report.md").write_text("\n".join(lines))
    print("\n".join(lines))
    print(f"\nwrote {out}/report.md and its figures")


if __name__ == "__main__":
    main()
