"""The typer applications every command module registers on (no commands here)."""

from __future__ import annotations

import sys

import typer
from typer.core import TyperGroup

from rockarch.core import __version__, jit_cache
from rockarch.core.console import one_line_warnings

# the click that typer runs on (typer >= 0.24 vendors its own copy)
_CLICK_ERROR = next(c for c in typer.BadParameter.__mro__ if c.__name__ == "ClickException")
_NO_ARGS = getattr(sys.modules[_CLICK_ERROR.__module__], "NoArgsIsHelpError", ())


def _notice(line: str) -> None:
    """A note on stderr (a closed or broken stderr: nothing to show it on)."""
    try:
        print(line, file=sys.stderr, flush=True)
    except (OSError, ValueError, AttributeError):
        pass


class OneLineErrors(TyperGroup):
    """Click's usage errors (unknown option, bad choice, missing value) become the same one
    line ``error: ...`` with exit status 2 as every other bad input."""

    def main(self, *args, standalone_mode: bool = True, **kwargs):
        one_line_warnings()
        jit_cache.compile_notice = _notice
        try:
            rv = super().main(*args, standalone_mode=False, **kwargs)
        except _NO_ARGS as exc:
            exc.show()
            rv = exc.exit_code
        except _CLICK_ERROR as exc:
            msg = " ".join(exc.format_message().split())
            typer.echo(f"error: {msg}", err=True)
            rv = 2
        except typer.Abort:
            typer.echo("error: interrupted", err=True)
            rv = 130
        if not standalone_mode:
            return rv
        sys.exit(rv if isinstance(rv, int) else 0)


# rich_markup_mode=None: help texts show units such as "[m/s²]" literally (not as markup)
app = typer.Typer(
    cls=OneLineErrors,
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=None,
    help="Seismic overturning assessment of rocking blocks and masonry arches.",
)
simulate_app = typer.Typer(no_args_is_help=True, rich_markup_mode=None,
                           help="Simulate one structure on one ground motion.")
app.add_typer(simulate_app, name="simulate")


def _version(value: bool) -> None:
    if value:
        typer.echo(f"rockarch {__version__}")
        raise typer.Exit()


@app.callback()
def main(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                      help="Print the version and exit.")) -> None:
    """Seismic overturning assessment of rocking blocks and masonry arches."""
