"""`rockarch oas` sweep options (issue 7): --store/--no-store, --workers, --scheduler,
--dask-workers; rerun is a cache hit; a corrupt chunk is reported; bad input exits 2."""

import json
import os
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app

runner = CliRunner()
REC = "src/rockarch/motion/data/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
BASE = ["oas", "--alpha", "0.2", "--record", REC, "--p-min", "1", "--p-max", "4",
        "--p-steps", "8", "--ratio-steps", "9", "--t-free", "3", "--json"]


def _default_sigint() -> None:
    """In the child before exec: SIGINT back to its default disposition."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _run(args, **kw):
    res = runner.invoke(app, args, **kw)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout), res.stderr


def test_store_rerun_is_a_cache_hit_and_corruption_is_reported(tmp_path):
    store = tmp_path / "store"
    first, err = _run([*BASE, "--store", str(store)])
    assert err == ""
    files = sorted(store.rglob("*.npz"))
    assert len(files) >= 8
    again, err = _run([*BASE, "--store", str(store)])
    assert again == first
    assert err.strip() == f"store {store}: {len(files)} chunks reused, 0 computed"
    data = bytearray(files[3].read_bytes())
    data[-7] ^= 0x01
    files[3].write_bytes(bytes(data))
    third, err = _run([*BASE, "--store", str(store)])
    assert third == first
    lines = err.strip().splitlines()
    assert len(lines) == 2 and lines[0].startswith(f"warning: store chunk {files[3]} is corrupt")
    assert lines[1].endswith(f"{len(files) - 1} chunks reused, 1 computed, 1 corrupt "
                             "(recomputed)")


def test_default_store_and_no_store(tmp_path):
    cache = tmp_path / "cache"
    out, _ = _run(BASE, env={"ROCKARCH_CACHE": str(cache)})
    assert len(list(cache.rglob("*.npz"))) >= 8
    nothing = tmp_path / "nothing"
    out2, err = _run([*BASE, "--no-store"], env={"ROCKARCH_CACHE": str(nothing)})
    assert out2 == out and err == "" and not nothing.exists()
    out3, _ = _run([*BASE, "--no-store", "--workers", "2"])
    assert out3 == out


@pytest.mark.parametrize("extra, msg", [
    (["--workers", "0"], "workers must be a positive integer"),
    (["--workers", "-1"], "workers must be a positive integer"),
    (["--dask-workers", "0"], "dask_workers must be a positive integer"),
    (["--scheduler", "localhost:8786"], "malformed scheduler address"),
    (["--scheduler", "tcp://127.0.0.1:1", "--dask-workers", "2"], "not both"),
    (["--scheduler", "tcp://127.0.0.1:1", "--workers", "2"], "--workers is for local"),
    (["--store", "/tmp", "--no-store"], "not both"),
    (["--store", "README.md/sub"], "store directory is not writable"),
])
def test_bad_sweep_options(extra, msg):
    res = runner.invoke(app, [*BASE, *extra])
    assert res.exit_code == 2
    assert res.stderr.startswith("error: ") and msg in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1


def test_unreachable_scheduler_is_one_line_without_hanging(tmp_path):
    """A closed port, and a port that accepts but never answers: exit 2, no hang."""
    with socket.socket() as srv:
        srv.bind(("127.0.0.1", 0))
        srv.listen(8)
        silent = srv.getsockname()[1]
        with socket.socket() as tmp:
            tmp.bind(("127.0.0.1", 0))
            closed = tmp.getsockname()[1]
        exe = os.path.join(os.path.dirname(sys.executable), "rockarch")
        procs = [(port, time.monotonic(), subprocess.Popen(
            [exe, *BASE, "--no-store", "--scheduler", f"tcp://127.0.0.1:{port}"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
            for port in (silent, closed)]
        for port, t0, proc in procs:
            out, err = proc.communicate(timeout=60)
            # a hang would be unbounded; 5 s of CONNECT_TIMEOUT plus the imports of numba
            # and distributed, which take up to ~20 s on a loaded 2-core machine
            assert time.monotonic() - t0 < 40
            assert proc.returncode == 2 and out == ""
            assert err.startswith(f"error: cannot reach a Dask scheduler at tcp://127.0.0.1:"
                                  f"{port}") and len(err.strip().splitlines()) == 1


def test_site_oas_resumes_from_the_store_and_matches_without_it(tmp_path):
    from rockarch.motion.records import bundled_record_path

    args = ["site-oas", "--records", str(bundled_record_path(180)),
            str(bundled_record_path(270)), "--p-min", "1", "--p-max", "4", "--p-steps", "4",
            "--ratio-steps", "11", "--t-free", "3", "--json"]
    store = tmp_path / "store"
    first, err = _run([*args, "--out", str(tmp_path / "a.nc"), "--store", str(store)])
    n = len(list(store.rglob("*.npz")))
    # stderr, not a terminal here: a "progress: ..." line per record done, nothing else
    assert [x[:30] for x in err.splitlines()] == ["progress: site OAS: record 1/2",
                                                  "progress: site OAS: record 2/2"]
    assert n >= 8  # chunks of both records
    again, err = _run([*args, "--out", str(tmp_path / "b.nc"), "--store", str(store)])
    assert err.splitlines()[-1] == f"store {store}: {n} chunks reused, 0 computed"
    assert len(err.splitlines()) == 3
    plain, _ = _run([*args, "--out", str(tmp_path / "c.nc"), "--no-store", "--workers", "2"])
    for js in (again, plain):
        assert {k: v for k, v in js.items() if k != "out"} == \
            {k: v for k, v in first.items() if k != "out"}
    with pytest.raises(AssertionError):
        _run([*args, "--out", str(tmp_path / "d.nc"), "--workers", "0"])


@pytest.mark.slow
@pytest.mark.parametrize("pool", [[], ["--workers", "2"], ["--dask-workers", "2"]])
def test_ctrl_c_is_one_line_without_leak_warnings(tmp_path, pool):
    """Ctrl-C in the middle of a sweep: exit 130, nothing on stderr but at most 'error:
    interrupted'; no SystemError traceback from a numba kernel (in-process), no traceback
    from a worker being started, no 'leaked semaphore' warning from the resource tracker,
    no notice from distributed."""
    store = tmp_path / "store"
    exe = os.path.join(os.path.dirname(sys.executable), "rockarch")
    args = [exe, "oas", "--alpha", "0.2", "--record", REC, "--p-min", "1", "--p-max", "4",
            "--p-steps", "96", "--ratio-steps", "41", "--no-progress", "--store", str(store),
            *pool]
    # Ctrl-C reaches the command even where pytest itself runs with SIGINT ignored (a
    # background job of a non-interactive shell): a terminal's child would have it. A
    # terminal sends it to the whole process group, the workers too: a session of its own
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=_default_sigint, start_new_session=True)
    deadline = time.monotonic() + 240
    while not list(store.rglob("*.npz")):  # interrupt once the workers run
        assert proc.poll() is None, proc.stderr.read()
        assert time.monotonic() < deadline
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and out == ""
    assert err in ("", "error: interrupted\n")  # typer exits 130 quietly on Ctrl-C


def _one_line_error(args, *, contains: str):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    assert res.stderr.startswith("error: ") and contains in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1 and res.stdout == ""
    return res.stderr


@pytest.mark.parametrize("grid, msg", [
    (["--p-min", "1", "--p-max", "2", "--p-steps", "1000000000"],
     "--p-steps 1000000000 is above the limit of 100000 values per axis"),
    (["--p", "1,2", "--ratio-steps", "100001"],
     "--ratio-steps 100001 is above the limit of 100000 values per axis"),
    (["--p", "1e300,1e301"], "p must lie in [0.001, 10000]"),  # hung before: p·t/h steps
    (["--p-min", "1", "--p-max", "2", "--p-steps", "100000", "--ratio-steps", "101"],
     "100000 p × 101 ratio values = 10,100,000 simulations (~0.505 GB), above the limit "
     "of 10,000,000 per command"),
])
def test_grid_limits_stop_before_any_work(grid, msg):
    t0 = time.monotonic()
    _one_line_error(["oas", "--alpha", "0.2", "--signal", "sine", "--period", "0.5", *grid,
                     "--no-store"], contains=msg)
    assert time.monotonic() - t0 < 20  # nothing allocated or run (under load: imports)


def test_grid_limit_of_the_library_and_of_a_site():
    from rockarch import systems
    from rockarch.core import sweep
    from rockarch.motion import signals as mo
    from rockarch.spectra import oas as spectra
    from rockarch.spectra import site

    big_p, big_r = np.linspace(1.0, 2.0, 20_000), np.linspace(1.0, 5.0, 501)
    with pytest.raises(ValueError, match="20000 p × 501 ratio values = 10,020,000"):
        spectra.compute_oas(systems.BlockSystem(alpha=0.2), mo.pulse("sine", period=0.5),
                            big_p, big_r, progress=False)
    shape = mo.pulse("sine", period=0.5)
    with pytest.raises(ValueError, match="3 records × 4000 p × 1000 ratio values"):
        site.site_oas([shape] * 3, np.linspace(1, 2, 4000), np.linspace(1, 5, 1000),
                      progress=False)
    assert sweep.MAX_SIMULATIONS == 10_000_000


def test_the_simulation_limit_can_be_raised_and_lowered(monkeypatch):
    from rockarch.core.sweep import limits

    monkeypatch.setenv("ROCKARCH_MAX_SIMULATIONS", "1e8")
    assert limits.check_simulations(50_000_000, "x") == 50_000_000
    monkeypatch.setenv("ROCKARCH_MAX_SIMULATIONS", "10")
    res = runner.invoke(app, ["oas", "--alpha", "0.2", "--signal", "sine", "--period", "0.5",
                              "--p", "1,2", "--ratio-steps", "6", "--no-store"])
    assert res.exit_code == 2 and res.stderr.strip().endswith(
        "above the limit of 10 per command: use fewer --p-steps/--ratio-steps, split the p "
        "range over several commands, or raise ROCKARCH_MAX_SIMULATIONS")
    monkeypatch.setenv("ROCKARCH_MAX_SIMULATIONS", "lots")
    with pytest.raises(ValueError, match="ROCKARCH_MAX_SIMULATIONS must be a positive"):
        limits.check_simulations(1, "x")


def test_site_oas_flags_a_record_given_twice(tmp_path):
    from rockarch.motion.records import bundled_record_path

    rec = bundled_record_path(180)
    copy = tmp_path / "copy_of_elcentro.AT2"
    copy.write_bytes(rec.read_bytes())
    base = ["site-oas", "--p-steps", "2", "--ratio-steps", "3", "--out", str(tmp_path / "s.nc")]
    _one_line_error([*base, "--records", str(rec), str(rec)],
                    contains=f"{rec}: the same record is given twice")
    _one_line_error([*base, "--records", str(rec.parent), str(rec)],
                    contains="the same record is given twice")
    _one_line_error([*base, "--records", str(rec), str(copy)],
                    contains=f"{copy.name}: the same record as {rec.name} (the same samples")
    assert not (tmp_path / "s.nc").exists()
    # the same record as a two-column file in m/s² (no --units: read as m/s², as it is):
    # refused by site-oas and by fragility, which took both before
    import numpy as np

    from rockarch.motion.records import read_record

    m = read_record(rec)
    txt = tmp_path / "elcentro_ms2.txt"
    np.savetxt(txt, np.c_[m.t, m.a])
    _one_line_error([*base, "--records", str(rec), str(txt)],
                    contains=f"{txt.name}: the same record as {rec.name} (the same samples")
    _one_line_error(["fragility", "--alpha", "0.1", "--p", "3", "--records", str(rec),
                     str(txt), "--no-store"],
                    contains=f"{txt.name}: the same record as {rec.name} (the same samples")


@pytest.mark.slow  # ~4-6 s: a sweep, then the import of distributed and a 1 s probe
def test_unreachable_scheduler_is_an_error_even_when_every_chunk_is_stored(tmp_path,
                                                                         monkeypatch):
    from rockarch.core.sweep import executors

    args = ["oas", "--alpha", "0.2", "--signal", "sine", "--period", "0.6", "--p", "1,2",
            "--ratio-steps", "3", "--t-free", "2", "--json", "--store", str(tmp_path)]
    _run(args)
    assert list(tmp_path.rglob("*.npz"))
    monkeypatch.setattr(executors, "CONNECT_TIMEOUT", 1.0)
    with socket.socket() as tmp:
        tmp.bind(("127.0.0.1", 0))
        closed = tmp.getsockname()[1]
    _one_line_error([*args, "--scheduler", f"tcp://127.0.0.1:{closed}"],
                    contains=f"cannot reach a Dask scheduler at tcp://127.0.0.1:{closed}")
