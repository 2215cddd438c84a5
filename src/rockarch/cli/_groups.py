"""Groups of options that several commands share, declared once: ``@options(MOTION, ...)``
appends a group's options to a command's signature, and their values reach the command
in its ``**opts``."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from pathlib import Path
from typing import Any

import typer

from rockarch.cli._common import (
    CYCLES_OPT,
    DASK_WORKERS_OPT,
    DT_OPT,
    G_OPT,
    JSON_OPT,
    MDOF_BLOCKS_OPT,
    MDOF_H_OPT,
    MDOF_TOL_OPT,
    NO_STORE_OPT,
    PERIOD_OPT,
    PLOT_OPT,
    RATIO_OPT,
    RECORD_OPT,
    REST_OPT,
    RISE_OPT,
    SCHEDULER_OPT,
    SHAPE_OPT,
    SIGNAL_OPT,
    SPAN_OPT,
    STORE_OPT,
    TFREE_OPT,
    THICK_OPT,
    UNITS_OPT,
    WORKERS_OPT,
    Shape,
    Signal,
    System,
    mdof_structure,
    value,
)
from rockarch.systems import system as make_system

#: One option: (parameter name, type, typer.Option).
Group = tuple[tuple[str, Any, Any], ...]

#: The MDOF structure options (piers, bridges, walls, colonnades, JSON assemblies, friction)
#: that every command taking ``--system mdof`` accepts (docs/theory.md §10).
STRUCTURE: Group = (
    ("column", str, typer.Option(None, help="A column instead of an arch: blocks bottom to "
                                 "top, 'B,H;B,H' or 'B,H,x_centre;...' [m] (x_centre: the "
                                 "block's centre, from the column's axis x = 0; default "
                                 "0).")),
    ("friction", float, typer.Option(None, help="Coulomb friction coefficient of every joint "
                                     "(0.001 to 1e6); absent: joints never slide. --ratio then "
                                     "multiplies the friction-aware ap,min.")),
    ("spans", int, typer.Option(None, help="Put the arch on piers: number of equal spans (1: "
                                "an arch on two piers; >= 2: a bridge between abutments).")),
    ("pier_height", float, typer.Option(None, help="Pier height, ground to intrados "
                                        "springing [m].")),
    ("pier_width", float, typer.Option(None, help="Pier width [m].")),
    ("pier_blocks", int, typer.Option(None, help="Blocks per pier (default: about square).")),
    ("abutments", bool, typer.Option(None, "--abutments/--end-piers", help="End springings "
                                     "on rigid abutments or on piers (default: abutments "
                                     "for --spans >= 2).")),
    ("wall", str, typer.Option(None, help="A wall in running bond: 'ROWS,COLUMNS' of --block "
                               "blocks.")),
    ("block", str, typer.Option(None, help="Block size 'B,H' [m] of --wall or of the columns "
                                "of --colonnade.")),
    ("colonnade", int, typer.Option(None, help="A colonnade: number of --block columns (2: a "
                                    "trilithon) under one lintel.")),
    ("drums", int, typer.Option(None, help="Colonnade: each column made of N equal drums "
                                "stacked on dry joints (default 1: monolithic columns; "
                                "--block is the whole column).")),
    ("bay", float, typer.Option(None, help="Colonnade: clear spacing of the columns [m].")),
    ("lintel", float, typer.Option(None, help="Colonnade: lintel depth [m].")),
    ("assembly", Path, typer.Option(None, help="An assembly of convex blocks from a JSON file "
                                    "(its format: docs/assemblies.md).")),
)

#: A multi-block arch by its real dimensions, or (STRUCTURE) any other MDOF structure.
MDOF: Group = (
    ("shape", Shape, SHAPE_OPT), ("span", float, SPAN_OPT), ("rise", float, RISE_OPT),
    ("thickness", float, THICK_OPT), ("blocks", int, MDOF_BLOCKS_OPT),
) + STRUCTURE

#: The time step of every simulation of a sweep (``ra.system``'s h_factor).
STEP: Group = (
    ("h_factor", float, typer.Option(None, help="Time step × p of every simulation "
                                     "(default: 0.005 for mdof, docs/mdof.md; 0.05 for the "
                                     "RK4 of the other kinds; range 1e-4 … 0.05).")),
)

#: Any system kind of ``ra.system`` (docs/architecture.md) by the options of ``rockarch oas``.
SYSTEM: Group = (
    ("system", System, typer.Option("block", help="Structure: a rigid block, the four-hinge "
                                    "mechanism of an arch, a rocking frame, any SDOF "
                                    "mechanism given by delta and ap,min, or a multi-block "
                                    "(MDOF) structure.")),
    ("alpha", float, typer.Option(None, help="block/frame: slenderness atan(B/H) [rad].")),
    ("shape", Shape, typer.Option(None, help="fourhinge/mdof: arch shape.")),
    ("rise_over_span", float, typer.Option(None, help="fourhinge/mdof: f/l.")),
    ("thickness_over_span", float, typer.Option(None, help="fourhinge/mdof: d/l.")),
    ("blocks", int, typer.Option(None, help="fourhinge: voussoirs (critical mechanism); "
                                 "default the continuous arch (critical optimal). mdof "
                                 "arch: voussoirs (required for an arch).")),
) + STRUCTURE + (
    ("mass_ratio", float, typer.Option(None, help="frame: lintel mass / mass of both "
                                       "columns.")),
    ("delta", float, typer.Option(None, help="sdof: neutral angle delta [rad].")),
    ("ap_min", float, typer.Option(None, "--ap-min", help="sdof: limit acceleration "
                                   "[m/s²].")),
    ("restitution", float, REST_OPT), ("t_free", float, TFREE_OPT), ("g", float, G_OPT),
) + STEP

#: The ground motion: a pulse (--signal/--period/--cycles) or a record (--record/--units,
#: --dt for a single-column file).
MOTION: Group = (
    ("signal", Signal, SIGNAL_OPT), ("period", float, PERIOD_OPT),
    ("cycles", int, CYCLES_OPT), ("record", Path, RECORD_OPT), ("units", str, UNITS_OPT),
    ("dt", float, DT_OPT),
)

#: The peak of the motion over the structure's ap,min.
RATIO: Group = (("ratio", float, RATIO_OPT),)

#: The impact law, free motion and gravity of an SDOF system (keywords of ra.system).
SDOF: Group = (("restitution", float, REST_OPT), ("t_free", float, TFREE_OPT),
               ("g", float, G_OPT))

#: One simulation of an SDOF system: the motion scaled to --ratio, and its outputs.
RUN: Group = MOTION + RATIO + SDOF + (
    ("plot", Path, PLOT_OPT), ("json_out", bool, JSON_OPT))

#: The time step and contact tolerance of the MDOF engine.
MDOF_STEP: Group = (("h_factor", float, MDOF_H_OPT), ("gap_tol", float, MDOF_TOL_OPT))

#: Where a sweep runs and is kept (rockarch.core.sweep; docs/sweeps.md).
SWEEP: Group = (
    ("workers", int, WORKERS_OPT), ("scheduler", str, SCHEDULER_OPT),
    ("dask_workers", int, DASK_WORKERS_OPT), ("store", Path, STORE_OPT),
    ("no_store", bool, NO_STORE_OPT),
)


def pick(opts: dict, group: Group) -> dict:
    """The values of one group's options among a command's ``opts``."""
    return {name: opts[name] for name, _, _ in group}


def options(*groups: Group, before: str | None = None) -> Callable[[Callable], Callable]:
    """Add the options of ``groups`` to a typer command whose signature ends in ``**opts``
    (before its option ``before``, else after its options; decorators stack): typer sees
    them as ordinary options, the command gets their values in ``opts``."""

    def decorate(func: Callable) -> Callable:
        sig = inspect.signature(func)
        own = [p.replace(kind=p.KEYWORD_ONLY) for p in sig.parameters.values()
               if p.kind is not p.VAR_KEYWORD]
        if len(own) == len(sig.parameters) and not hasattr(func, "__signature__"):
            raise TypeError(f"{func.__name__} needs **opts to take option groups")
        added = [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=opt,
                                   annotation=kind)
                 for group in groups for name, kind, opt in group]
        at = len(own) if before is None else [p.name for p in own].index(before)

        @functools.wraps(func)
        def command(**kwargs):
            return func(**kwargs)

        command.__signature__ = sig.replace(parameters=own[:at] + added + own[at:])
        command.__annotations__ = {**func.__annotations__,
                                   **{p.name: p.annotation for p in added}}
        return command

    return decorate


def system_of(opts: dict):
    """The system (:func:`rockarch.systems.system`) of the SYSTEM options."""
    return make_system(opts["system"].value, alpha=opts["alpha"], shape=value(opts["shape"]),
                       rise_over_span=opts["rise_over_span"],
                       thickness_over_span=opts["thickness_over_span"],
                       blocks=opts["blocks"], mass_ratio=opts["mass_ratio"],
                       delta=opts["delta"], ap_min=opts["ap_min"], g=opts["g"],
                       restitution=opts["restitution"], t_free=opts["t_free"],
                       h_factor=opts["h_factor"], **mdof_structure(opts))


def sweep_options(opts: dict) -> dict:
    """The keywords of :func:`rockarch.cli._sweep.open_sweep` from the SWEEP options."""
    return {"workers": opts["workers"], "scheduler": opts["scheduler"],
            "dask_workers": opts["dask_workers"], "store_dir": opts["store"],
            "no_store": opts["no_store"]}


#: Where an option given by the user comes from (Click's ParameterSource, by name: typer
#: carries its own copy of Click).
GIVEN_SOURCES = ("COMMANDLINE", "ENVIRONMENT")


def typed(ctx: typer.Context, name: str) -> bool:
    """Whether the user gave option ``name`` (on the command line or by an environment
    variable), whatever its value: ``--years 50`` is given although 50 is the default."""
    source = ctx.get_parameter_source(name)
    return getattr(source, "name", None) in GIVEN_SOURCES


def given(ctx: typer.Context, opts: dict, *groups: Group) -> list[str]:
    """The options of ``groups`` given on the command line (or by an environment variable),
    by their flags, whatever their value: Click's parameter source says so (``--system
    block`` and ``--g 9.81`` are given although they equal the defaults); a hidden argument
    is named by its values.

    Parameters
    ----------
    ctx : typer.Context
        The running command's context (a ``ctx: typer.Context`` parameter of the command).
    opts : dict
        The command's ``**opts``.
    *groups : Group
        The groups whose options are looked at.

    Returns
    -------
    list of str
        The flags (``--friction``, ``--end-piers``) in the groups' order.
    """
    out = []
    for group in groups:
        for name, _, opt in group:
            if not typed(ctx, name):
                continue
            v = opts[name]
            if isinstance(opt, typer.models.ArgumentInfo):
                out.append(" ".join(str(x) for x in v))
                continue
            decl = next((d for d in opt.param_decls or () if d.startswith("--")),
                        "--" + name.replace("_", "-"))
            on, _, off = decl.partition("/")
            out.append(off if off and v is False else on)
    return out
