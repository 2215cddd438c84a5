"""``rockarch oas``: the overturning acceleration spectrum of one system for one motion."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from rockarch.cli._app import app
from rockarch.cli._common import (
    JSON_OPT,
    TOL_OPT,
    echo_err,
    guarded,
    motion_shape,
    p_grid,
    print_json,
    ratio_grid,
)
from rockarch.cli._groups import MOTION, SWEEP, SYSTEM, options, pick, sweep_options, system_of
from rockarch.cli._sweep import open_sweep
from rockarch.output import check_outputs, staged
from rockarch.output.tables import boundary_table
from rockarch.spectra import oas as spectra


@app.command(short_help="OAS of a block, mechanism or MDOF arch for one motion.")
@guarded
@options(SYSTEM, MOTION, before="p")
@options(SWEEP)
def oas(
    p: str = typer.Option(None, "--p", help="Comma-separated p values [1/s]."),
    p_min: float = typer.Option(None, help="Smallest p of a linear grid [1/s]."),
    p_max: float = typer.Option(None, help="Largest p of a linear grid [1/s]."),
    p_steps: int = typer.Option(50, help="Number of p values of the grid."),
    ratio_min: float = typer.Option(1.0, help="Smallest ap/ap,min."),
    ratio_max: float = typer.Option(None, help="Largest ap/ap,min (default 5)."),
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values (1: --ratio-min "
                                    "only)."),
    tol: float = TOL_OPT,
    out: Path = typer.Option(None, help="Write the OAS to this NetCDF file."),
    plot: Path = typer.Option(None, help="Write a PNG plot of the OAS."),
    json_out: bool = JSON_OPT,
    progress: bool = typer.Option(True, help="Show a progress bar on stderr."),
    **opts,
) -> None:
    """Overturning acceleration spectrum (OAS) over p × ap/ap,min for one ground motion.

    Pulses have peak ap = ratio·ap,min; a record is scaled so that its PGA = ratio·ap,min.
    For mechanisms p varies by scaling the structure (p ∝ 1/sqrt(size), same shape).
    """
    sysobj = system_of(opts)
    shape_motion = motion_shape(**pick(opts, MOTION))
    ps = p_grid(p, p_min, p_max, p_steps)
    ratios = ratio_grid(ratio_min, ratio_max, ratio_steps)
    check_outputs((out, "--out", "netcdf"), (plot, "--plot", "png"))
    with open_sweep(**sweep_options(opts), n_sims=ps.size * ratios.size,
                    echo=echo_err) as (executor, chunk_store):
        ds = spectra.compute_oas(sysobj, shape_motion, ps, ratios, tol=tol,
                                 progress=progress and sys.stderr.isatty(),
                                 executor=executor, store=chunk_store)
    with staged(out, plot) as (out_tmp, plot_tmp):
        if out is not None:
            spectra.save(ds, out_tmp)
        if plot is not None:
            from rockarch.output.figures import plot_oas, save_figure
            save_figure(plot_oas(ds).figure, plot_tmp)
    if json_out:
        print_json({
            "p": ds["p"].values,
            "ratio": ds["ratio"].values,
            "overturned": ds["overturned"].values,
            "boundary": ds["boundary"].values,
        })
        return
    typer.echo(f"OAS of {sysobj.name} for {shape_motion.name}")
    typer.echo("\n".join(boundary_table(ds["p"].values, ds["boundary"].values, ratios[-1])))
    for path in (out, plot):
        if path is not None:
            typer.echo(f"wrote {path}")
