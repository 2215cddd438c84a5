"""The contact stepper's records passed by reference (rockarch.core.jit_struct)."""

import copy

import numpy as np
import pytest

from rockarch.mdof import builders as bd
from rockarch.mdof import graph_stepper as gs
from rockarch.mdof.kernel_data import GraphModel, graph_model


def test_records_read_from_python_and_share_memory_with_the_kernels():
    a = bd.wall(2, 2, 0.4, 0.2, mu=0.6)
    m = graph_model(a)
    assert isinstance(m, GraphModel)
    assert np.array_equal(m.mass, a.mass) and m.ba.dtype == np.int64
    assert m.kbody >= 2 and m.mu_contact == pytest.approx(0.6)
    ws = gs.make_work(m, 2.0, m.contact_cap)
    # the kernel scaled the corners by 2 and zeroed its work arrays
    assert np.allclose(ws.ra, 2.0 * m.ra) and not ws.lam.any()
    # a field named like numba's own constructor variable ("st") is a field like any other
    assert ws.sw.st.dtype == np.int8 and ws.sw.st.shape == ws.lam.shape
    # Python reads are views of the kernel's arrays, not copies
    ws.sw.state[2] = 7
    assert ws.sw.state[2] == 7
    with pytest.raises(AttributeError, match="no field 'nope'"):
        _ = ws.nope
    assert repr(ws.rows) == "Rows(rba, rbb, ja, jb, tn0, tn1, tmu)"


def test_a_deep_copy_is_independent():
    m = graph_model(bd.wall(2, 2, 0.4, 0.2, mu=0.6))
    ws = gs.make_work(m, 1.0, m.contact_cap)
    cp = copy.deepcopy(ws)
    cp.lam[0] = 1.0
    cp.sw.state[0] = 5
    assert ws.lam[0] == 0.0 and ws.sw.state[0] == 0
    assert np.array_equal(cp.rows.tmu, ws.rows.tmu)
