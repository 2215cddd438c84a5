"""Non-associative Coulomb friction in the limit analysis of assemblies (docs/theory.md §10).

The LP of :mod:`rockarch.mdof.statics` (Eq. 10.4) takes the friction cone as its yield
surface, so a joint can only slide while it opens at μ times the slip rate (associative
dilatancy), and a joint carrying no normal force can still carry shear when μ = ∞. Real
Coulomb friction slides without dilatancy. Following Gilbert, Casapulla & Ahmed (2006,
Computers & Structures 84), every joint's shear capacity is frozen at μ times the normal
force of the previous iterate (a Tresca-like, dilatancy-free condition, Eq. 10.6), the LP
is solved again, and the normal forces are relaxed towards the new ones until they stop
changing (Eq. 10.7). Among the LP's optimal force fields the one closest to the previous
normal forces is kept, except at joints sliding in the LP's mechanism, whose normal force
is made as small as possible (no self-stress props a sliding joint), Eq. (10.8).

The converged state is statically admissible for Coulomb friction and its mechanism slides
without dilatancy; it is *a* solution of the non-associative problem, not a bound (that
problem can have several; :mod:`rockarch.mdof.macroblock` looks for lower ones). Without
convergence the smallest load multiplier of the iterates is returned with a warning.
"""

from __future__ import annotations

import math
import sys
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import csr_matrix, hstack, identity, vstack
from tqdm import tqdm

#: Relaxation factor of the normal forces that set the shear capacities (Eq. 10.7); the
#: value is our choice.
RELAX = 0.5
#: Largest number of Tresca LPs per direction.
MAX_ITER = 100  # converged cases take 20-65 (walls up to 6 x 10 courses)
#: Convergence: change of λ (relative) and of the normal forces (relative to Σ m·g).
TOL_LAMBDA, TOL_FORCE = 1e-9, 1e-7


@dataclass(frozen=True)
class Iterate:
    """One solved state of the iteration: LP solution x = (N, T, λ) and its duals."""

    lambda_: float
    x: np.ndarray
    duals: np.ndarray


@dataclass(frozen=True)
class Outcome:
    """The result of :func:`iterate`: the returned state and how it was reached."""

    state: Iterate
    converged: bool
    iterations: int
    history: tuple


def shear_caps(mu: np.ndarray, normal: np.ndarray, weight: float) -> np.ndarray:
    """Shear capacity μ·Ñ of every corner (Eq. 10.6); μ = ∞: unbounded while compressed,
    zero once the normal force is below 1e-9 of the weight (an open joint holds nothing)."""
    m2 = np.repeat(np.asarray(mu, float)[:, None], 2, axis=1)
    fin = np.isfinite(m2)
    cap = np.where(fin, np.where(fin, m2, 0.0) * normal, np.inf)
    return np.where(~fin & (normal <= 1e-9 * weight), 0.0, cap)


def _bounds(cap: np.ndarray, cap_lambda: float) -> list:
    nj = cap.shape[0]
    tb = [(None, None) if math.isinf(c) else (-c, c) for c in cap.reshape(-1)]
    return [(0.0, None)] * (2 * nj) + tb + [(0.0, cap_lambda)]


def tresca_lp(a_eq, b_eq, cap: np.ndarray, cap_lambda: float):
    """max λ under (10.2) with N ≥ 0 and |T| ≤ cap (Eq. 10.6): scipy's result object."""
    n = a_eq.shape[1]
    cost = np.zeros(n)
    cost[-1] = -1.0
    return linprog(cost, A_eq=a_eq, b_eq=b_eq, bounds=_bounds(cap, cap_lambda),
                   method="highs")


