"""``rockarch simulate KIND`` and ``rockarch animate``: one structure on one ground motion."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import typer

from rockarch import mdof
from rockarch.cli._app import app, simulate_app
from rockarch.cli._common import (
    ARCH_RISE_OPT,
    ARCH_SHAPE_OPT,
    ARCH_SPAN_OPT,
    ARCH_THICK_OPT,
    G_OPT,
    JSON_OPT,
    TFREE_OPT,
    Shape,
    guarded,
    mdof_structure,
    motion_shape,
    print_json,
    value,
)
from rockarch.cli._groups import MDOF, MDOF_STEP, MOTION, RATIO, RUN, SDOF, options, pick
from rockarch.core.constants import g_label
from rockarch.core.validate import positive
from rockarch.mdof.simulate import STEP_CHECK_MAX_BLOCKS
from rockarch.output import check_outputs
from rockarch.systems import BlockSystem, check_drums, scale_to_ratio
from rockarch.systems import system as make_system

#: Slips below this [m] are the contact solve's tolerance (10⁻⁶·g·h per step, a few µm at
#: most over a record), not sliding: a 3 × 3 wall at 0.95·ap,min printed "largest slip
#: 2.44e-08 mm".
SLIP_NOISE = 1e-6


def _sdof(kind: str, header: Callable, opts: dict, **system_kw) -> None:
    """Check the outputs, build the SDOF system ``kind`` and run it (:func:`_run`) under the
    heading ``header(system)``."""
    check_outputs((opts["plot"], "--plot", "png"))
    sysobj = make_system(kind, **system_kw, **pick(opts, SDOF))
    _run(sysobj, header(sysobj), opts, extra=_sdof_parameters(sysobj))


def _sdof_parameters(sysobj) -> dict:
    """The system's parameters that its text header prints, for ``--json`` (SI units)."""
    if isinstance(sysobj, BlockSystem):
        blk = sysobj.block()
        return {"p": blk.p, "alpha": blk.alpha, "width": blk.width, "height": blk.height,
                "ap_min": blk.ap_min, "restitution": blk.r}
    mech = sysobj.mechanism
    # an arch's delta_u: the dynamics' coordinate, not Table 1's delta (`rockarch arch`)
    delta = "delta_u" if mech.info.get("kind") == "fourhinge" else "delta"
    return {"p": mech.p, delta: mech.delta, "ap_min": mech.ap_min,
            "restitution": [mech.plus.e_close, mech.minus.e_close]}


def _fourhinge_header(sysobj) -> str:
    mech = sysobj.mechanism
    return (f"{mech.name}: p={mech.p:.4g} 1/s, delta_u={mech.delta:.4g} rad, "
            f"ap,min={mech.ap_min:.4g} m/s², impact e={mech.plus.e_close:.4f}/"
            f"{mech.minus.e_close:.4f}")


def _frame_header(sysobj) -> str:
    mech = sysobj.mechanism
    return (f"{mech.name}: p={mech.p:.4g} 1/s (the frame's, from the columns' "
            f"p={mech.info['p_column']:g} 1/s: docs/mechanism.md), ap,min={mech.ap_min:.4g} "
            f"m/s², e={mech.plus.e_close:.4f}")


def _run(sysobj, header: str, opts: dict, extra: dict | None = None, **sim_kw) -> None:
    """Scale the motion to a peak of ratio·ap,min, run, then print JSON or a summary."""
    shape = motion_shape(**pick(opts, MOTION))
    ratio, plot, json_out = opts["ratio"], opts["plot"], opts["json_out"]
    mot = scale_to_ratio(shape, ratio, sysobj.ap_min)
    resp = sysobj.simulate(shape, ratio=ratio, **sim_kw)
    if plot is not None:
        from rockarch.output.figures import plot_response, save_figure
        save_figure(plot_response(resp, mot), plot)
    s = {**resp.to_dict(), **(extra or {})}
    if json_out:
        print_json(s)
        return
    typer.echo(header)
    typer.echo(f"motion: {mot.name}, PGA={mot.pga:.4g} m/s² = {ratio:g} ap,min")
    _verdict(s)
    stride = getattr(resp, "stride", 1)
    if stride > 1:  # docs/theory.md Eq. (8.6): the verdict above is exact
        typer.echo(f"history: every {stride}th step kept (ROCKARCH_MAX_SAMPLES)")
    if plot is not None:
        typer.echo(f"wrote {plot}")


