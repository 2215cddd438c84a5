"""Benchmark of the arch statics (issue 3 targets: 1000-joint LP <= 50 ms, full arch <= 0.5 s).

Usage::

    .venv/bin/python benchmarks/arch_lp.py

Prints the median wall time of: the thrust-line LP on a 1000-joint arch (matrix assembly +
HiGHS + hinge extraction, geometry prepared beforehand); the geometry of the continuous arch
(2000 voussoirs); a full ``analyse`` (geometry + LP + four-hinge mechanism + delta, p) through
the Python API; and the ``rockarch arch ... --json`` command as a subprocess (interpreter start
and imports included).
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import time

from rockarch.arch import analyse, catenary, circular, limit_analysis, voussoirs


def median_time(fn, repeat: int) -> float:
    fn()  # warm-up (imports, caches)
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    arch = catenary(10.0, 3.0, 0.25)
    v1000 = voussoirs(arch, 999)  # 999 voussoirs = 1000 joints
    t_lp = median_time(lambda: limit_analysis(v1000), 30)
    v1000c = voussoirs(circular(10.0, 2.89, 0.346), 999)
    t_lp_c = median_time(lambda: limit_analysis(v1000c), 30)
    t_geo = median_time(lambda: voussoirs(arch, 2000), 20)
    t_full = median_time(lambda: analyse(arch), 10)
    t_full_n = median_time(lambda: analyse(arch, 20), 10)
    exe = shutil.which("rockarch", path=os.path.dirname(sys.executable)) or "rockarch"
    cmd = [exe, "arch", "--shape", "catenary", "--span", "10", "--rise", "3", "--thickness",
           "0.25", "--json"]
    t_cli = median_time(lambda: subprocess.run(cmd, check=True, capture_output=True), 5)
    print(f"1000-joint LP, catenary (target <= 50 ms):      {1e3 * t_lp:7.1f} ms")
    print(f"1000-joint LP, circular (target <= 50 ms):      {1e3 * t_lp_c:7.1f} ms")
    print(f"geometry, 2000 voussoirs:                      {1e3 * t_geo:7.1f} ms")
    print(f"analyse(), continuous (target <= 500 ms):       {1e3 * t_full:7.1f} ms")
    print(f"analyse(), 20 voussoirs:                       {1e3 * t_full_n:7.1f} ms")
    print(f"rockarch arch --json subprocess (target <= 500 ms): {1e3 * t_cli:5.0f} ms")


if __name__ == "__main__":
    main()
