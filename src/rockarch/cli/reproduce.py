"""``rockarch reproduce``: the paper's tables and figures into one folder."""

from __future__ import annotations

from pathlib import Path

import typer

from rockarch.cli._app import app
from rockarch.cli._common import JSON_OPT, echo_err, guarded, print_json
from rockarch.output import check_outputs


@app.command("reproduce", short_help="The paper's tables and figures, paper vs computed.")
@guarded
def reproduce_command(
    out: Path = typer.Option(..., help="Folder to write (created if needed)."),
    quick: bool = typer.Option(False, "--quick", help="Coarse grids (about a minute)."),
    json_out: bool = JSON_OPT,
) -> None:
    """The paper's tables and figures (Figs. 2-3, Tables 1-2, Figs. 15-17 and 19, Sect. 9)
    into OUT, with an index.html showing paper vs computed side by side."""

    check_outputs((out, "--out", "dir"))
    from rockarch.paper.reproduce import reproduce

    reproduce(out, quick=quick, log=echo_err)
    index = out / "index.html"
    if json_out:
        print_json({"index": str(index),
                    "files": sorted(str(p) for p in out.rglob("*") if p.is_file())})
        return
    typer.echo(str(index))
