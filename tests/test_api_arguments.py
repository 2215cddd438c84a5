"""The Python front door checks its arguments (issue 22): every public function of
``import rockarch as ra`` raises TypeError (wrong type) or ValueError (wrong value) with a
message that names the argument, before any work; never an AttributeError or a numpy
message from deep inside."""

from __future__ import annotations

import re

import numpy as np
import pytest

import rockarch as ra

BLK = ra.system("block", alpha=0.1)
SINE = ra.pulse("sine", period=0.5)

#: (call, exception, words the message must hold: the argument's name first).
CASES = {
    "simulate-path-as-motion": (lambda: ra.simulate(BLK, "rec.AT2", ratio=2, p=2), TypeError,
                                ["motion", "ra.read_record"]),
    "simulate-swapped": (lambda: ra.simulate(SINE, BLK, ratio=2, p=2), TypeError,
                         ["sys_", "comes first"]),
    "simulate-ratio-list": (lambda: ra.simulate(BLK, SINE, ratio=[2, 3], p=2), TypeError,
                            ["ratio", "one number"]),
    "simulate-ratio-none": (lambda: ra.simulate(BLK, SINE, ratio=None, p=2), TypeError,
                            ["ratio", "None"]),
    "simulate-ratio-text": (lambda: ra.simulate(BLK, SINE, ratio="2", p=2), TypeError,
                            ["ratio"]),
    "simulate-ratio-1e300": (lambda: ra.simulate(BLK, SINE, ratio=1e300, p=2), ValueError,
                             ["ratio"]),
    "simulate-p-bool": (lambda: ra.simulate(BLK, SINE, ratio=2, p=True), TypeError, ["p"]),
    "simulate-check-step-on-a-block": (lambda: ra.simulate(BLK, SINE, ratio=2, p=2,
                                                           check_step=True),
                                       ValueError, ["check_step", "mdof"]),
    "simulate-check-step-text": (lambda: ra.mdof.simulate(ra.mdof.single_block(0.4, 2.0),
                                                          SINE, check_step="yes"),
                                 TypeError, ["check_step"]),
    "simulate-skip-rest-text": (lambda: ra.mdof.simulate(ra.mdof.single_block(0.4, 2.0),
                                                         SINE, skip_rest="no"),
                                TypeError, ["skip_rest"]),
    "system-blocks-fraction": (lambda: ra.system("mdof", shape="catenary", span=10, rise=3,
                                                 thickness=0.25, blocks=20.9),
                               TypeError, ["blocks", "20.9"]),
    "system-alpha-bool": (lambda: ra.system("block", alpha=True), TypeError, ["alpha"]),
    "system-alpha-text": (lambda: ra.system("block", alpha="0.1"), TypeError, ["alpha"]),
    "system-kind-number": (lambda: ra.system(3, alpha=0.1), TypeError, ["kind"]),
    "system-shape-on-a-block": (lambda: ra.system("block", alpha=0.1, shape="catenary"),
                                ValueError, ["shape", "does not apply"]),
    "system-blocks-on-a-block": (lambda: ra.system("block", alpha=0.1, blocks=5), ValueError,
                                 ["blocks", "does not apply"]),
    "system-alpha-on-sdof": (lambda: ra.system("sdof", p=2, delta=0.1, ap_min=1, alpha=0.1),
                             ValueError, ["alpha", "does not apply"]),
    "system-g-negative": (lambda: ra.system("block", alpha=0.1, g=-9.81), ValueError, ["g"]),
    "system-g-huge": (lambda: ra.system("block", alpha=0.1, g=1e308), ValueError, ["g"]),
    "system-restitution-list": (lambda: ra.system("block", alpha=0.1, restitution=[0.5]),
                                TypeError, ["restitution"]),
    "system-wall-number": (lambda: ra.system("mdof", wall=5, block=(0.4, 0.2)), TypeError,
                           ["wall"]),
    "system-friction-bool": (lambda: ra.system("mdof", column=[(0.4, 1.0)], friction=True),
                             TypeError, ["friction"]),
    "system-wall-too-many-blocks": (lambda: ra.system("mdof", wall=(1000, 1000),
                                                      block=(0.4, 0.2)),
                                    ValueError, ["ROCKARCH_MAX_BLOCKS"]),
    "system-drums-without-colonnade": (lambda: ra.system("mdof", wall=(2, 2), block=(0.4, 0.2),
                                                         drums=2),
                                       ValueError, ["--drums", "--colonnade"]),
    "system-drums-zero": (lambda: ra.system("mdof", colonnade=2, block=(0.3, 2), bay=1,
                                            lintel=0.4, drums=0),
                          ValueError, ["--drums", ">= 1", "got 0"]),
    "system-drums-fraction": (lambda: ra.system("mdof", colonnade=2, block=(0.3, 2), bay=1,
                                                lintel=0.4, drums=2.5),
                              TypeError, ["drums", "2.5"]),
    "system-drums-on-a-block": (lambda: ra.system("block", alpha=0.1, drums=2), ValueError,
                                ["drums", "mdof"]),
    "oas-ratio-none": (lambda: ra.oas(BLK, SINE, p=[1, 2], ratio=None), TypeError,
                       ["ratio"]),
    "oas-p-text": (lambda: ra.oas(BLK, SINE, p="1,2", ratio=[1, 2]), TypeError, ["p"]),
    "oas-swapped": (lambda: ra.oas(SINE, BLK, p=[1, 2], ratio=[1, 2]), TypeError, ["sys_"]),
    "oas-period-1e300": (lambda: ra.oas(BLK, ra.pulse("sine", period=1e300), p=[1, 2],
                                        ratio=[1, 2]),
                         ValueError, ["ROCKARCH_MAX_STEPS"]),
    "batch-p-none": (lambda: ra.batch(BLK, SINE, None, [1, 2]), TypeError, ["p"]),
    "pulse-cycles-with-sine": (lambda: ra.pulse("sine", period=1, cycles=4), ValueError,
                               ["cycles", "harmonic"]),
    "pulse-period-text": (lambda: ra.pulse("sine", period="1"), TypeError, ["period"]),
    "pulse-signal-number": (lambda: ra.pulse(1, period=1), TypeError, ["signal"]),
    "pulse-cycles-fraction": (lambda: ra.pulse("harmonic", period=1, cycles=2.5), TypeError,
                              ["cycles"]),
    "read_record-number": (lambda: ra.read_record(5), TypeError, ["path"]),
    "read_record-units-number": (lambda: ra.read_record("x.txt", units=3), TypeError,
                                 ["units"]),
    "read_record-dt-text": (lambda: ra.read_record("x.txt", dt="0.01"), TypeError, ["dt"]),
    "read_suite-number": (lambda: ra.read_suite(7), TypeError, ["sources"]),
    "read_suite-dt-nan": (lambda: ra.read_suite("x", dt=float("nan")), ValueError,
                          ["dt", "nan"]),
    "make_arch-shape-none": (lambda: ra.make_arch(None, 10, 3, 0.25), TypeError, ["shape"]),
    "make_arch-span-text": (lambda: ra.make_arch("catenary", "10", 3, 0.25), TypeError,
                            ["span"]),
    "make_arch-thickness-bool": (lambda: ra.make_arch("catenary", 10, 3, True), TypeError,
                                 ["thickness"]),
    "make_arch-flat": (lambda: ra.make_arch("catenary", 10, 1e-9, 0.25), ValueError,
                       ["rise/span"]),
    "synthetic_suite-n-fraction": (lambda: ra.synthetic_suite(2.5), TypeError, ["n"]),
    "synthetic_suite-seed-negative": (lambda: ra.synthetic_suite(2, -1), ValueError,
                                      ["seed"]),
    "synthetic_suite-n-1e9": (lambda: ra.synthetic_suite(10**9), ValueError,
                              ["ROCKARCH_MAX_RECORDS"]),
    "design_system-kind-text": (lambda: ra.design_system("block", records=[SINE]), TypeError,
                                ["system", "ra.system"]),
    "design_system-probability": (lambda: ra.design_system(ra.system("block", alpha=0.1, p=2),
                                                           records=[SINE], probability=2),
                                  ValueError, ["probability"]),
    "design_system-pga": (lambda: ra.design_system(ra.system("block", alpha=0.1, p=2),
                                                   records=[SINE], pga=-3),
                          ValueError, ["pga"]),
    "GroundMotion-text": (lambda: ra.GroundMotion("abc", [1, 2]), TypeError, ["time"]),
    "GroundMotion-none": (lambda: ra.GroundMotion(None, None), TypeError, ["time"]),
    "GroundMotion.scaled-text": (lambda: SINE.scaled("2"), TypeError, ["factor"]),
    "block-housner-negative": (lambda: ra.system("block", alpha=1.2, p=2), ValueError,
                               ["restitution", "0.9553"]),
    "oas-store-number": (lambda: ra.oas(BLK, SINE, p=[1, 2], ratio=[1, 2], store=5),
                         TypeError, ["store"]),
    "oas-tol-1e-300": (lambda: ra.oas(BLK, SINE, p=[1, 2], ratio=[1, 2], tol=1e-300),
                       ValueError, ["tol"]),
    "batch-shapes": (lambda: ra.batch(BLK, SINE, [1, 2, 3], [1, 2]), ValueError,
                     ["p and ratio", "(3,)"]),
    "system.batch-p-text": (lambda: BLK.batch(SINE, "1", [1]), TypeError, ["p"]),
    "system.simulate-path": (lambda: BLK.simulate("x.AT2", ratio=2, p=2), TypeError,
                             ["motion"]),
    "system-column-text": (lambda: ra.system("mdof", column="0.4,1"), TypeError,
                           ["column"]),
    "design_system-records-path": (lambda: ra.design_system(ra.system("block", alpha=0.1,
                                                                      p=2),
                                                            records="dir/"),
                                   TypeError, ["records"]),
    "design_system-site-path": (lambda: ra.design_system(ra.system("block", alpha=0.1, p=2),
                                                         site="site.nc"),
                                TypeError, ["site"]),
}


