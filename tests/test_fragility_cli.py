"""`rockarch fragility` (issue contract): JSON keys, pga in m/s², points named by file,
collapse points equal to `rockarch oas` boundaries × ap,min; bad input exits 2."""

import json
import re
import shutil

import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.motion.records import bundled_record_path

runner = CliRunner()


@pytest.fixture(scope="module")
def full(tmp_path_factory):
    """The two bundled El Centro components, whole (54 s each)."""
    d = tmp_path_factory.mktemp("suite")
    for c in (180, 270):
        shutil.copy(bundled_record_path(c), d)
    return d


@pytest.fixture(scope="module")
def folder(short_records):
    """The first 12 s of both El Centro components (tests/conftest.py)."""
    return short_records


@pytest.mark.slow
def test_contract_full_records(full, tmp_path):
    _check_contract(full, tmp_path)


def test_contract(folder, tmp_path):
    _check_contract(folder, tmp_path)


def _check_contract(folder, tmp_path):
    png = tmp_path / "f.png"
    res = runner.invoke(app, ["fragility", "--system", "block", "--alpha", "0.1", "--p", "2",
                              "--records", str(folder), "--im", "pga", "--no-store",
                              "--json", "--bootstrap", "50", "--plot", str(png),
                              "--search-step", "0"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["im"] == "pga" and out["search_step"] == 0
    # the block's default scan, as `rockarch oas` (below)
    assert out["scan"] == {"ratio_min": 1.0, "ratio_max": 5.0, "values": 81, "tol": 0.001}
    names = [q["record"] for q in out["points"]]
    assert names == sorted(p.name for p in folder.iterdir())
    assert png.stat().st_size > 1000
    # without the search, each collapse point is the `rockarch oas` boundary at p = 2
    # times ap,min (m/s²)
    rec = folder / names[0]
    oas = runner.invoke(app, ["oas", "--system", "block", "--alpha", "0.1", "--p", "2",
                              "--record", str(rec), "--no-store", "--json"])
    assert oas.exit_code == 0, oas.output
    boundary = json.loads(oas.stdout)["boundary"][0]
    assert out["points"][0]["im_collapse"] == boundary * out["ap_min"]
    assert all(q["resurrections"] >= 0 and not q["censored"] for q in out["points"])
    # two records: the MLE is the closed form (mean and std of ln x)
    import numpy as np

    lx = np.log([q["im_collapse"] for q in out["points"]])
    assert out["median"] == pytest.approx(np.exp(lx.mean()), rel=1e-12)
    assert out["beta"] == pytest.approx(lx.std(), rel=1e-12)
    # two records: every resample that can be fitted is the pair itself, no band
    assert out["ci"] == {}


def test_im_range_help_says_which_g():
    # --im-range is in g of the records (standard gravity), as the figure's top axis
    res = runner.invoke(app, ["fragility", "--help"])
    assert "LO,HI in g (pga, sa; g = 9.80665 m/s²)" in " ".join(res.stdout.split())


@pytest.mark.parametrize("extra, msg", [
    (["--im", "sa"], "--im sa needs --period"),
    (["--im", "pgd"], "'pgd' is not one of 'pga', 'pgv', 'sa', 'pga_norm', 'pgv_norm', "
                      "'all'"),
    (["--search-step", "-1"], "search step must be a finite number >= 0"),
    (["--im", "all", "--plot", "x.png"], "--im all prints a table of every IM"),
    (["--im-range", "5,1"], "--im-range must be two numbers"),
    (["--ratio-steps", "1"], "--ratio-steps must be >= 2"),
    (["--island-step", "0"], "island step must be an integer >= 1"),
    (["--level", "95"], "--level must lie in (0, 1)"),
    (["--ratio-max", "0.5"], "--ratio-max must be > 1"),
    (["--p", "0"], "p must be a finite number > 0"),
    (["--p", "nan"], "p must be a finite number > 0"),
    (["--alpha", "-1"], "alpha"),
    (["--im", "sa", "--period", "-1"], "--period must be a finite number > 0"),
    (["--im-range", "0.1,x"], "--im-range"),
    (["--bootstrap", "-1"], "--bootstrap must lie in [0, 10000]"),
    (["--records", "/nonexistent/folder"], "no such file or folder"),
    (["--system", "sdof", "--delta", "0.1"], "--alpha does not apply to --system sdof"),
])
def test_bad_input_is_one_line(folder, extra, msg):
    res = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(folder), "--no-store", *extra])
    assert res.exit_code == 2
    assert res.stderr.startswith("error: ") and msg in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1


