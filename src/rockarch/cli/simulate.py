"""``rockarch simulate KIND`` and ``rockarch animate``: one structure on one ground motion."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import typer

from rockarch._validate import positive
from rockarch.cli._app import app, simulate_app
from rockarch.cli._common import (
    ABUT_OPT,
    ARCH_RISE_OPT,
    ARCH_SHAPE_OPT,
    ARCH_SPAN_OPT,
    ARCH_THICK_OPT,
    ASSEMBLY_OPT,
    BAY_OPT,
    BLOCK_OPT,
    COLONNADE_OPT,
    COLUMN_OPT,
    CYCLES_OPT,
    FRICTION_OPT,
    G_OPT,
    JSON_OPT,
    LINTEL_OPT,
    MDOF_BLOCKS_OPT,
    MDOF_H_OPT,
    MDOF_TOL_OPT,
    PERIOD_OPT,
    PIER_BLOCKS_OPT,
    PIER_H_OPT,
    PIER_W_OPT,
    PLOT_OPT,
    RATIO_OPT,
    RECORD_OPT,
    REST_OPT,
    RISE_OPT,
    SHAPE_OPT,
    SIGNAL_OPT,
    SPAN_OPT,
    SPANS_OPT,
    TFREE_OPT,
    THICK_OPT,
    UNITS_OPT,
    WALL_OPT,
    Shape,
    Signal,
    guarded,
    mdof_structure,
    motion_shape,
    print_json,
    value,
)
from rockarch.output import check_outputs
from rockarch.output.animation import animate as write_gif
from rockarch.output.animation import check_options
from rockarch.output.collapse_plots import plot_collapse
from rockarch.output.figures import plot_response, save_figure
from rockarch.systems import scale_to_ratio
from rockarch.systems import system as make_system


def _run(sysobj, header: str, signal, period, cycles, record, units, ratio, plot,
         json_out, extra: dict | None = None) -> None:
    """Scale the motion to a peak of ratio·ap,min, run, then print JSON or a summary."""
    shape = motion_shape(signal, period, cycles, record, units)
    mot = scale_to_ratio(shape, ratio, sysobj.ap_min)
    resp = sysobj.simulate(shape, ratio=ratio)
    if plot is not None:
        save_figure(plot_response(resp, mot), plot)
    s = {**resp.to_dict(), **(extra or {})}
    if json_out:
        print_json(s)
        return
    typer.echo(header)
    typer.echo(f"motion: {mot.name}, PGA={mot.pga:.4g} m/s² = {ratio:g} ap,min")
    if s["overturned"]:
        typer.echo(f"OVERTURNED at t = {s['t_overturn']:.4f} s after {s['impacts']} impacts")
    else:
        typer.echo(f"safe: max rotation / its overturning value = "
                   f"{s['max_rotation_ratio']:.4f}, {s['impacts']} impacts")
    stride = getattr(resp, "stride", 1)
    if stride > 1:  # docs/theory.md Eq. (8.6): the verdict above is exact
        typer.echo(f"history: every {stride}th step kept (ROCKARCH_MAX_SAMPLES)")
    if plot is not None:
        typer.echo(f"wrote {plot}")


@simulate_app.command("block")
@guarded
def simulate_block(
    alpha: float = typer.Option(None, help="Slenderness angle atan(B/H) [rad]."),
    p: float = typer.Option(None, "--p", help="Frequency parameter [1/s]."),
    width: float = typer.Option(None, help="Full width B [m] (instead of --p/--alpha)."),
    height: float = typer.Option(None, help="Full height H [m] (instead of --p/--alpha)."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    restitution: float = REST_OPT, t_free: float = TFREE_OPT, g: float = G_OPT,
    plot: Path = PLOT_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate a rigid block (exact Housner equation) on a pulse or a record."""
    check_outputs((plot, "--plot", "png"))
    if width is None and height is None and (p is None or alpha is None):
        raise ValueError("give the block: --p P --alpha A (or --width B --height H)")
    sysobj = make_system("block", alpha=alpha, p=p, width=width, height=height,
                         restitution=restitution, g=g, t_free=t_free)
    blk = sysobj.block()
    header = (f"block p={blk.p:.4g} 1/s alpha={blk.alpha:.4g} rad (B={blk.width:.4g} m, "
              f"H={blk.height:.4g} m, ap,min={blk.ap_min:.4g} m/s², r={blk.r:.4f})")
    _run(sysobj, header, signal, period, cycles, record, units, ratio, plot, json_out)


