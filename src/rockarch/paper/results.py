"""The paper's tables and figures, computed (used by ``rockarch reproduce`` and examples/).

Reference values are the paper's (:mod:`rockarch.paper.reference`); every function returns plain
rows (dicts) with the paper's value next to rockarch's, or draws a figure.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rockarch import mdof, systems
from rockarch.arch import (
    analyse,
    catenary,
    circular,
    kinematics,
    mass_per_horizontal_length,
    weighted_catenary,
)
from rockarch.arch.replacement import replacement
from rockarch.core.constants import G
from rockarch.design import design_check
from rockarch.motion import signals as motion
from rockarch.motion.records import bundled_record_path
from rockarch.output.boundary_plots import Curve, Panel, plot_boundaries
from rockarch.output.report import write_report
from rockarch.paper.reference import SECT8, SECT9, TABLE1, TABLE2
from rockarch.risk import fragility as fr
from rockarch.rocking.fourhinge_motion import fourhinge_mechanism
from rockarch.spectra import oas as spectra
from rockarch.spectra import site

SIGNALS = ("sine", "square", "step")

def table1_rows(g: float = G) -> list[dict]:
    """Table 1: paper vs rockarch for every catenary arch (continuous mechanism, paper Eq. 14).

    ``c4`` is in Table 1's convention (docs/theory.md Eq. 5.4), ``c4_u`` on the dynamics'
    coordinate u (the other end part). ``c1c4_eq12`` is the delta-free product
    c1·c4 = g·A·d/(Bv·f·l) of paper Eq. 12 (docs/theory.md Eq. 5.5) with A and Bv on the
    coordinate of Table 1's delta; the paper's own c1·c4 can be set against it.
    """
    rows = []
    for (fl, dl), (c1, c2, c3, c3p, c4) in TABLE1.items():
        r = analyse(catenary(1.0, fl, dl), g=g)
        rate = abs(float(kinematics(r.mechanism, 0.0).dphi[r.end_part - 1, 0]))
        rows.append({"f/l": fl, "d/l": dl, "paper": {"c1": c1, "c2": c2, "c3": c3,
                                                       "c3p": c3p, "c4": c4},
                     "ours": {"c1": r.c1, "c2": r.c2, "c3": r.c3, "c3p": r.c3p, "c4": r.c4,
                              "c4_u": r.c4_u, "c1c4": r.c1 * r.c4,
                              "c1c4_eq12": g * r.A * dl / (r.Bv * fl * rate)},
                     "paper_c1c4_ratio": c1 * c4 / (g * r.A * dl / (r.Bv * fl * rate))})
    return rows


def sect8_rows(g: float = G) -> list[dict]:
    """The Sect. 8 circular arch at both quoted slendernesses."""
    rows = []
    for dl in (0.0346, 0.0345):
        r = analyse(circular(SECT8["span"], SECT8["rise"], SECT8["span"] * dl), g=g)
        rows.append({"d/l": dl, "ap_min": r.ap_min, "c1": r.c1, "c2": r.c2, "p": r.p,
                     "delta": r.delta_end, "hinges_x": [h.x for h in r.hinges]})
    return rows


def _replacement_row(r, span: float, g: float) -> dict:
    return {"d/l": r.thickness / span, "d/l'": r.thickness / r.span, "span": r.span,
            "rise": r.rise, "thickness": r.thickness, "c1": r.mechanism.c1,
            "c2": r.mechanism.c2, "ap_min": r.ap_min, "R/l": r.R_block / span, "p": r.p}


def table2_rows(g: float = G) -> dict:
    """Table 2: (a) the lower-bound construction of docs/theory.md Eqs. 7.3–7.7 on the Sect. 8
    arch (both mass options), (b) the paper's printed geometry (f = 2.924 m, l = 10 m)."""
    span = SECT8["span"]
    arch = circular(span, SECT8["rise"], span * SECT8["d_over_l"])
    rep = replacement(arch, g=g)
    rep_orig = replacement(arch, g=g, mass="original")
    fitted = {r.rule: _replacement_row(r, span, g) for r in (rep.equivalent, rep.lower_bound)}
    fitted_orig = {r.rule: _replacement_row(r, span, g)
                   for r in (rep_orig.equivalent, rep_orig.lower_bound)}
    w = mass_per_horizontal_length(arch)
    given = {}
    for rule, ref in TABLE2.items():
        m = analyse(weighted_catenary(span, ref["rise"], span * ref["d/l"], weights=w), g=g)
        given[rule] = {"d/l": ref["d/l"], "rise": ref["rise"], "c1": m.c1, "c2": m.c2,
                       "ap_min": m.ap_min, "R/l": 0.75 * g / m.p**2 / span, "p": m.p}
    o = rep.original
    return {"original": {"ap_min": o.ap_min, "c1": o.c1, "c2": o.c2, "p": o.p},
            "fitted": fitted, "fitted_original_mass": fitted_orig, "paper_geometry": given,
            "replacement": rep}


