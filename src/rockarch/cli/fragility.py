"""``rockarch fragility``: IDA of one structure over a suite of records and its lognormal
fragility curve (docs/theory.md Sect. 11.3)."""

from __future__ import annotations

import os
import sys
from dataclasses import replace
from enum import Enum
from pathlib import Path

import numpy as np
import typer

from rockarch.cli import _common as cc
from rockarch.cli._app import app
from rockarch.cli._common import echo_err, guarded, read_records
from rockarch.cli._groups import SWEEP, SYSTEM, Group, options, sweep_options, system_of
from rockarch.cli._sweep import open_sweep
from rockarch.core.constants import G_STANDARD, g_label
from rockarch.output import check_outputs
from rockarch.output.tables import unit_label
from rockarch.risk import fragility as fr
from rockarch.risk.record_scan import (
    MDOF_SEARCH_STEP,
    SEARCH_STEP,
    check_island_step,
    check_search_step,
    default_scan,
)

#: The --im choices (the library's registry, and "all": the dispersion of each on one IDA).
Im = Enum("Im", {v: v for v in (*fr.IMS, "all")}, type=str)

#: --search-step's help (fragility and design).
SEARCH_HELP = (f"Search for collapse islands narrower than the grid below its first collapse, "
               f"every STEP of ap/ap,min from 1 (the first collapse is the lowest found). "
               f"Default {SEARCH_STEP:g} for block, frame, sdof, fourhinge and a single "
               f"mdof block, {MDOF_SEARCH_STEP:g} for mdof assemblies of several blocks "
               f"(below a collapse of the grid only); 0: off.")

#: From this many records the IDA runs on local processes unless told otherwise: each
#: record is one task (its scan and bisection), records in parallel across processes
#: (benchmarks/fragility.py).
POOL_MIN_RECORDS = 16


def ida_sweep_options(opts: dict, n_records: int) -> dict:
    """The sweep options of an IDA (fragility, design --system --records): as given, else
    local processes on every core from :data:`POOL_MIN_RECORDS` records (records in
    parallel, one task each)."""
    sweep = sweep_options(opts)
    if sweep["workers"] is None and sweep["scheduler"] is None \
            and sweep["dask_workers"] is None and n_records >= POOL_MIN_RECORDS \
            and (os.cpu_count() or 1) > 1:
        sweep["workers"] = os.cpu_count()
    return sweep


#: The IDA of a structure over records (fragility; risk with the fragility inline): the
#: structure's p, the records and the scan (docs/theory.md §11.3).
IDA: Group = (
    ("p", float, typer.Option(None, "--p", help="Frequency parameter of the structure "
                              "[1/s] (default for mdof walls, columns, colonnades and "
                              "assembly files: their own, at the size given; another p "
                              "scales them, size ∝ 1/p², as the output says).")),
    ("records", list[Path], typer.Option(None, "--records", help="Folders of records "
                                         "(.AT2, .ASC, K-NET, .V2c, two-column, or "
                                         "single-column with --dt) or record files; several "
                                         "may follow one --records.")),
    ("more", list[Path], typer.Argument(None, hidden=True)),
    ("units", str, typer.Option(None, help="Units of two-column or single-column records: "
                                  "m/s2 (default), g, cm/s2 (= gal), mm/s2.")),
    ("dt", float, cc.DT_OPT),
    ("ratio_max", float, typer.Option(None, help="Scan limit ap/ap,min (default 5, as "
                                      "`rockarch oas`); records safe up to it are "
                                      "censored.")),
    ("ratio_steps", int, cc.IDA_STEPS_OPT),
    ("tol", float, cc.IDA_TOL_OPT),
    ("search_step", float, typer.Option(None, help=SEARCH_HELP)),
    ("island_step", int, typer.Option(1, help="Adaptive scan: every ratio up to the first "
                                      "collapse, then every K-th one, each safe value found "
                                      "widened to its safe island (same collapse points, "
                                      "fewer simulations; islands narrower than K ratios "
                                      "may be missed). 1: every ratio.")),
)


