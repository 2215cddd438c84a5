"""How the simulations of a sweep run: serially, in local processes, or on a Dask cluster,
and where their finished chunks are kept (a resumable, content-addressed store).

A sweep is a list of *chunks*: pieces of a grid, each one call
``system.run(motion, p, ratio)`` over many (p, ratio) pairs. :func:`run_chunks` runs them
with an :class:`Executor` and a :class:`Store`:

* the store maps a hash of a chunk's exact inputs (the structure's parameters, the motion's
  samples, the chunk's p and ratio values, the solver settings, the rockarch, numpy and
  numba versions and a digest of rockarch's own source code) to its result, so an
  interrupted sweep resumes where it stopped and a rerun is a cache hit; every chunk file
  carries a SHA-256 checksum and is written atomically (temporary file + rename);
* the executor runs the chunks that are not in the store: ``"serial"`` (in this process,
  numba threads on every core, chunk after chunk), ``"processes"`` (a pool of local
  processes, numba single-threaded in each) or ``"dask"`` (a running scheduler
  ``tcp://HOST:PORT`` or a ``LocalCluster`` that it starts and stops).

Each simulation is independent of the chunk it is run in, so every mode and every chunking
gives bit-identical maps.

Modules: :mod:`~rockarch.core.sweep.keys` (cache keys), :mod:`~rockarch.core.sweep.store` (the
store), :mod:`~rockarch.core.sweep.executors` (serial, processes, Dask),
:mod:`~rockarch.core.sweep.workers` (one chunk, worker set-up), :mod:`~rockarch.core.sweep.run` (the
run loop) and :mod:`~rockarch.core.sweep.limits` (grid limits). The command-line options that
choose them are read in :mod:`rockarch.cli._sweep`.
"""

from rockarch.core.sweep.executors import (
    CONNECT_TIMEOUT,
    MODES,
    Executor,
    as_executor,
    check_scheduler,
)
from rockarch.core.sweep.keys import STORE_FORMAT, chunk_key, code_digest, source_digest
from rockarch.core.sweep.limits import (
    MAX_SIMULATIONS,
    MAX_STEPS,
    check_simulations,
    check_steps,
)
from rockarch.core.sweep.run import run_chunks
from rockarch.core.sweep.store import (
    Store,
    StoreInfo,
    StoreWarning,
    as_store,
    clear_store,
    default_store_dir,
    store_info,
)
from rockarch.core.sweep.workers import run_chunk

__all__ = ["CONNECT_TIMEOUT", "MAX_SIMULATIONS", "MAX_STEPS", "MODES", "STORE_FORMAT",
           "Executor", "Store", "StoreInfo", "StoreWarning", "as_executor", "as_store",
           "check_scheduler", "check_simulations", "check_steps", "chunk_key", "clear_store",
           "code_digest", "default_store_dir", "run_chunk", "run_chunks", "source_digest",
           "store_info"]