def _boundary(system, signal: str, p, ratio) -> np.ndarray:
    return spectra.compute_oas(system, motion.pulse(signal, period=1.0), p, ratio,
                               progress=False).boundary.values


def fig15(path, n_p: int = 40, rises=(0.2, 0.3, 0.4), thick=(0.0125, 0.025, 0.05)
          ) -> list[dict]:
    """Hypothesis 1 (Fig. 15): four-hinge OAS of catenary arches and the slender block."""
    colors = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    p = np.linspace(0.5, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, 71)
    block = systems.BlockSystem(alpha=0.01)
    rows, panels = [], []
    for sig in SIGNALS:
        bb = _boundary(block, sig, p, ratio)
        b_inf = np.where(np.isfinite(bb), bb, np.inf)
        panels.append([])
        for rise in rises:
            slender, curves = None, []
            for d, col in zip(thick, colors, strict=False):
                mech = fourhinge_mechanism(catenary(1.0, rise, d))
                b = _boundary(systems.MechanismSystem(mech), sig, p, ratio)
                rhs = np.where(np.isfinite(b), b, np.inf)
                slender = rhs if slender is None else slender
                curves.append(Curve(f"arch d/l = {d}", p, b, style={"color": col, "lw": 1.5}))
                rows.append({"signal": sig, "f/l": rise, "d/l": d, "e": mech.plus.e_close,
                             "slender_safe": float(np.mean(slender <= rhs * (1 + 1e-3))),
                             "block_safe": float(np.mean(b_inf <= rhs * (1 + 1e-3)))})
            curves.append(Curve("slender block (alpha = 0.01)", p, bb, "k--"))
            panels[-1].append(Panel(f"{sig}, T = 1 s, catenary f/l = {rise}", curves))
    plot_boundaries(panels, path, panel_size=(4.4, 11 / 3), suptitle="Hypothesis 1 (paper "
                    "Fig. 15): OAS of critical optimal four-hinge mechanisms of catenary "
                    "arches")
    return rows


def equivalence_rows(n_p: int = 19, thick=(0.05, 0.025, 0.0125, 0.005, 0.0025)) -> list[dict]:
    """Four-hinge catenary (f/l = 0.3) vs the block with the same p and ap,min, d/l → 0."""
    p = np.linspace(1.0, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, 57)
    rows = []
    for sig in SIGNALS:
        for d in thick:
            mech = fourhinge_mechanism(catenary(1.0, 0.3, d))
            blk = systems.BlockSystem(alpha=math.atan(mech.ap_min / mech.g))
            rel = (_boundary(systems.MechanismSystem(mech), sig, p, ratio)
                   / _boundary(blk, sig, p, ratio) - 1)
            rows.append({"signal": sig, "d/l": d, "e": mech.plus.e_close,
                         "max_dev": float(np.nanmax(np.abs(rel))),
                         "mean_dev": float(np.nanmean(rel)),
                         "block_safe": float(np.nanmean(rel >= -1e-3))})
    return rows