def ida_scan(opts: dict, sysobj) -> tuple[np.ndarray, float]:
    """The IDA scan grid of ap/ap,min and bisection tolerance of --ratio-max,
    --ratio-steps and --tol, the structure's defaults where they are not given
    (:func:`rockarch.risk.record_scan.default_scan`)."""
    steps, tol = default_scan(sysobj)
    steps = steps if opts["ratio_steps"] is None else opts["ratio_steps"]
    if steps < 2:
        raise ValueError("--ratio-steps must be >= 2 for an IDA scan")
    if opts["ratio_max"] is not None and not opts["ratio_max"] > 1:
        raise ValueError(f"--ratio-max must be > 1 (the scan starts at ap/ap,min = 1), got "
                         f"{opts['ratio_max']}")
    return (cc.ratio_grid(1.0, opts["ratio_max"], steps),
            tol if opts["tol"] is None else opts["tol"])


def run_ida(opts: dict, im: str, period: float | None, *, progress: bool = True
            ) -> tuple[fr.IDAResult, list]:
    """The IDA of the SYSTEM, IDA and SWEEP options of a command in ``im`` (and the
    motions): options checked before any record is read."""
    if not opts["records"]:
        raise ValueError("give the records: --records DIR (or files)")
    sysobj = system_of(opts)
    name, p_structure = sysobj.name, None
    if opts["system"].value == "mdof" and opts["p"] is not None:
        # an assembly is built in metres (an arch of f/l, d/l on a span of 1): at another p
        # it is scaled, size ∝ 1/p² (docs/theory.md Eq. (10.5)), and the label says so
        p_structure = float(sysobj.p_ref)
        name = (f"{name} scaled ×{(p_structure / opts['p']) ** 2:.4g} (size ∝ 1/p², as "
                f"given p = {p_structure:.4g} 1/s)")
    if opts["p"] is None:
        # blocks (of alpha alone) and arches (of f/l, d/l) have no size; walls, columns,
        # colonnades and assembly files are given in metres and have their own p
        if opts["system"].value != "mdof" or opts["shape"] is not None:
            raise ValueError("give the structure's frequency parameter --p [1/s]")
        opts = {**opts, "p": float(sysobj.p_ref)}
    ratios, tol = ida_scan(opts, sysobj)
    check_island_step(opts["island_step"])
    if opts["search_step"] is not None:
        check_search_step(opts["search_step"])
    suite = read_records(list(opts["records"]) + list(opts["more"] or []), opts["units"],
                         opts["dt"])
    motions = suite.motions
    with open_sweep(**ida_sweep_options(opts, len(motions)), n_sims=ratios.size * len(motions),
                    echo=echo_err) as (executor, chunk_store):
        res = fr.ida(sysobj, motions, opts["p"], names=suite.names, im=im, period=period,
                     ratio=ratios, tol=tol,
                     progress=progress and sys.stderr.isatty(), executor=executor,
                     store=chunk_store, island_step=opts["island_step"],
                     search_step=opts["search_step"], log=cc.stage_echo(), name=name)
    return replace(res, p_structure=p_structure), motions


def im_range_si(text: str | None, im: str) -> tuple[float, float] | None:
    """--im-range LO,HI in display units (g for pga and sa, m/s for pgv) → SI."""
    if text is None:
        return None

    vals = cc.float_list("--im-range", text)
    if vals.size != 2 or not (0 < vals[0] < vals[1]):
        raise ValueError(f"--im-range must be two numbers 0 < LO < HI, got {text!r}")
    from rockarch.output.fragility_plots import display_units
    f = display_units(im)[1]
    return float(vals[0] / f), float(vals[1] / f)