def _verdict(s: dict) -> None:
    """Print the verdict lines of a response's summary ``s`` (its ``to_dict()``)."""
    if s["overturned"]:
        typer.echo(f"OVERTURNED at t = {s['t_overturn']:.4f} s after "
                   f"{_count(s['impacts'], 'impact')}")
        if s.get("open_joints_max") is not None and s["max_rotation_ratio"] < 1.0:
            typer.echo(f"  (its largest rotation was {s['max_rotation_ratio']:.4f} of the "
                       "reference angle: the collapse test decided, gravity alone moving a "
                       "part away from rest or a block slid off its supports; docs/mdof.md, "
                       "Collapse criterion)")
    else:
        typer.echo(f"safe: max rotation / its overturning value = "
                   f"{s['max_rotation_ratio']:.4f}, {_count(s['impacts'], 'impact')}"
                   f"{_beyond(s['max_rotation_ratio'], '; ')}")
    if s.get("sliding_contacts_max") and s["max_slip"] < SLIP_NOISE:
        typer.echo(f"sliding: none beyond {1e6 * SLIP_NOISE:g} µm (largest slip "
                   f"{s['max_slip']:.2g} m: the contact solve's tolerance, not a slide)")
    elif s.get("sliding_contacts_max"):  # a structure with friction that slid
        n = s["sliding_contacts_max"]
        typer.echo(f"sliding: largest slip {1e3 * s['max_slip']:.3g} mm, up to {n} "
                   f"joint{'s' if n > 1 else ''} sliding at once")
    if s.get("step_sensitive"):
        typer.echo(_step_note(s["h_half"]))
    if s.get("lcp_failures"):
        typer.echo(f"note: {s['lcp_failures']} of {s['steps']} steps not solved to the contact "
                   "solver's tolerance, even as substeps (docs/theory.md §9)")


def _beyond(ratio: float, sep: str) -> str:
    """What a safe run's ratio of 1 or more means, after ``sep`` (docs/mdof.md, "Step check
    of one history"): a block turned past the reference angle, and gravity still restores
    the structure; '' below 1."""
    return (f"{sep}rotated past the reference angle yet not collapsed: the collapse test "
            "decides (docs/mdof.md, Collapse criterion)" if ratio >= 1.0 else "")


def _step_note(half: dict) -> str:
    """The line saying that a history changes at h/2 (:func:`rockarch.mdof.simulate`)."""
    r = half["max_rotation_ratio"]
    got = (f"OVERTURNED at t = {half['t_overturn']:.4f} s" if half["overturned"] else
           f"safe, max rotation / its overturning value = {r:.4f}{_beyond(r, ', ')}")
    return (f"note: sensitive to the time step: at h/2 (--h-factor {half['h_factor']:g}) "
            f"{got}; read verdicts from maps or suites (docs/mdof.md, Convergence on "
            "records)")


@simulate_app.command("block")
@guarded
@options(RUN)
def simulate_block(
    alpha: float = typer.Option(None, help="Slenderness angle atan(B/H) [rad]."),
    p: float = typer.Option(None, "--p", help="Frequency parameter [1/s]."),
    width: float = typer.Option(None, help="Full width B [m] (instead of --p/--alpha)."),
    height: float = typer.Option(None, help="Full height H [m] (instead of --p/--alpha)."),
    **opts,
) -> None:
    """Simulate a rigid block (exact Housner equation) on a pulse or a record."""
    if width is None and height is None and (p is None or alpha is None):
        raise ValueError("give the block: --p P --alpha A (or --width B --height H)")

    def header(sysobj) -> str:
        blk = sysobj.block()
        return (f"block p={blk.p:.4g} 1/s alpha={blk.alpha:.4g} rad (B={blk.width:.4g} m, "
                f"H={blk.height:.4g} m, ap,min={blk.ap_min:.4g} m/s², r={blk.r:.4f})")

    _sdof("block", header, opts, alpha=alpha, p=p, width=width, height=height)


@simulate_app.command("fourhinge")
@guarded
@options(RUN)
def simulate_fourhinge(
    shape: Shape = ARCH_SHAPE_OPT, span: float = ARCH_SPAN_OPT, rise: float = ARCH_RISE_OPT,
    thickness: float = ARCH_THICK_OPT,
    blocks: int = typer.Option(None, help="Voussoirs (critical mechanism); default the "
                               "continuous arch (critical optimal mechanism)."),
    **opts,
) -> None:
    """Simulate the four-hinge mechanism of an arch (exact linkage kinematics, Sect. 5)."""
    _sdof("fourhinge", _fourhinge_header, opts, shape=shape.value,
          span=positive("--span", span), rise=positive("--rise", rise),
          thickness=positive("--thickness", thickness), blocks=blocks)


