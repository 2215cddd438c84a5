"""How coarse may the IDA scan of an MDOF assembly be? (docs/mdof.md, "The IDA scan of
assemblies")

The README's 20-voussoir catenary arch (span 10 m, rise 3 m, thickness 0.25 m) at its own p,
over the synthetic records of `rockarch records synth DIR --n N --seed 0`: the IDA of
:func:`rockarch.risk.fragility.ida` with the scan of the block (81 values of ap/ap,min
from 1 to 5, bisection to 0.001) as the reference, against coarser scans. For each: the
fragility median and β (lognormal fit, PGA), the records whose collapse point differs from
the reference by more than 1 % and by more than 3 % (the spread of one record's collapse
point when the step is halved, docs/mdof.md), the collapse → safe transitions above the
first collapse on the scan (resurrections: the islands a scan sees), and the time.

Run:  .venv/bin/python examples/mdof_ida_scan.py [--records 40] [--trilithon] [--scans ...]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import rockarch as ra
from rockarch.motion.synthetic import synthetic_motions
from rockarch.risk import fragility as fr

ARCH = {"shape": "catenary", "span": 10.0, "rise": 3.0, "thickness": 0.25, "blocks": 20}
TRILITHON = {"colonnade": 2, "block": [0.3, 2.0], "bay": 1.0, "lintel": 0.4, "friction": 0.6}
SCANS = "81:0.001,17:0.01:1:0.05,33:0.01,17:0.01,9:0.01"  # the second: the mdof default


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--records", type=int, default=10)
    ap.add_argument("--trilithon", action="store_true",
                    help="the trilithon of docs/assemblies.md (0.3 × 2 m columns, μ 0.6) "
                    "instead of the arch")
    ap.add_argument("--scans", default=SCANS,
                    help="VALUES:TOL[:ISLAND_STEP[:SEARCH_STEP]],...; the first is the "
                    "reference")
    args = ap.parse_args()
    scans = [[float(v) for v in item.split(":")] for item in args.scans.split(",")]
    motions = synthetic_motions(args.records, seed=0)
    sys_ = ra.system("mdof", **(TRILITHON if args.trilithon else ARCH))
    print(f"{sys_.name}, p = {sys_.p_ref:.4g} 1/s, {len(motions)} synthetic records (seed 0)")
    print("| scan (values, tol) | median [m/s²] | β | censored | collapse point moved "
          "> 1 % / > 3 % | resurrections | time [s] |")
    print("|---|---|---|---|---|---|---|")
    ref = None
    for steps, tol, *extra in scans:
        ratio = np.round(np.linspace(1.0, 5.0, int(steps)), 12)
        island = int(extra[0]) if extra else 1
        search = float(extra[1]) if len(extra) > 1 else 0.0
        t0 = time.perf_counter()
        res = fr.ida(sys_, motions, sys_.p_ref, ratio=ratio, tol=tol, island_step=island,
                     search_step=search)
        secs = time.perf_counter() - t0
        fit = fr.fit_ida(res, n_bootstrap=0).fit
        rc = res.ratio_collapse
        if ref is None:
            ref = rc
        both = np.isfinite(rc) & np.isfinite(ref)
        diff = np.where(both, np.abs(rc / np.where(both, ref, 1.0) - 1), np.inf)
        diff[np.isnan(rc) & np.isnan(ref)] = 0.0
        label = (f"{int(steps)}, {tol:g}" + (f", island step {island}" if island > 1 else "")
                 + (f", search step {search:g}" if search > 0 else ""))
        print(f"| {label} | {fit.median:.3f} | {fit.beta:.3f} | "
              f"{int(res.censored.sum())} | {int((diff > 0.01).sum())} / "
              f"{int((diff > 0.03).sum())} of {rc.size} | "
              f"{int(np.sum(res.resurrections))} | {secs:.0f} |", flush=True)


if __name__ == "__main__":
    main()
