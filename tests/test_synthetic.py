"""Synthetic ground motions (Rezaeian & Der Kiureghian model, rockarch.motion.synthetic)."""

import math

import numpy as np
import pytest
from scipy import integrate, stats

import rockarch as ra
from rockarch.core.constants import G_STANDARD, G
from rockarch.motion import intensity as im
from rockarch.motion import synthetic as sy
from rockarch.motion.signals import GroundMotion

P = sy.RDKParameters(arias=0.5, d5_95=15.0, t_mid=10.0, f_mid=5.0, f_slope=0.0, zeta_f=0.3)


def test_modulating_function_has_the_target_husid_quantiles_and_arias():
    # q² integrated numerically (independent of the gamma-quantile mapping)
    a1, a2, a3 = sy.modulation(P)
    t = np.linspace(1e-9, 200.0, 400_001)
    q2 = (a1 * t ** (a2 - 1) * np.exp(-a3 * t)) ** 2
    cum = integrate.cumulative_trapezoid(q2, t, initial=0.0)
    frac = cum / cum[-1]
    t05, t45, t95 = np.interp([0.05, 0.45, 0.95], frac, t)
    assert t95 - t05 == pytest.approx(P.d5_95, rel=1e-4)  # trapezoid at dt = 5e-4 s
    assert t45 == pytest.approx(P.t_mid, rel=1e-4)
    assert math.pi / (2 * G) * cum[-1] == pytest.approx(P.arias, rel=1e-4)


def test_same_seed_same_record_and_nested_suites():
    a = sy.generate(P, 7)
    b = sy.generate(P, 7)
    np.testing.assert_array_equal(a.a, b.a)
    assert not np.array_equal(a.a, sy.generate(P, 8).a)
    small = sy.synthetic_motions(3, seed=4)
    big = sy.synthetic_motions(5, seed=4)
    for x, y in zip(small, big[:3], strict=True):
        assert x.name == y.name
        np.testing.assert_array_equal(x.a, y.a)


def test_ensemble_has_the_target_duration_arias_and_frequency():
    records = [sy.generate(P, s) for s in range(20)]
    d = np.mean([im.significant_duration(m) for m in records])
    ia = np.mean([im.arias(m) for m in records])
    assert d == pytest.approx(P.d5_95, rel=0.05)  # sample sd of the mean ~ 0.9/sqrt(20) s
    # Arias of the samples read as piecewise linear is E[(a0²+a0·a1+a1²)/3] = σ²(2+ρ)/3
    # with ρ ≈ 0.9 the lag-1 correlation at 5 Hz and 100 Hz sampling: ~4 % low
    assert ia == pytest.approx(P.arias, rel=0.08)
    # Rice: a filtered white noise with |H|² of an oscillator of frequency f crosses zero
    # 2f times a second; counted over t_mid ± 3 s (≈ 60 crossings a record, 20 records)
    rates = []
    for m in records:
        seg = m.a[(m.t > P.t_mid - 3) & (m.t < P.t_mid + 3)]
        rates.append(np.count_nonzero(np.diff(np.sign(seg)) != 0) / 6.0)
    assert np.mean(rates) == pytest.approx(2 * P.f_mid, rel=0.1)


def test_high_pass_removes_most_of_the_residual_velocity():
    # the filtered noise has content at 0 Hz (|H(0)| = 1/ω_f): its integral drifts. The
    # high-pass oscillator (time constant 1/ω_c = 0.8 s) is still decaying when the record
    # ends, so a few % of PGV remain (≤ 3.7 % for these seeds) against 18–92 % without it.
    with_hp, without = [], []
    for seed in range(6):
        a, b = sy.generate(P, seed), sy.generate(P, seed, f_corner=0.0)
        with_hp.append(abs(im.velocity(a)[1][-1]) / im.pgv(a))
        without.append(abs(im.velocity(b)[1][-1]) / im.pgv(b))
    assert max(with_hp) < 0.05
    assert np.mean(without) > 5 * np.mean(with_hp)


def test_synthetic_suite_of_fifty_records():
    s = ra.synthetic_suite(50, seed=1)
    assert len(s) == 50 and s.names[0] == "rdk-s1-000" and s.names[-1] == "rdk-s1-049"
    pgas = np.array([m.pga for m in s.motions])
    assert np.all(np.isfinite(pgas)) and np.all(pgas > 0)
    assert len(set(np.round(pgas, 9))) == 50  # 50 different records
    assert set(s[0].motion.meta) >= {"arias", "d5_95", "t_mid", "f_mid", "f_slope", "zeta_f"}


