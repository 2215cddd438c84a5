"""Shared by the CLI commands: one-line errors (exit 2), JSON output, the option dialect,
choices read from the library's registries, and the parsing of lists and grids."""

from __future__ import annotations

import functools
import json
import math
import os
import sys
from collections.abc import Callable
from enum import Enum
from pathlib import Path
from typing import Any

import numpy as np
import typer

from rockarch.arch.geometry import SHAPES
from rockarch.core.console import on_terminal
from rockarch.core.constants import GAP_TOL, MDOF_H_FACTOR, OAS_TOL, T_FREE, G
from rockarch.core.sweep import check_steps, default_store_dir
from rockarch.core.validate import frequency, ratio_value
from rockarch.motion.records import read_record
from rockarch.motion.signals import SIGNALS, GroundMotion, pulse
from rockarch.motion.suite import Suite, check_distinct, read_suite
from rockarch.systems import KINDS


def _clean(obj: Any) -> Any:
    """Turn numpy scalars/arrays and NaN into plain JSON values (NaN/inf -> null)."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer, int)):
        return int(obj)
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    return obj


def print_json(obj: Any) -> None:
    """Print one JSON object on stdout (NaN -> null, numpy -> plain)."""
    sys.stdout.write(json.dumps(_clean(obj)) + "\n")
    sys.stdout.flush()


def write_json(path, obj: Any) -> None:
    """Write one JSON object to ``path`` atomically, as :func:`print_json` prints it."""
    from rockarch.core.paths import write_text

    write_text(path, json.dumps(_clean(obj)) + "\n")


def fail(message: str) -> None:
    """Print one clear line on stderr and exit with status 2."""
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code=2)


def guarded(func: Callable) -> Callable:
    """Decorate a CLI command: ValueError / TypeError / OSError (the library's checks of its
    arguments) become one line on stderr and exit 2 (as do MemoryError and OverflowError,
    which the limits of rockarch.core.limits should prevent)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from rockarch.mdof import statics_cache

        # statics of assemblies kept in the store (--store / --no-store where the command
        # has them, else the default store): a second command on a structure reuses them
        store = None if kwargs.get("no_store") else (kwargs.get("store")
                                                     or default_store_dir())
        try:
            with statics_cache.using(store):
                return func(*args, **kwargs)
        except BrokenPipeError:
            # the reader stopped (`rockarch ... | head`): stop quietly, as Unix tools do
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
            raise SystemExit(141) from None
        except (ValueError, TypeError, OSError) as exc:
            fail(" ".join(str(exc).split()) if str(exc) else exc.__class__.__name__)
        except MemoryError:
            fail("out of memory: use a shorter motion or --t-free, or fewer grid points")
        except OverflowError as exc:
            fail(f"a number is too large ({exc}): check the sizes and --p")

    return wrapper


# --- registries as CLI choices (defined once in the library) ------------------------------

def _choices(name: str, values) -> type[Enum]:
    return Enum(name, {v: v for v in values}, type=str)


Signal = _choices("Signal", SIGNALS)
Shape = _choices("Shape", SHAPES)
System = _choices("System", KINDS)


def value(choice) -> str | None:
    """The plain string of an enum choice (None stays None)."""
    return None if choice is None else choice.value


# --- parsing ---------------------------------------------------------------------------------

def float_list(name: str, text: str) -> np.ndarray:
    """A comma-separated list of finite numbers (``;`` also separates)."""
    parts = text.replace(";", ",").split(",")
    if any(not p.strip() for p in parts) and text.strip():
        raise ValueError(f"{name} has an empty entry: {text!r} (write e.g. 1,2,3)")
    try:
        vals = [float(v) for v in parts if v.strip()]
    except ValueError:
        raise ValueError(
            f"{name} must be a comma-separated list of numbers, got {text!r}") from None
    if not vals:
        raise ValueError(f"{name} is empty")
    if not all(math.isfinite(v) for v in vals):
        raise ValueError(f"{name} must hold finite numbers, got {text!r}")
    return np.array(vals)


