"""Sweep executor and resumable store (issue 7): identical maps in every mode, cache keys,
corrupt chunks, bad input."""

import dataclasses
import socket
import time
import warnings

import numpy as np
import pytest

from rockarch import systems
from rockarch.core import sweep
from rockarch.motion import signals as mo
from rockarch.motion.records import el_centro
from rockarch.spectra import oas as spectra

P = np.linspace(0.8, 4.0, 12)
R = np.linspace(1.0, 4.0, 13)


@pytest.fixture(scope="module")
def block():
    return systems.BlockSystem(alpha=0.2, t_free=3.0)


@pytest.fixture(scope="module")
def shape():
    return mo.pulse("sine", period=0.6)


@pytest.fixture(scope="module")
def reference(block, shape):
    return spectra.compute_oas(block, shape, P, R, progress=False, chunks=5)


def _same_maps(a, b) -> None:
    for v in ("overturned", "max_response", "boundary"):
        np.testing.assert_array_equal(a[v].values, b[v].values, strict=True)
    assert a.identical(b)


def test_every_local_mode_and_chunking_is_bit_identical(block, shape, reference):
    _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False, chunks=1))
    _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False, chunks=12,
                                              executor="serial"))
    with sweep.Executor("serial", workers=1) as ex:
        _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False,
                                                  chunks=5, executor=ex))
    with sweep.Executor("processes", workers=2) as ex:
        _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False,
                                                  chunks=5, executor=ex))
        # a mechanism through the same pool (pickled system with tables)
        from rockarch.rocking.mechanism import rocking_frame

        frame = systems.MechanismSystem(rocking_frame(0.2, 1.0, 0.5, 9.81, None), t_free=3.0)
        want = spectra.compute_oas(frame, shape, P[:4], R, progress=False)
        _same_maps(want, spectra.compute_oas(frame, shape, P[:4], R, progress=False,
                                             executor=ex))


def test_store_reuses_chunks_and_detects_corruption(block, shape, reference, tmp_path):
    st = sweep.Store(tmp_path)
    _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False, chunks=5,
                                              store=st))
    n = st.computed
    files = sorted((tmp_path / "chunks").rglob("*.npz"))
    assert st.reused == 0 and n == len(files) >= 5
    again = sweep.Store(tmp_path)
    _same_maps(reference, spectra.compute_oas(block, shape, P, R, progress=False, chunks=5,
                                              store=again))
    assert (again.reused, again.computed, again.corrupt) == (n, 0, 0)
    # damage two files: a flipped byte in the payload, and a truncated file
    data = bytearray(files[0].read_bytes())
    data[-20] ^= 0xFF
    files[0].write_bytes(bytes(data))
    files[1].write_bytes(files[1].read_bytes()[:30])
    third = sweep.Store(tmp_path)
    with pytest.warns(sweep.StoreWarning, match="corrupt") as rec:
        ds = spectra.compute_oas(block, shape, P, R, progress=False, chunks=5, store=third)
    _same_maps(reference, ds)
    assert len(rec) == 2 and str(files[0]) in str(rec[0].message) + str(rec[1].message)
    assert (third.reused, third.computed, third.corrupt) == (n - 2, 2, 2)
    assert not list((tmp_path / "chunks").rglob("*.part"))  # no temporary files left


def test_serial_thread_limit_does_not_stick(block, shape):
    import numba

    before = numba.get_num_threads()
    with sweep.Executor("serial", workers=1) as ex:
        sweep.run_chunks(block, shape, [(P[:2], R[:2])], executor=ex)
    assert numba.get_num_threads() == before


def test_cache_key_covers_every_input(block, shape):
    key = sweep.chunk_key(block, shape, P[:2], R)
    assert key == sweep.chunk_key(systems.BlockSystem(alpha=0.2, t_free=3.0), shape, P[:2], R)
    assert key == sweep.chunk_key(block, mo.pulse("sine", period=0.6), list(P[:2]), R)
    others = [
        sweep.chunk_key(dataclasses.replace(block, t_free=3.5), shape, P[:2], R),
        sweep.chunk_key(dataclasses.replace(block, restitution=0.9), shape, P[:2], R),
        sweep.chunk_key(dataclasses.replace(block, h_factor=block.h_factor / 2), shape,
                        P[:2], R),
        sweep.chunk_key(dataclasses.replace(block, alpha=0.2 + 1e-15), shape, P[:2], R),
        sweep.chunk_key(block, mo.pulse("sine", period=0.61), P[:2], R),
        sweep.chunk_key(block, shape.scaled(-1.0), P[:2], R),
        sweep.chunk_key(block, shape, P[:3], R),
        sweep.chunk_key(block, shape, P[:2], R[:-1]),
        sweep.chunk_key(block, shape, P[:2].reshape(2, 1), R),
    ]
    assert len({key, *others}) == len(others) + 1


def test_cache_key_depends_on_version(block, shape, monkeypatch):
    key = sweep.chunk_key(block, shape, P, R)
    monkeypatch.setattr(sweep.keys, "__version__", "99.0")
    assert sweep.chunk_key(block, shape, P, R) != key