def test_too_few_collapses_prints_the_points_and_no_fit(folder):
    res = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(folder), "--no-store", "--ratio-max", "1.1",
                              "--ratio-steps", "2", "--t-free", "1", "--json"])
    assert res.exit_code == 0, res.output
    # off a terminal, "progress: ..." lines tell the stages (the structure, the scan, each
    # record done), then the result's warning
    lines = res.stderr.splitlines()
    assert [x for x in lines if x.startswith("progress: ")] == lines[:4]
    assert lines[4].startswith("warning: only 0 of 2 records collapse up to ap/ap,min = 1.1")
    out = json.loads(res.stdout)
    assert out["median"] is None and out["beta"] is None and out["n_censored"] == 2
    assert all(q["censored"] and q["im_collapse"] is None for q in out["points"])


def test_empty_folder(tmp_path):
    res = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(tmp_path), "--no-store"])
    assert res.exit_code == 2 and "holds no record" in res.stderr


@pytest.mark.slow
def test_design_with_records(tmp_path):
    import numpy as np

    import rockarch as ra

    for c in (180, 270):  # the first 10 s of El Centro as two-column files
        m = ra.el_centro(c)
        np.savetxt(tmp_path / f"elc{c}.txt", np.c_[m.t[:1000], m.a[:1000]])
    res = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise", "5",
                              "--thickness", "1", "--records", str(tmp_path), "--pga", "3",
                              "--curve", "simplified", "--json", "--report",
                              str(tmp_path / "r.html"), "--save-site",
                              str(tmp_path / "site.nc"), "--store", str(tmp_path / "store")])
    assert res.exit_code == 0, res.output
    # the sweep options of oas: the site OAS's chunks went to the store given
    assert any((tmp_path / "store").rglob("*")), "no chunk in --store"
    out = json.loads(res.stdout)
    f = out["fragility"]
    assert f["n_records"] == 2
    assert 0 <= f["probability_at_pga"]["probability"] <= 1
    assert f["pga_at_probability"]["probability"] == 0.1
    assert f["pga_at_probability"]["pga"] < f["median"]  # the 10 % quantile
    assert out["pga_safe"] == pytest.approx(out["ratio"] * out["replacement"]["ap_min"])
    from rockarch.spectra import site

    saved = site.load(tmp_path / "site.nc")
    assert saved.sizes["record"] == 2 and "simplified" in saved
    page = (tmp_path / "r.html").read_text()
    assert "Fragility of the replacement" in page and "--records" in page
    assert "Response spectra of the records" in page


def test_design_needs_site_or_records(folder):
    res = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise", "5",
                              "--thickness", "1"])
    assert res.exit_code == 2 and "give either --site FILE or --records DIR" in res.stderr


