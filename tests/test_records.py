"""Record readers: PEER NGA .AT2 (new and old headers), ESM ASCII, two-column text, bad
files."""

import os
import re

import numpy as np
import pytest

from rockarch.motion.records import (
    G_STANDARD,
    UnitsWarning,
    bundled_record_path,
    el_centro,
    read_at2,
    read_record,
    read_two_column,
)

NEW = """PEER NGA STRONG MOTION DATABASE RECORD
Test event, 1/1/2000, Station, 90
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=      7, DT=   .0200 SEC
  .1000000E-01  -.2000000E-01   .3000000E-01   .0000000E+00  -.5000000E-01
  .1000000E-01   .0000000E+00
"""
OLD = """PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.
TEST 1/1/80 0000, STATION, 090
ACCELERATION TIME HISTORY IN UNITS OF G
     7    0.02000    NPTS, DT
  .1000000E-01  -.2000000E-01   .3000000E-01   .0000000E+00  -.5000000E-01
  .1000000E-01   .0000000E+00
"""


def _write(tmp_path, name, text):
    f = tmp_path / name
    f.write_text(text)
    return f


@pytest.mark.parametrize("text", [NEW, OLD], ids=["nga-west2", "old-nga"])
def test_both_header_styles(tmp_path, text):
    m = read_at2(_write(tmp_path, "x.AT2", text))
    assert m.t.size == 7
    assert np.allclose(np.diff(m.t), 0.02)
    assert m.a[2] == pytest.approx(0.03 * G_STANDARD)
    assert m.pga == pytest.approx(0.05 * G_STANDARD)


def test_bundled_el_centro_matches_its_provenance():
    m = el_centro()
    # ../shared/records/README.md: dt 0.01 s, 5372 points, PGA 0.281 g
    assert m.t.size == 5372
    assert m.t[1] - m.t[0] == pytest.approx(0.01)
    assert m.pga / G_STANDARD == pytest.approx(0.281, abs=5e-4)
    assert "El Centro" in m.name


def test_two_column_units_and_header(tmp_path):
    f = _write(tmp_path, "rec.txt", "time acc\n0.0 0.1\n0.01, 0.2\n0.02\t-0.3\n0.03 0.0\n")
    m = read_two_column(f, units="g")
    assert m.a[2] == pytest.approx(-0.3 * G_STANDARD)
    # m/s2 by default, with a warning: a peak of 0.3 is plausible in g too
    with pytest.warns(UnitsWarning, match="plausible PGA in g"):
        assert read_record(f).a[2] == pytest.approx(-0.3)


@pytest.mark.parametrize(
    "name, text, msg",
    [
        ("a.AT2", NEW.replace("NPTS=      7", "NPTS=      9"), "NPTS=9 but the file holds 7"),
        ("b.AT2", "\n".join(NEW.splitlines()[:4]) + "\n", "holds 0 values"),
        ("b1.AT2", "\n".join(NEW.splitlines()[:4]).replace("7,", "1,") + "\n .1\n",
         "at least 2 samples"),
        ("c.AT2", NEW.replace("-.2000000E-01", "NaN"), "not a finite number"),
        ("d.AT2", NEW.replace("ACCELERATION", "VELOCITY"), "not an acceleration record"),
        ("e.AT2", NEW.replace("NPTS=      7, DT=   .0200 SEC", "garbage"), "NPTS and DT"),
        ("f.AT2", NEW.replace(".3000000E-01", "abc"), "not all numbers"),
        ("g.AT2", "hello\n", "fewer than 4 header lines"),
        ("h.txt", "0 1\n0.01 2\n0.03 3\n0.04 1\n", "non-uniform time step"),
        ("i.txt", "0 1\n", "at least 2 samples"),
        ("j.txt", "", "at least 2 samples"),
        ("k.txt", "0 0\n0.01 0\n", "every sample is zero"),
        ("l.txt", "0 1\n0.01 x\n", "not two numbers"),
    ],
)
def test_bad_files_give_one_clear_message(tmp_path, name, text, msg):
    with pytest.raises(ValueError, match=msg):
        read_record(_write(tmp_path, name, text))


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        read_record(tmp_path / "nope.AT2")
    with pytest.raises(ValueError, match="is a directory"):
        read_record(tmp_path)


@pytest.mark.parametrize(
    "text, msg",
    [
        ("0 1\n0.01 2\n0.02 3 4\n0.03 1\n", "line 3 has 3 column"),   # a third column
        ("# c\n0 1\n0.01 2\n0.02 nan\n", "line 4 holds a value that is not a finite"),
        ("0 1\n0.01 2\n0.03 3\n0.04 1\n", "non-uniform time step at line 3"),
        ("0 1\n0.02 2\n0.01 3\n", "time must increase .line 3"),
        ("time acc\n", "no samples"),
        ("0 1\n", "at least 2 samples, found 1"),
        ("0 1\n0.01 2\n0.02\n", "line 3 has 1 column"),
        ("0,00;0,5\n0,01;0,25\n", "line 1 has 4 column.*decimal commas"),
        ("0.01\n-0.02\n0.03\n", "line 1 has 1 column.*no time step.*ESM .ASC"),
    ],
    ids=["third-column", "nan", "non-uniform", "backwards", "header-only", "one", "short",
         "decimal-comma", "single-column"],
)
def test_two_column_errors_name_the_line(tmp_path, text, msg):
    with pytest.raises(ValueError, match=msg):
        read_two_column(_write(tmp_path, "r.txt", text))