def motion_shape(signal, period: float | None, cycles: int | None, record: Path | None,
                 units: str | None, dt: float | None = None) -> GroundMotion:
    """The ground-motion shape of --signal/--period or --record (peak 1 for pulses; --dt:
    the time step of a single-column record)."""
    if record is not None and signal is not None:
        raise ValueError("give either --record or --signal/--period, not both")
    if record is not None and (period is not None or cycles is not None):
        raise ValueError(f"--{'period' if period is not None else 'cycles'} goes with "
                         "--signal, not --record (a record has its own time axis)")
    if record is None and units is not None:
        raise ValueError("--units goes with --record (the units of a two-column file)")
    if record is None and dt is not None:
        raise ValueError("--dt goes with --record (the time step of a single-column file, "
                         "accelerations alone)")
    if record is not None:
        if record.suffix.lower() == ".at2":
            if units not in (None, "g"):
                raise ValueError(f"{record}: a PEER .AT2 file is in units of g; --units "
                                 f"{units} contradicts it (leave --units out)")
            units = None  # --units g agrees with the file's own statement
        return read_record(record, units=units, dt=dt)
    if signal is None:
        raise ValueError("give a ground motion: --signal S --period T, or --record PATH")
    if period is None:
        raise ValueError(f"--signal {signal.value} needs --period T (seconds)")
    return pulse(signal.value, period=period, cycles=cycles)


def p_grid(p: str | None, p_min: float | None, p_max: float | None, p_steps: int
           ) -> np.ndarray:
    """The p values of --p LIST or --p-min/--p-max/--p-steps [1/s]."""
    if p is not None:
        if p_min is not None or p_max is not None:
            raise ValueError("give either --p LIST or --p-min/--p-max/--p-steps, not both")
        return float_list("--p", p)
    if p_min is None or p_max is None:
        raise ValueError("give the p values: --p 0.5,1,2 or --p-min A --p-max B --p-steps N")
    if not (0 < p_min < p_max):
        raise ValueError(f"need 0 < --p-min < --p-max, got {p_min} and {p_max}")
    frequency("--p-min [1/s]", p_min)
    frequency("--p-max [1/s]", p_max)
    if p_steps < 2:
        raise ValueError("--p-steps must be >= 2")
    check_steps("--p-steps", p_steps)
    return np.round(np.linspace(p_min, p_max, p_steps), 12)


#: Largest ap/ap,min of an OAS grid unless --ratio-max says otherwise.
RATIO_MAX = 5.0


def ratio_grid(ratio_min: float, ratio_max: float | None, ratio_steps: int) -> np.ndarray:
    """The ap/ap,min values of --ratio-min/--ratio-max/--ratio-steps (rounded to 12 digits so
    that 1.7 prints as 1.7, not 1.7000000000000002). One step is --ratio-min alone."""
    if ratio_steps < 1:
        raise ValueError("--ratio-steps must be >= 1")
    check_steps("--ratio-steps", ratio_steps)
    if ratio_steps == 1:
        if ratio_max is not None and ratio_max != ratio_min:
            raise ValueError("--ratio-steps 1 computes only --ratio-min: leave out --ratio-max "
                             "or give more steps")
        if not (ratio_min >= 0 and math.isfinite(ratio_min)):
            raise ValueError(f"need a finite --ratio-min >= 0, got {ratio_min}")
        return np.array([ratio_min])
    ratio_max = RATIO_MAX if ratio_max is None else ratio_max
    if not (0 <= ratio_min <= ratio_max and math.isfinite(ratio_max)):
        raise ValueError(f"need 0 <= --ratio-min <= --ratio-max, got {ratio_min}, {ratio_max}")
    ratio_value("--ratio-max", ratio_max)
    return np.round(np.linspace(ratio_min, ratio_max, ratio_steps), 12)


def echo_err(msg: str) -> None:
    typer.echo(msg, err=True)


