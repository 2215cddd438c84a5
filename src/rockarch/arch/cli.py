"""``rockarch arch``: arch statics from the command line (issue 3; paper Sect. 3–6, Eq. 12–14)."""

from __future__ import annotations

import typer

from rockarch._cli_util import guarded, print_json
from rockarch._validate import positive


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
    if blocks is not None and blocks < 4:
        raise ValueError(f"at least 4 voussoirs are needed for a four-hinge mechanism, "
                         f"got {blocks}")
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