def test_a_peer_file_under_another_name_is_read_as_peer(tmp_path):
    path = tmp_path / "elcentro.txt"
    path.write_bytes(bundled_record_path(180).read_bytes())
    got, ref = read_record(path), el_centro()
    assert got.meta["format"] == "AT2"
    np.testing.assert_array_equal(got.a, ref.a)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_pipe_is_refused_with_one_line(tmp_path):
    """A named pipe (or ``<(...)``) cannot be read twice as the readers do: one clear line,
    not an io error from deep inside (nor a hang waiting for a writer)."""
    fifo = tmp_path / "rec.txt"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match="not a regular file .a pipe.."):
        read_record(fifo)


def test_binary_and_unknown_units(tmp_path):
    f = tmp_path / "r.txt"
    f.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR")
    with pytest.raises(ValueError, match="binary file"):
        read_record(f)
    with pytest.raises(ValueError, match="binary file"):
        read_record(f.rename(tmp_path / "r.AT2"))
    with pytest.raises(ValueError, match="unknown acceleration unit 'furlong'"):
        read_two_column(_write(tmp_path, "s.txt", "0 1\n0.01 2\n"), units="furlong")


def test_two_column_with_a_byte_order_mark_keeps_its_first_sample(tmp_path):
    f = tmp_path / "bom.txt"
    f.write_bytes(b"\xef\xbb\xbf0 0.1\n0.01 0.2\n0.02 -0.3\n")
    a = read_record(f, units="m/s2").a
    # the three samples as written (to their last bit: make test-perturbed moves it)
    assert a.size == 3 and a == pytest.approx([0.1, 0.2, -0.3], rel=1e-15)


def test_two_column_without_units_warns_on_an_implausible_pga(tmp_path):
    """A file in mm/s² read as m/s² (PGA 3e5 m/s²): one warning naming the units to give."""
    f = _write(tmp_path, "mm.txt", "0 1e5\n0.01 2e5\n0.02 -3e5\n")
    with pytest.warns(UnitsWarning, match="not plausible: wrong units") as w:
        read_record(f)
    assert "3e+05 m/s² = 3.06e+04 g (g = 9.80665 m/s²) is not" in str(w[0].message)
    assert read_record(f, units="mm/s2").pga == pytest.approx(300.0)


# --------------------------------------------------------------------------- ESM / ITACA ASCII


def _esm_text(values_cm, dt=0.01, units="cm/s^2", data_type="ACCELERATION", ndata=None,
              drop=()):
    """An ESM ASCII file as the Engineering Strong-Motion database writes one: 64 header
    lines ``KEY: value`` (EVENT_NAME first), then one sample a line."""
    keys = {
        "EVENT_NAME": "CENTRAL_ITALY", "EVENT_ID": "EMSC-20160824_0000006",
        "EVENT_DATE_YYYYMMDD": "20160824", "EVENT_TIME_HHMMSS": "013632",
        "EVENT_LATITUDE_DEGREE": "42.6983", "EVENT_LONGITUDE_DEGREE": "13.2335",
        "EVENT_DEPTH_KM": "8.1", "HYPOCENTER_REFERENCE": "INGV", "MAGNITUDE_W": "6.0",
        "NETWORK": "IT", "STATION_CODE": "AMT", "STATION_NAME": "AMATRICE",
        "STATION_LATITUDE_DEGREE": "42.632600", "STATION_LONGITUDE_DEGREE": "13.286000",
        "STATION_ELEVATION_M": "0", "LOCATION": "", "SENSOR_DEPTH_M": "0", "VS30_M/S": "",
        "SITE_CLASSIFICATION_EC8": "B*", "MORPHOLOGIC_CLASSIFICATION": "",
        "EPICENTRAL_DISTANCE_KM": "8.5", "EARTHQUAKE_BACKAZIMUTH_DEGREE": "302.6",
        "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS": "20160824_013636.000",
        "DATE_TIME_FIRST_SAMPLE_PRECISION": "milliseconds",
        "SAMPLING_INTERVAL_S": f"{dt:.6f}", "NDATA": str(ndata or len(values_cm)),
        "DURATION_S": f"{dt * len(values_cm):.3f}", "STREAM": "HNE", "UNITS": units,
        "INSTRUMENT": "sensor = Unknown [Unknown] | digitizer = Unknown [Unknown]",
        "INSTRUMENT_ANALOG/DIGITAL": "D", "INSTRUMENTAL_FREQUENCY_HZ": "",
        "INSTRUMENTAL_DAMPING": "", "FULL_SCALE_G": "", "N_BIT_DIGITAL_CONVERTER": "",
        "PGA_CM/S^2": f"{np.abs(values_cm).max():.6f}", "TIME_PGA_S": "",
        "BASELINE_CORRECTION": "BASELINE REMOVED", "FILTER_TYPE": "BUTTERWORTH",
        "FILTER_ORDER": "2", "LOW_CUT_FREQUENCY_HZ": "0.100",
        "HIGH_CUT_FREQUENCY_HZ": "30.000", "LATE/NORMAL_TRIGGERED": "NT",
        "DATABASE_VERSION": "ESM 2018", "HEADER_FORMAT": "DYNA 1.2",
        "DATA_TYPE": data_type, "PROCESSING": "manual (Paolucci et al., 2011)",
        "DATA_TIMESTAMP_YYYYMMDD_HHMMSS": "20180101_000000.000",
        "DATA_LICENSE": "CC BY 4.0", "DATA_CITATION": "Luzi et al. (2016)",
        "DATA_CREATOR": "ESM", "ORIGINAL_DATA_MEDIATOR_CITATION": "",
        "ORIGINAL_DATA_MEDIATOR": "", "ORIGINAL_DATA_CREATOR_CITATION": "",
        "ORIGINAL_DATA_CREATOR": "",
    }
    for k in drop:
        keys.pop(k)
    lines = [f"{k}: {v}" for k, v in keys.items()]
    lines += [f"USER{i}:" for i in range(1, 65 - len(lines))]
    return "\n".join(lines + [f"{v:.6E}" for v in values_cm]) + "\n"


