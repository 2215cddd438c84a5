"""Bad inputs across every sub-command: one line ``error: ...`` on stderr, exit status 2,
no traceback, no file left behind, and no computation before the error (the whole file
runs in seconds: every case fails before any sweep or simulation starts).

The cases are generated: a valid base command per sub-command, then one option at a time
replaced by bad values (sizes, angles, restitution, grids, lists, records, paths, Dask
addresses, limits of rockarch.core.limits).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.motion.records import bundled_record_path
from rockarch.risk import hazard
from rockarch.spectra import site

runner = CliRunner()
REC = str(bundled_record_path(180))
HAZARD = str(Path(hazard.__file__).parent / "data" / "hazard_curve-mean-PGA.csv")

AT2_HEAD = ("PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 90\n"
            "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=      4, DT=   .0100 SEC\n")
#: Bad record files: name -> content (bytes for binary files).
BAD_RECORDS = {
    "empty.txt": "",
    "header_only.txt": "time acc\n",
    "one_sample.txt": "0 0.1\n",
    "nan.txt": "0 0.1\n0.01 nan\n0.02 0.3\n",
    "inf.txt": "0 0.1\n0.01 inf\n0.02 0.3\n",
    "nonuniform.txt": "0 0.1\n0.01 0.2\n0.03 0.3\n0.04 0.1\n",
    "backwards.txt": "0 0.1\n0.02 0.2\n0.01 0.3\n",
    "third_column.txt": "0 0.1\n0.01 0.2\n0.02 0.3 7\n0.03 0.1\n",
    "one_column.txt": "0 0.1\n0.01\n0.02 0.3\n",
    "words.txt": "0 0.1\n0.01 x\n",
    "zeros.txt": "0 0\n0.01 0\n0.02 0\n",
    "binary.txt": b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x01",
    "binary.AT2": b"\x00\x01\x02\x03" * 64,
    "short.AT2": "hello\n",
    "npts.AT2": AT2_HEAD.replace("NPTS=      4", "NPTS=      9") + " .1 .2 .3 .4\n",
    "velocity.AT2": AT2_HEAD.replace("ACCELERATION", "VELOCITY") + " .1 .2 .3 .4\n",
    "feet.AT2": AT2_HEAD.replace("UNITS OF G", "UNITS OF FT/S2") + " .1 .2 .3 .4\n",
    "dt.AT2": AT2_HEAD.replace(".0100", "0") + " .1 .2 .3 .4\n",
    "nan.AT2": AT2_HEAD + " .1 NaN .3 .4\n",
    "text.AT2": AT2_HEAD + " .1 abc .3 .4\n",
    # issue 22: sizes and values that used to overflow, hang or allocate gigabytes
    "huge.txt": "0 1e308\n0.01 -1e308\n0.02 1e308\n",
    "dt_tiny.txt": "0 1\n1e-300 2\n2e-300 -3\n",
    "dt_huge.txt": "0 1\n1e300 2\n2e300 -3\n",
    "npts_1e12.AT2": AT2_HEAD.replace("NPTS=      4", "NPTS=1000000000000") + " .1 .2\n",
    "huge.AT2": AT2_HEAD + " 1E300 .2 .3 .4\n",
}
#: Bad assembly files (JSON): name -> content.
BAD_ASSEMBLIES = {
    "latin1.json": b'{"name": "caf\xe9", "blocks": []}',
    "utf16.json": "{}".encode("utf-16"),
    "array.json": b"[1, 2, 3]",
    "empty.json": b"",
    "huge.json": b'{"blocks": [{"polygon": [[0, 0], [1e300, 0], [1e300, 1e300], [0, 1e300]]}]}',
    "nan.json": b'{"blocks": [{"polygon": [[0, 0], [1, 0], [1, NaN], [0, 2]]}]}',
    # a support below the ground, two overlapping supports, a contact given twice: each
    # gave a block a second joint on one face (the dynamics changed, nothing said)
    "support_below.json": b'{"blocks": [{"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]}], '
                          b'"supports": [[[0, -1], [1, -1], [1, 0], [0, 0]]]}',
    "supports_overlap.json": b'{"blocks": [{"polygon": [[0, 1], [1, 1], [1, 2], [0, 2]]}], '
                             b'"supports": [[[0, 0], [1, 0], [1, 1], [0, 1]], '
                             b'[[0.5, 0], [1.5, 0], [1.5, 1], [0.5, 1]]]}',
    "contact_twice.json": b'{"blocks": [{"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]}], '
                          b'"contacts": [{"blocks": [-1, 0]}, {"blocks": [0, -1]}]}',
    # a density of 1e100 failed deep in the statics ("bad operand type for abs()")
    "density1e100.json": b'{"blocks": [{"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]], '
                         b'"density": 1e100}]}',
    # 3000 stacked blocks: refused by the block limit before any statics
    "blocks3000.json": json.dumps({"blocks": [
        {"polygon": [[0, k / 10], [0.4, k / 10], [0.4, (k + 1) / 10], [0, (k + 1) / 10]]}
        for k in range(3000)]}).encode(),
}


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The bad records, a folder, a plain file, a good two-column record, a site file."""
    d = tmp_path_factory.mktemp("bad-inputs")
    for name, content in BAD_ASSEMBLIES.items():
        (d / name).write_bytes(content)
    for name, content in BAD_RECORDS.items():
        f = d / name
        if isinstance(content, bytes):
            f.write_bytes(content)
        else:
            f.write_text(content)
    (d / "folder").mkdir()
    (d / "plain.txt").write_text("not a netcdf file\n")
    (d / "good.txt").write_text("0 0.1\n0.01 0.2\n0.02 -0.3\n0.03 0.0\n")
    (d / "single.txt").write_text("0.1 0.2\n-0.3 0.0\n0.25\n")  # accelerations alone
    (d / "single_text.txt").write_text("0.1\n0.2\nend of part 1\n-0.3\n")
    motions, hashes = site.load_records([REC])
    ds = site.site_oas(motions, np.array([2.0, 4.0]), np.array([1.0, 3.0]), hashes=hashes,
                       tol=0.0, progress=False)
    site.save(ds, d / "site.nc")
    return d


