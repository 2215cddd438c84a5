"""Record suites: folders of .AT2 / two-column / single-column records with and without the
NGA-West2 _SearchResults.csv; ``rockarch records info``."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.core.constants import G_STANDARD
from rockarch.motion import suite
from rockarch.motion.records import bundled_record_path
from rockarch.spectra import site

FIXTURE = Path(__file__).parent / "data" / "nga_search_results.csv"
SHARED = Path("/work/shared/records")
runner = CliRunner()


@pytest.fixture
def folder(tmp_path):
    """The two bundled El Centro components in a folder, no csv."""
    for comp in (180, 270):
        shutil.copy(bundled_record_path(comp), tmp_path)
    return tmp_path


@pytest.fixture
def folder_csv(folder):
    shutil.copy(FIXTURE, folder / "_SearchResults.csv")
    return folder


def test_folder_without_csv_takes_metadata_from_the_at2_header(folder):
    s = suite.read_suite(folder)
    assert s.names == ["RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"]
    assert s.csv is None
    r = s[0]
    assert (r.event, r.year, r.station, r.component) == (
        "Imperial Valley-02", 1940, "El Centro Array #9", "180")
    assert r.rsn == 6 and r.magnitude is None and r.scale_factor is None
    assert r.dt == pytest.approx(0.01) and r.duration == pytest.approx(53.71)


def test_csv_metadata_is_matched_by_rsn_and_scale_applied_on_request(folder_csv):
    s = suite.read_suite(folder_csv)
    assert Path(s.csv).name == "_SearchResults.csv"
    r = s[1]
    assert (r.rsn, r.magnitude, r.rrup, r.vs30, r.scale_factor, r.mechanism) == (
        6, 6.95, 6.09, 213.44, 1.5, "strike slip")
    assert r.component == "270" and not r.scaled
    scaled = suite.read_suite(folder_csv, apply_scale=True)
    for a, b in zip(s, scaled, strict=True):
        assert b.scaled
        # the CSV's scale factor applied: one multiplication, to its rounding
        np.testing.assert_allclose(b.motion.a, 1.5 * a.motion.a, rtol=4e-16, atol=0)


def test_csv_matches_exact_peer_file_names_to_their_component(tmp_path):
    shutil.copy(bundled_record_path(270), tmp_path / "RSN6_IMPVALL.I_I-ELC270.AT2")
    shutil.copy(FIXTURE, tmp_path / "_SearchResults.csv")
    r = suite.read_suite(tmp_path)[0]
    assert r.station == "El Centro Array #9" and r.component == "270"
    assert suite._match("RSN6_IMPVALL.I_I-ELC270.AT2", suite.read_search_results(FIXTURE)
                        )[1] == "H2"


def test_record_missing_from_csv_is_a_note_or_an_error_with_apply_scale(folder_csv):
    shutil.copy(bundled_record_path(180), folder_csv / "RSN99_OTHER.AT2")
    s = suite.read_suite(folder_csv)
    assert any("RSN99_OTHER.AT2" in n for n in s.notes)
    with pytest.raises(ValueError, match="RSN99_OTHER.AT2: not listed"):
        suite.read_suite(folder_csv, apply_scale=True)


def test_apply_scale_without_csv_is_an_error(folder):
    with pytest.raises(ValueError, match="needs an NGA-West2 _SearchResults.csv"):
        suite.read_suite(folder, apply_scale=True)


@pytest.mark.parametrize("text, match", [
    ("just,some\n1,2\n", "no header row with a 'Record Sequence Number'"),
    (" Result ID, Record Sequence Number, Scale Factor\n\n", "has no record rows"),
    (" Result ID, Record Sequence Number, Scale Factor, Magnitude\n 1, 6, 1.0, big\n",
     "line 2: column 'magnitude' should be a number"),
    (" Result ID, Record Sequence Number, Scale Factor\n 1, 6, -2\n",
     "scale factor must be > 0"),
    (" Result ID, Record Sequence Number, Year\n 1, 6, inf\n",
     "line 2: column 'year' should be a number"),
    (" Result ID, Record Sequence Number, Scale Factor, Magnitude, Vs30\n 1, 6\n",
     "truncated row"),
])
def test_malformed_csv_gives_one_clear_line(folder, text, match):
    (folder / "_SearchResults.csv").write_text(text)
    with pytest.raises(ValueError, match=match):
        suite.read_suite(folder)
    res = runner.invoke(app, ["records", "info", str(folder)])
    assert res.exit_code == 2
    assert res.stderr.startswith("error: ") and res.stderr.count("\n") == 1
    assert "Traceback" not in res.output


def test_two_column_records_in_a_folder_and_a_file_list(tmp_path):
    t = np.linspace(0.0, 5.0, 201)  # dt = 0.025 s: the peaks of both sines are samples
    np.savetxt(tmp_path / "a.txt", np.c_[t, 0.1 * np.sin(2 * np.pi * t)])
    np.savetxt(tmp_path / "b.dat", np.c_[t, 0.2 * np.sin(4 * np.pi * t)])
    (tmp_path / "README.md").write_text("not a record")
    s = suite.read_suite(tmp_path, units="g")
    assert s.names == ["a.txt", "b.dat"]
    assert s[1].motion.pga == pytest.approx(0.2 * G_STANDARD, rel=1e-3)
    assert suite.read_suite([tmp_path / "b.dat"], units="g").names == ["b.dat"]
    assert not s.notes
    # a PGA of 0.1 read as cm/s² is 1.02e-4 g (plausible); 0.02 cm/s² is 2e-5 g: a note
    np.savetxt(tmp_path / "c.txt", np.c_[t, 0.02 * np.sin(2 * np.pi * t)])
    tiny = suite.read_suite([tmp_path / "a.txt", tmp_path / "c.txt"], units="cm/s2")
    assert [n.split(":")[0] for n in tiny.notes] == ["c.txt"]
    assert "not plausible" in tiny.notes[0]
    assert "PGA = 2.04e-05 g (g = 9.80665 m/s²) is" in tiny.notes[0]  # the records' g
    # site-oas reads folders through the same expansion
    assert [p.name for p in site.record_paths([tmp_path])] == ["a.txt", "b.dat", "c.txt"]


def test_single_column_records_in_a_folder_share_one_dt(tmp_path):
    """A folder of files of accelerations alone (one a line, or 5 a line) read with dt: every
    file at that step; a file that gives its own step (.AT2, two-column) refuses it, the
    file named; a bad dt is refused before any file is read, a coarse one warns once."""
    from rockarch.motion.records import TimeStepWarning

    t = np.arange(400) * 0.02
    a = 0.1 * np.sin(2 * np.pi * t) * np.exp(-0.1 * t)
    np.savetxt(tmp_path / "a.txt", a)
    np.savetxt(tmp_path / "b.acc", 2 * a[:395].reshape(-1, 5))
    s = suite.read_suite(tmp_path, units="g", dt=0.02)
    assert s.names == ["a.txt", "b.acc"] and not s.notes
    assert [r.motion.meta["format"] for r in s] == ["single-column"] * 2
    assert [r.dt for r in s] == pytest.approx([0.02, 0.02], rel=1e-12)
    assert s[1].motion.t.size == 395
    assert s[1].motion.pga == pytest.approx(2 * G_STANDARD * np.abs(a[:395]).max(), rel=1e-12)
    # without units: one note for both (peaks plausible in g), as for two-column files
    notes = suite.read_suite(tmp_path, dt=0.02).notes
    assert len(notes) == 1 and notes[0].startswith("2 single-column record(s) read as m/s²")
    with pytest.warns(TimeStepWarning) as caught:
        suite.read_suite(tmp_path, units="g", dt=0.2)
    assert len(caught) == 1
    with pytest.raises(ValueError, match=r"finite time step > 0 in seconds, got nan"):
        suite.read_suite(tmp_path / "nope", dt=float("nan"))
    shutil.copy(bundled_record_path(180), tmp_path)
    with pytest.raises(ValueError, match=r"ELC180-hor1.AT2: a PEER .AT2 file gives its own "
                                         r"time step"):
        suite.read_suite(tmp_path, units="g", dt=0.02)
    np.savetxt(tmp_path / "c.txt", np.c_[t, a])
    with pytest.raises(ValueError, match=r"c.txt: every line holds two numbers.*two-column"):
        suite.read_suite([tmp_path / "a.txt", tmp_path / "c.txt"], units="g", dt=0.02)


def test_bad_sources_give_one_clear_error(tmp_path):
    with pytest.raises(ValueError, match="no such file or folder") as err:
        suite.read_suite(tmp_path / "nope")
    # and where the bundled records are (older instructions gave src/rockarch/data/)
    hint = str(err.value).split("are in ")[1].rstrip(")")
    assert (Path(hint) / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2").is_file()
    with pytest.raises(ValueError, match="folder holds no record"):
        suite.read_suite(tmp_path)


def test_records_info_json_lists_metadata_and_intensity_measures(folder_csv):
    res = runner.invoke(app, ["records", "info", str(folder_csv), "--periods", "0.5,1",
                              "--apply-scale", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["periods"] == [0.5, 1.0] and out["apply_scale"] is True
    names = [r["name"] for r in out["records"]]
    assert names == ["RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"]
    r = out["records"][0]
    for key in ("event", "station", "component", "dt", "duration", "pga", "pgv", "pgd",
                "arias", "d5_95", "tm", "sa", "magnitude", "rrup", "vs30", "scale_factor",
                "pulse_indicator", "tp", "pulse_like", "pulse_class"):
        assert key in r
    assert r["pga"] == pytest.approx(1.5 * 0.281 * G_STANDARD, rel=2e-3)  # PEER 0.281 g × 1.5
    assert len(r["sa"]) == 2


def test_records_info_text(folder):
    res = runner.invoke(app, ["records", "info", str(folder)])
    assert res.exit_code == 0, res.output
    assert "El Centro Array #9" in res.stdout and "0.281" in res.stdout
    assert "Vs30" not in res.stdout  # no csv: no metadata columns
    assert "units: PGA g (g = 9.80665 m/s²), PGV m/s" in res.stdout  # which g: the records'
    shutil.copy(FIXTURE, folder / "_SearchResults.csv")
    res = runner.invoke(app, ["records", "info", str(folder), "--apply-scale"])
    assert res.exit_code == 0, res.output
    assert "Vs30" in res.stdout and " 0.421 " in res.stdout  # 0.281 g × 1.5


def test_records_info_text_shows_a_weak_record(tmp_path):
    """A weak record (PGA 3e-4 g, as many ESM and K-NET files) keeps its digits in the text
    table: e-notation where three decimals would print 0.000."""
    ref = suite.read_suite(bundled_record_path(180)).records[0].motion
    weak = tmp_path / "weak.txt"
    np.savetxt(weak, np.column_stack([ref.t, ref.a * (3e-4 * G_STANDARD / ref.pga)]))
    res = runner.invoke(app, ["records", "info", str(weak), "--units", "m/s2"])
    assert res.exit_code == 0, res.output
    row = next(line for line in res.stdout.splitlines() if line.startswith("weak.txt"))
    assert " 3.0e-04 " in row and "0.000" not in row


def test_records_info_pulse_methods(folder):
    # El Centro 180: Baker (2007) indicator 0.09 (non-pulse) and the late flag; the class
    # and the flags are separate columns and keys
    res = runner.invoke(app, ["records", "info", str(folder), "--json"])
    r = json.loads(res.stdout)["records"][0]
    assert r["pulse_method"] == "2007" and r["pulse_class"] == "non-pulse"
    assert r["pulse_late"] is True and r["pulse_low_pgv"] is False and not r["pulse_like"]
    res = runner.invoke(app, ["records", "info", str(folder)])
    line = next(x for x in res.stdout.splitlines() if "ELC180" in x)
    assert " non-pulse " in line and " late " in line
    for flag in ("--method", "--pulse-method"):
        res = runner.invoke(app, ["records", "info", str(folder), flag, "2014", "--json"])
        assert res.exit_code == 0, res.output
        out = json.loads(res.stdout)
        assert out["pulse_method"] == "2014"
        assert {r["pulse_class"] for r in out["records"]} <= {"pulse", "non-pulse"}
        assert all(r["pulse_low_pgv"] is False for r in out["records"])
    res = runner.invoke(app, ["records", "info", str(folder), "--method", "2010"])
    assert res.exit_code == 2 and "error: pulse method must be one of 2007, 2014" in res.stderr


@pytest.mark.skipif(not SHARED.is_dir(), reason="shared record folder absent")
def test_shared_records_match_their_readme_pgas():
    s = suite.read_suite(SHARED)
    pga_g = {r.name: r.motion.pga / G_STANDARD for r in s}
    table = {"RSN6_IMPVALL.I_I-ELC180-hor1.AT2": 0.281, "RSN6_IMPVALL.I_I-ELC270-hor2.AT2": 0.211,
             "RSN1690_NORTH151_SYL090-hor1.AT2": 0.086,
             "RSN1690_NORTH151_SYL360-hor2.AT2": 0.062}
    for name, value in table.items():
        assert pga_g[name] == pytest.approx(value, abs=5e-4)  # README rounds to 1e-3 g


def test_vertical_components_are_left_out_unless_asked(folder_csv):
    # a PEER vertical file: listed in the csv's "Vertical Acc. Filename" column
    shutil.copy(bundled_record_path(270), folder_csv / "RSN6_IMPVALL.I_I-ELCUP.AT2")
    s = suite.read_suite(folder_csv)
    assert "RSN6_IMPVALL.I_I-ELCUP.AT2" not in s.names and len(s) == 2
    assert any("vertical component left out" in n for n in s.notes)
    assert len(suite.read_suite(folder_csv, vertical=True)) == 3
    only = suite.read_suite([folder_csv / "RSN6_IMPVALL.I_I-ELCUP.AT2"], vertical=True)
    assert only[0].component == "270"  # the header's component (this is a copy of 270)
    motions, hashes = site.load_records([folder_csv])  # site-oas reads the same records
    assert len(motions) == 2 and len(set(hashes)) == 2
    with pytest.raises(ValueError, match="every record is a vertical component"):
        suite.read_suite([folder_csv / "RSN6_IMPVALL.I_I-ELCUP.AT2"], search_results=FIXTURE)


def test_vertical_component_from_the_at2_header(tmp_path):
    text = bundled_record_path(180).read_text(encoding="latin-1").splitlines()
    text[1] = "Imperial Valley-02, 5/19/1940, El Centro Array #9, UP"
    (tmp_path / "v.AT2").write_text("\n".join(text) + "\n", encoding="latin-1")
    shutil.copy(bundled_record_path(180), tmp_path)
    assert suite.read_suite(tmp_path).names == ["RSN6_IMPVALL.I_I-ELC180-hor1.AT2"]


def test_records_info_of_a_very_short_record(tmp_path):
    # 0.1 s: no Fourier amplitude in the Tm band and shorter than any pulse period
    t = np.arange(0.0, 0.1001, 0.01)
    np.savetxt(tmp_path / "short.txt", np.c_[t, 0.5 * np.sin(20 * np.pi * t)])
    res = runner.invoke(app, ["records", "info", str(tmp_path), "--units", "g", "--json"])
    assert res.exit_code == 0, res.output
    r = json.loads(res.stdout)["records"][0]
    assert r["tp"] is None and r["pulse_class"] == "-" and r["pga"] > 0
    res = runner.invoke(app, ["records", "info", str(tmp_path), "--units", "g"])
    assert res.exit_code == 0 and "short.txt" in res.stdout


def test_records_info_plot(folder, tmp_path):
    out = tmp_path / "spectra.png"
    one = str(folder / "RSN6_IMPVALL.I_I-ELC270-hor2.AT2")
    res = runner.invoke(app, ["records", "info", one, "--periods", "1", "--plot", str(out),
                              "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["plot"] == str(out)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    res = runner.invoke(app, ["records", "info", one, "--plot", str(tmp_path / "no" / "x.png")])
    assert res.exit_code == 2 and "directory does not exist" in res.stderr


def test_functions_over_records_take_a_suite_and_refuse_files_by_name():
    # site_oas, ida, design_system ... take what ra.read_suite returns (before: site_oas and
    # ida failed 11 frames deep with "'SuiteRecord' object has no attribute 'normalized'"),
    # a list of motions or one motion; a path is a TypeError that says to read it first
    from rockarch import systems
    from rockarch.design import design_system
    from rockarch.risk import fragility as fr

    path = str(bundled_record_path(180))
    s = suite.read_suite([path])
    grid = {"p": [2.0], "ratio": np.linspace(1.0, 3.0, 3), "progress": False}
    by_suite = site.site_oas(s, **grid)
    for same in (s.motions, s.motions[0]):
        np.testing.assert_array_equal(site.site_oas(same, **grid)["boundary"],
                                      by_suite["boundary"])
    block = systems.BlockSystem(alpha=0.2)
    res = fr.ida(block, s, 2.0, ratio=[1.0, 2.0], search_step=0)
    assert res.records == tuple(s.names)  # a suite's names: its file names
    assert design_system(block, records=s, p=2.0, ratio=[1.0, 2.0], search_step=0,
                         n_bootstrap=0).ratio > 0
    for call in (lambda x: site.site_oas(x, **grid), lambda x: fr.ida(block, x, 2.0),
                 lambda x: design_system(block, records=x, p=2.0)):
        with pytest.raises(TypeError, match="got str: read the files first"):
            call([path])
        with pytest.raises(TypeError, match="got SuiteRecord: a Suite's records are in"):
            call(list(s))
