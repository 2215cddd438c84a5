"""Numba kernels of the rigid rocking block (reach them through :mod:`rockarch.block`).

Event-driven integration of Housner's exact equation (physics note section 1)

    theta'' = -p² [ sin(s·alpha − theta) − (a_g/g) cos(s·alpha − theta) ],  s = sign(theta)

with the ground acceleration piecewise linear between knots. Each knot interval is
integrated with classical RK4 steps of length h ≤ h_max (h_max = c/p); events are located
inside a step to round-off by Newton iterations on the step length (safeguarded by
bisection), re-integrating from the start of the step, so event times are as accurate as
the RK4 solution itself and no step straddles an event:

* uplift: at rest, the first time |a_g| exceeds ap,min (exact: a_g is linear in a step);
* impact: theta crosses 0: theta' -> r·theta', the pivot switches;
* overturning: |theta| reaches alpha.

Chatter (settling) criterion: after an impact with post-impact rate w, if the ground does
not hold the block on its new side, its next excursion reaches at most
theta_peak = w² / (2·|theta''(0)|). If theta_peak < eps_rest·alpha the block is put to rest
(theta = theta' = 0); it starts again only when |a_g| > ap,min. The idealised model would
otherwise need infinitely many impacts in finite time (Zeno), each r times slower.

Status codes returned by :func:`run`: 0 safe (ended at rest or after the free time),
1 overturned, -1 output buffer full (the caller enlarges it and calls again).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

_NEWTON_ITERS = 60


@nb.njit(cache=True, inline="always")
def _rhs(th, s, ag, p2, alpha):
    x = s * alpha - th
    return -p2 * (math.sin(x) - ag * math.cos(x))


@nb.njit(cache=True)
def _rk4(th, om, h, a0, am, a1, s, p2, alpha):
    """One classical RK4 step of length h; a0, am, a1 = a_g/g at the start, middle, end."""
    k1t = om
    k1o = _rhs(th, s, a0, p2, alpha)
    k2t = om + 0.5 * h * k1o
    k2o = _rhs(th + 0.5 * h * k1t, s, am, p2, alpha)
    k3t = om + 0.5 * h * k2o
    k3o = _rhs(th + 0.5 * h * k2t, s, am, p2, alpha)
    k4t = om + h * k3o
    k4o = _rhs(th + h * k3t, s, a1, p2, alpha)
    th1 = th + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t)
    om1 = om + h / 6.0 * (k1o + 2.0 * k2o + 2.0 * k3o + k4o)
    return th1, om1


@nb.njit(cache=True)
def _locate(th, om, at, slope, hi, s, level, sgn, p2, alpha):
    """Step length tau in (0, hi] at which theta reaches an event, theta from one RK4 step.

    The event function is g(tau) = sgn·(s·theta(tau) − level): g ≤ 0 before the event
    (at tau = 0) and g > 0 (impact, sgn = −1, level = 0) or g ≥ 0 (overturning, sgn = +1,
    level = alpha) after it. ``at`` is a_g/g at the start of the step and ``slope`` its time
    derivative. Newton on tau, safeguarded by bisection of the bracket [lo, hi].
    Returns (tau, theta, theta', ok); ok is False if ``hi`` turned out not to be past the
    event (a Hermite estimate that the RK4 step does not confirm).
    """
    lo = 0.0
    f_lo = sgn * (s * th - level)
    th_hi, om_hi = _rk4(th, om, hi, at, at + 0.5 * hi * slope, at + hi * slope, s, p2, alpha)
    f_hi = sgn * (s * th_hi - level)
    if f_hi < 0.0 or (f_hi == 0.0 and sgn < 0.0):
        return hi, th_hi, om_hi, False
    ftol = 1e-13 * alpha
    tau = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(_NEWTON_ITERS):
        if not (lo < tau < hi):
            tau = 0.5 * (lo + hi)
        th_t, om_t = _rk4(th, om, tau, at, at + 0.5 * tau * slope, at + tau * slope,
                          s, p2, alpha)
        f = sgn * (s * th_t - level)
        d = sgn * s * om_t
        if abs(f) <= ftol and d > 0.0:
            return tau, th_t, om_t, True
        if f > 0.0:
            hi = tau
            th_hi = th_t
            om_hi = om_t
        else:
            lo = tau
        if hi - lo <= 4e-16 * max(hi, 1.0):
            break
        tau = tau - f / d if d != 0.0 else 0.5 * (lo + hi)
    return hi, th_hi, om_hi, True


@nb.njit(cache=True)
def run(tk, ak, scale, p, alpha, r, t_free, h_factor, eps_rest, th0, om0,
        record, out_t, out_th, out_om, out_imp):
    """Simulate one block; see the module docstring.

    Parameters
    ----------
    tk, ak : knots of the ground motion; ``scale·ak`` is a_g/g.
    scale : multiplier of ``ak`` giving a_g/g.
    p, alpha, r : frequency parameter [1/s], slenderness [rad], restitution.
    t_free : free-rocking time after the last knot [s].
    h_factor : RK4 step bound h_max = h_factor / p.
    eps_rest : settling threshold (fraction of alpha), see the chatter criterion.
    th0, om0 : initial rotation and rate (0, 0: at rest).
    record : store the history in out_* (else they may have length 1).

    Returns
    -------
    (status, n_rec, n_imp, t_overturn, max_abs_theta, t_end)
    """
    p2 = p * p
    amin = math.tan(alpha)
    hmax = h_factor / p
    n = tk.shape[0]
    cap = out_t.shape[0]
    cap_imp = out_imp.shape[0]
    n_rec = 0
    n_imp = 0
    th = th0
    om = om0
    s = 0.0
    resting = th0 == 0.0 and om0 == 0.0
    if th0 != 0.0:
        s = 1.0 if th0 > 0.0 else -1.0
    elif om0 != 0.0:
        s = 1.0 if om0 > 0.0 else -1.0
    max_abs = abs(th0)
    t = tk[0]
    if record:
        out_t[0] = t
        out_th[0] = th
        out_om[0] = om
        n_rec = 1
    for seg in range(n):
        if seg < n - 1:
            t0 = tk[seg]
            t1 = tk[seg + 1]
            a0 = scale * ak[seg]
            a1 = scale * ak[seg + 1]
            free = False
        else:
            t0 = tk[n - 1]
            t1 = t0 + t_free
            a0 = 0.0
            a1 = 0.0
            free = True
        if t1 <= t0:
            continue
        slope = (a1 - a0) / (t1 - t0)
        t = t0
        while t < t1:
            at = a0 + slope * (t - t0)
            if resting:
                if free:
                    return 0, n_rec, n_imp, np.nan, max_abs, t
                if abs(at) <= amin:
                    # first time in (t, t1] at which |a_g| exceeds amin
                    if slope > 0.0:
                        tau = (amin - at) / slope
                    elif slope < 0.0:
                        tau = (-amin - at) / slope
                    else:
                        tau = np.inf
                    if t + tau >= t1:
                        t = t1
                        continue
                    t = t + tau
                    at = a0 + slope * (t - t0)
                    s = 1.0 if slope > 0.0 else -1.0
                else:
                    s = 1.0 if at > 0.0 else -1.0
                resting = False
                th = 0.0
                om = 0.0
                if record:
                    if n_rec >= cap:
                        return -1, n_rec, n_imp, np.nan, max_abs, t
                    out_t[n_rec] = t
                    out_th[n_rec] = 0.0
                    out_om[n_rec] = 0.0
                    n_rec += 1
            h = min(hmax, t1 - t)
            th1, om1 = _rk4(th, om, h, at, at + 0.5 * h * slope, at + h * slope, s, p2, alpha)
            # event at the step end, or inside the step where theta' changes sign (the
            # extremum of the cubic Hermite interpolant crosses 0 or alpha first)
            ev_hi = -1.0
            ev_level = 0.0
            if om * om1 < 0.0:
                x = om / (om - om1)
                th_x = ((2 * x**3 - 3 * x**2 + 1) * th + (x**3 - 2 * x**2 + x) * h * om
                        + (-2 * x**3 + 3 * x**2) * th1 + (x**3 - x**2) * h * om1)
                if s * th_x >= alpha:
                    ev_hi = x * h
                    ev_level = alpha
                elif s * th_x < 0.0:
                    ev_hi = x * h
                elif abs(th_x) > max_abs:
                    max_abs = abs(th_x)
            if ev_hi < 0.0:
                if s * th1 >= alpha:
                    ev_hi = h
                    ev_level = alpha
                elif s * th1 < 0.0:
                    ev_hi = h
            ok = False
            if ev_hi > 0.0:
                sgn = 1.0 if ev_level > 0.0 else -1.0
                tau, th_e, om_e, ok = _locate(th, om, at, slope, ev_hi, s, ev_level, sgn,
                                              p2, alpha)
            if not ok:
                t = t + h
                th = th1
                om = om1
                if abs(th) > max_abs:
                    max_abs = abs(th)
                if record:
                    if n_rec >= cap:
                        return -1, n_rec, n_imp, np.nan, max_abs, t
                    out_t[n_rec] = t
                    out_th[n_rec] = th
                    out_om[n_rec] = om
                    n_rec += 1
                continue
            t = t + tau
            if ev_level > 0.0:
                th = s * alpha
                om = om_e
                max_abs = alpha
                if record:
                    if n_rec >= cap:
                        return -1, n_rec, n_imp, np.nan, max_abs, t
                    out_t[n_rec] = t
                    out_th[n_rec] = th
                    out_om[n_rec] = om
                    n_rec += 1
                return 1, n_rec, n_imp, t, max_abs, t
            # impact at theta = 0: the pivot switches, theta' -> r·theta'
            if record:
                if n_rec + 1 >= cap or n_imp >= cap_imp:
                    return -1, n_rec, n_imp, np.nan, max_abs, t
                out_t[n_rec] = t
                out_th[n_rec] = 0.0
                out_om[n_rec] = om_e
                n_rec += 1
                out_imp[n_imp] = t
            n_imp += 1
            s = -s
            th = 0.0
            om = r * om_e
            at = a0 + slope * (t - t0)
            acc = _rhs(0.0, s, at, p2, alpha)
            if s * acc <= 0.0:
                # the ground cannot hold the block on its new side: chatter criterion
                if om * om <= 2.0 * eps_rest * alpha * abs(acc) or om == 0.0:
                    resting = True
                    om = 0.0
                    s = 0.0
            if record:
                out_t[n_rec] = t
                out_th[n_rec] = 0.0
                out_om[n_rec] = om
                n_rec += 1
    return 0, n_rec, n_imp, np.nan, max_abs, t


@nb.njit(cache=True, parallel=True)
def run_batch(tk, ak, scales, ps, alpha, r, t_free, h_factor, eps_rest):
    """Run many (p, scale) pairs for one motion in parallel; summaries only.

    Returns (status, t_overturn, max_abs_theta, n_impacts) arrays.
    """
    m = ps.shape[0]
    status = np.zeros(m, dtype=np.int8)
    t_ov = np.full(m, np.nan)
    mx = np.zeros(m)
    nimp = np.zeros(m, dtype=np.int64)
    dummy = np.zeros(1)
    for i in nb.prange(m):
        st, _, ni, tov, mxa, _ = run(tk, ak, scales[i], ps[i], alpha, r, t_free, h_factor,
                                     eps_rest, 0.0, 0.0, False, dummy, dummy, dummy,
                                     dummy)
        status[i] = st
        t_ov[i] = tov
        mx[i] = mxa
        nimp[i] = ni
    return status, t_ov, mx, nimp
