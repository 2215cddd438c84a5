"""HTML output: the one page writer and the one stylesheet of every rockarch page (the
design report, the index of ``rockarch reproduce``). Pages are self-contained: no external
resources, figures inlined as base64 PNG or linked next to the page."""

from __future__ import annotations

import base64
import datetime as _dt
import html
from collections.abc import Iterable
from pathlib import Path

from rockarch.core.paths import write_text
from rockarch.output.figures import png_bytes

STYLESHEET = """
body { font-family: sans-serif; max-width: 70em; margin: 2em auto; padding: 0 1em;
       color: #222; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }
.result { font-size: 1.25em; background: #eef5ee; padding: 0.8em; border: 1px solid #9c9; }
.result .caveat { font-size: 0.8em; color: #8a4b00; margin: 0.4em 0 0 0; }
img { max-width: 100%; }
code { font-size: 0.85em; }
"""

escape = html.escape


def stamp() -> str:
    """Local date and time of a page (minutes)."""
    return _dt.datetime.now().strftime("%Y-%m-%d %H:%M")


def table(head: Iterable[str] | None, rows: Iterable[Iterable[object]]) -> str:
    """An HTML table; every cell is escaped."""
    th = "" if head is None else \
        "<tr>" + "".join(f"<th>{escape(str(h))}</th>" for h in head) + "</tr>"
    body = "".join("<tr>" + "".join(f"<td>{escape(str(c))}</td>" for c in r) + "</tr>"
                   for r in rows)
    return f"<table>{th}{body}</table>"


def key_value_table(rows: Iterable[tuple[str, object]]) -> str:
    """A two-column table: the key as a header cell, the value beside it."""
    return "<table>" + "".join(f"<tr><th>{escape(str(a))}</th><td>{escape(str(b))}</td></tr>"
                               for a, b in rows) + "</table>"


def inline_figure(fig, alt: str, *, dpi: int = 110) -> str:
    """An ``<img>`` holding the figure as base64 PNG."""
    data = base64.b64encode(png_bytes(fig, dpi=dpi)).decode("ascii")
    return f'<img alt="{escape(alt)}" src="data:image/png;base64,{data}">'


def page(title: str, body: str) -> str:
    """A whole HTML page with the stylesheet; ``body`` is HTML."""
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            f"<title>{escape(title)}</title>\n<style>{STYLESHEET}</style></head><body>\n"
            f"{body}\n</body></html>\n")


def write_page(path, title: str, body: str) -> Path:
    """Write :func:`page` to ``path`` atomically."""
    return write_text(path, page(title, body))
