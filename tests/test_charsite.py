"""Characteristic site OAS (docs/theory.md Sect. 11.2): the two durations of closed-form
pulses, the rectangular-pulse closed form against the exact block, the simplified and
normalised curves."""

import math

import numpy as np
import pytest

import rockarch as ra
from rockarch.spectra import characteristic as cs


def test_durations_of_a_rectangular_pulse_are_its_duration():
    d = cs.pulse_durations(ra.pulse("step", period=0.8, ap=3.0))
    # v is linear on the one step: the trapezoidal moment is exact
    assert d.t_impulse == pytest.approx(0.8, rel=1e-12)
    assert d.t_moment == pytest.approx(0.8, rel=1e-12)
    assert (d.t_start, d.t_end, d.impulse) == (0.0, 0.8, pytest.approx(2.4))


def test_durations_of_a_sine_pulse():
    # a = A sin(2πt/T): I = AT/π over [0, T/2], M = AT²/(4π) -> t_I = T/π, t_M = T/√(2π);
    # 1000 knots per period: the trapezoidal error of the moment is O((T/1000)²) ~ 1e-6
    d = cs.pulse_durations(ra.pulse("sine", period=0.8))
    assert d.t_impulse == pytest.approx(0.8 / math.pi, rel=1e-5)
    assert d.t_moment == pytest.approx(0.8 / math.sqrt(2 * math.pi), rel=1e-5)
    # either lobe (equal impulses): half a period
    assert d.t_end - d.t_start == pytest.approx(0.4)
    # the mirrored pulse has the same durations
    m = cs.pulse_durations(ra.pulse("sine", period=0.8).scaled(-1.0))
    assert m.t_impulse == pytest.approx(d.t_impulse) and m.t_moment == pytest.approx(d.t_moment)


def test_rectangular_pulse_closed_form_matches_the_exact_block():
    # Eq. (11.11) linearises the block: the exact (nonlinear) boundary differs by O(alpha²);
    # measured < 3e-4 at alpha = 0.05, plus the bisection tolerance 2e-4 -> 1e-3
    sys_ = ra.system("block", alpha=0.05)  # 10 s free: time to reach alpha
    p = np.array([1.0, 4.0])
    ds = ra.oas(sys_, ra.pulse("step", period=0.5), p=p,
                ratio=np.round(np.linspace(1, 5, 81), 12), tol=2e-4)
    assert ds["boundary"].values == pytest.approx(cs.rectangular_pulse_boundary(p, 0.5),
                                                  rel=1e-3)


def test_simplified_boundary_branches():
    p = np.array([0.01, 3.0, 100.0])
    r = cs.simplified_boundary(p, 0.2, 0.4)
    assert r[0] == pytest.approx(1 / -math.expm1(-0.002))  # no impact: ~1/(p t_I)
    assert r[1] == pytest.approx(cs.IMPACT_COEFF / (3 * 0.4) ** 2)  # after impact
    assert r[2] == 1.0  # no uplift below ap,min
    assert np.all(np.diff(cs.simplified_boundary(np.geomspace(0.1, 50, 50), 0.2, 0.4)) <= 0)


def test_normalised_curve_collapses_similar_records():
    # boundaries that are one function of p·Tm: the normalised median is that function
    p = np.geomspace(0.5, 10, 30)
    tm = np.array([0.3, 0.6, 1.2])
    f = lambda x: 1 + 2 / x  # noqa: E731
    b = np.stack([f(p * s) for s in tm])
    x, curve = cs.normalised_curve(b, p, tm)
    inside = (x >= p[0] * tm.max()) & (x <= p[-1] * tm.min())
    # log-log interpolation of a smooth function on 30 points per decade-and-a-bit
    assert curve[inside] == pytest.approx(f(x[inside]), rel=2e-3)


def test_characteristic_and_skill_on_a_small_site():
    from rockarch.motion.intensity import mean_period
    from rockarch.spectra import site

    motions = [ra.GroundMotion(m.t[:1500], m.a[:1500], m.name)
               for m in (ra.el_centro(180), ra.el_centro(270))]
    p = np.geomspace(1.0, 8.0, 6)
    ds = site.site_oas(motions, p, np.round(np.linspace(1, 5, 17), 12), t_free=3.0,
                       progress=False, tol=1e-2)
    out = cs.characteristic(ds, motions)
    assert out["tm"].values == pytest.approx([mean_period(m) for m in motions])
    d = cs.pulse_durations(motions[1])
    assert out["t_impulse"].values[1] == d.t_impulse
    assert np.array_equal(out["simplified_record"].values[1],
                          cs.simplified_boundary(p, d.t_impulse, d.t_moment, 0.05))
    # the site curves are percentiles over records: between the records' lowest and highest
    for name in ("simplified",):
        vals = out[name].values
        rec = out["simplified_record"].values
        assert np.all((rec.min(axis=0) <= vals) & (vals <= rec.max(axis=0)))
    assert np.isfinite(out["normalised"].values).any()
    sk = cs.skill(out)
    assert sk["pairs"] + sk["censored_pairs"] == 12
    for name in ("raw", "normalised", "simplified"):
        assert 0 <= sk[name]["safe"] <= 1 and sk[name]["dispersion"] >= 0
    with pytest.raises(ValueError, match="has 2 records"):
        cs.characteristic(ds, motions[:1])


@pytest.mark.slow
def test_site_file_holds_the_new_curves_and_design_reads_them(tmp_path):
    import json

    from typer.testing import CliRunner

    from rockarch.cli import app
    from rockarch.motion.records import bundled_record_path
    from rockarch.motion.suite import write_at2
    from rockarch.spectra import site

    runner = CliRunner()
    out = tmp_path / "s.nc"
    for c in (180, 270):  # the first 10 s of El Centro (fast)
        m = ra.read_record(bundled_record_path(c))
        write_at2(tmp_path / f"elc{c}.AT2", ra.GroundMotion(m.t[:1000], m.a[:1000]))
    res = runner.invoke(app, ["site-oas", "--records", str(tmp_path), "--p-min", "1",
                              "--p-max", "4", "--p-steps", "4", "--ratio-steps", "11",
                              "--t-free", "2", "--tol", "0.05", "--out", str(out)])
    assert res.exit_code == 0, res.output
    ds = site.load(out)
    for name in ("normalised", "simplified", "tm", "t_impulse", "t_moment"):
        assert name in ds
    for curve in ("normalised", "simplified"):
        res = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise",
                                  "5", "--thickness", "1", "--site", str(out), "--curve",
                                  curve, "--json"])
        assert res.exit_code == 0, res.output
        js = json.loads(res.stdout)
        assert js["ratio"] == site.curve_at(ds, js["replacement"]["p"], curve)[0]


def test_a_record_without_mean_period_is_left_out_of_the_normalised_curve():
    from rockarch.spectra import site

    m = ra.el_centro()
    long = ra.GroundMotion(m.t[:500], m.a[:500], "El Centro 5 s")
    tiny = ra.GroundMotion([0.0, 0.01, 0.02], [0.0, 1.0, 0.0], "20 ms blip")  # no Tm band
    ds = site.site_oas([long, tiny], [2.0, 4.0], [1.0, 2.0, 3.0], t_free=1.0,
                       progress=False, tol=0.0)
    out = cs.characteristic(ds, [long, tiny])
    assert np.isfinite(out["tm"].values[0]) and np.isnan(out["tm"].values[1])
    assert np.isfinite(out["t_impulse"].values).all()
    sk = cs.skill(out)
    assert sk["raw"]["pairs"] >= 0 and sk["normalised"]["pairs"] <= 2
