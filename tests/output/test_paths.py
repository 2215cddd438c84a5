"""Output paths: checked before any computation, written together or not at all, unique
temporaries (rockarch.core.paths and the commands that use it)."""

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.core import paths
from rockarch.core.paths import atomic_write, check_output, check_outputs, staged

runner = CliRunner()
# a small sweep (coarse bisection, short free motion): the outputs are under test here
OAS = ["oas", "--alpha", "0.1", "--signal", "sine", "--period", "1", "--p", "2,4",
       "--ratio-steps", "5", "--tol", "0.2", "--t-free", "1", "--no-store"]


def _leftovers(folder):
    return sorted(p.name for p in folder.iterdir())


# --- the check, one failure mode each ---------------------------------------------------

def test_missing_directory_names_the_missing_folder(tmp_path):
    with pytest.raises(ValueError, match=r"--out .*: directory does not exist: .*/no$"):
        check_output(tmp_path / "no" / "deeper" / "x.nc", "--out", "netcdf")


def test_file_used_as_directory_is_said_so(tmp_path):
    (tmp_path / "f.txt").write_text("x")
    with pytest.raises(ValueError, match=r"f\.txt is a file, not a directory"):
        check_output(tmp_path / "f.txt" / "x.png", "--plot", "png")


def test_directory_where_a_file_should_be(tmp_path):
    (tmp_path / "d.nc").mkdir()
    with pytest.raises(ValueError, match="is a directory, give a file name"):
        check_output(tmp_path / "d.nc", "--out", "netcdf")


NO_PROC = pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux /proc")


@NO_PROC
def test_folder_not_writable():
    # /proc refuses new files even to root (a chmod-ed folder would not stop root)
    with pytest.raises(ValueError, match="cannot write in directory /proc"):
        check_output("/proc/x.nc", "--out", "netcdf")


@pytest.mark.parametrize("name, fmt, expected", [
    ("x.txt", "netcdf", ".nc"), ("d.png", "html", ".html or .htm"), ("a.gif", "png", ".png"),
    ("noext", "gif", ".gif"),
])
def test_extension_mismatch_says_which_is_expected(tmp_path, name, fmt, expected):
    with pytest.raises(ValueError, match=f"must end in {expected}"):
        check_output(tmp_path / name, "--out", fmt)


def test_good_paths_pass_and_leave_nothing(tmp_path):
    check_outputs((tmp_path / "a.nc", "--out", "netcdf"), (tmp_path / "A.PNG", "--plot", "png"),
                  (None, "--report", "html"), (tmp_path / "new" / "dir", "--store", "dir"))
    assert _leftovers(tmp_path) == []  # the writability probe is removed


def test_two_outputs_on_one_file_are_refused(tmp_path):
    with pytest.raises(ValueError, match="the same file as --out"):
        check_outputs((tmp_path / "a.png", "--out"), (tmp_path / "a.png", "--plot"))


