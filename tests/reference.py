"""Independent references for the rigid block: exact quadratures of Housner's equation.

These do not use rockarch's integrator: they follow from energy conservation of the exact
(nonlinear) equation theta'' = -p² [sin(alpha - theta) - (a/g) cos(alpha - theta)] for
theta > 0 under a constant ground acceleration (docs/theory.md §1).
"""

import math

from scipy.integrate import quad
from scipy.optimize import brentq


def free_quarter_period(p: float, alpha: float, theta0: float) -> float:
    """Time from release at theta0 (rest) to the first impact, exact equation.

    t = ∫_0^theta0 dθ / sqrt(2p² [cos(α−θ) − cos(α−θ0)]), with θ = θ0 − w² removing the
    end singularity and cos A − cos B written as a product of sines (no cancellation).
    """

    def integrand(w):
        th = theta0 - w * w
        d = 2.0 * math.sin((2 * alpha - th - theta0) / 2) * math.sin((th - theta0) / -2)
        if w == 0.0:
            return 2.0 / math.sqrt(2 * p * p * math.sin(alpha - theta0))
        return 2.0 * w / math.sqrt(2 * p * p * d)

    return quad(integrand, 0.0, math.sqrt(theta0), epsabs=1e-14, epsrel=1e-13, limit=200)[0]


def step_overturns(p: float, alpha: float, rho: float, T: float) -> bool:
    """Does a step impulse a = rho·g·tan(alpha) on [0, T] overturn the block (exact)?

    During the step: theta'' = −(p²/cos β)·sin(α − β − θ), tan β = ρ·tan α, so
    ½θ'² = (p²/cos β)[cos(u0) − cos(u0 − θ)], u0 = α − β, and t(θ) is a quadrature.
    After it (a = 0) the block reaches α iff ½θ'_T² ≥ p²(1 − cos(α − θ_T)).
    """
    beta = math.atan(rho * math.tan(alpha))
    c = p * p / math.cos(beta)
    u0 = alpha - beta

    def integrand(w):
        th = w * w
        if w == 0.0:
            return 2.0 / math.sqrt(2 * c * math.sin(-u0))
        return 2.0 * w / math.sqrt(2 * c * 2 * math.sin(th / 2 - u0) * math.sin(th / 2))

    def t_of(th):
        return quad(integrand, 0.0, math.sqrt(th), epsabs=1e-14, epsrel=1e-13, limit=200)[0]

    if t_of(alpha) <= T:
        return True
    th_t = brentq(lambda th: t_of(th) - T, 0.0, alpha, xtol=1e-15, rtol=1e-14)
    kin = c * 2 * math.sin(th_t / 2 - u0) * math.sin(th_t / 2)  # ½θ'_T²
    return kin >= p * p * 2 * math.sin((alpha - th_t) / 2) ** 2


def step_boundary(p: float, alpha: float, T: float, tol: float = 1e-11) -> float:
    """Lowest overturning ratio of a step impulse, by bisection on :func:`step_overturns`."""
    lo, hi = 1.0, 50.0
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if step_overturns(p, alpha, mid, T):
            hi = mid
        else:
            lo = mid
    return hi
