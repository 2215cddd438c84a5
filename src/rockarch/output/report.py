"""Self-contained HTML report of a design check (paper Sect. 9): figures inlined as base64
PNG, no external resources, so it opens offline and can be archived with the project."""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from rockarch.core import __version__
from rockarch.core.constants import G_STANDARD, g_label
from rockarch.core.paths import write_text
from rockarch.design import DesignResult, SystemDesign
from rockarch.output.arch_plots import design_arch_figure
from rockarch.output.figures import new_figure
from rockarch.output.html import escape, inline_figure, key_value_table, page, stamp, table
from rockarch.spectra.site import read_with, record_sha256

ASSUMPTIONS = [
    "The arch is replaced by a catenary arch carrying its own mass (paper Sect. 4 and 8), on "
    "the axis of the thickest uniform catenary band inside the arch's contour with its "
    "springings on the arch's springing joints. That band's thickness (lower bound) is "
    "conservative; the equivalent thickness (same ap,min as the arch) is the paper's Sect. 9 "
    "choice and its safety rests on the other assumptions below.",
    "The catenary arch is replaced by a slender monolithic rigid block with the same p and "
    "ap,min (DeJong & Dimitrakopoulos equivalence; paper Hypotheses 1–3: the block's OAS is a "
    "safe approximation of the multi-block catenary arch's).",
    "The slender block's OAS neglects most of the energy dissipated at impacts, which is "
    "larger in real, thicker arches (paper Sect. 9.1).",
    "Overturning is declared when the block's rotation reaches alpha (the mechanism its "
    "neutral position), although the ground could still pull it back: conservative.",
    "The site curve is read at the grid value of p on the safe side (the smaller of the two "
    "neighbouring values); where no record overturns within the computed ratio range, the "
    "top of the range is used (a lower bound).",
]


def site_figure(result: DesignResult, site_ds: xr.Dataset):
    """Every record's OAS boundary, the envelope, the characteristic curve, the arch's point."""
    fig = new_figure((7, 4.4))
    ax = fig.subplots()
    p = site_ds["p"].values
    for k in range(site_ds.sizes["record"]):
        ax.plot(p, site_ds["boundary"].values[k], color="0.6", lw=0.7,
                label="records" if k == 0 else None)
    ax.plot(p, site_ds["envelope"].values, "k-", lw=1.8, label="envelope")
    ax.plot(p, site_ds["characteristic"].values, "k--", lw=1.2,
            label=f"{site_ds.attrs.get('percentile', 50):g}th percentile")
    c = result.chosen
    ax.axvline(c.p, color="tab:red", lw=0.8, ls=":")
    ax.plot([c.p], [result.ratio], "o", color="tab:red", ms=8,
            label=f"arch: p = {c.p:.3f} 1/s, ap/ap,min = {result.ratio:.3f}")
    ax.set_xlabel("frequency parameter p [1/s]")
    ax.set_ylabel(r"lowest overturning $a_p/a_{p,\min}$ [-]")
    ax.set_ylim(1.0, float(site_ds["ratio"].values[-1]))
    ax.legend(fontsize=8)
    ax.set_title(f"site OAS, slender block alpha = {site_ds.attrs.get('alpha', 0):g}",
                 fontsize=9)
    return fig


def _inputs_table(result: DesignResult, site_ds: xr.Dataset, inputs: dict,
                  site_path: str | None) -> str:
    site_hash = ""
    if site_path and Path(site_path).exists():
        site_hash = hashlib.sha256(Path(site_path).read_bytes()).hexdigest()
    p, r = site_ds["p"].values, site_ds["ratio"].values
    return key_value_table([(k, str(v)) for k, v in inputs.items()] + [
        ("thickness rule", result.rule), ("site curve", result.curve),
        ("g [m/s²]", f"{result.g:g}"), ("site file", str(site_path or "")),
        ("site file SHA-256", site_hash),
        ("site block alpha", f"{site_ds.attrs.get('alpha')}"),
        ("site percentile", f"{site_ds.attrs.get('percentile')}"),
        ("site p range [1/s]", f"{p[0]:g}…{p[-1]:g}"),
        ("site ratio range", f"{r[0]:g}…{r[-1]:g}"),
        ("site built with rockarch", str(site_ds.attrs.get("rockarch_version")))])


def read_as(units: str, dt: float) -> str:
    """How a site file says a record was read (its ``record_units``, ``record_dt``):
    '--units g --dt 0.01', 'its own units' (an .AT2, ESM, K-NET or COSMOS file)."""
    if not units:
        return "its own units"
    return f"--units {units}" + (f" --dt {dt:g}" if np.isfinite(dt) else "")


