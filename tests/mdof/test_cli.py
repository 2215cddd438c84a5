"""CLI contract of the MDOF model (issue 5): simulate mdof, oas --system mdof, animate."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app

runner = CliRunner()
ARCH = ["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.25"]


def _json(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_simulate_mdof_contract():
    keys = {"overturned", "t_overturn", "max_theta_over_alpha", "max_rotation_ratio", "impacts",
            "open_joints_max"}
    safe = _json(["simulate", "mdof", *ARCH, "--blocks", "20", "--signal", "sine",
                  "--period", "1", "--ratio", "0.9", "--json"])
    assert keys <= set(safe) and "ap_min" in safe
    assert safe["overturned"] is False and safe["t_overturn"] is None
    assert safe["open_joints_max"] == 0 and safe["impacts"] == 0
    over = _json(["simulate", "mdof", *ARCH, "--blocks", "20", "--signal", "sine",
                  "--period", "1", "--ratio", "3", "--json"])
    assert over["overturned"] is True and over["t_overturn"] > 0
    assert over["open_joints_max"] >= 4


def test_simulate_mdof_column_and_record(tmp_path):
    rec = tmp_path / "r.txt"
    t = np.arange(0, 2, 0.01)
    np.savetxt(rec, np.c_[t, np.sin(2 * np.pi * t)])
    out = _json(["simulate", "mdof", "--column", "0.3,1;0.12,1", "--record", str(rec),
                 "--ratio", "1.5", "--json"])
    assert isinstance(out["overturned"], bool)


def test_oas_mdof_contract():
    out = _json(["oas", "--system", "mdof", "--shape", "catenary", "--rise-over-span", "0.3",
                 "--thickness-over-span", "0.025", "--blocks", "12", "--signal", "sine",
                 "--period", "1", "--p", "2,6", "--ratio-steps", "9", "--json", "--no-store"])
    assert set(out) == {"p", "ratio", "overturned", "boundary"}
    assert np.array(out["overturned"]).shape == (2, 9)
    assert not any(row[0] for row in out["overturned"])  # ratio 1: nothing collapses


def test_animate_writes_gif(tmp_path):
    gif = tmp_path / "motion.gif"
    res = runner.invoke(app, ["animate", *ARCH, "--blocks", "10", "--signal", "sine",
                              "--period", "1", "--ratio", "1.5", "--t-free", "0.5",
                              "--frames", "8", "--out", str(gif)])
    assert res.exit_code == 0, res.output
    assert gif.read_bytes()[:3] == b"GIF"


@pytest.mark.parametrize("args, msg", [
    ([*ARCH, "--blocks", "3"], "at least 5"),
    ([*ARCH, "--blocks", "20", "--h-factor", "0.5"], "h_factor"),
    ([*ARCH, "--blocks", "20", "--gap-tol", "0.01"], "gap_tol"),
    (["--column", "1,1;1,1,3"], "contact face"),
    ([*ARCH], "--blocks"),
])
def test_bad_input_exit_2(args, msg):
    res = runner.invoke(app, ["simulate", "mdof", *args, "--signal", "sine", "--period", "1",
                              "--ratio", "1.5"])
    assert res.exit_code == 2
    assert msg in res.stderr and len(res.stderr.strip().splitlines()) == 1


def test_bad_oas_mdof_input():
    res = runner.invoke(app, ["oas", "--system", "mdof", "--shape", "catenary",
                              "--rise-over-span", "0.3", "--thickness-over-span", "0.025",
                              "--signal", "sine", "--period", "1", "--p", "2"])
    assert res.exit_code == 2 and "--blocks" in res.stderr
