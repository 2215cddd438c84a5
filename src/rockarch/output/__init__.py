"""Everything rockarch writes for people: figures, HTML pages, animations, text tables.

Theory: none of its own (it draws and tabulates what the stages compute).

Modules: :mod:`~rockarch.core.paths` (check before computing, atomic and staged writes,
the output formats), :mod:`~rockarch.output.figures` (canvas helpers, OAS maps, time
histories, site OAS), :mod:`~rockarch.output.arch_plots` (arch drawings),
:mod:`~rockarch.output.html` (the page writer and stylesheet),
:mod:`~rockarch.output.report` (design report), :mod:`~rockarch.output.animation` (MDOF
GIF), :mod:`~rockarch.output.tables` (text tables). Importing this package does not import
matplotlib; the names below load their module on first use.

A command that writes files checks them all first, before any computation, then writes
them together::

    check_outputs((out, "--out", "netcdf"), (plot, "--plot", "png"))
    ...  # compute
    with staged(out, plot) as (out_tmp, plot_tmp):
        save(ds, out_tmp)
        save_figure(fig, plot_tmp)

A new kind of file: add it to :data:`FORMATS` (name, extensions, description).
"""

from __future__ import annotations

import importlib

from rockarch.core.paths import (
    FORMATS,
    OutputError,
    atomic_write,
    check_output,
    check_output_dir,
    check_outputs,
    staged,
    write_text,
)

_LAZY = {
    "new_figure": "figures", "subplots": "figures", "save_figure": "figures",
    "png_bytes": "figures", "plot_oas": "figures", "plot_response": "figures",
    "plot_site": "figures", "mechanism_figure": "arch_plots", "plot_mechanism": "arch_plots",
    "design_arch_figure": "arch_plots", "write_report": "report", "animate": "animation",
    "boundary_table": "tables", "text_table": "tables",
}


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(importlib.import_module(f"rockarch.output.{_LAZY[name]}"), name)
    raise AttributeError(f"module 'rockarch.output' has no attribute {name!r}")


__all__ = ["FORMATS", "OutputError", "atomic_write", "check_output", "check_output_dir",
           "check_outputs", "staged", "write_text", *_LAZY]
