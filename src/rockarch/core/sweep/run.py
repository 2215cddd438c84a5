"""The run loop of a sweep: reuse the chunks found in the store, run the others on an
executor, store each one as it finishes."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from rockarch.core.sweep.executors import Executor
from rockarch.core.sweep.keys import _base_hash, _key_of
from rockarch.core.sweep.store import Store
from rockarch.core.sweep.workers import run_system


def run_chunks(system, motion, tasks: Sequence[tuple[np.ndarray, np.ndarray]], *,
               executor: Executor | None = None, store: Store | None = None,
               bar=None, keys: Sequence[str] | None = None
               ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Results ``system.run(motion, p, ratio)`` of every task ``(p, ratio)``, in order.

    Chunks found in ``store`` are reused; the others run on ``executor`` (None: in this
    process, numba as configured) and are written to ``store`` as each one finishes.
    ``bar`` (tqdm) advances by the number of simulations of each chunk. ``keys`` (one per
    task) replace the keys :func:`~rockarch.core.sweep.keys.chunk_key` would give, for tasks
    whose result depends on a part of ``motion`` only (e.g. one record of a suite: its key
    then holds that record, not the suite).
    """
    tasks = [(np.asarray(p, dtype=float), np.asarray(r, dtype=float)) for p, r in tasks]
    results: list = [None] * len(tasks)
    shapes = [np.broadcast_shapes(p.shape, r.shape) for p, r in tasks]
    if keys is not None:
        if len(keys) != len(tasks):
            raise ValueError(f"give one key per task: {len(keys)} keys, {len(tasks)} tasks")
        keys = list(keys) if store is not None else [None] * len(tasks)
    else:
        base = _base_hash(system, motion) if store is not None else None
        keys = [_key_of(base, p, r) if base is not None else None for p, r in tasks]
    todo = []
    for i, key in enumerate(keys):
        hit = store.get(key, shapes[i]) if store is not None else None
        if hit is None:
            todo.append(i)
        else:
            results[i] = hit
            if bar is not None:
                bar.update(math.prod(shapes[i]))

    def done(j: int, res) -> None:
        i = todo[j]
        over = np.broadcast_to(res[0], shapes[i])
        resp = np.broadcast_to(res[1], shapes[i])
        results[i] = (over, resp)
        if store is not None:
            store.put(keys[i], over, resp)
        if bar is not None:
            bar.update(math.prod(shapes[i]))

    sub = [tasks[i] for i in todo]
    if executor is None:
        for j, (p, r) in enumerate(sub):
            done(j, run_system(system, motion, p, r))
    else:
        executor.map(system, motion, sub, done)
    return results
