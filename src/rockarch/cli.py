"""The ``rockarch`` command line (typer). Every command accepts ``--json``.

Errors in the input print one line on stderr (``error: ...``) and exit with status 2.
"""

from __future__ import annotations

import sys
from enum import Enum
from pathlib import Path

import numpy as np
import typer

from rockarch._cli_util import fail, guarded, print_json
from rockarch._validate import positive

# rich_markup_mode=None: help texts show units such as "[m/s²]" literally (not as markup)
app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=None,
    help="Seismic overturning assessment of rocking blocks and masonry arches.",
)
simulate_app = typer.Typer(no_args_is_help=True, rich_markup_mode=None,
                           help="Simulate one structure on one ground motion.")
app.add_typer(simulate_app, name="simulate")


class Signal(str, Enum):
    sine = "sine"
    square = "square"
    step = "step"
    halfsine = "halfsine"
    harmonic = "harmonic"
    ricker = "ricker"


class System(str, Enum):
    block = "block"
    fourhinge = "fourhinge"
    frame = "frame"
    sdof = "sdof"
    mdof = "mdof"


class Shape(str, Enum):
    catenary = "catenary"
    circular = "circular"
    pointed = "pointed"
    elliptical = "elliptical"


def _oas_system(system: System, *, alpha, shape, rise_over_span, thickness_over_span, blocks,
                mass_ratio, delta, ap_min, g, restitution, t_free):
    """The OASSystem for --system (p varies across the map by scaling the size)."""
    from rockarch import spectra

    def need(**kw):
        missing = [k for k, v in kw.items() if v is None]
        if missing:
            flags = ", ".join("--" + k.replace("_", "-") for k in missing)
            raise ValueError(f"--system {system.value} needs {flags}")

    if system is System.block:
        need(alpha=alpha)
        return spectra.BlockSystem(alpha=alpha, g=g, restitution=restitution, t_free=t_free)
    if system is System.mdof:
        need(shape=shape, rise_over_span=rise_over_span,
             thickness_over_span=thickness_over_span, blocks=blocks)
        return _mdof_arch_system(shape, rise_over_span, thickness_over_span, blocks, g,
                                 restitution, t_free)
    from rockarch import mechanism as mc

    if system is System.fourhinge:
        need(shape=shape, rise_over_span=rise_over_span,
             thickness_over_span=thickness_over_span)
        from rockarch.arch.dynamics import fourhinge_mechanism
        from rockarch.arch.geometry import make_arch

        arch = make_arch(shape.value, 1.0, positive("--rise-over-span", rise_over_span),
                         positive("--thickness-over-span", thickness_over_span))
        mech = fourhinge_mechanism(
            arch, _check_blocks(blocks), g=g, restitution=restitution,
            name=f"{shape.value} f/l={rise_over_span:g} d/l={thickness_over_span:g}")
    elif system is System.frame:
        need(alpha=alpha, mass_ratio=mass_ratio)
        mech = mc.rocking_frame(alpha, 1.0, mass_ratio, g, restitution)
    else:
        need(delta=delta, ap_min=ap_min)
        mech = mc.generic(1.0, delta, ap_min, g, restitution)
    return spectra.MechanismSystem(mech, t_free=t_free)


def _mdof_arch_system(shape, rise_over_span, thickness_over_span, blocks, g, restitution,
                      t_free):
    """MDOF arch of span 1 (p varies by scaling): ratio relative to its N-voussoir ap,min."""
    from rockarch.arch.geometry import make_arch
    from rockarch.mdof import MDOFSystem, arch_assembly

    if restitution is not None:
        raise ValueError("--system mdof has no --restitution: joints close with inelastic "
                         "impacts (the restitution follows from the geometry)")
    arch = make_arch(shape.value, 1.0, positive("--rise-over-span", rise_over_span),
                     positive("--thickness-over-span", thickness_over_span))
    return MDOFSystem(arch_assembly(arch, blocks, g=positive("--g", g)), t_free=t_free)


def _check_blocks(blocks: int | None) -> int | None:
    if blocks is not None and blocks < 4:
        raise ValueError(f"at least 4 voussoirs are needed for a four-hinge mechanism, "
                         f"got {blocks}")
    return blocks


def _float_list(name: str, text: str) -> np.ndarray:
    try:
        vals = [float(v) for v in text.replace(";", ",").split(",") if v.strip()]
    except ValueError:
        raise ValueError(
            f"{name} must be a comma-separated list of numbers, got {text!r}") from None
    if not vals:
        raise ValueError(f"{name} is empty")
    return np.array(vals)