def _sub(args: list[str], **repl) -> list[str]:
    """Replace ``--opt value`` pairs (or append them); a value None removes the option."""
    out = list(args)
    for opt, val in repl.items():
        key = "--" + opt.replace("_", "-")
        if key in out:
            i = out.index(key)
            del out[i:i + 2]
        if val is not None:
            out += [key, str(val)]
    return out


SIM = {
    "block": ["simulate", "block", "--alpha", "0.15", "--p", "2"],
    "frame": ["simulate", "frame", "--alpha", "0.15", "--p", "2", "--mass-ratio", "0.5"],
    "sdof": ["simulate", "sdof", "--p", "2", "--delta", "0.1", "--ap-min", "1.5"],
    "fourhinge": ["simulate", "fourhinge", "--shape", "catenary", "--span", "10", "--rise",
                  "3", "--thickness", "0.25"],
    "mdof": ["simulate", "mdof", "--shape", "catenary", "--span", "10", "--rise", "3",
             "--thickness", "0.25", "--blocks", "12"],
}
MOTION = ["--signal", "sine", "--period", "1", "--ratio", "2"]
OAS = ["oas", "--alpha", "0.1", "--signal", "sine", "--period", "0.5", "--p", "1,2",
       "--ratio-steps", "3", "--no-store"]
ANIM = ["animate", "--shape", "catenary", "--span", "10", "--rise", "3", "--thickness",
        "0.25", "--blocks", "12", "--out", "{tmp}/a.gif"] + MOTION
ARCH = ["arch", "--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.25"]
SITE = ["site-oas", "--records", REC, "--p-min", "1", "--p-max", "2", "--p-steps", "2",
        "--ratio-steps", "2", "--out", "{tmp}/s.nc", "--no-store"]
DESIGN = ["design", "--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness",
          "0.35", "--site", "{files}/site.nc"]


