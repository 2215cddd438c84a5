"""How the simulations of a sweep run: serially, in local processes, or on a Dask cluster,
and where their finished chunks are kept (a resumable, content-addressed store).

A sweep is a list of *chunks*: pieces of a grid, each one call
``system.run(motion, p, ratio)`` over many (p, ratio) pairs. :func:`run_chunks` runs them
with an :class:`Executor` and a :class:`Store`:

* the store maps a hash of a chunk's exact inputs (the structure's parameters, the motion's
  samples, the chunk's p and ratio values, the solver settings and the rockarch, numpy and
  numba versions) to its result, so an interrupted sweep resumes where it stopped and a
  rerun is a cache hit; every chunk file carries a SHA-256 checksum and is written
  atomically (temporary file + rename);
* the executor runs the chunks that are not in the store: ``"serial"`` (in this process,
  numba threads on every core, chunk after chunk), ``"processes"`` (a pool of local
  processes, numba single-threaded in each) or ``"dask"`` (a running scheduler
  ``tcp://HOST:PORT`` or a ``LocalCluster`` that it starts and stops).

Each simulation is independent of the chunk it is run in, so every mode and every chunking
gives bit-identical maps.
"""

from __future__ import annotations

import contextlib
import dataclasses
import enum
import hashlib
import io
import math
import os
import pickle
import re
import signal
import tempfile
import time
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from rockarch import __version__

#: Executor modes.
MODES = ("serial", "processes", "dask")
#: Version of the chunk file format and of the key recipe (part of every key).
STORE_FORMAT = 1
#: Seconds to wait for a Dask scheduler before giving up.
CONNECT_TIMEOUT = 5.0
_MAGIC = b"RKCHUNK1\n"
_ADDRESS = re.compile(r"^(tcp|tls)://(\[[0-9a-fA-F:.]+\]|[A-Za-z0-9_.\-]+):(\d{1,5})$")


class StoreWarning(UserWarning):
    """A chunk file of the store was corrupt (it is recomputed)."""


# --------------------------------------------------------------------------- cache keys


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
    p and ratio values, and the rockarch / numpy / numba versions.
    """
    return _key_of(_base_hash(system, motion), p, ratio)


def _base_hash(system, motion):
    """The hash state after the versions, the system and the motion (shared by every chunk
    of a sweep: hashed once, copied per chunk)."""
    import numba

    h = hashlib.sha256()
    _feed(h, ("rockarch-chunk", STORE_FORMAT, __version__, np.__version__, numba.__version__))
    _feed(h, system)
    _feed(h, _motion_token(motion))
    return h


def _key_of(base, p, ratio) -> str:
    h = base.copy()
    _feed(h, np.asarray(p, dtype=float))
    _feed(h, np.asarray(ratio, dtype=float))
    return h.hexdigest()


# --------------------------------------------------------------------------- the store


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
        buf = io.BytesIO()
        np.savez(buf, overturned=np.asarray(over, dtype=bool),
                 max_response=np.asarray(resp, dtype=np.float64))
        payload = buf.getvalue()
        digest = hashlib.sha256(key.encode() + payload).hexdigest().encode()
        path = self.path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{key[:16]}-", suffix=".part")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(_MAGIC + digest + b"\n" + payload)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        self.computed += 1

    def summary(self) -> str:
        return (f"store {self.root}: {self.reused} chunks reused, {self.computed} computed"
                + (f", {self.corrupt} corrupt (recomputed)" if self.corrupt else ""))


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
    return Store(store)


# --------------------------------------------------------------------------- executors


def _check_count(name: str, n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"{name} must be a positive integer, got {n!r}")
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
    in a helper thread (so it also works under a running loop, e.g. Jupyter)."""
    import asyncio
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


def _alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, killed but not yet reaped, does not)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            return f.read().rsplit(b")", 1)[1].split()[0] not in (b"Z", b"X")
    except FileNotFoundError:
        return False
    except (OSError, IndexError):  # no /proc: ask the kernel
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        except PermissionError:
            return True
        return True


def _worker_init(parent: int) -> None:
    """Local worker process: numba on one thread (the pool supplies the parallelism); the
    parent handles Ctrl-C; and the worker exits once the parent is gone (after ``kill -9``
    of the sweep a worker finishes at most its current chunk, instead of idling forever)."""
    import threading

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    import numba

    numba.set_num_threads(1)
    ppid = os.getppid()

    def watch() -> None:
        while _alive(parent) and os.getppid() == ppid:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="rockarch-parent-watch", daemon=True).start()