def test_directory_output_that_is_a_file(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(ValueError, match="--out .*: is a file, not a directory"):
        check_outputs((tmp_path / "f", "--out", "dir"))
    with pytest.raises(ValueError, match=r"--store .*: .*/f is a file, not a directory"):
        check_outputs((tmp_path / "f" / "sub", "--store", "dir"))


# --- staged writing ----------------------------------------------------------------------

def test_staged_failure_leaves_nothing_and_hides_temporaries(tmp_path):
    a, b = tmp_path / "a.nc", tmp_path / "b.png"
    with pytest.raises(ValueError) as err:
        with staged(a, b) as (ta, tb):
            ta.write_text("whole")
            raise OSError(f"disk full while writing {tb}")
    assert _leftovers(tmp_path) == []
    msg = str(err.value)
    assert "b.png: cannot write" in msg and ".tmp" not in msg


def test_nested_stages_report_the_final_target_once(tmp_path):
    def fails(tmp):
        raise OSError(28, "No space left on device", str(tmp))

    with pytest.raises(ValueError) as err:
        with staged(tmp_path / "a.nc", tmp_path / "b.png") as (_, tb):
            atomic_write(tb, fails)  # e.g. save_figure on the staged temporary
    assert str(err.value) == f"{tmp_path / 'b.png'}: cannot write: No space left on device"
    assert _leftovers(tmp_path) == []


def test_staged_success_renames_all_and_keeps_none_slots(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    with staged(a, None, b) as (ta, none, tb):
        assert none is None and ta.suffix == ".txt" and ta.parent == tmp_path
        ta.write_text("A")
        tb.write_text("B")
        assert not a.exists()  # nothing is visible before the block ends
    assert (a.read_text(), b.read_text()) == ("A", "B")
    assert _leftovers(tmp_path) == ["a.txt", "b.txt"]


def test_temporary_names_are_unique(tmp_path):
    names = {paths.temporary_name(tmp_path / "x.nc") for _ in range(200)}
    assert len(names) == 200


def test_concurrent_writers_of_one_file_both_succeed(tmp_path):
    """Two processes write the same file 30 times each at once: every write succeeds and
    the file is always one writer's whole content (1 MB of one letter)."""
    target = tmp_path / "same.nc"
    script = textwrap.dedent(f"""
        import importlib.util, sys
        spec = importlib.util.spec_from_file_location("p", {paths.__file__!r})
        mod = sys.modules["p"] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)  # this module alone: no numba/xarray import
        atomic_write = mod.atomic_write
        letter = sys.argv[1].encode()
        for _ in range(30):
            atomic_write({str(target)!r}, lambda tmp: tmp.write_bytes(letter * 1_000_000))
    """)
    procs = [subprocess.Popen([sys.executable, "-c", script, c], stderr=subprocess.PIPE)
             for c in "ab"]
    for p in procs:
        _, err = p.communicate(timeout=60)
        assert p.returncode == 0, err.decode()
    data = target.read_bytes()
    assert len(data) == 1_000_000 and data in (b"a" * 1_000_000, b"b" * 1_000_000)
    assert _leftovers(tmp_path) == ["same.nc"]


def test_atomic_write_error_names_the_target(tmp_path):
    def fails(tmp):
        raise RuntimeError(f"HDF error opening {tmp}")

    with pytest.raises(ValueError, match=r"x\.nc: cannot write: HDF error opening .*x\.nc$"):
        atomic_write(tmp_path / "x.nc", fails)
    assert _leftovers(tmp_path) == []


# --- the commands ------------------------------------------------------------------------

def _one_line_error(res) -> str:
    assert res.exit_code == 2, res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    return lines[0]


@pytest.mark.parametrize("args, msg", [
    (["--out", "{d}/x.txt"], "must end in .nc"),
    (["--plot", "{d}/x.nc"], "must end in .png"),
    (["--out", "{d}/no/x.nc"], "directory does not exist"),
    pytest.param(["--out", "/proc/x.nc"], "cannot write in directory /proc", marks=NO_PROC),
    (["--plot", "{d}"], "is a directory"),
    (["--out", "{d}/f/x.nc"], "is a file, not a directory"),
])
def test_oas_refuses_bad_outputs_before_computing(tmp_path, args, msg):
    (tmp_path / "f").write_text("x")
    res = runner.invoke(app, [*OAS, *[a.format(d=tmp_path) for a in args]])
    assert msg in _one_line_error(res)
    assert _leftovers(tmp_path) == ["f"]


def test_design_report_must_be_html(tmp_path):
    res = runner.invoke(app, ["design", "--shape", "circular", "--span", "10", "--rise",
                              "2.89", "--thickness", "0.35", "--site", str(tmp_path / "s.nc"),
                              "--report", str(tmp_path / "d.png")])
    assert "must end in .html or .htm" in _one_line_error(res)


def test_animate_out_must_be_gif(tmp_path):
    res = runner.invoke(app, ["animate", "--shape", "catenary", "--span", "10", "--rise", "3",
                              "--thickness", "0.25", "--blocks", "8", "--signal", "sine",
                              "--period", "1", "--ratio", "1.5", "--out",
                              str(tmp_path / "m.mp4")])
    assert "must end in .gif" in _one_line_error(res)


def test_oas_plot_failure_leaves_no_netcdf(tmp_path, monkeypatch):
    """--out and --plot are written together: when the figure cannot be written, the
    NetCDF file is not left behind either."""
    from rockarch.output import figures

    def broken(fig, path, **kw):
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr(figures, "save_figure", broken)  # the command imports it when it plots
    res = runner.invoke(app, [*OAS, "--out", str(tmp_path / "a.nc"),
                              "--plot", str(tmp_path / "a.png")])
    line = _one_line_error(res)
    assert "No space left on device" in line and ".tmp" not in line
    assert _leftovers(tmp_path) == []


def test_oas_writes_both_outputs(tmp_path):
    res = runner.invoke(app, [*OAS, "--out", str(tmp_path / "a.nc"),
                              "--plot", str(tmp_path / "a.png")])
    assert res.exit_code == 0, res.output
    assert _leftovers(tmp_path) == ["a.nc", "a.png"]
    assert (tmp_path / "a.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.slow
def test_two_oas_processes_write_the_same_outputs(tmp_path):
    """Two `rockarch oas` processes with the same --out/--plot at once both succeed."""
    args = [sys.executable, "-c", "from rockarch.cli import app; app()", *OAS,
            "--out", str(tmp_path / "s.nc"), "--plot", str(tmp_path / "s.png")]
    procs = [subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
             for _ in range(2)]
    for p in procs:
        _, err = p.communicate(timeout=300)
        assert p.returncode == 0, err.decode()
    import xarray as xr

    assert xr.load_dataset(tmp_path / "s.nc")["boundary"].shape == (2,)
    assert _leftovers(tmp_path) == ["s.nc", "s.png"]
