"""``rockarch site-oas`` and ``rockarch design``: a site's OAS and the paper's design check."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from rockarch import charsite
from rockarch import fragility as fr
from rockarch import site as site_mod
from rockarch._validate import positive
from rockarch.arch.geometry import make_arch
from rockarch.arch.replacement import RULES
from rockarch.charsite import characteristic
from rockarch.cli._app import app
from rockarch.cli._common import (
    ARCH_RISE_OPT,
    ARCH_SHAPE_OPT,
    ARCH_SPAN_OPT,
    ARCH_THICK_OPT,
    DASK_WORKERS_OPT,
    G_OPT,
    JSON_OPT,
    NO_STORE_OPT,
    SCHEDULER_OPT,
    STORE_OPT,
    TFREE_OPT,
    TOL_OPT,
    WORKERS_OPT,
    Shape,
    echo_err,
    guarded,
    p_grid,
    print_json,
    ratio_grid,
)
from rockarch.cli._sweep import open_sweep
from rockarch.design import design_check
from rockarch.output import check_outputs, staged
from rockarch.output.figures import plot_site, save_figure
from rockarch.output.fragility_plots import fragility_html
from rockarch.output.report import write_report
from rockarch.suite import read_suite


@app.command("site-oas", short_help="Site OAS of a set of records: envelope and percentile.")
@guarded
def site_oas(
    records: list[Path] = typer.Option(None, "--records", help="Record files (.AT2 or "
                                       "two-column) or folders of .AT2; several may follow "
                                       "one --records."),
    more: list[Path] = typer.Argument(None, hidden=True),
    units: str = typer.Option(None, help="Units of two-column records: m/s2, g, cm/s2."),
    p_min: float = typer.Option(0.5, help="Smallest p [1/s]."),
    p_max: float = typer.Option(10.0, help="Largest p [1/s]."),
    p_steps: int = typer.Option(100, help="Number of p values."),
    ratio_min: float = typer.Option(1.0, help="Smallest ap/ap,min."),
    ratio_max: float = typer.Option(5.0, help="Largest ap/ap,min."),
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values (at least 2)."),
    alpha: float = typer.Option(site_mod.ALPHA, help="Slenderness of the site's block [rad]."),
    percentile: float = typer.Option(50.0, help="Percentile of the records' boundaries "
                                     "stored as the characteristic curve (lower: safer)."),
    tol: float = TOL_OPT, t_free: float = TFREE_OPT,
    out: Path = typer.Option(..., help="NetCDF file to write."),
    plot: Path = typer.Option(None, help="PNG of the records' OAS boundaries and curves."),
    json_out: bool = JSON_OPT,
    workers: int = WORKERS_OPT, scheduler: str = SCHEDULER_OPT,
    dask_workers: int = DASK_WORKERS_OPT, store: Path = STORE_OPT, no_store: bool = NO_STORE_OPT,
) -> None:
    """Site OAS: slender-block OAS of every record, their envelope and percentile curve."""
    paths = list(records or []) + list(more or [])
    check_outputs((out, "--out", "netcdf"), (plot, "--plot", "png"))
    motions, hashes = site_mod.load_records(paths, units)
    ps = p_grid(None, p_min, p_max, p_steps)
    if ratio_steps < 2:
        raise ValueError("--ratio-steps must be >= 2 for a site OAS")
    ratios = ratio_grid(ratio_min, ratio_max, ratio_steps)
    with open_sweep(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                    store_dir=store, no_store=no_store,
                    n_sims=ps.size * ratios.size * len(motions),
                    echo=echo_err) as (executor, chunk_store):
        ds = site_mod.site_oas(motions, ps, ratios, alpha=alpha, percentile=percentile,
                               tol=tol, hashes=hashes, t_free=t_free,
                               progress=sys.stderr.isatty(), executor=executor,
                               store=chunk_store)

    ds = characteristic(ds, motions)  # normalised and simplified curves (design --curve)
    with staged(out, plot) as (out_tmp, plot_tmp):
        site_mod.save(ds, out_tmp)
        if plot is not None:
            save_figure(plot_site(ds), plot_tmp)
    if json_out:
        print_json({"records": list(ds["record_name"].values), "p": ds["p"].values,
                    "envelope": ds["envelope"].values,
                    "characteristic": ds["characteristic"].values, "out": str(out)})
        return
    typer.echo(f"site OAS of {len(motions)} record(s) written to {out}")
    for path in ([plot] if plot else []):
        typer.echo(f"wrote {path}")


@app.command(short_help="Largest safe PGA of an arch at a site (paper Sect 9 method).")
@guarded
def design(
    shape: Shape = ARCH_SHAPE_OPT, span: float = ARCH_SPAN_OPT, rise: float = ARCH_RISE_OPT,
    thickness: float = ARCH_THICK_OPT,
    site_file: Path = typer.Option(None, "--site", help="Site OAS file (rockarch site-oas)."),
    records: list[Path] = typer.Option(None, "--records", help="Instead of --site: records "
                                       "(folder or files); the site OAS, its characteristic "
                                       "curves and the replacement's fragility are computed "
                                       "(and kept in the store) on the fly."),
    pga: float = typer.Option(None, help="With --records: probability of collapse at this "
                              "PGA [m/s²]."),
    probability: float = typer.Option(0.1, help="With --records: the PGA at this "
                                      "probability of collapse."),
    save_site: Path = typer.Option(None, help="With --records: also write the site OAS "
                                   "computed on the fly (NetCDF, reusable as --site)."),
    thickness_rule: str = typer.Option("equivalent", help="Replacement catenary thickness: "
                                       "equivalent (same ap,min) or lower-bound."),
    curve: str = typer.Option("envelope", help="Site curve: envelope, characteristic "
                              "(percentile), normalised (over p·Tm) or simplified (two "
                              "durations)."),
    replacement_axis: str = typer.Option("catenary", help="Replacement axis: catenary "
                                         "(uniform mass) or weighted (the funicular of the "
                                         "arch's own mass)."),
    replacement_mass: str = typer.Option("own", help="Replacement mass: own (its uniform "
                                         "mass) or original (the arch's mass on its axis)."),
    g: float = G_OPT,
    report: Path = typer.Option(None, help="Write a self-contained HTML report."),
    workers: int = WORKERS_OPT, scheduler: str = SCHEDULER_OPT,
    dask_workers: int = DASK_WORKERS_OPT, store: Path = STORE_OPT,
    no_store: bool = NO_STORE_OPT,
    json_out: bool = JSON_OPT,
) -> None:
    """Largest safe PGA of an arch at a site (paper Sect. 9): replacement catenary, site OAS.

    With --records the site OAS is computed on the sweep executor and store (the sweep
    options as in oas)."""
    if thickness_rule not in RULES:
        raise ValueError(f"--thickness-rule must be {' or '.join(RULES)}, got "
                         f"{thickness_rule!r}")
    check_outputs((report, "--report", "html"), (save_site, "--save-site", "netcdf"))
    if (site_file is None) == (not records):
        raise ValueError("give either --site FILE or --records DIR")
    if save_site is not None and not records:
        raise ValueError("--save-site goes with --records (the site OAS computed on the fly)")
    if records:
        suite = read_suite(records)
        n_sims = charsite.DESIGN_P.size * charsite.DESIGN_RATIO.size * len(suite)
        with open_sweep(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                        store_dir=store, no_store=no_store, n_sims=n_sims,
                        echo=echo_err) as (executor, chunk_store):
            site_ds = charsite.site_from_records(suite, executor=executor, store=chunk_store,
                                                progress=sys.stderr.isatty())
        if save_site is not None:
            site_mod.save(site_ds, save_site)
    else:
        site_ds = site_mod.load(site_file)
    arch = make_arch(shape.value, positive("--span", span), positive("--rise", rise),
                     positive("--thickness", thickness))
    res = design_check(arch, site_ds, rule=thickness_rule, curve=curve, g=g,
                       axis=replacement_axis, mass=replacement_mass)
    if res.ratio_is_lower_bound:
        echo_err("warning: no record overturns the equivalent block within the site's ratio "
                 "range; the result is a lower bound")
    extra, html_extra = {}, ""
    if records:
        frag = fr.site_fragility(suite.motions, res.chosen.p, res.chosen.ap_min,
                                 alpha=float(site_ds.attrs["alpha"]), names=suite.names,
                                 ratio=site_ds["ratio"].values)
        extra["fragility"] = fr.design_summary(frag, pga=pga, probability=probability, g=g)
        if report is not None:
            html_extra = fragility_html(frag, extra["fragility"], suite)
    if report is not None:
        cmd = (f"rockarch design --shape {shape.value} --span {span:g} --rise {rise:g} "
               f"--thickness {thickness:g} "
               + (f"--site {site_file}" if site_file else
                  " ".join(f"--records {r}" for r in records))
               + f" --thickness-rule {thickness_rule} --curve {curve} --replacement-axis "
               f"{replacement_axis} --replacement-mass {replacement_mass} --g {g:g}")
        write_report(res, site_ds, report, command=cmd,
                     site_path=str(site_file) if site_file else None, extra_html=html_extra,
                     inputs={"shape": shape.value, "span [m]": span, "rise [m]": rise,
                             "thickness [m]": thickness})
    if json_out:
        print_json({**res.to_dict(), **extra})
        return
    c = res.chosen
    typer.echo(f"{shape.value} arch l = {span:g} m, f = {rise:g} m, d = {thickness:g} m: "
               f"ap,min = {res.replacement.original.ap_min:.4f} m/s²")
    typer.echo(f"replacement catenary ({thickness_rule}): d = {c.thickness:.4f} m "
               f"(d/l' = {c.thickness / c.span:.4f}, d/l = {c.thickness / span:.4f}), "
               f"l' = {c.span:.4f} m, f' = {c.rise:.4f} m, p = {c.p:.4f} 1/s, "
               f"ap,min = {c.ap_min:.4f} m/s²")
    typer.echo(f"site {curve} at p: ap/ap,min = {res.ratio:.4f} -> safe PGA "
               f"{res.pga_safe:.3f} m/s² = {res.pga_safe / g:.3f} g")
    if extra:
        f = extra["fragility"]
        typer.echo(f"fragility of the replacement over {f['n_records']} records: median PGA "
                   f"{f['median']:.3f} m/s², beta {f['beta']:.3f}")
        for key in ("probability_at_pga", "pga_at_probability"):
            if key in f:
                typer.echo(f"  P(collapse) = {f[key]['probability']:.3g} at PGA "
                           f"{f[key]['pga']:.3f} m/s²")
    if report is not None:
        typer.echo(f"wrote {report}")