@pytest.mark.parametrize("case", CASES, ids=list(CASES))
def test_bad_argument_names_the_parameter(case):
    call, exc, words = CASES[case]
    with pytest.raises(exc) as info:
        call()
    msg = str(info.value)
    assert "\n" not in msg and "np.float64" not in msg, msg
    for word in words:
        assert word in msg, (word, msg)


def test_the_same_calls_with_good_arguments_run():
    """The good counterparts of the cases above: the checks refuse only what is wrong."""
    r = ra.simulate(BLK, SINE, ratio=2.0, p=np.float64(2.0))  # numpy scalars are numbers
    assert r.overturned in (True, False)
    mdof = ra.system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=20.0)
    assert mdof.assembly.n_blocks == 20  # a whole float is a whole number
    assert ra.system("block", alpha=1.2, p=2, restitution=0.0).block().r == 0.0
    assert ra.pulse("harmonic", period=1, cycles=np.int64(2)).duration == pytest.approx(2.0)


def test_messages_show_plain_numbers():
    """No ``np.float64(...)`` in a message: values are shown as the user wrote them."""
    with pytest.raises(ValueError) as info:
        ra.system("block", alpha=np.float64(-1.0))
    assert re.search(r"got -1\b", str(info.value)), info.value


def test_systems_repr_is_one_line():
    # print(ra.system("mdof", wall=[6, 5], block=[0.4, 0.2])) printed every array of the
    # assembly (hundreds of lines); the systems and Assembly now print one line each
    import rockarch as ra

    wall = ra.system("mdof", wall=[6, 5], block=[0.4, 0.2])
    a = wall.assembly
    cases = [(wall, [f"Assembly({a.name!r}, wall: {a.n_blocks} blocks, {a.n_joints} joints",
                    f"ap_min {a.ap_min:.4g} m/s²", f"p {a.p_ref:.4g} 1/s",
                    f"delta {a.delta_ref:.4g} rad"]),
             (a, [f"Assembly({a.name!r}, wall:"]),
             (ra.system("mdof", column=[[0.4, 1.0]], friction=0.5),
              ["1 block, 1 joint", "friction 0.5"]),
             (ra.system("block", alpha=0.1, p=2.0),
              ["BlockSystem('block', alpha 0.1 rad, p 2 1/s, ap_min 0.9843 m/s²"]),
             (ra.system("block", alpha=0.1), ["p varies"]),
             (ra.system("sdof", p=2.0, delta=0.3, ap_min=2.0),
              ["generic: p 2 1/s, delta 0.3 rad, ap_min 2 m/s²"]),
             (ra.system("frame", alpha=0.1, p=2.0, mass_ratio=1.0),
              ["frame alpha=0.1", "frame:"]),
             (ra.system("fourhinge", shape="circular", span=10, rise=2.89, thickness=0.35),
              ["MechanismSystem(SDOFMechanism('four-hinge circular arch", "fourhinge: p "])]
    for obj, parts in cases:
        text = repr(obj)
        assert "\n" not in text and len(text) < 300, text
        assert text.startswith(type(obj).__name__ + "(") and text == str(obj)
        for part in parts:
            assert part in text, (part, text)


def test_responses_repr_is_one_line_verdict():
    # a BlockResponse's repr printed every sample of theta and theta_dot (a screen of numbers
    # in a notebook); every Response kind now prints its verdict in one line
    import rockarch as ra

    m = ra.pulse("sine", period=0.5, ap=3.0)
    for s in (ra.system("block", alpha=0.2, p=2.0), ra.system("sdof", delta=0.2, ap_min=1.0)):
        r = ra.simulate(s, m, ratio=3.0)
        text = repr(r)
        assert "\n" not in text and len(text) < 300
        assert text.startswith(type(r).__name__ + "(")
        assert ("overturned at t=" in text) == bool(r.overturned)
        assert f"{r.impacts} impacts" in text
