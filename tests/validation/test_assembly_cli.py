"""CLI contract of general assemblies and friction options (simulate/oas/animate mdof):
the issue's acceptance command, structure options, and one-line errors (exit 2)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch import mdof
from rockarch.cli import app
from rockarch.core.constants import G
from rockarch.systems import system

runner = CliRunner()
ARCH = ["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.25",
        "--blocks", "10"]
PULSE = ["--signal", "sine", "--period", "1"]


def _json(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout.strip().splitlines()[-1])


def _error(args):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    return lines[0]


def test_contract_single_block_with_friction(tmp_path):
    rec = tmp_path / "rec.txt"  # a record in g
    t = np.arange(0.0, 2.0, 0.01)
    np.savetxt(rec, np.c_[t, 0.3 * np.sin(2 * np.pi * t)])
    out = _json(["simulate", "mdof", "--column", "0.5,1.0", "--friction", "0.2", "--record",
                 str(rec), "--units", "g", "--ratio", "2", "--json"])
    # --ratio multiplies the friction-aware ap_min: min(mu, B/H)·g = 0.2 g
    assert out["ap_min"] == pytest.approx(0.2 * G, rel=1e-7)
    # PGA 0.4 g < B/H = 0.5 g: it cannot rock (sliding caps the force at 0.2 g), it slides
    assert out["overturned"] is False and out["sliding_contacts_max"] == 1
    assert out["max_slip"] > 0.01
    # the header's numbers in --json: rocking alone from B/H·g, and the block's Housner p
    # and alpha (closed forms: p² = 3g/(4R), R the half-diagonal; alpha = atan(B/H))
    rocking = {"ap_min_rocking": 0.5 * G, "p": np.sqrt(3 * G / (4 * np.hypot(0.25, 0.5))),
               "delta": np.arctan(0.5), "blocks": 1, "joints": 1}
    assert {k: out[k] for k in rocking} == pytest.approx(rocking, rel=1e-9)
    # without --friction: the rocking ap_min, B/H·g, and no sliding mechanism to name
    out = _json(["simulate", "mdof", "--column", "0.5,1.0", "--record", str(rec), "--units",
                 "g", "--ratio", "0.5", "--json"])
    assert out["ap_min"] == pytest.approx(0.5 * G, rel=1e-12)
    assert "ap_min_rocking" not in out and out["p"] == pytest.approx(rocking["p"], rel=1e-9)


def test_no_friction_is_todays_assembly():
    # --friction absent: the same chain assembly as before (bit for bit: same arrays)
    a = system("mdof", column=[(0.5, 1.0), (0.3, 1.0)]).assembly
    b = mdof.column([(0.5, 1.0), (0.3, 1.0)])
    assert a.ap_min == b.ap_min and a.p_ref == b.p_ref and a.frictionless and a.is_chain
    assert np.array_equal(a.corners, b.corners) and np.array_equal(a.mass, b.mass)
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=10)
    assert s.assembly.ap_min == mdof.arch_assembly(
        __import__("rockarch.arch", fromlist=["catenary"]).catenary(10, 3, 0.25), 10).ap_min


@pytest.mark.parametrize("extra,kind,nb", [
    (["--spans", "2", "--pier-height", "3", "--pier-width", "1"], "bridge", 2 * 10 + 3),
    (["--spans", "1", "--pier-height", "3", "--pier-width", "2"], "bridge", 10 + 2 * 2),
])
def test_bridge_options_build_piers(extra, kind, nb):
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=10,
               **{"spans": int(extra[1]), "pier_height": float(extra[3]),
                  "pier_width": float(extra[5])})
    assert s.assembly.kind == kind and s.assembly.n_blocks == nb
    assert not s.assembly.is_chain


def test_wall_colonnade_and_assembly_file(tmp_path):
    w = system("mdof", wall=(3, 4), block=(0.4, 0.2), friction=0.5).assembly
    assert w.kind == "wall" and w.ap_min == pytest.approx(0.5 * G, rel=1e-7)
    # the CLI's text forms are the same wall; bad text is a one-line ValueError
    assert system("mdof", wall="3,4", block="0.4,0.2", friction=0.5).assembly.n_blocks \
        == w.n_blocks
    for wall, msg in (("3,x", "comma-separated numbers"), ("3.5,4", "whole numbers"),
                      ("3", "needs 2 values")):
        with pytest.raises(ValueError, match=msg):
            system("mdof", wall=wall, block="0.4,0.2")
    c = system("mdof", colonnade=2, block=(0.3, 2.0), bay=1.0, lintel=0.4).assembly
    assert c.kind == "trilithon" and c.ap_min == pytest.approx(0.15 * G, rel=1e-7)
    f = tmp_path / "a.json"
    f.write_text(json.dumps({"blocks": [{"polygon": [[0, 0], [1, 0], [1, 2], [0, 2]]}]}))
    a = system("mdof", assembly=f, friction=0.3).assembly
    assert a.ap_min == pytest.approx(0.3 * G, rel=1e-7)


def test_colonnade_of_drums_from_ra_system_and_the_cli():
    # --drums N / drums=N: columns of N equal drums (rockarch.mdof.builders.colonnade)
    tri = dict(colonnade=2, block=(0.3, 2.0), bay=1.0, lintel=0.4)
    a = system("mdof", drums=3, **tri).assembly
    b = mdof.colonnade(2, 0.3, 2.0, 1.0, 0.4, drums=3)
    assert a.n_blocks == b.n_blocks == 2 * 3 + 1 and a.info["drums"] == 3
    assert np.array_equal(a.corners, b.corners) and a.ap_min == b.ap_min
    assert "of 3 drums" in a.name
    one = system("mdof", drums=1, **tri).assembly  # drums=1: monolithic, as without it
    assert one.name == system("mdof", **tri).assembly.name and one.n_blocks == 3
    out = _json(["simulate", "mdof", "--colonnade", "2", "--drums", "3", "--block", "0.3,2",
                 "--bay", "1", "--lintel", "0.4", "--signal", "sine", "--period", "0.2",
                 "--ratio", "0.5", "--t-free", "0.5", "--no-step-check", "--json"])
    assert out["blocks"] == 7 and out["joints"] == 8


def test_drums_wherever_colonnade_is():
    # every command that takes --colonnade (the shared STRUCTURE group) takes --drums
    import typer

    def commands(group, prefix=""):
        for name, cmd in group.commands.items():
            if hasattr(cmd, "commands"):
                yield from commands(cmd, f"{prefix}{name} ")
            else:
                yield prefix + name, {p.name for p in cmd.params}

    found = {name for name, params in commands(typer.main.get_command(app))
             if "colonnade" in params}
    assert {"simulate mdof", "animate", "oas", "site-oas", "fragility", "risk",
            "design"} <= found
    for name, params in commands(typer.main.get_command(app)):
        assert ("drums" in params) == ("colonnade" in params), name


@pytest.mark.parametrize("args, msg", [
    (["simulate", "mdof", "--drums", "2", *PULSE, "--ratio", "1"], "--drums divides the "
     "columns of a colonnade: give --colonnade N"),
    (["simulate", "mdof", *ARCH, "--drums", "2", *PULSE, "--ratio", "1"], "give --colonnade"),
    (["oas", "--system", "mdof", "--wall", "2,2", "--block", "0.4,0.2", "--drums", "2",
      *PULSE, "--p", "2"], "give --colonnade"),
    (["simulate", "mdof", "--colonnade", "2", "--block", "0.3,2", "--bay", "1", "--lintel",
      "0.4", "--drums", "0", *PULSE, "--ratio", "1"], "--drums must be an integer >= 1"),
    (["oas", "--system", "block", "--alpha", "0.1", "--drums", "2", *PULSE, "--p", "2"],
     "--drums belongs to --system mdof"),
])
def test_bad_drums_are_one_line(args, msg):
    assert msg in _error(args)


def test_header_names_the_structure_and_mechanism_png(tmp_path):
    png = tmp_path / "mech.png"
    res = runner.invoke(app, ["simulate", "mdof", "--colonnade", "2", "--block", "0.3,2",
                              "--bay", "1", "--lintel", "0.4", "--friction", "0.6", *PULSE,
                              "--ratio", "0.5", "--mechanism", str(png)])
    assert res.exit_code == 0, res.output
    assert "trilithon" in res.output and "friction 0.6" in res.output
    assert "safe" in res.output  # half its collapse acceleration
    assert f"wrote {png}" in res.output and png.stat().st_size > 5000


def test_bad_input_one_line(tmp_path):
    notjson = tmp_path / "x.json"
    notjson.write_text("{blocks: ]")
    unknown = tmp_path / "u.json"
    unknown.write_text(json.dumps({"blocks": [], "walls": 1}))
    star = tmp_path / "s.json"
    star.write_text(json.dumps({"blocks": [{"polygon": [
        [1, 0], [1.588, 1.809], [0.049, 0.691], [1.951, 0.691], [0.412, 1.809]]}]}))
    bowtie = tmp_path / "b.json"
    bowtie.write_text(json.dumps({"blocks": [{"polygon": [[0, 0], [2, 2], [2, 0], [0, 2]]}]}))
    overlap = tmp_path / "o.json"
    overlap.write_text(json.dumps({"blocks": [
        {"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
        {"polygon": [[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]]}]}))
    falls = tmp_path / "f.json"
    falls.write_text(json.dumps({"blocks": [
        {"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]], "name": "base"},
        {"polygon": [[0.7, 1], [1.7, 1], [1.7, 2], [0.7, 2]], "name": "lintel"}]}))
    cases = [
        (["--column", "0.5,1", "--friction", "0"], "--friction must be a finite number > 0"),
        (["--column", "0.5,1", "--friction", "-0.2"], "--friction"),
        (["--column", "0.5,1", "--friction", "inf"], "--friction"),
        (["--column", "0.5,1", "--friction", "1e20"], "--friction must be at most 1e+06"),
        (["--assembly", str(notjson)], "not JSON"),
        (["--assembly", str(unknown)], "unknown key(s) 'walls'"),
        (["--assembly", str(star)], "self-intersecting"),
        (["--assembly", str(bowtie)], "not convex"),
        (["--assembly", str(overlap)], "overlap"),
        (["--assembly", str(falls)], "lintel falls"),
        (["--assembly", str(tmp_path / "missing.json")], "no such file"),
        (["--wall", "3", "--block", "0.4,0.2"], "--wall needs 2"),
        (["--wall", "3,4"], "--block"),
        ([*ARCH, "--spans", "2", "--pier-height", "3", "--pier-width", "0.05"],
         "--pier-width must exceed"),
        ([*ARCH, "--spans", "0", "--pier-height", "3", "--pier-width", "1"], "--spans"),
        (["--column", "0.5,1", "--spans", "2"], "give the arch too"),
    ]
    for extra, msg in cases:
        assert msg in _error(["simulate", "mdof", *extra, *PULSE, "--ratio", "1", "--json"])
    assert "belongs to --system mdof" in _error(
        ["oas", "--system", "block", "--alpha", "0.2", "--friction", "0.3", *PULSE,
         "--p", "2", "--ratio-steps", "1"])


@pytest.mark.parametrize("mu", ["2", "10"])
def test_block_beside_a_support_rocks_with_high_friction(tmp_path, mu):
    # issue 23: this was "no rocking mechanism below 1000 g"; LMGC90 rocks it away at
    # B/H·g = 3.924 m/s² (closed form; docs/validation.md)
    f = tmp_path / "beside.json"
    f.write_text(json.dumps({
        "blocks": [{"polygon": [[0, 0], [0.4, 0], [0.4, 1], [0, 1]]}],
        "supports": [[[-0.4, 0], [0, 0], [0, 0.5], [-0.4, 0.5]]]}))
    out = _json(["simulate", "mdof", "--assembly", str(f), "--friction", mu, *PULSE,
                 "--ratio", "0.5", "--json"])
    assert out["ap_min"] == pytest.approx(0.4 * G, rel=1e-7) and out["overturned"] is False