def _central_moments(dist):
    m1, m2, m3, m4 = (dist.moment(k) for k in (1, 2, 3, 4))
    var = m2 - m1**2
    mu4 = m4 - 4 * m1 * m3 + 6 * m1**2 * m2 - 3 * m1**4
    return m1, math.sqrt(var), mu4 / var**2


def test_parameter_draws_follow_the_published_rdk_2010_distributions():
    # The published marginals (RDK 2010 as coded in the SCEC Broadband Platform):
    # their means and sds in closed form, against the values quoted in issue 24.
    mg = sy.MARGINALS
    assert math.exp(mg["ln_arias"].median()) * G_STANDARD == pytest.approx(0.079, abs=5e-4)
    assert mg["d5_95"].mean() == pytest.approx(17.6, abs=0.06)
    assert mg["t_mid"].mean() == pytest.approx(12.45, abs=0.005)
    assert (mg["f_mid"].mean(), mg["f_mid"].std()) == pytest.approx((5.87, 2.90), abs=0.005)
    assert (mg["f_slope"].mean(), mg["f_slope"].std()) == pytest.approx((-0.089, 0.159),
                                                                        abs=5e-4)
    assert mg["zeta_f"].mean() == pytest.approx(0.215, abs=5e-4)
    # 2000 draws: each sample mean and sd within 4 standard errors of the distribution's:
    # SE(mean) = σ/√n, SE(sd) = σ √((κ − 1)/(4n)) with κ = μ4/σ⁴ (large-sample, exact
    # moments); the redrawn 4·10⁻⁵ of draws shift them by < 0.01 SE
    n = 2000
    rng = np.random.default_rng(24)
    draws = [sy.draw_parameters(rng) for _ in range(n)]
    samples = {k: np.array([getattr(d, k) for d in draws]) for k in mg if k != "ln_arias"}
    samples["ln_arias"] = np.log(np.array([d.arias for d in draws]) / G_STANDARD)
    for key, dist in mg.items():
        x = samples[key]
        mu, sd, kurt = _central_moments(dist)
        assert abs(x.mean() - mu) < 4 * sd / math.sqrt(n), key
        assert abs(x.std(ddof=1) - sd) < 4 * sd * math.sqrt((kurt - 1) / (4 * n)), key
        assert dist.cdf(x).min() > 0 and dist.cdf(x).max() < 1, key  # inside the support
    # the copula: correlation of the normal scores Φ⁻¹(F(θ)) within 4 SE, (1 − ρ²)/√n,
    # of the published matrix
    scores = np.column_stack([stats.norm.ppf(dist.cdf(samples[k])) for k, dist in mg.items()])
    rho = np.corrcoef(scores, rowvar=False)
    tol = 4 * (1 - sy.CORRELATION**2) / math.sqrt(n) + 1e-12
    assert np.all(np.abs(rho - sy.CORRELATION) <= tol), np.round(rho - sy.CORRELATION, 3)
    # the strongest published correlation (D5-95 with t_mid, 0.67) is not a chance result
    # of independent draws (SE 0.022)
    assert rho[1, 2] > 0.6


def test_two_sided_exponential_of_f_slope():
    d = sy.MARGINALS["f_slope"]
    total, _ = integrate.quad(d.pdf, -2.0, 0.5, points=[0.0])
    assert total == pytest.approx(1.0, abs=1e-9)
    assert d.mass == pytest.approx(1.0, abs=2e-5)  # the published constants, before scaling
    mean, _ = integrate.quad(lambda x: x * d.pdf(x), -2.0, 0.5, points=[0.0])
    assert d.mean() == pytest.approx(mean, abs=1e-9)  # closed form against quadrature
    u = np.linspace(0.0, 1.0, 1001)
    np.testing.assert_allclose(d.cdf(d.ppf(u)), u, atol=1e-12)
    assert d.ppf(0.0) == -2.0 and d.ppf(1.0) == pytest.approx(0.5, abs=1e-12)
    assert d.cdf(0.0) == pytest.approx(4.8512 / 6.7729 * (1 - math.exp(-13.5458)) / d.mass)


def test_draws_the_model_cannot_represent_are_redrawn():
    rng = np.random.default_rng(3)
    lo, hi = sy.ratio_bounds()
    for _ in range(200):
        p = sy.draw_parameters(rng, f_max=3.0)
        assert p.f_mid < 3.0 and lo < p.d5_95 / p.t_mid < hi
    with pytest.raises(ValueError, match="no representable"):
        sy.draw_parameters(rng, f_max=1e-9)


@pytest.mark.parametrize("kw, match", [
    ({"d5_95": 100.0, "t_mid": 1.0}, "cannot be represented"),
    ({"zeta_f": 1.0}, "zeta_f"),
    ({"arias": -1.0}, "Arias"),
])
def test_bad_parameters_give_one_clear_error(kw, match):
    with pytest.raises(ValueError, match=match):
        sy.generate(sy.RDKParameters(**{**P.to_dict(), **kw}), 0)
    with pytest.raises(ValueError, match="at least one"):
        sy.synthetic_motions(0)


