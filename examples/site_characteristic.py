"""How well do the normalised and the simplified OAS predict computed record boundaries?

Computes the slender-block site OAS of every record given (the bundled El Centro pair and
the folders of ``--records``, de-duplicated, and a seeded synthetic suite), adds the
characteristic curves (rockarch.spectra.characteristic) and prints the skill numbers quoted in
docs/sites.md; writes the figure site_characteristic.png in ``--out``.

    .venv/bin/python examples/site_characteristic.py [--records DIR] [--synthetic 20] [--out DIR]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from rockarch.motion.records import bundled_record_path
from rockarch.motion.suite import read_suite
from rockarch.spectra import characteristic as charsite
from rockarch.spectra import site

P = np.round(np.geomspace(0.5, 10.0, 16), 6)
RATIO = np.round(np.linspace(1.0, 8.0, 71), 12)


def real_records(folders=()):
    """Bundled El Centro and the records of ``folders``, each motion once."""
    sources = [bundled_record_path(180), bundled_record_path(270), *folders]
    seen, out = set(), []
    for src in sources:
        suite = read_suite([src])
        for name, m in zip(suite.names, suite.motions, strict=True):
            if m.fingerprint() not in seen:
                seen.add(m.fingerprint())
                out.append((name, m))
    return out


def analyse(label, named, progress):
    names = [n for n, _ in named]
    motions = [m for _, m in named]
    ds = site.site_oas(motions, P, RATIO, tol=1e-2, progress=progress, executor=None)
    ds = charsite.characteristic(ds, motions)
    sk = charsite.skill(ds)
    sk.update(variants(ds))
    print(f"{label}: {len(motions)} records")
    print(json.dumps(sk, indent=1))
    return names, ds, sk


def variants(ds):
    """Skill of the simplified curve's parts: the no-impact branch alone, and the constant C
    of the after-impact branch that minimises the dispersion (for the record, not used)."""
    b = ds["boundary"].values
    ti, tm = ds["t_impulse"].values, ds["t_moment"].values
    alpha = float(ds.attrs["alpha"])
    only = np.maximum(1.0, np.stack([charsite.rectangular_pulse_boundary(P, t) for t in ti]))
    out = {"no_impact_branch_only": charsite.log_skill(b, only)}
    for label, t2 in (("best_C", tm), ("best_C_with_t_I", ti),
                      ("best_C_with_Tm", ds["tm"].values)):
        best = None
        for c in np.geomspace(0.05, 50, 61):
            pred = np.stack([np.maximum(1, np.minimum(
                charsite.rectangular_pulse_boundary(P, a), c * np.cos(alpha) / (P * m) ** 2))
                for a, m in zip(ti, t2, strict=True)])
            sk = charsite.log_skill(b, pred)
            if best is None or sk["dispersion"] < best[1]["dispersion"]:
                best = (c, sk)
        out[label] = {"C": float(best[0]), **best[1]}
    return out


def _log_axes(ax):
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(NullFormatter())


def figure(real, synth, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    names, ds, _ = real
    ax = axes[0]
    for k, name in enumerate(names):
        c = f"C{k}"
        ax.plot(P, ds["boundary"].values[k], "o-", color=c, ms=3, label=name[:24])
        ax.plot(P, ds["simplified_record"].values[k], "--", color=c)
    _log_axes(ax)
    ax.set(xlabel="p [1/s]", ylabel="ap/ap,min",
           title="real records: computed (o) and simplified (--)")
    ax.legend(fontsize=6)
    for ax, (lab, res) in zip(axes[1:], (("raw p", synth), ("p·Tm", synth)), strict=True):
        names, ds, _ = res
        tm = ds["tm"].values
        for k in range(len(names)):
            x = P if lab == "raw p" else P * tm[k]
            ax.plot(x, ds["boundary"].values[k], "-", color="0.6", lw=0.8)
        if lab == "p·Tm":
            ax.plot(ds["x"].values, ds["normalised_curve"].values, "k-", lw=2,
                    label="median (normalised curve)")
            ax.legend(fontsize=7)
        _log_axes(ax)
        ax.set(xlabel=lab, ylabel="ap/ap,min",
               title=f"synthetic suite ({len(names)}): boundaries over {lab}")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--synthetic", type=int, default=20, help="synthetic records")
    ap.add_argument("--records", type=Path, action="append", default=[],
                    help="a folder of more real records (repeatable)")
    ap.add_argument("--out", type=Path, default=Path("."))
    ap.add_argument("--progress", action="store_true")
    args = ap.parse_args()
    from rockarch.motion.synthetic import synthetic_motions

    real = analyse("real", real_records(args.records), args.progress)
    motions = synthetic_motions(args.synthetic, seed=0)
    synth = analyse("synthetic", [(f"synthetic-{k:03d}", m) for k, m in enumerate(motions)],
                    args.progress)
    figure(real, synth, args.out / "site_characteristic.png")


if __name__ == "__main__":
    main()
