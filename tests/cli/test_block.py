"""CLI contract of `rockarch oas` and `rockarch simulate block` (issue 2), and bad input."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.motion.records import el_centro

runner = CliRunner()
REC = "src/rockarch/motion/data/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"


def _json(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_oas_json_contract():
    out = _json(["oas", "--system", "block", "--alpha", "0.1", "--signal", "sine",
                 "--period", "0.5", "--p", "0.5,1,2,4", "--ratio-min", "1", "--ratio-max",
                 "5", "--ratio-steps", "81", "--json"])
    assert set(out) == {"p", "ratio", "overturned", "boundary"}
    assert out["p"] == [0.5, 1.0, 2.0, 4.0]
    assert len(out["ratio"]) == 81 and out["ratio"][0] == 1.0 and out["ratio"][-1] == 5.0
    assert np.array(out["overturned"]).shape == (4, 81)
    assert out["boundary"][0] is None  # p = 0.5 never overturns below 5 ap,min
    for row, b in zip(out["overturned"], out["boundary"], strict=True):
        if b is not None:
            k = row.index(True)
            assert out["ratio"][max(k - 1, 0)] < b <= out["ratio"][k]


def test_oas_record_grid_files(tmp_path):
    nc, png = tmp_path / "o.nc", tmp_path / "o.png"
    out = _json(["oas", "--alpha", "0.1", "--record", REC, "--p-min", "1", "--p-max", "5",
                 "--p-steps", "5", "--ratio-steps", "11", "--out", str(nc), "--plot",
                 str(png), "--restitution", "0.95", "--t-free", "5", "--g", "9.81", "--json"])
    assert out["p"] == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert nc.stat().st_size > 0 and png.read_bytes()[:4] == b"\x89PNG"


def test_simulate_block_json_contract_and_plot(tmp_path):
    png = tmp_path / "s.png"
    out = _json(["simulate", "block", "--alpha", "0.15", "--p", "2", "--signal", "sine",
                 "--period", "1", "--ratio", "2", "--json", "--plot", str(png)])
    assert set(out) == {"overturned", "t_overturn", "max_theta_over_alpha", "max_rotation_ratio",
                        "impacts", "p", "alpha", "width", "height", "ap_min", "restitution"}
    assert out["overturned"] is True and 0 < out["t_overturn"] < 11
    # the block the text header describes: ap,min = g tan(alpha), p² = 3g/(4R) (Housner)
    assert out["ap_min"] == pytest.approx(9.81 * np.tan(0.15), rel=1e-12)
    half_diag = np.hypot(out["width"], out["height"]) / 2
    assert out["p"] ** 2 == pytest.approx(3 * 9.81 / (4 * half_diag), rel=1e-12)
    assert png.exists()
    safe = _json(["simulate", "block", "--alpha", "0.15", "--p", "2", "--record", REC,
                  "--ratio", "0.99", "--json"])
    assert {k: safe[k] for k in ("overturned", "t_overturn", "max_theta_over_alpha",
                                 "max_rotation_ratio", "impacts")} == {
        "overturned": False, "t_overturn": None, "max_theta_over_alpha": 0.0,
        "max_rotation_ratio": 0.0, "impacts": 0}


def test_record_scaling_in_cli_matches_api():
    from rockarch.rocking.block import RigidBlock, simulate

    out = _json(["simulate", "block", "--alpha", "0.1", "--p", "3", "--record", REC,
                 "--ratio", "1.3", "--json"])
    b = RigidBlock(3.0, 0.1)
    rec = el_centro()
    api = simulate(b, rec.scaled_to_pga(1.3 * b.ap_min)).to_dict()
    assert {k: out[k] for k in api} == json.loads(json.dumps(api))
    assert (out["p"], out["alpha"], out["ap_min"]) == (3.0, 0.1, b.ap_min)


def test_single_column_record_with_dt_is_the_record(tmp_path):
    """El Centro's accelerations in g, 5 a line, through --record FILE --dt 0.01 --units g:
    the response of the .AT2 file (the samples agree within a few units of the last digit,
    tests/test_records.py; the rotation within 1e-6 leaves room for the chaotic rocking to
    amplify them); a bad --dt is one line, exit 2."""
    g = el_centro().a / 9.80665
    rec = tmp_path / "elcentro_g.txt"
    rec.write_text("".join(" ".join(f"{v:.17g}" for v in g[k:k + 5]) + "\n"
                           for k in range(0, g.size, 5)))
    args = ["simulate", "block", "--alpha", "0.15", "--p", "2", "--ratio", "1.3", "--json"]
    got = _json([*args, "--record", str(rec), "--dt", "0.01", "--units", "g"])
    ref = _json([*args, "--record", REC])
    assert got["max_rotation_ratio"] == pytest.approx(ref["max_rotation_ratio"], rel=1e-6)
    assert (got["overturned"], got["ap_min"]) == (ref["overturned"], ref["ap_min"])
    for dt, msg in (("0", "dt (--dt) must be a finite time step > 0 in seconds, got 0"),
                    ("nan", "got nan"), ("10", "dt is in seconds"),
                    ("x", "Invalid value for '--dt'")):
        res = runner.invoke(app, [*args, "--record", str(rec), "--dt", dt, "--units", "g"])
        assert res.exit_code == 2 and res.stdout == "", (dt, res.output)
        assert res.stderr.count("\n") == 1 and res.stderr.startswith("error: "), res.stderr
        assert msg in res.stderr and "Traceback" not in res.stderr
    res = runner.invoke(app, [*args, "--record", str(rec), "--units", "g"])
    assert res.exit_code == 2 and "give their time step (--dt, dt= in Python)" in res.stderr


@pytest.mark.parametrize(
    "args, msg",
    [
        (["oas", "--alpha", "0.1", "--signal", "sine", "--p", "1"], "needs --period"),
        (["oas", "--alpha", "2", "--signal", "sine", "--period", "1", "--p", "1"], "alpha"),
        (["oas", "--alpha", "0.1", "--signal", "sine", "--period", "1", "--p", "0,1"], "p"),
        (["oas", "--alpha", "0.1", "--signal", "sine", "--period", "1"], "give the p values"),
        (["oas", "--alpha", "0.1", "--signal", "sine", "--period", "1", "--p", "1",
          "--restitution", "1.5"], "restitution"),
        (["oas", "--alpha", "0.1", "--record", "/no/such.AT2", "--p", "1"], "no such file"),
        (["oas", "--alpha", "0.1", "--p", "1"], "give a ground motion"),
        (["simulate", "block", "--alpha", "0.1", "--p", "-1", "--signal", "step",
          "--period", "1", "--ratio", "2"], "p must"),
        (["simulate", "block", "--width", "0", "--height", "1", "--signal", "step",
          "--period", "1", "--ratio", "2"], "width B"),
        # simulate block has no --system: the line names the option given (it said
        # "--system block needs --height")
        (["simulate", "block", "--width", "0.4", "--signal", "step", "--period", "1",
          "--ratio", "2"], "error: --width needs --height (keywords: height)"),
        (["simulate", "block", "--height", "2", "--signal", "step", "--period", "1",
          "--ratio", "2"], "error: --height needs --width (keywords: width)"),
        (["simulate", "block", "--alpha", "0.1", "--p", "1", "--signal", "step",
          "--period", "-1", "--ratio", "2"], "period T"),
    ],
)
def test_bad_input_exits_2_with_one_line(args, msg):
    res = runner.invoke(app, args)
    assert res.exit_code == 2
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:") and msg in lines[0]


def test_bad_record_file_exits_2(tmp_path):
    bad = tmp_path / "bad.AT2"
    bad.write_text("PEER\nx\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= .01 SEC\n1 2\n")
    nc = tmp_path / "o.nc"
    res = runner.invoke(app, ["oas", "--alpha", "0.1", "--record", str(bad), "--p", "1",
                              "--out", str(nc)])
    assert res.exit_code == 2 and "NPTS=3" in res.stderr
    assert not nc.exists()  # nothing half-written


def test_oas_messages_say_what_is_wrong():
    # a negative p among others is named as such (before: "must be strictly increasing")
    res = runner.invoke(app, ["oas", "--alpha", "0.1", "--signal", "sine", "--period", "0.5",
                              "--p", "1,-2"])
    assert res.exit_code == 2 and res.stderr == "error: p values must be > 0 [1/s], got -2\n"
    # a generic SDOF's own p (default 1) is not printed as the OAS's (p is the table's axis)
    res = runner.invoke(app, ["oas", "--system", "sdof", "--delta", "0.1", "--ap-min", "1",
                              "--signal", "sine", "--period", "0.5", "--p", "3,5"])
    assert res.exit_code == 0
    assert res.stdout.startswith("OAS of SDOF delta=0.1 rad, ap,min=1 m/s² for sine")
    # a ring too thick for four hinges: the reason once ("no four-hinge mechanism" was twice)
    res = runner.invoke(app, ["simulate", "fourhinge", "--shape", "catenary", "--span", "10",
                              "--rise", "3", "--thickness", "3", "--signal", "sine",
                              "--period", "0.5", "--ratio", "1"])
    assert res.exit_code == 2 and res.stderr.count("no four-hinge mechanism") == 1
