"""Text tables printed by the commands (fixed-width columns, right-aligned)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from rockarch.core.constants import G_STANDARD

#: Units as JSON files and the user write them -> as text and figures print them.
_PRINTED_UNITS = {"m/s2": "m/s²", "m/s^2": "m/s²", "cm/s2": "cm/s²", "cm/s^2": "cm/s²",
                  "mm/s2": "mm/s²", "mm/s^2": "mm/s²"}


def unit_label(units: str) -> str:
    """Units as printed in text and figures.

    Parameters
    ----------
    units : str
        Units as a JSON file or a hazard curve's header writes them (``"m/s2"``).

    Returns
    -------
    str
        The same units with a superscript square (``"m/s²"``); other units unchanged.
    """
    return _PRINTED_UNITS.get(units.strip(), units)


def g_label(g: float) -> str:
    """Which g an acceleration shown in g was divided by.

    Parameters
    ----------
    g : float
        A structure's own g (default 9.81 m/s², docs/theory.md §0) or standard gravity
        (9.80665 m/s²: records and hazard curves in units of g are converted with it).

    Returns
    -------
    str
        ``"g = 9.81 m/s²"``.
    """
    return f"g = {g:g} m/s²"


def standard_g(units: str) -> str:
    """:func:`g_label` of standard gravity where a file's units are g.

    Parameters
    ----------
    units : str
        Units as a hazard curve or a record writes them (``"g"``, ``"m/s2"``).

    Returns
    -------
    str
        ``"g = 9.80665 m/s²"`` for ``"g"``, else ``""``.
    """
    return g_label(G_STANDARD) if units.strip() == "g" else ""


def text_table(headers: Sequence[str], rows: Iterable[Sequence[str]],
               widths: Sequence[int], sep: str = "  ") -> list[str]:
    """Lines of a table: every cell right-aligned in its column's width (cells wider than
    their column are kept whole)."""
    def line(cells):
        return sep.join(f"{c:>{w}}" for c, w in zip(cells, widths, strict=True))

    return [line(headers), *(line(r) for r in rows)]


def boundary_table(p: np.ndarray, boundary: np.ndarray, ratio_max: float) -> list[str]:
    """The OAS boundary per p (``rockarch oas``); no overturning within the grid is shown
    as ``> ratio_max``."""
    rows = [(f"{pv:.4g}", f"{bv:.4f}" if np.isfinite(bv) else
             f"> {ratio_max:g} (none in range)") for pv, bv in zip(p, boundary, strict=True)]
    return text_table(("p [1/s]", "boundary ap/ap,min"), rows, (10, 20))
