"""Figure of a risk computation: the site's hazard curve, the structure's fragility and
their product, the deaggregation density of the annual frequency of collapse."""

from __future__ import annotations

import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from rockarch.core.constants import standard_g
from rockarch.output.figures import subplots
from rockarch.output.tables import unit_label
from rockarch.risk.hazard import FragilityCurve, HazardCurve, RiskResult

#: Standard normal quantile of 0.999: the fragility is drawn from P = 0.001 to 0.999.
Z_999 = 3.090232306167813
#: Share of λ_c left out at each end of the range where the integrand matters.
TAIL_SHARE = 1e-3
#: The hazard curve's own points are shown at most this factor beyond that range.
CURVE_MARGIN = 10.0


def im_range(hazard: HazardCurve, frag: FragilityCurve, res: RiskResult
             ) -> tuple[float, float]:
    """The x range [SI units] of :func:`plot_risk`.

    Rule: the integrand matters from ``a`` to ``b``, the wider of the fragility's range
    P = 0.001 … 0.999 (median·exp(∓3.09 β)) and the IM levels holding all of λ_c but
    0.1 % at each end; the range is [a, b] widened to the hazard curve's first and last
    points, but to no more than a factor :data:`CURVE_MARGIN` beyond ``a`` and ``b``
    (a curve's levels far from the fragility neither matter nor leave the range readable).

    Parameters
    ----------
    hazard, frag, res : the curve, the fragility and their :func:`collapse_rate`.

    Returns
    -------
    (lo, hi) : IM bounds in SI units, lo < hi.
    """
    lx = np.log(res.im_grid)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (res.density[1:] + res.density[:-1])
                                           * np.diff(lx))])
    a = frag.median * np.exp(-Z_999 * frag.beta)
    b = frag.median * np.exp(Z_999 * frag.beta)
    if cum[-1] > 0:
        cum /= cum[-1]
        a = min(a, float(np.exp(np.interp(TAIL_SHARE, cum, lx))))
        b = max(b, float(np.exp(np.interp(1.0 - TAIL_SHARE, cum, lx))))
    lo = max(min(hazard.x[0], a), a / CURVE_MARGIN)
    hi = min(max(hazard.x[-1], b), b * CURVE_MARGIN)
    return float(lo), float(hi)


def _im_ticks(ax, lo: float, hi: float) -> None:
    """Log ticks on the x axis of [lo, hi] that do not overlap: 1-2-5 in each decade over
    up to 3 decades, powers of 10 (at most 8 labelled) over more; labels as plain
    numbers (0.05, 2, 100)."""
    decades = np.log10(hi / lo)
    subs = (1.0, 2.0, 5.0) if decades <= 3 else (1.0,)
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=subs, numticks=9))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())


def plot_risk(hazard: HazardCurve, frag: FragilityCurve, res: RiskResult, *,
              title: str | None = None):
    """Three panels over the IM (the hazard file's units, log scale): (a) the hazard
    curve H(x) [1/yr], its points and the power laws beyond them; (b) the fragility
    P(collapse | x); (c) their product, the deaggregation density P(x)·|dH/d ln x|
    [1/yr], whose area is λ_c (docs/theory.md Eqs. (11.36), (11.41)). Returns the
    figure."""
    f, units = hazard.factor, unit_label(hazard.units)
    x = res.im_grid
    lo, hi = im_range(hazard, frag, res)
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
    _im_ticks(ax, lo / f, hi / f)
    ax.set_xlim(lo / f, hi / f)
    ax.set_xlabel(f"{hazard.label} [{standard_g(hazard.units) or units}]")
    for a in axes:
        a.grid(True, which="both", alpha=0.3)
    axes[0].set_title(title or f"λ_c = {res.annual_rate:.3g}/yr, P(collapse in "
                      f"{res.years:g} years) = {res.probability:.3g}", fontsize=10)
    return fig
