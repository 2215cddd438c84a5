"""General assemblies and their statics (docs/theory.md §10): closed forms, the arch
thrust-line LP as an independent formulation, the rocking frame of the SDOF model."""

import math
import warnings

import numpy as np
import pytest

from rockarch import mdof
from rockarch.arch import analyse, catenary, circular, elliptical, limit_analysis
from rockarch.core.constants import G
from rockarch.mdof import builders as bd
from rockarch.mdof import polygons as pg
from rockarch.mdof import statics
from rockarch.mdof.assembly_file import assembly_from_dict
from rockarch.motion.records import UnitsWarning
from rockarch.rocking import mechanism as mc

# Tolerance of LP results against closed forms: HiGHS solves to ~1e-9 relative (its
# default primal/dual feasibility tolerance 1e-7 on forces of order 1).
LP_TOL = 1e-7


def test_a_wall_without_friction_has_no_sliding_joint():
    # its wedge turns about one corner (a rigid rotation of every block about (2.0, 0.2)): the
    # crack's bed and head joints open at both corners, and the head joint beside the pivot
    # moves along its face carrying nothing; none slides (they were all called sliding, and
    # drawn so in --mechanism, on a wall whose joints cannot slide)
    c = statics.collapse(mdof.wall(6, 5, 0.4, 0.2))
    assert c.opening.any() and not c.sliding.any()


def _rect(x0, y0, w, h):
    return [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]


@pytest.mark.parametrize("mu", [0.1, 0.2, 0.49, 0.51, 2.0])
def test_single_block_ap_min_is_min_mu_lambda(mu):
    # closed form: rest below min(mu, B/H)·g (Eq. 10.4 for one block)
    blk = bd.with_friction(mdof.single_block(0.5, 1.0), mu)
    assert blk.ap_min == pytest.approx(min(mu, 0.5) * G, rel=LP_TOL)
    c = statics.collapse(blk)
    if mu < 0.5:  # the mechanism slides ...
        assert c.sliding.all()
    else:  # ... or rocks about the left corner (inertia to the left), the right one lifts
        assert not c.sliding.any() and c.opening.tolist() == [[False, True]]


def test_polygon_block_equals_column_block():
    # the same block built from its polygon: same statics and equivalent block (Housner)
    a = bd.from_polygons([_rect(-0.25, 0, 0.5, 1.0)])
    b = mdof.single_block(0.5, 1.0)
    assert a.ap_min == pytest.approx(b.ap_min, rel=LP_TOL)
    assert a.p_ref == pytest.approx(b.p_ref, rel=1e-12)  # Eq. (10.5) = Housner's p exactly
    assert a.delta_ref == pytest.approx(b.delta_ref, rel=1e-12)


@pytest.mark.parametrize("make,n", [(lambda: catenary(10.0, 3.0, 0.25), 10),
                                    (lambda: catenary(10.0, 3.0, 0.25), 20),
                                    (lambda: circular(10.0, 5.0, 0.6), 12),
                                    (lambda: elliptical(10.0, 3.0, 3.0), 20)])
def test_chain_lp_agrees_with_thrust_line_lp(make, n):
    # two formulations of the same limit analysis (corner forces vs thrust line): equal
    arch = make()
    a = mdof.arch_assembly(arch, n)
    c = statics.collapse(a)
    assert c.ap_min == pytest.approx(analyse(arch, n).ap_min, rel=1e-8)
    opened = {(int(k), int(s)) for k, s in np.argwhere(c.opening)}
    # the four-hinge mechanism: at each hinge the opposite corner opens (corner 0 is the
    # intrados, so an intrados hinge opens corner 1)
    hinges = {(h.joint, 1 if h.side == "intrados" else 0)
              for h in analyse(arch, n, direction=c.direction).hinges}
    assert opened == hinges
    # and the equivalent block of that mechanism: the general linkage's p and neutral angle
    # (docs/theory.md Eqs. (10.5)-(10.5b), rockarch.mdof.linkage) are the four-hinge
    # kinematics' (docs/theory.md §5, rockarch.arch.fourhinge), two implementations: to
    # 1e-9 (measured 1e-13 on these and an elliptical ring d/l = 0.3, delta 0.785 rad)
    assert c.p == pytest.approx(a.p_ref, rel=1e-9)
    assert c.delta == pytest.approx(a.delta_ref, rel=1e-9)


