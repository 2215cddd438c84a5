"""Where the compile time of the general contact stepper goes (a fresh clone pays it once).

Compiles one group of tests/warm_kernels.py into an empty numba cache, in a new process,
and splits the time: numba's own passes (typing, lowering), LLVM's function passes, LLVM's
module passes over each compiled function's module with its callees linked in, and machine
code. The plain reference is the group's total: the four parts sum to it. Not part of the
test suite (docs/performance.md, "Compile time").

Run:  .venv/bin/python benchmarks/compile_time.py [graph|rest]    (~1.5 min for graph)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = """
import json, sys, time
from numba.core import codegen
lib = codegen.CPUCodeLibrary
parts = {"llvm_function": 0.0, "llvm_module": 0.0, "machine_code": 0.0}
module_by_name = {}

def timed(name, per_library=False):
    f = getattr(lib, name)
    key = {"_optimize_functions": "llvm_function", "_optimize_final_module": "llvm_module",
           "_finalize_final_module": "machine_code"}[name]
    def wrapper(self, *a):
        t = time.perf_counter()
        out = f(self, *a)
        d = time.perf_counter() - t
        parts[key] += d
        if per_library:
            module_by_name[self.name] = module_by_name.get(self.name, 0.0) + d
        return out
    setattr(lib, name, wrapper)

timed("_optimize_functions")
timed("_optimize_final_module", per_library=True)
timed("_finalize_final_module")
sys.path.insert(0, sys.argv[2])
import warm_kernels
t = time.perf_counter()
warm_kernels.GROUPS[sys.argv[1]]()
total = time.perf_counter() - t
top = sorted(module_by_name.items(), key=lambda kv: -kv[1])[:6]
print(json.dumps({"total": total, **parts, "top_module_passes": top}))
"""


def main(group: str = "graph") -> None:
    with tempfile.TemporaryDirectory(prefix="rockarch-jit-") as cache:
        env = dict(os.environ, ROCKARCH_JIT_CACHE=cache)
        env.pop("NUMBA_CACHE_DIR", None)
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", CHILD, group, str(ROOT / "tests")],
                             env=env, capture_output=True, text=True, check=True)
        wall = time.perf_counter() - t0
    r = json.loads(out.stdout.strip().splitlines()[-1])
    numba_own = r["total"] - r["llvm_function"] - r["llvm_module"] - r["machine_code"]
    print(f"group {group}: {r['total']:.1f} s to compile in one process ({wall:.1f} s with "
          f"the imports)")
    for name, v in (("numba (typing, lowering)", numba_own),
                    ("LLVM function passes", r["llvm_function"]),
                    ("LLVM module passes (callees linked in)", r["llvm_module"]),
                    ("machine code", r["machine_code"])):
        print(f"  {name:40s} {v:6.1f} s  ({v / r['total']:5.1%})")
    print("  module passes of the largest libraries (each holds its callees):")
    for name, v in r["top_module_passes"]:
        print(f"    {name[:60]:60s} {v:5.2f} s")


if __name__ == "__main__":
    main(*sys.argv[1:2])
