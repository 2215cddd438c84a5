"""``rockarch risk``: the annual frequency of collapse of a structure at a site, from the
site's hazard curve and the structure's fragility (docs/theory.md Sect. 11.5)."""

from __future__ import annotations

import math
from pathlib import Path

import typer

from rockarch.cli import _common as cc
from rockarch.cli._app import app
from rockarch.cli._common import guarded
from rockarch.cli._groups import SWEEP, SYSTEM, Group, given, options
from rockarch.cli.fragility import IDA, run_ida
from rockarch.core.constants import standard_g
from rockarch.output import check_outputs
from rockarch.output.tables import unit_label
from rockarch.risk import fragility as fr
from rockarch.risk import hazard as hz

HAZARD_OPT = typer.Option(..., "--hazard", help="The site's hazard curve: a two-column CSV "
                          "(header 'PGA [g]', 'Sa(0.5) [m/s2]' or 'PGV [m/s]', then "
                          "'annual frequency of exceedance [1/yr]') or an OpenQuake "
                          "hazard-curve CSV (hazard_curve-mean-PGA.csv).")
SITE_ROW_OPT = typer.Option(None, help="OpenQuake file with several sites: the row (0, 1, "
                            "...) of the site.")
YEARS_OPT = typer.Option(50.0, help="N: the probability of collapse in N years, "
                         "1 - exp(-lambda_c N).")
EXTRAPOLATE_OPT = typer.Option(False, "--extrapolate", help="Accept a hazard curve that "
                               "does not cover the fragility: extrapolate its end segments "
                               "as power laws (the share of lambda_c from there is "
                               "reported).")

#: The options of the risk at a site that `risk` and `design --hazard` share.
RISK: Group = (("years", float, YEARS_OPT), ("site_row", int, SITE_ROW_OPT),
               ("extrapolate", bool, EXTRAPOLATE_OPT))

#: Deaggregation bins shown in the text output: those holding at least this share.
SHOW_SHARE = 0.01


def hazard_of(path: Path, site_row: int | None):
    """The hazard curve of --hazard (and --site-row), its notes printed as warnings."""
    if site_row is not None and site_row < 0:
        raise ValueError(f"--site-row must be >= 0, got {site_row}")
    curve = hz.read_hazard(path, site_row=site_row)
    for note in curve.notes:
        cc.echo_err(f"warning: {path}: {note}")
    return curve


def check_years(years: float) -> float:
    """--years: a finite number > 0."""
    if not (math.isfinite(years) and years > 0):
        raise ValueError(f"--years must be a finite number > 0, got {years}")
    return years


@app.command(short_help="Annual frequency and probability of collapse at a site "
             "(hazard curve x fragility).")