@app.command(short_help="Fragility curve of a structure over a suite of records (IDA).")
@guarded
@options(SYSTEM, IDA, before="im")
@options(SWEEP)
def fragility(
    im: Im = typer.Option("pga", help="Intensity measure of the curve's x axis: PGA, PGV, "
                          "Sa(T), PGA/(g tan alpha) (pga_norm; ap,min for any system), "
                          "PGV*p/(g tan alpha) (pgv_norm); all: the median and beta of "
                          "each on the same IDA (Sa at T = 2 pi/p unless --period)."),
    period: float = typer.Option(None, help="Period of Sa(T) [s] (--im sa, --im all)."),
    im_range: str = typer.Option(None, help="IM range of the curve and band: LO,HI in g "
                                 f"(pga, sa; {g_label(G_STANDARD)}) or m/s (pgv); default "
                                 "the records' range widened by 2."),
    bootstrap: int = typer.Option(fr.N_BOOTSTRAP, help="Bootstrap resamples of the band "
                                  "(0: none)."),
    level: float = typer.Option(0.95, help="Confidence level of the band."),
    plot: Path = typer.Option(None, help="Write a PNG of the curve, band and points."),
    out: Path = typer.Option(None, help="Also write the JSON that --json prints to this "
                             "file (e.g. for `rockarch risk --fragility FILE`)."),
    json_out: bool = cc.JSON_OPT,
    progress: bool = typer.Option(True, help="Show a progress bar on stderr."),
    **opts,
) -> None:
    """Incremental dynamic analysis at one p and a lognormal fragility (maximum likelihood,
    censored records included, bootstrap band). PGA and Sa in m/s², PGV in m/s."""
    im = im.value
    if im == "all":
        if plot is not None or im_range is not None:
            raise ValueError("--im all prints a table of every IM: --plot and --im-range go "
                             "with one IM (--im pga, pgv, sa, pga_norm, pgv_norm)")
        if period is not None and not (np.isfinite(period) and period > 0):
            raise ValueError(f"--period must be a finite number > 0, got {period}")
    if not 0 <= bootstrap <= fr.MAX_BOOTSTRAP:
        raise ValueError(f"--bootstrap must lie in [0, {fr.MAX_BOOTSTRAP}], got {bootstrap}")
    if not 0 < level < 1:
        raise ValueError(f"--level must lie in (0, 1), got {level}")
    rng = None if im == "all" else im_range_si(im_range, im)
    check_outputs((plot, "--plot", "png"), (out, "--out", "json"))
    res, motions = run_ida(opts, "pga" if im == "all" else im,
                           None if im == "all" else period, progress=progress)
    if im == "all":
        _all_ims(res, motions, period, bootstrap, level, json_out, out)
        return
    if rng is None:
        known = np.concatenate([res.im_collapse[~res.censored], res.im_limit])
        rng = (known.min() / 2, known.max() * 2)
    grid = np.geomspace(rng[0], rng[1], 41)
    try:
        frag = fr.fit_ida(res, n_bootstrap=bootstrap, level=level, im_grid=grid)
    except fr.TooFewCollapses as exc:  # the points are still the answer: print them
        echo_err(f"warning: {exc}; no lognormal fit")
        frag = fr.Fragility(res, None, {})
    if plot is not None:
        from rockarch.output.figures import save_figure
        from rockarch.output.fragility_plots import plot_fragility
        save_figure(plot_fragility(frag, rng), plot)
    if out is not None:
        cc.write_json(out, frag.to_dict())
    if json_out:
        cc.print_json(frag.to_dict())
        return
    _print_table(frag)
    for path in (p for p in (plot, out) if p is not None):
        typer.echo(f"wrote {path}")


