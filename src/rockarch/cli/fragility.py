"""``rockarch fragility``: IDA of one structure over a suite of records and its lognormal
fragility curve (docs/theory.md Sect. 11.3)."""

from __future__ import annotations

import os
import sys
from enum import Enum
from pathlib import Path

import numpy as np
import typer

from rockarch.cli import _common as cc
from rockarch.cli._app import app
from rockarch.cli._common import echo_err, guarded, read_records
from rockarch.cli._groups import SWEEP, SYSTEM, options, sweep_options, system_of
from rockarch.cli._sweep import open_sweep
from rockarch.output import check_outputs
from rockarch.output.figures import save_figure
from rockarch.output.fragility_plots import display_units, plot_fragility
from rockarch.risk import fragility as fr
from rockarch.risk.record_scan import check_island_step

#: The --im choices (the library's registry).
Im = Enum("Im", {v: v for v in fr.IMS}, type=str)

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


def im_range_si(text: str | None, im: str) -> tuple[float, float] | None:
    """--im-range LO,HI in display units (g for pga and sa, m/s for pgv) → SI."""
    if text is None:
        return None

    vals = cc.float_list("--im-range", text)
    if vals.size != 2 or not (0 < vals[0] < vals[1]):
        raise ValueError(f"--im-range must be two numbers 0 < LO < HI, got {text!r}")
    f = display_units(im)[1]
    return float(vals[0] / f), float(vals[1] / f)


@app.command(short_help="Fragility curve of a structure over a suite of records (IDA).")
@guarded
@options(SYSTEM, before="p")
@options(SWEEP)
def fragility(
    p: float = typer.Option(..., "--p", help="Frequency parameter of the structure [1/s]."),
    records: list[Path] = typer.Option(..., "--records", help="Folder of .AT2 records or "
                                       "record files; several may follow one --records."),
    more: list[Path] = typer.Argument(None, hidden=True),
    units: str = typer.Option(None, help="Units of two-column records: m/s2, g, cm/s2."),
    im: Im = typer.Option("pga", help="Intensity measure of the curve's x axis."),
    period: float = typer.Option(None, help="Period of Sa(T) [s] (--im sa)."),
    im_range: str = typer.Option(None, help="IM range of the curve and band: LO,HI in g "
                                 "(pga, sa) or m/s (pgv); default the records' range "
                                 "widened by 2."),
    ratio_max: float = typer.Option(None, help="Scan limit ap/ap,min (default 5, as "
                                    "`rockarch oas`); records safe up to it are censored."),
    ratio_steps: int = typer.Option(81, help="Scan values of ap/ap,min from 1."),
    tol: float = cc.TOL_OPT,
    island_step: int = typer.Option(1, help="Adaptive scan: every ratio up to the first "
                                    "collapse, then every K-th one, each safe value found "
                                    "widened to its safe island (same collapse points, "
                                    "fewer simulations; islands narrower than K ratios "
                                    "may be missed). 1: every ratio."),
    bootstrap: int = typer.Option(fr.N_BOOTSTRAP, help="Bootstrap resamples of the band "
                                  "(0: none)."),
    level: float = typer.Option(0.95, help="Confidence level of the band."),
    plot: Path = typer.Option(None, help="Write a PNG of the curve, band and points."),
    json_out: bool = cc.JSON_OPT,
    progress: bool = typer.Option(True, help="Show a progress bar on stderr."),
    **opts,
) -> None:
    """Incremental dynamic analysis at one p and a lognormal fragility (maximum likelihood,
    censored records included, bootstrap band). PGA and Sa in m/s², PGV in m/s."""
    im = im.value
    if not 0 <= bootstrap <= fr.MAX_BOOTSTRAP:
        raise ValueError(f"--bootstrap must lie in [0, {fr.MAX_BOOTSTRAP}], got {bootstrap}")
    if not 0 < level < 1:
        raise ValueError(f"--level must lie in (0, 1), got {level}")
    sysobj = system_of(opts)
    if ratio_steps < 2:
        raise ValueError("--ratio-steps must be >= 2 for an IDA scan")
    if ratio_max is not None and not ratio_max > 1:
        raise ValueError(f"--ratio-max must be > 1 (the scan starts at ap/ap,min = 1), got "
                         f"{ratio_max}")
    ratios = cc.ratio_grid(1.0, ratio_max, ratio_steps)
    check_island_step(island_step)
    rng = im_range_si(im_range, im)
    check_outputs((plot, "--plot", "png"))
    suite = read_records(list(records) + list(more or []), units)
    motions = suite.motions
    with open_sweep(**ida_sweep_options(opts, len(motions)), n_sims=ratios.size * len(motions),
                    echo=echo_err) as (executor, chunk_store):
        res = fr.ida(sysobj, motions, p, names=suite.names, im=im,
                     period=period, ratio=ratios, tol=tol,
                     progress=progress and sys.stderr.isatty(), executor=executor,
                     store=chunk_store, island_step=island_step)
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
        save_figure(plot_fragility(frag, rng), plot)
    if json_out:
        cc.print_json(frag.to_dict())
        return
    _print_table(frag)
    if plot is not None:
        typer.echo(f"wrote {plot}")


def _print_table(frag: fr.Fragility) -> None:
    r, fit, unit = frag.ida, frag.fit, fr.IM_UNITS[frag.ida.im]
    name = r.im if r.period is None else f"{r.im}(T = {r.period:g} s)"
    typer.echo(f"fragility of {r.system} at p = {r.p:g} 1/s over {len(r.records)} records "
               f"(IM = {name} [{unit}])")
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
