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

import sys
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix, hstack, identity, vstack
from tqdm import tqdm

from rockarch.core.console import bar_rows
from rockarch.mdof.highs import Model

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


class _Solver:
    """The LPs (10.6) and (10.8) of one load direction, kept alive between iterations
    (:class:`rockarch.mdof.highs.Model`): every solve starts from the previous optimal basis,
    so it is fast and returns the optimal vertex nearest to the previous one. Without that
    (scipy's linprog, a fresh solve each time) the 205-block walls' iteration wandered
    between vertices of the degenerate LPs and did not converge in 100 LPs."""

    def __init__(self, a_eq, b_eq, nj: int, cap_lambda: float) -> None:
        m, n, rows = 2 * nj, a_eq.shape[1], a_eq.shape[0]
        self.m, self.n, self.rows = m, n, rows
        lo = np.r_[np.zeros(m), np.full(m, -np.inf), 0.0]
        hi = np.r_[np.full(2 * m, np.inf), cap_lambda]
        cost = np.zeros(n)
        cost[-1] = -1.0
        self.tresca = Model(a_eq, lo, hi, cost, b_eq, b_eq)
        # (10.8): e >= |N - Ñ| as N - e <= Ñ and N + e >= Ñ (row bounds set per call)
        eye = identity(m, format="csr")
        pad = csr_matrix((m, n - m))
        a2 = vstack([hstack([a_eq, csr_matrix((rows, m))]), hstack([eye, pad, -eye]),
                     hstack([eye, pad, eye])])
        self.select = Model(a2, np.r_[lo, np.zeros(m)], np.r_[hi, np.full(m, np.inf)],
                            np.zeros(n + m), np.r_[b_eq, np.full(2 * m, -np.inf)],
                            np.r_[b_eq, np.full(2 * m, np.inf)])
        self.t_cols = np.arange(m, 2 * m)

    def solve_tresca(self, cap: np.ndarray) -> Iterate | None:
        """max λ under (10.2) with N ≥ 0 and |T| ≤ cap (Eq. 10.6)."""
        c = cap.reshape(-1)
        self.tresca.col_bounds(self.t_cols, -c, c)
        out = self.tresca.solve()
        return None if out is None else Iterate(float(out[0][-1]), out[0], out[1])

    def solve_select(self, cap, lam: float, target, sliding) -> np.ndarray | None:
        """Among the fields carrying λ (Eq. 10.8): least normal force at sliding joints, and
        closest (L1) to ``target`` elsewhere. The normal forces (nj, 2), or None."""
        m, n = self.m, self.n
        c, t = cap.reshape(-1), target.reshape(-1)
        free = np.repeat(~np.asarray(sliding, bool), 2)
        sel = self.select
        sel.col_bounds(self.t_cols, -c, c)
        sel.col_bounds([n - 1], [lam * (1 - 1e-9)], [lam])
        sel.row_bounds(np.arange(self.rows, self.rows + 2 * m),
                       np.r_[np.full(m, -np.inf), t], np.r_[t, np.full(m, np.inf)])
        sel.costs(np.r_[np.where(free, 0.0, 1.0), np.zeros(n - m), np.where(free, 1.0, 0.0)])
        out = sel.solve()
        return None if out is None else out[0][:m].reshape(-1, 2)


def iterate(a_eq, b_eq, mu, start: Iterate, weight: float, sliding_of,
            cap_lambda: float, *, desc: str | None = None, position: int = 0,
            progress: bool | None = None) -> Outcome:
    """Gilbert–Casapulla–Ahmed iteration from the associative state (Eqs. 10.6–10.8).

    ``sliding_of(duals)`` gives the sliding joints of an LP's mechanism. Normal forces relax
    (10.7), except that the opening corners of joints of μ = ∞ drop to zero at once (their
    capacity depends only on whether a corner is compressed, so relaxing would only creep
    towards zero, one halving per LP). Convergence: |Δλ| ≤ 1e-9·max(1, λ),
    max|N − Ñ| ≤ 1e-7·Σ m·g at finite-μ joints and the same compressed corners at μ = ∞
    joints. Without it (or when frozen capacities cannot carry gravity) the least λ of the
    iterates and of ``start`` (every solution lies below the associative one) is returned,
    not converged (:func:`warn_unconverged` says so). ``desc``: a progress bar of the LPs on
    stderr (line ``position``), shown if ``progress`` (default: when stderr is a terminal).
    """
    nj = len(mu)
    fin = np.isfinite(np.asarray(mu, float))[:, None]
    lps = _Solver(a_eq, b_eq, nj, cap_lambda)
    nt = start.x[:2 * nj].reshape(nj, 2).copy()
    lam_prev, best, hist = start.lambda_, start, []
    show = desc is not None and (sys.stderr.isatty() if progress is None else progress)
    with tqdm(total=MAX_ITER, desc=desc, unit="LP", disable=not show, file=sys.stderr,
              leave=False, position=position, nrows=bar_rows()) as bar:
        for k in range(MAX_ITER):
            bar.update(1)
            cap = shear_caps(mu, nt, weight)
            cur = lps.solve_tresca(cap)
            if cur is None:
                break
            hist.append(cur.lambda_)
            if 0 < cur.lambda_ < best.lambda_:  # above (10.4): no solution; 0: frozen caps
                best = cur
            n_new = lps.solve_select(cap, cur.lambda_, nt, sliding_of(cur.duals))
            if n_new is None:
                n_new = cur.x[:2 * nj].reshape(nj, 2)
            err = float(np.abs(np.where(fin, n_new - nt, 0.0)).max()) / weight
            zero = 1e-9 * weight
            if (abs(cur.lambda_ - lam_prev) <= TOL_LAMBDA * max(1.0, cur.lambda_)
                    and err <= TOL_FORCE and np.array_equal(n_new <= zero, nt <= zero)):
                return Outcome(cur, True, k + 1, tuple(hist))
            # (10.7); at μ = ∞ an opening corner drops to zero at once, the others relax
            lam_prev, nt = cur.lambda_, np.where(fin | (n_new > zero), nt + RELAX * (n_new - nt),
                                                 n_new)
    return Outcome(best, False, len(hist), tuple(hist))


def warn_unconverged(out: Outcome, direction: int) -> None:
    """The RuntimeWarning of an iteration that did not converge (docs/theory.md §10)."""
    lo, hi = min(out.history, default=out.state.lambda_), max(out.history,
                                                              default=out.state.lambda_)
    warnings.warn(f"non-associative limit analysis (direction {direction:+d}) did not "
                  f"converge after {out.iterations} LPs (lambda between {lo:.6g} and "
                  f"{hi:.6g}); ap_min is the smallest, {out.state.lambda_:.6g} g "
                  "(docs/theory.md §10)", RuntimeWarning, stacklevel=4)
