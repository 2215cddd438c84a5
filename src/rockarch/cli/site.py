"""``rockarch site-oas`` and ``rockarch design``: a site's OAS and the paper's design check."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import typer

from rockarch.arch.geometry import make_arch
from rockarch.arch.replacement import RULES, replacement
from rockarch.cli._app import app
from rockarch.cli._common import (
    DT_OPT,
    G_OPT,
    IDA_STEPS_OPT,
    IDA_TOL_OPT,
    JSON_OPT,
    TFREE_OPT,
    TOL_OPT,
    System,
    check_suite_units,
    echo_err,
    guarded,
    mdof_structure,
    p_grid,
    print_json,
    ratio_grid,
    read_records,
    stage_echo,
    value,
)
from rockarch.cli._groups import (
    MDOF,
    STEP,
    STRUCTURE,
    SWEEP,
    SYSTEM,
    options,
    sweep_options,
    system_of,
    typed,
)
from rockarch.cli._sweep import open_sweep
from rockarch.cli.fragility import SEARCH_HELP, _print_table, ida_scan, ida_sweep_options
from rockarch.cli.risk import RISK, check_years, hazard_of
from rockarch.core.constants import g_label, standard_g
from rockarch.core.validate import in_range, positive
from rockarch.design import design_check, design_system, site_risk, smallest_thickness
from rockarch.output import check_outputs, staged
from rockarch.risk import fragility as fr
from rockarch.risk.record_scan import SEARCH_STEP
from rockarch.spectra import characteristic as charsite
from rockarch.spectra import site as site_mod
from rockarch.spectra.characteristic import characteristic
from rockarch.systems import system as make_system


@app.command("site-oas", short_help="Site OAS of a set of records: envelope and percentile.")
@guarded
@options(SYSTEM, before="percentile")
@options(SWEEP)
def site_oas(
    records: list[Path] = typer.Option(None, "--records", help="Record files (.AT2, "
                                       ".ASC, K-NET, .V2c, two-column, or single-column with "
                                       "--dt) or folders of them; several may follow one "
                                       "--records."),
    more: list[Path] = typer.Argument(None, hidden=True),
    units: str = typer.Option(None, help="Units of two-column or single-column records: "
                              "m/s2, g, cm/s2."),
    dt: float = DT_OPT,
    p_min: float = typer.Option(0.5, help="Smallest p [1/s]."),
    p_max: float = typer.Option(10.0, help="Largest p [1/s]."),
    p_steps: int = typer.Option(100, help="Number of p values."),
    ratio_min: float = typer.Option(1.0, help="Smallest ap/ap,min."),
    ratio_max: float = typer.Option(5.0, help="Largest ap/ap,min."),
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values (at least 2)."),
    percentile: float = typer.Option(50.0, help="Percentile of the records' boundaries "
                                     "stored as the characteristic curve (lower: safer)."),
    tol: float = TOL_OPT,
    out: Path = typer.Option(..., help="NetCDF file to write."),
    plot: Path = typer.Option(None, help="PNG of the records' OAS boundaries and curves."),
    json_out: bool = JSON_OPT,
    **opts,
) -> None:
    """Site OAS: the OAS of a structure (default the slender block of --alpha, default
    0.05) for every record, their envelope and percentile curve. For any other --system the
    p axis is that of `rockarch oas`: the structure of the given shape scaled to each p
    (size ∝ 1/p²)."""
    paths = list(records or []) + list(more or [])
    is_block = opts["system"].value == "block"
    if is_block and opts["alpha"] is None:
        opts["alpha"] = site_mod.ALPHA
    sysobj = system_of(opts)
    check_outputs((out, "--out", "netcdf"), (plot, "--plot", "png"))
    check_suite_units(paths, units, dt)
    motions, hashes = site_mod.load_records(paths, units,
                                            log=lambda note: echo_err(f"warning: {note}"),
                                            dt=dt)
    ps = p_grid(None, p_min, p_max, p_steps)
    if ratio_steps < 2:
        raise ValueError("--ratio-steps must be >= 2 for a site OAS")
    ratios = ratio_grid(ratio_min, ratio_max, ratio_steps)
    with open_sweep(**sweep_options(opts), n_sims=ps.size * ratios.size * len(motions),
                    echo=echo_err) as (executor, chunk_store):
        ds = site_mod.site_oas(motions, ps, ratios, system=sysobj, percentile=percentile,
                               tol=tol, hashes=hashes, progress=sys.stderr.isatty(),
                               executor=executor, store=chunk_store, log=stage_echo())

    ds = characteristic(ds, motions)  # normalised and simplified curves (design --curve)
    with staged(out, plot) as (out_tmp, plot_tmp):
        site_mod.save(ds, out_tmp)
        if plot is not None:
            from rockarch.output.figures import plot_site, save_figure
            save_figure(plot_site(ds), plot_tmp)
    axis = {} if is_block else {"system": sysobj.name, "p_structure": sysobj.p_ref,
                                "ap_min": sysobj.ap_min}
    if json_out:
        print_json({"records": list(ds["record_name"].values), "p": ds["p"].values,
                    "envelope": ds["envelope"].values,
                    "characteristic": ds["characteristic"].values, "out": str(out), **axis})
        return
    typer.echo(f"site OAS of {len(motions)} record(s) written to {out}")
    if axis:
        typer.echo(f"{sysobj.name}: ap,min = {sysobj.ap_min:.4g} m/s²; p axis: the structure "
                   f"scaled to each p (size ∝ 1/p²), as given it has p = {sysobj.p_ref:.4g} "
                   "1/s")
    for path in ([plot] if plot else []):
        typer.echo(f"wrote {path}")


@app.command(short_help="Largest safe PGA of an arch (paper Sect 9 method) or of any "
             "--system at a site.")
@guarded
@options(MDOF + STEP, before="system")
@options(RISK, before="save_site")
@options(SWEEP)
def design(
    ctx: typer.Context,
    system: System = typer.Option(None, help="Any structure instead of the arch's "
                                  "replacement catenary: its own ap,min and, with --records, "
                                  "its own IDA (with --site: the equivalent SDOF). Options "
                                  "as in `rockarch oas`, at real size (arches: --shape "
                                  "--span --rise --thickness)."),
    alpha: float = typer.Option(None, help="block/frame: slenderness atan(B/H) [rad]."),
    p: float = typer.Option(None, "--p", help="block/frame/sdof: frequency parameter "
                            "[1/s] (fourhinge/mdof: from their size)."),
    mass_ratio: float = typer.Option(None, help="frame: lintel mass / mass of both columns."),
    delta: float = typer.Option(None, help="sdof: neutral angle delta [rad]."),
    ap_min: float = typer.Option(None, "--ap-min", help="sdof: limit acceleration [m/s²]."),
    percentile: float = typer.Option(None, help="With --records: percentile of the records' "
                                     "boundaries (--system: collapse PGAs) read by --curve "
                                     "characteristic (lower: safer)."),
    ratio_max: float = typer.Option(None, help="--system with --records: IDA scan limit "
                                    "ap/ap,min (default 5); records safe up to it are "
                                    "censored."),
    ratio_steps: int = IDA_STEPS_OPT, tol: float = IDA_TOL_OPT,
    search_step: float = typer.Option(None, help="--system with --records: " + SEARCH_HELP),
    t_free: float = TFREE_OPT,
    bootstrap: int = typer.Option(fr.N_BOOTSTRAP, help="--system with --records: bootstrap "
                                  "resamples of the fragility's interval (0: none)."),
    site_file: Path = typer.Option(None, "--site", help="Site OAS file (rockarch site-oas)."),
    records: list[Path] = typer.Option(None, "--records", help="Instead of --site: records "
                                       "(folder or files); the site OAS, its characteristic "
                                       "curves and the replacement's fragility are computed "
                                       "(and kept in the store) on the fly."),
    units: str = typer.Option(None, help="Units of two-column or single-column --records: "
                              "m/s2, g, cm/s2 (.AT2 files state their own)."),
    dt: float = DT_OPT,
    pga: float = typer.Option(None, help="With --records: probability of collapse at this "
                              "PGA [m/s²]."),
    probability: float = typer.Option(None, help="With --records: the PGA at this "
                                      "probability of collapse given the PGA (default "
                                      "0.1). With --hazard: the target probability of "
                                      "collapse in --years N years: the largest scale of "
                                      "the site's hazard (and, for the arch, the smallest "
                                      "thickness) that meets it."),
    hazard: Path = typer.Option(None, "--hazard", help="With --records: the site's hazard "
                                "curve in PGA (as `rockarch risk --hazard`): the annual "
                                "frequency of collapse and the probability of collapse in "
                                "--years N years."),
    save_site: Path = typer.Option(None, help="With --records: also write the site OAS "
                                   "computed on the fly (NetCDF, reusable as --site)."),
    thickness_rule: str = typer.Option(None, help="Replacement catenary thickness: "
                                       "equivalent (same ap,min; default) or lower-bound."),
    curve: str = typer.Option("envelope", help="Site curve: envelope, characteristic "
                              "(percentile), normalised (over p·Tm) or simplified (two "
                              "durations)."),
    replacement_axis: str = typer.Option(None, help="Replacement axis: catenary "
                                         "(uniform mass; default) or weighted (the funicular "
                                         "of the arch's own mass)."),
    replacement_mass: str = typer.Option(None, help="Replacement mass: own (its uniform "
                                         "mass; default) or original (the arch's mass on its "
                                         "axis)."),
    g: float = G_OPT,
    report: Path = typer.Option(None, help="Write a self-contained HTML report."),
    json_out: bool = JSON_OPT,
    **opts,
) -> None:
    """Largest safe PGA of a structure at a site. An arch by the paper's method (Sect. 9):
    replacement catenary, site OAS. Any --system (docs/theory.md Sect. 11.4): its own
    ap,min and its own IDA over --records (envelope or percentile, fragility), or the
    equivalent SDOF on a block's --site file.

    With --records the computation runs on the sweep executor and store (the sweep options
    as in oas)."""
    args = {k: v for k, v in locals().items() if k != "opts"} | opts
    _check_design_inputs(args, records or [])
    if system is not None:
        _design_system(args, records or [], json_out)
        return
    thickness_rule = thickness_rule or "equivalent"
    replacement_axis = replacement_axis or "catenary"
    replacement_mass = replacement_mass or "own"
    percentile = 50.0 if percentile is None else percentile
    unused = [k for k in _SYSTEM_ONLY if args[k] is not None]
    shape, span, rise, thickness = (opts[k] for k in ("shape", "span", "rise", "thickness"))
    if unused:
        raise ValueError(f"--{unused[0].replace('_', '-')} goes with --system KIND (the arch "
                         "design takes --shape --span --rise --thickness)")
    if shape is None or span is None or rise is None or thickness is None:
        raise ValueError("give the arch (--shape --span --rise --thickness) or --system KIND "
                         "with its options")
    if thickness_rule not in RULES:
        raise ValueError(f"--thickness-rule must be {' or '.join(RULES)}, got "
                         f"{thickness_rule!r}")
    check_outputs((report, "--report", "html"), (save_site, "--save-site", "netcdf"))
    site_hazard = _hazard(args, bool(records))
    if records:
        suite = read_records(records, units, dt)
        n_sims = charsite.DESIGN_P.size * charsite.DESIGN_RATIO.size * len(suite)
        with open_sweep(**sweep_options(opts), n_sims=n_sims,
                        echo=echo_err) as (executor, chunk_store):
            site_ds = charsite.site_from_records(suite, executor=executor, store=chunk_store,
                                                percentile=percentile,
                                                progress=sys.stderr.isatty(),
                                                log=stage_echo())
        if save_site is not None:
            site_mod.save(site_ds, save_site)
    else:
        site_ds = site_mod.check_block_site(
            site_mod.load(site_file), site_file,
            structure=f"{shape.value} arch l = {span:g} m, f = {rise:g} m, d = "
                      f"{thickness:g} m")
    arch = make_arch(shape.value, positive("--span", span), positive("--rise", rise),
                     positive("--thickness", thickness))
    repl = replacement(arch, g=g, axis=replacement_axis, mass=replacement_mass)
    ida = None
    if records:  # the records' first collapses at p, islands searched (Eq. (11.30a))
        chosen = repl.by_rule(thickness_rule)
        ida = fr.site_ida(suite.motions, chosen.p, chosen.ap_min,
                          alpha=float(site_ds.attrs["alpha"]), names=suite.names,
                          ratio=site_ds["ratio"].values)
    res = design_check(arch, site_ds, rule=thickness_rule, curve=curve, g=g, repl=repl,
                       ida=ida)
    caveats = _design_caveats(res, ida, curve, site_ds)
    if res.ratio_is_lower_bound:
        echo_err("warning: no record overturns the equivalent block within the site's ratio "
                 "range; the result is a lower bound")
    extra, html_extra = ({"caveats": caveats} if caveats else {}), ""
    if records:
        try:
            frag = fr.fit_ida(ida, hint=fr.SITE_HINT)
        except fr.TooFewCollapses as exc:  # the safe PGA is still the answer
            if site_hazard is not None:
                raise ValueError(f"--hazard needs the records' fragility: {exc}") from None
            echo_err(f"warning: {exc}; no fragility")
            frag, extra = None, {"fragility": None, "note": str(exc)}
        if frag is not None:
            extra["fragility"] = fr.design_summary(frag, pga=pga,
                                                   probability=_conditional(args), g=g)
            if report is not None:
                from rockarch.output.fragility_plots import fragility_html
                html_extra = fragility_html(frag, extra["fragility"], suite)
    if site_hazard is not None:
        years, extrapolate = args["years"], args["extrapolate"]
        risk = site_risk(frag.fit, site_hazard, years=years, probability=probability,
                         extrapolate=extrapolate)
        if probability is not None:
            d, trials = smallest_thickness(
                arch, suite.motions, site_hazard, probability, years=years,
                alpha=float(site_ds.attrs["alpha"]), ratio=site_ds["ratio"].values,
                rule=thickness_rule, axis=replacement_axis, mass=replacement_mass, g=g,
                extrapolate=extrapolate)
            risk = replace(risk, thickness=d, trials=trials)
        extra["risk"] = risk.to_dict()
    if report is not None:
        from rockarch.output.report import write_report
        write_report(res, site_ds, report, command=_command_line(args),
                     site_path=str(site_file) if site_file else None, extra_html=html_extra,
                     caveats=caveats,
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
    typer.echo(f"site {curve} at p: {_safe_pga(res, g)}")
    if extra.get("fragility"):
        f = extra["fragility"]
        typer.echo(f"fragility of the replacement over {f['n_records']} records: median PGA "
                   f"{f['median']:.3f} m/s², beta {f['beta']:.3f}")
        for key in ("probability_at_pga", "pga_at_probability"):
            if key in f:
                typer.echo(f"  P(collapse) = {f[key]['probability']:.3g} at PGA "
                           f"{f[key]['pga']:.3f} m/s²")
    if site_hazard is not None:
        _print_risk(risk)
    if report is not None:
        typer.echo(f"wrote {report}")


#: design options that need --records (a --site file holds its own curves).
_RECORDS_ONLY = ("pga", "probability", "percentile", "units", "dt", "ratio_max",
                 "save_site", "search_step")


def _check_design_inputs(opt: dict, records: list[Path]) -> None:
    """What ``rockarch design`` can check before any computation: one of --site and
    --records, the options that go with --records only, and the numbers of the fragility."""
    if (opt["site_file"] is None) == (not records):
        raise ValueError("give either --site FILE or --records DIR")
    if opt["site_file"] is not None:
        extra = [k for k in _RECORDS_ONLY if opt[k] is not None]
        if extra:
            raise ValueError(f"--{extra[0].replace('_', '-')} goes with --records (a --site "
                             "file holds its own curves)")
    if opt["search_step"] is not None and opt["system"] is None:
        raise ValueError(f"--search-step goes with --system (the arch's replacement block "
                         f"is searched every {SEARCH_STEP:g})")
    if opt["pga"] is not None:
        positive("--pga [m/s²]", opt["pga"])
    if opt["probability"] is not None:
        in_range("--probability", opt["probability"], 0.0, 1.0, lo_open=True, hi_open=True)
    if opt["percentile"] is not None:
        in_range("--percentile", opt["percentile"], 0.0, 100.0)


def _hazard(opt: dict, records: bool):
    """The hazard curve of design --hazard (None without it); --probability's meaning
    follows (docs/sites.md, "Risk")."""
    for name in ("site_row", "extrapolate"):
        if opt[name] not in (None, False) and opt["hazard"] is None:
            raise ValueError(f"--{name.replace('_', '-')} goes with --hazard FILE")
    if opt["hazard"] is None:
        if typed(opt["ctx"], "years"):
            raise ValueError("--years goes with --hazard FILE (the probability of collapse "
                             "in N years at the site)")
        return None
    if not records:
        raise ValueError("--hazard needs --records: the fragility comes from the records' "
                         "IDA (a site file holds no fragility)")
    check_years(opt["years"])
    if opt["probability"] is not None and not 0 < opt["probability"] < 1:
        raise ValueError(f"--probability must lie in (0, 1), got {opt['probability']}")
    curve = hazard_of(opt["hazard"], opt["site_row"])
    if curve.im != "pga":
        raise ValueError(f"the design's fragility is in PGA: give a PGA hazard curve "
                         f"({opt['hazard']} is in {curve.label}; `rockarch risk` takes any "
                         "IM)")
    return curve


def _conditional(opt: dict) -> float | None:
    """--probability as the design summary's P(collapse | PGA): default 0.1; none with
    --hazard (there it is the target in --years)."""
    if opt["hazard"] is not None:
        return None
    return 0.1 if opt["probability"] is None else opt["probability"]


def _print_risk(risk) -> None:
    r, c = risk.result, risk.hazard
    std = standard_g(c.units)
    typer.echo(f"risk at the site of {Path(c.source).name} ({c.label} {c.x[0] / c.factor:.4g} … "
               f"{c.x[-1] / c.factor:.4g} {c.units}{', ' + std if std else ''}): annual "
               "frequency of collapse "
               f"{r.annual_rate:.3g} /yr, P(collapse in {r.years:g} years) = "
               f"{r.probability:.3g}")
    if risk.target is not None:
        typer.echo(f"  P(collapse in {r.years:g} years) <= {risk.target:g} up to "
                   f"{risk.scale:.3g} x the site's hazard (ground motions "
                   f"{risk.scale:.3g} times as strong)")
    if risk.thickness is not None:
        typer.echo(f"  P(collapse in {r.years:g} years) <= {risk.target:g} at the site's "
                   f"hazard from a thickness of {risk.thickness:.3f} m "
                   f"({len(risk.trials)} thicknesses tried, bisection to 1 %)")


#: design options of --system only (the arch design by the replacement catenary refuses them).
_SYSTEM_ONLY = ("alpha", "p", "blocks", *(name for name, _, _ in STRUCTURE), "mass_ratio",
                "delta", "ap_min", "ratio_max", "h_factor")
#: design options of the arch design only (with their defaults: given when they differ).
_ARCH_ONLY = ("thickness_rule", "replacement_axis", "replacement_mass", "save_site")


def _design_system(opt: dict, records: list[Path], json_out: bool) -> None:
    """``rockarch design --system KIND``: ra.system from the options, then
    :func:`rockarch.design.design_system` (records: its IDA; --site: equivalent SDOF)."""
    kind = opt["system"].value
    extra = [k for k in _ARCH_ONLY if opt[k] is not None]
    if extra:
        raise ValueError(f"--{extra[0].replace('_', '-')} belongs to the arch design (without "
                         "--system)")
    check_outputs((opt["report"], "--report", "html"))
    if kind in ("frame", "sdof") and opt["p"] is None:
        raise ValueError(f"--system {kind} needs --p (its frequency parameter [1/s])")
    if kind in ("fourhinge", "mdof") and opt["p"] is not None:
        raise ValueError(f"--p: a {kind} structure's p follows from its size (give --span "
                         "--rise --thickness, or the blocks in metres)")
    sysobj = make_system(kind, alpha=opt["alpha"], p=opt["p"], shape=value(opt["shape"]),
                         span=opt["span"], rise=opt["rise"], thickness=opt["thickness"],
                         blocks=opt["blocks"], mass_ratio=opt["mass_ratio"],
                         delta=opt["delta"], ap_min=opt["ap_min"], g=opt["g"],
                         t_free=opt["t_free"], h_factor=opt["h_factor"],
                         **mdof_structure(opt))
    site_hazard = _hazard(opt, bool(records))
    kw = {"curve": opt["curve"],
          "percentile": 50.0 if opt["percentile"] is None else opt["percentile"],
          "g": opt["g"], "pga": opt["pga"], "probability": _conditional(opt)}
    suite, caveats = None, []
    if opt["site_file"] is not None:
        ds = site_mod.check_block_site(site_mod.load(opt["site_file"]), opt["site_file"],
                                       structure=sysobj.name)
        res = design_system(sysobj, site=ds, curve=kw["curve"], g=kw["g"])
        # the equivalent SDOF reads the site file's first collapses, as the arch design
        caveats = [site_file_note("structure", "docs/sites.md")]
        for c in caveats:
            echo_err(f"note: {c}")
    else:
        if not 0 <= opt["bootstrap"] <= fr.MAX_BOOTSTRAP:
            raise ValueError(f"--bootstrap must lie in [0, {fr.MAX_BOOTSTRAP}], got "
                             f"{opt['bootstrap']}")
        ratios, tol = ida_scan(opt, sysobj)
        suite = read_records(records, opt["units"], opt["dt"])
        with open_sweep(**ida_sweep_options(opt, len(suite)), n_sims=ratios.size * len(suite),
                        echo=echo_err) as (executor, chunk_store):
            res = design_system(sysobj, records=suite, ratio=ratios, tol=tol,
                                search_step=opt["search_step"], n_bootstrap=opt["bootstrap"],
                                executor=executor,
                                store=chunk_store, progress=sys.stderr.isatty(),
                                log=stage_echo(), **kw)
    for msg in (res.note,) if res.note else ():
        echo_err(f"warning: {msg}; no lognormal fit")
    if res.ratio_is_lower_bound:
        echo_err("warning: the site curve does not collapse the structure within the ratio "
                 "range; the safe PGA is a lower bound")
    risk = None
    if site_hazard is not None:
        if res.fragility is None or res.fragility.fit is None:
            raise ValueError("--hazard needs a fragility: fewer than two records collapse "
                             "(raise --ratio-max)")
        risk = site_risk(res.fragility.fit, site_hazard, years=opt["years"],
                         probability=opt["probability"], extrapolate=opt["extrapolate"])
    if opt["report"] is not None:
        from rockarch.output.report import write_system_report
        write_system_report(res, opt["report"], command=_command_line(opt), suite=suite,
                            caveats=caveats)
    if json_out:
        print_json(res.to_dict() | ({"caveats": caveats} if caveats else {})
                   | ({} if risk is None else {"risk": risk.to_dict()}))
        return
    _print_system_design(res)
    if risk is not None:
        _print_risk(risk)
    if opt["report"] is not None:
        typer.echo(f"wrote {opt['report']}")


def _command_line(opt: dict) -> str:
    """The command as the report's way to rerun it: every option given on the command line
    (at its default value too) and every other one whose value differs from its default."""
    import shlex

    words = ["rockarch", "design"]
    command = typer.main.get_command(app).get_command(None, "design")
    ctx = opt.get("ctx")
    for prm in command.params:
        v = opt.get(prm.name)
        if (v is None or v == [] or prm.name in ("report", "json_out")
                or (v == prm.default and not (ctx is not None and typed(ctx, prm.name)))):
            continue
        if getattr(prm, "is_flag", False):  # typer's options need not be click's class
            if v or prm.secondary_opts:
                words.append(prm.opts[0] if v else prm.secondary_opts[0])
            continue
        for item in v if isinstance(v, (list, tuple)) else [v]:
            words += [prm.opts[0], str(getattr(item, "value", item))]
    return " ".join(shlex.quote(w) for w in words)


def site_file_note(of: str, doc: str) -> str:
    """The caveat of a design read on a site file: its islands are not searched.

    Parameters
    ----------
    of : str
        What the records' collapses are searched for with --records ("arch",
        "structure").
    doc : str
        Where that search is described.

    Returns
    -------
    str
        One line, without the "note: " prefix.
    """
    return ("a site file holds each record's first collapse on its ratio grid; collapse "
            "islands narrower than the grid's step are not searched (with --records they "
            f"are, at the {of}'s p: {doc})")


def _design_caveats(res, ida, curve: str, site_ds) -> list[str]:
    """What an arch's design did not search or bound, each said once on stderr (and given
    to the report): a site file's islands; a fitted curve (normalised, simplified) read
    above records' first collapses (from the IDA, islands searched, or the site file's)."""
    notes, warns = [], []
    if ida is None:
        notes.append(site_file_note("arch", "docs/design.md"))
        first = site_mod.records_at(site_ds, res.chosen.p)
    else:
        first = ida.ratio_collapse
    first = first[np.isfinite(first)]
    below = first[first < res.ratio]
    if curve in ("normalised", "simplified") and below.size:
        warns.append(f"{below.size} of {site_ds.sizes['record']} records first collapse "
                     f"the replacement's block below the {curve} curve's ap/ap,min = "
                     f"{res.ratio:.4f} (the lowest at {below.min():.4f}): that curve is a "
                     "prediction fitted over p, not a bound (--curve envelope reads the "
                     "records' first collapses)")
    for c in notes:
        echo_err(f"note: {c}")
    for c in warns:
        echo_err(f"warning: {c}")
    return notes + warns


def _safe_pga(res, g: float) -> str:
    """'ap/ap,min = R -> safe PGA P m/s² = P/g g (g = G m/s²)' of a design result; '>='
    where the site curve reaches the top of the ratio range (a lower bound)."""
    low = res.ratio_is_lower_bound
    islands = (f" (the records' first collapses at p, collapse islands searched; the site "
               f"OAS grid reads {res.ratio_grid:.4f})" if getattr(res, "islands_lower", False)
               else "")
    return (f"ap/ap,min {'>=' if low else '='} {res.ratio:.4f}{islands} -> safe PGA "
            f"{'>= ' if low else ''}{res.pga_safe:.3f} m/s² = {res.pga_safe / g:.3f} g "
            f"({g_label(g)})")


def _print_system_design(res) -> None:
    slide = ""
    if res.ap_min_no_sliding is not None:
        slide = (f" (friction-aware; {res.ap_min_no_sliding:.4g} without sliding: the "
                 f"collapse mechanism {'slides' if res.sliding else 'rocks'})")
    typer.echo(f"{res.system}: p = {res.p:.4g} 1/s, ap,min = {res.ap_min:.4g} m/s²{slide}")
    if res.fragility is not None:
        _print_table(res.fragility)
    how = ("equivalent SDOF on the block site OAS" if res.method == "equivalent-sdof" else
           "over the records' collapse points")
    name = res.curve if res.curve == "envelope" else f"{res.percentile:g}th percentile"
    typer.echo(f"site {name} ({how}): {_safe_pga(res, res.g)}")
    f = res.summary or {}
    for key in ("probability_at_pga", "pga_at_probability"):
        if key in f:
            typer.echo(f"  P(collapse) = {f[key]['probability']:.3g} at PGA "
                       f"{f[key]['pga']:.3f} m/s²")
