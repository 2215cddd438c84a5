"""The benchmark that calls a numba kernel directly (not through the Python API) still runs:
its call follows the kernel's signature (it fell behind once, when the kernel gained an
argument, and docs/performance.md's command crashed)."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow  # ~20 s: a 200 x 200 OAS and every cell of a 10 x 10 grid three times
def test_block_oas_benchmark_runs():
    res = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "block_oas.py"), "--n",
                          "10", "--sample", "1", "--jobs", "1"], capture_output=True,
                         text=True, timeout=600, cwd=ROOT)
    assert res.returncode == 0, res.stderr
    assert "rockarch per simulation (1 thread" in res.stdout
    assert "same overturning verdict in" in res.stdout  # the verdict itself: the docs
