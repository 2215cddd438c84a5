"""Site OAS and design of any system kind (docs/theory.md §11.4): the IDA collapse points of
an assembly are its OAS boundary × ap,min, the safe PGA is the envelope (or percentile) of
them (Eq. (11.34)), a slender block's site file gives the equivalent-SDOF reading
(Eq. (11.35)) and is refused for a mechanism that slides; the CLI is one line per error."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

import rockarch as ra
from rockarch.cli import app
from rockarch.core.constants import G
from rockarch.motion.suite import write_at2
from rockarch.spectra import site

runner = CliRunner()
#: A coarse IDA scan (the equalities below are exact whatever the grid; coarse for speed).
RATIO = np.round(np.linspace(1.0, 5.0, 9), 12)
TOL = 0.05
COLUMN = [(0.3, 1.0), (0.25, 0.8)]


@pytest.fixture(scope="module")
def clips():
    """The strong first 12 s of the two bundled El Centro components."""
    out = []
    for c in (180, 270):
        m = ra.el_centro(c)
        out.append(ra.GroundMotion(m.t[:1200], m.a[:1200], name=f"ELC{c}-12s"))
    return out


@pytest.fixture(scope="module")
def folder(tmp_path_factory, clips):
    d = tmp_path_factory.mktemp("clips")
    for m in clips:
        write_at2(d / f"{m.name}.AT2", m)
    return d


@pytest.fixture(scope="module")
def block_site(clips):
    """A slender block's site OAS (the paper's) around p = 2 … 4."""
    return site.site_oas(clips, np.linspace(2.0, 4.0, 5), np.linspace(1.0, 5.0, 41),
                         progress=False)


def test_ida_points_are_the_oas_boundary_times_ap_min(clips):
    sys_ = ra.system("mdof", column=COLUMN, friction=0.5)
    # without the search below the grid's first collapse (Eq. (11.30a)), which an OAS
    # does not run
    d = ra.design_system(sys_, records=clips, ratio=RATIO, tol=TOL, n_bootstrap=0,
                         search_step=0)
    assert d.method == "records" and d.p == sys_.p_ref and d.ap_min == sys_.ap_min
    x = d.fragility.ida.im_collapse
    assert np.all(np.isfinite(x)), "both records collapse the column within the scan"
    for k, m in enumerate(clips):
        oas = ra.oas(sys_, m, p=[d.p], ratio=RATIO, tol=TOL)
        # the same scan and bisection code (Eq. (11.30)): equal bit for bit
        assert x[k] == oas["boundary"].values[0] * sys_.ap_min
    # Eq. (11.34), envelope: the lowest collapse; and it is the site OAS of the structure
    # at its own p (the same runs, so exactly equal)
    assert d.pga_safe == x.min() and not d.ratio_is_lower_bound
    ds = site.site_oas(clips, [d.p], RATIO, system=sys_, tol=TOL, progress=False)
    assert ds["envelope"].values[0] == d.ratio
    assert ds.attrs["system"] == sys_.name and "alpha" not in ds.attrs
    with pytest.raises(ValueError, match="not of a slender block"):
        site.check_block_site(ds)


def test_percentile_curve_of_the_records(clips):
    """Two records, 'lower' percentiles: 0 and 50 give the smaller collapse, 100 the
    larger (the site-curve rule of site.curves)."""
    sys_ = ra.system("block", alpha=0.1, p=2.0)
    pts = {}
    for q in (0.0, 50.0, 100.0):
        d = ra.design_system(sys_, records=clips, curve="characteristic", percentile=q,
                             n_bootstrap=0)
        pts[q] = d.pga_safe
        x = d.fragility.ida.im_collapse
    assert pts[0.0] == pts[50.0] == x.min() and pts[100.0] == x.max() > x.min()


@pytest.mark.parametrize("mu", [0.2, 0.3, 0.6, 1.0])
def test_one_block_with_friction_closed_form(mu, block_site):
    """One block 0.4 × 1.0 m on the ground: ap,min = min(mu, B/H)·g (docs/theory.md
    §10); 1e-7: the LP solver's feasibility tolerance. Below B/H it slides, and a block's
    site OAS is refused; above, the site curve is read at Housner's p."""
    sys_ = ra.system("mdof", column=[(0.4, 1.0)], friction=mu)
    assert sys_.ap_min == pytest.approx(min(mu, 0.4) * G, rel=1e-7)
    r = math.hypot(0.2, 0.5)
    assert sys_.p_ref == pytest.approx(math.sqrt(3 * G / (4 * r)), rel=1e-12)  # Eq. (1.2)
    if mu < 0.4:
        with pytest.raises(ValueError, match="slides"):
            ra.design_system(sys_, site=block_site)
        return
    d = ra.design_system(sys_, site=block_site)
    assert not d.sliding and d.method == "equivalent-sdof"
    ratio, lower = site.curve_at(block_site, sys_.p_ref, "envelope")
    assert (d.ratio, d.ratio_is_lower_bound) == (ratio, lower)
    assert d.pga_safe == ratio * sys_.ap_min


