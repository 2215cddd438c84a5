"""`rockarch reproduce --quick` writes every table and figure with a side-by-side index."""

import pytest
from typer.testing import CliRunner

from rockarch.cli import app


@pytest.mark.slow  # ~60 s alone, 170 s on a loaded machine: every table and figure
def test_reproduce_quick(tmp_path):
    out = tmp_path / "paper"
    res = CliRunner().invoke(app, ["reproduce", "--out", str(out), "--quick"])
    assert res.exit_code == 0, res.output
    index = (out / "index.html").read_text()
    for needle in ("Table 1", "Table 2", "Fig. 15", "Fig. 19", "Sect. 9", "0.219 / 0.21"):
        assert needle in index
    for f in ("fig15.png", "fig19.png", "design_report.html", "site.nc"):
        assert (out / f).stat().st_size > 0


def test_reproduce_refuses_a_file(tmp_path):
    f = tmp_path / "x"
    f.write_text("")
    res = CliRunner().invoke(app, ["reproduce", "--out", str(f)])
    assert res.exit_code == 2 and "not a folder" in res.stderr
