"""Fragility (docs/theory.md Sect. 11.3): IDA collapse points are OAS boundaries times
ap,min; the censored lognormal MLE recovers known parameters; the bootstrap band."""

import dataclasses
import math

import numpy as np
import pytest
from scipy import stats

import rockarch as ra
from rockarch.risk import fragility as fr

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
    res = fr.ida(sys_, records, p, ratio=RATIO, search_step=0)
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
    assert res.censored.tolist() == [True] and res.search_step == 0.0025
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
    from rockarch.motion.intensity import im_value

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
    # without the search below the boundary (Eq. (11.30a), on by default for assemblies)
    res = fr.ida(sys_, [m], 6.0, ratio=[1.0, 2.0, 4.0], tol=0.1, search_step=0)
    ds = ra.oas(sys_, m, p=[6.0], ratio=[1.0, 2.0, 4.0], tol=0.1)
    assert np.isfinite(res.ratio_collapse[0])
    assert res.ratio_collapse[0] == ds["boundary"].values[0]


def test_the_default_scan_follows_the_structure():
    # the block's scan (81 values, 0.001) and the cheaper one of assemblies (17, 0.01):
    # docs/mdof.md, "The IDA scan of assemblies"; a given grid or tolerance wins
    m = ra.pulse("sine", period=0.5)
    lines: list[str] = []
    col = ra.system("mdof", column=[(0.2, 0.6)], t_free=0.5)
    res = fr.ida(col, [m], float(col.p_ref), log=lines.append)
    assert res.ratio.size == 17 and res.tol == 0.01
    assert res.ratio[0] == 1.0 and res.ratio[-1] == 5.0
    assert lines[1].startswith("IDA: 1 record(s), ap/ap,min = 1 … 5 in 17 values")
    assert lines[2].endswith("s)") and "record 1/1 done" in lines[2] and len(lines) == 3
    blk = ra.system("block", alpha=0.1)
    res = fr.ida(blk, [m], 2.0)
    assert res.ratio.size == 81 and res.tol == 0.001
    res = fr.ida(col, [m], float(col.p_ref), ratio=[1.0, 3.0], tol=0.05)
    assert res.ratio.size == 2 and res.tol == 0.05


def test_an_assembly_is_searched_below_a_collapse_only():
    # MDOF (costly): the search of Eq. (11.30a) below the grid's first collapse, every
    # 0.0025 for one block (as the block's own IDA), one value per thread at a time; a
    # record safe on the whole grid is not searched
    col = ra.system("mdof", column=[(0.2, 0.6)], t_free=0.5)
    calls: list[int] = []

    class Counting(type(col)):
        def run(self, motion, p, ratio):
            calls.append(int(np.size(ratio)))
            return super().run(motion, p, ratio)

    cnt = Counting(**{f.name: getattr(col, f.name) for f in dataclasses.fields(col)})
    m = ra.pulse("sine", period=0.5)
    # this pulse overturns the column from ap/ap,min ≈ 1.34 on (every value above it up to
    # 6 collapses, a scan every 0.1 with bisection): 1.1 is safe with an 18 % margin, 5 far
    # inside the collapse region, so both verdicts hold on any machine
    res = fr.ida(cnt, [m], float(col.p_ref), ratio=[1.0, 1.1], tol=0.05)
    assert res.search_step == 0.0025 and res.censored.all() and calls == [2]
    calls.clear()
    res = fr.ida(cnt, [m], float(col.p_ref), ratio=[1.0, 5.0], tol=0.05)
    grid_only = fr.ida(col, [m], float(col.p_ref), ratio=[1.0, 5.0], tol=0.05,
                       search_step=0)
    assert res.overturned[0].tolist() == [False, True]
    # the search ran (batches of at most one value per numba thread) and its collapse
    # point is never above the grid's bisected one
    import numba

    assert len(calls) > 1 and max(calls[1:]) <= max(numba.get_num_threads(), 1)
    assert res.ratio_collapse[0] <= grid_only.ratio_collapse[0]