def _all_ims(res: fr.IDAResult, motions, period, bootstrap: int, level: float,
             json_out: bool, out: Path | None) -> None:
    """``--im all``: the fit of the same IDA in every IM (fragility.compare_ims)."""
    if np.unique(res.ratio_collapse[~res.censored]).size < 2:
        raise ValueError(f"only {int((~res.censored).sum())} of {len(res.records)} records "
                         f"collapse up to ap/ap,min = {res.ratio[-1]:g}: no IM can be fitted "
                         "(raise the scan limit, e.g. --ratio-max 10)")
    rows = fr.compare_ims(res, motions, period=period, n_bootstrap=bootstrap, level=level)
    points = [{"record": name, "ratio_collapse": float(c) if np.isfinite(c) else None,
               "censored": bool(not np.isfinite(c)), "resurrections": int(n)}
              for name, c, n in zip(res.records, res.ratio_collapse, res.resurrections,
                                    strict=True)]
    obj = {"system": res.system, "p": res.p, "ap_min": res.ap_min,
           "n_records": len(res.records), "n_censored": int(res.censored.sum()),
           "search_step": res.search_step, "ims": rows, "points": points}
    if res.p_structure is not None:
        obj |= {"scale": res.scale, "p_structure": res.p_structure}
    if out is not None:
        cc.write_json(out, obj)
    if json_out:
        cc.print_json(obj)
        return
    typer.echo(f"dispersion of each IM on one IDA: {res.system} at p = {res.p:g} 1/s over "
               f"{len(res.records)} records ({int(res.censored.sum())} censored)")
    has_ci = any(r["ci"].get("beta") for r in rows)
    lvl = f"{100 * level:g} % interval of beta" if has_ci else ""
    typer.echo(f"{'IM':<24} {'units':>5} {'median':>9} {'beta':>6}  {lvl}".rstrip())
    for r in rows:
        name = r["label"] if "period" not in r else f"Sa(T = {r['period']:.3g} s)"
        ci = r["ci"].get("beta")
        typer.echo(f"{name:<24} {unit_label(r['units']):>5} {r['median']:>9.4g} "
                   f"{r['beta']:>6.3f}"
                   + (f"  {ci[0]:.3f} … {ci[1]:.3f}" if ci else ""))
    if bootstrap and not has_ci and len(res.records) < fr.MIN_BOOTSTRAP_RECORDS:
        typer.echo(_no_band(len(res.records)))
    best = min(rows, key=lambda r: r["beta"])
    typer.echo(f"lowest beta: {best['label']} (the dimensionless IMs are PGA and PGV times "
               "constants here: the same beta)")
    if out is not None:
        typer.echo(f"wrote {out}")


def _print_table(frag: fr.Fragility) -> None:
    r, fit, unit = frag.ida, frag.fit, unit_label(fr.IM_UNITS[frag.ida.im])
    name = r.im if r.period is None else f"{r.im}(T = {r.period:g} s)"
    typer.echo(f"fragility of {r.system} at p = {r.p:g} 1/s over {len(r.records)} records "
               f"(IM = {name} [{unit}])")
    typer.echo(f"scan: {fr.scan_text(r.ratio, r.tol, r.search_step)}")
    typer.echo(f"{'record':<44} {'IM at collapse':>15} {'resurrections':>14}")
    for name, v, lim, n in zip(r.records, r.im_collapse, r.im_limit, r.resurrections,
                               strict=True):
        txt = f"{v:.4g}" if np.isfinite(v) else f"> {lim:.4g}"
        typer.echo(f"{name[:44]:<44} {txt:>15} {n:>14d}")
    if fit is None:
        return
    typer.echo(f"lognormal (maximum likelihood, {fit.n_censored} censored): median "
               f"{fit.median:.4g} {unit}, beta {fit.beta:.3f}")
    ci = frag.ci
    if ci:
        lvl = 100 * ci["level"]
        typer.echo(f"{lvl:g} % bootstrap interval ({ci['n']} resamples): median "
                   f"{ci['median'][0]:.4g} … {ci['median'][1]:.4g}, beta "
                   f"{ci['beta'][0]:.3f} … {ci['beta'][1]:.3f}")
    elif len(r.records) < fr.MIN_BOOTSTRAP_RECORDS:
        typer.echo(_no_band(len(r.records)))


def _no_band(n: int) -> str:
    """Why a suite of fewer than MIN_BOOTSTRAP_RECORDS records has no bootstrap interval."""
    return (f"no bootstrap interval with {n} records (the only resample that can be fitted "
            "is the sample itself): give more records")
