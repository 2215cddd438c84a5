"""``rockarch cache info`` and ``rockarch cache clear``: the store of finished sweep chunks
(:mod:`rockarch.core.sweep.store`; docs/sweeps.md, "The store")."""

from __future__ import annotations

import os
from pathlib import Path

import typer

from rockarch.cli._app import app
from rockarch.cli._common import JSON_OPT, guarded, print_json
from rockarch.core.sweep import clear_store, code_digest, store_info

cache_app = typer.Typer(no_args_is_help=True, rich_markup_mode=None,
                        help="The store of finished sweep chunks (oas, site-oas, "
                             "fragility): where it is, what it holds; empty it.")
app.add_typer(cache_app, name="cache", short_help="The sweep store: where it is, its size; "
              "clear it.")

CACHE_STORE_OPT = typer.Option(None, "--store", help="A store folder given to oas/site-oas "
                               "with --store (default: the default store, $ROCKARCH_CACHE, "
                               "else $XDG_CACHE_HOME/rockarch, else ~/.cache/rockarch).")


def _size(n: int) -> str:
    """Bytes in a human unit (1024-based)."""
    for unit in ("B", "KiB", "MiB", "GiB"):
        if n < 1024 or unit == "GiB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1024
    return f"{n} B"  # pragma: no cover - the loop always returns


def _origin(store: Path | None) -> str:
    if store is not None:
        return "--store"
    if os.environ.get("ROCKARCH_CACHE"):
        return "$ROCKARCH_CACHE"
    return "$XDG_CACHE_HOME" if os.environ.get("XDG_CACHE_HOME") else "default"


@cache_app.command("info", short_help="Where the store is, its chunks and size.")
@guarded
def info(store: Path = CACHE_STORE_OPT, json_out: bool = JSON_OPT) -> None:
    """Where the store of finished chunks lives, how many chunks it holds and their size.

    Chunks are keyed by their inputs and by a digest of rockarch's source code: chunks of
    other code versions are never reused (they only take space; 'rockarch cache clear')."""
    st = store_info(store)
    origin = _origin(store)
    if json_out:
        print_json({**st.as_dict(), "origin": origin, "code_digest": code_digest()})
        return
    typer.echo(f"store:  {st.root} ({origin}"
               + ("" if st.exists else "; not created yet") + ")")
    typer.echo(f"chunks: {st.chunks}")
    typer.echo(f"size:   {_size(st.size)}")
    typer.echo("move it: set ROCKARCH_CACHE=DIR, or give --store DIR to oas / site-oas "
               "(and to this command)")


@cache_app.command("clear", short_help="Delete every chunk of the store.")
@guarded
def clear(store: Path = CACHE_STORE_OPT, json_out: bool = JSON_OPT) -> None:
    """Delete every finished chunk of the store (later sweeps recompute them). Only the
    store's own chunk files are removed; other files in the folder are left alone."""
    removed = clear_store(store)
    if json_out:
        print_json({"store": str(removed.root), "removed_chunks": removed.chunks,
                    "removed_bytes": removed.size})
        return
    typer.echo(f"removed {removed.chunks} chunks ({_size(removed.size)}) from {removed.root}")
