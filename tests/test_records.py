"""Record readers: PEER NGA .AT2 (new and old headers), two-column text, bad files."""

import numpy as np
import pytest

from rockarch.motion.records import (
    G_STANDARD,
    UnitsWarning,
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
    ],
    ids=["third-column", "nan", "non-uniform", "backwards", "header-only", "one", "short",
         "decimal-comma"],
)
def test_two_column_errors_name_the_line(tmp_path, text, msg):
    with pytest.raises(ValueError, match=msg):
        read_two_column(_write(tmp_path, "r.txt", text))


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
    with pytest.warns(UnitsWarning, match="not plausible: wrong units"):
        read_record(f)
    assert read_record(f, units="mm/s2").pga == pytest.approx(300.0)
