"""Statics in the result store (rockarch.mdof.statics_cache): a second CLI command on the
same structure reuses them; the key changes with the geometry, the friction and the code."""

import json

import numpy as np
from typer.testing import CliRunner

from rockarch import mdof
from rockarch.cli import app
from rockarch.mdof import statics, statics_cache

runner = CliRunner()
WALL = ["simulate", "mdof", "--wall", "4,3", "--block", "0.4,0.2", "--friction", "0.6",
        "--signal", "sine", "--period", "1", "--ratio", "0.5", "--json"]


def _statics_files(root):
    return sorted((root / "statics").glob("*/*.npz"))


def test_second_cli_call_reuses_the_statics(tmp_path, monkeypatch):
    monkeypatch.setenv("ROCKARCH_CACHE", str(tmp_path))
    before = dict(statics_cache.counts)
    res = runner.invoke(app, WALL)
    assert res.exit_code == 0, res.output
    first = json.loads(res.stdout.strip().splitlines()[-1])
    computed = statics_cache.counts["computed"] - before["computed"]
    assert computed > 0 and statics_cache.counts["reused"] == before["reused"]
    files = _statics_files(tmp_path)
    assert files  # kept under $ROCKARCH_CACHE/statics

    def boom(*args, **kwargs):  # a second call must not solve anything
        raise AssertionError("limit analysis solved again")

    monkeypatch.setattr(statics, "_solve", boom)
    res = runner.invoke(app, WALL)
    assert res.exit_code == 0, res.output
    again = json.loads(res.stdout.strip().splitlines()[-1])
    assert again["ap_min"] == first["ap_min"]  # the same stored float
    assert statics_cache.counts["reused"] > before["reused"]
    assert _statics_files(tmp_path) == files
    # --no-store where a command has it, and `cache clear` removes the statics too
    res = runner.invoke(app, ["cache", "clear", "--json"])
    assert res.exit_code == 0, res.output
    assert _statics_files(tmp_path) == []


def test_a_corrupt_record_is_recomputed(tmp_path):
    w = mdof.wall(2, 2, 0.4, 0.2, mu=0.5)
    with statics_cache.using(tmp_path):
        c1 = statics.collapse(w)
        f = _statics_files(tmp_path)[0]
        f.write_bytes(f.read_bytes()[:-7] + b"garbage")
        c2 = statics.collapse(w)
    assert c2.ap_min == c1.ap_min and np.array_equal(c2.velocity, c1.velocity)


def test_key_changes_with_geometry_friction_and_settings(monkeypatch):
    w = mdof.wall(2, 2, 0.4, 0.2)
    base = (w.mass, w.inertia, w.centroid, w.corners, w.normal, w.body_a, w.body_b,
            np.full(w.n_joints, 0.5), 9.81, None, "nonassociative")
    k = statics_cache.key(base, (1.0,))
    assert statics_cache.key(base, (1.0,)) == k  # deterministic
    moved = list(base)
    moved[2] = w.centroid + 1e-12
    assert statics_cache.key(tuple(moved), (1.0,)) != k
    moved = list(base)
    moved[7] = np.full(w.n_joints, 0.6)
    assert statics_cache.key(tuple(moved), (1.0,)) != k
    assert statics_cache.key(base, (2.0,)) != k
    monkeypatch.setattr("rockarch.core.jit_cache.code_digest", lambda: "edited source")
    assert statics_cache.key(base, (1.0,)) != k


def test_unwritable_store_is_no_error(tmp_path):
    f = tmp_path / "a file"
    f.write_text("x")  # the store root is a file: nothing can be kept, nothing fails
    with statics_cache.using(f):
        c = statics.collapse(mdof.wall(2, 2, 0.4, 0.2, mu=0.5))
    assert c.converged
