"""Non-associative friction in the limit analysis (docs/theory.md §10, Eqs. 10.6-10.8):
where nothing slides the associative LP is returned unchanged, the converged state is
Coulomb-admissible, and a non-converged iteration warns and returns the safer value."""

import math

import numpy as np
import pytest

from rockarch import mdof
from rockarch.arch import catenary
from rockarch.core.constants import G
from rockarch.mdof import builders as bd
from rockarch.mdof import nonassoc, statics
from rockarch.mdof.linkage import corner_velocity

# HiGHS solves to ~1e-9 relative (primal/dual feasibility 1e-7 on forces of order 1).
LP_TOL = 1e-7


@pytest.mark.parametrize("make", [
    lambda: bd.bridge(catenary(10.0, 3.0, 0.25), 10, pier_height=3.0, pier_width=1.5),
    lambda: bd.bridge(catenary(10.0, 3.0, 0.25), 10, pier_height=3.0, pier_width=1.5, mu=0.5),
    lambda: bd.with_friction(mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 10), 0.5),
    lambda: bd.colonnade(2, 0.3, 2.0, 1.0, 0.4),
])
def test_nothing_slides_gives_the_associative_state_bit_for_bit(make):
    # the associative state is a fixed point of (10.6)-(10.8): returned as it is
    a = make()
    c, ca = statics.collapse(a), statics.collapse(a, friction="associative")
    assert c.iterations == 0 and c.converged
    assert c.ap_min == ca.ap_min and np.array_equal(c.normal_force, ca.normal_force)
    assert np.array_equal(c.velocity, ca.velocity)


def test_converged_state_is_coulomb_admissible_and_slides_without_dilatancy():
    r = [[0, 0], [0.4, 0], [0.4, 1.0], [0, 1.0]]
    a = bd.from_polygons([r], supports=[[[0.4, 0], [1.4, 0], [1.4, 2], [0.4, 2]]], mu=0.5)
    c = statics.collapse(a)
    assert c.converged and c.iterations > 1
    # |T| <= mu N at every corner (to the iteration's force tolerance 1e-7 of the weight)
    tol = 1e-6 * float(a.mass.sum())
    assert np.all(np.abs(c.tangential_force) <= 0.5 * c.normal_force + tol)
    # the support joint slides and opens; B/H = 0.4 g (closed form)
    k = int(np.flatnonzero(np.abs(a.normal[:, 0]) > 0.5)[0])  # the vertical face
    assert c.sliding[k] and c.opening[k].any()
    assert c.ap_min == pytest.approx(0.4 * G, rel=LP_TOL)


@pytest.mark.parametrize("direction", [1, -1])
def test_a_wall_that_slides_at_once_slides_without_lifting(direction):
    # 4 x 3 running-bond wall, mu = 0.6 everywhere: every bed joint reaches the cone at
    # lambda = mu, so the associative state is already a fixed point of (10.6)-(10.8); its
    # LP mechanism is the cone's flow (the wall lifts at v/u = mu), the returned one must
    # slide without opening where the joint carries load (Coulomb, no dilatancy)
    a = mdof.wall(4, 3, 0.4, 0.2, mu=0.6)
    c = statics.collapse(a, direction=direction)
    assert c.converged and c.ap_min == pytest.approx(0.6 * G, rel=LP_TOL)  # lambda = mu
    assert c.sliding.any()
    rel = corner_velocity(c.velocity, a.centroid, a.corners, a.body_b) - corner_velocity(
        c.velocity, a.centroid, a.corners, a.body_a)
    vn = np.einsum("kcd,kd->kc", rel, a.normal)
    loaded = c.normal_force > 1e-6 * float(a.mass.sum())
    # the mechanism is normalised to a largest speed of 1: 1e-9 is HiGHS's dual accuracy
    assert np.abs(vn[loaded & c.sliding[:, None]]).max() < 1e-9


BESIDE = {"blocks": [{"polygon": [[0, 0], [0.4, 0], [0.4, 1], [0, 1]], "name": "block"}],
          "supports": [[[-0.4, 0], [0, 0], [0, 0.5], [-0.4, 0.5]]]}