def test_one_block_in_the_contact_engine_is_searched_as_the_block():
    # one block: the block's own search step; several blocks cost 0.1-5 s a simulation:
    # the block grid's 0.05
    from rockarch.risk.record_scan import default_search_step

    tri = ra.system("mdof", colonnade=2, block=[0.3, 2.0], bay=1.0, lintel=0.4)
    assert default_search_step(tri) == 0.05
    assert default_search_step(ra.system("mdof", column=[(0.3, 1.5)])) == 0.0025
    assert default_search_step(ra.system("block", p=2.0, alpha=0.2)) == 0.0025


def test_likelihood_gradient_matches_finite_differences():
    from scipy.optimize import approx_fprime

    lx = np.log(_sample(2.0, 0.4, 40, 4))
    lc = np.log(np.full(6, 2.5))
    for params in ([0.3, -1.2], [0.7, -0.9], [1.4, 0.1]):
        value, grad = fr._neg_loglik(np.array(params), lx, lc)
        num = approx_fprime(np.array(params), lambda q: fr._neg_loglik(q, lx, lc)[0], 1e-7)
        # forward differences of step 1e-7 on values ~1e2: error ~1e-5 relative
        assert grad == pytest.approx(num, rel=1e-4, abs=1e-4)


# --------------------------------------------------------------------------- record tasks


@dataclasses.dataclass(frozen=True)
class _Pattern:
    """A stand-in structure whose verdict is a fixed set of scan values (no simulation):
    collapse at ``collapse`` (ratios), safe elsewhere; counts its runs in RUNS and fails
    on any record named in FAIL (to interrupt an IDA)."""

    collapse: tuple
    name: str = "pattern"
    ap_min: float = 1.0

    def run(self, motion, p, ratio):
        if motion.name in FAIL:
            raise RuntimeError(f"interrupted at {motion.name}")
        RUNS.append(np.size(ratio))
        ratio = np.atleast_1d(ratio)
        return np.isin(np.round(ratio, 9), np.round(self.collapse, 9)), ratio

    def attrs(self) -> dict:
        return {}


RUNS: list = []
FAIL: set = set()


def _motion(name, seconds=2.0):
    t = np.linspace(0.0, seconds, 11)
    return ra.GroundMotion(t, np.sin(t), name)


def test_adaptive_scan_finds_islands_from_every_kth_value():
    # grid 1 … 5 step 0.25 (17 values); first collapse at 2.0; a safe island of two values
    # (3.0, 3.25), one of one value (4.25) and the scan limit 5.0 safe
    grid = RATIO
    safe_above = {3.0, 3.25, 4.25, 5.0}
    sys_ = _Pattern(tuple(r for r in grid if r >= 2.0 and r not in safe_above))
    full = fr.ida(sys_, [_motion("a")], 1.0, ratio=grid, tol=0.0, search_step=0)
    assert full.resurrections.tolist() == [3] and full.evaluated.all()
    RUNS.clear()
    res = fr.ida(sys_, [_motion("a")], 1.0, ratio=grid, tol=0.0, island_step=4,
                 search_step=0)
    assert res.ratio_collapse[0] == full.ratio_collapse[0] == 2.0
    run = grid[res.evaluated[0]]
    # every value up to the first collapse (a batch of numba threads may run a few more),
    # every 4th above it (3.0, 4.0, 5.0), the neighbours of the safe ones until a collapse
    # (2.75, 3.25, 3.5; 4.75); the one-value island 4.25 lies between 4.0 (collapse) and
    # 4.75 (collapse) and is never run: missed, as documented
    assert {1.0, 1.25, 1.5, 1.75, 2.0, 2.75, 3.0, 3.25, 3.5, 4.0, 4.75, 5.0} <= set(run)
    assert 4.25 not in run and sum(RUNS) == res.evaluated.sum() < grid.size
    assert res.resurrections.tolist() == [2]  # the islands (3.0, 3.25) and (5.0)
    ev = res.evaluated[0]
    assert np.array_equal(res.overturned[0][ev], full.overturned[0][ev])
    assert res.overturned[0][~ev].all()  # values not run are taken as collapse