RINGS = [(make, rise, d) for make in (circular, catenary) for rise in (0.2, 0.3, 0.5)
         for d in (0.1, 0.15, 0.2)]


@pytest.mark.parametrize("make,rise,d", RINGS)
def test_chain_lp_and_thrust_line_lp_over_thick_rings(make, rise, d):
    """The corner-force LP of the 20-voussoir chain and the thrust-line LP (limit_analysis:
    valid whatever its hinges) give the same ap,min from slender to very thick rings
    (d/l = 0.1-0.2, f/l = 0.2-0.5; 5-10 g at d/l = 0.2), to 1e-8 as above; except flat
    rings (f/l = 0.2) at d/l = 0.2, where the thrust line's sections carry shear with a
    vanishing normal force at an abutment the ring lifts off, and it stays 5 % above the
    corner LP's mechanism, at 9-10 g (docs/validation.md). The corner LP is never above."""
    arch = make(10.0, 10.0 * rise, 10.0 * d)
    chain_lp = statics.collapse(mdof.arch_assembly(arch, 20)).ap_min
    thrust_lp = limit_analysis(arch, 20).ap_min
    if rise == 0.2 and d == 0.2:
        assert chain_lp < thrust_lp < 1.06 * chain_lp and chain_lp > 8.5 * G
    else:
        assert chain_lp == pytest.approx(thrust_lp, rel=1e-8)


def test_column_lp_agrees_with_critical_part():
    col = mdof.column([(0.5, 1.0), (0.4, 1.0), (0.3, 0.8, 0.05)])
    assert statics.collapse(col).ap_min == pytest.approx(col.ap_min, rel=LP_TOL)


def test_trilithon_is_the_rocking_frame():
    b, h, s, d = 0.3, 2.0, 1.0, 0.4
    tri = bd.colonnade(2, b, h, s, d)
    assert tri.kind == "trilithon" and tri.n_blocks == 3
    assert tri.ap_min == pytest.approx(G * b / h, rel=LP_TOL)  # frame: g·tan(alpha)
    gamma = (2 * b + s) * d / (2 * b * h)  # lintel mass over both columns' (unit density)
    r = 0.5 * math.hypot(b, h)
    frame = mc.rocking_frame(math.atan(b / h), math.sqrt(3 * G / (4 * r)), gamma, G)
    # Eq. (10.5) with the columns' rotation as coordinate is Makris & Vassiliou's frame
    # p² = (3g/4R)(1 + 2γ)/(1 + 3γ) exactly (rocking_frame's closed form)
    assert tri.p_ref ** 2 == pytest.approx(3 * G / (4 * r) * (1 + 2 * gamma) / (1 + 3 * gamma),
                                           rel=1e-9)
    # the SDOF model's own p (paper Eq. 12, an energy-based average over [0, delta])
    # differs from the initial-slope value by less than 0.5 % for this slender frame
    assert tri.p_ref == pytest.approx(frame.p, rel=5e-3)
    assert tri.delta_ref == pytest.approx(frame.delta, rel=1e-9)


def test_colonnade_of_drums():
    col = bd.colonnade(4, 0.4, 2.4, 1.2, 0.5, drums=3)
    assert col.n_blocks == 4 * 3 + 1 and col.kind == "colonnade"
    # drums of full column width under a lintel: the frame mechanism, g·B/H
    assert col.ap_min == pytest.approx(G * 0.4 / 2.4, rel=LP_TOL)


