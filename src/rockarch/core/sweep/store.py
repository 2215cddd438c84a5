"""The resumable store of a sweep: one checksummed file per finished chunk, named by its
key (:func:`rockarch.core.sweep.keys.chunk_key`), written atomically (docs/sweeps.md, "The store").
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import re
import tempfile
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

_MAGIC = b"RKCHUNK1\n"
#: Names of the files a store writes (chunks, and temporary files of unfinished writes);
#: ``clear_store`` removes these and nothing else.
_CHUNK_NAME = re.compile(r"^[0-9a-f]{64}\.npz$")
_PART_NAME = re.compile(r"^\.[0-9a-f]{16}-.*\.part$")
_SUBDIR_NAME = re.compile(r"^[0-9a-f]{2}$")


class StoreWarning(UserWarning):
    """A chunk file of the store was corrupt (it is recomputed)."""


def default_store_dir() -> Path:
    """``$ROCKARCH_CACHE``, else ``$XDG_CACHE_HOME/rockarch``, else ``~/.cache/rockarch``."""
    env = os.environ.get("ROCKARCH_CACHE")
    if env:
        return Path(env).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg).expanduser() if xdg else Path.home() / ".cache"
    return base / "rockarch"


class Store:
    """Finished chunks on disk, one file per chunk, named by :func:`chunk_key`.

    ``root/chunks/ab/abcdef….npz``: a magic line, the SHA-256 of (key + payload), then the
    payload (an uncompressed ``.npz`` of ``overturned`` and ``max_response``). Files are
    written to a temporary name and renamed, so a killed sweep leaves whole files only;
    a file whose checksum (or shape) does not match is reported through ``report``,
    deleted and recomputed.

    Attributes ``reused``, ``computed`` and ``corrupt`` count chunks since creation.
    """

    def __init__(self, root=None, *, report: Callable[[str], None] | None = None) -> None:
        self.root = Path(root).expanduser() if root is not None else default_store_dir()
        self.report = report if report is not None else _warn
        self.reused = 0
        self.computed = 0
        self.corrupt = 0
        chunks = self.root / "chunks"
        try:
            chunks.mkdir(parents=True, exist_ok=True)
            fd, probe = tempfile.mkstemp(dir=chunks, prefix=".probe-")
            os.close(fd)
            os.unlink(probe)
        except OSError as exc:
            raise ValueError(f"{self.root}: store directory is not writable "
                             f"({exc.strerror or exc})") from None

    def __repr__(self) -> str:
        return f"Store({str(self.root)!r})"

    def path(self, key: str) -> Path:
        return self.root / "chunks" / key[:2] / f"{key}.npz"

    def get(self, key: str, shape: tuple) -> tuple[np.ndarray, np.ndarray] | None:
        """The stored result of chunk ``key`` (arrays of ``shape``), or None."""
        path = self.path(key)
        try:
            data = path.read_bytes()
        except FileNotFoundError:
            return None
        except OSError as exc:  # a directory or an unreadable file where a chunk belongs
            data = exc
        try:
            if isinstance(data, OSError):
                raise data
            if not data.startswith(_MAGIC):
                raise ValueError("bad header")
            digest = data[len(_MAGIC):len(_MAGIC) + 64]
            payload = data[len(_MAGIC) + 65:]
            if hashlib.sha256(key.encode() + payload).hexdigest().encode() != digest:
                raise ValueError("checksum mismatch")
            with np.load(io.BytesIO(payload), allow_pickle=False) as z:
                over, resp = z["overturned"], z["max_response"]
            if over.shape != tuple(shape) or resp.shape != tuple(shape) \
                    or over.dtype != np.bool_ or resp.dtype != np.float64:
                raise ValueError("unexpected arrays")
        except Exception as exc:  # noqa: BLE001 - any damage means: recompute
            self.corrupt += 1
            self.report(f"store chunk {path} is corrupt ({exc}); recomputing it")
            with contextlib.suppress(OSError):
                path.unlink(missing_ok=True)
            return None
        self.reused += 1
        return over, resp

    def put(self, key: str, over: np.ndarray, resp: np.ndarray) -> None:
        """Write chunk ``key`` atomically."""
        _write(self.path(key), key, {"overturned": np.asarray(over, dtype=bool),
                                     "max_response": np.asarray(resp, dtype=np.float64)})
        self.computed += 1

    def summary(self) -> str:
        return (f"store {self.root}: {self.reused} chunks reused, {self.computed} computed"
                + (f", {self.corrupt} corrupt (recomputed)" if self.corrupt else ""))


def read_record(root, kind: str, key: str) -> dict | None:
    """The arrays stored under ``root/kind/ab/KEY.npz`` by :func:`write_record`, or None
    (missing, unreadable or corrupt: a corrupt file is deleted, the caller recomputes)."""
    path = Path(root) / kind / key[:2] / f"{key}.npz"
    try:
        data = path.read_bytes()
        if not data.startswith(_MAGIC):
            raise ValueError("bad header")
        digest, payload = data[len(_MAGIC):len(_MAGIC) + 64], data[len(_MAGIC) + 65:]
        if hashlib.sha256(key.encode() + payload).hexdigest().encode() != digest:
            raise ValueError("checksum mismatch")
        with np.load(io.BytesIO(payload), allow_pickle=False) as z:
            return {k: z[k] for k in z.files}
    except FileNotFoundError:
        return None
    except Exception:  # noqa: BLE001 - any damage means: recompute
        with contextlib.suppress(OSError):
            path.unlink(missing_ok=True)
        return None


def _write(path: Path, key: str, arrays: dict) -> None:
    """``arrays`` as an uncompressed .npz after the magic line and the SHA-256 of (key +
    payload), written to a temporary name and renamed onto ``path``."""
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    payload = buf.getvalue()
    digest = hashlib.sha256(key.encode() + payload).hexdigest().encode()
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{key[:16]}-", suffix=".part")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(_MAGIC + digest + b"\n" + payload)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_record(root, kind: str, key: str, arrays: dict) -> bool:
    """Store ``arrays`` (name -> array) under ``root/kind/ab/KEY.npz`` atomically, with the
    checksum of a chunk file. Best effort: False if the folder is not writable."""
    try:
        _write(Path(root) / kind / key[:2] / f"{key}.npz", key, arrays)
    except OSError:
        return False
    return True


def _warn(message: str) -> None:
    warnings.warn(message, StoreWarning, stacklevel=3)


def as_store(store) -> Store | None:
    """None/False → no store; True → the default directory; a path → a store there."""
    if store is None or store is False:
        return None
    if store is True:
        return Store()
    if isinstance(store, Store):
        return store
    if not isinstance(store, (str, os.PathLike)):
        raise TypeError(f"store must be None, True, a folder path or a Store, got "
                        f"{type(store).__name__}")
    return Store(store)




@dataclass(frozen=True)
class StoreInfo:
    """What a store directory holds: ``chunks`` finished chunk files of ``size`` bytes in
    total (``exists`` False: the directory has not been created yet)."""

    root: Path
    exists: bool
    chunks: int
    size: int

    def as_dict(self) -> dict:
        return {"store": str(self.root), "exists": self.exists, "chunks": self.chunks,
                "bytes": self.size}


#: Folders of a store: finished chunks, and the records of :func:`write_record`.
_KINDS = ("chunks", "statics")


def _store_files(root: Path):
    """(path, is_chunk) of every file that a store wrote under ``root/chunks`` (and the
    records under ``root/statics``, counted in the size, not as chunks)."""
    for kind in _KINDS:
        folder = root / kind
        if not folder.is_dir():
            continue
        for sub in sorted(folder.iterdir()):
            if not (sub.is_dir() and _SUBDIR_NAME.match(sub.name)):
                continue
            for f in sorted(sub.iterdir()):
                if _CHUNK_NAME.match(f.name) and f.is_file():
                    yield f, kind == "chunks"
                elif _PART_NAME.match(f.name) and f.is_file():
                    yield f, False


def _root(root) -> Path:
    return Path(root).expanduser() if root is not None else default_store_dir()


def store_info(root=None) -> StoreInfo:
    """Chunks and bytes of the store at ``root`` (None: the default directory); reads only."""
    root = _root(root)
    if root.exists() and not root.is_dir():
        raise ValueError(f"{root}: is a file, not a store directory")
    n = size = 0
    for f, is_chunk in _store_files(root):
        n += is_chunk
        size += f.stat().st_size
    return StoreInfo(root, root.is_dir(), n, size)


def clear_store(root=None) -> StoreInfo:
    """Delete every chunk (and unfinished temporary file) of the store at ``root`` and its
    emptied sub-folders; other files are left alone. Returns what was removed."""
    root = _root(root)
    removed = store_info(root)
    try:
        for f, _ in _store_files(root):
            f.unlink(missing_ok=True)
        for kind in _KINDS:
            folder = root / kind
            for sub in sorted(folder.iterdir()) if folder.is_dir() else []:
                if sub.is_dir() and _SUBDIR_NAME.match(sub.name):
                    with contextlib.suppress(OSError):  # not empty: someone else's files
                        sub.rmdir()
    except OSError as exc:
        raise ValueError(f"{root}: cannot clear the store ({exc.strerror or exc})") from None
    return removed