def _shape(signal: Signal | None, period: float | None, cycles: int, record: Path | None,
           units: str | None):
    """The ground-motion shape (peak 1 for pulses; the record as read)."""
    from rockarch import motion as mo
    from rockarch.records import read_record

    if record is not None and signal is not None:
        raise ValueError("give either --record or --signal/--period, not both")
    if record is not None:
        return read_record(record, units=units)
    if signal is None:
        raise ValueError("give a ground motion: --signal S --period T, or --record PATH")
    if period is None:
        raise ValueError(f"--signal {signal.value} needs --period T (seconds)")
    return mo.pulse(signal.value, 1.0, period, cycles)


def _p_grid(p: str | None, p_min: float | None, p_max: float | None, p_steps: int):
    if p is not None:
        if p_min is not None or p_max is not None:
            raise ValueError("give either --p LIST or --p-min/--p-max/--p-steps, not both")
        return _float_list("--p", p)
    if p_min is None or p_max is None:
        raise ValueError("give the p values: --p 0.5,1,2 or --p-min A --p-max B --p-steps N")
    if not (0 < p_min < p_max):
        raise ValueError(f"need 0 < --p-min < --p-max, got {p_min} and {p_max}")
    if p_steps < 2:
        raise ValueError("--p-steps must be >= 2")
    return np.round(np.linspace(p_min, p_max, p_steps), 12)


# sweep options (rockarch.sweep; docs/sweeps.md), shared by oas and site-oas
WORKERS_OPT = typer.Option(None, help="Local worker processes (default: every core; small "
                           "sweeps run in-process).")
SCHEDULER_OPT = typer.Option(None, help="Run on a running Dask scheduler tcp://HOST:PORT.")
DASK_WORKERS_OPT = typer.Option(None, help="Start a local Dask cluster of N workers.")
STORE_OPT = typer.Option(None, help="Resumable store of finished chunks (default: "
                         "$ROCKARCH_CACHE or ~/.cache/rockarch).")
NO_STORE_OPT = typer.Option(False, "--no-store", help="Keep no store (always recompute).")


