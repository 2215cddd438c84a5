"""What runs inside a sweep's worker: one chunk (:func:`run_chunk`), the set-up of a local
worker process, and the handling of Ctrl-C around a pool (docs/sweeps.md, "Executor
modes")."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time

import numpy as np

from rockarch.core.console import one_line_warnings


def run_chunk(system, motion, p, ratio, threads: int | None = None):
    """One chunk: ``system.run(motion, p, ratio)`` as (bool array, float64 array).

    ``threads`` limits the numba threads of this call (thread-local; None: unchanged).
    """
    if threads is None:
        over, resp = run_system(system, motion, p, ratio)
    else:
        import numba

        before = numba.get_num_threads()
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        try:
            over, resp = run_system(system, motion, p, ratio)
        finally:
            numba.set_num_threads(before)
    return np.asarray(over, dtype=bool), np.asarray(resp, dtype=np.float64)


def run_system(system, motion, p, ratio):
    """``system.run(motion, p, ratio)``; a Ctrl-C inside a numba kernel stays a
    KeyboardInterrupt (numba reports it as a SystemError "returned a result with an
    exception set", which would print a traceback instead of the interruption)."""
    try:
        return system.run(motion, p, ratio)
    except SystemError as exc:
        cause, seen = exc, 0
        while cause is not None and seen < 50:  # numba chains several SystemErrors
            if isinstance(cause, KeyboardInterrupt):
                raise KeyboardInterrupt from None
            cause, seen = cause.__cause__ or cause.__context__, seen + 1
        raise


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


def _ignore_sigint() -> None:
    """In a worker process of a LocalCluster that a sweep started (run by ``Client.run``
    in its main thread): Ctrl-C at the terminal reaches the whole process group; the
    sweep's own process handles it and stops the cluster, as for the process pool."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _worker_init(parent: int) -> None:
    """Local worker process: numba on one thread (the pool supplies the parallelism); the
    parent handles Ctrl-C; and the worker exits once the parent is gone (after ``kill -9``
    of the sweep a worker finishes at most its current chunk, instead of idling forever)."""
    import multiprocessing

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    one_line_warnings()  # the worker's warnings reach the command's stderr as one line
    # a worker starts no processes; with "spawn" as its start method, numba's threading
    # layer takes no multiprocessing lock, whose semaphore would be reported as "leaked"
    # by the resource tracker when a Ctrl-C terminates the worker
    multiprocessing.set_start_method("spawn", force=True)
    import numba

    numba.set_num_threads(1)
    ppid = os.getppid()

    def watch() -> None:
        while _alive(parent) and os.getppid() == ppid:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="rockarch-parent-watch", daemon=True).start()


@contextlib.contextmanager
def _deferred_sigint():
    """Hold a Ctrl-C (SIGINT) that arrives inside the block and raise KeyboardInterrupt
    after it (only in the main thread; elsewhere nothing changes)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list = []
    previous = signal.signal(signal.SIGINT, lambda *_: caught.append(True))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught:
        raise KeyboardInterrupt