def _compare(ref, other):
    """(share of p where `other` is at or below `ref` (safe side), mean relative gap)."""
    r = np.where(np.isfinite(ref), ref, np.inf)
    o = np.where(np.isfinite(other), other, np.inf)
    both = np.isfinite(r) & np.isfinite(o)
    safe = float(np.mean(o <= r * (1 + 2e-3)))
    rel = float(np.nanmean((o[both] - r[both]) / r[both])) if both.any() else math.nan
    return safe, rel


#: Geometries of Figs. 16–17 (the paper does not list them): catenaries at d/l = 0.025.
MDOF_GEOMETRIES = ((0.2, 0.025), (0.3, 0.025), (0.4, 0.025))


def fig16_17(out, n_p: int = 30, blocks: int = 20, n_ratio: int = 57,
             tol: float = 1e-3) -> list[dict]:
    """Hypotheses 2 and 3 (Figs. 16, 17): the MDOF catenary arch against its critical
    optimal four-hinge mechanism and against the block with the same p and ap,min.

    Every curve is on the axes of the continuous arch's optimal four-hinge mechanism (its p
    at the arch's size, ap / its ap,min). Writes hypothesis2.png and hypothesis3.png.
    """

    out = Path(out)
    p = np.linspace(0.5, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, n_ratio)
    panels: dict[int, list] = {2: [[] for _ in SIGNALS], 3: [[] for _ in SIGNALS]}
    rows = []
    for rise, d in MDOF_GEOMETRIES:
        arch = catenary(1.0, rise, d)
        fh = fourhinge_mechanism(arch)
        asm = mdof.arch_assembly(arch, blocks)
        sys_m = systems.MDOFSystem(asm, ap_min_override=fh.ap_min, p_override=fh.p)
        sys_f = systems.MechanismSystem(fh)
        sys_b = systems.BlockSystem(alpha=math.atan(fh.ap_min / fh.g))
        for i, sig in enumerate(SIGNALS):
            m = motion.pulse(sig, period=1.0)
            bm, bf, bb = (spectra.compute_oas(s, m, p, ratio, tol=tol,
                                              progress=False).boundary.values
                          for s in (sys_m, sys_f, sys_b))
            pp, rr = np.meshgrid(p, [1.5], indexing="ij")
            nopen = int(mdof.simulate_batch(asm, m, pp, rr, ap_min=fh.ap_min,
                                            p_ref=fh.p).extras["open_joints_max"].max())
            s2, r2 = _compare(bm, bf)
            s3, r3 = _compare(bm, bb)
            rows.append({"signal": sig, "f/l": rise, "d/l": d,
                         "ap_min_ratio": asm.ap_min / fh.ap_min, "fourhinge_safe": s2,
                         "fourhinge_rel": r2, "block_safe": s3, "block_rel": r3,
                         "open_joints_max": nopen})
            for h, other, lab in ((2, bf, "critical optimal four-hinge"),
                                  (3, bb, "block, same p and ap,min")):
                panels[h][i].append(Panel(
                    f"{sig}, T = 1 s, catenary f/l = {rise}, d/l = {d}",
                    [Curve(f"MDOF arch, N = {blocks}", p, bm,
                           style={"color": "tab:red", "lw": 1.8}),
                     Curve(lab, p, other, "k--")]))
    for h, title in ((2, "Hypothesis 2 (paper Fig. 16): MDOF catenary arch vs its critical "
                      "optimal four-hinge mechanism"),
                     (3, "Hypothesis 3 (paper Fig. 17): MDOF catenary arch vs the block with "
                      "the same p and ap,min")):
        plot_boundaries(panels[h], out / f"hypothesis{h}.png", suptitle=title,
                        xlabel="p [1/s] (optimal four-hinge mechanism)",
                        panel_size=(13 / 3, 11 / 3))
    return rows