def test_esm_file_reads_as_the_same_record(tmp_path):
    """El Centro written as an ESM file in cm/s² reads back as the bundled record: the same
    step and samples within the file's 7 significant digits (5e-7 relative)."""
    ref = el_centro()
    path = tmp_path / "IT.AMT..HNE.D.20160824.013632.C.ACC.ASC"
    path.write_text(_esm_text(ref.a * 100.0, dt=ref.t[1] - ref.t[0]))
    got = read_record(path, units="g")  # an ESM file states its units; --units is for text
    assert got.meta["format"] == "ESM" and got.meta["npts"] == ref.t.size
    assert got.name == f"{path.name} (CENTRAL_ITALY AMT HNE)"
    np.testing.assert_allclose(got.t, ref.t, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(got.a, ref.a, rtol=5e-7, atol=0)
    # any suffix: the first header line decides
    other = tmp_path / "amatrice.txt"
    other.write_text(path.read_text())
    assert read_record(other).meta["format"] == "ESM"


def test_esm_units_metadata_and_folder(tmp_path):
    """A folder's .ASC files are read with their units and header metadata; the vertical
    stream (HNZ) is left out as an .AT2 vertical is."""
    from rockarch.motion.suite import read_suite

    vals = np.array([0.0, 100.0, -200.0, 50.0, 0.0])  # cm/s²: PGA 0.2 g, a plausible one
    (tmp_path / "a.ASC").write_text(_esm_text(vals / 100.0, units="m/s^2"))
    (tmp_path / "b.asc").write_text(_esm_text(vals / 100.0 / G_STANDARD, units="g"))
    (tmp_path / "c.ASC").write_text(_esm_text(vals).replace("STREAM: HNE", "STREAM: HNZ"))
    suite = read_suite(tmp_path)
    assert [r.name for r in suite.records] == ["a.ASC", "b.asc"]
    assert "c.ASC: vertical component left out" in suite.notes[0]
    # ESM writes None where a value is unknown (EVENT_NAME: None in real files)
    (tmp_path / "d.ASC").write_text(_esm_text(vals).replace("EVENT_NAME: CENTRAL_ITALY",
                                                             "EVENT_NAME: None"))
    d = read_record(tmp_path / "d.ASC")
    assert d.name == "d.ASC (AMT HNE)" and "EVENT_NAME" in d.meta["header"]
    for r in suite.records:  # the file's 7 significant digits: 5e-7 relative
        np.testing.assert_allclose(r.motion.a, vals / 100.0, rtol=5e-7)
        assert (r.event, r.year, r.station, r.component, r.magnitude) == (
            "CENTRAL_ITALY", 2016, "AMATRICE", "HNE", 6.0)
        assert r.vs30 is None  # an empty header value


@pytest.mark.parametrize("kwargs, msg", [
    ({"ndata": 9}, "header says NDATA=9 but the file holds 5 values"),
    ({"drop": ("SAMPLING_INTERVAL_S",)}, "needs the header line SAMPLING_INTERVAL_S"),
    ({"drop": ("UNITS",)}, "needs the header line UNITS"),
    ({"data_type": "VELOCITY"}, "not an acceleration time history (DATA_TYPE: VELOCITY)"),
    ({"data_type": "ACCELERATION RESPONSE SPECTRUM"}, "not an acceleration time history"),
    ({"units": "cm/s"}, "unknown acceleration unit 'cm/s'"),
    ({"dt": 0.0}, "SAMPLING_INTERVAL_S must be > 0"),
])
def test_esm_bad_files_give_one_clear_message(tmp_path, kwargs, msg):
    path = tmp_path / "r.ASC"
    path.write_text(_esm_text(np.array([0.0, 1.0, -2.0, 0.5, 0.0]), **kwargs))
    with pytest.raises(ValueError, match=re.escape(msg)):
        read_record(path)


def test_esm_header_in_another_order_is_still_esm(tmp_path):
    """A file of ESM header lines that does not open with EVENT_NAME (ITACA's older files,
    files written by other tools) is read as ESM, not refused as a two-column file."""
    text = _esm_text(np.array([0.0, 100.0, -200.0, 50.0, 0.0]))
    lines = text.splitlines()
    path = tmp_path / "r.txt"
    path.write_text("\n".join(lines[1:64] + [lines[0]] + lines[64:]) + "\n")
    m = read_record(path)
    assert m.meta["format"] == "ESM" and m.pga == pytest.approx(2.0)


def test_site_oas_says_which_records_it_leaves_out(tmp_path):
    """site-oas reads a folder as every --records does and says so when it leaves a
    vertical stream out (it used to drop the suite's notes silently)."""
    from typer.testing import CliRunner

    from rockarch.cli import app

    ref = el_centro()
    text = _esm_text(ref.a[:500] * 100.0, dt=ref.t[1] - ref.t[0])
    (tmp_path / "recs").mkdir()
    (tmp_path / "recs" / "h.ASC").write_text(text)
    (tmp_path / "recs" / "z.ASC").write_text(text.replace("STREAM: HNE", "STREAM: HNZ"))
    res = CliRunner().invoke(app, ["site-oas", "--records", str(tmp_path / "recs"),
                                   "--p-steps", "2", "--ratio-steps", "2", "--t-free", "1",
                                   "--tol", "0", "--no-store", "--out", str(tmp_path / "s.nc")])
    assert res.exit_code == 0, res.output
    assert "warning: z.ASC: vertical component left out" in res.stderr
    assert "site OAS of 1 record(s)" in res.stdout


# --------------------------------------------------------------------------- K-NET / KiK-net

#: K-NET's recorder: 1 count = 2000/8388608 gal (the 24-bit loggers' Scale Factor).
KNET_SCALE = (2000.0, 8388608.0)


def _knet_text(gal, offset=-18000, fs=100, direction="E-W", duration=None, peak=None,
               drop=()):
    """A K-NET ASCII file as NIED writes one: 17 header lines (keys padded to column 18),
    then integer counts with the recorder's offset, 8 a line. ``Max. Acc.`` is the peak
    after the mean of the counts is removed, as NIED defines it."""
    num, den = KNET_SCALE
    counts = np.round(np.asarray(gal) * den / num).astype(int) + offset
    acc = counts * num / den
    keys = {
        "Origin Time": "2011/03/11 14:46:00", "Lat.": "38.103", "Long.": "142.860",
        "Depth. (km)": "24", "Mag.": "9.0", "Station Code": "MYG004",
        "Station Lat.": "38.7312", "Station Long.": "141.0214", "Station Height(m)": "230",
        "Record Time": "2011/03/11 14:46:59", "Sampling Freq(Hz)": f"{fs}Hz",
        "Duration Time(s)": str(duration if duration is not None else len(gal) // 100),
        "Dir.": direction, "Scale Factor": f"{num:.0f}(gal)/{den:.0f}",
        "Max. Acc. (gal)": f"{np.abs(acc - acc.mean()).max() if peak is None else peak:.3f}",
        "Last Correction": "2011/03/11 14:46:44", "Memo.": "",
    }
    lines = [f"{k:<18}{v}" for k, v in keys.items() if k not in drop]
    lines += ["".join(f"{c:>9d}" for c in counts[i:i + 8]) for i in range(0, len(counts), 8)]
    return "\n".join(lines) + "\n"


def test_knet_file_reads_as_the_same_record(tmp_path):
    """El Centro written as K-NET counts with a large recorder offset reads back as the
    bundled record less its mean: within one count (2.4e-4 gal), the offset removed as NIED
    removes it (the mean of the whole record)."""
    ref = el_centro()
    path = tmp_path / "MYG0041103111446.EW"
    path.write_text(_knet_text(ref.a * 100.0, duration=54))
    got = read_record(path, units="g")  # K-NET states its scale; --units is for text
    assert got.meta["format"] == "K-NET" and got.meta["npts"] == ref.t.size
    assert got.name == f"{path.name} (MYG004 E-W 2011/03/11 14:46:00)"
    np.testing.assert_allclose(got.t, ref.t, rtol=1e-12, atol=1e-12)
    one_count = KNET_SCALE[0] / KNET_SCALE[1] * 0.01  # m/s²
    assert np.abs(got.a - (ref.a - ref.a.mean())).max() <= one_count
    other = tmp_path / "knet.txt"  # any suffix: the first header line decides
    other.write_text(path.read_text())
    assert read_record(other).meta["format"] == "K-NET"


def test_knet_folder_metadata_vertical_and_borehole(tmp_path):
    """A folder's K-NET and KiK-net files are read with their header's metadata; the U-D
    component and KiK-net's borehole sensor (Dir. 1-3) are left out with a note."""
    from rockarch.motion.suite import read_suite

    gal = 150.0 * np.sin(np.linspace(0.0, 20.0, 1000))  # 10 s at 100 Hz, 0.15 g
    (tmp_path / "MYG0041103111446.NS").write_text(_knet_text(gal, direction="N-S"))
    (tmp_path / "MYG0041103111446.UD").write_text(_knet_text(gal, direction="U-D"))
    (tmp_path / "IWTH251103111446.EW1").write_text(_knet_text(gal, direction="2"))
    (tmp_path / "IWTH251103111446.EW2").write_text(_knet_text(gal, direction="5"))
    suite = read_suite(tmp_path)
    assert [r.name for r in suite.records] == ["IWTH251103111446.EW2", "MYG0041103111446.NS"]
    assert "vertical component left out" in " ".join(suite.notes)
    assert "IWTH251103111446.EW1: KiK-net borehole sensor left out" in " ".join(suite.notes)
    r = suite.records[1]
    assert (r.event, r.year, r.station, r.component, r.magnitude) == (
        "2011/03/11 14:46:00", 2011, "MYG004", "N-S", 9.0)
    assert suite.records[0].component == "E-W"  # KiK-net's Dir. 5: the surface E-W sensor


# --------------------------------------------------------------------------- COSMOS


def _cosmos_text(cm, dt=0.01, orientation=340, kind="acceleration", units="cm/sec2(04)",
                 dt_ms=None, approx=None, peak=None, channels=1):
    """A COSMOS v1.20 file as CESMD writes a corrected record (V2): 13 text lines, 100
    integer and 100 real header values (orientation: integer 54; the sampling interval in
    ms: real 62; the peak: real 64), comments, the data line and the values in (8F8.3):
    fields of 8 characters that touch where a value fills its field (-275.123-12.000)."""
    cm = np.round(np.asarray(cm, dtype=float), 3)
    ints = np.full(100, -999)
    ints[39], ints[53] = 1940, orientation
    reals = np.full(100, -999.0)
    reals[61] = dt * 1000.0 if dt_ms is None else dt_ms
    reals[63] = cm[np.argmax(np.abs(cm))] if peak is None else peak
    text = ["Corrected acceleration    (Format v01.20 with 13 text lines) Src: test",
            "Record of Imperial Valley Earthquake of May 19, 1940",
            "Hypocenter: 32.7330 -115.5000 H= 9km Mw=6.95",
            "Origin: 05/19/1940, 04:36:40 UTC", "Statn No: 01-117  Code:CE-117  El Centro",
            *[f"text line {i}" for i in range(6, 14)]]
    lines = text + [" 100 Integer-header values follow on  10 lines, Format= (10I8)"]
    lines += ["".join(f"{v:8d}" for v in ints[i:i + 10]) for i in range(0, 100, 10)]
    lines += [" 100 Real-header values follow on  20 lines, Format= (5F15.6)"]
    lines += ["".join(f"{v:15.6f}" for v in reals[i:i + 5]) for i in range(0, 100, 5)]
    lines += ['  1 Comment line(s) follow, each starting with a "|":', "| a comment"]
    lines += [f"{cm.size:8d} {kind} pts, approx {approx or round(cm.size * dt):4d} secs, "
              f"units={units},Format=(8F8.3)"]
    lines += ["".join(f"{v:8.3f}" for v in cm[i:i + 8]) for i in range(0, cm.size, 8)]
    lines += ["/&  ----------  End of data for channel  1  ----------"]
    return "\n".join(lines * channels) + "\n"


def test_cosmos_file_reads_as_the_same_record(tmp_path):
    """El Centro written as a COSMOS V2 file in cm/s² with fields that touch reads back as
    the bundled record: the same step, the samples within the file's 3 decimals in cm/s²
    (5e-6 m/s²), the metadata from its header."""
    from rockarch.motion.suite import read_suite

    ref = el_centro()
    path = tmp_path / "CE117.V2c"
    text = _cosmos_text(ref.a * 100.0)
    assert re.search(r"\d-\d", text.split("Format=(8F8.3)")[1])  # fields that touch
    path.write_text(text)
    got = read_record(path, units="g")  # COSMOS states its units; --units is for text
    assert got.meta["format"] == "COSMOS" and got.t.size == ref.t.size
    np.testing.assert_allclose(got.t, ref.t, rtol=1e-12, atol=1e-12)
    assert np.abs(got.a - ref.a).max() <= 5.0001e-6
    r = read_suite(path).records[0]
    assert (r.event, r.year, r.station, r.component, r.magnitude) == (
        "Record of Imperial Valley Earthquake of May 19, 1940", 1940, "CE-117", "340", 6.95)
    up = tmp_path / "up.txt"  # any suffix: the first line decides
    up.write_text(_cosmos_text(ref.a[:1000] * 100.0, orientation=400))
    assert read_record(up).meta["component"] == "Up"


@pytest.mark.parametrize("fmt, kwargs, msg", [
    ("knet", {"duration": 30}, "last 10.00 s, the header's Duration Time(s) is 30 s (truncated"),
    ("knet", {"peak": 99.0}, "the header's Max. Acc. is 99 gal (edited or corrupted"),
    ("knet", {"drop": ("Scale Factor",)}, "needs the header line 'Scale Factor'"),
    ("knet", {"fs": "fast"}, "Sampling Freq(Hz) must be a positive number"),
    ("cosmos", {"channels": 2}, "holds 2 acceleration channels (#1 340, #2 340): give one as "
                                "r.V2c#N (N = 1..2), or the file in a suite (--records)"),
    ("cosmos", {"kind": "raw accel.", "units": "counts (50)"}, "not an acceleration in physical"),
    ("cosmos", {"kind": "velocity", "units": "cm/sec(04)"}, "not an acceleration in physical"),
    ("cosmos", {"dt_ms": -999.0}, "the sampling interval (real header value 62, ms) is unknown"),
    ("cosmos", {"approx": 30}, "the data line says approx 30 secs"),
    ("cosmos", {"peak": 99.0}, "its header's (real value 64) 99 cm/sec2 (edited or corrupted"),
])
def test_knet_and_cosmos_bad_files_give_one_clear_message(tmp_path, fmt, kwargs, msg):
    write, name = {"knet": (_knet_text, "r.NS"), "cosmos": (_cosmos_text, "r.V2c")}[fmt]
    path = tmp_path / name
    path.write_text(write(150.0 * np.sin(np.linspace(0.0, 20.0, 1000)), **kwargs))
    with pytest.raises(ValueError, match=re.escape(msg)):
        read_record(path)


def test_cosmos_file_of_several_channels(tmp_path):
    """A COSMOS file of three channels (340, 250 and the vertical, each followed by its
    velocity, as in a V2 file): ``FILE#N`` reads channel N as the single-channel file of it
    reads; a suite reads the two horizontal ones as ``FILE#1``, ``FILE#2`` and leaves the
    vertical out with a note; wrong channels and ``#N`` on other formats are one line."""
    from rockarch.motion.suite import read_suite

    cm = [150.0 * np.sin(np.linspace(0.0, 20.0 + 5 * k, 1000)) for k in range(3)]
    texts = [_cosmos_text(c, orientation=o) for c, o in zip(cm, (340, 250, 400), strict=True)]
    velocity = [t.replace("Corrected acceleration", "Corrected velocity")
                .replace("acceleration pts", "velocity pts").replace("cm/sec2", "cm/sec")
                for t in texts]
    path = tmp_path / "three.V2c"
    path.write_text("".join(a + v for a, v in zip(texts, velocity, strict=True)))
    for k in range(3):
        one = tmp_path / f"one{k}.V2c"
        one.write_text(texts[k])
        got, ref = read_record(f"{path}#{k + 1}"), read_record(one)
        assert np.array_equal(got.a, ref.a) and np.array_equal(got.t, ref.t)
        assert got.name.startswith(f"three.V2c#{k + 1} (") and got.meta["channel"] == k + 1
    suite = read_suite(tmp_path / "three.V2c")
    assert [r.name for r in suite] == ["three.V2c#1", "three.V2c#2"]
    assert [r.component for r in suite] == ["340", "250"]
    assert {r.path for r in suite} == {str(path)}  # the file, for its hash in reports
    assert suite.notes == ("three.V2c#3: vertical component left out (--vertical keeps it)",)
    assert [r.name for r in read_suite(f"{path}#2")] == ["three.V2c#2"]
    with pytest.raises(ValueError, match=re.escape("three.V2c#2: the same record is given "
                                                   "twice")):
        read_suite([path, f"{path}#2"])
    with pytest.raises(ValueError, match=re.escape("channel must be 1..3 (the file's "
                                                   "acceleration channels), got 4")):
        read_record(f"{path}#4")
    with pytest.raises(ValueError, match=re.escape("holds one acceleration channel, not "
                                                   "channel 2: give the file without '#N'")):
        read_record(f"{tmp_path / 'one0.V2c'}#2")
    (tmp_path / "r.txt").write_text("0 0.1\n0.01 0.2\n0.02 0.3\n")
    with pytest.raises(ValueError, match="r.txt is not a COSMOS file"):
        read_record(f"{tmp_path / 'r.txt'}#1")
    with pytest.raises(ValueError, match="no such file"):
        read_record(f"{tmp_path / 'missing.V2c'}#1")


def test_cosmos_truncated_and_legacy_files(tmp_path):
    path = tmp_path / "r.V2c"
    text = _cosmos_text(150.0 * np.sin(np.linspace(0.0, 20.0, 1000)))
    path.write_text("\n".join(text.splitlines()[:100]) + "\n")
    with pytest.raises(ValueError, match="the file ends inside its values"):
        read_record(path)
    # the channel's velocity after its acceleration (one file, two series) is no second
    # channel: the acceleration is read
    both = tmp_path / "both.V2c"
    both.write_text(text + text.replace("Corrected acceleration", "Corrected velocity")
                    .replace("acceleration pts", "velocity pts").replace("cm/sec2", "cm/sec"))
    assert read_record(both).t.size == 1000
    legacy = tmp_path / "CHAN001.V2"  # CSMIP's older format: refused by name, with the way out
    legacy.write_text("CORRECTED ACCELEROGRAM\n1 2\n")
    with pytest.raises(ValueError, match="older CSMIP .V1/.V2 format is not read"):
        read_record(legacy)


def test_a_folder_of_every_format_is_one_suite(tmp_path):
    """The same 5 s of El Centro as a PEER .AT2, an ESM .ASC, a K-NET .EW, a COSMOS .V2c and
    a two-column text file: one suite of five records whose motions agree within the
    coarsest file's rounding (the K-NET count, 2.4e-6 m/s², and its mean removed; COSMOS's
    3 decimals in cm/s², 5e-6 m/s²)."""
    from rockarch.motion.signals import GroundMotion
    from rockarch.motion.suite import read_suite, write_at2

    ref = el_centro()
    cut = ref.a[:500] - ref.a[:500].mean()  # K-NET removes the mean: give it none to remove
    dt = ref.t[1] - ref.t[0]
    write_at2(tmp_path / "a.AT2", GroundMotion(ref.t[:500], cut))
    (tmp_path / "b.ASC").write_text(_esm_text(cut * 100.0, dt=dt))
    (tmp_path / "c.EW").write_text(_knet_text(cut * 100.0, duration=5))
    (tmp_path / "d.V2c").write_text(_cosmos_text(cut * 100.0, approx=5))
    np.savetxt(tmp_path / "e.txt", np.column_stack([ref.t[:500], cut]))
    suite = read_suite(tmp_path, units="m/s2")
    assert [r.motion.meta["format"] for r in suite.records] == [
        "AT2", "ESM", "K-NET", "COSMOS", "two-column"]
    for r in suite.records:
        assert np.abs(r.motion.a - cut).max() <= 6e-6, r.name
        np.testing.assert_allclose(r.motion.t, ref.t[:500], rtol=1e-9, atol=1e-12)


# --------------------------------------------------------------- single-column text, given dt


def _rows(values, per_line: int, head: str = "") -> str:
    """``values`` written ``per_line`` a line in fixed-width fields of 17 significant
    digits (the last line shorter where they do not fill it), after ``head``."""
    return head + "".join(" ".join(f"{v:25.16E}" for v in values[i:i + per_line]) + "\n"
                          for i in range(0, len(values), per_line))


@pytest.mark.parametrize("per_line", [1, 8])
def test_single_column_round_trip(tmp_path, per_line):
    """El Centro's accelerations in g, one a line or 8 a line (5372 = 671·8 + 4: a short last
    row, as fixed-width legacy files end), read back with dt and units="g": the same times,
    bit for bit (k·dt, as the .AT2 reader builds them), and the same samples within 1e-12.
    The file holds a/g to 17 significant digits, which parse back to the same double; what
    is left is a/g·g (two roundings, ~2e-16 relative) and make test-perturbed's last bit
    (1e-16): 1e-12 bounds that with room and still fails on any real loss (a 7-digit file
    is 5e-8 off)."""
    ref = el_centro()
    path = tmp_path / "elcentro_g.txt"
    path.write_text(_rows(ref.a / G_STANDARD, per_line,
                          head="El Centro 1940, 180 deg\nunits: g, dt = 0.01 s\n"))
    got = read_record(path, dt=0.01, units="g")
    np.testing.assert_array_equal(got.t, ref.t)
    np.testing.assert_allclose(got.a, ref.a, rtol=1e-12, atol=0.0)
    assert got.meta == {"source": str(path), "dt": 0.01, "npts": 5372,
                        "format": "single-column", "units_in_file": "g"}
    # the same keys as a two-column file's meta, whose reader it stands beside
    two = tmp_path / "two.txt"
    np.savetxt(two, np.c_[ref.t[:10], ref.a[:10]])
    assert set(read_record(two, units="m/s2").meta) == set(got.meta)


def test_single_column_header_comments_separators_and_units(tmp_path):
    text = ("station X\n# a comment\n0.1, 0.2; 0.3\t-0.4   # after the values\n\n"
            "# between rows\n-0.5 0.6 0.7 0.8\n0.9\n")
    path = tmp_path / "rows.dat"
    path.write_text(text)
    got = read_record(path, dt=0.005, units="cm/s2")
    assert got.a == pytest.approx(0.01 * np.array([0.1, 0.2, 0.3, -0.4, -0.5, 0.6, 0.7, 0.8,
                                                   0.9]), rel=1e-15)
    assert got.t[-1] == pytest.approx(8 * 0.005, rel=1e-15)
    # without units: m/s², with the two-column reader's warning (a peak of 0.9 is a
    # plausible PGA in g too)
    with pytest.warns(UnitsWarning, match="plausible PGA in g"):
        assert read_record(path, dt=0.005).pga == pytest.approx(0.9)


@pytest.mark.parametrize(
    "text, kwargs, err, msg",
    [
        # no dt: the two-column reader's error says how to give it
        ("0.01\n-0.02\n0.03\n", {}, ValueError,
         r"line 1 has 1 column.*no time step: give it \(--dt .*dt= in Python\)"),
        (_rows(np.arange(1, 17) / 100, 8), {}, ValueError,
         r"line 1 has 8 column.*give their time step \(--dt, dt= in Python\)"),
        # dt itself
        ("0.01\n-0.02\n", {"dt": 0}, ValueError, r"finite time step > 0 in seconds, got 0$"),
        ("0.01\n-0.02\n", {"dt": -0.01}, ValueError, r"> 0 in seconds, got -0.01$"),
        ("0.01\n-0.02\n", {"dt": float("nan")}, ValueError, r"> 0 in seconds, got nan$"),
        ("0.01\n-0.02\n", {"dt": float("inf")}, ValueError, r"> 0 in seconds, got inf$"),
        ("0.01\n-0.02\n", {"dt": 10}, ValueError, r"dt is in seconds \(10 ms is dt = 0.01"),
        ("0.01\n-0.02\n", {"dt": 1e-7}, ValueError, r"dt is in seconds"),
        ("0.01\n-0.02\n", {"dt": "0.01"}, TypeError, r"dt must be a number, got str"),
        # files that give their own step
        ("0 0.1\n0.01 0.2\n0.02 -0.3\n0.03 0.1\n", {"dt": 0.01}, ValueError,
         r"two numbers, the first increasing \(0, 0.01, 0.02, \.\.\.\): a two-column file "
         r"\(time, acceleration\), which has its own time column: read it without dt"),
        ("0 0.1\n0.01 0.2\n0.03 -0.3\n", {"dt": 0.01}, ValueError,  # non-uniform too
         r"a two-column file"),
        ("0 0.1 5\n0.01 0.2 6\n0.02 -0.3 7\n", {"dt": 0.01}, ValueError,
         r"a time column\? .*\(3 a line here\)"),
        # the samples
        ("0.01\n-0.02\n0.03\nabc\n0.04\n", {"dt": 0.01}, ValueError,
         r"line 4 is not numbers: 'abc'"),
        ("acc [g]\n0.01 0.02\n0.03 end\n", {"dt": 0.01}, ValueError,
         r"line 3 is not numbers: '0.03 end'"),
        ("0.01\n-0.02\nnan\n", {"dt": 0.01}, ValueError,
         r"line 3 holds a value that is not a finite number \(sample 2\)"),
        ("5372 0.01\n0.1\n0.2\n0.3\n", {"dt": 0.01}, ValueError,
         r"line 2 holds 1 value.*first sample line \(line 1\) 2.*NPTS, DT"),
        ("0.1 0.2 0.3\n0.4 0.5\n0.6 0.7 0.8\n", {"dt": 0.01}, ValueError,
         r"line 2 holds 2 value.*\(the last may hold fewer\)"),
        ("0,01\n-0,02\n0,03\n", {"dt": 0.01}, ValueError, r"decimal commas\?"),
        ("time\nacc\n", {"dt": 0.01}, ValueError, r"no samples"),
        ("0.5\n", {"dt": 0.01}, ValueError, r"at least 2 samples, found 1"),
        ("0 0\n0 0\n", {"dt": 0.01}, ValueError, r"every sample is zero"),
        ("1e6\n-2e6\n", {"dt": 0.01, "units": "g"}, ValueError, r"not a plausible ground"),
    ],
    ids=["no-dt", "no-dt-rows", "dt=0", "dt<0", "dt=nan", "dt=inf", "dt=10", "dt=1e-7",
         "dt-str", "two-column", "two-column-non-uniform", "time-column", "text-line",
         "text-in-a-row", "nan", "npts-dt-header", "ragged", "decimal-comma", "header-only",
         "one", "zeros", "huge"],
)
def test_single_column_errors(tmp_path, text, kwargs, err, msg):
    with pytest.raises(err, match=msg):
        read_record(_write(tmp_path, "acc.txt", text), **kwargs)


def test_single_column_coarse_dt_warns(tmp_path):
    """A dt above 0.1 s (records are sampled every 0.001-0.05 s) is read, with a warning
    that dt is in seconds."""
    from rockarch.motion.records import TimeStepWarning

    with pytest.warns(TimeStepWarning, match="dt = 0.5 s .*dt is in seconds"):
        m = read_record(_write(tmp_path, "acc.txt", "0.01\n-0.02\n"), dt=0.5, units="g")
    assert m.t[-1] == 0.5


def test_dt_is_refused_for_a_file_that_gives_its_own_step(tmp_path):
    """Every format whose header gives the time step refuses dt, recognised by its
    contents as without dt (a PEER file under another name too)."""
    cm = el_centro().a[:200] * 100.0
    files = {"x.AT2": NEW, "peer.txt": NEW, "e.ASC": _esm_text(cm),
             "k.EW": _knet_text(cm, duration=2), "c.V2c": _cosmos_text(cm, approx=2)}
    for name, text in files.items():
        path = _write(tmp_path, name, text)
        read_record(path)  # a valid file
        with pytest.raises(ValueError, match=r"gives its own time step \(in its header\); "
                                             r"dt \(--dt\) .* does not apply"):
            read_record(path, dt=0.01)
    with pytest.raises(ValueError, match="COSMOS file gives its own time step"):
        read_record(f"{_write(tmp_path, 'c2.V2c', _cosmos_text(cm, approx=2, channels=2))}#2",
                    dt=0.01)


def test_single_column_samples_are_counted_before_they_are_parsed(tmp_path, monkeypatch):
    monkeypatch.setenv("ROCKARCH_MAX_SAMPLES", "300")
    path = _write(tmp_path, "long.txt", _rows(np.sin(np.arange(304.0)), 8))
    with pytest.raises(ValueError, match=r"needs 304 samples.*ROCKARCH_MAX_SAMPLES"):
        read_record(path, dt=0.01)
    assert read_record(_write(tmp_path, "short.txt", _rows(np.sin(np.arange(296.0)), 8)),
                       dt=0.01, units="g").t.size == 296
