"""``rockarch records``: read a suite of records and list their metadata and intensity
measures."""

from __future__ import annotations

from pathlib import Path

import typer

from rockarch.cli._app import app
from rockarch.cli._common import (
    DT_OPT,
    JSON_OPT,
    check_suite_units,
    float_list,
    guarded,
    print_json,
)
from rockarch.core.constants import G_STANDARD, g_label
from rockarch.motion import intensity, synthetic
from rockarch.motion.suite import describe, read_suite
from rockarch.motion.velocity_pulse import check_method
from rockarch.output import check_outputs

records_app = typer.Typer(no_args_is_help=True, rich_markup_mode=None,
                          help="Record suites: metadata and intensity measures.")
app.add_typer(records_app, name="records")

SOURCES_ARG = typer.Argument(..., help="Record files (.AT2, .ASC, K-NET, .V2c, "
                             "two-column, or single-column with --dt) and/or folders of them "
                             "(with an optional NGA-West2 _SearchResults.csv).")
UNITS_OPT = typer.Option(None, help="Units of two-column or single-column records: m/s2 "
                         "(default), g, cm/s2 (= gal), mm/s2; also written m/s/s, m/s^2, "
                         "cm/sec2, ...")
APPLY_SCALE_OPT = typer.Option(False, "--apply-scale", help="Multiply each record by the "
                               "scale factor of its _SearchResults.csv row.")
SEARCH_RESULTS_OPT = typer.Option(None, "--search-results", help="The NGA-West2 metadata "
                                  "csv (default: _SearchResults.csv of a given folder).")


@records_app.command("info", short_help="List records with metadata and intensity measures.")
@guarded
def info(
    sources: list[Path] = SOURCES_ARG,
    units: str = UNITS_OPT,
    dt: float = DT_OPT,
    apply_scale: bool = APPLY_SCALE_OPT,
    search_results: Path = SEARCH_RESULTS_OPT,
    vertical: bool = typer.Option(False, "--vertical", help="Keep vertical components "
                                  "(left out by default)."),
    periods: str = typer.Option(",".join(f"{p:g}" for p in intensity.PERIODS),
                                help="Periods of Sa(T) [s], comma-separated."),
    damping: float = typer.Option(intensity.DAMPING, help="Damping ratio of Sa(T)."),
    plot: Path = typer.Option(None, help="PNG of the records' Sa/PGA spectra, median and "
                              "16–84 % band."),
    pulse_method: str = typer.Option("2007", "--pulse-method", "--method",
                                     help="Velocity-pulse classification: 2007 (Baker "
                                     "2007) or 2014 (Shahi & Baker 2014)."),
    json_out: bool = JSON_OPT,
) -> None:
    """Each record's event, station, component, dt, duration and intensity measures (PGA,
    PGV, PGD, Arias, D5-95, Tm, Sa(T)) and its velocity-pulse class, flags and period
    (Baker 2007, or Shahi & Baker 2014 with --pulse-method 2014); SI units in --json."""
    per = float_list("--periods", periods)
    method = check_method(pulse_method)
    check_outputs((plot, "--plot", "png"))
    check_suite_units(sources, units, dt)
    suite = read_suite(sources, units=units, apply_scale=apply_scale,
                       search_results=search_results, vertical=vertical, dt=dt)
    rows = describe(suite, per, damping, method)
    if plot is not None:
        from rockarch.output.figures import save_figure
        from rockarch.output.suite_plots import plot_spectra
        save_figure(plot_spectra(suite, damping=damping), plot)
    if json_out:
        print_json({"csv": suite.csv, "apply_scale": apply_scale, "periods": list(per),
                    "damping": damping, "pulse_method": method, "records": rows,
                    "notes": list(suite.notes),
                    "plot": None if plot is None else str(plot)})
        return
    if suite.csv:
        typer.echo(f"metadata: {suite.csv}")
    for note in suite.notes:
        typer.echo(f"note: {note}")
    meta = any(r["magnitude"] is not None or r["scale_factor"] is not None for r in rows)
    head = (f"{'record':40s} {'event':22s} {'station':26s} {'comp':>5s} {'dt':>6s} "
            f"{'dur':>6s} {'PGA[g]':>7s} {'PGV':>6s} {'PGD':>6s} {'Ia':>6s} "
            f"{'D5-95':>6s} {'Tm':>5s} {'pulse':>10s} {'flags':>11s} {'Tp':>5s}")
    typer.echo(head + (f" {'M':>5s} {'Rrup':>6s} {'Vs30':>6s} {'SF':>6s}" if meta else ""))
    for r in rows:
        line = (f"{r['name'][:40]:40s} {(r['event'] or '-')[:22]:22s} "
                f"{(r['station'] or '-')[:26]:26s} {(r['component'] or '-')[:5]:>5s} "
                f"{r['dt']:6.3f} {r['duration']:6.1f} {_num(r['pga'] / G_STANDARD, 7, 3)} "
                f"{_num(r['pgv'], 6, 3)} {_num(r['pgd'], 6, 3)} {_num(r['arias'], 6, 3)} "
                f"{r['d5_95']:6.1f} "
                f"{r['tm']:5.2f} {r['pulse_class']:>10s} {_flags(r):>11s} "
                f"{_num(r['tp'], 5, 2)}")
        if meta:
            line += "".join(f" {_num(r[k], w, d)}" for k, w, d in
                            (("magnitude", 5, 2), ("rrup", 6, 1), ("vs30", 6, 0),
                             ("scale_factor", 6, 3)))
        typer.echo(line)
    source = "Baker 2007" if method == "2007" else "Shahi & Baker 2014"
    typer.echo(f"pulse: class of the {source} indicator; flags: late (the pulse arrives "
               "late)" + (", pgv<30 (PGV <= 30 cm/s)" if method == "2007" else "")
               + "; pulse-like = class pulse and no flag")
    typer.echo(f"units: PGA g ({g_label(G_STANDARD)}), PGV m/s, PGD m, Ia m/s, D5-95 s, "
               f"Tm s, Tp s ({source} pulse "
               "period)" + ("; Rrup km, Vs30 m/s, SF csv scale factor" if meta else "")
               + "; Sa(T) in --json")
    if plot is not None:
        typer.echo(f"wrote {plot}")


