"""``rockarch oas``: the overturning acceleration spectrum of one system for one motion."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from rockarch import spectra
from rockarch.cli._app import app
from rockarch.cli._common import (
    ABUT_OPT,
    ASSEMBLY_OPT,
    BAY_OPT,
    BLOCK_OPT,
    COLONNADE_OPT,
    COLUMN_OPT,
    CYCLES_OPT,
    DASK_WORKERS_OPT,
    FRICTION_OPT,
    G_OPT,
    JSON_OPT,
    LINTEL_OPT,
    NO_STORE_OPT,
    PERIOD_OPT,
    PIER_BLOCKS_OPT,
    PIER_H_OPT,
    PIER_W_OPT,
    RECORD_OPT,
    SCHEDULER_OPT,
    SIGNAL_OPT,
    SPANS_OPT,
    STORE_OPT,
    TFREE_OPT,
    TOL_OPT,
    UNITS_OPT,
    WALL_OPT,
    WORKERS_OPT,
    Shape,
    Signal,
    System,
    echo_err,
    guarded,
    mdof_structure,
    motion_shape,
    p_grid,
    print_json,
    ratio_grid,
    value,
)
from rockarch.cli._sweep import open_sweep
from rockarch.output import check_outputs, staged
from rockarch.output.figures import plot_oas, save_figure
from rockarch.output.tables import boundary_table
from rockarch.systems import system as make_system


@app.command(short_help="OAS of a block, mechanism or MDOF arch for one motion.")
@guarded
def oas(
    system: System = typer.Option("block", help="Structure whose OAS is computed: a "
                                  "rigid block, the four-hinge mechanism of an arch, a rocking "
                                  "frame, any SDOF mechanism given by delta and ap,min, or a "
                                  "multi-block (MDOF) arch."),
    alpha: float = typer.Option(None, help="block/frame: slenderness atan(B/H) [rad]."),
    shape: Shape = typer.Option(None, help="fourhinge/mdof: arch shape."),
    rise_over_span: float = typer.Option(None, help="fourhinge/mdof: f/l."),
    thickness_over_span: float = typer.Option(None, help="fourhinge/mdof: d/l."),
    blocks: int = typer.Option(None, help="fourhinge: voussoirs (critical mechanism); "
                               "default the continuous arch (critical optimal). mdof: "
                               "voussoirs (required)."),
    column: str = COLUMN_OPT, friction: float = FRICTION_OPT, spans: int = SPANS_OPT,
    pier_height: float = PIER_H_OPT, pier_width: float = PIER_W_OPT,
    pier_blocks: int = PIER_BLOCKS_OPT, abutments: bool = ABUT_OPT, wall: str = WALL_OPT,
    block: str = BLOCK_OPT, colonnade: int = COLONNADE_OPT, bay: float = BAY_OPT,
    lintel: float = LINTEL_OPT, assembly: Path = ASSEMBLY_OPT,
    mass_ratio: float = typer.Option(None, help="frame: lintel mass / mass of both columns."),
    delta: float = typer.Option(None, help="sdof: neutral angle delta [rad]."),
    ap_min: float = typer.Option(None, "--ap-min", help="sdof: limit acceleration [m/s²]."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT,
    p: str = typer.Option(None, "--p", help="Comma-separated p values [1/s]."),
    p_min: float = typer.Option(None, help="Smallest p of a linear grid [1/s]."),
    p_max: float = typer.Option(None, help="Largest p of a linear grid [1/s]."),
    p_steps: int = typer.Option(50, help="Number of p values of the grid."),
    ratio_min: float = typer.Option(1.0, help="Smallest ap/ap,min."),
    ratio_max: float = typer.Option(None, help="Largest ap/ap,min (default 5)."),
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values (1: --ratio-min "
                                    "only)."),
    tol: float = TOL_OPT,
    restitution: float = typer.Option(None, help="Coefficient of restitution in [0, 1] "
                                      "(default: Housner's 1 - 1.5 sin²alpha)."),
    t_free: float = TFREE_OPT, g: float = G_OPT,
    out: Path = typer.Option(None, help="Write the OAS to this NetCDF file."),
    plot: Path = typer.Option(None, help="Write a PNG plot of the OAS."),
    json_out: bool = JSON_OPT,
    progress: bool = typer.Option(True, help="Show a progress bar on stderr."),
    workers: int = WORKERS_OPT, scheduler: str = SCHEDULER_OPT,
    dask_workers: int = DASK_WORKERS_OPT, store: Path = STORE_OPT, no_store: bool = NO_STORE_OPT,
) -> None:
    """Overturning acceleration spectrum (OAS) over p × ap/ap,min for one ground motion.

    Pulses have peak ap = ratio·ap,min; a record is scaled so that its PGA = ratio·ap,min.
    For mechanisms p varies by scaling the structure (p ∝ 1/sqrt(size), same shape).
    """
    structure = mdof_structure(locals())
    sysobj = make_system(system.value, alpha=alpha, shape=value(shape),
                         rise_over_span=rise_over_span,
                         thickness_over_span=thickness_over_span, blocks=blocks,
                         mass_ratio=mass_ratio, delta=delta, ap_min=ap_min, g=g,
                         restitution=restitution, t_free=t_free, **structure)
    shape_motion = motion_shape(signal, period, cycles, record, units)
    ps = p_grid(p, p_min, p_max, p_steps)
    ratios = ratio_grid(ratio_min, ratio_max, ratio_steps)
    check_outputs((out, "--out", "netcdf"), (plot, "--plot", "png"))
    with open_sweep(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                    store_dir=store, no_store=no_store, n_sims=ps.size * ratios.size,
                    echo=echo_err) as (executor, chunk_store):
        ds = spectra.compute_oas(sysobj, shape_motion, ps, ratios, tol=tol,
                                 progress=progress and sys.stderr.isatty(),
                                 executor=executor, store=chunk_store)
    with staged(out, plot) as (out_tmp, plot_tmp):
        if out is not None:
            spectra.save(ds, out_tmp)
        if plot is not None:
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