def test_mechanism_keys_are_reproducible(shape):
    from rockarch.arch.geometry import make_arch
    from rockarch.rocking.fourhinge_motion import fourhinge_mechanism

    def make():
        arch = make_arch("catenary", 1.0, 0.3, 0.05)
        return systems.MechanismSystem(fourhinge_mechanism(arch, None))

    assert sweep.chunk_key(make(), shape, P, R) == sweep.chunk_key(make(), shape, P, R)


def test_progress_counts_every_simulation_in_every_mode(block, shape):
    class Bar:
        n = 0

        def update(self, k):
            self.n += k

    tasks = [np.meshgrid(P[i:i + 3], R, indexing="ij") for i in range(0, 12, 3)]
    with sweep.Executor("processes", workers=2) as ex:
        for executor in (None, sweep.Executor("serial"), ex):
            bar = Bar()
            out = sweep.run_chunks(block, shape, tasks, executor=executor, bar=bar)
            assert bar.n == P.size * R.size and len(out) == 4


@pytest.mark.parametrize("kwargs, match", [
    ({"workers": 0}, "workers must be a positive integer"),
    ({"workers": -2}, "workers must be a positive integer"),
    ({"workers": 1.5}, "workers must be a positive integer"),
    ({"dask_workers": 0}, "dask_workers must be a positive integer"),
    ({"scheduler": "localhost:8786"}, "malformed scheduler address"),
    ({"scheduler": "tcp://host"}, "malformed scheduler address"),
    ({"scheduler": "tcp://host:99999"}, "malformed scheduler address"),
    ({"scheduler": "tcp://a:1", "dask_workers": 2}, "not both"),
    ({"mode": "threads"}, "unknown executor mode"),
    ({"mode": "dask"}, "needs a scheduler"),
    ({"mode": "serial", "dask_workers": 2}, "takes no scheduler"),
])
def test_bad_executor_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        sweep.Executor(**kwargs)


def test_bare_dask_string_says_what_to_give():
    """executor="dask" (the docstring once offered it) names the two Executor objects that
    make a Dask sweep, before any simulation runs."""
    for call in (lambda: spectra.compute_oas(systems.BlockSystem(alpha=0.2),
                                             mo.pulse("sine", period=0.6), [1.0], [1.0, 2.0],
                                             executor="dask"),
                 lambda: sweep.Executor("dask")):
        with pytest.raises(ValueError) as err:
            call()
        msg = str(err.value)
        assert "Executor(dask_workers=n)" in msg and 'Executor(scheduler="tcp://' in msg
        assert "rockarch.core.sweep" in msg


def test_unwritable_store(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ValueError, match="store directory is not writable"):
        sweep.Store(blocker / "store")
    with pytest.raises(ValueError, match="executor must be"):
        spectra.compute_oas(systems.BlockSystem(alpha=0.2), mo.pulse("sine", period=0.6), [1.0],
                            [1.0, 2.0], executor=3)


def test_silent_scheduler_fails_fast(monkeypatch):
    """A port that accepts connections but never speaks Dask: a ValueError, no hang."""
    monkeypatch.setattr(sweep.executors, "CONNECT_TIMEOUT", 1.5)
    with socket.socket() as srv:
        srv.bind(("127.0.0.1", 0))
        srv.listen(8)
        port = srv.getsockname()[1]
        t0 = time.monotonic()
        with pytest.raises(ValueError, match="cannot reach a Dask scheduler"), \
                sweep.Executor(scheduler=f"tcp://127.0.0.1:{port}") as ex:
            sweep.run_chunks(systems.BlockSystem(alpha=0.2), mo.pulse("sine", period=0.6),
                             [(P[:2], R[:2])], executor=ex)
        assert time.monotonic() - t0 < 8


@pytest.mark.slow  # 20-60 s: starts a Dask cluster (--dask-workers covers Dask in make test)
def test_dask_local_cluster_is_bit_identical(block, reference):
    """The test's own LocalCluster (2 single-threaded worker processes on loopback), reached
    by its address like any running cluster; the El Centro record too."""
    import logging

    from distributed import LocalCluster

    rec = el_centro()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # distributed's own start-up notices
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          host="127.0.0.1", dashboard_address=None,
                          silence_logs=logging.ERROR) as cluster, \
                sweep.Executor(scheduler=cluster.scheduler_address) as ex:
            ds = spectra.compute_oas(block, mo.pulse("sine", period=0.6), P, R, progress=False,
                                     chunks=5, executor=ex)
            assert ex.n_workers == 2
            ds_rec = spectra.compute_oas(block, rec, P[::3], R, progress=False, executor=ex)
    _same_maps(reference, ds)
    _same_maps(spectra.compute_oas(block, rec, P[::3], R, progress=False), ds_rec)


def test_dask_workers_option_starts_and_stops_a_cluster(block, shape, reference):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ex = sweep.Executor(dask_workers=1)
        with ex:
            ds = spectra.compute_oas(block, shape, P, R, progress=False, chunks=5, executor=ex)
            cluster = ex._cluster
            assert cluster is not None and ex.n_workers == 1
    _same_maps(reference, ds)
    assert ex._cluster is None and cluster.status.name == "closed"
