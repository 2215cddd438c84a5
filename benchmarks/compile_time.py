"""Where the compile time of the general contact stepper goes (a fresh clone pays it once).

Compiles one group of tests/warm_kernels.py into an empty numba cache, in a new process,
and splits the time: numba's own passes (typing, lowering), LLVM's function passes, LLVM's
module passes over each compiled function's module with its callees linked in, and machine
code. The plain reference is the group's total: the four parts sum to it. Not part of the
test suite (docs/performance.md, "Compile time").

``tuples`` instead measures what a named tuple of arrays passed by value costs (the way the
stepper's kernel data travelled until 2026-11-29): a chain of 5 small kernels, each calling
the next, compiled with a tuple of 40 arrays, of 8 arrays, with a record of 40 arrays passed
by reference (:mod:`rockarch.core.jit_struct`, as they travel now), and with the 3 arrays
each kernel reads.

Run:  .venv/bin/python benchmarks/compile_time.py [graph|rest]    (~1.5 min for graph)
      .venv/bin/python benchmarks/compile_time.py tuples          (~10 s)
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


TUPLES = """
import sys, time
from typing import NamedTuple
import numpy as np
import numba as nb

n, mode, depth = int(sys.argv[1]), sys.argv[2], 5
W = NamedTuple("W", [(f"a{i}", np.ndarray) for i in range(n)])
if mode == "struct":  # the same fields in a record passed by reference
    from rockarch.core.jit_struct import JitStruct, jit_struct
    W = jit_struct(type("W", (JitStruct,), {"__annotations__": dict.fromkeys(W._fields)}))
src = []
for d in range(depth):
    if mode != "arrays":  # each kernel reads 3 fields of the record and passes it on
        nxt = f"f{d + 1}(w, k)" if d < depth - 1 else "0.0"
        body = f"w.a{d}[i] * w.a{d + 1}[i] + w.a{d + 2}[i]"
        args = "w, k"
    else:  # each kernel gets the 3 arrays it reads
        nxt = f"f{d + 1}(y, z, x, k)" if d < depth - 1 else "0.0"
        body, args = "x[i] * y[i] + z[i]", "x, y, z, k"
    src.append(f"@nb.njit\\ndef f{d}({args}):\\n    s = 0.0\\n    for i in range(k):\\n"
               f"        s += {body}\\n    return s + {nxt}\\n")
ns = {"nb": nb}
exec("\\n".join(src), ns)
arrays = [np.ones(10) for _ in range(n)]
if mode == "struct":  # built in a kernel (outside the timing: its constructor compiles)
    make = nb.njit(lambda *a: W(*a))
    w = make(*arrays)
else:
    w = W(*arrays)
t = time.perf_counter()
ns["f0"](w, 10) if mode != "arrays" else ns["f0"](w.a0, w.a1, w.a2, 10)
print(time.perf_counter() - t)
"""


def tuples() -> None:
    """Compile time of a chain of 5 kernels: a named tuple of n arrays, the same fields in a
    record passed by reference (:mod:`rockarch.core.jit_struct`), or the 3 arrays each
    kernel reads."""
    print("a chain of 5 kernels, each calling the next (fresh process each, no cache):")
    for n, mode in ((40, "tuple"), (8, "tuple"), (40, "struct"), (40, "arrays")):
        out = subprocess.run([sys.executable, "-c", TUPLES, str(n), mode], check=True,
                             capture_output=True, text=True)
        what = {"tuple": f"a named tuple of {n} arrays",
                "struct": f"a record of {n} arrays (by reference)",
                "arrays": "the 3 arrays it reads"}[mode]
        print(f"  each passed {what:40s} {float(out.stdout):5.2f} s")


def main(group: str = "graph") -> None:
    if group == "tuples":
        tuples()
        return
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
