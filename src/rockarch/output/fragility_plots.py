"""Figure of a fragility: the lognormal curve, its bootstrap band and the records' points."""

from __future__ import annotations

import numpy as np

from rockarch.core.constants import G_STANDARD, g_label
from rockarch.output.figures import subplots
from rockarch.output.html import inline_figure, key_value_table
from rockarch.output.suite_plots import plot_spectra
from rockarch.risk.fragility import Fragility

#: Units of each intensity measure in g (the CLI's --im-range), by which it is divided.
DISPLAY = {"pga": ("PGA [g]", 1.0 / G_STANDARD), "sa": ("Sa(T) [g]", 1.0 / G_STANDARD),
           "pgv": ("PGV [m/s]", 1.0), "pga_norm": ("PGA/(g tan α) [-]", 1.0),
           "pgv_norm": ("PGV·p/(g tan α) [-]", 1.0)}
#: SI label of each intensity measure: the fragility figure's axis, as --json gives it.
SI_LABEL = {"pga": "PGA [m/s²]", "sa": "Sa(T) [m/s²]", "pgv": "PGV [m/s]",
            "pga_norm": "PGA/(g tan α) [-]", "pgv_norm": "PGV·p/(g tan α) [-]"}


def display_units(im: str) -> tuple[str, float]:
    """(label, factor SI → g) of an intensity measure (g for accelerations; the CLI's
    --im-range is given in them)."""
    return DISPLAY[im]


def plot_fragility(frag: Fragility, im_range=None):
    """Draw the fitted curve over ``im_range`` (SI units; default the records' range
    widened by 2 on each side), the bootstrap band if computed, the collapse points as an
    empirical distribution (plotting positions (i − 0.5)/n) and the censored records at
    their scan limit. Returns the figure."""
    r, fit, ci = frag.ida, frag.fit, frag.ci
    # the x axis in SI units (those of --json: m/s², m/s); accelerations also in g on top
    label, f = SI_LABEL[r.im], 1.0
    in_g = r.im in ("pga", "sa")
    x = r.im_collapse
    if im_range is None:
        known = np.concatenate([x[np.isfinite(x)], r.im_limit])
        im_range = (known.min() / 2, known.max() * 2)
    grid = np.geomspace(im_range[0], im_range[1], 300)
    fig, ax = subplots(figsize=(6.4, 4.6))
    if ci.get("im"):
        ax.fill_between(np.asarray(ci["im"]) * f, ci["probability_lo"],
                        ci["probability_hi"], color="#6a9fd4", alpha=0.3, lw=0,
                        label=f"{100 * ci['level']:g} % bootstrap band")
    if fit is not None:
        unit = label[label.index("[") + 1:-1]
        ax.plot(grid * f, fit.probability(grid), "k-",
                label=f"lognormal θ = {fit.median * f:.3g} {unit}, β = {fit.beta:.2f}")
    n = x.size
    order = np.sort(x[np.isfinite(x)])
    ax.plot(order * f, (np.arange(1, order.size + 1) - 0.5) / n, "o", ms=4, color="C3",
            label=f"collapse points ({order.size} of {n})")
    cens = r.im_limit[r.censored]
    if cens.size:
        ax.plot(cens * f, np.full(cens.size, 1.0), "^", ms=5, color="0.4", mfc="none",
                label=f"censored: safe up to scan limit ({cens.size})")
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlim(grid[0] * f, grid[-1] * f)
    ax.set_ylim(-0.02, 1.05)
    name = label if r.im != "sa" else f"Sa(T = {r.period:g} s) [m/s²]"
    ax.set_xlabel(name)
    ax.set_ylabel("P(collapse | IM) [-]")
    if in_g:
        top = ax.secondary_xaxis("top", functions=(lambda v: v / G_STANDARD,
                                                   lambda v: v * G_STANDARD))
        top.set_xscale("log")
        top.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        top.xaxis.set_major_formatter(ScalarFormatter())
        top.xaxis.set_minor_formatter(NullFormatter())
        top.set_xlabel(name.replace("[m/s²]", f"[{g_label(G_STANDARD)}]"), fontsize=9)
    ax.set_title(f"fragility of {r.system}, p = {r.p:g} 1/s ({n} records)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    return fig


def fragility_html(frag: Fragility, summary: dict, suite=None, *,
                   of: str = "the replacement") -> str:
    """HTML sections (figures inlined as base64 PNG) for the design report: the suite's
    response spectra (Sa/PGA, if ``suite`` is given), then the replacement's fragility:
    the curve with its band and points, θ, β and the probabilities of
    :func:`rockarch.risk.fragility.design_summary`; ``of`` names the structure in the title."""

    spectra = ""
    if suite is not None:
        spectra = ("<h2>Response spectra of the records</h2>\n"
                   f"{inline_figure(plot_spectra(suite), 'response spectra')}\n")

    rows = [("median PGA θ [m/s²]", f"{summary['median']:.3f}"),
            ("β", f"{summary['beta']:.3f}"),
            ("records (censored)", f"{summary['n_records']} ({summary['n_censored']})")]
    for key in ("probability_at_pga", "pga_at_probability"):
        if key in summary:
            d = summary[key]
            rows.append((f"P(collapse) = {d['probability']:.3g} at PGA [m/s²]",
                         f"{d['pga']:.3f}"))
    return (spectra + f"<h2>Fragility of {of} (IDA over the records)</h2>\n"
            f"{inline_figure(plot_fragility(frag), 'fragility')}\n"
            f"{key_value_table(rows)}\n<p>Lognormal fit by maximum likelihood (records "
            "that do not collapse within the scan are censored), docs/theory.md §11.3.</p>")
