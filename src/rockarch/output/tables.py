"""Text tables printed by the commands (fixed-width columns, right-aligned)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

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
