"""A long single simulation shows how far it has got (mdof.simulate, ``progress``): the
kernel runs in a thread, its recorded times read while it runs; the result is unchanged."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from rockarch import mdof
from rockarch.mdof import builders as bd
from rockarch.motion import signals as motion

ms = importlib.import_module("rockarch.mdof.simulate")  # the module, not mdof.simulate()


@pytest.fixture(scope="module")
def case():
    wall = bd.wall(3, 4, 0.4, 0.2, mu=0.6)
    return wall, motion.pulse("sine", period=1.0, ap=1.3 * wall.ap_min)


def test_progress_bar_on_request_and_the_same_history(case, capsys, monkeypatch):
    wall, ground = case
    plain = mdof.simulate(wall, ground, t_free=1.0, progress=False)
    assert capsys.readouterr().err == ""
    monkeypatch.setattr(ms, "PROGRESS_AFTER", 0.0)  # every run is "long"
    shown = mdof.simulate(wall, ground, t_free=1.0, progress=True)
    err = capsys.readouterr().err
    assert "simulating" in err and f"of {ground.duration + 1.0:.2f} s" in err
    np.testing.assert_array_equal(shown.q, plain.q)
    assert shown.to_dict() == plain.to_dict()


def test_no_bar_off_a_terminal(case, capsys, monkeypatch):
    # progress None: only on a terminal; pytest's captured stderr is not one
    wall, ground = case
    monkeypatch.setattr(ms, "PROGRESS_AFTER", 0.0)
    mdof.simulate(wall, ground, t_free=0.5)
    assert capsys.readouterr().err == ""


def test_an_error_in_the_kernel_reaches_the_caller(case, monkeypatch):
    wall, ground = case
    monkeypatch.setattr(ms, "PROGRESS_AFTER", 0.0)

    def broken(*args):
        raise ValueError("from the kernel")

    broken.signatures = ["compiled"]  # as a numba dispatcher that has machine code
    monkeypatch.setattr(ms._g, "run", broken)
    with pytest.raises(ValueError, match="from the kernel"):
        mdof.simulate(wall, ground, t_free=0.5, progress=True)
