"""Design checks: the largest safe PGA of a structure at a site.

Theory: docs/theory.md §7 (replacement catenary arch, Eq. 7.2), §11.4 (design of any
structure, Eqs. 11.34–11.35), §11.5 (the annual frequency of collapse at a site and its
inverse, Eqs. 11.36–11.42).

- An arch by the paper's method (Sect. 9, Fig. 20; docs/theory.md §7), :func:`design_check`:
  the arch is replaced by a catenary arch (:mod:`rockarch.arch.replacement`), whose
  critical optimal four-hinge mechanism gives p and ap,min; the site's OAS of a slender
  block read at p gives the ratio ap/ap,min it survives, and the largest safe peak ground
  acceleration is ap = ratio·ap,min (paper Eq. 16, docs/theory.md Eq. 7.2).
- Any system (block, mechanism, MDOF assembly with friction), :func:`design_system`: its
  own ap,min (friction-aware limit analysis) and either its own IDA over the records
  (Eq. (11.34)) or a slender block's site OAS read at its p (Eq. (11.35)).
- With a site's hazard curve, :func:`site_risk`: the annual frequency of collapse of the
  fragility found, the probability of collapse in N years and the largest scale of the
  hazard that meets a target; :func:`smallest_thickness`: the thinnest arch that meets it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rockarch.arch.geometry import Arch
from rockarch.arch.replacement import RULES, Replacement, replacement
from rockarch.core.constants import G
from rockarch.core.validate import in_range, integer, positive
from rockarch.motion.suite import as_motions
from rockarch.risk import fragility as fr
from rockarch.risk import hazard as hz
from rockarch.spectra import site as site_mod
from rockarch.systems import check_system

if TYPE_CHECKING:  # xarray (half a second to import) where a dataset is made or read
    import xarray as xr


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
    ratio_grid: float = float("nan")

    @property
    def chosen(self):
        return self.replacement.by_rule(self.rule)

    def to_dict(self) -> dict:
        """The CLI's JSON contract (``rockarch design --json``)."""
        repl = {**self.chosen.to_dict(), "axis": self.replacement.band.axis,
                "mass": self.replacement.mass,
                "original_ap_min": self.replacement.original.ap_min}
        out = {"replacement": repl, "ratio": self.ratio, "pga_safe": self.pga_safe,
               "pga_safe_g": self.pga_safe / self.g}
        if np.isfinite(self.ratio_grid):
            out["ratio_site_grid"] = self.ratio_grid
        return out

    @property
    def islands_lower(self) -> bool:
        """True where the records' first collapses at p (collapse islands searched) read the
        site curve lower than the site OAS grid does."""
        return bool(self.ratio < self.ratio_grid)