def test_adaptive_scan_keeps_every_collapse_point(records):
    sys_ = ra.system("block", alpha=0.2, t_free=3.0)
    grid = np.round(np.linspace(1.0, 5.0, 41), 12)
    full = fr.ida(sys_, records, 2.0, ratio=grid)
    assert full.evaluated.all()
    for step in (2, 5):
        # the search runs after the grid's scan, from its first collapse down: the same
        # first collapse whatever the scan above it
        res = fr.ida(sys_, records, 2.0, ratio=grid, island_step=step)
        # the same values up to the first collapse, the same bisection: bit-identical
        assert np.array_equal(res.ratio_collapse, full.ratio_collapse)
        ev = res.evaluated
        assert np.array_equal(res.overturned[ev], full.overturned[ev])
        assert np.all(res.resurrections <= full.resurrections)
    with pytest.raises(ValueError, match="island step must be an integer >= 1"):
        fr.ida(sys_, records, 2.0, ratio=grid, island_step=0)


def test_each_record_is_stored_as_it_finishes_and_resumes(tmp_path):
    from rockarch.core import sweep

    sys_ = _Pattern(tuple(RATIO[RATIO >= 2.5]))
    suite = [_motion("short", 1.0), _motion("long", 3.0), _motion("mid", 2.0)]
    store = sweep.Store(tmp_path)
    FAIL.add("short")  # longest first: "long" and "mid" finish, then "short" fails
    try:
        with pytest.raises(RuntimeError, match="interrupted at short"):
            fr.ida(sys_, suite, 1.0, ratio=RATIO, tol=0.0, store=store)
    finally:
        FAIL.clear()
    assert store.computed == 2
    store = sweep.Store(tmp_path)
    RUNS.clear()
    res = fr.ida(sys_, suite, 1.0, ratio=RATIO, tol=0.0, store=store)
    assert (store.reused, store.computed) == (2, 1)
    assert res.ratio_collapse.tolist() == [2.5, 2.5, 2.5]
    # a record's key holds the record, not the suite: another suite reuses it
    store = sweep.Store(tmp_path)
    fr.ida(sys_, [suite[2], _motion("new", 1.5)], 1.0, ratio=RATIO, tol=0.0, store=store)
    assert (store.reused, store.computed) == (1, 1)


def test_ida_on_worker_processes_is_bit_identical(records):
    from rockarch.core import sweep

    sys_ = ra.system("block", alpha=0.2, t_free=3.0)
    ref = fr.ida(sys_, records, 2.0, ratio=RATIO)
    with sweep.Executor("processes", workers=2) as ex:
        for step in (1, 3):
            res = fr.ida(sys_, records, 2.0, ratio=RATIO, executor=ex, island_step=step)
            assert np.array_equal(res.ratio_collapse, ref.ratio_collapse)
            ev = res.evaluated
            assert np.array_equal(res.overturned[ev], ref.overturned[ev])


# --------------------------------------------------------------------------- collapse islands


def test_search_finds_a_collapse_island_narrower_than_the_grid():
    # grid 1 … 5 step 0.25; the structure collapses on the grid from 2.5 and on one value
    # of the search, 1.6 (= 1 + 240·0.0025), alone: an island narrower than the grid
    sys_ = _Pattern((1.6, *RATIO[RATIO >= 2.5]))
    RUNS.clear()
    res = fr.ida(sys_, [_motion("a")], 1.0, ratio=RATIO, tol=0.0)
    assert res.ratio_collapse[0] == 1.6 and res.im_collapse[0] == 1.6
    # the grid values 1.75, 2.0, 2.25 above it are safe: one resurrection
    assert res.resurrections.tolist() == [1]
    # the search stops at the first collapse: the grid, then batches of at most
    # SEARCH_BATCH·threads values from 1.0025 up to 1.6 (239 values off the grid)
    import numba

    from rockarch.risk.record_scan import SEARCH_BATCH

    assert sum(RUNS) <= RATIO.size + 239 + SEARCH_BATCH * numba.get_num_threads()
    # without the search: the grid's first collapse, the island missed
    off = fr.ida(sys_, [_motion("a")], 1.0, ratio=RATIO, tol=0.0, search_step=0)
    assert off.ratio_collapse[0] == 2.5 and off.resurrections.tolist() == [0]
    # an island narrower than the search step between two of its values is missed
    narrow = _Pattern((1.6012, *RATIO[RATIO >= 2.5]))
    assert fr.ida(narrow, [_motion("a")], 1.0, ratio=RATIO, tol=0.0).ratio_collapse[0] == 2.5
    # a coarser search step given by the caller: 1.6 is on the grid 1 + 0.1k too
    assert fr.ida(sys_, [_motion("a")], 1.0, ratio=RATIO, tol=0.0,
                  search_step=0.1).ratio_collapse[0] == 1.6
    with pytest.raises(ValueError, match="search step must be a finite number >= 0"):
        fr.ida(sys_, [_motion("a")], 1.0, ratio=RATIO, search_step=-0.1)


