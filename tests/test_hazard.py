"""Hazard curves and the annual frequency of collapse (docs/theory.md §11.5): the closed
form for a power-law hazard, an independent quadrature on a real-looking curve, the
readers (two-column CSV, OpenQuake), the deaggregation, the coverage check and its bound,
and the inverse (largest scale of the hazard)."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate, stats

from rockarch.core.constants import G_STANDARD
from rockarch.risk import hazard as hz

DATA = Path(hz.__file__).parent / "data"
TWO_COLUMN = DATA / "illustrative_hazard_PGA.csv"
OPENQUAKE = DATA / "hazard_curve-mean-PGA.csv"


def power_law(k0, k, median, beta, span=9.0, n=30):
    """H(x) = k0 x^-k tabulated over the range where the integrand of λ_c lives: z = ln(x/θ)/β
    within ±span of -kβ (the centre of H·dP, a normal density of unit width)."""
    z = -k * beta + np.linspace(-span, span, n)
    x = median * np.exp(beta * z)
    return hz.hazard_curve(x, k0 * x ** -k, "pga")


@pytest.mark.parametrize("k0, k, median, beta", [
    (1e-4, 2.5, 3.0, 0.4), (2e-4, 3.0, 1.5, 0.3), (1e-3, 1.5, 4.0, 0.6),
    (1e-5, 4.0, 2.0, 0.5), (5e-4, 2.0, 0.5, 0.1),
])
def test_power_law_hazard_matches_the_closed_form(k0, k, median, beta):
    # Cornell et al. (2002): lambda_c = k0 theta^-k exp(k^2 beta^2 / 2) for H = k0 x^-k and
    # a lognormal fragility; the issue asks for 0.5 %. The tabulated power law is exact
    # between its points (log-log), the grid's midpoint rule is O(step^2) = O(2.5e-5), the
    # range truncation below 1e-15: 1e-4 is a bound with margin
    curve = power_law(k0, k, median, beta)
    res = hz.collapse_rate(curve, hz.fragility_curve("pga", median, beta), years=50)
    exact = hz.power_law_rate(k0, k, median, beta)
    assert res.annual_rate == pytest.approx(exact, rel=1e-4)
    assert res.probability == pytest.approx(1 - math.exp(-50 * exact), rel=1e-4)
    assert sum(res.shares) == pytest.approx(1.0, rel=1e-12)
    assert res.extrapolated_share < 1e-3 and not res.extrapolated
    # the lower bound (no extrapolation) is below the rate, and close when covered
    assert exact * (1 - 1e-3) < res.lower_bound <= res.annual_rate * (1 + 1e-12)


def test_power_law_closed_form_by_scipy_quadrature():
    # the closed form itself, against scipy's adaptive quadrature of ∫ H dP (by parts)
    k0, k, median, beta = 1e-4, 2.5, 3.0, 0.4
    dens = stats.lognorm(s=beta, scale=median).pdf
    num, _ = integrate.quad(lambda x: k0 * x ** -k * dens(x), 0, np.inf, limit=200)
    assert hz.power_law_rate(k0, k, median, beta) == pytest.approx(num, rel=1e-8)


def test_real_looking_curve_against_an_independent_quadrature():
    # the bundled (illustrative) curve is concave in log-log, not a power law; the
    # reference integrates H(x) f(x) dx (the by-parts form, Eq. 11.36) by scipy.quad
    # over each interval of the curve, H log-log interpolated, the fragility's density f;
    # plus the two ends: a fragility inside the curve (P < 1e-9 below 0.02 g; H(2 g)·(1 -
    # P(2 g)) above, and H(0.02 g)·P(0.02 g) below, both from the by-parts boundary terms)
    curve = hz.read_hazard(TWO_COLUMN)
    median, beta = 0.25 * G_STANDARD, 0.35
    frag = hz.fragility_curve("pga", median, beta)
    res = hz.collapse_rate(curve, frag)
    dens = stats.lognorm(s=beta, scale=median).pdf
    x = curve.x
    inside = sum(integrate.quad(lambda v: float(curve.rate_at(v)) * dens(v), a, b,
                                epsabs=0, epsrel=1e-10)[0]
                 for a, b in zip(x[:-1], x[1:], strict=True))
    ref = inside + curve.rate[0] * float(frag.probability(x[0]))
    ref += integrate.quad(lambda v: float(curve.rate_at(v)) * dens(v), x[-1], np.inf,
                          epsabs=0, epsrel=1e-10)[0]
    # midpoint rule on a step of beta/200 in ln x: 1e-5 with margin
    assert res.annual_rate == pytest.approx(ref, rel=1e-5)
    # a direct sum P(x)·ΔH over a million log-spaced steps of the curve's range
    xs = np.geomspace(x[0], x[-1], 1_000_001)
    h = curve.rate_at(xs)
    direct = float(np.sum(frag.probability(np.sqrt(xs[:-1] * xs[1:])) * -np.diff(h)))
    assert res.inside == pytest.approx(direct, rel=1e-6)
    # the deaggregation: shares per interval of the curve, summing to 1; half of λ_c
    # below the median: the bins below its bin hold <= 1/2, with its bin >= 1/2
    assert sum(res.shares) == pytest.approx(1.0, rel=1e-12)
    k = np.searchsorted(res.im_bins, res.median_im) - 1
    assert res.shares[:k].sum() <= 0.5 <= res.shares[:k + 1].sum()
    # each share is the integral over its bin: the quadrature of the bin 0.2–0.25 g
    a, b = 0.2 * G_STANDARD, 0.25 * G_STANDARD
    j = np.flatnonzero(np.isclose(res.im_bins, a))[0]
    part = integrate.quad(lambda v: float(frag.probability(v) * -curve.rate_at(v)
                                          * curve_slope(curve, v) / v), a, b,
                          epsabs=0, epsrel=1e-10)[0]
    assert res.shares[j] == pytest.approx(part / res.annual_rate, rel=1e-5)


@pytest.mark.parametrize("median", [1.7728510609765913, 0.25 * G_STANDARD])
def test_density_is_the_integrand_without_rounding_spikes(median):
    # the plotted density of lambda_c per unit ln x is P(x)·|dH/d ln x| (Eq. 11.41); the
    # first median put a grid point within 1e-16 of another, and that step's density was
    # rounding noise twice the curve's height, taken as the largest contribution
    curve = hz.read_hazard(TWO_COLUMN)
    frag = hz.fragility_curve("pga", median, 0.46986004970112377)
    res = hz.collapse_rate(curve, frag)
    inner = (res.im_grid > curve.x[0]) & (res.im_grid < curve.x[-1])
    x = res.im_grid[inner]
    exact = frag.probability(x) * -curve.rate_at(x) * curve_slope(curve, x)
    # a midpoint step of beta/200 (and <= 1/COARSE_PER_LN outside): 1 % with margin
    assert np.allclose(res.density[inner], exact, rtol=0.01, atol=1e-3 * exact.max())
    assert res.mode == pytest.approx(x[np.argmax(exact)], rel=0.01)


def curve_slope(curve, x):
    """d ln H / d ln x of the log-log interpolation at x (inside an interval)."""
    k = np.searchsorted(curve.x, x) - 1
    return np.log(curve.rate[k + 1] / curve.rate[k]) / np.log(curve.x[k + 1] / curve.x[k])


def test_the_two_formats_of_the_bundled_curve_agree():
    a, b = hz.read_hazard(TWO_COLUMN), hz.read_hazard(OPENQUAKE)
    assert (a.im, a.units, b.im, b.units) == ("pga", "g", "pga", "g")
    assert b.investigation_time == 50.0 and b.site == (0.0, 0.0)
    assert np.array_equal(a.x, b.x) and a.x[0] == pytest.approx(0.02 * G_STANDARD)
    # poe written to 7 digits, converted by -ln(1 - poe)/50: the rates agree to 1e-6
    assert b.rate == pytest.approx(a.rate, rel=1e-6)


def test_openquake_headers_old_and_new_and_without_depth(tmp_path):
    new = tmp_path / "hazard_curve-mean-SA(0.5).csv"
    new.write_text("#,,,,,\"generated_by='OpenQuake engine 3.15.0', kind='mean', "
                   "investigation_time=1.0, imt='SA(0.5)'\"\n"
                   "lon,lat,depth,poe-0.1000000,poe-0.4000000,poe-0.6000000\n"
                   "0.00000,0.00000,-0.10000,6.081918E-01,3.287217E-01,1.994702E-01\n")
    c = hz.read_hazard(new)
    assert (c.im, c.period, c.units, c.investigation_time) == ("sa", 0.5, "g", 1.0)
    assert c.rate[0] == pytest.approx(-math.log(1 - 0.6081918))
    old = tmp_path / "hazard_curve-PGV.csv"
    old.write_text("# source_model_tree_path=('b1',), investigation_time=50.0,imt=\"PGV\"\n"
                   "lon,lat,poe-10,poe-20,poe-40\n1.5,42.0,0.3,0.1,0.01\n")
    c = hz.read_hazard(old)
    assert (c.im, c.units, c.site) == ("pgv", "cm/s", (1.5, 42.0))
    assert c.x.tolist() == pytest.approx([0.1, 0.2, 0.4])  # cm/s → m/s
    assert c.rate == pytest.approx(hz.poe_to_rate([0.3, 0.1, 0.01], 50.0))


def test_two_column_headers(tmp_path):
    f = tmp_path / "h.csv"
    f.write_text("# a comment\nSa(1.0) [m/s2];lambda [1/yr]\n0.5;1e-2\n1;2e-3\n\n2;1e-4\n")
    c = hz.read_hazard(f)
    assert (c.im, c.period, c.label, c.x.tolist()) == ("sa", 1.0, "Sa(1)", [0.5, 1, 2])
    f.write_text("PGV [cm/s]\tannual frequency of exceedance\n10\t1e-2\n20\t1e-3\n")
    assert hz.read_hazard(f).x.tolist() == pytest.approx([0.1, 0.2])
    # trailing zero rates: the curve ends at its last positive rate (a note says so)
    f.write_text("PGA [g],rate [1/yr]\n0.1,1e-2\n0.2,1e-3\n0.4,0\n0.8,0\n")
    c = hz.read_hazard(f)
    assert c.x.size == 2 and "left out" in c.notes[0]


@pytest.mark.parametrize("text, msg", [
    ("PGA [g],rate [1/yr]\n0.1,0.01\n0.2,0.02\n", "not monotonic: the annual rate of "
     "exceedance rises from 0.01 at 0.1 g to 0.02 at 0.2 g"),
    ("PGA [g],rate [1/yr]\n0.1,0.01\n0.2,0\n0.3,0.001\n", "not monotonic"),
    ("PGA [g],rate [1/yr]\n0.2,0.01\n0.1,0.001\n", "IM levels must increase"),
    ("PGV [g],rate [1/yr]\n0.1,0.01\n0.2,0.001\n", "PGV is a velocity: its units"),
    ("PGA [m/s],rate [1/yr]\n0.1,0.01\n0.2,0.001\n", "PGA is an acceleration"),
    ("PGA,rate\n0.1,0.01\n", "must name the IM and its units"),
    ("PGA [g],poe in 50 years\n0.1,0.4\n", "probabilities of exceedance in T years"),
    ("PGA [g],rate [1/month]\n0.1,0.4\n", "is in 1/yr"),
    ("PGA [g],rate [1/yr]\n0.1,x\n", "line 2: expected two numbers"),
    ("PGA [g],rate [1/yr]\n0.1,0.01\n", "at least two IM levels"),
    ("", "empty"),
    ("#,,\"investigation_time=50.0, imt='PGA'\"\nlon,lat,poe-0.1\n0,0,1.0\n",
     "must lie in [0, 1)"),
    ("#,,\"investigation_time=0, imt='PGA'\"\nlon,lat,poe-0.1\n0,0,0.5\n",
     "no investigation_time > 0"),
    ("#,,\"investigation_time=50.0\"\nlon,lat,poe-0.1\n0,0,0.5\n", "without its IM"),
    ("#,,\"investigation_time=50.0, imt='PGA'\"\nx,y,poe-0.1\n0,0,0.5\n",
     "expected OpenQuake's header"),
])
def test_bad_curves_are_one_clear_error(tmp_path, text, msg):
    f = tmp_path / "h.csv"
    f.write_text(text)
    with pytest.raises(ValueError, match=msg.replace("(", r"\(").replace(")", r"\)")
                       .replace("[", r"\[")) as err:
        hz.read_hazard(f)
    assert str(f) in str(err.value)


def test_openquake_sites_are_chosen_by_row(tmp_path):
    f = tmp_path / "hazard_curve-mean-PGA.csv"
    lines = OPENQUAKE.read_text().splitlines()
    f.write_text("\n".join([*lines, lines[2].replace("0.00000,0.00000", "1.0,2.0", 1)]))
    with pytest.raises(ValueError, match=r"holds 2 sites: choose one with --site-row K"):
        hz.read_hazard(f)
    assert hz.read_hazard(f, site_row=1).site == (1.0, 2.0)
    with pytest.raises(ValueError, match="--site-row must lie in 0 … 1"):
        hz.read_hazard(f, site_row=2)
    with pytest.raises(ValueError, match="--site-row is for OpenQuake files"):
        hz.read_hazard(TWO_COLUMN, site_row=0)


def test_a_curve_that_does_not_cover_the_fragility_is_refused_with_its_bound():
    curve = hz.read_hazard(TWO_COLUMN)
    inner = hz.hazard_curve(curve.x[7:10] / G_STANDARD, curve.rate[7:10], "pga", units="g")
    frag = hz.fragility_curve("pga", 0.25 * G_STANDARD, 0.35)
    full = hz.collapse_rate(curve, frag)
    with pytest.raises(ValueError, match=r"does not cover the fragility .* rests on its "
                       r"extrapolation below and above it .* a lower bound") as err:
        hz.collapse_rate(inner, frag)
    res = hz.collapse_rate(inner, frag, extrapolate=True)
    assert res.extrapolated and res.extrapolated_share > 0.3
    assert f"{100 * res.extrapolated_share:.1f} %" in str(err.value)
    assert " g, g = 9.80665 m/s²) does not cover" in str(err.value)  # which g: the curve's
    assert f"{res.lower_bound:.3g}/yr" in str(err.value)
    # Eq. (11.40): the bound without extrapolation is below the rate of the full curve
    # (which the short one is a piece of); the extrapolation is an estimate, not a bound
    assert res.lower_bound < full.annual_rate
    assert res.lower_bound < res.annual_rate


def test_im_and_period_must_match():
    curve = hz.read_hazard(TWO_COLUMN)
    with pytest.raises(ValueError, match=r"in PGA \[g\] and the fragility in PGV: they must "
                       r"be in the same IM \(rerun the fragility with --im pga\)"):
        hz.collapse_rate(curve, hz.fragility_curve("pgv", 0.3, 0.4))
    sa = hz.hazard_curve([0.1, 1.0], [1e-2, 1e-4], "sa", 0.5, units="g")
    with pytest.raises(ValueError, match=r"Sa\(0.5\) and the fragility Sa\(1\)"):
        hz.collapse_rate(sa, hz.fragility_curve("sa", 3.0, 0.4, period=1.0))


def test_fragility_json(tmp_path):
    f = tmp_path / "frag.json"
    f.write_text('{"im": "pga", "units": "m/s2", "median": 2.0, "beta": 0.3}')
    assert hz.read_fragility(f) == hz.FragilityCurve("pga", 2.0, 0.3, None, str(f))
    for text, msg in [('{"im": "pga", "units": "g", "median": 2.0, "beta": 0.3}',
                       "has units m/s2"),
                      ('{"im": "pga_norm", "units": "-", "median": 2.0, "beta": 0.3}',
                       "cannot meet a hazard curve"),
                      ('{"im": "pga", "units": "m/s2", "median": null, "beta": null}',
                       "no lognormal fit"),
                      ('{"im": "pga", "units": "m/s2", "median": -1, "beta": 0.3}',
                       "median must be a finite number > 0"),
                      ("[1, 2]", "not the JSON of rockarch fragility"), ("{", "not a JSON")]:
        f.write_text(text)
        with pytest.raises(ValueError, match=msg):
            hz.read_fragility(f)


def test_largest_scale_reaches_the_target_probability():
    curve = hz.read_hazard(TWO_COLUMN)
    frag = hz.fragility_curve("pga", 0.25 * G_STANDARD, 0.35)
    s = hz.largest_scale(curve, frag, 0.02, years=50)
    assert hz.collapse_rate(curve.scaled(s), frag).probability == pytest.approx(0.02,
                                                                                rel=1e-5)
    # a stronger site (s > 1) collapses the structure more often: monotonic in s
    p = [hz.collapse_rate(curve.scaled(v), frag).probability for v in (0.5, 1.0, 2.0)]
    assert p[0] < p[1] < p[2]
    # scaling the hazard by s is scaling the fragility's median by 1/s (Eq. 11.42)
    other = hz.collapse_rate(curve, hz.fragility_curve("pga", frag.median / 1.3, 0.35))
    assert hz.collapse_rate(curve.scaled(1.3), frag).annual_rate == pytest.approx(
        other.annual_rate, rel=1e-4)
    with pytest.raises(ValueError, match=r"must lie in \(0, 1\)"):
        hz.largest_scale(curve, frag, 1.5)


def test_poisson_probability_and_its_inverse():
    assert hz.probability_in(1e-3, 50) == pytest.approx(1 - math.exp(-0.05))
    assert hz.rate_for_probability(hz.probability_in(2e-4, 50), 50) == pytest.approx(2e-4)
    assert hz.poe_to_rate(0.1, 50) == pytest.approx(1 / 474.56, rel=1e-4)  # the 475 years


def test_a_sharp_fragility_gives_the_hazard_at_its_median():
    # beta -> 0: the structure collapses exactly above theta, so lambda_c -> H(theta)
    # (Eq. 11.36); beta = 1e-4 moves it by k^2 beta^2 / 2 ~ 1e-8 inside a power-law piece
    # (theta off the curve's levels: at a kink the two slopes give a first-order term
    # ~ beta (k1 - k2)/2.5, 6e-6), and the grid stays small (fine steps only where P varies)
    curve = hz.read_hazard(TWO_COLUMN)
    theta = 0.27 * G_STANDARD
    res = hz.collapse_rate(curve, hz.fragility_curve("pga", theta, 1e-4))
    assert res.annual_rate == pytest.approx(float(curve.rate_at(theta)), rel=1e-6)
    assert res.im_grid.size < 10_000
    with pytest.raises(ValueError, match="a fragility in Sa needs its period"):
        hz.fragility_curve("sa", 1.0, 0.3)