def test_wall_closed_forms():
    w = bd.wall(4, 3, 0.4, 0.2)
    # running bond: courses of 3, and 2 + 2 halves
    assert w.n_blocks == 2 * 3 + 2 * 4 and w.kind == "wall"
    # no sliding: a stepped wedge at the wall's end (the end half block of course 2, the
    # end block of course 3 and the two end blocks of course 4) rocks about its lowest
    # outer corner with every joint around it open (a macro-block solution of the
    # non-associative problem, Eq. 10.9): moment balance of its centroid about that corner,
    # lever 0.2 + 1/30 m over height 0.3667 m = 7/11 exactly
    assert w.ap_min == pytest.approx(G * 7 / 11, rel=LP_TOL)
    c = statics.collapse(w)
    assert c.converged and np.flatnonzero(c.moving).tolist() in ([3, 7, 10, 11], [6, 9, 12, 13])
    # associative friction (Eq. 10.4 alone) props the wall by shear on joints that carry no
    # normal force: the whole wall's width / height, an unsafe 1.5 g
    assoc = statics.collapse(w, friction="associative")
    assert assoc.ap_min == pytest.approx(G * 1.2 / 0.8, rel=LP_TOL)
    # friction below that: a course slides on its bed joint at exactly mu·g
    assert bd.wall(4, 3, 0.4, 0.2, mu=0.3).ap_min == pytest.approx(0.3 * G, rel=LP_TOL)
    # joints: 4 ground faces under course 1, bed joints, head joints; all found
    assert int(np.sum(w.body_a == -1)) == 3


@pytest.mark.slow
@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_wall_without_sliding_stands_where_pymunk_does(direction):
    # the 4 x 3 running-bond wall without sliding, load ramped in over 0.5 s and held 2 s
    # (validation/wall_ramp.py, the pymunk scan's protocol; docs/validation.md): every
    # pymunk run stands at 0.70 g and none collapses below 0.80 g, so the time history must
    # stand at 0.80 g in both directions, with every step solved, above the statics' 7/11 g
    # (a lower bound over the non-associative solutions). In direction -1 pymunk's runs (60
    # solver iterations) collapse by 1.01 g and so must ours at 1.0 g. In direction +1 the
    # engine keeps a hyperstatic state that stands beyond 1.45 g (a known over-strength of
    # mu = inf walls, docs/validation.md): not asserted.
    from rockarch.motion.signals import GroundMotion

    w = bd.wall(4, 3, 0.4, 0.2)
    t = np.linspace(0.0, 2.5, 2501)
    for f in (0.8, 1.0) if direction < 0 else (0.8,):
        acc = direction * f * G * np.clip(t / 0.5, 0.0, 1.0)
        r = mdof.simulate(w, GroundMotion(t, acc, "ramp"), t_free=0.0)
        d = np.hypot(r.q[:, :, 0] - r.q[0, :, 0], r.q[:, :, 1] - r.q[0, :, 1]).max()
        assert r.lcp_failures == 0
        assert (d > 1e-4 * w.size) == (f > 0.9), f
        assert r.overturned == (f > 0.9), f


def test_bridge_geometry_and_statics():
    arch = catenary(10.0, 3.0, 0.25)
    alone = mdof.arch_assembly(arch, 10).ap_min
    wide = bd.bridge(arch, 10, pier_height=3.0, pier_width=2.0)
    narrow = bd.bridge(arch, 10, pier_height=3.0, pier_width=1.5)
    # kinematic theorem: the arch's mechanisms on fixed piers remain mechanisms, so piers
    # only lower ap_min; wide piers do not move (the arch's own mechanism governs)
    assert wide.ap_min == pytest.approx(alone, rel=LP_TOL)
    assert narrow.ap_min < alone * (1 - 1e-3)
    assert narrow.n_blocks == 10 + 2 * 2  # two piers of round(3/1.5) = 2 blocks
    two = bd.bridge(arch, 10, spans=2, pier_height=3.0, pier_width=1.0)
    assert two.kind == "bridge" and two.info["abutments"] == 1
    assert two.n_blocks == 2 * 10 + 3  # one pier of three blocks
    # the pier on the ground and the two springings on the abutments
    assert np.sum(two.body_a == -1) + np.sum(two.body_b == -1) == 3
    assert 0 < two.ap_min <= alone * (1 + LP_TOL)
    # the abutments are outlines (drawn, and struck by a block that reaches them): each
    # stands on the ground and holds its springing joint on a face of its own
    assert len(two.info["supports"]) == 2 and not wide.info["supports"]
    springings = [j for j in range(two.n_joints) if -1 in (two.body_a[j], two.body_b[j])
                  and two.corners[j, :, 1].min() > 0]  # the pier's base is at y = 0
    for k, sup in zip(springings, two.info["supports"], strict=True):
        assert sup[:, 1].min() == pytest.approx(0.0, abs=1e-12)
        for c in two.corners[k]:  # both corners of the springing joint are its vertices
            assert np.min(np.hypot(*(sup - c).T)) < 1e-9
    with pytest.raises(ValueError, match=r"pier 1 block 1 falls"):
        bd.bridge(arch, 10, pier_height=3.0, pier_width=1.0)
    with pytest.raises(ValueError, match="--pier-width must exceed"):
        bd.bridge(arch, 10, spans=2, pier_height=3.0, pier_width=0.1)