def design_check(arch: Arch, site_ds: xr.Dataset, *, rule: str = "equivalent",
                 curve: str = "envelope", g: float = G, axis: str = "catenary",
                 mass: str = "own", repl: Replacement | None = None,
                 ida: fr.IDAResult | None = None) -> DesignResult:
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
    ida : the site's records' IDA at the replacement's p
        (:func:`rockarch.risk.fragility.site_ida`, collapse islands searched below the
        grid, Eq. (11.30a)). The site OAS's boundaries are the first collapse *on its grid*
        and miss islands narrower than the grid's step; with ``ida`` the ratio is the
        smaller of the site curve at p and the same curve (envelope or percentile) of the
        records' first collapses at p (``ratio_grid`` keeps the site curve's value). The
        normalised and simplified curves, fits over p (Sect. 11.2), are read as they are.
    """
    if rule not in RULES:
        raise ValueError(f"thickness rule must be one of {', '.join(RULES)}, got {rule!r}")
    g = positive("g", g)
    repl = repl if repl is not None else replacement(arch, g=g, axis=axis, mass=mass)
    chosen = repl.by_rule(rule)
    ratio, lower = site_mod.curve_at(site_ds, chosen.p, curve)
    grid = float("nan")
    if ida is not None and curve in SYSTEM_CURVES:  # the two curves that are statistics of
        # the records' boundaries at p (normalised and simplified curves are fits over p)
        if not math.isclose(ida.p, chosen.p, rel_tol=1e-9):
            raise ValueError(f"the IDA is at p = {ida.p:.6g} 1/s, the replacement has p = "
                             f"{chosen.p:.6g} 1/s")
        env, char = site_mod.curves(ida.ratio_collapse[:, None],
                                    float(site_ds.attrs.get("percentile", 50.0)))
        at_p = float((env if curve == "envelope" else char)[0])
        grid = ratio
        if at_p < ratio:
            ratio, lower = at_p, False
    return DesignResult(arch, repl, rule, curve, ratio, lower, ratio * chosen.ap_min, g, grid)


# --------------------------------------------------------------------------- any system

#: Site curves of the design of any system: the lowest collapse over the records, or a
#: percentile of them.
SYSTEM_CURVES = ("envelope", "characteristic")


@dataclass(frozen=True)
class SystemDesign:
    """Outcome of :func:`design_system`: the largest safe PGA of one structure at a site
    (docs/theory.md Eqs. (11.34)–(11.35)).

    ``method`` is ``"records"`` (the structure's own IDA over the records; ``fragility``
    holds its points and lognormal fit) or ``"equivalent-sdof"`` (a slender block's site
    OAS read at the structure's p). ``sliding``: the limit analysis's collapse mechanism
    slides (friction governs ap,min).
    """

    system: str
    p: float
    ap_min: float
    method: str
    curve: str
    percentile: float
    ratio: float
    ratio_is_lower_bound: bool
    pga_safe: float
    g: float
    sliding: bool = False
    ap_min_no_sliding: float | None = None
    fragility: fr.Fragility | None = None
    summary: dict | None = None
    note: str | None = None

    def to_dict(self) -> dict:
        """The CLI's JSON contract (``rockarch design --system ... --json``)."""
        out = {"system": self.system, "p": self.p, "ap_min": self.ap_min,
               "method": self.method, "curve": self.curve, "ratio": self.ratio,
               "ratio_is_lower_bound": self.ratio_is_lower_bound,
               "pga_safe": self.pga_safe, "pga_safe_g": self.pga_safe / self.g,
               "sliding": self.sliding}
        if self.curve == "characteristic":
            out["percentile"] = self.percentile
        if self.ap_min_no_sliding is not None:
            out["ap_min_no_sliding"] = self.ap_min_no_sliding
        if self.fragility is not None:
            frag = self.fragility.to_dict()
            out["points"] = frag["points"]
            out["scan"] = {**frag["scan"], "search_step": frag["search_step"]}
            out["fragility"] = self.summary
        return out


def _structure(system, p: float | None) -> tuple[float, bool, float | None]:
    """(p, sliding, ap_min without sliding) of a system at its own size or at ``p``."""
    p = system.p_ref if p is None else p
    if p is None:
        raise ValueError(f"{system.name}: give its frequency parameter p (a block: p or "
                         "width and height)")
    a = getattr(system, "assembly", None)
    if a is None or a.frictionless:
        return float(p), False, None
    return float(p), a.slides, float(a.info.get("ap_min_no_sliding", a.ap_min))


def _safe_ratio(value: float, top: float) -> tuple[float, bool]:
    """A site curve's ratio, or the top of the range (a lower bound) where it is +inf."""
    return (float(value), False) if np.isfinite(value) else (float(top), True)


def design_system(system, *, records=None, names=None, site: xr.Dataset | None = None,
                  p: float | None = None, curve: str = "envelope", percentile: float = 50.0,
                  ratio=None, tol: float | None = None, n_bootstrap: int = fr.N_BOOTSTRAP,
                  level: float = 0.95, pga: float | None = None,
                  probability: float | None = 0.1, g: float = G, executor=None,
                  store=None, progress: bool = False,
                  log: Callable[[str], None] | None = None,
                  search_step: float | None = None) -> SystemDesign:
    """Largest safe PGA of any structure at a site (docs/theory.md Eqs. (11.34)–(11.35)).

    Parameters
    ----------
    system : a system of :func:`rockarch.systems.system` (block, fourhinge, frame, sdof,
        mdof with friction, piers, walls, colonnades, assembly files).
    records, names : the site's records (a :class:`rockarch.motion.suite.Suite` or motions): the
        structure's own IDA at ``p`` over them (:func:`rockarch.risk.fragility.ida`); the safe
        ratio is the envelope (lowest) or ``percentile`` of the records' collapse ratios,
        Eq. (11.34), and the collapse points are fitted by a lognormal (§11.3).
    site : instead of records, a slender block's site OAS (:func:`rockarch.spectra.site.site_oas`)
        read at the structure's p, Eq. (11.35) (refused if its collapse mechanism slides).
    p : the structure's frequency parameter [1/s] (default its own, ``system.p_ref``).
    curve : ``"envelope"`` or ``"characteristic"`` (the percentile; with ``site`` the
        file's own percentile).
    ratio, tol : the IDA scan grid of ap/ap,min and bisection tolerance (default those of
        :func:`rockarch.risk.fragility.ida`: 1 … 5 in 81 values and 0.001, 17 values and
        0.01 for MDOF assemblies); n_bootstrap, level, pga, probability : as in
        :func:`rockarch.risk.fragility.design_summary`.
    executor, store, progress : as in :func:`rockarch.spectra.oas.compute_oas`.
    log, search_step : as in :func:`rockarch.risk.fragility.ida` (a line per stage; the
        search for collapse islands below the grid's first collapse).
    """
    check_system(system, "system")
    import xarray as xr

    if site is not None and not isinstance(site, xr.Dataset):
        raise TypeError(f"site must be a site OAS (xarray.Dataset of rockarch.spectra.site."
                        f"load), got {type(site).__name__}")
    if records is not None:
        motions, names = as_motions(records, names)
    if curve not in SYSTEM_CURVES:
        raise ValueError(f"the site curve of a structure's design must be one of "
                         f"{', '.join(SYSTEM_CURVES)}, got {curve!r}")
    if (records is None) == (site is None):
        raise ValueError("give either records or a site OAS")
    g = positive("g", g)
    # the fragility's numbers before the IDA (minutes) rather than after it
    if pga is not None:
        positive("pga [m/s²]", pga)
    if probability is not None:
        in_range("probability", probability, 0.0, 1.0, lo_open=True, hi_open=True)
    in_range("percentile", percentile, 0.0, 100.0)
    in_range("level", level, 0.0, 1.0, lo_open=True, hi_open=True)
    if not 0 <= integer("n_bootstrap", n_bootstrap) <= fr.MAX_BOOTSTRAP:
        raise ValueError(f"n_bootstrap must lie in [0, {fr.MAX_BOOTSTRAP}], got {n_bootstrap}")
    p, sliding, rock = _structure(system, p)
    ap_min = float(system.ap_min)
    common = {"system": system.name, "p": p, "ap_min": ap_min, "curve": curve, "g": g,
              "sliding": sliding, "ap_min_no_sliding": rock}
    if site is not None:
        site_mod.check_block_site(site, structure=system.name)
        if sliding:
            raise ValueError(f"the collapse mechanism of {system.name} slides (ap,min = "
                             f"{ap_min:.4g} m/s² with friction, {rock:.4g} m/s² without): a "
                             "rocking block's site OAS does not apply; give --records")
        r, lower = site_mod.curve_at(site, p, curve)
        return SystemDesign(method="equivalent-sdof", ratio=r, ratio_is_lower_bound=lower,
                            pga_safe=r * ap_min,
                            percentile=float(site.attrs.get("percentile", 50.0)),
                            **common)
    res = fr.ida(system, motions, p, names=names, ratio=ratio, tol=tol, executor=executor,
                 store=store, progress=progress, log=log, search_step=search_step)
    env, char = site_mod.curves(res.ratio_collapse, percentile)
    r, lower = _safe_ratio(env if curve == "envelope" else char, res.ratio[-1])
    note, summary = None, None
    try:
        frag = fr.fit_ida(res, n_bootstrap=n_bootstrap, level=level)
        summary = fr.design_summary(frag, pga=pga, probability=probability, g=g)
    except fr.TooFewCollapses as exc:  # the points and the safe PGA are still the answer
        frag, note = fr.Fragility(res, None, {}), str(exc)
    return SystemDesign(method="records", ratio=r, ratio_is_lower_bound=lower,
                        pga_safe=r * ap_min, percentile=float(percentile), fragility=frag,
                        summary=summary, note=note, **common)


# --------------------------------------------------------------------------- risk


@dataclass(frozen=True)
class SiteRisk:
    """The annual frequency of collapse of a designed structure at a site and, given a
    target probability of collapse in N years, the inverse (docs/theory.md Sect. 11.5):
    the largest scale of the site's hazard (Eq. (11.42)) and, for an arch, the smallest
    thickness with P(collapse in N years) ≤ the target.

    ``trials`` are the (thickness [m], P in N years) pairs the thickness search ran.
    """

    result: hz.RiskResult
    hazard: hz.HazardCurve
    fragility: hz.FragilityCurve
    target: float | None = None
    scale: float | None = None
    thickness: float | None = None
    trials: tuple = ()

    def to_dict(self) -> dict:
        """The ``risk`` object of ``rockarch design --hazard --json``: ``annual_rate``
        [1/yr], ``probability``, ``years``, the deaggregation (IM in the hazard file's
        units), and with a target ``target_probability``, ``largest_scale`` and (arches)
        ``smallest_thickness`` [m] with its ``trials``."""
        out = {**self.result.to_dict(self.hazard.factor, self.hazard.units),
               "hazard": self.hazard.source, "median": self.fragility.median,
               "beta": self.fragility.beta}
        if self.target is not None:
            out.update(target_probability=self.target, largest_scale=self.scale)
        if self.thickness is not None:
            out.update(smallest_thickness=self.thickness,
                       trials=[{"thickness": d, "probability": q} for d, q in self.trials])
        return out


def site_risk(fit, hazard: hz.HazardCurve, *, years: float = 50.0,
              probability: float | None = None, extrapolate: bool = False) -> SiteRisk:
    """λ_c and P(collapse in ``years``) of a lognormal PGA fragility ``fit`` (θ, β in
    m/s², e.g. :class:`rockarch.risk.fragility.LognormalFit`) at a site of hazard curve
    ``hazard`` (Eqs. (11.36)–(11.37)); with a target ``probability`` the largest scale of
    the hazard that meets it (Eq. (11.42))."""
    frag = hz.fragility_curve("pga", fit.median, fit.beta)
    if hazard.im != "pga":
        raise ValueError(f"the design's fragility is in PGA: give a PGA hazard curve "
                         f"({hazard.source} is in {hazard.label})")
    res = hz.collapse_rate(hazard, frag, years=years, extrapolate=extrapolate)
    scale = None if probability is None else hz.largest_scale(
        hazard, frag, probability, years=years, extrapolate=extrapolate)
    return SiteRisk(res, hazard, frag, probability, scale)


def smallest_thickness(arch: Arch, motions, hazard: hz.HazardCurve, probability: float, *,
                       years: float = 50.0, alpha: float = site_mod.ALPHA, ratio=None,
                       rule: str = "equivalent", axis: str = "catenary", mass: str = "own",
                       g: float = G, extrapolate: bool = False, rel_tol: float = 0.01
                       ) -> tuple[float, tuple]:
    """The smallest uniform thickness of ``arch``'s shape (same span and rise) whose
    replacement's fragility (the site's slender block at its p, in units of its ap,min:
    :func:`rockarch.risk.fragility.site_fragility`) gives P(collapse in ``years``) ≤
    ``probability`` at the site (Eqs. (7.2), (11.36)–(11.37)).

    From the arch's thickness, steps of ×1.25 bracket the answer (a thickness whose
    statics fail counts as unsafe), then bisection to ``rel_tol``. P is assumed to fall
    as the thickness grows (ap,min grows about linearly with d, p hardly changes); the
    bracket's ends are checked, the points between are not. Returns (thickness [m], the
    (thickness, P) pairs run).
    """
    from rockarch.arch.geometry import make_arch

    target = float(probability)
    if not 0 < target < 1:
        raise ValueError(f"a probability of collapse in N years must lie in (0, 1), got "
                         f"{target}")
    trials = []

    def prob(d: float) -> float:
        try:
            a = make_arch(arch.shape, arch.span, arch.rise, d)
            chosen = replacement(a, g=g, axis=axis, mass=mass).by_rule(rule)
        except ValueError:  # too thin for a thrust line: it does not stand
            trials.append((d, 1.0))
            return 1.0
        frag = fr.site_fragility(motions, chosen.p, chosen.ap_min, alpha=alpha, ratio=ratio,
                                 n_bootstrap=0)
        q = hz.collapse_rate(hazard, hz.fragility_curve("pga", frag.fit.median,
                                                        frag.fit.beta),
                             years=years, extrapolate=True).probability
        trials.append((d, q))
        return q

    d0 = float(arch.thickness)
    lo, hi = (None, d0) if prob(d0) <= target else (d0, None)
    for _ in range(12):
        if lo is None:
            d = hi / 1.25
            lo, hi = (None, d) if prob(d) <= target else (d, hi)
        elif hi is None:
            d = lo * 1.25
            lo, hi = (lo, d) if prob(d) <= target else (d, None)
        else:
            break
    if lo is None or hi is None:
        raise ValueError(f"no thickness between {d0 / 1.25 ** 12:.3g} and "
                         f"{d0 * 1.25 ** 12:.3g} m brackets P(collapse in {years:g} years) "
                         f"= {target:g}")
    while hi - lo > rel_tol * hi:
        d = 0.5 * (lo + hi)
        lo, hi = (lo, d) if prob(d) <= target else (d, hi)
    # the answer's coverage of the hazard, as the caller asked (extrapolate or not)
    a = make_arch(arch.shape, arch.span, arch.rise, hi)
    chosen = replacement(a, g=g, axis=axis, mass=mass).by_rule(rule)
    frag = fr.site_fragility(motions, chosen.p, chosen.ap_min, alpha=alpha, ratio=ratio,
                             n_bootstrap=0)
    hz.collapse_rate(hazard, hz.fragility_curve("pga", frag.fit.median, frag.fit.beta),
                     years=years, extrapolate=extrapolate)
    return hi, tuple(sorted(trials))