def _cases():
    cases = []

    def add(name, args):
        cases.append(pytest.param(args, id=name))

    # --- the five simulate kinds: sizes, angles, restitution, motion options
    block = SIM["block"] + MOTION
    for v in ("0", "-0.1", "1.5708", "2", "nan", "inf", "abc"):
        add(f"block-alpha={v}", _sub(block, alpha=v))
    for v in ("0", "-1", "nan", "1e300", "x"):
        add(f"block-p={v}", _sub(block, p=v))
    for v in ("-1", "nan", "inf", "two"):
        add(f"block-ratio={v}", _sub(block, ratio=v))
    for v in ("0", "-1", "nan", "inf"):
        add(f"block-period={v}", _sub(block, period=v))
    for v in ("-0.1", "1.5", "nan"):
        add(f"block-restitution={v}", _sub(block, restitution=v))
    for v in ("-1", "nan", "inf", "1e9"):
        add(f"block-t-free={v}", _sub(block, t_free=v))
    for v in ("0", "-9.81", "nan"):
        add(f"block-g={v}", _sub(block, g=v))
    for v in ("0", "-2", "1.5", "1000000"):
        add(f"block-cycles={v}", _sub(block, signal="harmonic", cycles=v))
    add("block-period=1e9", _sub(block, period="1e9"))
    add("block-signal=bogus", _sub(block, signal="bogus"))
    add("block-no-ratio", _sub(block, ratio=None))
    add("block-no-motion", _sub(block, signal=None, period=None))
    add("block-no-period", _sub(block, period=None))
    add("block-record-and-signal", _sub(block, record=REC))
    add("block-no-size", _sub(block, alpha=None))
    add("block-width=0", _sub(block, alpha=None, p=None, width="0", height="2"))
    add("block-height=-2", _sub(block, alpha=None, p=None, width="0.3", height="-2"))
    add("block-unknown-option", block + ["--foo", "1"])
    add("block-extra-argument", block + ["extra"])
    add("simulate-unknown-kind", ["simulate", "cube"] + MOTION)
    add("unknown-command", ["overturn", "--alpha", "0.1"])
    for name in BAD_RECORDS:
        add(f"block-record-{name}", _sub(block, signal=None, period=None,
                                         record=f"{{files}}/{name}"))
    add("block-record-missing", _sub(block, signal=None, period=None, record="{tmp}/no.AT2"))
    add("block-record-folder", _sub(block, signal=None, period=None, record="{files}/folder"))
    add("block-units=furlong", _sub(block, signal=None, period=None,
                                    record="{files}/good.txt", units="furlong"))
    add("block-units-with-AT2", _sub(block, signal=None, period=None, record=REC, units="cm/s2"))
    # --dt: the time step of a single-column record (accelerations alone)
    single = _sub(block, signal=None, period=None, record="{files}/single.txt", units="g")
    for v in ("0", "-0.01", "nan", "inf", "abc", "10", "1e-9"):
        add(f"block-dt={v}", _sub(single, dt=v))
    add("block-single-column-no-dt", single)
    add("block-single-column-text-line", _sub(single, record="{files}/single_text.txt",
                                              dt="0.01"))
    add("block-dt-with-AT2", _sub(single, record=REC, units=None, dt="0.01"))
    add("block-dt-with-two-column", _sub(single, record="{files}/good.txt", dt="0.01"))
    add("block-dt-with-signal", _sub(block, dt="0.01"))
    add("oas-dt=nan", _sub(OAS, signal=None, period=None, record="{files}/single.txt",
                           dt="nan"))
    add("block-plot-missing-dir", _sub(block, plot="{tmp}/no/th.png"))
    add("block-plot-is-folder", _sub(block, plot="{files}/folder"))
    for v in ("0", "-0.1", "nan"):
        add(f"frame-alpha={v}", _sub(SIM["frame"] + MOTION, alpha=v))
    for v in ("-1", "nan"):
        add(f"frame-mass-ratio={v}", _sub(SIM["frame"] + MOTION, mass_ratio=v))
    add("frame-p=0", _sub(SIM["frame"] + MOTION, p="0"))
    for v in ("0", "2", "nan"):
        add(f"sdof-delta={v}", _sub(SIM["sdof"] + MOTION, delta=v))
    for v in ("0", "-1", "inf"):
        add(f"sdof-ap-min={v}", _sub(SIM["sdof"] + MOTION, ap_min=v))
    add("sdof-p=-2", _sub(SIM["sdof"] + MOTION, p="-2"))
    add("sdof-restitution=2", _sub(SIM["sdof"] + MOTION, restitution="2"))
    fh = SIM["fourhinge"] + MOTION
    for opt in ("span", "rise", "thickness"):
        for v in ("0", "-1", "nan"):
            add(f"fourhinge-{opt}={v}", _sub(fh, **{opt: v}))
    add("fourhinge-shape=dome", _sub(fh, shape="dome"))
    add("fourhinge-blocks=1", _sub(fh, blocks="1"))
    add("fourhinge-blocks=-3", _sub(fh, blocks="-3"))
    mdof = SIM["mdof"] + MOTION
    add("mdof-no-arch", ["simulate", "mdof"] + MOTION)
    for v in ("0", "2", "-5"):
        add(f"mdof-blocks={v}", _sub(mdof, blocks=v))
    for v in ("0", "-1"):
        add(f"mdof-thickness={v}", _sub(mdof, thickness=v))
    for v in ("1", "0", "nan"):
        add(f"mdof-h-factor={v}", _sub(mdof, h_factor=v))
    for v in ("0.1", "0"):
        add(f"mdof-gap-tol={v}", _sub(mdof, gap_tol=v))
    add("mdof-t-free=1e9", _sub(mdof, t_free="1e9"))
    add("mdof-period=1e9", _sub(mdof, period="1e9"))
    col = ["simulate", "mdof"] + MOTION
    for v in (";", "a,b", "0.3,0", "0.3,-2", "0.3"):
        add(f"mdof-column={v}", col + ["--column", v])

    # --- animate: output, frames, magnification, limits
    add("animate-out-png", _sub(ANIM, out="{tmp}/a.png"))
    add("animate-out-missing-dir", _sub(ANIM, out="{tmp}/no/a.gif"))
    add("animate-fps=0", _sub(ANIM, fps="0"))
    add("animate-frames=1", _sub(ANIM, frames="1"))
    for v in ("0.5", "nan", "inf"):
        add(f"animate-magnify={v}", _sub(ANIM, magnify=v))
    add("animate-t-free=1e9", _sub(ANIM, t_free="1e9"))
    add("animate-period=1e9", _sub(ANIM, period="1e9"))
    add("animate-no-out", _sub(ANIM, out=None))

    # --- oas: grids, lists, systems, sweeps, Dask addresses, outputs
    for v in ("1,,2", "a,b", ",", "0,1", "-1,2", "nan", "1;;2", "1e300"):
        add(f"oas-p={v}", _sub(OAS, p=v))
    add("oas-p-and-p-min", OAS + ["--p-min", "1", "--p-max", "2"])
    add("oas-p-min>p-max", _sub(OAS, p=None, p_min="2", p_max="1"))
    add("oas-p-min=0", _sub(OAS, p=None, p_min="0", p_max="1"))
    add("oas-p-steps=1", _sub(OAS, p=None, p_min="1", p_max="2", p_steps="1"))
    add("oas-no-p", _sub(OAS, p=None))
    add("oas-p-steps=1e9", _sub(OAS, p=None, p_min="1", p_max="2", p_steps="1000000000"))
    add("oas-ratio-steps=1e9", _sub(OAS, ratio_steps="1000000000"))
    add("site-ratio-steps=1e9", _sub(SITE, ratio_steps="1000000000"))
    add("oas-ratio-steps=0", _sub(OAS, ratio_steps="0"))
    add("oas-ratio-steps=1-with-max", _sub(OAS, ratio_steps="1", ratio_max="3"))
    add("oas-ratio-min=-1", _sub(OAS, ratio_min="-1"))
    add("oas-ratio-max=nan", _sub(OAS, ratio_max="nan"))
    add("oas-ratio-min>max", _sub(OAS, ratio_min="4", ratio_max="2"))
    for v in ("-1", "nan"):
        add(f"oas-tol={v}", _sub(OAS, tol=v))
    add("oas-system=cube", _sub(OAS, system="cube"))
    add("oas-fourhinge-no-shape", _sub(OAS, system="fourhinge", alpha=None))
    add("oas-sdof-no-delta", _sub(OAS, system="sdof", alpha=None, ap_min="1"))
    add("oas-alpha=0", _sub(OAS, alpha="0"))
    add("oas-restitution=1.5", _sub(OAS, restitution="1.5"))
    for v in ("0", "-2"):
        add(f"oas-workers={v}", _sub(OAS, workers=v))
    for v in ("foo", "tcp://", "tcp://host:abc", "http://x:1", "tcp://:8786"):
        add(f"oas-scheduler={v}", _sub(OAS, scheduler=v))
    add("oas-scheduler-and-dask-workers",
        _sub(OAS, scheduler="tcp://127.0.0.1:1", dask_workers="2"))
    add("oas-dask-workers=0", _sub(OAS, dask_workers="0"))
    add("oas-out-missing-dir", _sub(OAS, out="{tmp}/no/o.nc"))
    add("oas-out-is-folder", _sub(OAS, out="{files}/folder"))
    add("oas-plot-missing-dir", _sub(OAS, plot="{tmp}/no/o.png"))
    add("oas-record-nan", _sub(OAS, signal=None, period=None, record="{files}/nan.txt"))
    add("oas-cycles=1000000", _sub(OAS, signal="harmonic", cycles="1000000"))

    # --- arch statics
    for opt in ("span", "rise", "thickness"):
        for v in ("0", "-1"):
            add(f"arch-{opt}={v}", _sub(ARCH, **{opt: v}))
    add("arch-shape=dome", _sub(ARCH, shape="dome"))
    add("arch-no-thickness", _sub(ARCH, thickness=None))
    add("arch-blocks=2", _sub(ARCH, blocks="2"))
    add("arch-direction=0", _sub(ARCH, direction="0"))
    add("arch-mass-model=bogus", _sub(ARCH, mass_model="bogus"))
    add("arch-lambda-without-min-thickness", _sub(ARCH, **{"lambda": "0.1"}))
    add("arch-min-thickness-lambda=nan", _sub(ARCH, thickness=None, **{"lambda": "nan"})
        + ["--min-thickness"])
    add("arch-min-thickness-lambda=-1", _sub(ARCH, thickness=None, **{"lambda": "-1"})
        + ["--min-thickness"])
    add("arch-min-thickness-with-thickness", ARCH + ["--min-thickness"])
    add("arch-plot-missing-dir", _sub(ARCH, plot="{tmp}/no/a.png"))

    # --- site OAS and design
    add("site-no-records", _sub(SITE, records=None))
    for name in ("empty.txt", "nan.txt", "binary.AT2", "third_column.txt"):
        add(f"site-record-{name}", _sub(SITE, records=f"{{files}}/{name}"))
    add("site-record-missing", _sub(SITE, records="{tmp}/none.AT2"))
    add("site-percentile=150", _sub(SITE, percentile="150"))
    add("site-ratio-steps=1", _sub(SITE, ratio_steps="1"))
    add("site-p-min=0", _sub(SITE, p_min="0"))
    add("site-alpha=0", _sub(SITE, alpha="0"))
    add("site-out-missing-dir", _sub(SITE, out="{tmp}/no/s.nc"))
    add("site-out-is-folder", _sub(SITE, out="{files}/folder"))
    add("site-units=furlong", _sub(SITE, records="{files}/good.txt", units="furlong"))
    add("site-dt=0", _sub(SITE, records="{files}/single.txt", dt="0"))
    add("site-dt-with-AT2", _sub(SITE, dt="0.01"))
    add("design-dt-with-site", _sub(DESIGN, dt="0.01"))
    add("site-no-out", _sub(SITE, out=None))
    add("design-site-missing", _sub(DESIGN, site="{tmp}/none.nc"))
    add("design-site-not-netcdf", _sub(DESIGN, site="{files}/plain.txt"))
    add("design-site-folder", _sub(DESIGN, site="{files}/folder"))
    add("design-thickness-rule=bogus", _sub(DESIGN, thickness_rule="bogus"))
    add("design-curve=bogus", _sub(DESIGN, curve="bogus"))
    for opt in ("span", "rise", "thickness"):
        add(f"design-{opt}=0", _sub(DESIGN, **{opt: "0"}))
    add("design-report-missing-dir", _sub(DESIGN, report="{tmp}/no/d.html"))
    # design of any --system: option combinations that do not go together
    col = ["design", "--system", "mdof", "--column", "0.4,1.0", "--site", "{files}/site.nc"]
    add("design-system-sliding-with-site", col + ["--friction", "0.2"])
    add("design-system-thickness-rule", col + ["--thickness-rule", "lower-bound"])
    add("design-system-report-missing-dir", col + ["--report", "{tmp}/no/d.html"])
    add("design-system-curve=simplified", col + ["--curve", "simplified"])
    add("design-system-mdof-p", col + ["--p", "2"])
    add("design-system-no-site-no-records", col[:-2])
    add("design-system-friction-on-a-block", ["design", "--system", "block", "--alpha", "0.1",
                                              "--p", "2", "--friction", "0.3", "--site",
                                              "{files}/site.nc"])
    add("design-system-frame-without-p", ["design", "--system", "frame", "--alpha", "0.1",
                                          "--mass-ratio", "0.5", "--site", "{files}/site.nc"])
    add("design-arch-with-friction", DESIGN + ["--friction", "0.5"])
    add("design-no-structure", ["design", "--site", "{files}/site.nc"])
    add("site-system-frame-without-mass-ratio", SITE + ["--system", "frame", "--alpha", "0.1"])

    # --- fragility, records, cache
    frag = ["fragility", "--system", "block", "--alpha", "0.1", "--p", "2", "--records",
            REC, "--im", "pga", "--no-progress"]
    # .AT2 files state their units (g): another --units is refused for suites as for one
    # --record (site-oas and records info accepted it silently)
    add("fragility-units-on-AT2", frag + ["--units", "cm/s2"])
    add("site-oas-units-on-AT2", SITE + ["--units", "m/s2"])
    add("records-info-units-on-AT2", ["records", "info", REC, "--units", "cm/s2"])
    for opt, v in (("im", "bogus"), ("p", "0"), ("p", "1e300"), ("alpha", "0"),
                   ("records", "{tmp}/none/"), ("records", "{files}/nan.txt"),
                   ("records", "{files}/binary.AT2"), ("level", "2"), ("bootstrap", "-1"),
                   ("im-range", "a,b"), ("ratio-steps", "0"), ("tol", "nan"),
                   ("plot", "{tmp}/no/f.png"), ("scheduler", "foo")):
        add(f"fragility-{opt}={v.split('/')[-1]}", _sub(frag, **{opt.replace("-", "_"): v}))
    add("fragility-im=sa-period=0", _sub(frag, im="sa", period="0"))
    info = ["records", "info", REC]
    add("records-info-missing", ["records", "info", "{tmp}/none.AT2"])
    add("records-info-nan", ["records", "info", "{files}/nan.txt"])
    add("records-info-third-column", ["records", "info", "{files}/third_column.txt"])
    add("records-info-periods=1,,2", info + ["--periods", "1,,2"])
    add("records-info-periods=-1", info + ["--periods", "-1"])
    add("records-info-damping=-0.1", info + ["--damping", "-0.1"])
    add("records-info-plot-missing-dir", info + ["--plot", "{tmp}/no/s.png"])
    add("records-info-no-source", ["records", "info"])
    add("records-info-dt=-1", ["records", "info", "{files}/single.txt", "--dt", "-1"])
    add("records-info-dt-with-AT2", info + ["--dt", "0.01"])
    add("fragility-dt=nan", _sub(frag, records="{files}/single.txt", dt="nan"))
    synth = ["records", "synth", "{tmp}/synth"]
    for opt, v in (("n", "0"), ("n", "-3"), ("dt", "0"), ("dt", "nan"), ("f-corner", "-1"),
                   ("pulse-fraction", "1.5")):
        add(f"records-synth-{opt}={v}", synth + [f"--{opt}", v])
    add("records-synth-into-a-file", ["records", "synth", "{files}/plain.txt"])
    add("cache-unknown-subcommand", ["cache", "purge"])
    add("records-unknown-subcommand", ["records", "list"])

    # --- reproduce
    add("reproduce-out-is-file", ["reproduce", "--out", "{files}/plain.txt", "--quick"])
    add("reproduce-no-out", ["reproduce", "--quick"])
    _issue22_cases(add)
    return cases


