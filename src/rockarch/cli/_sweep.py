"""The sweep options of ``rockarch oas``, ``site-oas`` and ``fragility`` (``--workers``,
``--scheduler``, ``--dask-workers``, ``--store``, ``--no-store``): which executor and store
of :mod:`rockarch.core.sweep` they ask for (docs/sweeps.md, "Command line")."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable

from rockarch.core.sweep import Executor, Store

#: Below this many simulations the CLI runs a sweep in-process (numba threads on every
#: core): starting a process pool (~0.8 s) costs more than it saves (docs/sweeps.md).
AUTO_PROCESS_MIN_SIMS = 20_000


def executor_for(*, workers: int | None = None, scheduler: str | None = None,
                 dask_workers: int | None = None, n_sims: int | None = None
                 ) -> Executor | None:
    """The executor the command-line options ask for.

    ``scheduler`` / ``dask_workers`` → Dask; ``workers`` → that many local processes;
    none of them → local processes on every core, or the in-process path (None) for a
    sweep of fewer than :data:`AUTO_PROCESS_MIN_SIMS` simulations or on one core.
    """
    if scheduler is not None or dask_workers is not None:
        if workers is not None:
            raise ValueError("--workers is for local processes; with Dask give "
                             "--dask-workers or --scheduler")
        return Executor("dask", scheduler=scheduler, dask_workers=dask_workers)
    if workers is not None:
        return Executor("processes", workers=workers)
    if (os.cpu_count() or 1) < 2 or (n_sims is not None and n_sims < AUTO_PROCESS_MIN_SIMS):
        return None
    return Executor("processes")


def store_for(store_dir=None, *, no_store: bool = False,
              report: Callable[[str], None] | None = None) -> Store | None:
    """The store the command-line options ask for: none with ``no_store``, else
    ``store_dir`` or the default cache directory."""
    if no_store:
        if store_dir is not None:
            raise ValueError("give either --store DIR or --no-store, not both")
        return None
    return Store(store_dir, report=report)


@contextlib.contextmanager
def open_sweep(*, workers: int | None = None, scheduler: str | None = None,
               dask_workers: int | None = None, store_dir=None, no_store: bool = False,
               n_sims: int | None = None, echo: Callable[[str], None] | None = None):
    """``with open_sweep(...) as (executor, store):`` the executor and store that the
    command-line options ask for (:func:`executor_for`, :func:`store_for`); the executor is
    closed on exit. ``echo`` (e.g. a line on stderr) gets corrupt-chunk warnings and, after
    a successful sweep that reused anything, the store's summary."""
    report = None if echo is None else (lambda msg: echo(f"warning: {msg}"))
    store = store_for(store_dir, no_store=no_store, report=report)
    executor = executor_for(workers=workers, scheduler=scheduler, dask_workers=dask_workers,
                            n_sims=n_sims)
    try:
        if executor is not None:
            executor.check_reachable()
        yield executor, store
    finally:
        if executor is not None:
            executor.close()
    if echo is not None and store is not None and (store.reused or store.corrupt):
        echo(store.summary())
