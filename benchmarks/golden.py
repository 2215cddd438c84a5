"""Bit-identical guard for refactors (a developer tool, not a test).

A refactor that should not change any result is checked by running the same cases before
and after it on the same machine: the first run records a golden file (hashes of whole
histories and the printed summaries), later runs compare against it. The file is named by
a fingerprint of the machine and of the numeric libraries (CPU model and flags, numpy,
scipy, numba, llvmlite, Python): floating-point order in those builds differs between
machines, so the file is only ever compared on the machine that wrote it, and it is not
committed (``.golden/`` is in ``.gitignore``). The test suite checks results to their
physical tolerances instead (docs/validation.md).

Run::

    make golden                                   # record if absent, else compare
    .venv/bin/python benchmarks/golden.py --record   # record again (after an intended change)

Exit status 1 when a case differs; each differing case prints its largest difference.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

import rockarch as ra
from rockarch import mdof
from rockarch.arch import catenary
from rockarch.mdof import builders as bd

ROOT = Path(__file__).resolve().parents[1]
FOLDER = ROOT / ".golden"


def fingerprint() -> str:
    """The machine and the numeric libraries, as a short hex digest (and its text)."""
    import llvmlite
    import numba
    import scipy

    cpu = ""
    try:
        info = Path("/proc/cpuinfo").read_text()
        model = next((ln for ln in info.splitlines() if ln.startswith("model name")), "")
        flags = next((ln for ln in info.splitlines() if ln.startswith("flags")), "")
        cpu = model + flags
    except OSError:
        cpu = platform.processor()
    text = "|".join([platform.machine(), cpu, sys.version, np.__version__, scipy.__version__,
                     numba.__version__, llvmlite.__version__])
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _digest(*arrays) -> str:
    h = hashlib.sha256()
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(str(a.dtype).encode() + str(a.shape).encode())
        h.update(a.tobytes())
    return h.hexdigest()


def _ec(seconds: float):
    rec = ra.el_centro()
    keep = rec.t <= seconds
    return ra.GroundMotion(rec.t[keep], rec.a[keep], f"ec{seconds:g}")


def _mdof(a, m, ratio, t_free=1.0):
    r = mdof.simulate(a, m.scaled(ratio * a.ap_min / m.pga), t_free=t_free)
    return {"summary": {k: v for k, v in r.to_dict().items()},
            "history": _digest(r.t, r.q, r.joints)}


def cases() -> dict:
    """name -> callable returning a JSON-able dict (summary values and history digests)."""
    arch = catenary(10.0, 3.0, 0.25)
    chain = mdof.arch_assembly(arch, 20)
    return {
        "chain 20 voussoirs, 5 s El Centro, 1.5 ap,min": lambda: _mdof(chain, _ec(5.0), 1.5),
        "chain with friction 0.5": lambda: _mdof(bd.with_friction(chain, 0.5), _ec(5.0), 1.5),
        "bridge 2 spans": lambda: _mdof(bd.bridge(arch, 10, spans=2, pier_height=3.0,
                                                  pier_width=1.0), _ec(5.0), 0.5),
        "wall 4x3 mu 0.6, sine": lambda: _mdof(bd.wall(4, 3, 0.4, 0.2, mu=0.6),
                                              ra.pulse("sine", period=0.5), 2.0),
        "block oas, El Centro": lambda: {"boundary": ra.oas(
            ra.system("block", alpha=0.1), _ec(10.0), p=[1.0, 2.0, 4.0],
            ratio=np.linspace(1, 5, 41)).boundary.values.tolist()},
        "fourhinge, sine": lambda: ra.simulate(
            ra.system("fourhinge", shape="catenary", rise_over_span=0.3,
                      thickness_over_span=0.025), ra.pulse("sine", period=1.0), p=2.0,
            ratio=1.5).to_dict(),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="record the golden file again")
    args = ap.parse_args(argv)
    fp = fingerprint()
    path = FOLDER / f"golden-{fp}.json"
    results = {}
    for name, run in cases().items():
        t0 = time.perf_counter()
        results[name] = json.loads(json.dumps(run(), default=float))
        print(f"  {name}: {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    if args.record or not path.exists():
        FOLDER.mkdir(exist_ok=True)
        path.write_text(json.dumps(results, indent=1, sort_keys=True))
        print(f"golden: recorded {len(results)} cases for this machine ({fp}) in {path}")
        return 0
    golden = json.loads(path.read_text())
    bad = 0
    for name, got in results.items():
        want = golden.get(name)
        if want is None:
            print(f"new      {name} (not in the golden file; --record to add it)")
        elif want == got:
            print(f"same     {name}")
        else:
            bad += 1
            diffs = [f"{k}: {want.get(k)!r} -> {got.get(k)!r}"
                     for k in sorted(set(want) | set(got)) if want.get(k) != got.get(k)]
            print(f"DIFFERS  {name}: " + "; ".join(diffs)[:400])
    print(f"golden: {len(results) - bad} of {len(results)} cases bit-identical to {path.name}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