def _issue22_cases(add) -> None:
    """Issue 22's bad inputs that slipped through (hangs, unbounded work and memory, raw
    library text, late checks, options that do not apply, Housner's law out of range) and
    held-out ones of the same kinds: each one line, exit 2, before any work."""
    block = SIM["block"] + MOTION
    mdof_col = ["simulate", "mdof"] + MOTION
    # hangs and unbounded work: every sweep estimates its runs' steps first
    add("oas-period=1e300", _sub(OAS, period="1e300"))
    add("oas-square-period=1e200", _sub(OAS, signal="square", period="1e200"))
    add("oas-mdof-period=1e300", ["oas", "--system", "mdof", "--shape", "catenary",
                                  "--rise-over-span", "0.3", "--thickness-over-span", "0.025",
                                  "--blocks", "12", "--p", "2", "--ratio-steps", "3",
                                  "--signal", "sine", "--period", "1e300", "--no-store"])
    add("oas-fourhinge-period=1e300", ["oas", "--system", "fourhinge", "--shape", "catenary",
                                       "--rise-over-span", "0.3", "--thickness-over-span",
                                       "0.025", "--p", "2", "--ratio-steps", "3", "--signal",
                                       "sine", "--period", "1e300", "--no-store"])
    add("oas-sdof-period=1e300", ["oas", "--system", "sdof", "--delta", "0.1", "--ap-min",
                                  "1.5", "--p", "2", "--ratio-steps", "3", "--signal", "sine",
                                  "--period", "1e300", "--no-store"])
    add("site-t-free=1e300", _sub(SITE, t_free="1e300"))
    add("fragility-t-free=1e300", ["fragility", "--system", "block", "--alpha", "0.1", "--p",
                                   "2", "--records", REC, "--t-free", "1e300", "--no-store"])
    add("records-synth-n=1e9", ["records", "synth", "{tmp}/s", "--n", "1000000000"])
    add("records-synth-seed=-1", ["records", "synth", "{tmp}/s", "--n", "2", "--seed", "-1"])
    add("records-synth-dt=1e-9", ["records", "synth", "{tmp}/s", "--n", "2", "--dt", "1e-9"])
    add("records-synth-f-corner=1e9", ["records", "synth", "{tmp}/s", "--n", "2",
                                       "--f-corner", "1e9"])
    add("mdof-wall=1000x1000", mdof_col + ["--wall", "1000,1000", "--block", "0.4,0.2"])
    add("mdof-wall=30x30", mdof_col + ["--wall", "30,30", "--block", "0.4,0.2"])
    add("mdof-colonnade=1e6", mdof_col + ["--colonnade", "1000000", "--block", "0.4,2",
                                          "--bay", "1", "--lintel", "0.5"])
    # --drums: a whole number >= 1, with --colonnade only, on every command that takes it
    col = ["--colonnade", "2", "--block", "0.3,2", "--bay", "1", "--lintel", "0.4"]
    add("mdof-drums=0", mdof_col + col + ["--drums", "0"])
    add("mdof-drums=1e6", mdof_col + col + ["--drums", "1000000"])
    add("mdof-drums-without-colonnade", mdof_col + ["--column", "0.4,1", "--drums", "2"])
    add("animate-drums-without-colonnade", _sub(ANIM, drums="2"))
    add("oas-mdof-drums=-1", _sub(OAS, alpha=None, system="mdof", colonnade="2",
                                  block="0.3,2", bay="1", lintel="0.4", drums="-1"))
    add("site-mdof-drums-without-colonnade", _sub(SITE, system="mdof", wall="2,2",
                                                  block="0.4,0.2", drums="2"))
    add("fragility-drums-without-colonnade", ["fragility", "--system", "mdof", "--column",
                                              "0.4,1", "--drums", "2", "--records", REC,
                                              "--no-store"])
    add("risk-drums-without-colonnade", ["risk", "--hazard", HAZARD, "--system", "mdof",
                                         "--column", "0.4,1", "--drums", "2", "--p", "2",
                                         "--records", REC, "--no-store"])
    add("design-system-drums=0", ["design", "--system", "mdof", *col, "--drums", "0",
                                  "--site", "{files}/site.nc"])
    add("design-arch-drums", DESIGN + ["--drums", "2"])
    add("mdof-bridge-spans=300", _sub(SIM["mdof"] + MOTION, spans="300", pier_height="3",
                                      pier_width="1"))
    add("mdof-pier-blocks=1e6", _sub(SIM["mdof"] + MOTION, spans="1", pier_height="3",
                                     pier_width="1", pier_blocks="1000000"))
    add("mdof-assembly-3000-blocks", mdof_col + ["--assembly", "{files}/blocks3000.json"])
    add("oas-mdof-wall=1000x1000", _sub(OAS, alpha=None, system="mdof", wall="1000,1000",
                                        block="0.4,0.2"))
    add("arch-blocks=1e6", _sub(ARCH, blocks="1000000"))
    add("animate-frames=1e9", _sub(ANIM, frames="1000000000"))
    add("animate-fps=1e6", _sub(ANIM, fps="1000000"))
    add("animate-magnify=1e300", _sub(ANIM, magnify="1e300"))
    add("oas-dask-workers=1e5", _sub(OAS, dask_workers="100000"))
    add("oas-workers=1e6", _sub(OAS, workers="1000000"))
    add("fragility-bootstrap=1e9", ["fragility", "--system", "block", "--alpha", "0.1", "--p",
                                    "2", "--records", REC, "--bootstrap", "1000000000",
                                    "--no-store"])
    add("records-info-periods=1e300", ["records", "info", REC, "--periods", "1e300"])
    add("records-info-periods=1e-9", ["records", "info", REC, "--periods", "1e-9"])
    add("site-p-min=1e-300", _sub(SITE, p_min="1e-300", p_max="1e-299"))
    # records: sizes and values known before the samples are parsed
    for name in ("huge.txt", "dt_tiny.txt", "dt_huge.txt", "npts_1e12.AT2", "huge.AT2"):
        add(f"block-record-{name}", _sub(block, signal=None, period=None,
                                         record=f"{{files}}/{name}"))
    add("records-info-huge.txt", ["records", "info", "{files}/huge.txt"])
    # raw library text: scipy's brentq, undecodable files, numbers out of range
    add("arch-rise=1e-9", _sub(ARCH, rise="1e-9"))
    add("arch-rise=1e9", _sub(ARCH, rise="1e9"))
    add("arch-span=1e300", _sub(ARCH, span="1e300"))
    add("arch-all=1e300", _sub(ARCH, span="1e300", rise="1e299", thickness="1e298"))
    add("arch-thickness=1e-9", _sub(ARCH, thickness="1e-9"))
    add("arch-pointed-rise=1e9", _sub(ARCH, shape="pointed", rise="1e9"))
    for name in BAD_ASSEMBLIES:
        add(f"mdof-assembly-{name}", mdof_col + ["--assembly", f"{{files}}/{name}"])
    add("mdof-column=1e300", mdof_col + ["--column", "1e300,1e300"])
    add("mdof-friction=1e-300", mdof_col + ["--column", "0.4,1", "--friction", "1e-300"])
    add("block-g=1e308", _sub(block, g="1e308"))
    add("block-ratio=1e300", _sub(block, ratio="1e300"))
    add("block-ratio=0", _sub(block, ratio="0"))  # no ground motion: (0, 1e6]
    add("oas-ratio-max=1e300", _sub(OAS, ratio_min="0", ratio_max="1e300"))
    add("oas-tol=1e-300", _sub(OAS, tol="1e-300"))  # ~1000 bisection rounds: a hang
    add("mdof-column-empty-block", mdof_col + ["--column", "0.4,1;;0.3,0.5"])
    # pier options that were ignored (one span between abutments) or read in metres
    # beside an arch of span 1 (f/l, d/l)
    arch10 = ["--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness", "0.35",
              "--blocks", "10"]
    add("mdof-one-span-abutments", mdof_col + arch10 + [
        "--spans", "1", "--abutments", "--pier-height", "3", "--pier-width", "1.5"])
    add("oas-mdof-piers-beside-ratios", ["oas", "--system", "mdof", "--shape", "catenary",
                                         "--rise-over-span", "0.3", "--thickness-over-span",
                                         "0.025", "--blocks", "10", "--spans", "2",
                                         "--pier-height", "3", "--pier-width", "1", "--signal",
                                         "sine", "--period", "1", "--p", "3", "--no-store"])
    add("mdof-column=0.3-plain-numbers", mdof_col + ["--column", "0.3"])
    # late checks: refused before the IDA
    des = ["design", "--shape", "circular", "--span", "10", "--rise", "2.89", "--thickness",
           "0.35", "--records", REC]
    add("design-probability=1.5", des + ["--pga", "3", "--probability", "1.5"])
    add("design-pga=-3", des + ["--pga", "-3"])
    add("design-percentile=150", des + ["--percentile", "150"])
    add("design-system-probability=0", ["design", "--system", "block", "--alpha", "0.1",
                                        "--p", "2", "--records", REC, "--probability", "0",
                                        "--no-store"])
    # options that do not apply
    add("design-system-block-shape", ["design", "--system", "block", "--alpha", "0.1", "--p",
                                      "2", "--shape", "circular", "--site",
                                      "{files}/site.nc"])
    add("design-system-block-blocks", ["design", "--system", "block", "--alpha", "0.1",
                                       "--p", "2", "--blocks", "7", "--site",
                                       "{files}/site.nc"])
    add("design-system-thickness-rule=equivalent",
        ["design", "--system", "mdof", "--column", "0.4,1.0", "--thickness-rule",
         "equivalent", "--site", "{files}/site.nc"])
    add("design-site-probability", DESIGN + ["--probability", "0.2"])
    add("design-site-percentile", DESIGN + ["--curve", "characteristic", "--percentile", "10"])
    add("design-site-pga", DESIGN + ["--pga", "3"])
    add("oas-block-shape", _sub(OAS, shape="circular"))
    add("oas-block-blocks", _sub(OAS, blocks="5"))
    add("oas-sdof-alpha", _sub(OAS, system="sdof", delta="0.1", ap_min="1"))
    add("oas-fourhinge-mass-ratio", ["oas", "--system", "fourhinge", "--shape", "catenary",
                                     "--rise-over-span", "0.3", "--thickness-over-span",
                                     "0.025", "--mass-ratio", "0.5", "--p", "2", "--signal",
                                     "sine", "--period", "1", "--no-store"])
    add("mdof-wall-blocks", mdof_col + ["--wall", "4,10", "--block", "0.4,0.2", "--blocks",
                                        "5"])
    add("mdof-wall-no-block", mdof_col + ["--wall", "4,10"])
    add("block-cycles-with-sine", _sub(block, cycles="5"))
    add("block-cycles-with-record", _sub(block, signal=None, period=None, record=REC,
                                         cycles="5"))
    add("block-units-with-signal", _sub(block, units="g"))
    # Housner's restitution 1 - 1.5 sin²alpha < 0: refused, --restitution asked for
    add("block-alpha=1.2-housner", _sub(block, alpha="1.2"))
    add("block-3x1-housner", _sub(block, alpha=None, p=None, width="3", height="1"))
    add("frame-stocky-housner", _sub(SIM["frame"] + MOTION, alpha="0.9", mass_ratio="5"))
    add("sdof-delta=1.2-housner", _sub(SIM["sdof"] + MOTION, delta="1.2"))
    add("oas-alpha=1.0-housner", _sub(OAS, alpha="1.0"))


