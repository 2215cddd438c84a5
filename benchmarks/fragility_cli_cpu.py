"""Benchmark: `rockarch fragility` over 50 synthetic records as a user runs it, its wall
time and the CPU seconds of its whole process tree (the command and its worker processes),
with the default search for collapse islands and with the grid alone (issue 24: <= 10 s
on 2 cores).

Run:  .venv/bin/python benchmarks/fragility_cli_cpu.py [--n 50] [--seed 0] [--repeat 1]
      [-- EXTRA OPTIONS OF rockarch fragility]

The records are written by ``rockarch records synth DIR --n N --seed S`` into a temporary
folder; the command is ``rockarch fragility --system block --alpha 0.1 --p 2 --records DIR
--no-store`` (2 worker processes from 16 records, 500 bootstrap resamples). The CPU time
is summed over every process of the tree from /proc (Linux), sampled every 50 ms: the last
value seen of each process (a process that lives less than 50 ms may be missed).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HZ = os.sysconf("SC_CLK_TCK")
ROCKARCH = str(Path(sys.executable).with_name("rockarch"))


def descendants(root: int) -> dict[int, float]:
    """CPU seconds (user + system) of every descendant of ``root`` now running."""
    children: dict[int, list] = {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        children.setdefault(int(fields[1]), []).append(
            (int(name), (int(fields[11]) + int(fields[12])) / HZ))
    out, todo = {}, [root]
    while todo:
        for pid, cpu in children.get(todo.pop(), []):
            out[pid] = cpu
            todo.append(pid)
    return out


def measure(argv: list[str]) -> tuple[float, float, int]:
    """(wall [s], CPU of the process tree [s], processes seen) of one command."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL)
    seen: dict[int, float] = {}
    while proc.poll() is None:
        seen.update(descendants(os.getpid()))
        time.sleep(0.05)
    if proc.returncode:
        raise SystemExit(f"{' '.join(argv)} exited with {proc.returncode}")
    return time.perf_counter() - t0, sum(seen.values()), len(seen)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=50)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("extra", nargs="*", help="more options of rockarch fragility")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "syn"
        subprocess.run([ROCKARCH, "records", "synth", str(folder), "--n", str(args.n),
                        "--seed", str(args.seed)], check=True, stdout=subprocess.DEVNULL)
        base = [ROCKARCH, "fragility", "--system", "block", "--alpha", "0.1", "--p", "2",
                "--records", str(folder), "--no-store", *args.extra]
        print(f"{args.n} synthetic records (seed {args.seed}); {os.cpu_count()} cores")
        for label, extra in (("default (search every 0.0025)", []),
                             ("grid alone (--search-step 0)", ["--search-step", "0"])):
            for _ in range(args.repeat):
                load = os.getloadavg()[0]
                wall, cpu, n = measure(base + extra)
                print(f"{label:<32} wall {wall:6.2f} s, CPU of the process tree {cpu:6.2f} s "
                      f"({n} processes), load average {load:.2f} -> "
                      f"{os.getloadavg()[0]:.2f}", flush=True)


if __name__ == "__main__":
    main()
