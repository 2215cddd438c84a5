"""Rigid rocking block (Housner): parameters, exact equation of motion, simulation.

Sign convention (docs/theory.md §1, used everywhere in rockarch): x to the right, y up,
rotations positive counter-clockwise; a_g > 0 accelerates the ground to the right, so the
inertia load pushes the block to the left. theta > 0: the block pivots on its *left* bottom
corner. At rest it starts to rock when |a_g| > ap,min = g·tan(alpha), with
sign(theta) = sign(a_g). It overturns when |theta| reaches alpha.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockarch.core import limits
from rockarch.core.constants import EPS_REST, T_FREE, G
from rockarch.core.constants import SDOF_H_FACTOR as H_FACTOR
from rockarch.core.response import Batch, Response, run_batch
from rockarch.core.validate import frequency, in_range, positive, show
from rockarch.motion.signals import GroundMotion
from rockarch.rocking import kernels as _k

_NO_TABLE = np.zeros((2, 3, 2))


#: Largest slenderness of Housner's impact law [rad]: 1 − 1.5·sin²(alpha) = 0 at
#: asin(sqrt(2/3)) ≈ 0.9553 (B/H = sqrt(2)); above it the law gives r < 0.
HOUSNER_ALPHA_MAX = math.asin(math.sqrt(2.0 / 3.0))


def housner_restitution(alpha: float) -> float:
    """Housner's coefficient of restitution r = 1 − 1.5·sin²(alpha) of a rectangular block:
    the ratio of angular velocities after and before impact from the conservation of
    angular momentum about the new pivot (Housner 1963, BSSA 53(2); his energy ratio is its
    square; docs/theory.md Eq. (1.6)); negative above :data:`HOUSNER_ALPHA_MAX`, where
    callers refuse it."""
    return 1.0 - 1.5 * math.sin(alpha) ** 2


@dataclass(frozen=True)
class RigidBlock:
    """A free-standing rigid rectangular block, defined by (p, alpha) (paper Eq. 1).

    Parameters
    ----------
    p : float
        Frequency parameter sqrt(3g / (4R)) [1/s] (Housner 1963; docs/theory.md Eq. (1.2)).
    alpha : float
        Slenderness angle atan(B/H) [rad], in (0, π/2).
    g : float
        Acceleration of gravity [m/s²].
    restitution : float or None
        Angular-velocity ratio at impact, in [0, 1]; None for Housner's value.
    """

    p: float
    alpha: float
    g: float = G
    restitution: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "p", frequency("p", self.p))
        object.__setattr__(self, "alpha", in_range("alpha", self.alpha, 0.0, math.pi / 2,
                                                   lo_open=True, hi_open=True))
        object.__setattr__(self, "g", positive("g", self.g))
        if self.restitution is not None:
            object.__setattr__(self, "restitution",
                               in_range("restitution", self.restitution, 0.0, 1.0))
        elif self.alpha > HOUSNER_ALPHA_MAX:
            raise ValueError(
                f"Housner's restitution 1 - 1.5 sin²(alpha) is negative "
                f"({housner_restitution(self.alpha):.4g}) for alpha = {self.alpha:g} rad > "
                f"{HOUSNER_ALPHA_MAX:.4f} rad (B/H > 1.414): give the restitution "
                "(--restitution R in [0, 1]; 0: the block stops at its first impact)")

    @classmethod
    def from_dimensions(cls, width: float, height: float, g: float = G,
                        restitution: float | None = None) -> RigidBlock:
        """Block of full width B and full height H [m] (paper Eq. 1): p = sqrt(3g/(4R)),
        R the half-diagonal, and alpha = atan(B/H) (Housner 1963)."""
        b, h, g = positive("width B", width), positive("height H", height), positive("g", g)
        r_half = 0.5 * math.hypot(b, h)
        return cls(math.sqrt(3.0 * g / (4.0 * r_half)), math.atan2(b, h), g, restitution)

    @property
    def R(self) -> float:  # noqa: N802 - the field's name
        """Half-diagonal R = 3g / (4p²) [m]."""
        return 3.0 * self.g / (4.0 * self.p**2)

    @property
    def width(self) -> float:
        """Full width B = 2R·sin(alpha) [m]."""
        return 2.0 * self.R * math.sin(self.alpha)

    @property
    def height(self) -> float:
        """Full height H = 2R·cos(alpha) [m]."""
        return 2.0 * self.R * math.cos(self.alpha)

    @property
    def ap_min(self) -> float:
        """Limit acceleration g·tan(alpha) [m/s²]: below it the block does not move."""
        return self.g * math.tan(self.alpha)

    @property
    def r(self) -> float:
        """Coefficient of restitution in use (Housner's unless given)."""
        return housner_restitution(self.alpha) if self.restitution is None else self.restitution

    def kernel_args(self) -> tuple:
        """(model, prm, tab, amin, level, e) of :func:`rockarch.rocking.kernels.run`."""
        r = self.r
        return (_k.MODEL_BLOCK, np.array([self.alpha]), _NO_TABLE,
                np.full(2, math.tan(self.alpha)), np.full(2, self.alpha), np.array([r, r]))

    def theta_ddot(self, theta, a_g):
        """Angular acceleration of Housner's exact equation (docs/theory.md Eq. 1.4)."""
        theta = np.asarray(theta, dtype=float)
        s = np.where(theta >= 0.0, 1.0, -1.0)
        x = s * self.alpha - theta
        return -self.p**2 * (np.sin(x) - np.asarray(a_g) / self.g * np.cos(x))


@dataclass(frozen=True, kw_only=True, repr=False)
class BlockResponse(Response):
    """Time history of one block simulation (a :class:`~rockarch.core.response.Response`).

    ``t``, ``theta``, ``theta_dot`` are sampled at every integration step and event
    (every ``stride``-th of them when the history would exceed
    :func:`rockarch.core.limits.max_samples`); ``impact_times`` holds the impact times (the
    first max_samples of them); ``max_rotation_ratio`` is max |theta|/alpha.
    """

    block: RigidBlock
    theta: np.ndarray
    theta_dot: np.ndarray
    impact_times: np.ndarray
    stride: int = 1


def _check_settings(t_free: float, h_factor: float, eps_rest: float) -> None:
    in_range("t_free", t_free, 0.0, math.inf, hi_open=True)
    in_range("h_factor (RK4 step · p)", h_factor, 1e-4, 0.5)
    in_range("eps_rest", eps_rest, 0.0, 1e-2)


def simulate(block: RigidBlock, motion: GroundMotion | None, *, t_free: float = T_FREE,
             theta0: float = 0.0, theta_dot0: float = 0.0, h_factor: float = H_FACTOR,
             eps_rest: float = EPS_REST) -> BlockResponse:
    """Simulate the block on the ground motion (Housner, docs/theory.md Eqs. 1.4–1.6).

    The motion is used as given (m/s²); free rocking continues ``t_free`` seconds after it
    ends, or until the block rests. ``motion=None`` is free rocking from (theta0,
    theta_dot0) for ``t_free`` seconds. See :mod:`rockarch.rocking.kernels` for the
    integrator, event location and the chatter criterion.
    """
    _check_settings(t_free, h_factor, eps_rest)
    th0 = in_range("theta0", theta0, -block.alpha, block.alpha, lo_open=True, hi_open=True)
    om0 = float(theta_dot0)
    if not math.isfinite(om0):
        raise ValueError(f"theta_dot0 must be finite, got {show(theta_dot0)}")
    tk, ak, name, duration = _k.motion_arrays(motion, block.g, "free rocking")
    cap = history_capacity(tk.size, duration + t_free, block.p, h_factor)
    model, prm, tab, amin, level, e = block.kernel_args()
    status, t_ov, mx, t_end, t, th, om, imp, stride = _k.run_recorded(
        tk, ak, 1.0, model, block.p**2, block.p, prm, tab, amin, level, e, t_free, h_factor,
        eps_rest, th0, om0, cap)
    return BlockResponse(
        system=f"block p={block.p:g} alpha={block.alpha:g}", block=block, motion_name=name,
        t=t, theta=th, theta_dot=om, impact_times=imp, impacts=int(imp.size),
        overturned=bool(status == 1), t_overturn=float(t_ov) if status == 1 else None,
        max_rotation_ratio=float(mx), t_end=float(t_end), stride=stride)


def history_capacity(n_knots: int, duration: float, p: float, h_factor: float) -> int:
    """Samples a recorded SDOF history is expected to need (one per RK4 step of at most
    h_factor/p and per knot, +10 % and 1024 for events), capped at
    :func:`rockarch.core.limits.max_samples` before anything is allocated (docs/theory.md
    Eq. (8.6)); a longer history is decimated, the verdict is unchanged."""
    need = n_knots + duration * p / h_factor * 1.1 + 1024
    return int(min(need, limits.max_samples()))


def simulate_batch(block: RigidBlock, motion: GroundMotion, p, ratio, *,
                   t_free: float = T_FREE, h_factor: float = H_FACTOR,
                   eps_rest: float = EPS_REST) -> Batch:
    """Blocks of ``block``'s alpha at many frequency parameters p_i, on the motion scaled
    to PGA = ratio_i·ap,min, in parallel (numba threads on every core).

    ``block.p`` is ignored (each run has its own p); ``p`` and ``ratio`` broadcast. The
    motion's *shape* is used: normalised to unit peak and scaled so that its peak |a_g| is
    ratio·g·tan(alpha) (the OAS axes, docs/theory.md Eq. 2.1); with the exact equation g
    drops out.
    """
    _check_settings(t_free, h_factor, eps_rest)
    unit = motion.normalized()
    tk = np.ascontiguousarray(unit.t)
    ak = np.ascontiguousarray(unit.a)
    tan_a = math.tan(block.alpha)
    model, prm, tab, amin, level, e = block.kernel_args()

    def run(ps, rs):
        if ps.size:  # the work of the longest run, before any (Eq. 8.5)
            _k.check_steps(tk, t_free, float(np.max(ps)), h_factor)
        return _k.run_batch(tk, ak, rs * tan_a, model, ps * ps, ps, prm, tab, amin, level,
                            e, float(t_free), float(h_factor), float(eps_rest))

    return run_batch(p, ratio, run)