def test_faces_found_and_corner_touch_ignored():
    base, top = _rect(0, 0, 1, 1), _rect(0.25, 1, 1.5, 0.5)
    corner = _rect(1, 0, 1, 1)  # shares the whole side face x = 1 with the base
    diag = _rect(-1, 1, 1, 0.4)  # touches the base at its corner only
    p = [pg.convex_polygon(x) for x in (base, top, corner, diag)]
    f = pg.shared_face(p[0], p[1], 1e-9)
    assert np.allclose(sorted([f[0][0], f[1][0]]), [0.25, 1.0]) and np.allclose(f[2], [0, 1])
    assert pg.shared_face(p[0], p[3], 1e-9) is None
    assert np.allclose(pg.shared_face(p[0], p[2], 1e-9)[2], [1, 0])
    assert pg.overlap_depth(p[0], p[2]) <= 0 < pg.overlap_depth(p[0], pg.convex_polygon(
        _rect(0.9, 0, 1, 1)))


@pytest.mark.parametrize("poly,msg", [
    ([[0, 0], [2, 0], [1, 0.5], [2, 2], [0, 2]], "not convex"),
    ([[0, 0], [2, 2], [2, 0], [0, 2]], "not convex"),  # a bow tie: edges cross
    ([[1, 0], [1.588, 1.809], [0.049, 0.691], [1.951, 0.691], [0.412, 1.809]],
     "self-intersecting"),  # a pentagram turns one way but winds twice
    ([[0, 0], [1, 0], [2, 0]], "no area"),
    ([[0, 0], [1, 0]], "at least 3"),
])
def test_bad_polygons(poly, msg):
    with pytest.raises(ValueError, match=msg):
        pg.convex_polygon(poly, "block 0")


@pytest.mark.parametrize("polys,msg", [
    ([_rect(0, 0, 1, 1), _rect(0.5, 0.5, 1, 1)], "block 0 and block 1 overlap"),
    ([_rect(0, 0, 1, 1), _rect(3, 0.5, 1, 1)], "block 1 touches nothing"),
    ([_rect(0, 0, 1, 1), _rect(0.6, 1, 1, 1)], "block 1 falls"),
    ([_rect(0, -0.5, 1, 1)], "below the ground"),
    # the top block's centroid right above the base's corner: ap,min = 0, no margin
    ([_rect(0, 0, 1, 1), _rect(0.5, 1, 1, 1)], "only just balances"),
])
def test_bad_assemblies(polys, msg):
    with pytest.raises(ValueError, match=msg):
        bd.from_polygons(polys)


#: A block on a support sloping 0.45 (tan of its angle): it slides off unless μ ≥ 0.45.
SLOPE = [[0, 0], [2, 0], [2, 0.9]]
ON_SLOPE = [[0.6, 0.27], [1.4, 0.63], [1.4, 1.03], [0.6, 0.67]]


