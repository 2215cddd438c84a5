"""Compile rockarch's numba kernels into the cache before the suite runs (``make test``).

A fresh clone compiles every kernel: numba's cache index checks the source files' times,
new in every clone. Left to the suite, each pytest worker (and each CLI test's process that
starts before the cache is written) compiles the same kernels again, at the same time. Here
the kernels are split into groups of about equal compile time, one process per core, each
compiling different kernels once; the suite then loads them all from the cache.

``--overlap`` (``make test``) uses the second core better: the general contact stepper (the
longest group, ~90 s) compiles in the background while the rest compiles here; then the
suite starts at once, the stepper's tests last, and a test that needs the stepper before it
is in the cache waits for it (tests/conftest.py reads :data:`MARKER`) instead of compiling it
a second time.

Run:  python tests/warm_kernels.py            (every group, in parallel; prints the times)
      python tests/warm_kernels.py --overlap  (the stepper in the background; see above)
      python tests/warm_kernels.py GROUP      (one group, in this process)
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def _graph() -> None:
    """The general contact stepper (friction, walls, bridges), single runs and batches."""
    import rockarch as ra
    from rockarch import mdof
    from rockarch.arch import catenary
    from rockarch.mdof.simulate import simulate_batch

    a = mdof.with_friction(mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 6), 0.5)
    gm = ra.pulse("sine", period=1.0, ap=2.0 * a.ap_min)
    mdof.simulate(a, gm, t_free=0.0)
    simulate_batch(a, gm, np.array([3.0]), np.array([1.5]), t_free=0.0)


def _rest() -> None:
    """The chain stepper, the rigid block and SDOF mechanisms, intensity and synthetic
    records: every other kernel."""
    import rockarch as ra
    from rockarch import mdof
    from rockarch.arch import catenary
    from rockarch.mdof.simulate import simulate_batch
    from rockarch.motion import intensity
    from rockarch.rocking.block import RigidBlock, simulate
    from rockarch.rocking.block import simulate_batch as block_batch

    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 6)
    gm = ra.pulse("sine", period=1.0, ap=2.0 * a.ap_min)
    mdof.simulate(a, gm, t_free=0.0)
    simulate_batch(a, gm, np.array([3.0]), np.array([1.5]), t_free=0.0)
    blk = RigidBlock(2.0, 0.2)
    simulate(blk, gm)
    simulate(blk, None, t_free=1.0)
    mdof.simulate(a, None, t_free=0.5)
    block_batch(blk, gm, np.array([2.0]), np.array([1.5]))
    intensity.spectral_acceleration(gm, [0.5])
    ra.synthetic_suite(1, seed=0)


GROUPS = {"graph": _graph, "rest": _rest}
#: The group ``--overlap`` compiles in the background.
BACKGROUND = "graph"
#: While that group compiles in the background, this file holds its process id (removed
#: when it ends; a stale one names a process that no longer runs).
MARKER = Path(__file__).resolve().parents[1] / ".pytest_cache" / "warm-graph.pid"


def main(argv: list[str]) -> int:
    if argv and argv[0] in GROUPS:
        try:
            GROUPS[argv[0]]()
        finally:
            if argv[1:] == ["--marker"]:
                MARKER.unlink(missing_ok=True)
        return 0
    if argv not in ([], ["--overlap"]):
        sys.exit(f"usage: {os.path.basename(__file__)} [--overlap | GROUP]")
    t0 = time.perf_counter()
    overlap = argv == ["--overlap"]
    if overlap:
        MARKER.parent.mkdir(exist_ok=True)
        # outlives this process; Ctrl-C on the suite ends it too (same process group)
        bg = subprocess.Popen([sys.executable, __file__, BACKGROUND, "--marker"],
                              stdout=subprocess.DEVNULL)
        MARKER.write_text(str(bg.pid))
    names = [name for name in GROUPS if not (overlap and name == BACKGROUND)]
    procs = [subprocess.Popen([sys.executable, __file__, name]) for name in names]
    failed = [name for name, p in zip(names, procs, strict=True) if p.wait()]
    print(("numba kernels but the general contact stepper" if overlap else "numba kernels")
          + f" compiled or loaded from the cache in {time.perf_counter() - t0:.0f} s"
          + (f"; the stepper goes on in the background (process {bg.pid})" if overlap else "")
          + (f" (group {', '.join(failed)} failed: the suite compiles it itself)"
             if failed else ""))
    return 0

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
