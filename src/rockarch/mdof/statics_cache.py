"""The statics of assemblies kept in the result store, so that a second command on the same
structure does not solve them again (docs/theory.md §10; docs/sweeps.md, "The store").

A limit analysis (Eqs. 10.4–10.9) of a 205-block wall takes seconds, and every CLI command
builds its structure again. Its :class:`~rockarch.mdof.statics.Collapse` is stored under
``<store>/statics/`` and keyed like a sweep chunk
(:func:`rockarch.core.sweep.keys.content_key`): the geometry, the friction coefficients,
the load direction and friction model, the settings of the iteration, the rockarch / numpy /
numba versions and the digest of rockarch's source code. Only converged results are kept
(an unconverged one warns each time it is computed).

Off by default in the library (tests monkeypatch the solvers); the command line turns it on
for each command with :func:`using` and the default store (``$ROCKARCH_CACHE``, ...).
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from rockarch.core.sweep.keys import content_key
from rockarch.core.sweep.store import read_record, write_record

#: The store folder in use (None: no caching). Process-wide, not per thread: the analyses of
#: one build run on worker threads.
_ROOT: Path | None = None
_LOCK = threading.Lock()
#: Results served from the store and computed since the process started (for tests and the
#: user's curiosity).
counts = {"reused": 0, "computed": 0}

_FIELDS_ARRAY = ("velocity", "opening", "sliding", "normal_force", "tangential_force")
_FIELDS_SCALAR = ("ap_min", "lambda_", "direction", "p", "delta", "converged", "iterations")


@contextlib.contextmanager
def using(root) -> Iterator[None]:
    """Keep statics in the store at ``root`` (None: none) inside the block."""
    global _ROOT
    with _LOCK:
        before, _ROOT = _ROOT, None if root is None else Path(root).expanduser()
    try:
        yield
    finally:
        with _LOCK:
            _ROOT = before


def root() -> Path | None:
    """The store folder in use, or None."""
    return _ROOT


def key(inputs: tuple, settings: tuple) -> str:
    """The store key of a limit analysis: its inputs (arrays, μ, g, direction, friction
    model) and the solver settings that shape its result."""
    return content_key("statics", tuple(np.asarray(v) if isinstance(v, np.ndarray) else v
                                        for v in inputs), settings)


def load(k: str, make):
    """The stored result of key ``k`` rebuilt by ``make(**fields)``, or None."""
    where = _ROOT
    if where is None:
        return None
    rec = read_record(where, "statics", k)
    if rec is None or any(f not in rec for f in _FIELDS_ARRAY + _FIELDS_SCALAR):
        return None
    fields = {f: rec[f] for f in _FIELDS_ARRAY}
    fields.update({f: rec[f].item() for f in _FIELDS_SCALAR})
    fields["direction"], fields["iterations"] = int(fields["direction"]), int(
        fields["iterations"])
    fields["converged"] = bool(fields["converged"])
    counts["reused"] += 1
    return make(**fields)


def save(k: str, collapse) -> None:
    """Store a converged :class:`~rockarch.mdof.statics.Collapse` under key ``k``."""
    counts["computed"] += 1
    where = _ROOT
    if where is None or not collapse.converged:
        return
    arrays = {f: np.asarray(getattr(collapse, f)) for f in _FIELDS_ARRAY + _FIELDS_SCALAR}
    write_record(where, "statics", k, arrays)
