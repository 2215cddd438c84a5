"""Fragility (docs/theory.md Sect. 11.3): IDA collapse points are OAS boundaries times
ap,min; the censored lognormal MLE recovers known parameters; the bootstrap band."""

import math

import numpy as np
import pytest
from scipy import stats

import rockarch as ra
from rockarch import fragility as fr

RATIO = np.round(np.linspace(1.0, 5.0, 17), 12)


@pytest.fixture(scope="module")
def records():
    # the first 12 s of both El Centro components (the strong motion; keeps the test fast)
    return [ra.GroundMotion(m.t[:1200], m.a[:1200], m.name)
            for m in (ra.el_centro(180), ra.el_centro(270))]


@pytest.mark.parametrize("kind, kw, p", [
    ("block", {"alpha": 0.2, "t_free": 3.0}, 2.0),
    ("sdof", {"p": 3.0, "delta": 0.15, "ap_min": 1.2, "t_free": 3.0}, 3.0),
])
def test_ida_collapse_is_the_oas_boundary_times_ap_min(records, kind, kw, p):
    sys_ = ra.system(kind, **kw)
    res = fr.ida(sys_, records, p, ratio=RATIO)
    for k, m in enumerate(records):
        ds = ra.oas(sys_, m, p=[p], ratio=RATIO)
        # same grid, same bisection, same simulations: bit-identical, not just close
        assert res.ratio_collapse[k] == ds["boundary"].values[0]
        assert res.im_collapse[k] == ds["boundary"].values[0] * sys_.ap_min
        row = ds["overturned"].values[0]
        assert np.array_equal(res.overturned[k], row)
        assert res.resurrections[k] == fr.count_resurrections(row[None])[0]
    assert np.all(np.isfinite(res.ratio_collapse))


def test_ida_censors_records_safe_up_to_the_scan_limit(records):
    sys_ = ra.system("block", alpha=0.2, t_free=3.0)
    res = fr.ida(sys_, records[:1], 2.0, ratio=[0.5, 0.8, 1.0])
    assert res.censored.tolist() == [True]
    assert res.im_limit[0] == pytest.approx(1.0 * sys_.ap_min)


def test_count_resurrections():
    over = np.array([[0, 1, 1, 0, 0, 1, 0, 1],
                     [0, 0, 0, 0, 0, 0, 0, 0],
                     [1, 1, 1, 1, 1, 1, 1, 1]], dtype=bool)
    assert fr.count_resurrections(over).tolist() == [2, 0, 0]


def _sample(theta, beta, n, seed):
    return theta * np.exp(beta * np.random.default_rng(seed).standard_normal(n))


def test_mle_recovers_theta_and_beta():
    theta, beta, n = 2.0, 0.4, 2000
    fit = fr.fit_lognormal(_sample(theta, beta, n, 1))
    # standard errors of the MLE: beta/sqrt(n) for ln(theta), beta/sqrt(2n) for beta;
    # 4 standard errors (a failure chance of 6e-5 per parameter)
    assert abs(math.log(fit.median / theta)) < 4 * beta / math.sqrt(n)
    assert abs(fit.beta - beta) < 4 * beta / math.sqrt(2 * n)


def test_mle_with_censoring_recovers_theta_and_beta_and_matches_scipy():
    theta, beta, n = 2.0, 0.4, 2000
    x = _sample(theta, beta, n, 2)
    limit = theta * math.exp(0.5 * beta)  # ~31 % of the records never collapse
    done = x[x <= limit]
    fit = fr.fit_lognormal(done, np.full(n - done.size, limit))
    assert fit.n_censored == n - done.size > 0.25 * n
    # censoring inflates the standard errors (Fisher information of a censored normal,
    # about 1.3x here): 5 uncensored standard errors
    assert abs(math.log(fit.median / theta)) < 5 * beta / math.sqrt(n)
    assert abs(fit.beta - beta) < 5 * beta / math.sqrt(2 * n)
    # dropping the censored records instead biases both far beyond that
    naive = fr.fit_lognormal(done)
    assert abs(math.log(naive.median / theta)) > 10 * beta / math.sqrt(n)
    # an independent implementation of the same likelihood (scipy.stats' censored fit)
    data = stats.CensoredData(uncensored=done, right=np.full(n - done.size, limit))
    s, _, scale = stats.lognorm.fit(data, floc=0)
    assert fit.median == pytest.approx(scale, rel=1e-3)
    assert fit.beta == pytest.approx(s, rel=1e-3)


def test_probability_and_intensity_are_inverse():
    fit = fr.LognormalFit(median=3.0, beta=0.5, n_collapsed=10, n_censored=0, loglik=0.0)
    assert fit.probability(3.0) == pytest.approx(0.5)
    assert fit.intensity(0.1) == pytest.approx(3.0 * math.exp(0.5 * stats.norm.ppf(0.1)))
    assert fit.probability(fit.intensity([0.1, 0.9])) == pytest.approx([0.1, 0.9])
    with pytest.raises(ValueError, match="probability"):
        fit.intensity(1.0)


