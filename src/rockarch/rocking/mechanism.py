"""Single-degree-of-freedom (SDOF) rocking mechanisms in motion (docs/theory.md §3, §5).

A mechanism has two sides: side + opens for a positive ground acceleration (a_g > 0, inertia
load to the left), side − is the mechanism that forms for a_g < 0 (for a symmetric structure
the mirror image). On each side q ≥ 0 is its opening coordinate and Lagrange's equation

    A(q) q'' + ½ A'(q) q'² = −V'(q) + s·a_g·Q(q)                (docs/theory.md Eq. 3.1)

holds, with A the generalised inertia, V the potential of gravity and Q the generalised force
per unit ground acceleration (Bv = V'(0), Bh = Q(0), ap,min = g·Bv/Bh, delta: V'(delta) = 0,
p² = Bv/(A(0)·delta), paper Eq. 12–13). The functions are tabulated at a reference size; a
structure of the same shape at another size has p ∝ 1/sqrt(size) and the same equation in
the time scaled by p/p_ref (the kernel does this), so an OAS sweeps p by scaling the size.

When q returns to 0 the mechanism of the other side takes over with an impact that projects
the velocity field onto the new mechanism in the kinetic-energy metric,
q_new' = e·|q_old'| with e = −(J_newᵀ M J_old)/(J_newᵀ M J_new) (docs/theory.md §5; for
a rectangular block this is Housner's r = 1 − 1.5 sin²alpha). A user value overrides it.
Collapse: q reaches delta (the neutral position; the criterion used for the block).

Concrete mechanisms: :func:`from_block` (Housner's block, tabulated exactly), :func:`generic`
(given only p, delta, ap,min: the dimensionless equivalence form), :func:`rocking_frame`, and
the four-hinge arch in :func:`rockarch.rocking.fourhinge_motion.fourhinge_mechanism`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from rockarch.core.constants import EPS_REST, T_FREE, G
from rockarch.core.constants import SDOF_H_FACTOR as H_FACTOR
from rockarch.core.response import Batch, Response, run_batch
from rockarch.core.validate import frequency, in_range, positive
from rockarch.motion.signals import GroundMotion
from rockarch.rocking import kernels as _k
from rockarch.rocking.block import history_capacity, housner_restitution

#: Intervals of the tables of A, V', Q over [0, delta]. Linear interpolation of smooth
#: functions with 4000 intervals is accurate to ~(delta/4000)²·|f''|/8: ~1e-9 relative.
TABLE_INTERVALS = 4000


@dataclass(frozen=True)
class MechanismSide:
    """One side of an SDOF mechanism at the reference size (docs/theory.md §3).

    Attributes
    ----------
    q : (n,) uniform grid of the opening coordinate over [0, q_max], q_max ≥ delta.
    A, dA, dV, Q : (n,) generalised inertia, its derivative, gravity's generalised moment
        V'(q) (includes g) and the generalised force per unit ground acceleration.
    delta : neutral position (collapse level), rad (or the coordinate's unit).
    e_close : impact coefficient when this side closes and the other one opens.
    """

    q: np.ndarray
    A: np.ndarray
    dA: np.ndarray
    dV: np.ndarray
    Q: np.ndarray
    delta: float
    e_close: float

    @property
    def Bv(self) -> float:  # noqa: N802 - the field's name
        return float(self.dV[0])

    @property
    def Bh(self) -> float:  # noqa: N802
        return float(self.Q[0])

    @property
    def A0(self) -> float:  # noqa: N802
        return float(self.A[0])

    @property
    def ap_min(self) -> float:
        """Bv/Bh [m/s²] (Bv includes g, Bh is per unit ground acceleration): below it this
        side does not open (docs/theory.md §3)."""
        return self.Bv / self.Bh

    def p(self) -> float:
        """sqrt(Bv / (A(0)·delta)) at the reference size (paper Eq. 12)."""
        return math.sqrt(self.Bv / (self.A0 * self.delta))


def tabulate(delta: float, A: Callable, dA: Callable, dV: Callable, Q: Callable,
             e_close: float, n: int = TABLE_INTERVALS) -> MechanismSide:
    """Sample the mechanism functions on [0, delta] (vectorised callables of q)."""
    q = np.linspace(0.0, delta, n + 1)
    vals = [np.broadcast_to(np.asarray(f(q), dtype=float), q.shape).copy()
            for f in (A, dA, dV, Q)]
    for name, v in zip(("A", "A'", "V'", "Q"), vals, strict=True):
        if not np.all(np.isfinite(v)):
            raise ValueError(f"the mechanism's {name}(q) is not finite on [0, delta]")
    if np.any(vals[0] <= 0):
        raise ValueError("the generalised inertia A(q) must be > 0")
    if vals[2][0] <= 0 or vals[3][0] <= 0:
        raise ValueError("gravity must resist (Bv > 0) and the ground drive (Bh > 0) "
                         "the mechanism at q = 0")
    return MechanismSide(q, *vals, delta=float(delta), e_close=float(e_close))


@dataclass(frozen=True)
class SDOFMechanism:
    """An SDOF rocking mechanism: its two sides at a reference size (docs/theory.md §3, §5).

    Attributes
    ----------
    name : short description.
    plus, minus : the sides opening for a_g > 0 and a_g < 0.
    g : gravity [m/s²].
    size : reference size (e.g. the span) at which the tables hold [m]; p ∝ 1/sqrt(size).
    restitution : None (the projection impact law of each side) or a user value r in
        [0, 1]: the kinetic energy after an impact is r² times the energy before (for
        sides with equal A(0), the coordinate rate is multiplied by r, as for Housner).
    info : extra parameters for reports.
    """

    name: str
    plus: MechanismSide
    minus: MechanismSide
    g: float = G
    size: float = 1.0
    restitution: float | None = None
    info: dict = field(default_factory=dict, compare=False)

    def __repr__(self) -> str:
        """One line: the name, kind, p, delta and ap_min (not the tables of its sides)."""
        r = "" if self.restitution is None else f", restitution {self.restitution:.4g}"
        return (f"SDOFMechanism({self.name!r}, {self.info.get('kind', 'mechanism')}: "
                f"p {self.p:.4g} 1/s, delta {self.delta:.4g} rad, "
                f"ap_min {self.ap_min:.4g} m/s²{r})")

    def __post_init__(self) -> None:
        if self.restitution is not None:
            object.__setattr__(self, "restitution",
                               in_range("restitution", self.restitution, 0.0, 1.0))
        else:
            e = min(self.plus.e_close, self.minus.e_close)
            if e < 0:
                raise ValueError(
                    f"{self.name}: its impact law gives a negative coefficient of "
                    f"restitution ({e:.4g}): the law does not apply to so stocky a mechanism; "
                    "give the restitution (--restitution R in [0, 1]; 0: it stops at its "
                    "first impact)")

    @property
    def p(self) -> float:
        """Frequency parameter of side + at the reference size [1/s] (paper Eq. 12)."""
        return self.plus.p()

    @property
    def delta(self) -> float:
        return self.plus.delta

    @property
    def ap_min(self) -> float:
        """Limit acceleration [m/s²]: the smaller of the two sides' (nothing moves below)."""
        return min(self.plus.ap_min, self.minus.ap_min)

    def size_for(self, p: float) -> float:
        """Size of the same shape whose frequency parameter is p (p ∝ 1/sqrt(size))."""
        return self.size * (self.p / frequency("p", p)) ** 2

    def with_restitution(self, restitution: float | None) -> SDOFMechanism:
        return SDOFMechanism(self.name, self.plus, self.minus, self.g, self.size, restitution,
                             self.info)

    def kernel_args(self) -> tuple:
        """(model, prm, tab, amin, level, e) of :func:`rockarch.rocking.kernels.run`."""
        sides = (self.plus, self.minus)
        n = max(s.q.size for s in sides)
        tab = np.zeros((2, 3, n))
        for i, sd in enumerate(sides):
            m = sd.q.size
            tab[i, 0, :m] = sd.dV / (self.g * sd.A)
            tab[i, 1, :m] = sd.Q / sd.A
            tab[i, 2, :m] = sd.dA / sd.A
        prm = np.array([self.p, self.g, self.plus.q[1], self.minus.q[1],
                        float(self.plus.q.size), float(self.minus.q.size)])
        amin = np.array([s.ap_min / self.g for s in sides])
        level = np.array([s.delta for s in sides])
        if self.restitution is None:
            e = np.array([s.e_close for s in sides])
        else:  # kinetic energy ratio r² whatever the two sides' coordinates
            e = self.restitution * np.sqrt(np.array([self.plus.A0 / self.minus.A0,
                                                     self.minus.A0 / self.plus.A0]))
        return _k.MODEL_TABLE, prm, tab, amin, level, e


def from_block(p: float, alpha: float, g: float = G, restitution: float | None = None
               ) -> SDOFMechanism:
    """Housner's rectangular block as a tabulated mechanism (docs/theory.md §1).

    Per unit mass and R = 3g/(4p²): A = (4/3)R², V' = gR·sin(alpha − q),
    Q = R·cos(alpha − q), delta = alpha, e = 1 − 1.5 sin²alpha. Reproduces
    :func:`rockarch.rocking.block.simulate` to the table accuracy.
    """
    p, g = frequency("p", p), positive("g", g)
    alpha = in_range("alpha", alpha, 0.0, math.pi / 2, lo_open=True, hi_open=True)
    r_half = 3.0 * g / (4.0 * p * p)
    side = tabulate(alpha, lambda q: np.full_like(q, 4.0 / 3.0 * r_half**2),
                    lambda q: np.zeros_like(q), lambda q: g * r_half * np.sin(alpha - q),
                    lambda q: r_half * np.cos(alpha - q), housner_restitution(alpha))
    return SDOFMechanism(f"block alpha={alpha:g}", side, side, g, r_half, restitution,
                         {"kind": "block", "alpha": alpha})


def generic(p: float, delta: float, ap_min: float, g: float = G,
            restitution: float | None = None) -> SDOFMechanism:
    """Any mechanism given only (p, delta, ap,min): the dimensionless equivalence form.

    DeJong & Dimitrakopoulos (paper ref. [13]; docs/theory.md §1, §3): for slender mechanisms
    and small q, phi = q/delta obeys phi'' = p²·(phi − 1 + s·a_g/ap,min) on each side. The
    impact coefficient defaults to Housner's value for a block with alpha = delta.
    """
    p, g = frequency("p", p), positive("g", g)
    delta = in_range("delta", delta, 0.0, math.pi / 2, lo_open=True, hi_open=True)
    ap_min = positive("ap_min", ap_min)
    # per unit inertia: A = 1, V' = p²(delta − q), Q = p²·delta/ap_min
    side = tabulate(delta, np.ones_like, np.zeros_like, lambda q: p * p * (delta - q),
                    lambda q: np.full_like(q, p * p * delta / ap_min),
                    housner_restitution(delta), n=2)
    return SDOFMechanism(f"SDOF p={p:g} 1/s, delta={delta:g} rad, ap,min={ap_min:g} m/s²",
                         side, side, g, 1.0, restitution,
                         {"kind": "generic", "delta": delta, "ap_min": ap_min})


def rocking_frame(alpha: float, p_column: float, mass_ratio: float, g: float = G,
                  restitution: float | None = None) -> SDOFMechanism:
    """Two equal rigid columns and a rigid lintel (paper Fig. 1, middle).

    Columns of slenderness alpha and half-diagonal R = 3g/(4 p_column²), each of mass m_c,
    rock about opposite bottom corners; the lintel (mass m_b = mass_ratio·2·m_c, i.e.
    gamma = m_b/(2 m_c)) rests on their top corners and translates with them. Per unit m_c:

        A = (8/3 + 8·gamma)·R²,  V' = 2gR(1 + 2 gamma)·sin(alpha − q),
        Q = 2R(1 + 2 gamma)·cos(alpha − q),  delta = alpha,  ap,min = g·tan(alpha),

    so p² = (3g/4R)·(1 + 2 gamma)/(1 + 3 gamma) (Makris & Vassiliou 2013, EESD 42(3), the
    frame's frequency parameter). The projection impact law (docs/theory.md Eq. (5.3))
    gives e = 1 − 1.5·sin²(alpha)·(1 + 4 gamma)/(1 + 3 gamma) (our derivation; gamma = 0:
    Housner's 1963 block).
    """
    alpha = in_range("alpha", alpha, 0.0, math.pi / 2, lo_open=True, hi_open=True)
    p_column, g = positive("p_column", p_column), positive("g", g)
    gamma = in_range("mass_ratio", mass_ratio, 0.0, math.inf, hi_open=True)
    r_half = 3.0 * g / (4.0 * p_column**2)
    k = 1.0 + 2.0 * gamma
    e = 1.0 - 1.5 * math.sin(alpha) ** 2 * (1.0 + 4.0 * gamma) / (1.0 + 3.0 * gamma)
    side = tabulate(alpha, lambda q: np.full_like(q, (8.0 / 3.0 + 8.0 * gamma) * r_half**2),
                    lambda q: np.zeros_like(q),
                    lambda q: 2.0 * g * r_half * k * np.sin(alpha - q),
                    lambda q: 2.0 * r_half * k * np.cos(alpha - q), e)
    return SDOFMechanism(f"frame alpha={alpha:g} gamma={gamma:g}", side, side, g,
                         r_half, restitution, {"kind": "frame", "alpha": alpha,
                                               "gamma": gamma, "p_column": p_column})


@dataclass(frozen=True, kw_only=True, repr=False)
class MechanismResponse(Response):
    """Time history of one SDOF mechanism simulation (a :class:`~rockarch.core.response.Response`).

    ``u`` is signed: u > 0 on side + (opening for a_g > 0), u < 0 on side −; ``u_dot`` its
    rate; ``max_rotation_ratio`` is max |u|/delta of the active side; ``p`` the frequency
    parameter of the simulated size; ``stride`` > 1: every stride-th sample is kept (a
    history longer than :func:`rockarch.core.limits.max_samples`; the verdict is exact).
    """

    mechanism: SDOFMechanism
    p: float
    u: np.ndarray
    u_dot: np.ndarray
    impact_times: np.ndarray
    stride: int = 1


def _settings(t_free, h_factor, eps_rest):
    in_range("t_free", t_free, 0.0, math.inf, hi_open=True)
    in_range("h_factor (RK4 step · p)", h_factor, 1e-4, 0.5)
    in_range("eps_rest", eps_rest, 0.0, 1e-2)


def simulate(mech: SDOFMechanism, motion: GroundMotion | None, *, p: float | None = None,
             t_free: float = T_FREE, u0: float = 0.0, u_dot0: float = 0.0,
             h_factor: float = H_FACTOR, eps_rest: float = EPS_REST) -> MechanismResponse:
    """Simulate the mechanism (at the size whose frequency parameter is ``p``; default: the
    reference size) on the ground motion [m/s²] (docs/theory.md §3)."""
    _settings(t_free, h_factor, eps_rest)
    p = mech.p if p is None else frequency("p", p)
    model, prm, tab, amin, level, e = mech.kernel_args()
    lim = mech.plus.delta if u0 >= 0 else mech.minus.delta
    u0 = in_range("u0", u0, -lim, lim, lo_open=True, hi_open=True)
    tk, ak, name, duration = _k.motion_arrays(motion, mech.g, "free motion")
    c = (p / mech.p) ** 2 * mech.g
    cap = history_capacity(tk.size, duration + t_free, p, h_factor)
    status, t_c, mx, t_end, t, u, ud, imp, stride = _k.run_recorded(
        tk, ak, 1.0, model, c, p, prm, tab, amin, level, e, t_free, h_factor, eps_rest, u0,
        float(u_dot0), cap)
    return MechanismResponse(
        system=mech.name, mechanism=mech, p=p, motion_name=name, t=t, u=u, u_dot=ud,
        impact_times=imp, impacts=int(imp.size), overturned=bool(status == 1),
        t_overturn=float(t_c) if status == 1 else None, max_rotation_ratio=float(mx),
        t_end=float(t_end), stride=stride)


def simulate_batch(mech: SDOFMechanism, motion: GroundMotion, p, ratio, *,
                   t_free: float = T_FREE, h_factor: float = H_FACTOR,
                   eps_rest: float = EPS_REST) -> Batch:
    """Many (p, ratio) pairs in parallel: the motion's shape scaled to a peak of
    ratio·ap,min, the mechanism scaled to frequency parameter p (docs/theory.md Eq. 2.1)."""
    _settings(t_free, h_factor, eps_rest)
    unit = motion.normalized()
    tk, ak = np.ascontiguousarray(unit.t), np.ascontiguousarray(unit.a)
    model, prm, tab, amin, level, e = mech.kernel_args()

    def run(pp, rs):
        if pp.size:  # the work of the longest run, before any (Eq. 8.5)
            _k.check_steps(tk, t_free, float(np.max(pp)), h_factor)
        return _k.run_batch(tk, ak, rs * mech.ap_min / mech.g, model,
                            (pp / mech.p) ** 2 * mech.g, pp, prm, tab, amin, level, e,
                            float(t_free), float(h_factor), float(eps_rest))

    return run_batch(p, ratio, run)