def stage_echo() -> Callable[[str], None] | None:
    """Where stderr is not a terminal (a log file, a pipe), a function that prints
    ``progress: MESSAGE`` there: a long command then prints a line per stage (the structure
    built, each record's IDA done); None on a terminal, where its progress bars show the
    stages."""
    return None if on_terminal(None) else _progress_line


def _progress_line(msg: str) -> None:
    echo_err(f"progress: {msg}")


def check_suite_units(sources, units: str | None, dt: float | None = None) -> None:
    """--units sets the units of two-column files; where every record of ``sources`` states
    its own (.AT2 in g, ESM, K-NET, COSMOS) another unit is refused, as with --record.
    With --dt every record must be a single-column file, whose units --units sets (the
    reader refuses --dt for the others)."""
    if units is None or dt is not None:
        return
    from rockarch.motion.suite import TWO_COLUMN_SUFFIXES, record_files

    files = record_files(sources)[0]
    if files and not any(f.suffix.lower() in TWO_COLUMN_SUFFIXES for f in files):
        if not (units == "g" and all(f.suffix.lower() == ".at2" for f in files)):
            raise ValueError(f"--units {units}: these records state their own units (.AT2 "
                             "in g, ESM, K-NET, COSMOS); --units is for two-column files "
                             "(leave it out)")


def read_records(sources, units: str | None, dt: float | None = None) -> Suite:
    """The suite of --records, its notes (records left out, implausible PGAs: wrong units?)
    printed as warnings on stderr (--units as :func:`check_suite_units`; --dt: the time
    step of single-column files)."""
    check_suite_units(sources, units, dt)
    suite = read_suite(sources, units=units, dt=dt)
    check_distinct(suite)
    for note in suite.notes:
        echo_err(f"warning: {note}")
    return suite


# --- options shared by several commands ----------------------------------------------------

SIGNAL_OPT = typer.Option(None, help="Pulse shape (paper Fig. 14).")
PERIOD_OPT = typer.Option(None, help="Pulse period T [s].")
CYCLES_OPT = typer.Option(None, help="Number of cycles of --signal harmonic (default 3).")
RECORD_OPT = typer.Option(None, help="Record file (.AT2, ESM .ASC, K-NET .NS/.EW, "
                          "COSMOS .V2c (FILE#N: channel N of a file of several), "
                          "two-column time/acc, or accelerations alone with --dt).")
UNITS_OPT = typer.Option(None, help="Units of a two-column or single-column record: m/s2 "
                         "(default), g, cm/s2 (= gal), mm/s2; also written m/s/s, m/s^2, "
                         "cm/sec2, ...")
#: --dt wherever --units is: the time step of single-column record files.
DT_HELP = ("Time step [s] of single-column record files (accelerations only, one or more per "
           "line).")
DT_OPT = typer.Option(None, "--dt", help=DT_HELP)
RATIO_OPT = typer.Option(..., help="ap/ap,min: pulse peak or record PGA over ap,min.")
REST_OPT = typer.Option(None, help="Coefficient of restitution in [0, 1] (default: the "
                        "structure's own impact law).")
TFREE_OPT = typer.Option(T_FREE, help="Free motion after the ground motion ends [s].")
G_OPT = typer.Option(G, help="Acceleration of gravity [m/s²].")
PLOT_OPT = typer.Option(None, help="Write a PNG of the rotation and a_g over time.")
JSON_OPT = typer.Option(False, "--json", help="Print one JSON object.")
TOL_OPT = typer.Option(OAS_TOL, help="Bisection tolerance of the boundary (ratio); 0 "
                       "turns the bisection off (the boundary is then the first "
                       "overturning grid value).")

#: The IDA scan's options (fragility, risk, design --system --records): the defaults
#: follow the structure (rockarch.risk.record_scan.default_scan).
IDA_STEPS_OPT = typer.Option(None, help="IDA scan values of ap/ap,min from 1 (default 81; "
                             "17 for mdof, whose simulations cost seconds, searched below its "
                             "first collapse every --search-step, docs/mdof.md).")