def test_bootstrap_band_contains_the_truth_and_is_reproducible():
    theta, beta = 2.0, 0.4
    x = _sample(theta, beta, 200, 3)
    ci = fr.bootstrap(x, n=300, im_grid=[1.0, 2.0, 4.0], seed=5)
    assert ci["median"][0] < theta < ci["median"][1]
    assert ci["beta"][0] < beta < ci["beta"][1]
    assert all(lo <= hi for lo, hi in zip(ci["probability_lo"], ci["probability_hi"],
                                          strict=True))
    assert ci["probability_lo"][1] < 0.5 < ci["probability_hi"][1]
    assert fr.bootstrap(x, n=300, im_grid=[1.0, 2.0, 4.0], seed=5) == ci


@pytest.mark.parametrize("args, msg", [
    (([1.0],), "at least two different"),
    (([1.0, 1.0, 1.0],), "at least two different"),
    (([1.0, -2.0],), "finite numbers > 0"),
    (([1.0, 2.0], [np.nan]), "finite numbers > 0"),
])
def test_fit_rejects_bad_data(args, msg):
    with pytest.raises(ValueError, match=msg):
        fr.fit_lognormal(*args)


def test_im_choices():
    m = ra.el_centro()
    assert fr.im_per_unit_pga(m, "pga") == 1.0
    with pytest.raises(ValueError, match="unknown intensity measure"):
        fr.im_per_unit_pga(m, "pgd")
    with pytest.raises(ValueError, match="needs --period"):
        fr.im_per_unit_pga(m, "sa")
    with pytest.raises(ValueError, match="--period is for --im sa only"):
        fr.im_per_unit_pga(m, "pgv", 0.5)


@pytest.mark.parametrize("im, period", [("pgv", None), ("sa", 0.5)])
def test_im_collapse_is_the_im_of_the_record_scaled_to_collapse(records, im, period):
    from rockarch.intensity import im_value

    sys_ = ra.system("block", alpha=0.2, t_free=3.0)
    res = fr.ida(sys_, records[:1], 2.0, ratio=RATIO, im=im, period=period)
    m = records[0]
    scaled = m.scaled(res.ratio_collapse[0] * sys_.ap_min / m.pga)
    # IMs are linear in the scale: equal up to round-off
    assert res.im_collapse[0] == pytest.approx(im_value(scaled, im, period=period),
                                               rel=1e-12)


def test_site_fragility_is_in_units_of_the_structures_ap_min(records):
    frag = fr.site_fragility(records, 2.0, ap_min=3.0, ratio=RATIO, t_free=3.0,
                             n_bootstrap=20)
    block = fr.ida(ra.system("block", alpha=0.05, t_free=3.0), records, 2.0, ratio=RATIO)
    assert np.array_equal(frag.ida.im_collapse, block.ratio_collapse * 3.0)
    s = fr.design_summary(frag, pga=frag.fit.median, probability=0.5)
    assert s["probability_at_pga"]["probability"] == pytest.approx(0.5)
    assert s["pga_at_probability"]["pga"] == pytest.approx(frag.fit.median)
    with pytest.raises(ValueError, match="--pga"):
        fr.design_summary(frag, pga=-1.0)


@pytest.mark.slow
def test_ida_of_an_mdof_arch_is_its_oas_boundary():
    m = ra.el_centro()
    m = ra.GroundMotion(m.t[:600], m.a[:600], "El Centro, first 6 s")
    sys_ = ra.system("mdof", shape="circular", rise_over_span=0.5, thickness_over_span=0.15,
                     blocks=8, t_free=2.0)
    res = fr.ida(sys_, [m], 6.0, ratio=[1.0, 2.0, 4.0], tol=0.1)
    ds = ra.oas(sys_, m, p=[6.0], ratio=[1.0, 2.0, 4.0], tol=0.1)
    assert np.isfinite(res.ratio_collapse[0])
    assert res.ratio_collapse[0] == ds["boundary"].values[0]


def test_likelihood_gradient_matches_finite_differences():
    from scipy.optimize import approx_fprime

    lx = np.log(_sample(2.0, 0.4, 40, 4))
    lc = np.log(np.full(6, 2.5))
    for params in ([0.3, -1.2], [0.7, -0.9], [1.4, 0.1]):
        value, grad = fr._neg_loglik(np.array(params), lx, lc)
        num = approx_fprime(np.array(params), lambda q: fr._neg_loglik(q, lx, lc)[0], 1e-7)
        # forward differences of step 1e-7 on values ~1e2: error ~1e-5 relative
        assert grad == pytest.approx(num, rel=1e-4, abs=1e-4)
