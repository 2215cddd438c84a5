"""Where the chunks of a sweep run: serially, in local processes, or on a Dask cluster
(docs/sweeps.md, "Executor modes")."""

from __future__ import annotations

import contextlib
import logging
import os
import re
from collections.abc import Callable, Sequence

import numpy as np

from rockarch.core.sweep.workers import (
    _deferred_sigint,
    _ignore_sigint,
    _worker_init,
    run_chunk,
)

#: Executor modes.
MODES = ("serial", "processes", "dask")
#: Why "dask" alone (as a mode string or ``Executor("dask")``) is refused, and what to give.
DASK_NEEDS = ("mode 'dask' needs a scheduler address or a number of workers: give "
              "executor=Executor(dask_workers=n) (a LocalCluster of n local workers) or "
              "executor=Executor(scheduler=\"tcp://HOST:PORT\") (a running scheduler), "
              "with Executor from rockarch.core.sweep")
#: Seconds to wait for a Dask scheduler before giving up.
CONNECT_TIMEOUT = 5.0
_ADDRESS = re.compile(r"^(tcp|tls)://(\[[0-9a-fA-F:.]+\]|[A-Za-z0-9_.\-]+):(\d{1,5})$")


#: Most worker processes of one sweep (local or a LocalCluster): each imports numpy, numba
#: and rockarch (~250 MB), so more than a few per core only swaps.
MAX_WORKERS = 64


def _check_count(name: str, n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"{name} must be a positive integer, got {n!r}")
    if n > MAX_WORKERS:
        raise ValueError(f"{name} must be at most {MAX_WORKERS} (each worker process holds "
                         f"~250 MB), got {int(n)}")
    return int(n)


def check_scheduler(address: str) -> str:
    """Validate a Dask scheduler address ``tcp://HOST:PORT`` (or ``tls://``)."""
    m = _ADDRESS.match(str(address).strip())
    if m is None or not (1 <= int(m.group(3)) <= 65535):
        raise ValueError(f"malformed scheduler address {address!r}: expected tcp://HOST:PORT")
    return str(address).strip()


def _probe_scheduler(address: str, timeout: float) -> None:
    """Connect and complete Dask's handshake within ``timeout`` seconds, or raise.

    ``distributed.Client(timeout=...)`` bounds the TCP connect but not the handshake: a
    port that accepts and never answers would hang it. The probe runs on its own event loop
    in a helper thread (so it also works under a running loop, e.g. Jupyter). A plain TCP
    connect comes first: a closed port is refused at once (distributed would retry it until
    the timeout)."""
    import asyncio
    import socket

    m = _ADDRESS.match(address)
    if m is not None:
        with socket.create_connection((m.group(2).strip("[]"), int(m.group(3))), timeout):
            pass
    from concurrent.futures import ThreadPoolExecutor
    from concurrent.futures import TimeoutError as FutTimeout

    from distributed.comm import connect

    async def probe() -> None:
        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        await comm.close()

    pool = ThreadPoolExecutor(1)
    try:
        pool.submit(asyncio.run, probe()).result(timeout + 2.0)
    except (asyncio.TimeoutError, FutTimeout):
        raise TimeoutError(f"no Dask handshake within {timeout:g} s") from None
    finally:
        pool.shutdown(wait=False)


def _start_local_cluster(factory, **kwargs):
    """``factory(**kwargs)`` (a Dask ``LocalCluster``); if it is interrupted while starting
    (Ctrl-C), close what it had started, quietly, so that distributed's exit handler does
    not print a traceback about a half-started cluster."""
    from distributed.deploy.spec import SpecCluster

    before = set(SpecCluster._instances)
    try:
        return factory(**kwargs)
    except BaseException:
        for cluster in set(SpecCluster._instances) - before:
            with contextlib.suppress(BaseException):
                cluster.close(timeout=5)
            cluster.shutdown_on_close = False
        raise


