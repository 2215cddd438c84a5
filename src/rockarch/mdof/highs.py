"""A linear programme kept alive between solves: HiGHS through highspy, warm-started.

The non-associative iteration of :mod:`rockarch.mdof.nonassoc` (docs/theory.md §10,
Eqs. 10.6–10.8) solves the same two LPs a hundred times with new bounds, costs and row
bounds. scipy's ``linprog`` builds and solves each from scratch, so every solve may land on
another optimal vertex of a degenerate LP, and the iteration then wanders without
converging (the 205-block walls, docs/performance.md). A model kept here starts every solve
from the previous optimal basis (HiGHS' simplex hot start): it is faster, and it returns
the optimal vertex nearest to the previous one, which is what lets the fixed point settle.
"""

from __future__ import annotations

import numpy as np
from highspy import _core
from scipy.sparse import csc_matrix

#: HiGHS' infinity (bounds beyond it are free).
INF = float(_core.kHighsInf)


def _highs():
    """A silent HiGHS instance (``_Highs`` prints no banner on stdout; ``Highs`` does)."""
    h = getattr(_core, "_Highs", None)
    h = h() if h is not None else __import__("highspy").Highs()
    h.setOptionValue("output_flag", False)
    return h


def _finite(v) -> np.ndarray:
    return np.nan_to_num(np.asarray(v, dtype=float), posinf=INF, neginf=-INF)


class Model:
    """min cost·x subject to row_lo <= A x <= row_hi, lo <= x <= hi (any bound may be ±inf).

    :meth:`solve` returns ``(x, row_duals)`` or None when HiGHS does not report an optimum;
    later changes of bounds or costs keep the basis, so the next solve starts from it.
    """

    def __init__(self, a, lo, hi, cost, row_lo, row_hi) -> None:
        a = csc_matrix(a)
        lp = _core.HighsLp()
        lp.num_col_, lp.num_row_ = a.shape[1], a.shape[0]
        lp.col_cost_ = np.asarray(cost, dtype=float)
        lp.col_lower_, lp.col_upper_ = _finite(lo), _finite(hi)
        lp.row_lower_, lp.row_upper_ = _finite(row_lo), _finite(row_hi)
        lp.a_matrix_.format_ = _core.MatrixFormat.kColwise
        lp.a_matrix_.start_ = a.indptr.astype(np.int32)
        lp.a_matrix_.index_ = a.indices.astype(np.int32)
        lp.a_matrix_.value_ = a.data.astype(float)
        self.h = _highs()
        self.h.passModel(lp)
        self.n = a.shape[1]

    def col_bounds(self, idx, lo, hi) -> None:
        idx = np.asarray(idx, dtype=np.int32)
        self.h.changeColsBounds(len(idx), idx, _finite(lo), _finite(hi))

    def row_bounds(self, idx, lo, hi) -> None:
        idx, lo, hi = np.asarray(idx, dtype=np.int32), _finite(lo), _finite(hi)
        if hasattr(self.h, "changeRowsBounds"):
            self.h.changeRowsBounds(len(idx), idx, lo, hi)
        else:  # highspy < 1.9
            for i, a, b in zip(idx.tolist(), lo.tolist(), hi.tolist(), strict=True):
                self.h.changeRowBounds(i, a, b)

    def costs(self, cost) -> None:
        self.h.changeColsCost(self.n, np.arange(self.n, dtype=np.int32),
                              np.asarray(cost, dtype=float))

    def solve(self, *, warm: bool = True) -> tuple[np.ndarray, np.ndarray] | None:
        """Solve from the previous basis (``warm``) or from scratch."""
        if not warm:
            self.h.clearSolver()
        self.h.run()
        if self.h.getModelStatus() != _core.HighsModelStatus.kOptimal:
            return None
        sol = self.h.getSolution()
        return np.asarray(sol.col_value), np.asarray(sol.row_dual)
