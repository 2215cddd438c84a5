"""An interrupted sweep (kill -9 or Ctrl-C) resumes from its store: identical result, and
no finished chunk is computed twice (issue 7)."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

from rockarch import systems
from rockarch.core import sweep
from rockarch.motion import signals as mo
from rockarch.spectra import oas as spectra

SCRIPT = textwrap.dedent('''
    import dataclasses, json, sys, time
    import numpy as np
    from rockarch import systems
    from rockarch.motion import signals as mo
    from rockarch.spectra import oas as spectra
    from rockarch.core import sweep

    @dataclasses.dataclass(frozen=True)
    class SlowBlock(systems.BlockSystem):
        """A block whose chunks take a while, so that the sweep can be interrupted."""
        def run(self, motion, p, ratio):
            time.sleep(0.25)  # 16 chunks on 2 workers: ~2 s, time to interrupt it
            return super().run(motion, p, ratio)

    if __name__ == "__main__":
        store = sweep.Store(sys.argv[1])
        ex = sweep.Executor(dask_workers=2) if sys.argv[2] == "dask" else sys.argv[2]
        try:
            ds = spectra.compute_oas(
                SlowBlock(alpha=0.2, t_free=3.0), mo.pulse("sine", period=0.6),
                np.linspace(0.8, 4.0, 16), np.linspace(1.0, 4.0, 13), progress=False,
                chunks=16, executor=ex)
        except KeyboardInterrupt:
            sys.exit(130)
        finally:
            if not isinstance(ex, str):
                ex.close()
        np.savez(sys.argv[3], overturned=ds["overturned"].values,
                 max_response=ds["max_response"].values, boundary=ds["boundary"].values)
        print(json.dumps({"reused": store.reused, "computed": store.computed}))
''').replace("chunks=16,", "chunks=16, store=store,")


def _default_sigint() -> None:
    """In the child before exec: SIGINT back to its default disposition."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _chunks(root):
    return sorted((root / "chunks").rglob("*.npz"))


@pytest.mark.parametrize("sig, mode", [
    pytest.param(signal.SIGKILL, "serial", marks=pytest.mark.slow),  # 30-100 s
    (signal.SIGINT, "processes"),
    pytest.param(signal.SIGKILL, "processes", marks=pytest.mark.slow),  # 30 s
    pytest.param(signal.SIGINT, "dask", marks=pytest.mark.slow),  # 40 s: a LocalCluster
])
def test_interrupted_sweep_resumes(tmp_path, sig, mode):
    script = tmp_path / "sweep_job.py"
    script.write_text(SCRIPT)
    store = tmp_path / "store"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    cmd = [sys.executable, str(script), str(store), mode, str(tmp_path / "out.npz")]
    # SIGINT reaches the job even where pytest runs with it ignored (a background job of a
    # non-interactive shell, whose children inherit the ignore): as under a terminal
    # in a session of its own: a Ctrl-C at a terminal reaches the whole process group, the
    # sweep's worker processes too
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            preexec_fn=_default_sigint, start_new_session=True)
    deadline = time.monotonic() + 60
    while len(_chunks(store)) < 4 if store.exists() else True:
        assert proc.poll() is None, proc.stderr.read().decode()
        assert time.monotonic() < deadline
        time.sleep(0.02)
    os.killpg(proc.pid, sig)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode != 0  # it was interrupted, not finished
    if sig == signal.SIGINT:  # Ctrl-C: nothing but a clean stop (docs/sweeps.md)
        assert err.decode() == ""
        assert proc.returncode == 130  # the script's KeyboardInterrupt, not a crash
    finished = len(_chunks(store))
    assert not (tmp_path / "out.npz").exists()

    res = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    counts = json.loads(res.stdout)
    total = len(_chunks(store))
    # every chunk that was finished before the interruption is reused, none is recomputed
    assert counts == {"reused": finished, "computed": total - finished}
    assert 4 <= finished < total
    assert not list(store.rglob("*.part"))

    want = spectra.compute_oas(systems.BlockSystem(alpha=0.2, t_free=3.0),
                               mo.pulse("sine", period=0.6), np.linspace(0.8, 4.0, 16),
                               np.linspace(1.0, 4.0, 13), progress=False)
    with np.load(tmp_path / "out.npz") as got:
        for v in ("overturned", "max_response", "boundary"):
            np.testing.assert_array_equal(got[v], want[v].values, strict=True)

    if sig == signal.SIGKILL and mode == "serial":  # and a third run is a pure cache hit
        res = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)
        assert json.loads(res.stdout) == {"reused": total, "computed": 0}


def test_store_counts_are_per_chunk(tmp_path):
    st = sweep.Store(tmp_path)
    shape = mo.pulse("sine", period=0.6)
    blk = systems.BlockSystem(alpha=0.2, t_free=3.0)
    spectra.compute_oas(blk, shape, [1.0, 2.0], [1.0, 3.0], progress=False, tol=0, chunks=2,
                        store=st)
    assert (st.computed, st.reused) == (2, 0) and len(_chunks(tmp_path)) == 2