@simulate_app.command("fourhinge")
@guarded
def simulate_fourhinge(
    shape: Shape = ARCH_SHAPE_OPT, span: float = ARCH_SPAN_OPT, rise: float = ARCH_RISE_OPT,
    thickness: float = ARCH_THICK_OPT,
    blocks: int = typer.Option(None, help="Voussoirs (critical mechanism); default the "
                               "continuous arch (critical optimal mechanism)."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    restitution: float = REST_OPT, t_free: float = TFREE_OPT, g: float = G_OPT,
    plot: Path = PLOT_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate the four-hinge mechanism of an arch (exact linkage kinematics, Sect. 5)."""
    check_outputs((plot, "--plot", "png"))
    sysobj = make_system("fourhinge", shape=shape.value, span=positive("--span", span),
                         rise=positive("--rise", rise),
                         thickness=positive("--thickness", thickness), blocks=blocks, g=g,
                         restitution=restitution, t_free=t_free)
    mech = sysobj.mechanism
    header = (f"{mech.name}: p={mech.p:.4g} 1/s, delta={mech.delta:.4g} rad, "
              f"ap,min={mech.ap_min:.4g} m/s², impact e={mech.plus.e_close:.4f}/"
              f"{mech.minus.e_close:.4f}")
    _run(sysobj, header, signal, period, cycles, record, units, ratio, plot, json_out)


@simulate_app.command("frame")
@guarded
def simulate_frame(
    alpha: float = typer.Option(..., help="Column slenderness atan(b/h) [rad]."),
    p: float = typer.Option(..., "--p", help="Frequency parameter of one column [1/s]."),
    mass_ratio: float = typer.Option(..., help="Lintel mass / mass of both columns."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    restitution: float = REST_OPT, t_free: float = TFREE_OPT, g: float = G_OPT,
    plot: Path = PLOT_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate a rocking frame: two rigid columns and a rigid lintel (paper Fig. 1)."""
    check_outputs((plot, "--plot", "png"))
    sysobj = make_system("frame", alpha=alpha, p=p, mass_ratio=mass_ratio, g=g,
                         restitution=restitution, t_free=t_free)
    mech = sysobj.mechanism
    header = (f"{mech.name}: p={mech.p:.4g} 1/s (Eq. 12), ap,min={mech.ap_min:.4g} m/s², "
              f"e={mech.plus.e_close:.4f}")
    _run(sysobj, header, signal, period, cycles, record, units, ratio, plot, json_out)


@simulate_app.command("sdof")
@guarded
def simulate_sdof(
    p: float = typer.Option(..., "--p", help="Frequency parameter [1/s]."),
    delta: float = typer.Option(..., help="Neutral angle delta [rad]."),
    ap_min: float = typer.Option(..., "--ap-min", help="Limit acceleration [m/s²]."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    restitution: float = REST_OPT, t_free: float = TFREE_OPT, g: float = G_OPT,
    plot: Path = PLOT_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate any SDOF mechanism given by (p, delta, ap,min) (equivalence form, ref. [13])."""
    check_outputs((plot, "--plot", "png"))
    sysobj = make_system("sdof", p=p, delta=delta, ap_min=ap_min, g=g,
                         restitution=restitution, t_free=t_free)
    _run(sysobj, sysobj.name, signal, period, cycles, record, units, ratio, plot, json_out)


def _mdof_system(shape, span, rise, thickness, blocks, structure, g, t_free, h_factor,
                 gap_tol):
    """The MDOF structure of `simulate mdof` / `animate`: an arch (alone or on piers) or
    the structure of the other options (``structure``: :func:`mdof_structure` keywords)."""
    others = {"column", "wall", "colonnade", "assembly"} & set(structure)
    if not others and None in (shape, span, rise, thickness, blocks):
        raise ValueError("give the arch: --shape S --span L --rise F --thickness D --blocks N "
                         "(or --column 'B,H;B,H', --wall R,C --block B,H, --colonnade N "
                         "--block B,H --bay S --lintel D, or --assembly FILE.json)")
    if not others:
        span, rise = positive("--span", span), positive("--rise", rise)
        thickness = positive("--thickness", thickness)
    return make_system("mdof", shape=value(shape), span=span, rise=rise, thickness=thickness,
                       blocks=blocks, g=g, t_free=t_free, h_factor=h_factor, gap_tol=gap_tol,
                       **structure)


def _mdof_header(a) -> str:
    fr = "" if a.frictionless else f", friction {np.min(a.mu):g}" + (
        "" if np.ptp(a.mu) == 0 else f"..{np.max(a.mu):g}")
    return (f"{a.name}: {a.n_blocks} blocks, {a.n_joints} joints{fr}, "
            f"ap,min={a.ap_min:.4g} m/s², p={a.p_ref:.4g} 1/s, delta={a.delta_ref:.4g} rad "
            "(Moreau–Jean, docs/mdof.md)")


@simulate_app.command("mdof")
@guarded
def simulate_mdof(
    shape: Shape = SHAPE_OPT, span: float = SPAN_OPT, rise: float = RISE_OPT,
    thickness: float = THICK_OPT, blocks: int = MDOF_BLOCKS_OPT, column: str = COLUMN_OPT,
    friction: float = FRICTION_OPT, spans: int = SPANS_OPT, pier_height: float = PIER_H_OPT,
    pier_width: float = PIER_W_OPT, pier_blocks: int = PIER_BLOCKS_OPT,
    abutments: bool = ABUT_OPT, wall: str = WALL_OPT, block: str = BLOCK_OPT,
    colonnade: int = COLONNADE_OPT, bay: float = BAY_OPT, lintel: float = LINTEL_OPT,
    assembly: Path = ASSEMBLY_OPT,
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    t_free: float = TFREE_OPT, g: float = G_OPT, h_factor: float = MDOF_H_OPT,
    gap_tol: float = MDOF_TOL_OPT, plot: Path = typer.Option(
        None, help="Write a PNG of the largest block rotation / delta and a_g over time."),
    json_out: bool = JSON_OPT,
    mechanism: Path = typer.Option(None, help="Also write a PNG of the static collapse "
                                   "mechanism (docs/theory.md §10)."),
) -> None:
    """Simulate a multi-block structure whose joints open, close and (with --friction)
    slide: an arch (alone, on piers, a bridge), a column, a wall, a colonnade, a JSON file.

    --ratio is relative to the structure's ap,min (limit analysis, friction included).
    """
    check_outputs((plot, "--plot", "png"), (mechanism, "--mechanism", "png"))
    sysobj = _mdof_system(shape, span, rise, thickness, blocks, mdof_structure(locals()), g,
                          t_free, h_factor, gap_tol)
    if mechanism is not None:
        plot_collapse(sysobj.assembly, mechanism)
    _run(sysobj, _mdof_header(sysobj.assembly), signal, period, cycles, record, units, ratio,
         plot, json_out, extra={"ap_min": sysobj.ap_min})
    if mechanism is not None and not json_out:
        typer.echo(f"wrote {mechanism}")


@app.command(short_help="GIF of an MDOF arch or column in motion.")
@guarded
def animate(
    out: Path = typer.Option(..., help="GIF file to write."),
    shape: Shape = SHAPE_OPT, span: float = SPAN_OPT, rise: float = RISE_OPT,
    thickness: float = THICK_OPT, blocks: int = MDOF_BLOCKS_OPT, column: str = COLUMN_OPT,
    friction: float = FRICTION_OPT, spans: int = SPANS_OPT, pier_height: float = PIER_H_OPT,
    pier_width: float = PIER_W_OPT, pier_blocks: int = PIER_BLOCKS_OPT,
    abutments: bool = ABUT_OPT, wall: str = WALL_OPT, block: str = BLOCK_OPT,
    colonnade: int = COLONNADE_OPT, bay: float = BAY_OPT, lintel: float = LINTEL_OPT,
    assembly: Path = ASSEMBLY_OPT,
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    t_free: float = typer.Option(3.0, help="Free motion after the ground motion ends [s]."),
    g: float = G_OPT, h_factor: float = MDOF_H_OPT, gap_tol: float = MDOF_TOL_OPT,
    fps: int = typer.Option(20, help="Frames per second of simulated time (the GIF plays "
                            "in real time)."),
    frames: int = typer.Option(150, help="Largest number of frames (when fps × duration is "
                               "larger, this many, spread evenly over the motion)."),
    magnify: float = typer.Option(1.0, help="Magnify the displacements (>= 1); the held "
                                  "last frame is magnified further when its displacements "
                                  "would be too small to see (the factor is in its title)."),
    progress: bool = typer.Option(None, "--progress/--no-progress",
                                  help="Progress bar on stderr (default: when stderr is a "
                                  "terminal)."),
    json_out: bool = JSON_OPT,
) -> None:
    """Animate an MDOF arch or column on a ground motion: blocks, open joints, a_g(t)."""

    check_options(fps, frames, magnify)
    check_outputs((out, "--out", "gif"))
    sysobj = _mdof_system(shape, span, rise, thickness, blocks, mdof_structure(locals()), g,
                          t_free, h_factor, gap_tol)
    resp = sysobj.simulate(motion_shape(signal, period, cycles, record, units), ratio=ratio)
    write_gif(resp, out, fps=fps, max_frames=frames, magnify=magnify, progress=progress)
    if json_out:
        print_json({**resp.to_dict(), "out": str(out)})
        return
    typer.echo(_mdof_header(sysobj.assembly))
    typer.echo(f"wrote {out}")