@pytest.mark.parametrize("mu", [0.5, 1.0, 2.0, 10.0, None])
def test_block_beside_a_low_support_rocks_away_at_b_over_h_for_every_mu(mu):
    # 0.4 x 1 m block beside a 0.4 x 0.5 m support: with mu > 1 the associative LP jams it
    # (a self-stress against the support, lambda capped); Coulomb friction cannot hold that
    # and the block rocks away about its outer corner at B/H g (closed form; LMGC90 and
    # compas_cra agree, docs/validation.md). The whole structure is a macro-block (10.9).
    from rockarch.mdof.assembly_file import assembly_from_dict

    a = assembly_from_dict(dict(BESIDE, **({} if mu is None else {"friction": mu})))
    assert a.ap_min == pytest.approx(0.4 * G, rel=LP_TOL)
    c = statics.collapse(a)
    assert c.converged and c.direction == -1  # ground to -x: inertia pushes it away (+x)
    assert c.velocity[0, 2] < 0 and c.velocity[0, 0] > 0  # clockwise about (0.4, 0)
    k = int(np.flatnonzero(np.abs(a.normal[:, 0]) > 0.5)[0])  # the face on the support
    assert c.opening[k].any()
    tol = 1e-6 * float(a.mass.sum())  # the iteration's force tolerance (1e-7 of the weight)
    inf = np.isinf(a.mu)[:, None]  # mu = inf: no limit once compressed
    cap = np.where(inf, np.where(c.normal_force > 0, np.inf, 0.0),
                   np.where(inf, 0.0, a.mu[:, None]) * c.normal_force)
    assert np.all(np.abs(c.tangential_force) <= cap + tol)


def test_stack_beside_a_support_rocks_as_one_cluster():
    # two 0.4 x 0.5 m blocks beside the same support, mu = 10: the stack rocks away as one
    # rigid cluster, B/H = 0.4 g; the top block alone would need 0.8 g
    a = bd.from_polygons([[[0, 0], [0.4, 0], [0.4, 0.5], [0, 0.5]],
                          [[0, 0.5], [0.4, 0.5], [0.4, 1], [0, 1]]],
                         supports=[[[-0.4, 0], [0, 0], [0, 0.5], [-0.4, 0.5]]], mu=10.0)
    c = statics.collapse(a)
    assert c.ap_min == pytest.approx(0.4 * G, rel=LP_TOL) and c.moving.all()


def test_no_convergence_takes_the_macro_block(monkeypatch):
    # an unconverged iterate is no solution: the end wedge (Eq. 10.9, 7/11 g closed form,
    # see test_assemblies) below the associative bound is taken, without a warning
    w = bd.wall(4, 3, 0.4, 0.2)  # converges in ~22 LPs per direction
    monkeypatch.setattr(nonassoc, "MAX_ITER", 2)
    c = statics.collapse(w, direction=1)
    assert c.converged and c.lambda_ == pytest.approx(7 / 11, rel=1e-7)


def test_no_convergence_warns_and_returns_the_smallest_iterate(monkeypatch):
    w = bd.wall(4, 3, 0.4, 0.2)  # converges in ~22 LPs per direction
    monkeypatch.setattr(nonassoc, "MAX_ITER", 2)
    monkeypatch.setattr(statics.mb, "lowest", lambda *args: None)  # no macro-block
    with pytest.warns(RuntimeWarning, match="did not converge after 2 LPs"):
        c = statics.collapse(w, direction=1)
    assert not c.converged and c.iterations == 2
    # the safer value: not above the associative LP's, and the least of the iterates
    assert c.lambda_ <= statics.collapse(w, direction=1, friction="associative").lambda_
    assert c.lambda_ < 1.0  # the first Tresca LP: capacities of the associative state


def test_mu_infinite_caps():
    # mu = inf: unbounded while compressed, nothing once open (Eq. 10.6)
    n = np.array([[1.0, 0.0], [1e-12, 2.0]])
    cap = nonassoc.shear_caps(np.array([math.inf, 0.5]), n, 1.0)
    assert cap[0, 0] == math.inf and cap[0, 1] == 0.0
    assert cap[1].tolist() == [0.5e-12, 1.0]


def test_friction_option_is_checked():
    with pytest.raises(ValueError, match="friction must be"):
        statics.collapse(mdof.single_block(0.5, 1.0), friction="dilatant")


def test_macro_block_wedge_of_the_long_wall():
    # the same stepped end wedge in a 4 x 10 wall: 7/11 g (closed form, see
    # test_assemblies); its boundary joints carry nothing but the pivot corner
    w = bd.wall(4, 10, 0.4, 0.2)
    c = statics.collapse(w)
    assert c.ap_min == pytest.approx(G * 7 / 11, rel=LP_TOL)
    s = np.append(c.moving, False)
    boundary = s[w.body_a] ^ s[w.body_b]
    loaded = np.abs(c.normal_force[boundary]) > 1e-9 * float(w.mass.sum())
    assert c.moving.sum() == 4 and loaded.sum() == 1  # one corner: the pivot



def test_long_limit_analysis_shows_progress_on_a_terminal(monkeypatch, capsys):
    # big assemblies take up to a minute (docs/performance.md): on a terminal the LPs of
    # each direction are counted on stderr; off a terminal (pipes, these tests) nothing
    import sys

    bd.wall(4, 3, 0.4, 0.2, mu=0.3)
    assert "limit analysis" not in capsys.readouterr().err
    monkeypatch.setattr(statics, "PROGRESS_JOINTS", 1)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    bd.wall(4, 3, 0.4, 0.2, mu=0.3)
    err = capsys.readouterr().err
    assert "limit analysis of 14 blocks, +x" in err and "limit analysis of 14 blocks, -x" in err
