"""A numba cache that follows the source code of the whole package.

numba's own cache (``cache=True``) is invalidated only by the timestamp of the file that
defines a function, not by the modules whose kernels it calls: after an edit of
``contact_solver.py``, ``graph_run.run`` would keep running its old compiled code. rockarch
therefore keeps its compiled kernels in a folder named by a digest of every ``.py`` file of
the package (:func:`code_digest`, also part of every sweep-store key): any edit compiles
afresh, unchanged code reuses what was compiled. ``NUMBA_CACHE_DIR`` set by the user wins.
"""

from __future__ import annotations

import functools
import hashlib
import os
from collections.abc import Callable
from pathlib import Path

import numba
import numpy as np

#: The installed rockarch package (the folder whose ``.py`` files :func:`code_digest` reads).
PACKAGE_ROOT = Path(__file__).resolve().parent.parent


def source_digest(root: Path) -> str:
    """SHA-256 (hex) of every ``.py`` file under ``root``: relative path and bytes, in
    sorted order (compiled caches, data files and other files are not part of it)."""
    root = Path(root)
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py"), key=lambda q: q.relative_to(root).as_posix()):
        if "__pycache__" in path.parts:
            continue
        data = path.read_bytes()
        h.update(f"{path.relative_to(root).as_posix()}\0{len(data)}\0".encode())
        h.update(data)
    return h.hexdigest()


@functools.cache
def code_digest() -> str:
    """:func:`source_digest` of the running rockarch package (computed once per process)."""
    return source_digest(PACKAGE_ROOT)


def jit_cache_dir() -> Path:
    """``$ROCKARCH_JIT_CACHE``, else ``$XDG_CACHE_HOME/rockarch-jit``, else
    ``~/.cache/rockarch-jit``; one sub-folder per source digest."""
    env = os.environ.get("ROCKARCH_JIT_CACHE")
    if env:
        base = Path(env).expanduser()
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = (Path(xdg).expanduser() if xdg else Path.home() / ".cache") / "rockarch-jit"
    return base / code_digest()[:16]


def use_digest_cache() -> None:
    """Point numba's cache at :func:`jit_cache_dir` (before any kernel is defined), unless
    ``NUMBA_CACHE_DIR`` is set or the folder cannot be written (then numba's default)."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    path = jit_cache_dir()
    try:
        path.mkdir(parents=True, exist_ok=True)
        if not os.access(path, os.W_OK):
            return
    except OSError:
        return
    numba.config.CACHE_DIR = str(path)


def kernel_array(x) -> np.ndarray:
    """``x`` as a read-only C-contiguous float64 array, the one type in which every motion
    reaches a kernel: numba compiles a kernel once per argument type, writable or not."""
    x = np.ascontiguousarray(x, dtype=float)
    if x.flags.writeable:
        x = x.copy()
        x.setflags(write=False)
    return x


#: Called with one line of text before a slow kernel is compiled for the first time on this
#: machine (None: silent, the library's default; the command line prints it on stderr).
compile_notice: Callable[[str], None] | None = None


def announce_compile(kernel, what: str, seconds: float) -> None:
    """Pass :data:`compile_notice` a line saying that ``kernel`` (a numba dispatcher) is
    about to be compiled, if it has no machine code in this process nor an index in the
    cache folder: ``what`` takes about ``seconds`` of one core, once per version."""
    if compile_notice is None or kernel.signatures:
        return
    try:
        if os.path.exists(kernel._cache._cache_file._index_path):
            return
    except AttributeError:  # a numba without this cache layout: say nothing
        return
    compile_notice(f"note: compiling {what} once for this version of rockarch (about "
                   f"{seconds:.0f} s of one core; cached in {jit_cache_dir().parent})")