def fig19(path, rep=None, n_p: int = 37, mdof_blocks: int | None = 20) -> list[dict]:
    """Fig. 19: OAS of the Sect. 8 arch (four-hinge mechanism and, unless ``mdof_blocks`` is
    None, the MDOF arch of that many voussoirs) and of the blocks of both replacement
    catenaries (each block on its own p and ap,min).

    Returns one row per signal and curve: the share of p at which the curve is at or below
    the reference (the MDOF arch, else the four-hinge mechanism) and the mean relative gap.
    """
    arch = circular(SECT8["span"], SECT8["rise"], SECT8["span"] * SECT8["d_over_l"])
    rep = rep if rep is not None else replacement(arch)
    p = np.linspace(1.0, 10.0, n_p)
    ratio = np.linspace(1.0, 8.0, 57)
    fh = fourhinge_mechanism(arch)
    curves = [("circular arch, four-hinge mechanism", systems.MechanismSystem(fh), "k-")]
    if mdof_blocks is not None:

        curves.append((f"circular arch, MDOF N = {mdof_blocks}",
                        systems.MDOFSystem(mdof.arch_assembly(arch, mdof_blocks),
                                           ap_min_override=fh.ap_min, p_override=fh.p),
                        "r-"))
    for r, style in ((rep.equivalent, "b--"), (rep.lower_bound, "b:")):
        curves.append((f"block of the {r.rule} replacement",
                        systems.BlockSystem(alpha=math.atan(r.ap_min / G)), style))
    rows, panels = [], []
    for sig in SIGNALS:
        bounds = [_boundary(system, sig, p, ratio) for _, system, _ in curves]
        ref = bounds[1] if mdof_blocks is not None else bounds[0]
        for (label, _, _), b in zip(curves, bounds, strict=True):
            if b is not ref:
                safe, rel = _compare(ref, b)
                rows.append({"signal": sig, "curve": label, "safe": safe, "mean_rel": rel})
        panels.append(Panel(f"{sig}, T = 1 s", [
            Curve(label, p, b, style_) for (label, _, style_), b in zip(curves, bounds,
                                                                        strict=True)]))
    plot_boundaries([panels], path, panel_size=(5.0, 4.4), ylim=None,
                    suptitle="Paper Fig. 19: OAS of the circular arch (f/l = 0.289, d/l = "
                    "0.0346) and of its replacement blocks")
    return rows


def sect9(out: Path, n_p: int = 100) -> dict:
    """Sect. 9 design example on a site OAS of the two bundled El Centro components."""

    out = Path(out)
    motions, hashes = site.load_records([bundled_record_path(180), bundled_record_path(270)])
    site_ds = site.site_oas(motions, np.linspace(0.5, 10.0, n_p), np.linspace(1.0, 5.0, 81),
                            hashes=hashes, progress=False)
    site.save(site_ds, out / "site.nc")
    arch = circular(10.0, 2.89, SECT9["thickness"])
    repl = replacement(arch)
    c = repl.equivalent  # the records' first collapses at its p, islands searched
    ida = fr.site_ida(motions, c.p, c.ap_min, ratio=site_ds["ratio"].values)
    res = design_check(arch, site_ds, rule="equivalent", repl=repl, ida=ida)
    records = bundled_record_path(180).parent
    if records.is_relative_to(Path.cwd()):  # a clone's own folder, as the docs quote it
        records = records.relative_to(Path.cwd())
    cmd = ("rockarch design --shape circular --span 10 --rise 2.89 --thickness 0.35 "
           f"--records {records}/ --thickness-rule equivalent --curve envelope")
    write_report(res, site_ds, out / "design_report.html", command=cmd,
                 site_path=str(out / "site.nc"),
                 inputs={"shape": "circular", "span [m]": 10.0, "rise [m]": 2.89,
                         "thickness [m]": SECT9["thickness"]})
    return {"thickness": c.thickness, "rise": c.rise, "p": c.p, "ap_min": c.ap_min,
            "ratio": res.ratio, "ratio_grid": res.ratio_grid, "pga_safe": res.pga_safe,
            "pga_safe_g": res.pga_safe / G,
            "pga_with_paper_ratio": SECT9["ratio"] * c.ap_min, "command": cmd}
