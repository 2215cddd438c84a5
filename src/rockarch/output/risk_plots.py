"""Figure of a risk computation: the site's hazard curve, the structure's fragility and
their product, the deaggregation density of the annual frequency of collapse."""

from __future__ import annotations

import numpy as np

from rockarch.output.figures import subplots
from rockarch.risk.hazard import FragilityCurve, HazardCurve, RiskResult


def plot_risk(hazard: HazardCurve, frag: FragilityCurve, res: RiskResult, *,
              title: str | None = None):
    """Three panels over the IM (the hazard file's units, log scale): (a) the hazard
    curve H(x) [1/yr], its points and the power laws beyond them; (b) the fragility
    P(collapse | x); (c) their product, the deaggregation density P(x)·|dH/d ln x|
    [1/yr], whose area is λ_c (docs/theory.md Eqs. (11.36), (11.41)). Returns the
    figure."""
    f, units = hazard.factor, hazard.units
    x = res.im_grid
    lo, hi = min(x[0], hazard.x[0]), max(x[-1], hazard.x[-1])
    xs = np.geomspace(lo, hi, 400)
    fig, axes = subplots(3, 1, figsize=(6.4, 8.2), sharex=True)
    ax = axes[0]
    inside = (xs >= hazard.x[0]) & (xs <= hazard.x[-1])
    h = hazard.rate_at(xs)
    ax.plot(xs[inside] / f, h[inside], "k-", lw=1.2, label="hazard curve (log-log between "
            "points)")
    for part in (xs <= hazard.x[0], xs >= hazard.x[-1]):
        if part.sum() > 1:
            ax.plot(xs[part] / f, h[part], "k--", lw=1.0)
    ax.plot([], [], "k--", lw=1.0, label="power-law extrapolation")
    ax.plot(hazard.x / f, hazard.rate, "o", ms=3.5, color="k")
    ax.set_yscale("log")
    ax.set_ylabel("annual frequency of\nexceedance H [1/yr]")
    ax.legend(loc="lower left", fontsize=8)
    ax = axes[1]
    ax.plot(xs / f, frag.probability(xs), "C3-", lw=1.4,
            label=f"lognormal: median {frag.median / f:.3g} {units}, β = {frag.beta:.2f}")
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("P(collapse | IM)")
    ax.legend(loc="upper left", fontsize=8)
    ax = axes[2]
    ax.fill_between(x / f, res.density, color="C0", alpha=0.35, lw=0)
    ax.plot(x / f, res.density, "C0-", lw=1.2, label="P(collapse | IM)·|dH/d ln IM|")
    ax.axvline(res.median_im / f, color="0.3", lw=0.8, ls=":",
               label=f"half of λ_c below {res.median_im / f:.3g} {units}")
    ax.set_ylabel("deaggregation density\n[1/yr per unit of ln IM]")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", fontsize=8)
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlim(lo / f, hi / f)
    ax.set_xlabel(f"{hazard.label} [{units}]")
    for a in axes:
        a.grid(True, which="both", alpha=0.3)
    axes[0].set_title(title or f"λ_c = {res.annual_rate:.3g}/yr, P(collapse in "
                      f"{res.years:g} years) = {res.probability:.3g}", fontsize=10)
    return fig