@app.command()
@guarded
def oas(
    system: System = typer.Option(System.block, help="Structure whose OAS is computed: a "
                                  "rigid block, the four-hinge mechanism of an arch, a rocking "
                                  "frame, or any SDOF mechanism given by delta and ap,min."),
    alpha: float = typer.Option(None, help="block/frame: slenderness atan(B/H) [rad]."),
    shape: Shape = typer.Option(None, help="fourhinge/mdof: arch shape."),
    rise_over_span: float = typer.Option(None, help="fourhinge/mdof: f/l."),
    thickness_over_span: float = typer.Option(None, help="fourhinge/mdof: d/l."),
    blocks: int = typer.Option(None, help="fourhinge: voussoirs (critical mechanism); "
                               "default the continuous arch (critical optimal). mdof: "
                               "voussoirs (required)."),
    mass_ratio: float = typer.Option(None, help="frame: lintel mass / mass of both columns."),
    delta: float = typer.Option(None, help="sdof: neutral angle delta [rad]."),
    ap_min: float = typer.Option(None, "--ap-min", help="sdof: limit acceleration [m/s²]."),
    signal: Signal = typer.Option(None, help="Pulse shape (paper Fig. 14)."),
    period: float = typer.Option(None, help="Pulse period T [s]."),
    cycles: int = typer.Option(3, help="Number of cycles of --signal harmonic."),
    record: Path = typer.Option(None, help="Record file (.AT2 or two-column time/acc)."),
    units: str = typer.Option(None, help="Units of a two-column record: m/s2 (default), g, "
                              "cm/s2."),
    p: str = typer.Option(None, "--p", help="Comma-separated p values [1/s]."),
    p_min: float = typer.Option(None, help="Smallest p of a linear grid [1/s]."),
    p_max: float = typer.Option(None, help="Largest p of a linear grid [1/s]."),
    p_steps: int = typer.Option(50, help="Number of p values of the grid."),
    ratio_min: float = typer.Option(1.0, help="Smallest ap/ap,min."),
    ratio_max: float = typer.Option(5.0, help="Largest ap/ap,min."),
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values."),
    tol: float = typer.Option(1e-3, help="Bisection tolerance of the boundary (ratio)."),
    restitution: float = typer.Option(None, help="Coefficient of restitution in [0, 1] "
                                      "(default: Housner's 1 - 1.5 sin²alpha)."),
    t_free: float = typer.Option(10.0, help="Free rocking after the motion ends [s]."),
    g: float = typer.Option(9.81, help="Acceleration of gravity [m/s²]."),
    out: Path = typer.Option(None, help="Write the OAS to this NetCDF file."),
    plot: Path = typer.Option(None, help="Write a PNG plot of the OAS."),
    json_out: bool = typer.Option(False, "--json", help="Print one JSON object."),
    progress: bool = typer.Option(True, help="Show a progress bar on stderr."),
    workers: int = WORKERS_OPT, scheduler: str = SCHEDULER_OPT,
    dask_workers: int = DASK_WORKERS_OPT, store: Path = STORE_OPT, no_store: bool = NO_STORE_OPT,
) -> None:
    """Overturning acceleration spectrum (OAS) over p × ap/ap,min for one ground motion.

    Pulses have peak ap = ratio·ap,min; a record is scaled so that its PGA = ratio·ap,min.
    For mechanisms p varies by scaling the structure (p ∝ 1/sqrt(size), same shape).
    """
    from rockarch import spectra

    sysobj = _oas_system(system, alpha=alpha, shape=shape, rise_over_span=rise_over_span,
                         thickness_over_span=thickness_over_span, blocks=blocks,
                         mass_ratio=mass_ratio, delta=delta, ap_min=ap_min, g=g,
                         restitution=restitution, t_free=t_free)
    shape_motion = _shape(signal, period, cycles, record, units)
    ps = _p_grid(p, p_min, p_max, p_steps)
    if ratio_steps < 1:
        raise ValueError("--ratio-steps must be >= 1")
    if not (0 <= ratio_min <= ratio_max):
        raise ValueError(f"need 0 <= --ratio-min <= --ratio-max, got {ratio_min}, {ratio_max}")
    # rounded to 12 digits so that 1.7 prints as 1.7, not 1.7000000000000002
    ratios = np.round(np.linspace(ratio_min, ratio_max, ratio_steps), 12) \
        if ratio_steps > 1 else np.array([ratio_min])
    for path in (out, plot):
        if path is not None and not path.resolve().parent.is_dir():
            raise ValueError(f"{path.parent}: directory does not exist")
    from rockarch.sweep import open_sweep

    with open_sweep(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                    store_dir=store, no_store=no_store, n_sims=ps.size * ratios.size,
                    echo=lambda msg: typer.echo(msg, err=True)) as (executor, chunk_store):
        ds = spectra.compute_oas(sysobj, shape_motion, ps, ratios, tol=tol,
                                 progress=progress and sys.stderr.isatty(),
                                 executor=executor, store=chunk_store)
    if out is not None:
        spectra.save(ds, out)
    if plot is not None:
        from rockarch.plot import plot_oas, save_figure

        ax = plot_oas(ds)
        save_figure(ax.figure, plot)
    if json_out:
        print_json({
            "p": ds["p"].values,
            "ratio": ds["ratio"].values,
            "overturned": ds["overturned"].values,
            "boundary": ds["boundary"].values,
        })
        return
    typer.echo(f"OAS of {sysobj.name} for {shape_motion.name}")
    typer.echo(f"{'p [1/s]':>10}  {'boundary ap/ap,min':>20}")
    for pv, bv in zip(ds["p"].values, ds["boundary"].values, strict=True):
        txt = f"{bv:.4f}" if np.isfinite(bv) else f"> {ratios[-1]:g} (none in range)"
        typer.echo(f"{pv:>10.4g}  {txt:>20}")
    for path in (out, plot):
        if path is not None:
            typer.echo(f"wrote {path}")


def _run_simulation(structure, header: str, ap_min: float, run, signal, period, cycles,
                    record, units, ratio, plot, json_out) -> None:
    """Scale the motion to a peak of ratio·ap,min, run, then print JSON or a summary."""
    if not (ratio >= 0 and np.isfinite(ratio)):
        raise ValueError(f"--ratio must be a finite number >= 0, got {ratio}")
    shape = _shape(signal, period, cycles, record, units)
    mot = shape.scaled(ratio * ap_min / shape.pga)
    if plot is not None and not plot.resolve().parent.is_dir():
        raise ValueError(f"{plot.parent}: directory does not exist")
    resp = run(mot)
    if plot is not None:
        from rockarch.plot import plot_response, save_figure

        save_figure(plot_response(resp, mot), plot)
    s = resp.summary()
    if json_out:
        print_json(s)
        return
    typer.echo(header)
    typer.echo(f"motion: {mot.name}, PGA={mot.pga:.4g} m/s² = {ratio:g} ap,min")
    if s["overturned"]:
        typer.echo(f"OVERTURNED at t = {s['t_overturn']:.4f} s after {s['impacts']} impacts")
    else:
        typer.echo(f"safe: max rotation / its overturning value = "
                   f"{s['max_theta_over_alpha']:.4f}, {s['impacts']} impacts")
    if plot is not None:
        typer.echo(f"wrote {plot}")


