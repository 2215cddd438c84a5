"""Self-contained HTML report of a design check (paper Sect. 9): figures inlined as base64
PNG, no external resources, so it opens offline and can be archived with the project."""

from __future__ import annotations

import base64
import datetime as _dt
import hashlib
import html
import io
from pathlib import Path

import numpy as np
import xarray as xr

from rockarch import __version__
from rockarch.design import DesignResult

ASSUMPTIONS = [
    "The arch is replaced by a catenary arch carrying its own mass distribution (paper "
    "Sect. 4 and 8). The lower-bound thickness (the thickest such catenary inside the "
    "contour) is conservative; the equivalent thickness (same ap,min as the arch) is the "
    "paper's Sect. 9 choice and its safety rests on the other assumptions below.",
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


def _png(fig) -> str:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def arch_figure(result: DesignResult):
    """The arch, both replacement catenaries, the chosen one's thrust line and hinges."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.2))
    sig = np.linspace(0.0, 1.0, 1201)
    ip, ep = result.arch.joints_at(sig)
    outline = np.concatenate([ip, ep[::-1], ip[:1]])
    ax.fill(outline[:, 0], outline[:, 1], color="0.88", label="arch")
    ax.plot(outline[:, 0], outline[:, 1], color="0.45", lw=0.8)
    for rep, style in ((result.replacement.lower_bound, ":"),
                       (result.replacement.equivalent, "--")):
        ri, re_ = rep.arch.joints_at(sig)
        lw = 1.6 if rep.rule == result.rule else 0.9
        lab = f"replacement ({rep.rule}), d = {rep.thickness:.3f} m, f = {rep.rise:.3f} m"
        ax.plot(ri[:, 0], ri[:, 1], "b" + style, lw=lw, label=lab)
        ax.plot(re_[:, 0], re_[:, 1], "b" + style, lw=lw)
    chosen = result.chosen.mechanism
    th = chosen.thrust.thrust
    ax.plot(th[:, 0], th[:, 1], color="tab:red", lw=1.1,
            label=f"thrust line at collapse, ap,min = {chosen.ap_min:.3f} m/s²")
    for h in chosen.hinges:
        ax.plot(h.x, h.y, "o", ms=6, mfc="white" if h.side == "intrados" else "k", mec="k")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
    return fig


def site_figure(result: DesignResult, site_ds: xr.Dataset):
    """Every record's OAS boundary, the envelope, the characteristic curve, the arch's point."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.4))
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
    ax.set_ylabel(r"lowest overturning $a_p/a_{p,\min}$")
    ax.set_ylim(1.0, float(site_ds["ratio"].values[-1]))
    ax.legend(fontsize=8)
    ax.set_title(f"site OAS, slender block alpha = {site_ds.attrs.get('alpha', 0):g}",
                 fontsize=9)
    return fig


def _table(rows: list[tuple[str, str]]) -> str:
    return "<table>" + "".join(f"<tr><th>{html.escape(a)}</th><td>{html.escape(b)}</td></tr>"
                               for a, b in rows) + "</table>"


def write_report(result: DesignResult, site_ds: xr.Dataset, path, *, command: str,
                 inputs: dict, site_path: str | None = None, extra_html: str = "") -> Path:
    """Write the HTML report atomically; ``command`` reruns the check, ``inputs`` lists the
    arch's parameters; ``extra_html`` (e.g. the fragility of a suite) follows the site OAS."""
    path = Path(path)
    if not path.resolve().parent.is_dir():
        raise ValueError(f"{path.parent}: directory does not exist")
    c = result.chosen
    rep = result.replacement
    g = result.g
    lower = " (at least: no record overturns within the computed range)" \
        if result.ratio_is_lower_bound else ""
    site_hash = ""
    if site_path and Path(site_path).exists():
        site_hash = hashlib.sha256(Path(site_path).read_bytes()).hexdigest()
    rec_rows = "".join(
        f"<tr><td>{html.escape(str(n))}</td><td>{pga / 9.80665:.4f}</td>"
        f"<td><code>{html.escape(str(h))}</code></td></tr>"
        for n, pga, h in zip(site_ds["record_name"].values, site_ds["record_pga"].values,
                             site_ds["record_sha256"].values, strict=True))
    repl_rows = "".join(
        f"<tr><td>{r.rule}</td><td>{r.thickness:.4f}</td><td>{r.thickness / r.arch.span:.5f}"
        f"</td><td>{r.rise:.4f}</td><td>{r.p:.4f}</td><td>{r.ap_min:.4f}</td>"
        f"<td>{r.mechanism.c1:.4f}</td><td>{r.mechanism.c2:.4f}</td>"
        f"<td>{r.R_block:.4f}</td></tr>" for r in (rep.lower_bound, rep.equivalent))
    body = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>rockarch design check</title>
<style>
body {{ font-family: sans-serif; max-width: 60em; margin: 2em auto; color: #222; }}
table {{ border-collapse: collapse; margin: 0.6em 0; }}
th, td {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }}
.result {{ font-size: 1.25em; background: #eef5ee; padding: 0.8em; border: 1px solid #9c9; }}
code {{ font-size: 0.85em; }}
</style></head><body>
<h1>Overturning design check of a masonry arch</h1>
<p>rockarch {__version__}, {_dt.datetime.now().strftime('%Y-%m-%d %H:%M')}.
Method: paper Sect. 9 (replacement catenary arch, slender-block OAS of the site).</p>
<div class="result">Largest safe peak ground acceleration:
<b>{result.pga_safe:.3f} m/s² = {result.pga_safe / g:.3f} g</b><br>
ap/ap,min = {result.ratio:.4f}{lower} read on the site's {result.curve} at
p = {c.p:.4f} 1/s; ap,min = {c.ap_min:.4f} m/s² ({result.rule} thickness).
Below this PGA the arch may move but does not collapse.</div>
<h2>Arch and replacement catenary arch</h2>
<img alt="arch" src="data:image/png;base64,{_png(arch_figure(result))}">
<p>Original arch: critical optimal four-hinge mechanism ap,min = {rep.original.ap_min:.4f} m/s²
(lambda = {rep.original.lambda_:.5f}), p = {rep.original.p:.4f} 1/s,
delta = {rep.original.delta:.5f} rad.</p>
<table><tr><th>replacement</th><th>d [m]</th><th>d/l</th><th>f [m]</th><th>p [1/s]</th>
<th>ap,min [m/s²]</th><th>c1</th><th>c2</th><th>block R [m]</th></tr>{repl_rows}</table>
<h2>Site OAS</h2>
<img alt="site OAS" src="data:image/png;base64,{_png(site_figure(result, site_ds))}">
<table><tr><th>record</th><th>PGA [g]</th><th>SHA-256 of the file</th></tr>{rec_rows}</table>
{extra_html}
<h2>Chain of conservative assumptions</h2>
<ol>{''.join(f'<li>{html.escape(a)}</li>' for a in ASSUMPTIONS)}</ol>
<h2>Inputs (to rerun)</h2>
<p><code>{html.escape(command)}</code></p>
{_table([(k, str(v)) for k, v in inputs.items()] + [
        ("thickness rule", result.rule), ("site curve", result.curve), ("g [m/s²]", f"{g:g}"),
        ("site file", str(site_path or "")), ("site file SHA-256", site_hash),
        ("site block alpha", f"{site_ds.attrs.get('alpha')}"),
        ("site percentile", f"{site_ds.attrs.get('percentile')}"),
        ("site p range [1/s]", f"{site_ds['p'].values[0]:g}…{site_ds['p'].values[-1]:g}"),
        ("site ratio range", f"{site_ds['ratio'].values[0]:g}…"
                             f"{site_ds['ratio'].values[-1]:g}"),
        ("site built with rockarch", str(site_ds.attrs.get("rockarch_version")))])}
</body></html>
"""
    tmp = path.with_name(f".{path.name}.part")
    try:
        tmp.write_text(body, encoding="utf-8")
        tmp.replace(path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path
