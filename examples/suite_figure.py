"""Figure of docs/sites.md: intensity measures of real and synthetic suites.

(a) one synthetic record (Rezaeian & Der Kiureghian model) and its Husid function with the
D5-95 window; (b) 5 %-damped Sa/PGA of real records (``--records``) against the
median and 16-84 % band of a 50-record synthetic suite; (c) El Centro 180 ground velocity
and the Baker (2007) pulse extracted from it.

Run:  .venv/bin/python examples/suite_figure.py --records records/ --out suite_ims.png
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import rockarch as ra
from rockarch.core.constants import G_STANDARD
from rockarch.motion import intensity as im
from rockarch.motion.records import el_centro
from rockarch.motion.velocity_pulse import baker_pulse
from rockarch.output.figures import save_figure, subplots

PERIODS = np.geomspace(0.05, 5.0, 60)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("suite_ims.png"))
    ap.add_argument("--records", type=Path, default=None,
                    help="folder of real records (default: the bundled El Centro pair)")
    args = ap.parse_args()

    synth = ra.synthetic_suite(50, seed=1)
    real = ra.read_suite(args.records) if args.records else None
    real_motions = real.motions if real else [el_centro(180), el_centro(270)]
    real_names = real.names if real else ["El Centro 180", "El Centro 270"]

    fig, axes = subplots(1, 3, figsize=(15, 4.2))
    # (a) a synthetic record and its Husid function
    m = synth[0].motion
    ax = axes[0]
    ax.plot(m.t, np.asarray(m.a) / G_STANDARD, lw=0.5, color="0.3")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("a_g [g]")
    husid = im.husid_integral(m) / im.husid_integral(m)[-1]
    t05, t95 = np.interp([0.05, 0.95], husid, m.t)
    ax2 = ax.twinx()
    ax2.plot(m.t, husid, color="C3")
    ax2.axvspan(t05, t95, color="C3", alpha=0.1)
    ax2.set_ylabel("Husid function", color="C3")
    ax.set_title(f"(a) {synth.names[0]}: D5-95 = {t95 - t05:.1f} s")
    # (b) spectra
    ax = axes[1]
    sa = np.array([im.spectral_acceleration(x, PERIODS) / x.pga for x in synth.motions])
    lo, med, hi = np.percentile(sa, [16, 50, 84], axis=0)
    ax.fill_between(PERIODS, lo, hi, color="C0", alpha=0.2, label="synthetic 16-84 %")
    ax.plot(PERIODS, med, color="C0", label="synthetic median (50 records)")
    for k, (name, x) in enumerate(zip(real_names, real_motions, strict=True)):
        ax.plot(PERIODS, im.spectral_acceleration(x, PERIODS) / x.pga, lw=1,
                color=f"C{k + 1}", label=name[:28])
    ax.set_xscale("log")
    ax.set_xlabel("T [s]")
    ax.set_ylabel("Sa / PGA (5 % damping)")
    ax.legend(fontsize=7)
    ax.set_title("(b) normalised response spectra")
    # (c) Baker pulse
    ax = axes[2]
    x = el_centro(180)
    res = baker_pulse(x)
    t, v = im.velocity(x)
    ax.plot(t, v, color="0.3", lw=0.8, label="ground velocity")
    ax.plot(res.t, res.pulse, color="C1", label=f"extracted pulse, Tp = {res.tp:.2f} s")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("v [m/s]")
    ax.legend(fontsize=8)
    ax.set_title(f"(c) El Centro 180: PI = {res.pulse_indicator:.2f}, "
                 f"{'late, ' if res.late else ''}{res.classification}")
    fig.tight_layout()
    save_figure(fig, args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