SIGNAL_OPT = typer.Option(None, help="Pulse shape (paper Fig. 14).")
PERIOD_OPT = typer.Option(None, help="Pulse period T [s].")
CYCLES_OPT = typer.Option(3, help="Number of cycles of --signal harmonic.")
RECORD_OPT = typer.Option(None, help="Record file (.AT2 or two-column time/acc).")
UNITS_OPT = typer.Option(None, help="Units of a two-column record: m/s2 (default), g, cm/s2.")
RATIO_OPT = typer.Option(..., help="ap/ap,min: pulse peak or record PGA over ap,min.")
REST_OPT = typer.Option(None, help="Coefficient of restitution in [0, 1] (default: the "
                        "structure's own impact law).")
TFREE_OPT = typer.Option(10.0, help="Free motion after the ground motion ends [s].")
G_OPT = typer.Option(9.81, help="Acceleration of gravity [m/s²].")
PLOT_OPT = typer.Option(None, help="Write a PNG of the rotation and a_g over time.")
JSON_OPT = typer.Option(False, "--json", help="Print one JSON object.")


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
    from rockarch.block import RigidBlock, simulate

    if width is not None or height is not None:
        if p is not None or alpha is not None:
            raise ValueError("give either --width/--height or --p/--alpha, not both")
        if width is None or height is None:
            raise ValueError("--width and --height go together")
        blk = RigidBlock.from_dimensions(width, height, g, restitution)
    else:
        if p is None or alpha is None:
            raise ValueError("give the block: --p P --alpha A (or --width B --height H)")
        blk = RigidBlock(p, alpha, g, restitution)
    header = (f"block p={blk.p:.4g} 1/s alpha={blk.alpha:.4g} rad (B={blk.width:.4g} m, "
              f"H={blk.height:.4g} m, ap,min={blk.ap_min:.4g} m/s², r={blk.r:.4f})")
    _run_simulation(blk, header, blk.ap_min, lambda m: simulate(blk, m, t_free=t_free),
                    signal, period, cycles, record, units, ratio, plot, json_out)


def _simulate_mechanism(mech, p, header, signal, period, cycles, record, units, ratio,
                        t_free, plot, json_out) -> None:
    from rockarch import mechanism as mc

    _run_simulation(mech, header, mech.ap_min,
                    lambda m: mc.simulate(mech, m, p=p, t_free=t_free),
                    signal, period, cycles, record, units, ratio, plot, json_out)