def select(a_eq, b_eq, cap, lam: float, target: np.ndarray, sliding: np.ndarray,
           cap_lambda: float) -> np.ndarray | None:
    """Among the fields carrying λ (Eq. 10.8): least normal force at sliding joints, and
    closest (L1) to ``target`` elsewhere. Returns the normal forces (nj, 2) or None."""
    nj = cap.shape[0]
    m, n = 2 * nj, a_eq.shape[1]
    free = np.repeat(~np.asarray(sliding, bool), 2)
    eye = identity(m, format="csr")
    pad = csr_matrix((m, n - m))
    a_ub = vstack([hstack([eye, pad, -eye]), hstack([-eye, pad, -eye])]).tocsr()
    t = target.reshape(-1)
    b_ub = np.concatenate([t, -t])
    a2 = hstack([a_eq, csr_matrix((a_eq.shape[0], m))]).tocsr()
    bounds = _bounds(cap, cap_lambda)[:-1] + [(lam * (1 - 1e-9), lam)] + [(0.0, None)] * m
    cost = np.concatenate([np.where(free, 0.0, 1.0), np.zeros(n - m),
                           np.where(free, 1.0, 0.0)])
    res = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a2, b_eq=b_eq, bounds=bounds,
                  method="highs")
    return res.x[:m].reshape(nj, 2) if res.status == 0 else None


def iterate(a_eq, b_eq, mu, start: Iterate, weight: float, sliding_of,
            cap_lambda: float, *, desc: str | None = None, position: int = 0,
            progress: bool | None = None) -> Outcome:
    """Gilbert–Casapulla–Ahmed iteration from the associative state (Eqs. 10.6–10.8).

    ``sliding_of(duals)`` gives the sliding joints of an LP's mechanism. Convergence:
    |Δλ| ≤ 1e-9·max(1, λ) and max|N − Ñ| ≤ 1e-7·Σ m·g. Without it (or when frozen
    capacities cannot carry gravity) the least λ of the iterates and of ``start`` (every
    solution lies below the associative one) is returned, not converged
    (:func:`warn_unconverged` says so). ``desc``: a progress bar of the LPs on stderr
    (line ``position``), shown if ``progress`` (default: when stderr is a terminal).
    """
    nj = len(mu)
    nt = start.x[:2 * nj].reshape(nj, 2).copy()
    lam_prev, best, hist = start.lambda_, start, []
    show = desc is not None and (sys.stderr.isatty() if progress is None else progress)
    with tqdm(total=MAX_ITER, desc=desc, unit="LP", disable=not show, file=sys.stderr,
              leave=False, position=position) as bar:
        for k in range(MAX_ITER):
            bar.update(1)
            cap = shear_caps(mu, nt, weight)
            res = tresca_lp(a_eq, b_eq, cap, cap_lambda)
            if res.status != 0:
                break
            cur = Iterate(float(res.x[-1]), res.x, np.asarray(res.eqlin.marginals))
            hist.append(cur.lambda_)
            if 0 < cur.lambda_ < best.lambda_:  # above (10.4): no solution; 0: frozen caps
                best = cur
            n_new = select(a_eq, b_eq, cap, cur.lambda_, nt, sliding_of(cur.duals),
                           cap_lambda)
            if n_new is None:
                n_new = res.x[:2 * nj].reshape(nj, 2)
            err = float(np.abs(n_new - nt).max()) / weight
            if (abs(cur.lambda_ - lam_prev) <= TOL_LAMBDA * max(1.0, cur.lambda_)
                    and err <= TOL_FORCE):
                return Outcome(cur, True, k + 1, tuple(hist))
            lam_prev, nt = cur.lambda_, nt + RELAX * (n_new - nt)
    return Outcome(best, False, len(hist), tuple(hist))


def warn_unconverged(out: Outcome, direction: int) -> None:
    """The RuntimeWarning of an iteration that did not converge (docs/theory.md §10)."""
    lo, hi = min(out.history, default=out.state.lambda_), max(out.history,
                                                              default=out.state.lambda_)
    warnings.warn(f"non-associative limit analysis (direction {direction:+d}) did not "
                  f"converge after {out.iterations} LPs (lambda between {lo:.6g} and "
                  f"{hi:.6g}); ap_min is the smallest, {out.state.lambda_:.6g} g "
                  "(docs/theory.md §10)", RuntimeWarning, stacklevel=4)
