"""Compiled kernels are cached per source digest: an edit of any module (not only of the
file that defines a kernel) compiles afresh, so no stale machine code runs."""

from __future__ import annotations

import os
import shutil

import numba
import pytest

import rockarch
from rockarch.core import jit_cache as _jit_cache


@pytest.mark.skipif(bool(os.environ.get("NUMBA_CACHE_DIR")), reason="user's NUMBA_CACHE_DIR")
def test_numba_cache_folder_is_named_by_the_source_digest():
    assert numba.config.CACHE_DIR == str(_jit_cache.jit_cache_dir())
    assert _jit_cache.jit_cache_dir().name == _jit_cache.code_digest()[:16]


def test_editing_a_callee_module_changes_the_cache_folder(tmp_path):
    """numba alone would keep graph_run's compiled code after an edit of contact_solver;
    the digest of the whole package changes, and with it the folder."""
    pkg = tmp_path / "rockarch"
    shutil.copytree(os.path.dirname(rockarch.__file__), pkg,
                    ignore=shutil.ignore_patterns("__pycache__"))
    before = _jit_cache.source_digest(pkg)
    solver = pkg / "mdof" / "contact_solver.py"
    solver.write_text(solver.read_text() + "\n# an edit\n")
    assert _jit_cache.source_digest(pkg) != before


def test_each_run_kernel_is_compiled_once():
    """A single run and a batch of runs use one compiled copy of each stepper: the motion
    always arrives as a read-only array (``kernel_array``) and the batches pass their
    options typed as the single runs do (MDOF batches call the very kernel from threads).
    A second signature would compile the general stepper again (about 55 s on one core)."""
    from rockarch.mdof import chain_stepper, graph_run
    from rockarch.rocking import kernels
    from tests import warm_kernels

    for group in warm_kernels.GROUPS.values():
        group()
    for kernel in (graph_run.run, chain_stepper.run, kernels.run):
        assert len(kernel.signatures) == 1, kernel.signatures


def test_first_compilation_is_announced_once(tmp_path, monkeypatch):
    """The command line's notice: said for a kernel with no machine code here and no index
    in the cache folder, not said once either exists, never said by the library alone."""
    from types import SimpleNamespace

    index = tmp_path / "kernel.nbi"
    kernel = SimpleNamespace(signatures=[], _cache=SimpleNamespace(
        _cache_file=SimpleNamespace(_index_path=str(index))))
    lines = []
    monkeypatch.setattr(_jit_cache, "compile_notice", None)
    _jit_cache.announce_compile(kernel, "a kernel", 5)
    assert lines == []
    monkeypatch.setattr(_jit_cache, "compile_notice", lines.append)
    _jit_cache.announce_compile(kernel, "a kernel", 5)
    assert len(lines) == 1 and lines[0].startswith("note: compiling a kernel once")
    index.write_text("")
    _jit_cache.announce_compile(kernel, "a kernel", 5)
    kernel.signatures.append(("float64",))
    index.unlink()
    _jit_cache.announce_compile(kernel, "a kernel", 5)
    assert len(lines) == 1


def test_a_stale_warm_marker_is_not_waited_for(tmp_path, monkeypatch):
    """make test's background compilation (tests/warm_kernels.py --overlap) is waited for
    while its process runs, never after it ended (a marker left by a killed run)."""
    import subprocess
    import sys

    from tests import conftest

    marker = tmp_path / "warm-graph.pid"
    monkeypatch.setattr(conftest, "_WARMING", marker)
    assert not conftest._compiling()  # no marker
    marker.write_text(str(os.getpid()))
    assert conftest._compiling()  # a running process
    done = subprocess.Popen([sys.executable, "-c", "pass"])
    done.wait()
    marker.write_text(str(done.pid))
    assert not conftest._compiling()  # an ended one
    marker.write_text("garbage")
    assert not conftest._compiling()
