"""CLI contract for the SDOF mechanisms (issue 4): oas/simulate for fourhinge, frame, sdof."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app

runner = CliRunner()


def _json(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_oas_fourhinge_contract():
    out = _json(["oas", "--system", "fourhinge", "--shape", "catenary", "--rise-over-span",
                 "0.3", "--thickness-over-span", "0.025", "--signal", "sine", "--period",
                 "0.5", "--p", "2,4,8", "--ratio-steps", "41", "--json"])
    assert set(out) == {"p", "ratio", "overturned", "boundary"}
    assert np.array(out["overturned"]).shape == (3, 41)
    b = [x for x in out["boundary"] if x is not None]
    assert b and all(1.0 < x <= 5.0 for x in b)


@pytest.mark.parametrize("extra", [["--system", "frame", "--alpha", "0.1", "--mass-ratio",
                                    "0.5"],
                                   ["--system", "sdof", "--delta", "0.1", "--ap-min", "1.0"]])
def test_oas_other_mechanisms(extra):
    out = _json(["oas", *extra, "--signal", "step", "--period", "1", "--p", "1,3",
                 "--ratio-steps", "21", "--json"])
    assert len(out["boundary"]) == 2


def test_simulate_fourhinge_frame_sdof(tmp_path):
    keys = {"overturned", "t_overturn", "max_theta_over_alpha", "max_rotation_ratio", "impacts",
            "p", "ap_min", "restitution"}
    png = tmp_path / "fh.png"
    out = _json(["simulate", "fourhinge", "--shape", "catenary", "--span", "10", "--rise",
                 "3", "--thickness", "0.25", "--signal", "sine", "--period", "1", "--ratio",
                 "2", "--json", "--plot", str(png)])
    assert set(out) == keys | {"delta_u"} and out["overturned"] is True and png.exists()
    # what the text header prints (an arch's delta_u: the dynamics' coordinate)
    assert out["p"] == pytest.approx(3.55, abs=0.005) and out["delta_u"] > 0
    out = _json(["simulate", "fourhinge", "--shape", "catenary", "--span", "10", "--rise",
                 "3", "--thickness", "0.25", "--blocks", "20", "--signal", "sine",
                 "--period", "1", "--ratio", "0.99", "--json"])
    assert {k: out[k] for k in keys - {"p", "ap_min", "restitution"}} == {
        "overturned": False, "t_overturn": None, "max_theta_over_alpha": 0.0,
        "max_rotation_ratio": 0.0, "impacts": 0}
    out = _json(["simulate", "frame", "--alpha", "0.15", "--p", "2", "--mass-ratio", "0.5",
                 "--signal", "square", "--period", "1", "--ratio", "1.5", "--json"])
    assert set(out) == keys | {"delta"}
    out = _json(["simulate", "sdof", "--p", "2", "--delta", "0.1", "--ap-min", "1",
                 "--signal", "step", "--period", "1", "--ratio", "1.5", "--json"])
    # step impulse, linear equivalence form: overturns iff ratio ≥ 1/(1 − e^{−pT}) = 1.157
    assert out["overturned"] is True
    assert (out["p"], out["delta"], out["ap_min"]) == (2.0, 0.1, 1.0)  # as given


@pytest.mark.parametrize(
    "args, msg",
    [
        (["oas", "--system", "fourhinge", "--shape", "catenary", "--signal", "sine",
          "--period", "1", "--p", "1"], "needs --rise-over-span, --thickness-over-span"),
        (["oas", "--system", "fourhinge", "--shape", "circular", "--rise-over-span", "0.5",
          "--thickness-over-span", "0.01", "--signal", "sine", "--period", "1", "--p", "1"],
         "cannot carry its own weight: minimum thickness is"),
        (["oas", "--system", "fourhinge", "--shape", "catenary", "--rise-over-span", "0.3",
          "--thickness-over-span", "0.05", "--blocks", "3", "--signal", "sine", "--period",
          "1", "--p", "1"], "at least 4 voussoirs"),
        (["oas", "--system", "sdof", "--delta", "0.1", "--signal", "sine", "--period", "1",
          "--p", "1"], "needs --ap-min"),
        (["simulate", "sdof", "--p", "2", "--delta", "-0.1", "--ap-min", "1", "--signal",
          "step", "--period", "1", "--ratio", "1.5"], "delta must lie in"),
        (["simulate", "frame", "--alpha", "0.1", "--p", "2", "--mass-ratio", "0.5",
          "--signal", "step", "--period", "1", "--ratio", "1.5", "--restitution", "3"],
         "restitution"),
        (["simulate", "fourhinge", "--shape", "catenary", "--span", "10", "--rise", "-3",
          "--thickness", "0.25", "--signal", "sine", "--period", "1", "--ratio", "2"],
         "--rise"),
    ],
)
def test_bad_input_exits_2(args, msg):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and msg in lines[0]