@simulate_app.command("frame")
@guarded
@options(RUN)
def simulate_frame(
    alpha: float = typer.Option(..., help="Column slenderness atan(b/h) [rad]."),
    p: float = typer.Option(..., "--p", help="Frequency parameter of one column [1/s]."),
    mass_ratio: float = typer.Option(..., help="Lintel mass / mass of both columns."),
    **opts,
) -> None:
    """Simulate a rocking frame: two rigid columns and a rigid lintel (paper Fig. 1)."""
    _sdof("frame", _frame_header, opts, alpha=alpha, p=p, mass_ratio=mass_ratio)


@simulate_app.command("sdof")
@guarded
@options(RUN)
def simulate_sdof(
    p: float = typer.Option(..., "--p", help="Frequency parameter [1/s]."),
    delta: float = typer.Option(..., help="Neutral angle delta [rad]."),
    ap_min: float = typer.Option(..., "--ap-min", help="Limit acceleration [m/s²]."),
    **opts,
) -> None:
    """Simulate any SDOF mechanism given by (p, delta, ap,min) (equivalence form, ref. [13])."""
    _sdof("sdof", lambda sysobj: sysobj.name, opts, p=p, delta=delta, ap_min=ap_min)


def _mdof_system(opts: dict, t_free: float, g: float):
    """The MDOF structure of `simulate mdof` / `animate`: an arch (alone or on piers) or
    the structure of the other options (:func:`mdof_structure`)."""
    structure = mdof_structure(opts)
    check_drums(structure.get("drums"), structure.get("colonnade"))
    arch = [opts[k] for k in ("shape", "span", "rise", "thickness", "blocks")]
    others = {"column", "wall", "colonnade", "assembly"} & set(structure)
    if not others and None in arch:
        raise ValueError("give the arch: --shape S --span L --rise F --thickness D --blocks N "
                         "(or --column 'B,H;B,H', --wall R,C --block B,H, --colonnade N "
                         "--block B,H --bay S --lintel D, or --assembly FILE.json)")
    shape, span, rise, thickness, blocks = arch
    if not others:
        span, rise = positive("--span", span), positive("--rise", rise)
        thickness = positive("--thickness", thickness)
    return make_system("mdof", shape=value(shape), span=span, rise=rise, thickness=thickness,
                       blocks=blocks, g=g, t_free=t_free, **pick(opts, MDOF_STEP),
                       **structure)


def _count(n: int, word: str) -> str:
    """'1 block', '2 blocks'."""
    return f"{n} {word}{'' if n == 1 else 's'}"


def _delta_name(a) -> str:
    """An arch's reference is its four-hinge mechanism, on the dynamics' coordinate u."""
    return "delta_u" if "hinges" in a.info else "delta"


def _mdof_header(a) -> str:
    fr = "" if a.frictionless else f", friction {np.min(a.mu):g}" + (
        "" if np.ptp(a.mu) == 0 else f"..{np.max(a.mu):g}")
    ref = f"p={a.p_ref:.4g} 1/s, {_delta_name(a)}={a.delta_ref:.4g} rad"
    if a.slides:
        ref = (f"its collapse mechanism slides; rocking alone from "
               f"{a.info['ap_min_no_sliding']:.4g} m/s², {ref}")
    return (f"{a.name}: {_count(a.n_blocks, 'block')}, {_count(a.n_joints, 'joint')}{fr}, "
            f"ap,min={a.ap_min:.4g} m/s², {ref} (Moreau–Jean, docs/mdof.md)")


def _mdof_parameters(a) -> dict:
    """The structure's numbers that :func:`_mdof_header` prints, for ``--json`` (SI units):
    ap_min, the reference mechanism's p and delta (delta_u for an arch), and rocking's
    ap_min where the collapse mechanism slides."""
    out = {"ap_min": a.ap_min, "p": a.p_ref, _delta_name(a): a.delta_ref, "blocks": a.n_blocks,
           "joints": a.n_joints}
    if a.slides:
        out["ap_min_rocking"] = a.info["ap_min_no_sliding"]
    return out


def _with_ramp(a, header: str, extra: dict) -> tuple[str, dict]:
    """The header and JSON fields of --ramp (:func:`rockarch.mdof.ramp.ramp_onset`).

    JSON: ``ap_ramp`` (the smaller onset, m/s²), ``ramp_direction`` (+1: ground to +x),
    ``ramp_onsets`` (per direction, null: nothing moved) and ``ramp_end`` (m/s², the ramp's
    last ground acceleration: a null onset means the structure stood up to it).
    """
    from rockarch.mdof.ramp import ramp_onset

    r = ramp_onset(a)
    side = {1: "+x", -1: "-x"}
    if math.isfinite(r.ap_onset):
        other = r.onsets[-r.direction]
        rest = (f"{side[-r.direction]} at {other:.4g} m/s²" if math.isfinite(other) else
                f"{side[-r.direction]} stands up to {r.end:.4g} m/s²")
        line = (f"ramp {r.rate / a.g:g} g/s ({g_label(a.g)}) from rest: a mechanism starts at "
                f"{r.ap_onset:.4g} m/s² = {r.ap_onset / a.ap_min:.4g} ap,min (ground to "
                f"{side[r.direction]}; {rest}); ap,min is the lowest static solution")
    else:
        line = (f"ramp {r.rate / a.g:g} g/s ({g_label(a.g)}) from rest: nothing moves up to "
                f"{r.end:.4g} m/s²")
    return f"{header}\n{line}", {**extra, "ap_ramp": r.ap_onset,
                                 "ramp_direction": r.direction,
                                 "ramp_onsets": {side[k]: v for k, v in r.onsets.items()},
                                 "ramp_end": r.end}


