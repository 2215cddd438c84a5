"""`rockarch risk` and `rockarch design --hazard` (docs/sites.md, "Risk"): the JSON
contract, the two hazard formats, the fragility from a file or inline, the plot, and bad
input as one line with exit status 2."""

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.risk import hazard as hz

runner = CliRunner()
DATA = Path(hz.__file__).parent / "data"
TWO_COLUMN = str(DATA / "illustrative_hazard_PGA.csv")
OPENQUAKE = str(DATA / "hazard_curve-mean-PGA.csv")


@pytest.fixture(scope="module")
def folder(short_records):
    """The first 12 s of both El Centro components (tests/conftest.py)."""
    return short_records


@pytest.fixture()
def frag_json(tmp_path):
    f = tmp_path / "frag.json"
    f.write_text(json.dumps({"im": "pga", "units": "m/s2", "median": 2.0, "beta": 0.35}))
    return f


def _json(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 0, (res.stdout, res.stderr)
    return json.loads(res.stdout)


def test_risk_json_contract_and_both_formats_agree(frag_json, tmp_path):
    png = tmp_path / "risk.png"
    a = _json(["risk", "--hazard", TWO_COLUMN, "--fragility", str(frag_json), "--json",
               "--plot", str(png)])
    b = _json(["risk", "--hazard", OPENQUAKE, "--fragility", str(frag_json), "--json",
               "--years", "50"])
    assert png.stat().st_size > 10_000
    assert {"annual_rate", "probability", "years", "deaggregation", "lower_bound",
            "extrapolated_share", "hazard", "fragility"} <= set(a)
    # the OpenQuake file holds the same curve as poe in 50 years written to 7 digits
    assert b["annual_rate"] == pytest.approx(a["annual_rate"], rel=1e-5)
    assert a["years"] == 50 and a["probability"] == pytest.approx(
        1 - math.exp(-50 * a["annual_rate"]), rel=1e-12)
    d = a["deaggregation"]
    assert d["units"] == "g" and sum(x["share"] for x in d["bins"]) == pytest.approx(1.0)
    assert d["bins"][1]["im_lo"] == 0.02  # the curve's own levels, in its units
    assert b["hazard"]["investigation_time"] == 50 and a["hazard"]["investigation_time"] is None
    # the library's number (the CLI composes nothing)
    lib = hz.collapse_rate(hz.read_hazard(TWO_COLUMN), hz.read_fragility(frag_json))
    assert a["annual_rate"] == lib.annual_rate
    # N years: 1 - exp(-lambda N)
    c = _json(["risk", "--hazard", TWO_COLUMN, "--fragility", str(frag_json), "--json",
               "--years", "1"])
    assert c["probability"] == pytest.approx(-math.expm1(-a["annual_rate"]))


def test_risk_text(frag_json):
    res = runner.invoke(app, ["risk", "--hazard", TWO_COLUMN, "--fragility", str(frag_json)])
    assert res.exit_code == 0, res.stderr
    out = res.stdout
    assert "annual frequency of collapse:" in out
    assert "probability of collapse in 50 years:" in out
    assert "deaggregation by PGA [g]" in out and "half of lambda_c below" in out
    # the curve's g is standard gravity (its levels are converted with it), not the 9.81 of
    # design's "= ... g (g = 9.81 m/s²)": the first line in g says which
    assert "PGA 0.02 … 2 g (g = 9.80665 m/s²), 18 levels" in out.splitlines()[0]


def test_inline_fragility_runs_the_ida_in_the_hazards_im(folder, tmp_path):
    # one store for the three commands: the IDA (in PGA; the IM only scales it) runs once
    args = ["--system", "block", "--alpha", "0.1", "--p", "2", "--records", str(folder),
            "--store", str(tmp_path / "store")]
    inline = _json(["risk", "--hazard", TWO_COLUMN, *args, "--json"])
    frag = _json(["fragility", *args, "--json", "--bootstrap", "0", "--out",
                  str(tmp_path / "f.json")])
    assert json.loads((tmp_path / "f.json").read_text()) == frag  # --out: what --json prints
    via = _json(["risk", "--hazard", TWO_COLUMN, "--fragility", str(tmp_path / "f.json"),
                 "--json"])
    assert inline["fragility"]["median"] == frag["median"]
    assert inline["annual_rate"] == via["annual_rate"]
    # a curve in Sa(T): the inline IDA runs in Sa at the curve's period; its collapse
    # points are the PGA ones times Sa(0.5)/PGA of each record (Eq. 11.30b), and with no
    # censored record the fit is the closed form (mean and std of ln x)
    sa = tmp_path / "sa.csv"
    sa.write_text("Sa(0.5) [g],annual frequency of exceedance [1/yr]\n" + "\n".join(
        f"{x:g},{1e-4 * x ** -2.5:.6g}" for x in (0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30)))
    out = _json(["risk", "--hazard", str(sa), *args, "--json"])
    assert out["fragility"]["im"] == "sa" and out["fragility"]["period"] == 0.5
    import numpy as np

    from rockarch.motion.intensity import im_value
    from rockarch.motion.records import read_record

    x = [q["im_collapse"] * im_value(m, "sa", period=0.5) / m.pga
         for q in frag["points"] for m in [read_record(folder / q["record"])]]
    assert out["fragility"]["median"] == pytest.approx(np.exp(np.mean(np.log(x))),
                                                       rel=1e-12)


@pytest.mark.parametrize("extra, named", [
    (["--system", "mdof", "--column", "0.4,1", "--friction", "0.6"],
     "--system, --column, --friction"),
    (["--system", "block", "--alpha", "0.1"], "--system, --alpha"),
    (["--wall", "2,2", "--block", "0.4,0.2"], "--wall, --block"),
    (["--end-piers"], "--end-piers"),
    (["--ratio-steps", "9"], "--ratio-steps"),
    (["--tol", "0.5", "--search-step", "0.1"], "--tol, --search-step"),
    (["--island-step", "3", "--g", "9.8", "--t-free", "5"], "--t-free, --g, --island-step"),
    (["--units", "g", "--workers", "1", "--no-store"], "--units, --workers, --no-store"),
    # typed at their defaults: given all the same (Click's parameter source, not the value)
    (["--system", "block"], "--system"),
    (["--g", "9.81", "--t-free", "10"], "--t-free, --g"),
    (["--island-step", "1", "--abutments"], "--abutments, --island-step"),
])
def test_fragility_file_refuses_the_inline_options(frag_json, extra, named):
    # a fragility file holds its structure and scan: every option that builds one inline
    # is refused with it (they were silently ignored), named in the one line, whatever
    # its value (`--system block`, the default, passed silently before)
    res = runner.invoke(app, ["risk", "--hazard", TWO_COLUMN, "--fragility", str(frag_json),
                              *extra])
    assert res.exit_code == 2, res.stdout
    assert res.stderr.startswith("error: give the fragility: either --fragility"), res.stderr
    assert res.stderr.count("\n") == 1 and f"not both ({named} given" in res.stderr, \
        res.stderr


@pytest.mark.parametrize("extra, msg", [
    ([], "give the fragility: either --fragility FRAG.json"),
    (["--fragility", "F", "--p", "2"], "give the fragility: either --fragility"),
    (["--fragility", "F", "--years", "0"], "--years must be a finite number > 0"),
    (["--fragility", "F", "--site-row", "-1"], "--site-row must be >= 0"),
    (["--fragility", "F", "--plot", "x.pdf"], "--plot"),
    (["--fragility", "F", "--json", "--p", "x"], "Invalid value for '--p'"),
    (["--fragility", "/nonexistent.json"], "/nonexistent.json: no such file"),
    (["--p", "2"], "give the records"),
])
def test_bad_input_is_one_line(frag_json, extra, msg):
    extra = [str(frag_json) if e == "F" else e for e in extra]
    res = runner.invoke(app, ["risk", "--hazard", TWO_COLUMN, *extra])
    assert res.exit_code == 2, res.stdout
    assert res.stderr.startswith("error: ") and msg in res.stderr, res.stderr
    assert len(res.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("text, msg", [
    ("PGA [g],rate [1/yr]\n0.1,0.01\n0.2,0.02\n0.4,0.001\n", "not monotonic"),
    ("PGV [m/s],rate [1/yr]\n0.1,0.01\n0.2,0.002\n", "they must be in the same IM"),
    ("PGA [g],rate [1/yr]\n0.3,0.001\n0.4,0.0005\n", "does not cover the fragility"),
])
def test_bad_curves_are_one_line(frag_json, tmp_path, text, msg):
    f = tmp_path / "h.csv"
    f.write_text(text)
    res = runner.invoke(app, ["risk", "--hazard", str(f), "--fragility", str(frag_json)])
    assert res.exit_code == 2 and msg in res.stderr, res.stderr
    assert len(res.stderr.strip().splitlines()) == 1


def test_extrapolate_accepts_a_short_curve_and_says_so(frag_json, tmp_path):
    f = tmp_path / "h.csv"
    f.write_text("PGA [g],rate [1/yr]\n0.15,0.006\n0.2,0.0034\n0.3,0.0014\n")
    out = _json(["risk", "--hazard", str(f), "--fragility", str(frag_json), "--json",
                 "--extrapolate"])
    assert out["extrapolated"] and out["extrapolated_share"] > 0.01
    assert out["lower_bound"] < out["annual_rate"]
    res = runner.invoke(app, ["risk", "--hazard", str(f), "--fragility", str(frag_json),
                              "--extrapolate"])
    assert res.exit_code == 0 and "warning: " in res.stderr and "extrapolation" in res.stderr


def test_design_system_with_a_hazard_gives_the_largest_scale(folder):
    out = _json(["design", "--system", "block", "--alpha", "0.1", "--p", "2", "--records",
                 str(folder), "--no-store", "--bootstrap", "0", "--hazard", TWO_COLUMN,
                 "--probability", "0.1", "--years", "50", "--json"])
    r = out["risk"]
    assert r["years"] == 50 and r["target_probability"] == 0.1
    # the fragility's own risk at the scale found is the target
    frag = hz.fragility_curve("pga", out["fragility"]["median"], out["fragility"]["beta"])
    at = hz.collapse_rate(hz.read_hazard(TWO_COLUMN).scaled(r["largest_scale"]), frag)
    assert at.probability == pytest.approx(0.1, rel=1e-4)
    # without --hazard, --probability keeps its meaning: the PGA at P(collapse | PGA)
    plain = _json(["design", "--system", "block", "--alpha", "0.1", "--p", "2", "--records",
                   str(folder), "--no-store", "--bootstrap", "0", "--probability", "0.2",
                   "--json"])
    assert plain["fragility"]["pga_at_probability"]["probability"] == 0.2
    assert "risk" not in plain


@pytest.mark.parametrize("extra, msg", [
    (["--hazard", TWO_COLUMN, "--site", "s.nc"], "--hazard needs --records"),
    (["--years", "10"], "--years goes with --hazard"),
    # typed at its default value: still given (Click's parameter source, not the value)
    (["--years", "50"], "--years goes with --hazard"),
    (["--extrapolate"], "--extrapolate goes with --hazard"),
])
def test_design_hazard_errors(extra, msg):
    res = runner.invoke(app, ["design", "--system", "block", "--alpha", "0.1", "--p", "2",
                              *(["--records", "x"] if "--site" not in extra else []),
                              *extra])
    assert res.exit_code == 2 and msg in res.stderr, res.stderr


@pytest.mark.slow  # ~60 s: replacement statics and an IDA per thickness tried
def test_design_arch_smallest_thickness(tmp_path):
    import rockarch as ra
    from rockarch.motion.suite import write_at2

    for c in (180, 270):
        m = ra.el_centro(c)
        write_at2(tmp_path / f"ELC{c}.AT2", ra.GroundMotion(m.t[:1200], m.a[:1200]))
    out = _json(["design", "--shape", "circular", "--span", "10", "--rise", "2.89",
                 "--thickness", "0.35", "--records", str(tmp_path), "--no-store",
                 "--hazard", TWO_COLUMN, "--probability", "0.05", "--json"])
    r = out["risk"]
    d = r["smallest_thickness"]
    trials = {t["thickness"]: t["probability"] for t in r["trials"]}
    # the answer meets the target, and a thickness at most 1 % thinner tried on the way
    # (the bisection's other end) does not
    assert trials[d] <= 0.05
    thinner = [t for t in trials if t < d]
    assert thinner and trials[max(thinner)] > 0.05 and max(thinner) >= 0.99 * d - 1e-12


@pytest.mark.parametrize("beta", [0.3, 0.75, 0.9, 1.5])
def test_risk_plot_x_axis_is_readable(beta):
    """The IM axis spans where the integrand matters (not 100-1000 g), and its tick labels
    are distinct numbers that do not overlap (they read "0.00 0.00 ... 10.0020.00")."""
    from rockarch.output.risk_plots import im_range, plot_risk

    curve = hz.read_hazard(OPENQUAKE)
    frag = hz.fragility_curve("pga", 0.222 * 9.80665, beta)
    res = hz.collapse_rate(curve, frag, extrapolate=True)  # beta 1.5 needs it
    fig = plot_risk(curve, frag, res)
    ax = fig.axes[-1]
    assert ax.get_xlabel() == "PGA [g = 9.80665 m/s²]"  # the curve's g, standard gravity
    lo, hi = ax.get_xlim()
    assert (lo, hi) == pytest.approx(tuple(v / curve.factor for v in im_range(curve, frag,
                                                                               res)))
    # the fragility's 0.1-99.9 % range (and the curve's 0.02 ... 2 g) fit in the axis
    z = 3.09 * beta
    assert lo <= min(0.02, 0.222 * math.exp(-z)) * 1.001
    assert hi >= max(2.0, 0.222 * math.exp(z)) / 1.001
    assert hi <= 10 * max(2.0, 0.222 * math.exp(z))
    assert hi < 100 if beta <= 0.9 else hi < 1000
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    shown = [t for t in ax.get_xticklabels() if t.get_text() and lo <= t.get_position()[0]
             <= hi]
    texts = [t.get_text() for t in shown]
    assert 3 <= len(texts) <= 12 and len(set(texts)) == len(texts), texts
    assert all(float(t) > 0 for t in texts), texts
    boxes = sorted((t.get_window_extent(renderer) for t in shown), key=lambda b: b.x0)
    assert all(a.x1 < b.x0 for a, b in zip(boxes[:-1], boxes[1:], strict=True)), texts


def test_text_and_figure_print_m_per_s_squared(frag_json, tmp_path):
    """A curve in 'PGA [m/s2]': the text and the figure print m/s², the JSON keeps what the
    file says."""
    f = tmp_path / "h.csv"
    f.write_text("PGA [m/s2],rate [1/yr]\n0.2,0.06\n0.5,0.02\n1,0.005\n2,0.001\n5,1e-4\n"
                 "10,1e-5\n20,1e-6\n")
    res = runner.invoke(app, ["risk", "--hazard", str(f), "--fragility", str(frag_json)])
    assert res.exit_code == 0, res.stderr
    assert "m/s2" not in res.stdout and "deaggregation by PGA [m/s²]" in res.stdout
    assert "frag.json: median PGA 2 m/s², beta 0.350" in res.stdout
    assert _json(["risk", "--hazard", str(f), "--fragility", str(frag_json),
                  "--json"])["hazard"]["units"] == "m/s2"
    from rockarch.output.risk_plots import plot_risk

    curve = hz.read_hazard(f)
    frag = hz.read_fragility(frag_json)
    fig = plot_risk(curve, frag, hz.collapse_rate(curve, frag))
    texts = [fig.axes[-1].get_xlabel()] + [t.get_text() for ax in fig.axes
                                           for t in ax.get_legend().get_texts()]
    assert texts[0] == "PGA [m/s²]" and not any("m/s2" in t for t in texts), texts
