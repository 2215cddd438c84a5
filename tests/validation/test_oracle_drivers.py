"""The rockarch side of the oracle drivers of ``make validate`` (validation/*_compare.py).

The comparisons themselves need Siconos and LMGC90 and run only in ``make validate``; this
checks, on every machine, that the drivers still call rockarch's API correctly (a driver
once stopped at its time history because ``pulse`` had begun to refuse an argument it
passed). The oracles are replaced by stubs: nothing here compares physics.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

VALIDATION = Path(__file__).resolve().parents[2] / "validation"


def _load(name: str):
    spec = importlib.util.spec_from_file_location(name, VALIDATION / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_lmgc90_driver_time_history(monkeypatch, capsys):
    drv = _load("lmgc90_compare")
    sent = []

    def oracle(python, case):  # LMGC90's answer: a block that stays put
        sent.append(case)
        return {"max_rotation": 0.0, "displacement": 0.0}

    monkeypatch.setattr(drv, "_run", oracle)
    drv.time_history("python")
    out = capsys.readouterr().out
    assert out.count("time history:") == 2
    # the ground the oracle is driven by: the velocity of a one-cycle sine pulse, back to
    # ~0 at its end (the integral of a full sine period), then held
    for case in sent:
        v = np.asarray(case["ground"]["v"])
        assert abs(v[-1]) < 1e-3 * np.max(np.abs(v))
    names = [c[0] for c in drv.cases(quick=True)]
    assert any("wall 4 x 3" in n for n in names)


def test_lmgc90_driver_arch_history(monkeypatch, capsys):
    drv = _load("lmgc90_compare")
    sent = []

    def oracle(python, case):  # LMGC90's answer: every voussoir at rest, 3 records
        sent.append(case)
        n = len(case["polygons"])
        return {"history": [[t, 0.0, 0.0] + [0.0] * n for t in (0.0, 0.1, 0.2)]}

    monkeypatch.setattr(drv, "_run", oracle)
    drv.arch_history("python")
    out = capsys.readouterr().out
    assert out.count("thick arch") == 2
    # rockarch's voussoirs rotate, LMGC90's stub does not: 100 % of the largest rotation
    assert "100.00 %" in out
    quads, sups = drv.thick_arch()
    assert all(c["polygons"] == quads and c["supports"] == sups for c in sent)


def test_siconos_driver_cases_serialise():
    drv = _load("siconos_compare")
    n = 0
    for name, a, m, h_factor in [*drv.cases(), *drv.more_cases()]:
        case = drv.case_json(a, m, h_factor / a.p_ref, float(m.t[-1]))
        json.dumps(case)  # what goes to the oracle's process
        assert len(case["mass"]) == a.mass.shape[0], name
        n += 1
    assert n == 6 + 8


def test_siconos_driver_refuses_bad_options(capsys):
    drv = _load("siconos_compare")
    for argv in (["--more", "--until", "-1"], ["--convergence", "--gap-tol", "1"]):
        with pytest.raises(SystemExit) as e:
            drv.main(argv)
        assert e.value.code == 2
        assert "error:" in capsys.readouterr().err