def run_chunk(system, motion, p, ratio, threads: int | None = None):
    """One chunk: ``system.run(motion, p, ratio)`` as (bool array, float64 array).

    ``threads`` limits the numba threads of this call (thread-local; None: unchanged).
    """
    if threads is None:
        over, resp = system.run(motion, p, ratio)
    else:
        import numba

        before = numba.get_num_threads()
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        try:
            over, resp = system.run(motion, p, ratio)
        finally:
            numba.set_num_threads(before)
    return np.asarray(over, dtype=bool), np.asarray(resp, dtype=np.float64)


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
            raise ValueError("mode 'dask' needs a scheduler address or a number of workers")
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
    def _ensure_pool(self):
        if self._pool is None:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            ctx = multiprocessing.get_context("forkserver")
            ctx.set_forkserver_preload(["rockarch.spectra"])
            self._pool = ProcessPoolExecutor(self.n_workers, mp_context=ctx,
                                             initializer=_worker_init,
                                             initargs=(os.getpid(),))
        return self._pool

    def _ensure_client(self):
        if self._client is not None:
            return self._client
        import logging

        from distributed import Client, LocalCluster

        if self.scheduler is not None:
            try:
                _probe_scheduler(self.scheduler, CONNECT_TIMEOUT)
                self._client = Client(self.scheduler, timeout=f"{CONNECT_TIMEOUT}s")
            except Exception as exc:  # noqa: BLE001 - no scheduler, or not a Dask one
                why = (str(exc).splitlines() or [""])[0][:120] or type(exc).__name__
                raise ValueError(f"cannot reach a Dask scheduler at {self.scheduler} "
                                 f"(waited up to {CONNECT_TIMEOUT:g} s): {why}") from None
        else:
            self._cluster = LocalCluster(n_workers=self.dask_workers, threads_per_worker=1,
                                         processes=True, host="127.0.0.1",
                                         dashboard_address=None,
                                         silence_logs=logging.ERROR)
            self._client = Client(self._cluster)
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
        futs = {pool.submit(run_chunk, system, motion, p, r): i
                for i, (p, r) in enumerate(tasks)}
        try:
            pending = set(futs)
            while pending:
                finished, pending = wait(pending, return_when=FIRST_COMPLETED)
                for f in finished:
                    done(futs[f], f.result())
        except BaseException as exc:
            for f in futs:
                f.cancel()
            if isinstance(exc, KeyboardInterrupt):
                self._abort_pool()
            raise

    def _abort_pool(self) -> None:
        """Ctrl-C: stop the workers now rather than after their current chunks."""
        pool, self._pool = self._pool, None
        if pool is None:
            return
        for proc in list(getattr(pool, "_processes", {}).values()):
            proc.terminate()
        pool.shutdown(wait=False, cancel_futures=True)

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
        except BaseException:
            client.cancel(futs)
            raise


def as_executor(executor) -> tuple[Executor | None, bool]:
    """(executor, owned): None → (None, False): the plain in-process path; a mode string →
    a new executor that the caller must close (owned=True); an Executor → itself."""
    if executor is None:
        return None, False
    if isinstance(executor, Executor):
        return executor, False
    if isinstance(executor, str):
        return Executor(executor), True
    raise ValueError(f"executor must be None, a mode {MODES} or an Executor, got "
                     f"{executor!r}")


def run_chunks(system, motion, tasks: Sequence[tuple[np.ndarray, np.ndarray]], *,
               executor: Executor | None = None, store: Store | None = None,
               bar=None) -> list[tuple[np.ndarray, np.ndarray]]:
    """Results ``system.run(motion, p, ratio)`` of every task ``(p, ratio)``, in order.

    Chunks found in ``store`` are reused; the others run on ``executor`` (None: in this
    process, numba as configured) and are written to ``store`` as each one finishes.
    ``bar`` (tqdm) advances by the number of simulations of each chunk.
    """
    tasks = [(np.asarray(p, dtype=float), np.asarray(r, dtype=float)) for p, r in tasks]
    results: list = [None] * len(tasks)
    shapes = [np.broadcast_shapes(p.shape, r.shape) for p, r in tasks]
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
            done(j, system.run(motion, p, r))
    else:
        executor.map(system, motion, sub, done)
    return results


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
        yield executor, store
    finally:
        if executor is not None:
            executor.close()
    if echo is not None and store is not None and (store.reused or store.corrupt):
        echo(store.summary())
