"""Memory and work bounds (rockarch.core.limits): known before the work, exact verdicts."""

import re

import numpy as np
import pytest

from rockarch.core import limits
from rockarch.mdof.simulate import _plan
from rockarch.motion import signals as motion
from rockarch.rocking.block import RigidBlock, simulate
from rockarch.rocking.mechanism import from_block
from rockarch.rocking.mechanism import simulate as mech_simulate


@pytest.fixture
def rocking():
    """A block rocking for ~30 s with ~100 impacts on a harmonic (no overturning)."""
    blk = RigidBlock(2.0, 0.15)
    return blk, motion.harmonic(1.3 * blk.ap_min, 1.0, 3)


def test_decimated_history_keeps_the_verdict(rocking, monkeypatch):
    blk, mot = rocking
    full = simulate(blk, mot, t_free=20)
    assert full.stride == 1 and full.impacts > 20 and not full.overturned
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "300")
    dec = simulate(blk, mot, t_free=20)
    # the integration does not depend on the recording: every summary number is equal
    assert dec.to_dict() == full.to_dict() and dec.t_end == full.t_end
    assert dec.stride > 1 and dec.t.size <= 300
    assert set(dec.t.tolist()) <= set(full.t.tolist())  # a subset of the full history
    assert np.all(np.diff(dec.t) > 0)
    assert dec.impact_times.size == min(300, full.impacts)


def test_decimated_history_keeps_the_collapse_state(monkeypatch):
    blk = RigidBlock(2.0, 0.15)
    mot = motion.sine(2.0 * blk.ap_min, 1.0)
    full = simulate(blk, mot)
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "40")
    dec = simulate(blk, mot)
    assert dec.overturned and dec.t_overturn == full.t_overturn and dec.stride > 1
    assert dec.t[-1] == full.t[-1] and dec.theta[-1] == full.theta[-1]


def test_mechanism_history_decimated_too(rocking, monkeypatch):
    blk, mot = rocking
    mech = from_block(blk.p, blk.alpha)
    full = mech_simulate(mech, mot, t_free=20)
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "300")
    dec = mech_simulate(mech, mot, t_free=20)
    assert dec.to_dict() == full.to_dict() and dec.stride > 1 and dec.t.size <= 300


def test_steps_refused_before_the_work(rocking):
    blk, mot = rocking
    # (3 s + 1e9 s)·p/h = 4e10 RK4 steps at most: refused at once, naming the variable
    with pytest.raises(ValueError, match="ROCKARCH_MAX_STEPS"):
        simulate(blk, mot, t_free=1e9)


def test_motion_knots_refused_before_allocation(monkeypatch):
    with pytest.raises(ValueError, match=r"needs 1e\+09 samples.*ROCKARCH_MAX_SAMPLES"):
        motion.harmonic(1.0, 1.0, 1_000_000)
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "2e9")
    assert limits.max_samples() == 2_000_000_000
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "-3")
    with pytest.raises(ValueError, match="positive integer"):
        limits.max_samples()


def test_mdof_plan():
    # 10 s at h = 1e-3: 10^4 steps, recorded every step (the history is small)
    assert _plan(10.0, 1e-3, 20, 21, 1) == (10_000, 1)
    # 1e7 steps of 20 blocks (~500 bytes each) would be 5 GB: every k-th step recorded
    n, rec = _plan(1e4, 1e-3, 20, 21, 1)
    assert n == 10_000_000 and n // rec * (8 * 62 + 21) <= limits.MAX_HISTORY_BYTES
    with pytest.raises(ValueError, match="ROCKARCH_MAX_MDOF_STEPS"):
        _plan(1e9, 1e-3, 20, 21, 1)


def test_p_above_its_bound_is_one_clear_error():
    with pytest.raises(ValueError, match="p must lie in"):
        RigidBlock(1e300, 0.1)


def test_cli_says_when_the_history_is_decimated(monkeypatch):
    from typer.testing import CliRunner

    from rockarch.cli import app

    # a square pulse has 4 knots, so only the history (~170 impacts) meets the limit
    argv = ["simulate", "block", "--alpha", "0.15", "--p", "2", "--signal", "square",
            "--period", "0.3", "--ratio", "1.5", "--t-free", "20"]
    full = CliRunner().invoke(app, argv)
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "300")
    dec = CliRunner().invoke(app, argv)
    assert full.exit_code == dec.exit_code == 0
    # the same summary lines, and one line more that says how the history was thinned
    extra = dec.stdout.splitlines()[len(full.stdout.splitlines()):]
    assert dec.stdout.startswith(full.stdout) and len(extra) == 1
    assert re.fullmatch(r"history: every \d+th step kept \(ROCKARCH_MAX_SAMPLES\)", extra[0])