CASES = _cases()


def test_there_are_at_least_100_cases():
    assert len(CASES) >= 100


@pytest.mark.parametrize("args", CASES)
def test_bad_input_is_one_line_exit_2(args, files, tmp_path):
    argv = [a.replace("{tmp}", str(tmp_path)).replace("{files}", str(files)) for a in args]
    before = sorted(files.rglob("*"))
    res = runner.invoke(app, argv)
    # off a terminal a long command prints a "progress: ..." line per stage before it
    # fails (rockarch.cli._common.stage_echo); the error itself is one line
    lines = [x for x in res.stderr.strip().splitlines() if not x.startswith("progress: ")]
    assert res.exit_code == 2, (res.exit_code, res.stdout, res.stderr, res.exception)
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert "Traceback" not in res.stderr + res.stdout
    assert list(tmp_path.iterdir()) == [], "a file was left behind"
    assert sorted(files.rglob("*")) == before, "a file was left behind"


def test_bad_input_in_a_real_process(tmp_path):
    """The real entry point (not CliRunner): same one line, status 2, no warning."""
    args = ["simulate", "block", "--alpha", "0.1", "--p", "2", "--signal", "harmonic",
            "--period", "1", "--cycles", "1000000", "--ratio", "2"]
    code = "import sys; from rockarch.cli import app; sys.argv[0] = 'rockarch'; app()"
    # every warning rockarch itself raises is shown; third-party deprecations (matplotlib
    # 3.8-3.10 under pyparsing 3.3 warn at import) are not rockarch's output
    env = {**os.environ, "PYTHONWARNINGS": "default,ignore::DeprecationWarning"}
    res = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True,
                         cwd=tmp_path, env=env, timeout=60)
    assert res.returncode == 2 and res.stdout == ""
    assert len(res.stderr.strip().splitlines()) == 1 and res.stderr.startswith("error: ")
    assert list(tmp_path.iterdir()) == []
