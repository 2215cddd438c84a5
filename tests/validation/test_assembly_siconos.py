"""The Siconos oracle's input (validation/siconos_oracle.py) and, where Siconos is installed
for /usr/bin/python3, one time history against rockarch (the rest: ``make validate``)."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.core.constants import G
from rockarch.mdof import builders as bd
from rockarch.motion import signals as motion

ROOT = Path(__file__).resolve().parents[2]


def _load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "validation" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_oracle_contacts_start_closed():
    # every corner contact the oracle builds has zero gap in the reference configuration:
    # the corner seen from body b and from body a (or the ground) is the same point
    oracle, compare = _load("siconos_oracle"), _load("siconos_compare")
    a = bd.bridge(catenary(10.0, 3.0, 0.25), 10, spans=2, pier_height=3.0, pier_width=1.0,
                  mu=0.6)
    case = compare.case_json(a, motion.pulse("sine", period=1.0), 1e-3, 1.0)
    contacts = oracle._contacts(case)
    assert len(contacts) == 2 * a.n_joints
    cen = np.asarray(case["centroid"])
    for c in contacts:
        pa = np.asarray(c["ra"]) + (cen[c["a"]] if c["a"] >= 0 else 0.0)
        pb = np.asarray(c["rb"]) + cen[c["b"]]
        assert np.allclose(pa, pb, atol=1e-12) and c["b"] >= 0
        assert c["mu"] == pytest.approx(0.6)


def _siconos() -> bool:
    try:
        return subprocess.run(["/usr/bin/python3", "-c", "import siconos.kernel"],
                              capture_output=True, timeout=60).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


@pytest.mark.slow
@pytest.mark.skipif(not _siconos(), reason="python3-siconos not installed (make validate)")
def test_sliding_rocking_block_against_siconos(tmp_path):
    compare = _load("siconos_compare")
    blk = bd.with_friction(mdof.single_block(0.5, 2.0), 0.28)
    m = motion.pulse("sine", period=1.5, ap=0.7 * G)
    ok, line = compare.compare("slide-rock block", blk, m, tmp_path)
    print(line)
    assert ok, line  # within compare.TOL = 5 % (docs/validation.md: 1.7 % / 3.2 %)
