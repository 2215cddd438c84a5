"""`rockarch arch` command line: JSON contract, minimum thickness, plot, bad input."""

import json

import pytest
from typer.testing import CliRunner

from rockarch.cli import app

runner = CliRunner()
BASE = ["arch", "--shape", "catenary", "--span", "10", "--rise", "3"]


def run(args):
    return runner.invoke(app, args)


def test_json_contract_continuous():
    r = run(BASE + ["--thickness", "0.25", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert set(out) == {"ap_min", "lambda", "p", "delta", "delta_part", "delta_u", "Bv", "Bh",
                        "A", "hinges", "c1", "c2", "c3", "c3p", "c4", "c4_u"}
    assert out["c4"] == pytest.approx(0.025 / out["delta"], rel=1e-12)  # d/l = 0.025
    assert out["c4_u"] == pytest.approx(0.025 / out["delta_u"], rel=1e-12)
    assert out["delta_part"] in (1, 3)
    assert out["ap_min"] == pytest.approx(9.81 * out["lambda"], rel=1e-12)
    assert out["ap_min"] == pytest.approx(9.81 * out["Bv"] / out["Bh"], rel=1e-8)
    assert len(out["hinges"]) == 4
    xs = [h["x"] for h in out["hinges"]]
    assert xs == sorted(xs)
    assert all(h["joint"] is None for h in out["hinges"])
    assert {h["side"] for h in out["hinges"]} == {"intrados", "extrados"}


def test_json_with_blocks_gives_joint_indices_and_g():
    r = run(["arch", "--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness",
             "0.346", "--blocks", "20", "--g", "9.80665", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    joints = [h["joint"] for h in out["hinges"]]
    assert all(isinstance(j, int) for j in joints) and joints == sorted(joints)
    assert out["ap_min"] == pytest.approx(9.80665 * out["lambda"], rel=1e-12)


@pytest.mark.parametrize("shape, rise", [("pointed", "7"), ("elliptical", "3")])
def test_other_shapes(shape, rise):
    r = run(["arch", "--shape", shape, "--span", "10", "--rise", rise, "--thickness", "0.8",
             "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["ap_min"] > 0


def test_min_thickness_semicircle_and_with_lambda():
    r = run(["arch", "--shape", "circular", "--span", "10", "--rise", "5", "--min-thickness",
             "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["d_min_over_l"] * 2 == pytest.approx(0.1075, abs=1e-4)  # Milankovitch t/R
    r = run(BASE + ["--min-thickness", "--lambda", "0.1", "--json"])
    out = json.loads(r.stdout)
    assert out["d_min"] == pytest.approx(10 * out["d_min_over_l"])
    assert 0.05 < out["d_min"] < 0.2


def test_plot_and_summary(tmp_path):
    png = tmp_path / "arch.png"
    r = run(BASE + ["--thickness", "0.3", "--blocks", "12", "--plot", str(png)])
    assert r.exit_code == 0, r.output
    assert png.stat().st_size > 10_000
    assert "ap,min" in r.stdout and "delta" in r.stdout


@pytest.mark.parametrize("args, msg", [
    (["--shape", "catenary", "--span", "0", "--rise", "3", "--thickness", "0.2"], "span"),
    (["--shape", "catenary", "--span", "10", "--rise", "-3", "--thickness", "0.2"], "rise"),
    (["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0"], "thickness"),
    (["--shape", "circular", "--span", "10", "--rise", "2", "--thickness", "30"], "too large"),
    (["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.2", "--blocks",
      "3"], "at least 4"),
    (["--shape", "circular", "--span", "10", "--rise", "5", "--thickness", "0.3"],
     "cannot carry its own weight: minimum thickness is 0.537"),
    (["--shape", "parabola", "--span", "10", "--rise", "3", "--thickness", "0.3"], "shape"),
    (["--shape", "catenary", "--span", "10", "--rise", "3"], "--thickness is required"),
])
def test_bad_input_one_line_exit_2(args, msg):
    r = runner.invoke(app, ["arch", *args, "--json"])
    assert r.exit_code == 2
    err = r.stderr.strip()
    assert err.startswith("error:") and msg in err
    assert len(err.splitlines()) == 1
    assert r.stdout == ""
