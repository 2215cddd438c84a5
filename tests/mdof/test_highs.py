"""The warm-started HiGHS model of the non-associative iteration (rockarch.mdof.highs)."""

import numpy as np
import pytest

from rockarch.mdof.highs import Model


def test_model_resolves_after_changes_and_reports_infeasible():
    # max x0 + x1 s.t. x0 + x1 <= 1, x1 >= x0: optimum 1 (exact vertex arithmetic)
    m = Model(np.array([[1.0, 1.0], [1.0, -1.0]]), [0, 0], [np.inf, np.inf], [-1.0, -1.0],
              [-np.inf, -np.inf], [1.0, 0.0])
    x, duals = m.solve()
    assert x.sum() == pytest.approx(1.0, abs=1e-12) and duals.shape == (2,)
    m.row_bounds([0], [-np.inf], [2.0])
    m.costs([-1.0, -2.0])
    x, _ = m.solve()
    assert x == pytest.approx([0.0, 2.0], abs=1e-12)  # from the previous basis
    assert m.solve(warm=False)[0] == pytest.approx([0.0, 2.0], abs=1e-12)
    m.col_bounds([0, 1], [3.0, 0.0], [4.0, 0.0])  # x0 >= 3 with x0 + x1 <= 2: infeasible
    assert m.solve() is None


def test_no_banner_on_stdout(capfd):
    # the CLI's --json output must stay one line: highspy.Highs() prints a banner
    Model(np.eye(1), [0], [1], [-1.0], [0], [1]).solve()
    assert capfd.readouterr().out == ""
