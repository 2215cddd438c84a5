"""Collapse verdicts over a pulse grid against pymunk (independent engine, tests only).

The same structure on the same sine pulse (period T, peak ratio·ap,min) in rockarch (MDOF
Moreau–Jean, with or without friction) and in pymunk (tilted gravity): the overturned /
safe verdicts agree in >= 95 % of all cells, with and without friction, and in all but at
most three cells of every structure's grid, not counting cells where rockarch's own verdict
flips within ±0.1 % of the amplitude (a chaotic verdict is not pinned). The 4 × 3 wall with
mu = 0.8 differs in three firm cells under its 1.9–3.8 g short pulses, where it slides and
tumbles and pymunk's verdict is not monotonic in the amplitude, and in the lowest ratio of
its longest pulse, next to the boundary, whose verdict flips within ±0.1 %; every other
structure differs in at most one. Cells in disagreement are printed and
recorded in docs/validation.md (command: ``pytest -m slow -s
tests/validation/test_pymunk_dynamic.py``).
"""

import numpy as np
import pytest

pytest.importorskip("pymunk")

from rockarch import mdof  # noqa: E402
from rockarch.arch import catenary  # noqa: E402
from rockarch.core.constants import G  # noqa: E402
from rockarch.mdof import builders as bd  # noqa: E402
from rockarch.motion import signals as motion
from rockarch.systems import MDOFSystem, scale_to_ratio  # noqa: E402
from tests.validation import pymunk_oracle as po  # noqa: E402

#: Free motion after the pulse: long enough for a started collapse to finish in both.
T_FREE = 3.0
#: pymunk collapse: some block has turned by more than 1 rad (a rocking survivor turns by
#: less than its slenderness, <= 0.46 rad here; a collapsed block or voussoir falls flat).
ROT_FALL = 1.0

STRUCTURES = {
    "block": lambda: mdof.single_block(0.5, 1.0),
    "block mu=0.3": lambda: bd.with_friction(mdof.single_block(0.5, 1.0), 0.3),
    "arch N=10": lambda: mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 10),
    "arch on piers": lambda: bd.bridge(catenary(10.0, 3.0, 0.25), 10, pier_height=3.0,
                                       pier_width=1.5),
    "arch on piers mu=0.5": lambda: bd.bridge(catenary(10.0, 3.0, 0.25), 10,
                                              pier_height=3.0, pier_width=1.5, mu=0.5),
    "wall mu=0.6": lambda: bd.wall(4, 3, 0.4, 0.2, mu=0.6),
    "wall": lambda: bd.wall(4, 3, 0.4, 0.2),
    "wall mu=0.8": lambda: bd.wall(4, 3, 0.4, 0.2, mu=0.8),
}
GRIDS = {  # (periods [s], ratios): around each structure's boundary and away from it
    "block": ([0.5, 1.0, 2.0, 3.0], [1.5, 2.5, 3.5, 5.0, 7.0]),
    "block mu=0.3": ([0.5, 1.0, 2.0, 3.0], [1.5, 3.0, 4.5, 6.0, 9.0]),
    "arch N=10": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
    "arch on piers": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
    "arch on piers mu=0.5": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
    "wall mu=0.6": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
    "wall": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
    "wall mu=0.8": ([0.5, 1.0, 2.0], [1.2, 2.0, 3.0, 4.5, 6.0]),
}


def verdict_grid(name):
    """(rockarch, pymunk) overturned verdicts over the grid of ``name``."""
    a = STRUCTURES[name]()
    sysobj = MDOFSystem(a, t_free=T_FREE)
    periods, ratios = GRIDS[name]
    ra = np.zeros((len(periods), len(ratios)), bool)
    pm = np.zeros_like(ra)
    for i, period in enumerate(periods):
        shape = motion.pulse("sine", period=period)
        for j, r in enumerate(ratios):
            ra[i, j] = sysobj.simulate(shape, ratio=r).overturned
            m = scale_to_ratio(shape, r, a.ap_min)
            _, rot = po.run(a, lambda t, m=m: float(np.interp(t, m.t, m.a, right=0.0)),
                            m.duration + T_FREE, dt=5e-4)
            pm[i, j] = rot > ROT_FALL
    return ra, pm


#: Structures that cannot overturn: friction below every rocking threshold (mu < B/H of
#: every block and of the whole), so sliding caps what reaches them (closed form).
NEVER = {"block mu=0.3", "wall mu=0.6"}
_DONE: dict = {}


def _grid(name):
    if name not in _DONE:
        _DONE[name] = verdict_grid(name)
    return _DONE[name]


def _flips(name, period, ratio, verdict):
    """True if rockarch's verdict at ratio·(1 ± 0.001) differs from ``verdict``."""
    sysobj = MDOFSystem(STRUCTURES[name](), t_free=T_FREE)
    shape = motion.pulse("sine", period=period)
    return any(sysobj.simulate(shape, ratio=ratio * f).overturned != verdict
               for f in (0.999, 1.001))


@pytest.mark.slow
@pytest.mark.parametrize("name", list(STRUCTURES))
def test_verdicts_agree(name):
    ra, pm = _grid(name)
    periods, ratios = GRIDS[name]
    agree = float(np.mean(ra == pm))
    off = [(periods[i], ratios[j], bool(ra[i, j])) for i, j in np.argwhere(ra != pm)]
    # a chaotic verdict is not pinned: a differing cell where rockarch's own verdict flips
    # within ±0.1 % of the amplitude sits on a fractal boundary (docs/validation.md)
    sensitive = [c for c in off if _flips(name, *c)]
    print(f"\n{name}: agreement {agree:.3f} over {ra.size} cells; rockarch overturned "
          f"{int(ra.sum())}, pymunk {int(pm.sum())}; (T, ratio, rockarch) differing: {off}; "
          f"of them sensitive to ±0.1 % of the amplitude: {sensitive}")
    firm = [c for c in off if c not in sensitive]
    assert len(firm) <= 3, f"cells (T, ratio, rockarch verdict) in disagreement: {firm}"
    if name in NEVER:
        assert not ra.any()
    else:
        assert ra.any() and not ra.all()  # the grid crosses the boundary


@pytest.mark.slow
def test_verdicts_agree_overall():
    same = [np.ravel(ra == pm) for ra, pm in map(_grid, STRUCTURES)]
    assert float(np.mean(np.concatenate(same))) >= 0.95


@pytest.mark.parametrize("width", [0.4, 2.0])
def test_block_sliding_off_a_pedestal_as_pymunk(width):
    # the pedestal block of test_friction (mu = 0.1, step pulses of 0.5 g): pymunk, with
    # real polygons, tips the block over the edge of the narrow pedestal exactly when
    # rockarch does (Newmark slip > B/2) and slides it the Newmark distance on the wide one
    # (measured agreement: 4 digits; asserted to 1 mm, pymunk's slop and step are far below)
    from tests.validation.test_friction import _on_pedestal

    a = _on_pedestal(width)
    for duration in (0.1, 0.15, 0.2, 0.3):
        r = mdof.simulate(a, motion.step(0.5 * G, duration), t_free=2.0)
        disp, rot = po.run(a, lambda t, d=duration: 0.5 * G if t < d else 0.0,
                           duration + 2.0)
        assert r.overturned == (rot > ROT_FALL)
        if not r.overturned:
            assert r.max_slip == pytest.approx(disp, abs=1e-3)