@simulate_app.command("mdof")
@guarded
@options(MDOF, MOTION + RATIO, MDOF_STEP, before="t_free")
def simulate_mdof(
    t_free: float = TFREE_OPT, g: float = G_OPT, plot: Path = typer.Option(
        None, help="Write a PNG of the largest block rotation / delta and a_g over time."),
    json_out: bool = JSON_OPT,
    mechanism: Path = typer.Option(None, help="Also write a PNG of the static collapse "
                                   "mechanism (docs/theory.md §10)."),
    ramp: bool = typer.Option(False, "--ramp", help="Also report the ground acceleration at "
                              "which the engine starts a mechanism under a slow ramp (0.1 "
                              "g/s, g = --g, from rest, both directions), beside ap,min: "
                              "walls with high friction stand above it (docs/assemblies.md)."),
    step_check: bool = typer.Option(None, "--step-check/--no-step-check", help="Run the "
                                    "history again at h/2 and say if the verdict changes "
                                    "(or the largest rotation by more than 0.1 of its "
                                    "overturning value); default: on for chains without "
                                    f"friction and up to {STEP_CHECK_MAX_BLOCKS} blocks "
                                    "(the rerun costs twice the run)."),
    **opts,
) -> None:
    """Simulate a multi-block structure whose joints open, close and (with --friction)
    slide: an arch (alone, on piers, a bridge), a column, a wall, a colonnade, a JSON file.

    --ratio is relative to the structure's ap,min (limit analysis, friction included).
    """
    check_outputs((plot, "--plot", "png"), (mechanism, "--mechanism", "png"))
    sysobj = _mdof_system(opts, t_free, g)
    if mechanism is not None:
        from rockarch.output.collapse_plots import plot_collapse
        plot_collapse(sysobj.assembly, mechanism)
    header, extra = _mdof_header(sysobj.assembly), _mdof_parameters(sysobj.assembly)
    if ramp:
        header, extra = _with_ramp(sysobj.assembly, header, extra)
    _run(sysobj, header, {**opts, "plot": plot, "json_out": json_out}, extra=extra,
         check_step=step_check)
    if mechanism is not None and not json_out:
        typer.echo(f"wrote {mechanism}")


@app.command(short_help="GIF of an MDOF structure (arch, bridge, wall, column, blocks) in "
             "motion.")
@guarded
@options(MDOF, MOTION + RATIO, MDOF_STEP, before="t_free")
def animate(
    out: Path = typer.Option(..., help="GIF file to write."),
    t_free: float = typer.Option(3.0, help="Free motion after the ground motion ends [s]."),
    g: float = G_OPT,
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
    **opts,
) -> None:
    """Animate an MDOF structure on a ground motion: blocks, open joints, a_g(t); after a
    collapse the blocks are followed as they fall, land and come to rest (new contacts)."""
    from rockarch.output.animation import animate as write_gif
    from rockarch.output.animation import check_options

    check_options(fps, frames, magnify)
    check_outputs((out, "--out", "gif"))
    sysobj = _mdof_system(opts, t_free, g)
    motion = scale_to_ratio(motion_shape(**pick(opts, MOTION)), opts["ratio"], sysobj.ap_min)
    resp = mdof.simulate(sysobj.assembly, motion, t_free=sysobj.t_free,
                         h_factor=sysobj.h_factor, gap_tol=sysobj.gap_tol,
                         through_collapse=True)
    write_gif(resp, out, fps=fps, max_frames=frames, magnify=magnify, progress=progress)
    if json_out:
        print_json({**resp.to_dict(), "out": str(out)})
        return
    typer.echo(_mdof_header(sysobj.assembly))
    typer.echo(f"motion: {motion.name}, PGA={motion.pga:.4g} m/s² = {opts['ratio']:g} ap,min")
    _verdict(resp.to_dict())
    if resp.overturned:
        typer.echo(f"the fall after the collapse is animated until t = {resp.t_end:.2f} s")
    typer.echo(f"wrote {out}")