@pytest.mark.parametrize("mu", [0.1, 0.449])
def test_a_block_that_slides_under_gravity_says_friction_is_the_cause(mu):
    # it was "the structure cannot stand under gravity: block 0 falls: no equilibrium at
    # rest", as if it could not stand at all: without sliding it does
    assert bd.from_polygons([ON_SLOPE], supports=[SLOPE]).ap_min > 0
    with pytest.raises(ValueError) as err:
        bd.from_polygons([ON_SLOPE], supports=[SLOPE], mu=mu)
    msg = str(err.value)
    assert msg.startswith(f"the structure cannot stand under gravity with friction μ = {mu}: "
                          "its joints slide and block 0 falls; it stands with μ > ")
    need = float(msg.rsplit("> ", 1)[1])
    assert 0.45 <= need <= 0.451  # tan of the slope, rounded up to 3 digits
    assert bd.from_polygons([ON_SLOPE], supports=[SLOPE], mu=need + 1e-3).ap_min > 0


def test_an_arch_that_slides_under_gravity_says_from_which_friction_it_stands():
    arch = mdof.arch_assembly(circular(10.0, 5.0, 0.6), 12)
    with pytest.raises(ValueError, match=r"with friction μ = 0\.2: its joints slide and block "
                       r"\d+ falls \(with \d+ more block\(s\)\); it stands with μ > 0\.38$"):
        bd.with_friction(arch, 0.2)
    assert bd.with_friction(arch, 0.38).ap_min > 0  # the value it names


def test_json_assembly_with_contact_friction():
    data = {"name": "two", "friction": 0.6,
            "blocks": [{"polygon": _rect(0, 0, 1, 1), "density": 2.0, "name": "base"},
                       {"polygon": _rect(0.25, 1, 0.5, 1)}],
            "contacts": [{"blocks": [-1, 0]}, {"blocks": [0, 1], "friction": 0.1}]}
    a = assembly_from_dict(data)
    assert a.n_blocks == 2 and np.allclose(sorted(a.mu), [0.1, 0.6])
    # the top block slides on the base first: rest below 0.1·g (its own friction)
    assert a.ap_min == pytest.approx(0.1 * G, rel=LP_TOL)
    assert a.mass[0] == pytest.approx(2.0) and a.mass[1] == pytest.approx(0.5)
    # --friction replaces the file's default, not a contact's own
    assert np.allclose(sorted(assembly_from_dict(data, mu=0.05).mu), [0.05, 0.1])
    with pytest.raises(ValueError, match="unknown key"):
        assembly_from_dict({**data, "colour": "red"})
    with pytest.raises(ValueError, match="unknown key"):
        assembly_from_dict({**data, "blocks": [{"polygon": _rect(0, 0, 1, 1), "mass": 3}]})
    with pytest.raises(ValueError, match="'friction': friction coefficient"):
        assembly_from_dict({**data, "friction": -1})
    # a contact's own friction: the error names the contact (before: not which one)
    bad = {**data, "contacts": [{"blocks": [-1, 0]}, {"blocks": [0, 1], "friction": -0.4}]}
    with pytest.raises(ValueError, match=r"contact 1 \[0, 1\]: friction coefficient must "
                                         r"be a finite number > 0, got -0.4"):
        assembly_from_dict(bad)


def test_json_assembly_in_millimetres_warns():
    blocks = [{"polygon": _rect(0, 0, 1, 1)}, {"polygon": _rect(0.25, 1, 0.5, 1)}]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assembly_from_dict({"blocks": blocks})   # 2 m across: no warning
    mm = [{"polygon": (np.asarray(b["polygon"]) * 1000).tolist()} for b in blocks]
    with pytest.warns(UnitsWarning, match="2000 m across: coordinates are in metres"):
        a = assembly_from_dict({"blocks": mm})
    # still read as given (ap,min is scale-free, p is not)
    assert a.ap_min == pytest.approx(assembly_from_dict({"blocks": blocks}).ap_min, rel=1e-9)
    # a small object in millimetres is of plausible extent (500 m) but its block is not
    vase = [{"polygon": _rect(0, 0, 200, 500)}]
    with pytest.warns(UnitsWarning, match="a block is 500 m long"):
        assembly_from_dict({"blocks": vase})


