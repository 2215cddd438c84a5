"""A store that follows the code: chunk keys hold a digest of rockarch's own source, so an
edited package recomputes and an unchanged one is a cache hit; ``rockarch cache info`` and
``rockarch cache clear``."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import rockarch
from rockarch import systems
from rockarch.cli import app
from rockarch.core import sweep
from rockarch.motion import signals as mo
from rockarch.spectra import oas as spectra

runner = CliRunner()
PKG = Path(rockarch.__file__).resolve().parent
HOUSNER = "return 1.0 - 1.5 * math.sin(alpha) ** 2"
OAS = ["oas", "--alpha", "0.2", "--signal", "sine", "--period", "0.6", "--p", "1,2,3",
       "--ratio-steps", "9", "--t-free", "3", "--json", "--no-progress"]


def _copy_sources(dst: Path) -> Path:
    shutil.copytree(PKG, dst, ignore=shutil.ignore_patterns("__pycache__", "data"))
    return dst


def test_source_digest_follows_every_py_file_and_nothing_else(tmp_path):
    copy = _copy_sources(tmp_path / "rockarch")
    assert sweep.source_digest(copy) == sweep.code_digest()  # same files, same digest
    (copy / "__pycache__").mkdir()
    (copy / "__pycache__" / "x.cpython-311.pyc").write_bytes(b"\0compiled")
    (copy / "notes.txt").write_text("not code")
    assert sweep.source_digest(copy) == sweep.code_digest()
    block = copy / "rocking" / "block.py"
    text = block.read_text()
    assert HOUSNER in text
    block.write_text(text.replace(HOUSNER, HOUSNER.replace("1.5", "1.4")))
    edited = sweep.source_digest(copy)
    assert edited != sweep.code_digest()
    block.write_text(text)  # an edit undone: the same digest again
    assert sweep.source_digest(copy) == sweep.code_digest()
    (copy / "arch" / "new_module.py").write_text("X = 1\n")  # a new file counts too
    assert sweep.source_digest(copy) not in (edited, sweep.code_digest())


def test_other_code_never_reuses_a_chunk(tmp_path, monkeypatch):
    """In process: the same sweep under another code digest recomputes every chunk."""
    block, shape = systems.BlockSystem(alpha=0.2, t_free=3.0), mo.pulse("sine", period=0.6)
    p, r = np.linspace(1.0, 3.0, 4), np.linspace(1.0, 4.0, 7)
    first = sweep.Store(tmp_path)
    ds = spectra.compute_oas(block, shape, p, r, progress=False, chunks=2, store=first)
    n = first.computed
    same = sweep.Store(tmp_path)
    spectra.compute_oas(block, shape, p, r, progress=False, chunks=2, store=same)
    assert (same.reused, same.computed) == (n, 0)
    monkeypatch.setattr(sweep.keys, "code_digest", lambda: "0" * 64)
    other = sweep.Store(tmp_path)
    ds2 = spectra.compute_oas(block, shape, p, r, progress=False, chunks=2, store=other)
    assert (other.reused, other.computed) == (0, n)
    assert ds.identical(ds2)


@pytest.mark.slow
def test_edited_package_copy_recomputes_and_agrees_with_no_store(tmp_path):
    """End to end, as a user would: a copy of the package (with its compiled numba caches),
    a stored sweep, the same sweep again (cache hit), then Housner's restitution edited in
    the copy: the stored sweep recomputes everything and equals --no-store."""
    root = tmp_path / "src"
    shutil.copytree(PKG, root / "rockarch")
    env = {**os.environ, "PYTHONPATH": str(root), "ROCKARCH_CACHE": str(tmp_path / "unused")}
    store = tmp_path / "store"

    def run(*extra):
        res = subprocess.run([sys.executable, "-c", "from rockarch.cli import app; app()",
                              *OAS, *extra], env=env, capture_output=True, text=True,
                             timeout=300, cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        return json.loads(res.stdout), res.stderr

    first, err = run("--store", str(store))
    n = len(list(store.rglob("*.npz")))
    assert err == "" and n >= 3
    again, err = run("--store", str(store))
    assert again == first and err.strip() == f"store {store}: {n} chunks reused, 0 computed"
    block = root / "rockarch" / "rocking" / "block.py"
    block.write_text(block.read_text().replace(HOUSNER, HOUSNER.replace("1.5", "1.2")))
    edited, err = run("--store", str(store))
    assert err == ""  # nothing reused
    assert edited == run("--no-store")[0]
    assert edited["boundary"] != first["boundary"]  # the edit does change the answer
    assert len(list(store.rglob("*.npz"))) == 2 * n


def _invoke(args, **kw):
    res = runner.invoke(app, args, **kw)
    assert res.exit_code == 0, res.output
    return res


def test_cache_info_and_clear(tmp_path):
    store = tmp_path / "store"
    _invoke([*OAS, "--store", str(store)])
    files = sorted(store.rglob("*.npz"))
    assert len(files) >= 3
    info = json.loads(_invoke(["cache", "info", "--store", str(store), "--json"]).stdout)
    assert info["store"] == str(store) and info["exists"] is True
    assert info["chunks"] == len(files)
    assert info["bytes"] == sum(f.stat().st_size for f in files)
    assert info["code_digest"] == sweep.code_digest()
    text = _invoke(["cache", "info", "--store", str(store)]).stdout
    assert f"store:  {store} (--store)" in text and f"chunks: {len(files)}" in text
    # someone else's files in the folder survive a clear
    (store / "mine.txt").write_text("keep")
    (store / "chunks" / "notes.npz").write_text("keep")
    res = _invoke(["cache", "clear", "--store", str(store)])
    assert res.stdout.strip().startswith(f"removed {len(files)} chunks (")
    assert not list(store.rglob("*/??/*.npz"))
    assert (store / "mine.txt").exists() and (store / "chunks" / "notes.npz").exists()
    info = json.loads(_invoke(["cache", "info", "--store", str(store), "--json"]).stdout)
    assert (info["chunks"], info["bytes"]) == (0, 0)


def test_cache_info_default_location_from_the_environment(tmp_path):
    cache = tmp_path / "cache"
    _invoke(OAS, env={"ROCKARCH_CACHE": str(cache)})
    n = len(list(cache.rglob("*.npz")))
    info = json.loads(_invoke(["cache", "info", "--json"],
                              env={"ROCKARCH_CACHE": str(cache)}).stdout)
    assert (info["store"], info["origin"], info["chunks"]) == (str(cache), "$ROCKARCH_CACHE", n)
    out = _invoke(["cache", "clear", "--json"], env={"ROCKARCH_CACHE": str(cache)}).stdout
    assert json.loads(out)["removed_chunks"] == n
    missing = json.loads(_invoke(["cache", "info", "--json", "--store",
                                  str(tmp_path / "none")]).stdout)
    assert (missing["exists"], missing["chunks"]) == (False, 0)
    assert not (tmp_path / "none").exists()  # info creates nothing


def test_cache_on_a_file_is_one_line_error(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    for cmd in ("info", "clear"):
        res = runner.invoke(app, ["cache", cmd, "--store", str(f)])
        assert res.exit_code == 2
        assert res.stderr.strip() == f"error: {f}: is a file, not a store directory"


@pytest.mark.parametrize("command", ["oas", "site-oas", "fragility"])
def test_help_says_where_the_store_lives(command):
    text = " ".join(_invoke([command, "--help"]).stdout.split())
    assert ("Default: $ROCKARCH_CACHE, else $XDG_CACHE_HOME/rockarch, else "
            "~/.cache/rockarch (here: ") in text
    assert "rockarch cache info" in text
