"""Benchmark: `rockarch animate` against `rockarch simulate mdof` of the same case.

Run:  .venv/bin/python benchmarks/animate.py          (≈ 1 min on 2 cores)

1. the README example (20-voussoir catenary arch l = 10 m, f = 3 m, d = 0.25 m, sine pulse
   T = 1 s, ratio 1.5: it collapses at t ≈ 0.97 s) and the same arch at ratio 1.0 (safe,
   the whole 1 s pulse plus 3 s of free motion): wall time of the two commands, each a fresh
   process as a user runs them (median of 3), and their ratio (target: animate ≤ 6 ×
   simulate);
2. in one process, warm: the simulation, the animation as rockarch draws it (only what
   moves, fixed palette), and a plain reference drawing the same frames with matplotlib's
   FuncAnimation + PillowWriter (a full redraw of the figure per frame, as before).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from matplotlib.animation import FuncAnimation, PillowWriter

from rockarch.motion.signals import pulse
from rockarch.output import animation
from rockarch.systems import system

ARCH = ["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.25",
        "--blocks", "20", "--signal", "sine", "--period", "1"]
RUN = [sys.executable, "-c", "from rockarch.cli import app; app()"]


def wall(args: list[str], reps: int = 3) -> float:
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        subprocess.run(args, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def full_redraw(resp, path: Path, fps: int = 20) -> None:
    """The plain reference: every frame redraws the whole figure (FuncAnimation without
    blitting, PillowWriter), on the frames rockarch chooses."""
    plan = animation.plan_frames(resp, fps, 150, 1.0)
    fig = animation.new_figure((10, 4.1), dpi=animation.DPI)
    ax, axg = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1]})
    from matplotlib.patches import Polygon

    patches = [ax.add_patch(Polygon(p, closed=True, fc="0.82", ec="0.25", lw=0.6))
               for p in animation._outlines(resp, resp.q[0])]
    ax.autoscale_view()
    ax.set_aspect("equal")
    axg.plot(resp.ground.t, resp.ground.a)
    marker = axg.axvline(0.0, color="k")
    title = fig.suptitle("")

    def update(k):
        i = int(plan.indices[k])
        for patch, poly in zip(patches, animation._outlines(resp, resp.q[i]), strict=True):
            patch.set_xy(poly)
        marker.set_xdata([resp.t[i], resp.t[i]])
        title.set_text(f"t = {resp.t[i]:.2f} s")
        return patches

    FuncAnimation(fig, update, frames=plan.indices.size, blit=False).save(
        str(path), writer=PillowWriter(fps=fps))


def in_process(ratio: float, t_free: float, tmp: Path) -> None:
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=20,
               t_free=t_free)
    m = pulse("sine", period=1.0)
    s.simulate(m, ratio=ratio)  # JIT / cache load
    t0 = time.perf_counter()
    r = s.simulate(m, ratio=ratio)
    t_sim = time.perf_counter() - t0
    animation.animate(r, tmp / "warm.gif", progress=False)  # first figure: font cache
    t0 = time.perf_counter()
    animation.animate(r, tmp / "a.gif", progress=False)
    t_anim = time.perf_counter() - t0
    t0 = time.perf_counter()
    full_redraw(r, tmp / "ref.gif")
    t_ref = time.perf_counter() - t0
    n = animation.plan_frames(r, 20, 150, 1.0).indices.size
    print(f"  in process: simulation {1e3 * t_sim:.0f} ms; animation {t_anim:.2f} s "
          f"({n} frames, {1e3 * t_anim / n:.0f} ms/frame); full-redraw reference "
          f"{t_ref:.2f} s: {t_ref / t_anim:.1f}x faster")


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for ratio, t_free, what in ((1.5, 3.0, "README example (collapses at 0.97 s)"),
                                    (1.0, 3.0, "safe: rests before the 3 s of free motion end")):
            case = [*ARCH, "--ratio", str(ratio), "--t-free", str(t_free)]
            t_s = wall([*RUN, "simulate", "mdof", *case, "--json"])
            t_a = wall([*RUN, "animate", *case, "--out", str(tmp / "m.gif")])
            print(f"ratio {ratio}, {what}:")
            print(f"  commands: simulate mdof {t_s:.2f} s, animate {t_a:.2f} s, ratio "
                  f"{t_a / t_s:.2f} (target <= 6)")
            in_process(ratio, t_free, tmp)


if __name__ == "__main__":
    main()
