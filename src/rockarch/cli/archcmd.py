"""``rockarch arch``: limit analysis and the four-hinge mechanism of one arch (statics)."""

from __future__ import annotations

import math
from pathlib import Path

import typer

from rockarch.arch.fourhinge import analyse
from rockarch.arch.geometry import MASS_MODELS, make_arch
from rockarch.arch.thrust import minimum_thickness
from rockarch.cli._app import app
from rockarch.cli._common import (
    ARCH_RISE_OPT,
    ARCH_SHAPE_OPT,
    ARCH_SPAN_OPT,
    G_OPT,
    JSON_OPT,
    Shape,
    guarded,
    print_json,
)
from rockarch.core.validate import in_range, positive
from rockarch.output import check_outputs
from rockarch.systems import check_blocks


@app.command(short_help="Arch statics: ap,min, four hinges, p, delta, minimum thickness.")
@guarded
def arch(
    shape: Shape = ARCH_SHAPE_OPT, span: float = ARCH_SPAN_OPT, rise: float = ARCH_RISE_OPT,
    thickness: float = typer.Option(None, help="Uniform thickness d normal to the axis [m]."),
    blocks: int = typer.Option(None, help="Voussoirs (critical mechanism); default the "
                               "continuous arch (critical optimal mechanism)."),
    g: float = G_OPT,
    min_thickness: bool = typer.Option(False, "--min-thickness",
                                       help="Print the minimum thickness of this axis shape "
                                            "(--thickness is then not used)."),
    lambda_: float = typer.Option(0.0, "--lambda",
                                  help="With --min-thickness: horizontal acceleration / g."),
    direction: int = typer.Option(1, help="+1: ground acceleration to the right (the arch "
                                  "falls to the left); -1: the mirror case."),
    mass_model: str = typer.Option("voussoir", help="voussoir (true voussoir polygons) or "
                                   "axis (mass lumped on the axis)."),
    plot: Path = typer.Option(None, help="Write a PNG of the collapse mechanism."),
    json_out: bool = JSON_OPT,
) -> None:
    """Limit acceleration ap,min, four-hinge mechanism (p, delta, hinges), paper Eq. 14's constants.

    Sign convention: lambda >= 0 is the magnitude of the ground acceleration / g; with
    --direction +1 the ground accelerates to the right and the inertia loads push the arch to
    the left.
    """
    span = positive("--span", span)
    rise = positive("--rise", rise)
    g = positive("--g", g)
    check_blocks(blocks)
    if not min_thickness and lambda_ != 0.0:
        raise ValueError("--lambda is used only with --min-thickness")
    lambda_ = in_range("--lambda", lambda_, 0.0, math.inf, hi_open=True)
    if mass_model not in MASS_MODELS[:2]:
        raise ValueError(f"--mass-model must be voussoir or axis, got {mass_model!r}")
    if min_thickness:
        if thickness is not None:
            raise ValueError("--thickness is not used with --min-thickness: leave it out")
        if plot is not None:
            raise ValueError("--plot draws a mechanism: not with --min-thickness")
        probe = make_arch(shape.value, span, rise, 0.01 * span, mass_model=mass_model)
        d = minimum_thickness(probe, lambda_, blocks=blocks, direction=direction)
        if json_out:
            print_json({"d_min": d, "d_min_over_l": d / span})
        else:
            typer.echo(f"{shape.value} arch l = {span:g} m, f = {rise:g} m: minimum thickness "
                       f"{d:.6g} m (d/l = {d / span:.6g}) at lambda = {lambda_:g}")
        return
    if thickness is None:
        raise ValueError("--thickness is required (unless --min-thickness)")
    check_outputs((plot, "--plot", "png"))
    a = make_arch(shape.value, span, rise, positive("--thickness", thickness),
                  mass_model=mass_model)
    res = analyse(a, blocks, g=g, direction=direction)
    if plot:
        from rockarch.output.arch_plots import plot_mechanism
        plot_mechanism(res, plot)
    if json_out:
        print_json(res.to_dict())
        return
    lines = [
        f"{shape.value} arch: l = {span:g} m, f = {rise:g} m, d = {thickness:g} m, "
        + (f"{blocks} voussoirs (critical mechanism)" if blocks
           else "continuous (critical optimal mechanism)"),
        f"  ap,min = {res.ap_min:.4f} m/s² (lambda = {res.lambda_:.5f}; virtual work "
        f"g*Bv/Bh = {res.ap_min_vw:.4f})",
        f"  p = {res.p:.4f} 1/s, delta = {res.delta_end:.5f} rad (part {res.end_part}, "
        f"Table 1), delta_u = {res.delta:.5f} rad (coordinate u), Bv = {res.Bv:.5g}, "
        f"Bh = {res.Bh:.5g}, A = {res.A:.5g}",
        f"  c1 = {res.c1:.4f}, c2 = {res.c2:.4f}, c3/c3' = {res.c3:.3f}/{res.c3p:.3f}, "
        f"c4 = {res.c4:.4f} (c4_u = {res.c4_u:.4f})",
        "  hinges: " + ", ".join(f"({h.x:.3f}, {h.y:.3f}) {h.side}" for h in res.hinges),
    ]
    if plot:
        lines.append(f"  figure: {plot}")
    typer.echo("\n".join(lines))
