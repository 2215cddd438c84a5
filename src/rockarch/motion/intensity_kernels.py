"""Numba kernel of the linear SDOF oscillator under piecewise-linear base acceleration (reach
it through :mod:`rockarch.motion.intensity`).

The oscillator u'' + 2ζω u' + ω² u = −a_g(t) is stepped with the exact recurrence of a
piecewise-linear excitation (Nigam & Jennings 1969; docs/theory.md Eq. (11.6)):

    [u, u']_{k+1} = Φ_xx [u, u']_k + Φ_xa a_k + Φ_xs (a_{k+1} − a_k)/h,

with Φ = exp(K h) the exponential of the system matrix K of the augmented state
[u, u', a_g, a_g'] (computed in closed form once per period by the caller). Each sample
interval is cut into ``sub`` equal sub-steps (a_g linear inside), so that the peak is
sampled finely enough.
"""

from __future__ import annotations

import numba as nb


@nb.njit(cache=True)
def march(acc, sub, coef, n_free, out):
    """max |u| of the oscillator at rest at t = 0 under ``acc`` (uniform samples).

    Parameters
    ----------
    acc : float64[n]
        Base acceleration at uniform samples [m/s²].
    sub : int
        Sub-steps per sample interval (the coefficients belong to the sub-step h).
    coef : float64[8]
        [Φ_uu, Φ_uv, Φ_vu, Φ_vv, Φ_ua, Φ_va, Φ_us/h, Φ_vs/h] of the sub-step h: the last
        two multiply the change of a_g over one sub-step.
    n_free : int
        Sub-steps of free vibration (a_g = 0) after the last sample.
    out : float64[m]
        If m > 0, u at every sub-step is written to it (m = (n − 1)·sub + 1 + n_free).
    """
    u = 0.0
    v = 0.0
    peak = 0.0
    n = acc.shape[0]
    keep = out.shape[0] > 0
    k = 1
    for i in range(n - 1 + n_free):
        if i < n - 1:
            slope = (acc[i + 1] - acc[i]) / sub
            a0 = acc[i]
            steps = sub
        else:  # after the last sample the ground is at rest: free vibration
            slope = 0.0
            a0 = 0.0
            steps = 1
        for j in range(steps):
            aj = a0 + slope * j
            un = coef[0] * u + coef[1] * v + coef[4] * aj + coef[6] * slope
            vn = coef[2] * u + coef[3] * v + coef[5] * aj + coef[7] * slope
            u = un
            v = vn
            if abs(u) > peak:
                peak = abs(u)
            if keep:
                out[k] = u
                k += 1
    return peak