def _flags(row: dict) -> str:
    """The pulse flags of a ``describe`` row: late, pgv<30, or "-"."""
    flags = [name for key, name in (("pulse_late", "late"), ("pulse_low_pgv", "pgv<30"))
             if row[key]]
    return ",".join(flags) or "-"


def _num(value, width: int, digits: int) -> str:
    """``value`` in ``width`` characters with ``digits`` decimals; "-" for None; a value that
    those decimals would show as zero (a weak record's PGA of 3e-4 g) in e-notation."""
    if value is None:
        return f"{'-':>{width}s}"
    if value != 0 and abs(value) < 0.5 * 10.0 ** -digits:
        return f"{value:{width}.{max(width - 6, 0)}e}"
    return f"{value:{width}.{digits}f}"


@records_app.command("synth", short_help="Write a seeded synthetic suite of .AT2 records.")
@guarded
def synth(
    directory: Path = typer.Argument(..., help="Folder to write (created if missing)."),
    n: int = typer.Option(50, "--n", help="Number of records."),
    seed: int = typer.Option(0, help="Random seed (same seed, same records)."),
    dt: float = typer.Option(synthetic.DT, help="Time step [s]."),
    f_corner: float = typer.Option(synthetic.F_CORNER, help="High-pass corner [Hz] (0: none)."),
    pulse_fraction: float = typer.Option(0.0, help="Probability that a record carries a "
                                         "near-fault velocity pulse (Mavroeidis & "
                                         "Papageorgiou 2003), 0…1."),
    json_out: bool = JSON_OPT,
) -> None:
    """Synthetic records of the Rezaeian & Der Kiureghian (2008) stochastic model, their
    parameters drawn from the distributions RDK (2010) fitted to NGA records, written as
    .AT2 files with their parameters in _synthetic_parameters.csv (docs/sites.md)."""
    if f_corner < 0:
        raise ValueError(f"--f-corner must be >= 0, got {f_corner}")
    check_outputs((directory, "DIRECTORY", "dir"))
    paths = synthetic.write_suite(directory, n, seed, dt=dt, f_corner=f_corner,
                                  pulse_fraction=pulse_fraction)
    if json_out:
        print_json({"directory": str(directory), "seed": seed,
                    "records": [p.name for p in paths],
                    "parameters": str(directory / synthetic.PARAMETERS_FILE)})
        return
    typer.echo(f"wrote {len(paths)} synthetic record(s) to {directory} (seed {seed}); "
               f"parameters in {synthetic.PARAMETERS_FILE}")
