"""Cache keys of sweep chunks: a SHA-256 of everything that determines a chunk's result.

A key covers the structure (every dataclass field, solver settings included), the motion's
samples, the chunk's exact p and ratio values, the versions of rockarch, numpy and numba,
and a digest of the rockarch source code itself (:func:`code_digest`), so that editing any
line of the package (a restitution law, a kernel) never reuses a chunk computed by the old
code (docs/sweeps.md, "Cache keys").
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import pickle

import numpy as np

from rockarch.core import __version__
from rockarch.core import jit_cache as _jit_cache
from rockarch.core.jit_cache import PACKAGE_ROOT, source_digest  # noqa: F401 - re-exported

#: Version of the chunk file format and of the key recipe (part of every key).
#: 2: the key holds :func:`code_digest`.
STORE_FORMAT = 2
def code_digest() -> str:
    """:func:`~rockarch.core.jit_cache.source_digest` of the running rockarch package (computed
    once per process; the numba cache follows the same digest).

    Part of every chunk key: any edit of the package's source, in a checkout, an editable
    install or a new release, changes every key, so the store never serves a result that
    the running code would not compute; unchanged code keeps its keys (cache hits)."""
    return _jit_cache.code_digest()


def _feed(h, obj) -> None:
    """Feed a canonical, type-tagged encoding of ``obj`` to the hash ``h``."""
    token = getattr(obj, "cache_token", None)
    if callable(token):
        h.update(b"T" + type(obj).__qualname__.encode())
        _feed(h, token())
    elif obj is None or isinstance(obj, (bool, int, str, bytes)):
        h.update(f"{type(obj).__name__}:{obj!r};".encode())
    elif isinstance(obj, float):
        h.update(f"float:{float.hex(obj)};".encode())
    elif isinstance(obj, (np.ndarray, np.generic)):
        arr = np.ascontiguousarray(obj)
        if arr.dtype.hasobject:
            raise TypeError("cannot key an object array")
        h.update(f"nd:{arr.dtype.str}:{arr.shape};".encode())
        h.update(arr.tobytes())
    elif isinstance(obj, enum.Enum):
        h.update(f"enum:{type(obj).__qualname__}.{obj.name};".encode())
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        h.update(f"dc:{type(obj).__module__}.{type(obj).__qualname__}(".encode())
        for f in dataclasses.fields(obj):
            h.update(f.name.encode() + b"=")
            _feed(h, getattr(obj, f.name))
        h.update(b")")
    elif isinstance(obj, dict):
        h.update(f"dict{len(obj)}(".encode())
        for k in sorted(obj, key=repr):
            _feed(h, k)
            _feed(h, obj[k])
        h.update(b")")
    elif isinstance(obj, (list, tuple)):
        h.update(f"{type(obj).__name__}{len(obj)}(".encode())
        for v in obj:
            _feed(h, v)
        h.update(b")")
    else:  # anything else: its pickle (deterministic for a given version; at worst a miss)
        h.update(f"pk:{type(obj).__module__}.{type(obj).__qualname__}:".encode())
        h.update(pickle.dumps(obj, protocol=4))


def _motion_token(motion):
    fp = getattr(motion, "fingerprint", None)
    return ("motion", fp()) if callable(fp) else motion


def chunk_key(system, motion, p, ratio) -> str:
    """SHA-256 (hex) of everything that determines ``system.run(motion, p, ratio)``.

    The structure's parameters (every dataclass field, solver settings included, or its
    ``cache_token()``), the motion's samples (:meth:`GroundMotion.fingerprint`), the exact
    p and ratio values, the rockarch / numpy / numba versions and :func:`code_digest`.
    """
    return _key_of(_base_hash(system, motion), p, ratio)


def content_key(tag: str, *objs) -> str:
    """SHA-256 (hex) of ``objs`` under the recipe of :func:`chunk_key` (the store format,
    the rockarch / numpy / numba versions and :func:`code_digest`), for results other than
    chunks that the store keeps (``tag`` names their kind, e.g. the statics of an
    assembly, :mod:`rockarch.mdof.statics_cache`)."""
    import numba

    h = hashlib.sha256()
    _feed(h, (f"rockarch-{tag}", STORE_FORMAT, __version__, code_digest(), np.__version__,
              numba.__version__))
    _feed(h, objs)
    return h.hexdigest()


def _base_hash(system, motion):
    """The hash state after the versions, the system and the motion (shared by every chunk
    of a sweep: hashed once, copied per chunk)."""
    import numba

    h = hashlib.sha256()
    _feed(h, ("rockarch-chunk", STORE_FORMAT, __version__, code_digest(), np.__version__,
              numba.__version__))
    _feed(h, system)
    _feed(h, _motion_token(motion))
    return h


def _key_of(base, p, ratio) -> str:
    h = base.copy()
    _feed(h, np.asarray(p, dtype=float))
    _feed(h, np.asarray(ratio, dtype=float))
    return h.hexdigest()
