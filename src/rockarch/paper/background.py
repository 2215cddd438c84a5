"""The paper's background figures (Figs. 2 and 3), computed with rockarch's own engines.

* Fig. 2: the OAS of a rigid block (overturned region over p × ap/ap,min) for a sine pulse
  and for a record (the bundled El Centro 1940 record, component 180°).
* Fig. 3a: the lowest overturning boundary of a slender block against less slender ones on
  the same (p, ap/ap,min) axes — the design method's claim is that the slender block is on
  the safe side (lowest boundary).
* Fig. 3b: multi-block columns of equal blocks (MDOF engine) against the monolithic block
  of the same overall size — the claim is that the columns are less vulnerable.

Each function returns plain rows (one per curve and signal) with the share of p where the
claim holds, and draws its figure. The columns use the monolith's axes: stacking equal
blocks changes neither ap,min = g·tan(alpha) of the whole nor its size, so the MDOF
system's own p and ap,min are the monolith's (checked in the rows).
"""

from __future__ import annotations

import math

import numpy as np

from rockarch import systems
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro
from rockarch.output.boundary_plots import Curve, Panel, plot_boundaries, plot_regions
from rockarch.spectra import oas as spectra
from rockarch.spectra import site

#: Slendernesses of Fig. 3a (the slender one is the site OAS's block).
FIG3_ALPHAS = (site.ALPHA, 0.1, 0.2, 0.3)
#: Fig. 3b: overall slenderness and height of the columns, and their numbers of blocks.
FIG3B_ALPHA = 0.2
FIG3B_HEIGHT = 4.0
FIG3B_BLOCKS = (1, 2, 3, 5)
_SAFE = 2e-3  # two curves within 0.2 % count as equal (the bisection tolerance is 1e-3)


SINE = "sine, T = 1 s"
RECORD = "El Centro 1940 (180°)"


def _motions(names=None) -> dict:
    names = (SINE, RECORD) if names is None else tuple(names)
    known = {SINE: lambda: motion.pulse("sine", period=1.0), RECORD: el_centro}
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ValueError(f"unknown excitation {unknown[0]!r}: choose from {', '.join(known)}")
    return {n: known[n]() for n in names}


def _boundary(system, m, p, ratio, tol) -> np.ndarray:
    b = spectra.compute_oas(system, m, p, ratio, tol=tol, progress=False).boundary.values
    return np.where(np.isfinite(b), b, np.inf)


def _share(lower: np.ndarray, upper: np.ndarray) -> float:
    """Share of p where ``lower`` is at or below ``upper`` (within :data:`_SAFE`)."""
    both = np.isfinite(lower) | np.isfinite(upper)
    if not both.any():
        return math.nan
    return float(np.mean(lower[both] <= upper[both] * (1 + _SAFE)))


def _where_above(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> list[float]:
    """The p where ``a`` is above ``b`` by more than :data:`_SAFE` (a claim a <= b fails)."""
    bad = (a > b * (1 + _SAFE)) & (np.isfinite(a) | np.isfinite(b))
    return [round(float(x), 3) for x in p[bad]]


def _below(a: np.ndarray, b: np.ndarray) -> float:
    """Share of p where ``a`` is clearly below ``b`` (by more than :data:`_SAFE`)."""
    both = np.isfinite(a) | np.isfinite(b)
    return float(np.mean(a[both] < b[both] * (1 - _SAFE))) if both.any() else math.nan


def fig2(path, *, n_p: int = 60, n_ratio: int = 71, alpha: float = site.ALPHA) -> list[dict]:
    """Fig. 2: the overturned region of a slender block, sine pulse and record."""
    p = np.linspace(0.5, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, n_ratio)
    blk = systems.BlockSystem(alpha=alpha)
    rows, maps = [], []
    for name, m in _motions().items():
        ds = spectra.compute_oas(blk, m, p, ratio, tol=0.0, progress=False)
        over = ds.overturned.values
        maps.append((f"block alpha = {alpha:g}, {name} (grey: overturns)", p, ratio, over,
                     ds.boundary.values))
        # islands: overturning at a ratio, not at a larger one, for the same p
        islands = int(np.sum(np.any(over[:, :-1] & ~over[:, 1:], axis=1)))
        rows.append({"signal": name, "alpha": alpha, "overturned_share": float(over.mean()),
                     "p_with_safe_islands": islands, "n_p": n_p})
    plot_regions(maps, path)
    return rows


def fig3a(path, *, n_p: int = 40, n_ratio: int = 57, tol: float = 1e-3,
          signals=None) -> list[dict]:
    """Fig. 3a: slender block vs less slender blocks (each on its own ap,min).

    ``signals``: a subset of (:data:`SINE`, :data:`RECORD`) (default both).
    """
    motions = _motions(signals)
    p = np.linspace(0.5, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, n_ratio)
    rows, panels = [], []
    for name, m in motions.items():
        curves = {a: _boundary(systems.BlockSystem(alpha=a), m, p, ratio, tol)
                  for a in FIG3_ALPHAS}
        slender = curves[FIG3_ALPHAS[0]]
        panels.append(Panel(f"{name}: slender vs less slender blocks", [
            Curve(f"alpha = {a:g}", p, b, style={"lw": 1.8 if a == FIG3_ALPHAS[0] else 1.1})
            for a, b in curves.items()]))
        rows += [{"signal": name, "alpha": a, "slender_safe": _share(slender, b),
                  "p_not": _where_above(p, slender, b)}
                 for a, b in curves.items() if a != FIG3_ALPHAS[0]]
    plot_boundaries([panels], path)
    return rows


def fig3b(path, *, n_p: int = 20, n_ratio: int = 57, tol: float = 1e-3,
          blocks=FIG3B_BLOCKS, signals=None) -> list[dict]:
    """Fig. 3b: columns of N equal blocks vs the monolith of the same size (MDOF engine for
    all, the block engine's monolith drawn for reference). ``blocks`` must start with 1."""
    if tuple(blocks)[0] != 1:
        raise ValueError("fig3b compares with the monolith: blocks must start with 1")
    motions = _motions(signals)
    p = np.linspace(0.5, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, n_ratio)
    width = FIG3B_HEIGHT * math.tan(FIG3B_ALPHA)
    rows, panels = [], []
    for name, m in motions.items():
        ref = _boundary(systems.BlockSystem(alpha=FIG3B_ALPHA), m, p, ratio, tol)
        curves = [Curve("monolith, block engine", p, ref, "k:", {"lw": 1.2})]
        mono = None
        for n in blocks:
            col = systems.system("mdof", column=[(width, FIG3B_HEIGHT / n)] * n)
            b = _boundary(col, m, p, ratio, tol)
            curves.append(Curve("monolith, MDOF engine" if n == 1 else
                                f"column of {n} blocks", p, b, style={"lw": 1.8 if n == 1
                                                                       else 1.1}))
            if n == 1:
                mono = b
                continue
            both = np.isfinite(b) & np.isfinite(mono)
            rows.append({"signal": name, "blocks": n, "ap_min": col.ap_min,
                         "p_ref": col.p_ref, "column_safer": _share(mono, b),
                         "column_weaker": _below(b, mono),
                         "p_weaker": _where_above(p, mono, b),
                         "mean_rel": float(np.mean(b[both] / mono[both] - 1)) if both.any()
                         else math.nan})
        panels.append(Panel(f"{name}: columns vs monolith, alpha = {FIG3B_ALPHA:g}, "
                            f"H = {FIG3B_HEIGHT:g} m", curves))
    plot_boundaries([panels], path, xlabel="p [1/s] (monolith)")
    return rows