def test_a_sliding_block_never_collapses(clips):
    """mu = 0.2 < B/H: the block slides at 0.2 g and does not overturn within 5 × that; the
    records are censored, the safe PGA is the scan's top (a lower bound), no lognormal."""
    sys_ = ra.system("mdof", column=[(0.4, 1.0)], friction=0.2)
    d = ra.design_system(sys_, records=clips, ratio=RATIO, tol=TOL, n_bootstrap=0)
    assert d.sliding and d.ratio_is_lower_bound and d.ratio == RATIO[-1]
    assert d.fragility.fit is None and "fragility needs" in d.note
    assert d.to_dict()["fragility"] is None


def test_design_cli_says_a_lower_bound_is_one(folder):
    # the sliding block of the test above through the CLI: its site line reads ">=" (the
    # scan's top), and so does its safe PGA, beside the warning
    res = runner.invoke(app, ["design", "--system", "mdof", "--column", "0.4,1.0",
                              "--friction", "0.2", "--records", str(folder), "--ratio-steps",
                              "9", "--tol", "0.05", "--bootstrap", "0", "--no-store"])
    assert res.exit_code == 0, res.output
    line = [x for x in res.stdout.splitlines() if x.startswith("site envelope")]
    assert len(line) == 1 and "ap/ap,min >= 5.0000 -> safe PGA >= " in line[0]
    assert "the safe PGA is a lower bound" in res.stderr


def test_design_text_of_a_safe_pga_that_is_read_on_the_curve(block_site, capsys):
    from rockarch.cli.site import _print_system_design

    d = ra.design_system(ra.system("block", alpha=0.1, p=2.0), site=block_site)
    assert not d.ratio_is_lower_bound
    _print_system_design(d)
    line = [x for x in capsys.readouterr().out.splitlines() if x.startswith("site envelope")]
    # which g it divides by (the structure's; records and hazard curves in g are in standard
    # gravity, 9.80665 m/s², and say so)
    assert line == [f"site envelope (equivalent SDOF on the block site OAS): ap/ap,min = "
                    f"{d.ratio:.4f} -> safe PGA {d.pga_safe:.3f} m/s² = "
                    f"{d.pga_safe / G:.3f} g (g = 9.81 m/s²)"]


def test_block_design_with_a_site_file(block_site):
    d = ra.design_system(ra.system("block", alpha=0.1, p=2.0), site=block_site)
    ratio, _ = site.curve_at(block_site, 2.0, "envelope")
    assert d.ratio == ratio
    # ap,min = g·tan(alpha) (Eq. (1.3)); 1e-15: the order of the two roundings
    assert d.pga_safe == pytest.approx(ratio * G * math.tan(0.1), rel=1e-15)
    with pytest.raises(ValueError, match="give its frequency parameter"):
        ra.design_system(ra.system("block", alpha=0.1), site=block_site)


def test_site_oas_cli_any_system(folder, tmp_path, block_site):
    out = tmp_path / "col.nc"
    res = runner.invoke(app, ["site-oas", "--system", "mdof", "--column", "0.3,1.0;0.25,0.8",
                              "--friction", "0.5", "--records", str(folder), "--p-min", "2",
                              "--p-max", "4", "--p-steps", "3", "--ratio-steps", "9",
                              "--tol", "0.05", "--no-store", "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    sys_ = ra.system("mdof", column=COLUMN, friction=0.5)
    assert js["system"] == sys_.name and js["p_structure"] == sys_.p_ref
    ds = site.load(out)
    assert "p ~ 1/sqrt(size)" in ds.attrs["p_axis"]
    b = np.where(np.isfinite(ds["boundary"].values), ds["boundary"].values, np.inf)
    assert np.array_equal(np.where(np.isfinite(ds["envelope"].values),
                                   ds["envelope"].values, np.inf), b.min(axis=0))
    # the paper's design reads a block's site OAS only
    bad = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise",
                              "2.89", "--thickness", "0.35", "--site", str(out)])
    assert bad.exit_code == 2 and "not of a slender block" in bad.stderr