IDA_TOL_OPT = typer.Option(None, help="Bisection tolerance of each record's collapse point "
                           "(ratio; default 0.001, 0.01 for mdof); 0 turns it off.")

SHAPE_OPT = typer.Option(None, help="Arch shape.")
SPAN_OPT = typer.Option(None, help="Span l of the axis [m].")
RISE_OPT = typer.Option(None, help="Rise f of the axis [m].")
THICK_OPT = typer.Option(None, help="Uniform thickness d [m].")
# the same, required: one arch given by its real dimensions (arch, simulate fourhinge, design)
ARCH_SHAPE_OPT = typer.Option(..., help="Arch shape.")
ARCH_SPAN_OPT = typer.Option(..., help="Span l of the axis [m].")
ARCH_RISE_OPT = typer.Option(..., help="Rise f of the axis [m].")
ARCH_THICK_OPT = typer.Option(..., help="Uniform thickness d normal to the axis [m].")
MDOF_BLOCKS_OPT = typer.Option(None, help="Number of voussoirs N (at least 5).")
MDOF_H_OPT = typer.Option(MDOF_H_FACTOR, help="Time step × p (safe range 1e-4 … 0.05).")
MDOF_TOL_OPT = typer.Option(GAP_TOL, help="Contact tolerance / thinnest joint (1e-10 … "
                            "1e-3), times δ/0.05 where the overturning rotation δ < 0.05 rad.")

# sweep options (rockarch.core.sweep; docs/sweeps.md), shared by oas and site-oas
WORKERS_OPT = typer.Option(None, help="Local worker processes (default: every core; small "
                           "sweeps run in-process).")
SCHEDULER_OPT = typer.Option(None, help="Run on a running Dask scheduler tcp://HOST:PORT.")
DASK_WORKERS_OPT = typer.Option(None, help="Start a local Dask cluster of N workers.")
STORE_OPT = typer.Option(None, help="Folder of the resumable store of finished chunks. "
                         "Default: $ROCKARCH_CACHE, else $XDG_CACHE_HOME/rockarch, else "
                         f"~/.cache/rockarch (here: {default_store_dir()}). Set "
                         "ROCKARCH_CACHE or give --store DIR to move it; 'rockarch cache "
                         "info' / 'rockarch cache clear' show and empty it.")
NO_STORE_OPT = typer.Option(False, "--no-store", help="Keep no store (always recompute).")


def column_blocks(column: str) -> list[np.ndarray]:
    """--column 'B,H;B,H' as a list of (B, H[, x]) rows."""
    rows = column.strip().rstrip(";").split(";")
    if not column.strip() or any(not r.strip() for r in rows):
        raise ValueError(f"--column has an empty block: {column!r} (give 'B,H;B,H', bottom "
                         "to top, metres)")
    return [float_list("--column block", r) for r in rows]


# --- MDOF structures (rockarch.systems.mdof_assembly; docs/theory.md §10) -------------------

#: The command parameters of the MDOF structure options, passed on to systems.system().
MDOF_STRUCTURE_KEYS = ("column", "friction", "spans", "pier_height", "pier_width",
                       "pier_blocks", "abutments", "wall", "block", "colonnade", "drums",
                       "bay", "lintel", "assembly")


def mdof_structure(params: dict) -> dict:
    """The keywords of :func:`rockarch.systems.system` for the MDOF structure options found
    among a command's ``params`` (its ``locals()``); absent options are left out."""
    kw = {k: params.get(k) for k in MDOF_STRUCTURE_KEYS if params.get(k) is not None}
    if "friction" in kw:
        from rockarch.mdof.builders import friction_value  # scipy: not at CLI start-up

        friction_value(kw["friction"], "--friction")
    if "column" in kw:
        kw["column"] = column_blocks(kw["column"])
    return kw  # --wall and --block stay text: rockarch.systems parses them