@pytest.mark.parametrize("k, hint", [(1000.0, "millimetres"), (1e-4, "kilometres")])
def test_a_gate_in_wrong_units_has_the_same_statics(k, hint):
    """A gate (two piers 0.5 x 2.5 m, a lintel 2.7 x 0.5 m, mu = 0.7) read as given at 1000
    and 1e-4 times its size: the same ap,min (scale-free) and p x 1/sqrt(k) (p² ∝ g/length),
    Eq. (11.33). Before, HiGHS's absolute tolerances failed it: 'cannot stand under
    gravity with any margin' at 1000x, 'hangs on shear' at 1e-4x."""
    gate = {"friction": 0.7, "blocks": [{"polygon": _rect(0, 0, 0.5, 2.5)},
                                        {"polygon": _rect(2, 0, 0.5, 2.5)},
                                        {"polygon": _rect(-0.1, 2.5, 2.7, 0.5)}]}
    ref = assembly_from_dict(gate)
    big = {**gate, "blocks": [{"polygon": (np.asarray(b["polygon"]) * k).tolist()}
                              for b in gate["blocks"]]}
    with pytest.warns(UnitsWarning, match=hint):
        a = assembly_from_dict(big)
    # LP tolerance: HiGHS's 1e-7 on the scaled problem (the metre gate is solved as given)
    assert a.ap_min == pytest.approx(ref.ap_min, rel=1e-7)
    assert a.p_ref == pytest.approx(ref.p_ref / math.sqrt(k), rel=1e-7)
    assert a.delta_ref == pytest.approx(ref.delta_ref, rel=1e-7)


def test_supports_move_with_the_ground():
    # a block against a support: the support is the ground (body -1)
    blk, sup = [_rect(0, 0, 0.4, 1.0)], [_rect(0.4, 0, 1, 2)]
    a = bd.from_polygons(blk, supports=sup, mu=0.5)
    assert set(zip(a.body_a.tolist(), a.body_b.tolist(), strict=True)) == {(-1, 0), (0, -1)}
    # pushed towards the support it cannot move: only the other direction remains
    assert not math.isfinite(statics.collapse(a, direction=-1).ap_min)  # inertia to +x
    # rocking away, its lower corner slides up the support's face while the face opens:
    # non-associative friction carries nothing there, ap_min = B/H·g = 0.4 g (closed form)
    assert a.ap_min == pytest.approx(G * 0.4, rel=LP_TOL)
    # associative friction (Eq. 10.4 alone) props the corner by a self-stress between the
    # support and the base, above B/H (the defect that Eqs. 10.6-10.8 remove)
    assert statics.collapse(a, friction="associative").ap_min > G * 0.4 * 1.05
    # without sliding the same: an opening joint carries no shear, whatever mu
    assert bd.from_polygons(blk, supports=sup).ap_min == pytest.approx(G * 0.4, rel=LP_TOL)


def test_trilithon_mechanism_and_drawing(tmp_path):
    from rockarch.output.collapse_plots import plot_collapse

    tri = bd.colonnade(2, 0.3, 2.0, 1.0, 0.4)
    c = statics.collapse(tri)
    # the frame mechanism: both columns rotate alike, the lintel translates without turning
    assert np.allclose(np.abs(c.velocity[:2, 2]), 1.0, atol=1e-6)
    assert abs(c.velocity[2, 2]) < 1e-6 and c.moving.all()
    assert np.sum(c.opening) == 2 * 2  # one base corner and one top corner per column
    out = plot_collapse(tri, tmp_path / "m.png", c)
    assert out.stat().st_size > 5000