def _records_table(site_ds: xr.Dataset) -> str:
    """The site's records: name, PGA, how each was read (files that record it) and the
    SHA-256 of its file."""
    cols = [site_ds["record_name"].values, site_ds["record_pga"].values / G_STANDARD]
    head = ["record", f"PGA [{g_label(G_STANDARD)}]"]
    if "record_units" in site_ds and "record_dt" in site_ds:  # older files do not say
        head.append("read with")
        cols.append([read_as(str(u), float(d)) for u, d in zip(
            site_ds["record_units"].values, site_ds["record_dt"].values, strict=True)])
    cols.append(site_ds["record_sha256"].values)
    rows = [(row[0], f"{row[1]:.4f}", *row[2:]) for row in zip(*cols, strict=True)]
    return table([*head, "SHA-256 of the file"], rows)


def report_html(result: DesignResult, site_ds: xr.Dataset, *, command: str, inputs: dict,
                site_path: str | None = None, extra_html: str = "",
                caveats: Sequence[str] = ()) -> str:
    """The report as one HTML page; ``command`` reruns the check, ``inputs`` lists the
    arch's parameters; ``extra_html`` (e.g. the fragility of a suite) follows the site
    OAS; ``caveats`` (what the check did not search or bound) follow the result."""
    c = result.chosen
    rep = result.replacement
    g = result.g
    lower = " (at least: no record overturns within the computed range)" \
        if result.ratio_is_lower_bound else ""
    islands = (f"from the {result.curve} of the records' first collapses at p (collapse "
               f"islands searched below the site OAS grid, which reads "
               f"{result.ratio_grid:.4f} there) " if result.islands_lower
               else f"read on the site's {result.curve} ")
    records = _records_table(site_ds)
    replacements = table(
        ["replacement", "d [m]", "d/l′", "d/l", "l′ [m]", "f′ [m]", "p [1/s]",
         "ap,min [m/s²]", "c1", "c2", "block R [m]"],
        [(r.rule, f"{r.thickness:.4f}", f"{r.thickness / r.span:.5f}",
          f"{r.thickness / r.original_span:.5f}", f"{r.span:.4f}", f"{r.rise:.4f}",
          f"{r.p:.4f}", f"{r.ap_min:.4f}", f"{r.mechanism.c1:.4f}", f"{r.mechanism.c2:.4f}",
          f"{r.R_block:.4f}") for r in (rep.lower_bound, rep.equivalent)])
    body = f"""<h1>Overturning design check of a masonry arch</h1>
<p>rockarch {__version__}, {stamp()}.
Method: paper Sect. 9 (replacement catenary arch, slender-block OAS of the site).</p>
<div class="result">Largest safe peak ground acceleration:
<b>{result.pga_safe:.3f} m/s² = {result.pga_safe / g:.3f} g</b> ({g_label(g)})<br>
ap/ap,min = {result.ratio:.4f}{lower} {islands}at
p = {c.p:.4f} 1/s; ap,min = {c.ap_min:.4f} m/s² ({result.rule} thickness).
{"Below this PGA the arch may move but does not collapse." if not caveats else
 "Below this PGA the arch may move; that it does not collapse holds within these caveats:"}
{"".join(f'<p class="caveat">{escape(c)}</p>' for c in caveats)}</div>
<h2>Arch and replacement catenary arch</h2>
{inline_figure(design_arch_figure(result), "arch")}
<p>Original arch: critical optimal four-hinge mechanism ap,min = {rep.original.ap_min:.4f} m/s²
(lambda = {rep.original.lambda_:.5f}), p = {rep.original.p:.4f} 1/s,
delta_u = {rep.original.delta:.5f} rad (its hinges: <code>rockarch arch</code>). The
figure draws the chosen replacement's thrust line and four hinges. Replacement springings
(square markers, original's coordinates):
P_L = ({c.springings[0, 0]:.4f}, {c.springings[0, 1]:.4f}) m,
P_R = ({c.springings[1, 0]:.4f}, {c.springings[1, 1]:.4f}) m, on the springing joints;
l′ is the replacement's own span, l the arch's.</p>
{replacements}
<h2>Site OAS</h2>
{inline_figure(site_figure(result, site_ds), "site OAS")}
{records}
{extra_html}
<h2>Chain of conservative assumptions</h2>
<ol>{''.join(f'<li>{escape(a)}</li>' for a in ASSUMPTIONS)}</ol>
<h2>Inputs (to rerun)</h2>
<p><code>{escape(command)}</code></p>
{_inputs_table(result, site_ds, inputs, site_path)}"""
    return page("rockarch design check", body)


def write_report(result: DesignResult, site_ds: xr.Dataset, path, *, command: str,
                 inputs: dict, site_path: str | None = None, extra_html: str = "",
                 caveats: Sequence[str] = ()) -> Path:
    """Write the HTML report atomically (see :func:`report_html`)."""
    return write_text(path, report_html(result, site_ds, command=command, inputs=inputs,
                                        site_path=site_path, extra_html=extra_html,
                                        caveats=caveats))