@simulate_app.command("fourhinge")
@guarded
def simulate_fourhinge(
    shape: Shape = typer.Option(..., help="Arch shape."),
    span: float = typer.Option(..., help="Span l of the axis [m]."),
    rise: float = typer.Option(..., help="Rise f of the axis [m]."),
    thickness: float = typer.Option(..., help="Uniform thickness d [m]."),
    blocks: int = typer.Option(None, help="Voussoirs (critical mechanism); default the "
                               "continuous arch (critical optimal mechanism)."),
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    restitution: float = REST_OPT, t_free: float = TFREE_OPT, g: float = G_OPT,
    plot: Path = PLOT_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate the four-hinge mechanism of an arch (exact linkage kinematics, Sect. 5)."""
    from rockarch.arch.dynamics import fourhinge_mechanism
    from rockarch.arch.geometry import make_arch

    arch = make_arch(shape.value, positive("--span", span), positive("--rise", rise),
                     positive("--thickness", thickness))
    mech = fourhinge_mechanism(arch, _check_blocks(blocks), g=positive("--g", g),
                               restitution=restitution)
    header = (f"{mech.name}: p={mech.p:.4g} 1/s, delta={mech.delta:.4g} rad, "
              f"ap,min={mech.ap_min:.4g} m/s², impact e={mech.plus.e_close:.4f}/"
              f"{mech.minus.e_close:.4f}")
    _simulate_mechanism(mech, None, header, signal, period, cycles, record, units, ratio,
                        t_free, plot, json_out)


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
    from rockarch.mechanism import rocking_frame

    mech = rocking_frame(alpha, p, mass_ratio, g, restitution)
    header = (f"{mech.name}: p={mech.p:.4g} 1/s (Eq. 12), ap,min={mech.ap_min:.4g} m/s², "
              f"e={mech.plus.e_close:.4f}")
    _simulate_mechanism(mech, None, header, signal, period, cycles, record, units, ratio,
                        t_free, plot, json_out)


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
    from rockarch.mechanism import generic

    mech = generic(p, delta, ap_min, g, restitution)
    _simulate_mechanism(mech, None, mech.name, signal, period, cycles, record, units, ratio,
                        t_free, plot, json_out)


def _mdof_assembly(shape, span, rise, thickness, blocks, column, g):
    """The MDOF structure of `simulate mdof` / `animate`: an arch or a column."""
    from rockarch import mdof

    g = positive("--g", g)
    if column is not None:
        if shape is not None or blocks is not None:
            raise ValueError("give either --column or an arch (--shape ... --blocks N)")
        rows = [r for r in column.split(";") if r.strip()]
        return mdof.column([_float_list("--column block", r) for r in rows], g=g)
    if shape is None or span is None or rise is None or thickness is None or blocks is None:
        raise ValueError("give the arch: --shape S --span L --rise F --thickness D --blocks N "
                         "(or a column: --column 'B,H;B,H')")
    from rockarch.arch.geometry import make_arch

    arch = make_arch(shape.value, positive("--span", span), positive("--rise", rise),
                     positive("--thickness", thickness))
    return mdof.arch_assembly(arch, blocks, g=g)


MDOF_SHAPE_OPT = typer.Option(None, help="Arch shape.")
MDOF_SPAN_OPT = typer.Option(None, help="Span l of the axis [m].")
MDOF_RISE_OPT = typer.Option(None, help="Rise f of the axis [m].")
MDOF_THICK_OPT = typer.Option(None, help="Uniform thickness d [m].")
MDOF_BLOCKS_OPT = typer.Option(None, help="Number of voussoirs N (at least 5).")
MDOF_COLUMN_OPT = typer.Option(None, help="A column instead of an arch: blocks bottom to "
                               "top, 'B,H;B,H' or 'B,H,x_centre;...' [m].")
MDOF_H_OPT = typer.Option(0.005, help="Time step × p (safe range 1e-4 … 0.05).")
MDOF_TOL_OPT = typer.Option(1e-4, help="Contact tolerance / joint thickness (1e-10 … 1e-3).")


def _mdof_header(a) -> str:
    return (f"{a.name}: {a.n_blocks} blocks, {a.n_joints} joints, ap,min={a.ap_min:.4g} m/s², "
            f"p={a.p_ref:.4g} 1/s, delta={a.delta_ref:.4g} rad (Moreau–Jean, docs/mdof.md)")


@simulate_app.command("mdof")
@guarded
def simulate_mdof(
    shape: Shape = MDOF_SHAPE_OPT, span: float = MDOF_SPAN_OPT, rise: float = MDOF_RISE_OPT,
    thickness: float = MDOF_THICK_OPT, blocks: int = MDOF_BLOCKS_OPT,
    column: str = MDOF_COLUMN_OPT,
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    t_free: float = TFREE_OPT, g: float = G_OPT, h_factor: float = MDOF_H_OPT,
    gap_tol: float = MDOF_TOL_OPT, json_out: bool = JSON_OPT,
) -> None:
    """Simulate a multi-block arch (any joint may open and close) or column (MDOF model).

    --ratio is relative to the ap,min of the N-voussoir arch (thrust-line LP).
    """
    from rockarch import mdof

    a = _mdof_assembly(shape, span, rise, thickness, blocks, column, g)
    mdof.simulate(a, None, t_free=t_free, h_factor=h_factor, gap_tol=gap_tol)  # validate
    _run_simulation(a, _mdof_header(a), a.ap_min,
                    lambda m: mdof.simulate(a, m, t_free=t_free, h_factor=h_factor,
                                            gap_tol=gap_tol),
                    signal, period, cycles, record, units, ratio, None, json_out)


@app.command()
@guarded
def animate(
    out: Path = typer.Option(..., help="GIF file to write."),
    shape: Shape = MDOF_SHAPE_OPT, span: float = MDOF_SPAN_OPT, rise: float = MDOF_RISE_OPT,
    thickness: float = MDOF_THICK_OPT, blocks: int = MDOF_BLOCKS_OPT,
    column: str = MDOF_COLUMN_OPT,
    signal: Signal = SIGNAL_OPT, period: float = PERIOD_OPT, cycles: int = CYCLES_OPT,
    record: Path = RECORD_OPT, units: str = UNITS_OPT, ratio: float = RATIO_OPT,
    t_free: float = typer.Option(3.0, help="Free motion after the ground motion ends [s]."),
    g: float = G_OPT, h_factor: float = MDOF_H_OPT, gap_tol: float = MDOF_TOL_OPT,
    fps: int = typer.Option(20, help="Frames per second."),
    frames: int = typer.Option(150, help="Largest number of frames."),
    magnify: float = typer.Option(1.0, help="Magnify the displacements (>= 1)."),
    json_out: bool = JSON_OPT,
) -> None:
    """Animate an MDOF arch or column on a ground motion: blocks, open joints, a_g(t)."""
    from rockarch import mdof
    from rockarch.mdof.animate import animate as write_gif

    a = _mdof_assembly(shape, span, rise, thickness, blocks, column, g)
    if out.suffix.lower() != ".gif":
        raise ValueError(f"--out must be a .gif file, got {out}")
    if not out.resolve().parent.is_dir():
        raise ValueError(f"{out.parent}: directory does not exist")
    if not (ratio >= 0 and np.isfinite(ratio)):
        raise ValueError(f"--ratio must be a finite number >= 0, got {ratio}")
    shape_m = _shape(signal, period, cycles, record, units)
    mot = shape_m.scaled(ratio * a.ap_min / shape_m.pga)
    resp = mdof.simulate(a, mot, t_free=t_free, h_factor=h_factor, gap_tol=gap_tol)
    write_gif(resp, out, fps=fps, max_frames=frames, magnify=magnify)
    if json_out:
        print_json({**resp.summary(), "out": str(out)})
        return
    typer.echo(_mdof_header(a))
    typer.echo(f"wrote {out}")


# --- arch statics (rockarch.arch; imported inside the command: scipy.optimize is slow to load)


@app.command()
@guarded
def arch(
    shape: str = typer.Option(..., "--shape",
                              help="catenary, circular, pointed or elliptical"),
    span: float = typer.Option(..., "--span", help="span l of the axis, m"),
    rise: float = typer.Option(..., "--rise", help="rise f of the axis, m"),
    thickness: float = typer.Option(None, "--thickness",
                                    help="uniform thickness d normal to the axis, m"),
    blocks: int = typer.Option(None, "--blocks",
                               help="number of voussoirs (critical mechanism); default: the "
                                    "continuous arch (critical optimal mechanism)"),
    g: float = typer.Option(9.81, "--g", help="gravity, m/s²"),
    min_thickness: bool = typer.Option(False, "--min-thickness",
                                       help="print the minimum thickness of this axis shape"),
    lambda_: float = typer.Option(0.0, "--lambda",
                                  help="with --min-thickness: horizontal acceleration / g"),
    direction: int = typer.Option(1, "--direction",
                                  help="+1: ground acceleration to the right (the arch falls "
                                       "to the left); -1: the mirror case"),
    mass_model: str = typer.Option("voussoir", "--mass-model",
                                   help="voussoir (true voussoir polygons) or axis (mass "
                                        "lumped on the axis)"),
    plot: str = typer.Option(None, "--plot", help="save a PNG of the collapse mechanism"),
    as_json: bool = typer.Option(False, "--json", help="print one JSON object"),
) -> None:
    """Limit acceleration ap,min, four-hinge mechanism (p, delta, hinges) and Eq. 14 constants.

    Sign convention: lambda >= 0 is the magnitude of the ground acceleration / g; with
    --direction +1 the ground accelerates to the right and the inertia loads push the arch to
    the left.
    """
    from rockarch.arch.fourhinge import analyse
    from rockarch.arch.geometry import make_arch
    from rockarch.arch.thrust import minimum_thickness

    span = positive("span", span)
    rise = positive("rise", rise)
    g = positive("g", g)
    _check_blocks(blocks)
    if min_thickness:
        probe = make_arch(shape, span, rise, thickness if thickness else 0.01 * span,
                          mass_model=mass_model)
        d = minimum_thickness(probe, lambda_, blocks=blocks, direction=direction)
        if as_json:
            print_json({"d_min": d, "d_min_over_l": d / span})
        else:
            typer.echo(f"{shape} arch l = {span:g} m, f = {rise:g} m: minimum thickness "
                       f"{d:.6g} m (d/l = {d / span:.6g}) at lambda = {lambda_:g}")
        return
    if thickness is None:
        raise ValueError("--thickness is required (unless --min-thickness)")
    a = make_arch(shape, span, rise, positive("thickness", thickness), mass_model=mass_model)
    res = analyse(a, blocks, g=g, direction=direction)
    if plot:
        from rockarch.plot_arch import plot_mechanism

        plot_mechanism(res, plot)
    if as_json:
        print_json(res.as_dict())
        return
    lines = [
        f"{shape} arch: l = {span:g} m, f = {rise:g} m, d = {thickness:g} m, "
        + (f"{blocks} voussoirs (critical mechanism)" if blocks
           else "continuous (critical optimal mechanism)"),
        f"  ap,min = {res.ap_min:.4f} m/s² (lambda = {res.lambda_:.5f}; virtual work "
        f"g*Bv/Bh = {res.ap_min_vw:.4f})",
        f"  p = {res.p:.4f} 1/s, delta = {res.delta:.5f} rad, Bv = {res.Bv:.5g}, "
        f"Bh = {res.Bh:.5g}, A = {res.A:.5g}",
        f"  c1 = {res.c1:.4f}, c2 = {res.c2:.4f}, c3/c3' = {res.c3:.3f}/{res.c3p:.3f}, "
        f"c4 = {res.c4:.4f}",
        "  hinges: " + ", ".join(f"({h.x:.3f}, {h.y:.3f}) {h.side}" for h in res.hinges),
    ]
    if plot:
        lines.append(f"  figure: {plot}")
    typer.echo("\n".join(lines))


# --- site OAS and design check (paper Sect. 9) --------------------------------------------------


@app.command("site-oas")
@guarded
def site_oas_command(
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
    ratio_steps: int = typer.Option(81, help="Number of ap/ap,min values."),
    alpha: float = typer.Option(0.05, help="Slenderness of the site's block [rad]."),
    percentile: float = typer.Option(50.0, help="Percentile of the records' boundaries "
                                     "stored as the characteristic curve (lower: safer)."),
    tol: float = typer.Option(1e-3, help="Bisection tolerance of each boundary."),
    t_free: float = typer.Option(10.0, help="Free rocking after each record [s]."),
    out: Path = typer.Option(..., help="NetCDF file to write."),
    plot: Path = typer.Option(None, help="PNG of the records' OAS boundaries and curves."),
    json_out: bool = typer.Option(False, "--json", help="Print one JSON object."),
    workers: int = WORKERS_OPT, scheduler: str = SCHEDULER_OPT,
    dask_workers: int = DASK_WORKERS_OPT, store: Path = STORE_OPT, no_store: bool = NO_STORE_OPT,
) -> None:
    """Site OAS: slender-block OAS of every record, their envelope and percentile curve."""
    from rockarch import site

    paths = list(records or []) + list(more or [])
    for path in (out, plot):
        if path is not None and not path.resolve().parent.is_dir():
            raise ValueError(f"{path.parent}: directory does not exist")
    motions, hashes = site.load_records(paths, units)
    ps = _p_grid(None, p_min, p_max, p_steps)
    if ratio_steps < 2 or not (0 <= ratio_min < ratio_max):
        raise ValueError("need --ratio-steps >= 2 and 0 <= --ratio-min < --ratio-max")
    ratios = np.round(np.linspace(ratio_min, ratio_max, ratio_steps), 12)
    from rockarch.sweep import open_sweep

    with open_sweep(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                    store_dir=store, no_store=no_store,
                    n_sims=ps.size * ratios.size * len(motions),
                    echo=lambda msg: typer.echo(msg, err=True)) as (executor, chunk_store):
        ds = site.site_oas(motions, ps, ratios, alpha=alpha, percentile=percentile, tol=tol,
                           hashes=hashes, t_free=t_free, progress=sys.stderr.isatty(),
                           executor=executor, store=chunk_store)
    site.save(ds, out)
    if plot is not None:
        import matplotlib.pyplot as plt

        from rockarch.plot import save_figure

        fig, ax = plt.subplots(figsize=(7, 4.4))
        for k in range(ds.sizes["record"]):
            ax.plot(ds["p"].values, ds["boundary"].values[k], lw=0.8,
                    label=str(ds["record_name"].values[k])[:50])
        ax.plot(ds["p"].values, ds["envelope"].values, "k-", lw=2, label="envelope")
        ax.plot(ds["p"].values, ds["characteristic"].values, "k--", lw=1.2,
                label=f"{percentile:g}th percentile")
        ax.set_xlabel("frequency parameter p [1/s]")
        ax.set_ylabel("lowest overturning ap/ap,min")
        ax.set_title(ds.attrs["title"], fontsize=9)
        ax.legend(fontsize=7)
        save_figure(fig, plot)
    if json_out:
        print_json({"records": list(ds["record_name"].values), "p": ds["p"].values,
                    "envelope": ds["envelope"].values,
                    "characteristic": ds["characteristic"].values, "out": str(out)})
        return
    typer.echo(f"site OAS of {len(motions)} record(s) written to {out}")
    for path in ([plot] if plot else []):
        typer.echo(f"wrote {path}")


@app.command()
@guarded
def design(
    shape: Shape = typer.Option(..., help="Arch shape."),
    span: float = typer.Option(..., help="Span l of the axis [m]."),
    rise: float = typer.Option(..., help="Rise f of the axis [m]."),
    thickness: float = typer.Option(..., help="Uniform thickness d [m]."),
    site_file: Path = typer.Option(..., "--site", help="Site OAS file (rockarch site-oas)."),
    thickness_rule: str = typer.Option("equivalent", help="Replacement catenary thickness: "
                                       "equivalent (same ap,min) or lower-bound."),
    curve: str = typer.Option("envelope", help="Site curve: envelope or characteristic."),
    g: float = typer.Option(9.81, help="Acceleration of gravity [m/s²]."),
    report: Path = typer.Option(None, help="Write a self-contained HTML report."),
    json_out: bool = typer.Option(False, "--json", help="Print one JSON object."),
) -> None:
    """Largest safe PGA of an arch at a site (paper Sect. 9): replacement catenary, site OAS."""
    from rockarch import site
    from rockarch.arch.geometry import make_arch
    from rockarch.design import design_check

    if thickness_rule not in ("equivalent", "lower-bound"):
        raise ValueError(f"--thickness-rule must be equivalent or lower-bound, got "
                         f"{thickness_rule!r}")
    if report is not None and not report.resolve().parent.is_dir():
        raise ValueError(f"{report.parent}: directory does not exist")
    site_ds = site.load(site_file)
    arch = make_arch(shape.value, positive("--span", span), positive("--rise", rise),
                     positive("--thickness", thickness))
    res = design_check(arch, site_ds, rule=thickness_rule, curve=curve, g=g)
    if res.ratio_is_lower_bound:
        typer.echo("warning: no record overturns the equivalent block within the site's ratio "
                   "range; the result is a lower bound", err=True)
    if report is not None:
        from rockarch.report import write_report

        cmd = (f"rockarch design --shape {shape.value} --span {span:g} --rise {rise:g} "
               f"--thickness {thickness:g} --site {site_file} --thickness-rule "
               f"{thickness_rule} --curve {curve} --g {g:g}")
        write_report(res, site_ds, report, command=cmd, site_path=str(site_file),
                     inputs={"shape": shape.value, "span [m]": span, "rise [m]": rise,
                             "thickness [m]": thickness})
    if json_out:
        print_json(res.as_dict())
        return
    c = res.chosen
    typer.echo(f"{shape.value} arch l = {span:g} m, f = {rise:g} m, d = {thickness:g} m: "
               f"ap,min = {res.replacement.original.ap_min:.4f} m/s²")
    typer.echo(f"replacement catenary ({thickness_rule}): d = {c.thickness:.4f} m, "
               f"f = {c.rise:.4f} m, p = {c.p:.4f} 1/s, ap,min = {c.ap_min:.4f} m/s²")
    typer.echo(f"site {curve} at p: ap/ap,min = {res.ratio:.4f} -> safe PGA "
               f"{res.pga_safe:.3f} m/s² = {res.pga_safe / g:.3f} g")
    if report is not None:
        typer.echo(f"wrote {report}")


@app.command("reproduce")
@guarded
def reproduce_command(
    out: Path = typer.Option(..., help="Folder to write (created if needed)."),
    quick: bool = typer.Option(False, "--quick", help="Coarse grids (about a minute)."),
) -> None:
    """Regenerate the paper's Tables 1–2, Figs. 15, 16, 17, 19 and the Sect. 9 example into
    OUT with an index.html showing paper vs computed side by side."""
    from rockarch.reproduce import reproduce

    if out.exists() and not out.is_dir():
        raise ValueError(f"{out}: exists and is not a folder")
    reproduce(out, quick=quick, log=lambda msg: typer.echo(msg, err=True))
    typer.echo(str(out / "index.html"))


__all__ = ["app", "fail"]