def test_supports_are_drawn():
    # a support given as a polygon is drawn (hatched) in the collapse figure and in every
    # frame of the animation, where a block sliding off it would otherwise tip in mid-air
    from matplotlib.patches import Polygon

    from rockarch.motion import signals as motion
    from rockarch.output.animation import _Renderer, plan_frames
    from rockarch.output.collapse_plots import collapse_figure

    a = bd.from_polygons([[[0, 1], [0.4, 1], [0.4, 1.2], [0, 1.2]]], mu=0.1,
                         supports=[[[0, 0], [0.4, 0], [0.4, 1], [0, 1]]])

    def hatched(ax):
        return [p for p in ax.patches if isinstance(p, Polygon) and p.get_hatch()]

    assert len(hatched(collapse_figure(a).axes[0])) == 1
    r = mdof.simulate(a, motion.step(0.5 * G, 0.2), t_free=1.0)
    rend = _Renderer(r, plan_frames(r, fps=5, max_frames=4, magnify=1.0))
    assert len(hatched(rend.fig.axes[0])) == 1


def test_docs_vase_on_a_pedestal_example():
    # the second example of docs/assemblies.md, with the numbers it quotes (the Newmark slip
    # 0.1177 m at 0.3 g for 0.2 s; tips over at 0.5 g: Newmark 0.392 m > B/2)
    import json
    import re
    from pathlib import Path

    from rockarch.motion import signals as motion
    from rockarch.systems import MDOFSystem

    text = (Path(__file__).resolve().parents[2] / "docs" / "assemblies.md").read_text()
    data = json.loads(re.findall(r"```json\n(.*?)```", text, re.S)[1])
    s = MDOFSystem(assembly_from_dict(data))
    step = motion.pulse("step", period=0.2)
    r3, r5 = s.simulate(step, ratio=3), s.simulate(step, ratio=5)
    assert not r3.overturned and r3.max_slip == pytest.approx(0.118, abs=5e-4)
    assert r5.overturned


def test_docs_assembly_file_example():
    # the example of docs/assemblies.md: ground + support under block 0, block 1 on it
    import json
    import re
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "assemblies.md").read_text()
    data = json.loads(re.search(r"```json\n(.*?)```", text, re.S).group(1))
    a = assembly_from_dict(data)
    pairs = sorted(zip(a.body_a.tolist(), a.body_b.tolist(), a.mu.tolist(), strict=True))
    assert pairs == [(-1, 0, 0.6), (-1, 0, 0.6), (0, 1, 0.4)]
    # the top block (0.6 × 1 m, b/h = 0.6) slides first, at its own friction 0.4
    assert a.ap_min == pytest.approx(0.4 * G, rel=LP_TOL)


def test_collapse_takes_one_friction_coefficient_or_one_per_joint():
    # a number was a TypeError deep in the LP set-up (len() of unsized object), a zero
    # returned ap_min = -0.0 and a negative one said the wall cannot stand
    w = mdof.wall(2, 2, 0.4, 0.2)
    one = statics.collapse(w, mu=0.5)
    assert one.ap_min == statics.collapse(w, mu=np.full(w.n_joints, 0.5)).ap_min
    assert one.ap_min < statics.collapse(w).ap_min  # friction only lowers ap_min
    for bad, msg in ((0.0, "must be > 0"), (-1.0, "must be > 0"), (np.nan, "must be > 0"),
                     ([0.5, 0.5], "one per joint")):
        with pytest.raises(ValueError, match=msg):
            statics.collapse(w, mu=bad)


def test_an_mdof_arch_has_the_blocks_limit_of_every_structure():
    # it had a fixed cap of 400 voussoirs that ROCKARCH_MAX_BLOCKS (500) could not raise
    with pytest.raises(ValueError, match="600 blocks, above the limit of 500 "
                                         r"\(ROCKARCH_MAX_BLOCKS\)"):
        mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 600)


@pytest.mark.parametrize("kw", [dict(wall="2,2", block="400,200"), dict(column=[(400, 1000)]),
                                dict(colonnade=2, block="300,2000", bay=1000, lintel=400)])
def test_built_in_structures_in_millimetres_warn(kw):
    # the size sets p, and p the site, design and fragility results: arches and assembly
    # files warned 'millimetres?', walls, columns and colonnades did not
    from rockarch.motion.records import UnitsWarning
    from rockarch.systems import system

    with pytest.warns(UnitsWarning, match="millimetres"):
        system("mdof", **kw)