def test_first_collapse_is_that_of_the_fine_scan_below_it(records):
    # a real block: every value 1 + 0.0025k below the collapse point is safe, and the
    # collapse point lies within one search step below a collapse (bisection to tol)
    sys_ = ra.system("block", alpha=0.1, t_free=3.0)
    res = fr.ida(sys_, records, 2.0, ratio=RATIO)
    coarse = fr.ida(sys_, records, 2.0, ratio=RATIO, search_step=0)
    for k, m in enumerate(records):
        x = res.ratio_collapse[k]
        assert x <= coarse.ratio_collapse[k]
        fine = np.round(1 + 0.0025 * np.arange(int((x - 1) / 0.0025) + 2), 12)
        over, _ = sys_.run(m, np.full(fine.size, 2.0), fine)
        first = fine[np.argmax(over)]
        assert over.any() and not over[fine < x].any()
        assert first - 0.0025 < x <= first


def test_el_centro_270_overturns_the_block_on_its_narrow_island():
    # issue 24: block alpha = 0.1, p = 2 on El Centro 270: the fine scan (step 0.0025 of
    # ap/ap,min, and an independent engine) overturns it first at PGA 1.4075 m/s2 (ratio
    # 1.43, an island ~0.015 wide); the 81-value grid alone first at 1.543 m/s2 (9.6 %
    # higher). The default scan must be within 1 % of the fine scan (the issue's bound)
    sys_ = ra.system("block", alpha=0.1)
    res = fr.ida(sys_, [ra.el_centro(270)], 2.0)
    assert res.im_collapse[0] == pytest.approx(1.4075, rel=0.01)
    coarse = fr.ida(sys_, [ra.el_centro(270)], 2.0, search_step=0)
    assert coarse.im_collapse[0] > 1.09 * 1.4075
    assert res.resurrections[0] > coarse.resurrections[0]


@pytest.mark.slow  # ~60 s: a fine scan of 22 records
def test_default_scan_is_within_1_percent_of_the_fine_scan_on_95_percent_of_records():
    # issue 24's acceptance: with default options every record's first collapse within
    # 1 % of a fine scan (ratio 1 … 10 every 0.0025, no bisection) on >= 95 % of a suite:
    # the bundled records and 20 synthetic ones (seed 7, not a seed the scheme was tuned
    # on). A record censored by the default scan (no collapse up to 5) agrees if the
    # fine scan does not collapse up to 5 either.
    sys_ = ra.system("block", alpha=0.1)
    motions = [ra.el_centro(180), ra.el_centro(270),
               *ra.synthetic_suite(20, seed=7).motions]
    res = fr.ida(sys_, motions, 2.0)
    fine = np.round(np.linspace(1.0, 10.0, 3601), 12)
    agree = []
    for k, m in enumerate(motions):
        over, _ = sys_.run(m, np.full(fine.size, 2.0), fine)
        first = fine[np.argmax(over)] if over.any() else np.inf
        x = res.ratio_collapse[k]
        agree.append(abs(x / first - 1) <= 0.01 if np.isfinite(x) else first > 5.0)
    assert np.mean(agree) >= 0.95, agree