@pytest.mark.slow
def test_mdof_structure_options(folder):
    res = runner.invoke(app, ["fragility", "--system", "mdof", "--column", "0.4,2;0.4,2",
                              "--p", "2", "--records", str(folder), "--no-store",
                              "--ratio-max", "4", "--ratio-steps", "4", "--tol", "0.2",
                              "--t-free", "2", "--bootstrap", "0", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert len(out["points"]) == 2
    # given in metres and analysed at --p 2: the label and the JSON say it was scaled
    from rockarch import systems
    own = systems.system("mdof", column=[(0.4, 2.0), (0.4, 2.0)]).p_ref
    assert out["scale"] == pytest.approx((own / 2) ** 2, rel=1e-12)
    assert out["p_structure"] == pytest.approx(own, rel=1e-12)
    assert out["system"].startswith("2-block column scaled ×")


def test_mdof_structure_scaled_to_p_says_so(folder):
    """A wall of 0.4 m blocks has p = 7.21 1/s; at --p 2 its blocks are 13 times as large:
    the label and the JSON say so (they named the wall as given at p = 2)."""
    from rockarch import systems
    own = systems.system("mdof", wall="2,2", block="0.4,0.2").p_ref
    base = ["fragility", "--system", "mdof", "--wall", "2,2", "--block", "0.4,0.2",
            "--records", str(folder), "--no-store", "--ratio-steps", "2", "--ratio-max",
            "1.5", "--tol", "0.5", "--bootstrap", "0"]
    res = runner.invoke(app, [*base, "--p", "2"])
    assert res.exit_code == 0, res.output
    k = (own / 2) ** 2
    assert (f"fragility of wall 2x2 blocks 0.4x0.2 m scaled ×{k:.4g} (size ∝ 1/p², as "
            f"given p = {own:.4g} 1/s) at p = 2 1/s") in res.stdout, res.stdout
    out = json.loads(runner.invoke(app, [*base, "--p", "2", "--json"]).stdout)
    assert out["p"] == 2 and out["scale"] == pytest.approx(k, rel=1e-12)
    assert out["p_structure"] == pytest.approx(own, rel=1e-12)
    # at its own p (no --p) nothing is scaled: no scale in the JSON
    own_out = json.loads(runner.invoke(app, [*base, "--json"]).stdout)
    assert own_out["system"] == "wall 2x2 blocks 0.4x0.2 m" and "scale" not in own_out


def test_im_all_reports_the_dispersion_of_every_im_on_one_ida(folder):
    res = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(folder), "--no-store", "--im", "all", "--json",
                              "--bootstrap", "0"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    rows = {r["im"]: r for r in out["ims"]}
    assert list(rows) == ["pga", "pgv", "sa", "pga_norm", "pgv_norm"]
    import math

    assert rows["sa"]["period"] == pytest.approx(2 * math.pi / 2)
    # the dimensionless IMs are PGA and PGV times constants on one structure: the same
    # beta (the MLE is scale-equivariant) and medians scaled by g tan(alpha), p/(g tan alpha)
    ap_min = out["ap_min"]
    assert rows["pga_norm"]["beta"] == pytest.approx(rows["pga"]["beta"], rel=1e-9)
    assert rows["pga_norm"]["median"] == pytest.approx(rows["pga"]["median"] / ap_min)
    assert rows["pgv_norm"]["median"] == pytest.approx(rows["pgv"]["median"] * 2 / ap_min)
    # the same IDA as `--im pga`, and `--im pgv` gives the same fit as the pgv row
    one = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(folder), "--no-store", "--im", "pgv", "--json",
                              "--bootstrap", "0"])
    pgv = json.loads(one.stdout)
    assert pgv["median"] == pytest.approx(rows["pgv"]["median"], rel=1e-12)
    assert pgv["beta"] == pytest.approx(rows["pgv"]["beta"], rel=1e-12)
    text = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                               str(folder), "--no-store", "--im", "all", "--bootstrap", "0"])
    assert "Sa(T = 3.14 s)" in text.stdout and "lowest beta:" in text.stdout
    # printed units are m/s² as every other output (the JSON keeps "units": "m/s2")
    assert "m/s²" in text.stdout and "m/s2" not in text.stdout, text.stdout
    assert rows["pga"]["units"] == "m/s2"


def test_text_prints_units_as_m_per_s_squared(folder):
    res = runner.invoke(app, ["fragility", "--alpha", "0.1", "--p", "2", "--records",
                              str(folder), "--no-store", "--bootstrap", "0"])
    assert res.exit_code == 0, res.output
    assert "(IM = pga [m/s²])" in res.stdout and "m/s2" not in res.stdout, res.stdout
    assert re.search(r"^lognormal .*: median [0-9.]+ m/s², beta", res.stdout, re.M), res.stdout


def test_mdof_structure_of_real_size_needs_no_p(folder):
    """A wall given in metres has its own p (as in `design --system mdof`); a block of alpha
    alone and an arch of f/l, d/l have no size and still need --p."""
    base = ["fragility", "--system", "mdof", "--records", str(folder), "--no-store",
            "--ratio-steps", "2", "--ratio-max", "1.5", "--tol", "0.5", "--bootstrap", "0",
            "--json"]
    res = runner.invoke(app, [*base, "--column", "0.4,1.0", "--friction", "0.6"])
    assert res.exit_code == 0, res.output
    from rockarch import systems
    own = systems.system("mdof", column=[(0.4, 1.0)], friction=0.6).p_ref
    assert json.loads(res.stdout)["p"] == pytest.approx(own, rel=1e-12)  # the same structure
    res = runner.invoke(app, [*base, "--shape", "catenary", "--rise-over-span", "0.3",
                              "--thickness-over-span", "0.03", "--blocks", "8"])
    assert res.exit_code == 2 and "--p" in res.stderr
    res = runner.invoke(app, [*base[:2], "block", *base[3:], "--alpha", "0.1"])
    assert res.exit_code == 2 and "--p" in res.stderr
