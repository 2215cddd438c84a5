"""Numba kernels of SDOF rocking systems (reach them through :mod:`rockarch.rocking.block` and
:mod:`rockarch.rocking.mechanism`).

One event-driven integrator serves every single-degree-of-freedom rocking system. The
coordinate ``theta`` is signed: on side s = sign(theta) the system is the mechanism that
opens for s·a_g > 0 (for the block: pivot on the left corner for s = +1), with
q = s·theta ≥ 0 its opening coordinate. Two models give theta'':

* ``MODEL_BLOCK`` — Housner's exact equation (docs/theory.md §1)
  theta'' = −p² [sin(s·alpha − theta) − (a_g/g) cos(s·alpha − theta)];
* ``MODEL_TABLE`` — Lagrange's equation of any SDOF mechanism (docs/theory.md §3),
  A(q) q'' + ½ A'(q) q'² = −V'(q) + s·a_g·Q(q), written as
  q'' = k²g [−Wv(q) + s (a_g/g) Wh(q)] − ½ D(q) q'² with Wv = V'/(gA), Wh = Q/A,
  D = A'/A tabulated (linear interpolation) for each side at a reference size, and
  k = p / p_ref the time scale of the actual size (p ∝ 1/sqrt(size) at fixed shape).

Each knot interval of the (piecewise linear) ground motion is integrated with classical RK4
steps of length h ≤ h_factor/p; events are located inside a step to round-off by Newton
iterations on the step length (safeguarded by bisection), re-integrating from the start of
the step, so no step straddles an event:

* uplift: at rest, the first time a_g/g exceeds amin[+] or falls below −amin[−] (exact:
  a_g is linear in a step);
* impact: theta crosses 0: theta' → e·theta' (e of the closing side), the side switches;
* collapse: s·theta reaches level[side] (alpha for the block, delta for a mechanism).

Chatter (settling) criterion: after an impact with post-impact rate w, if the ground does
not hold the system on its new side (s·theta''(0) ≤ 0), its next excursion reaches at most
w²/(2|theta''(0)|). If that is below eps_rest·level the system is put to rest (theta =
theta' = 0); it starts again only when the uplift condition holds. The idealised model
would otherwise need infinitely many impacts in finite time (Zeno).

Status codes of :func:`run`: 0 safe (ended at rest or after the free time), 1 collapsed
(overturned), -2 step limit reached (:func:`run_recorded` turns it into a ValueError).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from rockarch.core import limits
from rockarch.core.jit_cache import kernel_array

MODEL_BLOCK = 0
MODEL_TABLE = 1
_NEWTON_ITERS = 60
#: Step limit of the summary-only runs of :func:`run_batch` (none: an OAS is unchanged).
_NO_LIMIT = np.iinfo(np.int64).max


def motion_arrays(motion, g: float, free_name: str) -> tuple:
    """(knot times, a_g/g at the knots, name, duration) of a motion for :func:`run`;
    ``motion=None``: no ground motion (free motion named ``free_name``)."""
    if motion is None:
        return kernel_array(np.zeros(2)), kernel_array(np.zeros(2)), free_name, 0.0
    return (kernel_array(motion.t), kernel_array(np.asarray(motion.a, dtype=float) / g),
            motion.name, motion.duration)


@nb.njit(cache=True)
def _rhs(model, th, om, s, ag, c, prm, tab):
    """theta'' on side s; c = p² (block) or k²·g (table); ag = a_g/g."""
    if model == MODEL_BLOCK:
        x = s * prm[0] - th
        return -c * (math.sin(x) - ag * math.cos(x))
    i = 0 if s > 0.0 else 1
    q = s * th
    x = q / prm[2 + i]
    n = int(prm[4 + i])
    j = int(math.floor(x))
    if j < 0:
        j = 0
    elif j > n - 2:
        j = n - 2
    f = x - j
    wv = tab[i, 0, j] + f * (tab[i, 0, j + 1] - tab[i, 0, j])
    wh = tab[i, 1, j] + f * (tab[i, 1, j + 1] - tab[i, 1, j])
    d = tab[i, 2, j] + f * (tab[i, 2, j + 1] - tab[i, 2, j])
    return s * (c * (-wv + s * ag * wh) - 0.5 * d * om * om)


@nb.njit(cache=True)
def _rk4(model, th, om, h, a0, am, a1, s, c, prm, tab):
    """One classical RK4 step of length h; a0, am, a1 = a_g/g at the start, middle, end."""
    k1t = om
    k1o = _rhs(model, th, om, s, a0, c, prm, tab)
    k2t = om + 0.5 * h * k1o
    k2o = _rhs(model, th + 0.5 * h * k1t, k2t, s, am, c, prm, tab)
    k3t = om + 0.5 * h * k2o
    k3o = _rhs(model, th + 0.5 * h * k2t, k3t, s, am, c, prm, tab)
    k4t = om + h * k3o
    k4o = _rhs(model, th + h * k3t, k4t, s, a1, c, prm, tab)
    th1 = th + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t)
    om1 = om + h / 6.0 * (k1o + 2.0 * k2o + 2.0 * k3o + k4o)
    return th1, om1


@nb.njit(cache=True)
def _locate(model, th, om, at, slope, hi, s, level, sgn, c, prm, tab):
    """Step length tau in (0, hi] at which theta reaches an event, theta from one RK4 step.

    The event function is g(tau) = sgn·(s·theta(tau) − level): g ≤ 0 before the event
    (at tau = 0) and g > 0 after it (impact: sgn = −1, level = 0; collapse: sgn = +1,
    level = alpha or delta). ``at`` is a_g/g at the start of the step and ``slope`` its
    time derivative. Newton on tau, safeguarded by bisection of the bracket [lo, hi].
    Returns (tau, theta, theta', ok); ok is False if ``hi`` turned out not to be past the
    event (a Hermite estimate that the RK4 step does not confirm).
    """
    lo = 0.0
    f_lo = sgn * (s * th - level)
    th_hi, om_hi = _rk4(model, th, om, hi, at, at + 0.5 * hi * slope, at + hi * slope, s,
                        c, prm, tab)
    f_hi = sgn * (s * th_hi - level)
    if f_hi < 0.0 or (f_hi == 0.0 and sgn < 0.0):
        return hi, th_hi, om_hi, False
    ftol = 1e-13 * max(level, 1e-3)
    tau = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(_NEWTON_ITERS):
        if not (lo < tau < hi):
            tau = 0.5 * (lo + hi)
        th_t, om_t = _rk4(model, th, om, tau, at, at + 0.5 * tau * slope, at + tau * slope,
                          s, c, prm, tab)
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


@nb.njit(cache=True, inline="always")
def _push(record, rs, out_t, out_th, out_om, t, th, om):
    """Append (t, theta, theta') to the history. ``rs`` = [n, stride, count]: n samples
    stored, every stride-th offered sample is kept. A full buffer is halved in place (every
    other sample kept) and the stride doubled: the history stays within the buffer."""
    if not record:
        return
    c = rs[2]
    rs[2] = c + 1
    if c % rs[1] != 0:
        return
    n = rs[0]
    cap = out_t.shape[0]
    if n >= cap:
        half = (n + 1) // 2
        for i in range(half):
            out_t[i] = out_t[2 * i]
            out_th[i] = out_th[2 * i]
            out_om[i] = out_om[2 * i]
        rs[1] *= 2
        n = half
        if c % rs[1] != 0:
            rs[0] = n
            return
    out_t[n] = t
    out_th[n] = th
    out_om[n] = om
    rs[0] = n + 1


@nb.njit(cache=True)
def run(tk, ak, scale, model, c, p, prm, tab, amin, level, e, t_free, h_factor, eps_rest,
        th0, om0, record, max_steps, out_t, out_th, out_om, out_imp):
    """Simulate one SDOF rocking system; see the module docstring.

    Parameters
    ----------
    tk, ak : knots of the ground motion; ``scale·ak`` is a_g/g.
    model, prm, tab : the model (MODEL_BLOCK: prm = [alpha]; MODEL_TABLE: prm = [p_ref, g,
        dq+, dq−, n+, n−] and tab (2, 3, n) = Wv, Wh, D per side).
    c : p² (block) or (p/p_ref)²·g (table).
    p : frequency parameter [1/s] (sets the step bound h_factor/p).
    amin, level, e : per side (index 0: s = +1, 1: s = −1): uplift threshold (a_g/g),
        collapse coordinate, impact coefficient of a closing motion on that side.
    t_free : free motion after the last knot [s].
    eps_rest : settling threshold (fraction of level), see the chatter criterion.
    th0, om0 : initial coordinate and rate (0, 0: at rest).
    record : store the history in out_* (else they may have length 1). A history longer
        than out_t is decimated (see :func:`_push`); the first len(out_imp) impact times
        are stored.
    max_steps : stop with status -2 after this many RK4 steps.

    Returns
    -------
    (status, n_rec, n_imp, t_collapse, max_ratio, t_end, stride), max_ratio = max
    s·theta/level, stride: every stride-th history sample was kept.
    """
    hmax = h_factor / p
    n = tk.shape[0]
    cap_imp = out_imp.shape[0]
    rs = np.array([0, 1, 0], dtype=np.int64)
    steps = 0
    n_imp = 0
    th = th0
    om = om0
    s = 0.0
    resting = th0 == 0.0 and om0 == 0.0
    if th0 != 0.0:
        s = 1.0 if th0 > 0.0 else -1.0
    elif om0 != 0.0:
        s = 1.0 if om0 > 0.0 else -1.0
    max_r = 0.0
    if s != 0.0:
        max_r = s * th0 / level[0 if s > 0.0 else 1]
    t = tk[0]
    _push(record, rs, out_t, out_th, out_om, t, th, om)
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
                    return 0, rs[0], n_imp, np.nan, max_r, t, rs[1]
                if -amin[1] <= at <= amin[0]:
                    # first time in (t, t1] at which a_g leaves [-amin-, amin+]
                    if slope > 0.0:
                        tau = (amin[0] - at) / slope
                    elif slope < 0.0:
                        tau = (-amin[1] - at) / slope
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
                _push(record, rs, out_t, out_th, out_om, t, 0.0, 0.0)
            steps += 1
            if steps > max_steps:
                return -2, rs[0], n_imp, np.nan, max_r, t, rs[1]
            side = 0 if s > 0.0 else 1
            lev = level[side]
            h = min(hmax, t1 - t)
            th1, om1 = _rk4(model, th, om, h, at, at + 0.5 * h * slope, at + h * slope, s,
                            c, prm, tab)
            # event at the step end, or inside the step where theta' changes sign (the
            # extremum of the cubic Hermite interpolant crosses 0 or the level first)
            ev_hi = -1.0
            ev_level = 0.0
            if om * om1 < 0.0:
                x = om / (om - om1)
                th_x = ((2 * x**3 - 3 * x**2 + 1) * th + (x**3 - 2 * x**2 + x) * h * om
                        + (-2 * x**3 + 3 * x**2) * th1 + (x**3 - x**2) * h * om1)
                if s * th_x >= lev:
                    ev_hi = x * h
                    ev_level = lev
                elif s * th_x < 0.0:
                    ev_hi = x * h
                elif s * th_x / lev > max_r:
                    max_r = s * th_x / lev
            if ev_hi < 0.0:
                if s * th1 >= lev:
                    ev_hi = h
                    ev_level = lev
                elif s * th1 < 0.0:
                    ev_hi = h
            ok = False
            tau = 0.0
            th_e = 0.0
            om_e = 0.0
            if ev_hi > 0.0:
                sgn = 1.0 if ev_level > 0.0 else -1.0
                tau, th_e, om_e, ok = _locate(model, th, om, at, slope, ev_hi, s, ev_level,
                                              sgn, c, prm, tab)
            if not ok:
                t = t + h
                th = th1
                om = om1
                if s * th / lev > max_r:
                    max_r = s * th / lev
                _push(record, rs, out_t, out_th, out_om, t, th, om)
                continue
            t = t + tau
            if ev_level > 0.0:
                th = s * lev
                om = om_e
                max_r = 1.0
                rs[2] = 0  # the collapse state is always kept
                _push(record, rs, out_t, out_th, out_om, t, th, om)
                return 1, rs[0], n_imp, t, max_r, t, rs[1]
            # impact at theta = 0: the side switches, theta' -> e·theta'
            _push(record, rs, out_t, out_th, out_om, t, 0.0, om_e)
            if record and n_imp < cap_imp:
                out_imp[n_imp] = t
            n_imp += 1
            om = e[side] * om_e
            s = -s
            th = 0.0
            at = a0 + slope * (t - t0)
            acc = _rhs(model, 0.0, 0.0, s, at, c, prm, tab)
            if s * acc <= 0.0:
                # the ground cannot hold the system on its new side: chatter criterion
                if om * om <= 2.0 * eps_rest * level[0 if s > 0.0 else 1] * abs(acc) \
                        or om == 0.0:
                    resting = True
                    om = 0.0
                    s = 0.0
            _push(record, rs, out_t, out_th, out_om, t, 0.0, om)
    return 0, rs[0], n_imp, np.nan, max_r, t, rs[1]


def check_steps(tk, t_free: float, p: float, h_factor: float) -> float:
    """RK4 steps one run may take at most (one per knot and per h_factor/p seconds of
    motion and free motion, docs/theory.md Eq. (8.5)), known before the work; ValueError
    above :func:`rockarch.core.limits.max_steps` (``p``: the largest of a batch)."""
    span = float(tk[-1] - tk[0]) + float(t_free)
    need = tk.shape[0] + span * float(p) / float(h_factor)
    if not need <= limits.max_steps():
        raise limits.too_many(f"a simulation of {span:.6g} s at p = {float(p):.4g} 1/s", need,
                              "steps", limits.max_steps(),
                              "lower --t-free, --p or the motion's duration")
    return need


def run_recorded(tk, ak, scale, model, c, p, prm, tab, amin, level, e, t_free, h_factor,
                 eps_rest, th0, om0, capacity):
    """:func:`run` with the history in buffers of ``capacity`` samples (at most
    :func:`rockarch.core.limits.max_samples`), enlarged and rerun while the history was
    decimated below that limit; at the limit the history is decimated (the verdict is the
    same). Returns (status, t_collapse, max_ratio, t_end, t, theta, theta', impact_times,
    stride); raises ValueError, before any work, if the run may need more than
    :func:`rockarch.core.limits.max_steps` RK4 steps (docs/theory.md Eq. (8.5))."""
    limit = limits.max_samples()
    need = check_steps(tk, t_free, p, h_factor)
    max_steps = 2 * int(need) + 1000  # safety net: events split steps
    cap = max(min(int(capacity), limit), 16)
    while True:
        out = [np.empty(cap) for _ in range(4)]
        status, n_rec, n_imp, t_c, mx, t_end, stride = run(
            tk, ak, scale, model, c, p, prm, tab, amin, level, e, float(t_free),
            float(h_factor), float(eps_rest), float(th0), float(om0), True, max_steps, *out)
        if status == -2:
            raise ValueError(f"the simulation stopped at t = {t_end:.6g} s after "
                             f"{max_steps:.3g} integration steps (twice the estimate)")
        if stride == 1 or cap >= limit:
            # a mostly full buffer is returned as is (no second copy at the memory peak)
            hist = [b[:n] if 2 * n >= cap else b[:n].copy()
                    for b, n in zip(out, (n_rec, n_rec, n_rec, min(n_imp, cap)), strict=True)]
            return (status, t_c, mx, t_end, *hist, int(stride))
        cap = min(cap * 4, limit)


@nb.njit(cache=True)
def _summary_options():
    """(record, max_steps) of a summary-only run of a batch, returned by a function so that
    numba types them bool, int64 as :func:`run_recorded` passes them: :func:`run` is
    compiled once for both (constants would compile a second, literal-typed copy)."""
    return np.bool_(False), np.int64(_NO_LIMIT)


@nb.njit(cache=True, parallel=True)
def run_batch(tk, ak, scales, model, cs, ps, prm, tab, amin, level, e, t_free, h_factor,
              eps_rest):
    """Run many (c, p, scale) triples for one motion in parallel; summaries only.

    Returns (status, t_collapse, max_ratio, n_impacts) arrays.
    """
    m = ps.shape[0]
    status = np.zeros(m, dtype=np.int8)
    t_ov = np.full(m, np.nan)
    mx = np.zeros(m)
    nimp = np.zeros(m, dtype=np.int64)
    dummy = np.zeros(1)
    record, limit = _summary_options()
    for i in nb.prange(m):
        st, _, ni, tov, mxa, _, _ = run(tk, ak, scales[i], model, cs[i], ps[i], prm, tab,
                                        amin, level, e, t_free, h_factor, eps_rest, 0.0, 0.0,
                                        record, limit, dummy, dummy, dummy, dummy)
        status[i] = st
        t_ov[i] = tov
        mx[i] = mxa
        nimp[i] = ni
    return status, t_ov, mx, nimp