#: What the design of any structure assumes, per method (docs/theory.md §11.4).
SYSTEM_ASSUMPTIONS = {
    "records": [
        "No equivalence: the structure itself is simulated at its own size under every record "
        "scaled up until it collapses (incremental dynamic analysis, docs/theory.md Eq. "
        "(11.30)); the safe PGA is the lowest collapse PGA over the records (envelope) or "
        "their chosen percentile, Eq. (11.34).",
        "ap,min (the unit of the scan) is the structure's limit value (a block: g·tan "
        "alpha; a four-hinge mechanism: docs/theory.md §5); for an MDOF assembly it is the "
        "limit analysis with non-associative Coulomb friction, docs/theory.md Eqs. "
        "(10.4)–(10.9): from the associative LP (10.4), an iteration of LPs whose shear "
        "capacities are mu times the previous normal forces (10.6)–(10.8), so that a joint "
        "slides without opening and an open joint carries no shear, and a search of rigid "
        "clusters rocking about one corner (10.9), the smaller of the two. These are "
        "solutions of the non-associative problem, not bounds (a lower mechanism of several "
        "clusters may exist, docs/theory.md §10); the time histories do not depend on it.",
        "Collapse is declared once the structure, frozen at rest, would move away under "
        "gravity alone (past its neutral configuration, docs/theory.md §6): conservative.",
        "Records that do not collapse the structure up to the top of the scan are censored; "
        "a safe PGA read on a censored record is a lower bound.",
    ],
    "equivalent-sdof": [
        "The structure is replaced by the slender block with the same p and ap,min (its own "
        "rocking collapse mechanism, docs/theory.md Eq. (11.35)); its collapse mechanism "
        "does not slide (ap,min with friction equals ap,min without sliding).",
        "The slender block's OAS neglects most of the energy dissipated at impacts.",
        "The site curve is read at the grid value of p on the safe side; where no record "
        "overturns within the computed ratio range, the top of the range is used (a lower "
        "bound).",
    ],
}


def system_report_html(result: SystemDesign, *, command: str, suite=None,
                       caveats: Sequence[str] = ()) -> str:
    """The design report of any structure (:func:`rockarch.design.design_system`) as one
    HTML page: the safe PGA, the structure's p and ap,min, the records' collapse points
    and fragility (``suite``: their response spectra and file hashes), the assumptions and
    the command that reruns it; ``caveats`` (what the check did not search or bound)
    follow the result, as in :func:`report_html`."""
    from rockarch.output.fragility_plots import fragility_html

    r, g = result, result.g
    lower = " (at least: the governing record does not collapse the structure within the " \
        "scan)" if r.ratio_is_lower_bound else ""
    curve = r.curve if r.curve == "envelope" else f"{r.percentile:g}th percentile"
    how = ("its own collapse points over the records" if r.method == "records" else
           "a slender block's site OAS at its p (equivalent SDOF)")
    slide = "" if r.ap_min_no_sliding is None else (
        f" (friction-aware; {r.ap_min_no_sliding:.4f} m/s² without sliding: the collapse "
        f"mechanism {'slides' if r.sliding else 'rocks'})")
    body = f"""<h1>Overturning design check of {escape(r.system)}</h1>
<p>rockarch {__version__}, {stamp()}. Method: {escape(how)}, docs/theory.md §11.4.</p>
<div class="result">Largest safe peak ground acceleration:
<b>{r.pga_safe:.3f} m/s² = {r.pga_safe / g:.3f} g</b> ({g_label(g)})<br>
ap/ap,min = {r.ratio:.4f}{lower} ({escape(curve)}) at p = {r.p:.4f} 1/s;
ap,min = {r.ap_min:.4f} m/s²{escape(slide)}.
{"" if not caveats else
 "Below this PGA the structure may move; that it does not collapse holds within these "
 "caveats:"}
{"".join(f'<p class="caveat">{escape(c)}</p>' for c in caveats)}</div>\n"""
    frag = r.fragility
    if frag is not None:
        ida = frag.ida
        body += "<h2>Collapse points (IDA)</h2>\n" + table(
            ["record", "collapse PGA [m/s²]", "resurrections"],
            [(n, f"{x:.4f}" if np.isfinite(x) else f"> {lim:.4f} (censored)", k)
             for n, x, lim, k in zip(ida.records, ida.im_collapse, ida.im_limit,
                                     ida.resurrections, strict=True)])
        if frag.fit is not None:
            body += fragility_html(frag, r.summary, suite, of=escape(r.system))
    if suite is not None:
        body += "<h2>Records</h2>\n" + table(
            ["record", f"PGA [{g_label(G_STANDARD)}]", "read with", "SHA-256 of the file"],
            [(rec.name, f"{rec.motion.pga / G_STANDARD:.4f}", read_as(*read_with(rec.motion)),
              record_sha256(rec))
             for rec in suite])
    body += f"""<h2>Assumptions</h2>
<ol>{''.join(f'<li>{escape(a)}</li>' for a in SYSTEM_ASSUMPTIONS[r.method])}</ol>
<h2>Inputs (to rerun)</h2>
<p><code>{escape(command)}</code></p>"""
    return page("rockarch design check", body)


def write_system_report(result: SystemDesign, path, *, command: str, suite=None,
                        caveats: Sequence[str] = ()) -> Path:
    """Write :func:`system_report_html` atomically."""
    return write_text(path, system_report_html(result, command=command, suite=suite,
                                               caveats=caveats))
