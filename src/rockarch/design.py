"""Design check of an arch with a site OAS (paper Sect. 9, Fig. 20; docs/theory.md §7).

The arch is replaced by a catenary arch (:mod:`rockarch.arch.replacement`), whose critical
optimal four-hinge mechanism gives p and ap,min; the site's OAS of a slender block read at p
gives the ratio ap/ap,min it survives, and the largest safe peak ground acceleration is
ap = ratio·ap,min (paper Eq. 16, docs/theory.md Eq. 7.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import xarray as xr

from rockarch import site
from rockarch._validate import positive
from rockarch.arch.geometry import Arch
from rockarch.arch.replacement import RULES, Replacement, replacement
from rockarch.constants import G


@dataclass(frozen=True)
class DesignResult:
    """Outcome of :func:`design_check` (paper Eq. 16)."""

    arch: Arch
    replacement: Replacement
    rule: str
    curve: str
    ratio: float
    ratio_is_lower_bound: bool
    pga_safe: float
    g: float

    @property
    def chosen(self):
        return self.replacement.by_rule(self.rule)

    def to_dict(self) -> dict:
        """The CLI's JSON contract (``rockarch design --json``)."""
        repl = {**self.chosen.to_dict(), "axis": self.replacement.band.axis,
                "mass": self.replacement.mass,
                "original_ap_min": self.replacement.original.ap_min}
        return {"replacement": repl, "ratio": self.ratio, "pga_safe": self.pga_safe,
                "pga_safe_g": self.pga_safe / self.g}


def design_check(arch: Arch, site_ds: xr.Dataset, *, rule: str = "equivalent",
                 curve: str = "envelope", g: float = G, axis: str = "catenary",
                 mass: str = "own", repl: Replacement | None = None) -> DesignResult:
    """Largest safe PGA of ``arch`` at the site (paper Sect. 9, Eq. 16).

    Parameters
    ----------
    rule : "equivalent" (ap,min of the replacement equals the arch's; the paper's Sect. 9
        choice) or "lower-bound" (the thickest catenary inside the contour; more
        conservative).
    curve : "envelope" (lowest boundary over the site's records) or "characteristic" (the
        site file's percentile curve).
    axis, mass : the replacement's axis family and mass
        (:func:`rockarch.arch.replacement.replacement`).
    """
    if rule not in RULES:
        raise ValueError(f"thickness rule must be one of {', '.join(RULES)}, got {rule!r}")
    g = positive("g", g)
    repl = repl if repl is not None else replacement(arch, g=g, axis=axis, mass=mass)
    chosen = repl.by_rule(rule)
    ratio, lower = site.curve_at(site_ds, chosen.p, curve)
    return DesignResult(arch, repl, rule, curve, ratio, lower, ratio * chosen.ap_min, g)