class Executor:
    """Runs chunks: ``"serial"``, ``"processes"`` (default) or ``"dask"``.

    Parameters
    ----------
    mode : str
        ``"serial"``: in this process, one chunk after another; the numba kernels use
        ``workers`` threads (default: every core). ``"processes"``: ``workers`` local
        processes (default: the number of cores), numba single-threaded in each.
        ``"dask"``: a Dask cluster (give ``scheduler`` or ``dask_workers``).
    workers : int, optional
        Local processes (or numba threads in serial mode).
    scheduler : str, optional
        Address ``tcp://HOST:PORT`` of a running Dask scheduler (implies mode "dask").
    dask_workers : int, optional
        Start a ``LocalCluster`` of that many single-threaded worker processes on loopback
        (implies mode "dask"); it is stopped by :meth:`close`.

    Notes
    -----
    Use it as a context manager (or call :meth:`close`); pools and clusters start lazily,
    at the first chunk that is not in the store.
    """

    def __init__(self, mode: str | None = None, *, workers: int | None = None,
                 scheduler: str | None = None, dask_workers: int | None = None) -> None:
        if scheduler is not None and dask_workers is not None:
            raise ValueError("give either a scheduler address or a number of Dask workers, "
                             "not both")
        if mode is None:
            mode = "dask" if (scheduler is not None or dask_workers is not None) \
                else "processes"
        if mode not in MODES:
            raise ValueError(f"unknown executor mode {mode!r}; expected one of {MODES}")
        if mode != "dask" and (scheduler is not None or dask_workers is not None):
            raise ValueError(f"mode {mode!r} takes no scheduler or dask workers")
        if mode == "dask" and scheduler is None and dask_workers is None:
            raise ValueError(DASK_NEEDS)
        if mode == "dask" and workers is not None:
            raise ValueError("workers is for local modes; give dask_workers for a "
                             "LocalCluster")
        self.mode = mode
        self.workers = None if workers is None else _check_count("workers", workers)
        self.scheduler = None if scheduler is None else check_scheduler(scheduler)
        self.dask_workers = None if dask_workers is None \
            else _check_count("dask_workers", dask_workers)
        self._pool = None
        self._client = None
        self._cluster = None
        self._scattered: dict = {}

    def __repr__(self) -> str:
        extra = {"processes": f"workers={self.n_workers}", "serial": f"threads={self.workers}",
                 "dask": f"scheduler={self.scheduler}" if self.scheduler
                 else f"dask_workers={self.dask_workers}"}[self.mode]
        return f"Executor({self.mode!r}, {extra})"

    @property
    def n_workers(self) -> int:
        """How many chunks run at once (for dask: the workers' threads, once connected)."""
        if self.mode == "processes":
            return self.workers or os.cpu_count() or 1
        if self.mode == "serial":
            return 1
        if self._client is not None:
            return max(sum(self._client.nthreads().values()), 1)
        return self.dask_workers or 1

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Stop the process pool / Dask client and any LocalCluster this executor started."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        if self._client is not None:
            self._client.close()
            self._client = None
            self._scattered = {}
        if self._cluster is not None:
            self._cluster.close()
            self._cluster = None

    # -- starting
    def check_reachable(self) -> None:
        """Raise ValueError within ~:data:`CONNECT_TIMEOUT` s if the Dask scheduler of this
        executor does not answer (nothing to check in the other modes). A command calls it
        before looking in the store, so that a wrong address is an error even when every
        chunk is already stored."""
        if self.scheduler is not None and self._client is None:
            with self._unreachable():
                _probe_scheduler(self.scheduler, CONNECT_TIMEOUT)

    @contextlib.contextmanager
    def _unreachable(self):
        """Any failure to reach the scheduler becomes one ValueError line."""
        try:
            yield
        except Exception as exc:  # noqa: BLE001 - no scheduler, or not a Dask one
            why = (str(exc).splitlines() or [""])[0][:120] or type(exc).__name__
            if not isinstance(exc, (OSError, TimeoutError)):  # e.g. garbage read as a frame
                why = f"something answers there, but not a Dask scheduler ({why[:60]})"
            raise ValueError(f"cannot reach a Dask scheduler at {self.scheduler} "
                             f"(waited up to {CONNECT_TIMEOUT:g} s): {why}") from None

    def _ensure_pool(self):
        if self._pool is None:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            ctx = multiprocessing.get_context("forkserver")
            ctx.set_forkserver_preload(["rockarch.spectra.oas"])
            self._pool = ProcessPoolExecutor(self.n_workers, mp_context=ctx,
                                             initializer=_worker_init,
                                             initargs=(os.getpid(),))
        return self._pool

    def _ensure_client(self):
        if self._client is not None:
            return self._client
        from distributed import Client, LocalCluster

        if self.scheduler is not None:
            with self._unreachable():
                _probe_scheduler(self.scheduler, CONNECT_TIMEOUT)
                self._client = Client(self.scheduler, timeout=f"{CONNECT_TIMEOUT}s")
        else:
            # no dashboard, and its HTTP server on a free port (the default 8787 may be
            # taken by another cluster: distributed would warn)
            self._cluster = _start_local_cluster(
                LocalCluster, n_workers=self.dask_workers, threads_per_worker=1,
                processes=True, host="127.0.0.1", dashboard_address=None,
                silence_logs=logging.ERROR,
                scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"})
            self._client = Client(self._cluster)
            self._client.run(_ignore_sigint)
        return self._client

    # -- running
    def map(self, system, motion, tasks: Sequence[tuple[np.ndarray, np.ndarray]],
            done: Callable[[int, tuple], None]) -> None:
        """Run ``run_chunk(system, motion, p, ratio)`` for every task; call ``done(i,
        result)`` in this process as each finishes (in any order)."""
        if not tasks:
            return
        if self.mode == "serial":
            for i, (p, r) in enumerate(tasks):
                done(i, run_chunk(system, motion, p, r, self.workers))
        elif self.mode == "processes":
            self._map_pool(system, motion, tasks, done)
        else:
            self._map_dask(system, motion, tasks, done)

    def _map_pool(self, system, motion, tasks, done) -> None:
        from concurrent.futures import FIRST_COMPLETED, wait

        pool = self._ensure_pool()
        futs: dict = {}
        try:
            with _deferred_sigint():  # submitting starts the workers: no Ctrl-C halfway
                for i, (p, r) in enumerate(tasks):
                    futs[pool.submit(run_chunk, system, motion, p, r)] = i
            pending = set(futs)
            while pending:
                finished, pending = wait(pending, return_when=FIRST_COMPLETED)
                for f in finished:
                    done(futs[f], f.result())
        except KeyboardInterrupt:
            self._abort_pool()  # the pool itself marks the chunks it did not run
            raise
        except BaseException:
            for f in futs:
                f.cancel()
            raise

    def _abort_pool(self) -> None:
        """Ctrl-C: stop the workers now rather than after their current chunks."""
        pool, self._pool = self._pool, None
        if pool is None:
            return
        call_queue = getattr(pool, "_call_queue", None)
        if call_queue is not None:  # its feeder thread may be stuck on a full pipe that
            call_queue.cancel_join_thread()  # no worker reads any more: do not wait for it
        procs = list(getattr(pool, "_processes", {}).values())
        for proc in procs:
            proc.terminate()
        # wait for them: a worker still starting up would otherwise look for the pool's
        # semaphores after this process has removed them, and print a traceback
        for proc in procs:
            proc.join(5.0)
        pool.shutdown(wait=False)

    def _scatter(self, client, obj):
        key = id(obj)
        hit = self._scattered.get(key)
        if hit is None or hit[0] is not obj:
            if len(self._scattered) >= 16:  # a site sweep: many motions, keep the recent
                self._scattered.pop(next(iter(self._scattered)))
            hit = (obj, client.scatter(obj, broadcast=True, hash=False))
            self._scattered[key] = hit
        return hit[1]

    def _map_dask(self, system, motion, tasks, done) -> None:
        from distributed import as_completed

        client = self._ensure_client()
        sys_f = self._scatter(client, system)
        mot_f = self._scatter(client, motion)
        futs = [client.submit(run_chunk, sys_f, mot_f, p, r, 1, pure=False)
                for p, r in tasks]
        index = {f.key: i for i, f in enumerate(futs)}
        try:
            for f, res in as_completed(futs, with_results=True):
                done(index[f.key], res)
        except KeyboardInterrupt:
            # Ctrl-C: what distributed logs as the cluster is stopped early (lost scattered
            # data, a callback interrupted in its event loop) is not news to the user
            for name in ("distributed", "tornado"):
                logging.getLogger(name).setLevel(logging.CRITICAL + 1)
            client.cancel(futs)
            raise
        except BaseException:
            client.cancel(futs)
            raise


def as_executor(executor) -> tuple[Executor | None, bool]:
    """(executor, owned): None → (None, False): the plain in-process path; a mode string →
    a new executor that the caller must close (owned=True); an Executor → itself.

    The string ``"dask"`` is a ValueError (:data:`DASK_NEEDS`): a Dask executor needs a
    cluster, given as ``Executor(dask_workers=n)`` or ``Executor(scheduler="tcp://...")``.
    """
    if executor is None:
        return None, False
    if isinstance(executor, Executor):
        return executor, False
    if isinstance(executor, str):
        return Executor(executor), True
    raise ValueError(f"executor must be None, a mode {MODES} or an Executor, got "
                     f"{executor!r}")