def test_records_synth_writes_a_suite_that_records_info_reads(tmp_path):
    import json

    from typer.testing import CliRunner

    from rockarch.cli import app

    out = tmp_path / "suite"
    res = CliRunner().invoke(app, ["records", "synth", str(out), "--n", "3", "--seed", "5",
                                   "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["records"] == [f"rdk-s5-00{k}.AT2" for k in range(3)]
    s = ra.read_suite(out)
    assert s.names == ["rdk-s5-000.AT2", "rdk-s5-001.AT2", "rdk-s5-002.AT2"]
    for rec, m in zip(s, sy.synthetic_motions(3, seed=5), strict=True):
        # .AT2 keeps 7 significant digits of each value in g
        np.testing.assert_allclose(rec.motion.a, m.a, rtol=1e-6, atol=1e-7 * m.pga)
        assert rec.station == m.name and rec.event == "Synthetic RDK08 seed 5"
    params = (out / sy.PARAMETERS_FILE).read_text().splitlines()
    assert params[0].startswith("file,arias,d5_95") and len(params) == 4
    # the same command again rewrites the same files; fewer records, or another seed,
    # would leave records of the first run in the suite: refused
    again = ["records", "synth", str(out), "--seed", "5", "--n"]
    assert CliRunner().invoke(app, [*again, "3"]).exit_code == 0
    res = CliRunner().invoke(app, [*again, "2"])
    assert res.exit_code == 2 and "already holds 1 other record file" in res.stderr
    assert len(ra.read_suite(out).names) == 3
    (tmp_path / "f").write_text("a file in the way")
    res = CliRunner().invoke(app, ["records", "synth", str(tmp_path / "f" / "b")])
    assert res.exit_code == 2 and "is a file" in res.stderr
    res = CliRunner().invoke(app, ["records", "synth", str(tmp_path / "p"), "--n", "1",
                                   "--pulse-fraction", "1"])
    assert res.exit_code == 0, res.output
    head, row = (tmp_path / "p" / sy.PARAMETERS_FILE).read_text().splitlines()
    tp = dict(zip(head.split(","), row.split(","), strict=True))["pulse_tp"]
    assert 0.5 <= float(tp) <= 8.0
    res = CliRunner().invoke(app, ["records", "synth", str(tmp_path / "q"),
                                   "--pulse-fraction", "2"])
    assert res.exit_code == 2 and "pulse fraction" in res.stderr


def test_mavroeidis_papageorgiou_pulse_acceleration_integrates_to_its_velocity():
    pulse = sy.MPPulse(tp=1.3, amplitude=0.5, gamma=2.0, nu=0.7, t0=3.0)
    t = np.arange(0.0, 8.0, 0.001)
    base = GroundMotion(t, 1e-12 * np.sin(t))  # a (nearly) silent record to add it to
    m = sy.add_pulse(base, pulse)
    _, v = im.velocity(m)
    # trapezoid integration of the closed-form derivative at 1 ms: error ~ (k dt)²/12 · A
    np.testing.assert_allclose(v, pulse.velocity(m.t), atol=1e-5)
    assert np.max(np.abs(v)) <= pulse.amplitude


def test_baker_finds_the_pulses_of_a_pulse_like_synthetic_suite():
    # all records carry an MP pulse: Baker's method classifies most as pulses, with Tp
    # ~10 % above the MP period (db4's pseudo-period; 27 of 30 and median 1.10 for 30
    # records, measured); the same records without pulses give none
    from rockarch.motion.velocity_pulse import baker_pulse

    with_pulse = sy.synthetic_motions(6, seed=3, pulse_fraction=1.0)
    found = [baker_pulse(m) for m in with_pulse]
    assert sum(r.pulse_like for r in found) >= 5
    ratio = np.median([r.tp / m.meta["pulse_tp"] for r, m in zip(found, with_pulse,
                                                                  strict=True)])
    assert 1.0 <= ratio <= 1.2
    plain = sy.synthetic_motions(3, seed=3)
    assert not any(baker_pulse(m).pulse_like for m in plain)
    for a, b in zip(plain, with_pulse[:3], strict=True):  # same noise part
        pulse = sy.MPPulse(**{k: b.meta[f"pulse_{k}"]
                              for k in ("tp", "amplitude", "gamma", "nu", "t0")})
        np.testing.assert_allclose(a.a, b.a[:a.a.size] - pulse.acceleration(a.t), rtol=0,
                                   atol=1e-12)