@guarded
@options(RISK, SYSTEM, IDA, before="plot")
@options(SWEEP)
def risk(
    ctx: typer.Context,
    hazard: Path = HAZARD_OPT,
    fragility: Path = typer.Option(None, "--fragility", help="The fragility: the JSON of "
                                   "`rockarch fragility --json` in the hazard's IM; or, "
                                   "instead, the fragility options inline (--system ... --p "
                                   "--records: the IDA runs in the hazard curve's IM)."),
    plot: Path = typer.Option(None, help="Write a PNG of the hazard curve, the fragility and "
                              "their product (the deaggregation density)."),
    json_out: bool = cc.JSON_OPT,
    **opts,
) -> None:
    """Mean annual frequency of collapse lambda_c = integral of P(collapse | im) |dH(im)|
    (docs/theory.md Eq. (11.36)), the probability of collapse in --years N,
    1 - exp(-lambda_c N), and the IM levels that contribute most (deaggregation)."""
    years, extrapolate = check_years(opts["years"]), opts["extrapolate"]
    check_outputs((plot, "--plot", "png"))
    curve = hazard_of(hazard, opts["site_row"])
    ask = ("give the fragility: either --fragility FRAG.json (rockarch fragility --json) "
           "or its options inline (--system ... --p P --records DIR), not both")
    if fragility is None and opts["p"] is None and not opts["records"]:
        raise ValueError(ask)
    inline = given(ctx, opts, SYSTEM, IDA, SWEEP)
    if fragility is not None and inline:
        # a fragility file holds its structure and scan: no option of either applies
        raise ValueError(f"{ask} ({', '.join(inline)} given with --fragility)")
    if fragility is not None:
        frag = hz.read_fragility(fragility)
        described = f"{fragility}"
    else:
        res, _ = run_ida(opts, curve.im, curve.period)
        fit = fr.fit_ida(res, n_bootstrap=0).fit
        frag = hz.fragility_curve(curve.im, fit.median, fit.beta, curve.period, res.system)
        described = (f"{res.system} at p = {res.p:g} 1/s over {len(res.records)} records "
                     f"({fit.n_censored} censored)")
    result = hz.collapse_rate(curve, frag, years=years, extrapolate=extrapolate)
    if result.extrapolated:
        cc.echo_err(f"warning: {100 * result.extrapolated_share:.1f} % of lambda_c rests on "
                    "the extrapolation of the hazard curve beyond its ends; without it "
                    f"lambda_c >= {result.lower_bound:.3g}/yr")
    if plot is not None:
        from rockarch.output.figures import save_figure
        from rockarch.output.risk_plots import plot_risk
        save_figure(plot_risk(curve, frag, result), plot)
    f, units = curve.factor, curve.units
    if json_out:
        cc.print_json({**result.to_dict(f, units), "hazard": _hazard_dict(curve),
                       "fragility": {"source": described, "im": frag.im,
                                     "period": frag.period, "median": frag.median,
                                     "beta": frag.beta,
                                     "units": fr.IM_UNITS[frag.im]}})
        return
    print_risk(curve, frag, result, described)
    if plot is not None:
        typer.echo(f"wrote {plot}")


def _hazard_dict(curve) -> dict:
    return {"source": curve.source, "im": curve.im, "period": curve.period,
            "units": curve.units, "levels": len(curve.x), "im_min": curve.x[0] / curve.factor,
            "im_max": curve.x[-1] / curve.factor,
            "investigation_time": curve.investigation_time, "site": curve.site}


def print_risk(curve, frag, result, described: str) -> None:
    """The text output of ``rockarch risk`` (and ``design --hazard``)."""
    f, units, name = curve.factor, unit_label(curve.units), curve.label
    how = ("annual rates" if curve.investigation_time is None else
           f"OpenQuake poe in {curve.investigation_time:g} years -> rates")
    std = standard_g(curve.units)  # which g the values in g divide by
    typer.echo(f"hazard: {Path(curve.source).name}: {name} {curve.x[0] / f:.4g} … "
               f"{curve.x[-1] / f:.4g} {units}{f' ({std})' if std else ''}, "
               f"{len(curve.x)} levels ({how})")
    typer.echo(f"fragility: {described}: median {name} {frag.median / f:.4g} {units}, "
               f"beta {frag.beta:.3f}")
    typer.echo(f"annual frequency of collapse: {result.annual_rate:.3g} /yr (return period "
               f"{1 / result.annual_rate:.4g} years)")
    typer.echo(f"probability of collapse in {result.years:g} years: {result.probability:.3g}")
    typer.echo(f"deaggregation by {name} [{units}] (bins with >= {100 * SHOW_SHARE:g} % of "
               "lambda_c):")
    bins = [float(f"{v:.12g}") for v in result.im_bins / f]
    shown = 0.0
    for a, b, s in zip(bins[:-1], bins[1:], result.shares, strict=True):
        if s >= SHOW_SHARE:
            typer.echo(f"  {a:>8.4g} … {b:<8.4g} {100 * s:5.1f} %")
            shown += s
    typer.echo(f"  other bins {100 * (1 - shown):5.1f} %")
    share = 100 * result.extrapolated_share
    typer.echo(f"largest contribution at {name} {result.mode / f:.3g} {units}; half of "
               f"lambda_c below {result.median_im / f:.3g} {units}; "
               + ("< 0.01" if share < 0.01 else f"{share:.2g}")
               + " % of it rests on the curve's extrapolation")