def test_design_cli_records_any_system(folder, tmp_path):
    args = ["design", "--system", "mdof", "--column", "0.3,1.0;0.25,0.8", "--friction",
            "0.5", "--records", str(folder), "--ratio-steps", "9", "--tol", "0.05",
            "--bootstrap", "20", "--no-store"]
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["method"] == "records" and out["sliding"] is False
    pts = [q["im_collapse"] for q in out["points"]]
    assert out["pga_safe"] == min(pts)
    # two records, no censoring: the MLE is the closed form (mean and std of ln x)
    assert out["fragility"]["median"] == pytest.approx(math.exp(np.log(pts).mean()),
                                                       rel=1e-12)
    rep = tmp_path / "r.html"
    text = runner.invoke(app, [*args, "--report", str(rep)])
    assert text.exit_code == 0 and "safe PGA" in text.stdout and "ELC180-12s" in text.stdout
    html = rep.read_text()
    # self-contained (spectra and fragility inlined), with the command that reruns it
    assert not re.search(r'(src|href)\s*=\s*"(https?:|//)', html)
    assert html.count('src="data:image/png;base64,') == 2
    assert "rockarch design --column" in html and "--system mdof" in html
    assert "--friction 0.5" in html
    assert f"{out['pga_safe']:.3f} m/s²" in html and "SHA-256" in html
    # ap,min of an assembly as computed: the non-associative iteration and the macro-block
    # search (docs/theory.md §10); the associative LP alone is friction="associative" (the
    # report said ap,min was that LP, Eq. (10.4), and could be too high)
    assert "with associative Coulomb friction" not in html
    assert "non-associative Coulomb friction, docs/theory.md Eqs. (10.4)–(10.9)" in html


def test_design_cli_search_step(folder):
    # --search-step reaches the IDA (stated in the scan line and the JSON); the search only
    # adds collapses below the grid's, so the safe PGA never rises with it
    args = ["design", "--system", "block", "--alpha", "0.2", "--p", "2", "--records",
            str(folder), "--no-store", "--bootstrap", "0", "--json"]
    outs = {}
    for step in ("0", "0.01"):
        res = runner.invoke(app, [*args, "--search-step", step])
        assert res.exit_code == 0, res.output
        outs[step] = json.loads(res.stdout)
        assert outs[step]["scan"]["search_step"] == float(step)
    assert outs["0.01"]["pga_safe"] <= outs["0"]["pga_safe"]
    res = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise",
                              "2.89", "--thickness", "0.35", "--records", str(folder),
                              "--search-step", "0.01"])
    assert res.exit_code == 2 and "--search-step goes with --system" in res.output


