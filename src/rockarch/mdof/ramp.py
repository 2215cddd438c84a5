"""The load at which the time-stepping engine starts a mechanism under a slow ramp of ground
acceleration: the dynamic counterpart of ap,min (docs/assemblies.md, "What ap,min means";
docs/theory.md §10).

Non-associative limit analysis can have several solutions; ap,min (Eqs. 10.6–10.9) is the
lowest one found, the safe value. A real assembly, built without self-stress, may stand
above it: LMGC90 collapses the 4 × 3 wall of 0.4 × 0.2 m blocks at 0.69 g with μ = 2 and
0.84 g with μ = 10, where ap,min is the end wedge's 0.636 g. :func:`ramp_onset` shows that
spread with rockarch's own engine (:func:`rockarch.mdof.simulate`, Moreau–Jean with Coulomb
friction, §9): the ground acceleration rises linearly at ``rate`` from ``start``·ap,min,
from rest, and the onset is the ground acceleration when the largest centroid displacement
first exceeds ``threshold``·size (LMGC90's "stands" criterion is 1 mm on a ~1 m structure).
The ramp ends at twice the associative LP's λ·g (Eq. 10.4; above λ·g no Coulomb-admissible
field exists, so a mechanism has started and grown). It is run in stages ending at 1/16,
1/8, 1/4, 1/2 and all of that range, each from rest and in both directions, and stops at
the first stage in which something moves, so the engine does not run long after the onset.
The onset found is late by the time the motion takes to grow to the threshold: about
0.2 s, i.e. 0.02 g at 0.1 g/s, for a 0.4 × 1 m block (an upper estimate of the load).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockarch.core.constants import GAP_TOL
from rockarch.core.constants import MDOF_H_FACTOR as H_FACTOR
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.simulate import _simulate
from rockarch.mdof.statics import collapse
from rockarch.motion.signals import GroundMotion

#: Default ramp rate [g/s], start [ap,min] and displacement threshold [size].
RATE, START, THRESHOLD = 0.1, 0.9, 1e-3
#: Sampling step of the ramp's ground motion [s] (the engine's own step is finer).
DT = 1e-3
#: The ramp is run in stages (each from rest) ending at these fractions of its range.
STAGES = (1 / 16, 1 / 8, 1 / 4, 1 / 2, 1.0)


@dataclass(frozen=True)
class RampOnset:
    """The onset of motion under a slow ramp, per load direction.

    Attributes
    ----------
    ap_onset : float
        The smaller onset over both directions [m/s²] (inf: none before the ramp's end).
    direction : int
        Its direction (+1: ground accelerating to +x).
    onsets : dict
        {+1: onset [m/s²], -1: onset} (inf where nothing moved).
    rate, threshold : float
        Ramp rate [m/s³] and displacement threshold [m].
    end : float
        Last ground acceleration of the ramp that was run [m/s²]: a direction without
        motion (inf) stood up to it.
    """

    ap_onset: float
    direction: int
    onsets: dict
    rate: float
    threshold: float
    end: float


def _first_motion(assembly: Assembly, a0: float, end: float, rate: float, thr: float,
                  sign: int) -> float:
    """The ground acceleration when the displacement first exceeds ``thr`` on the ramp
    from ``a0`` to ``end`` (from rest), or inf."""
    dur = (end - a0) / rate
    t = np.linspace(0.0, dur, max(int(math.ceil(dur / DT)), 2) + 1)
    acc = sign * (a0 + (end - a0) * t / dur)
    label = f"slow ramp {'+' if sign > 0 else '−'}x to {end / assembly.g:.3g} g"
    r = _simulate(assembly, GroundMotion(t, acc, f"ramp to {end:.4g} m/s²"), p=None,
                  t_free=0.0, h_factor=H_FACTOR, gap_tol=GAP_TOL, record_every=1,
                  through_collapse=False, skip_rest=True, progress=None, label=label)
    q = r.q
    d = np.hypot(q[:, :, 0] - q[0, :, 0], q[:, :, 1] - q[0, :, 1]).max(axis=1)
    moved = np.flatnonzero(d > thr)
    return float(a0 + (end - a0) * min(r.t[moved[0]] / dur, 1.0)) if len(moved) else math.inf


def ramp_onset(assembly: Assembly, *, rate: float = RATE, start: float = START,
               threshold: float = THRESHOLD) -> RampOnset:
    """The ground acceleration at which a slow linear ramp starts a mechanism (module doc).

    Parameters
    ----------
    assembly : Assembly
    rate : float
        Ramp rate in g per second (> 0; slow: 0.1 g/s takes ~10 s of simulated time per
        g of spread).
    start : float
        First ground acceleration of the ramp, in units of ap,min (0 < start <= 1: the
        structure stands there).
    threshold : float
        Displacement that counts as motion, in units of the assembly's size.
    """
    for name, v, hi in (("rate", rate, math.inf), ("start", start, 1.0),
                        ("threshold", threshold, 1.0)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and 0 < v <= hi):
            raise ValueError(f"{name} must be a number in (0, {hi:g}], got {v!r}")
    if not math.isfinite(assembly.ap_min):
        raise ValueError("the assembly has no finite ap,min to start the ramp from")
    g = assembly.g
    upper = collapse(assembly, friction="associative").ap_min
    a0 = start * assembly.ap_min
    a1 = 2.0 * (upper if math.isfinite(upper) else assembly.ap_min)
    thr = threshold * assembly.size
    onsets = {1: math.inf, -1: math.inf}
    end = a1
    for frac in STAGES:  # both directions per stage: the first motion ends the search
        end = a0 + frac * (a1 - a0)
        onsets = {s: _first_motion(assembly, a0, end, rate * g, thr, s) for s in (1, -1)}
        if min(onsets.values()) < math.inf:
            break
    d = min(onsets, key=lambda s: onsets[s])
    return RampOnset(ap_onset=onsets[d], direction=d, onsets=onsets, rate=rate * g,
                     threshold=thr, end=end)