def test_design_cli_fourhinge_with_a_site_file(block_site, tmp_path):
    """The arch's own four-hinge mechanism as the equivalent SDOF (no replacement)."""
    f = tmp_path / "site.nc"
    site.save(block_site, f)
    arch = ["--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness", "0.35"]
    res = runner.invoke(app, ["design", "--system", "fourhinge", *arch, "--site", str(f),
                              "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    sys_ = ra.system("fourhinge", shape="circular", span=10, rise=2.89, thickness=0.35)
    ratio, _ = site.curve_at(block_site, sys_.p_ref, "envelope")
    assert (out["p"], out["ap_min"], out["ratio"]) == (sys_.p_ref, sys_.ap_min, ratio)


@pytest.mark.parametrize("structure", [
    ["--system", "mdof", "--column", "0.4,1.0", "--friction", "0.6"],
    ["--system", "fourhinge", "--shape", "circular", "--span", "10", "--rise", "2.89",
     "--thickness", "0.35"],
    ["--system", "block", "--alpha", "0.1", "--p", "3"],
])
def test_design_cli_any_system_with_a_site_file_says_islands_are_not_searched(
        block_site, tmp_path, structure):
    """A site file holds each record's first collapse on its grid, whatever reads it: the
    --system routes say so as the arch's does (a note on stderr, JSON caveats, the
    report)."""
    f = tmp_path / "site.nc"
    site.save(block_site, f)
    rep = tmp_path / "r.html"
    res = runner.invoke(app, ["design", *structure, "--site", str(f), "--json", "--report",
                              str(rep)])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["method"] == "equivalent-sdof"
    assert len(out["caveats"]) == 1
    assert out["caveats"][0].startswith("a site file holds each record's first collapse on "
                                        "its ratio grid; collapse islands narrower than")
    assert res.stderr.startswith("note: a site file holds each record's first collapse")
    assert "holds within these caveats" in rep.read_text()


@pytest.mark.parametrize("structure, named", [
    (["--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness", "0.35"],
     "the design of the circular arch l = 10 m, f = 2.89 m, d = 0.35 m reads"),
    (["--system", "mdof", "--column", "0.4,1.0", "--friction", "0.6"],
     "the design of the block reads"),
])
def test_design_on_another_structures_site_file_names_the_right_one(block_site, tmp_path,
                                                                    structure, named):
    """A site file of a trilithon (site-oas --system mdof --colonnade 2 ..., its attrs; the
    file's grid is the block's here, for speed) read by the design of another structure:
    the one line names the file's structure and the one designed, and asks for a block's
    site file or --records for the latter (it said 'for this structure give --records'
    right after naming the trilithon)."""
    tri = "trilithon: 2 columns 0.3x2 m, spacing 1 m, lintel 0.4 m"
    ds = block_site.copy()
    ds.attrs = {**ds.attrs, "system": tri}
    f = tmp_path / "tri_site.nc"
    site.save(ds, f)
    res = runner.invoke(app, ["design", *structure, "--site", str(f)])
    assert res.exit_code == 2, res.output
    err = res.stderr
    assert err.startswith(f"error: {f}: this is the site OAS of {tri}, not of a slender "
                          "block") and err.count("\n") == 1, err
    assert named in err and err.rstrip().endswith(
        "reads a block's site OAS (rockarch site-oas without --system): give one, or "
        "--records"), err
    assert "this structure" not in err


def test_design_records_units(clips, tmp_path):
    # two-column records in cm/s² read with --units cm/s2 give the design of the same
    # records in m/s² (a rigid block: the Housner kernel, fast); without --units they are
    # taken as m/s²: the IDA scales every record, so the design is the same, but the
    # implausible PGA (wrong units?) is a warning on stderr
    for unit, f in (("m", 1.0), ("cm", 100.0)):
        d = tmp_path / unit
        d.mkdir()
        for m in clips:
            np.savetxt(d / f"{m.name}.txt", np.column_stack([m.t, f * m.a]))
    base = ["design", "--system", "block", "--alpha", "0.2", "--p", "2", "--ratio-steps", "9",
            "--tol", "0.05", "--bootstrap", "0", "--no-store", "--json", "--records"]
    ref = runner.invoke(app, [*base, str(tmp_path / "m")])
    cm = runner.invoke(app, [*base, str(tmp_path / "cm"), "--units", "cm/s2"])
    assert ref.exit_code == 0 and cm.exit_code == 0, ref.output + cm.output
    # the same records to the last bit of the unit conversion (×0.01 of a ×100 value)
    assert json.loads(cm.stdout)["pga_safe"] == pytest.approx(
        json.loads(ref.stdout)["pga_safe"], rel=1e-12)
    bad = runner.invoke(app, [*base, str(tmp_path / "cm")])
    assert bad.exit_code == 0 and "not plausible: wrong units?" in bad.stderr
    assert "warning" not in cm.stderr


def test_report_command_writes_flags_as_flags():
    # the report's rerun command printed "--no-store True", which the command line refuses
    from rockarch.cli.site import _command_line

    cmd = _command_line({"no_store": True, "system": "mdof", "column": "0.4,1.0"})
    assert "--no-store" in cmd.split() and "True" not in cmd.split()


def test_system_report_names_a_record_without_a_file_by_its_samples(clips):
    """A record built in Python has no file: the report gives its samples' SHA-256 (as a
    site file does, site.record_sha256), not an empty cell."""
    from rockarch.motion.suite import Suite, SuiteRecord
    from rockarch.output.report import system_report_html

    sys_ = ra.system("block", alpha=0.1, p=2.0)
    d = ra.design_system(sys_, records=clips, ratio=RATIO, tol=TOL, n_bootstrap=0)
    suite = Suite(tuple(SuiteRecord(m.name, m) for m in clips))
    html = system_report_html(d, command="rockarch design ...", suite=suite)
    for m in clips:
        assert m.fingerprint() in html
