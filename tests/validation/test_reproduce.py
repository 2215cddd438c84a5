"""`rockarch reproduce --quick` writes every table and figure with a side-by-side index."""

import math

import pytest
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.core.constants import G
from rockarch.paper import background


@pytest.mark.slow  # ~60 s alone, 170 s on a loaded machine: every table and figure
def test_reproduce_quick(tmp_path):
    out = tmp_path / "paper"
    res = CliRunner().invoke(app, ["reproduce", "--out", str(out), "--quick"])
    assert res.exit_code == 0, res.output
    index = (out / "index.html").read_text()
    for needle in ("Fig. 2", "Fig. 3a", "Fig. 3b", "Table 1", "Table 2", "Fig. 15", "Fig. 19",
                   "Sect. 9", "0.219 / 0.21"):
        assert needle in index
    for f in ("fig2.png", "fig3a.png", "fig3b.png", "fig15.png", "fig19.png",
              "design_report.html", "site.nc"):
        assert (out / f).stat().st_size > 0


def test_reproduce_refuses_a_file(tmp_path):
    f = tmp_path / "x"
    f.write_text("")
    res = CliRunner().invoke(app, ["reproduce", "--out", str(f)])
    assert res.exit_code == 2 and "not a directory" in res.stderr


def test_fig3a_slender_block_is_the_safe_side_for_the_sine_pulse(tmp_path):
    """The claim of Fig. 3a, for the sine pulse: the slender block's lowest overturning ratio
    is at or below every less slender block's at every p of a coarse grid (bisection
    tolerance 2e-2, the comparison allows 0.2 %)."""
    rows = background.fig3a(tmp_path / "f.png", n_p=6, n_ratio=15, tol=2e-2,
                            signals=[background.SINE])
    assert [r["alpha"] for r in rows] == list(background.FIG3_ALPHAS[1:])
    assert all(r["slender_safe"] == 1.0 for r in rows)
    assert (tmp_path / "f.png").stat().st_size > 0


def test_fig3b_columns_on_the_monoliths_axes(tmp_path):
    """Equal-width columns share the monolith's ap,min = g·tan(alpha) and p (size R =
    H/(2 cos alpha), p² = 3g/(4R)), closed forms; under the sine pulse their joints stay
    shut, so the boundary equals the monolith's (MDOF engine) exactly."""
    rows = background.fig3b(tmp_path / "f.png", n_p=3, n_ratio=9, tol=5e-2, blocks=(1, 2),
                            signals=[background.SINE])
    (r,) = rows
    a, h = background.FIG3B_ALPHA, background.FIG3B_HEIGHT
    assert r["ap_min"] == pytest.approx(G * math.tan(a), rel=1e-12)
    assert r["p_ref"] == pytest.approx(math.sqrt(3 * G / (4 * h / (2 * math.cos(a)))),
                                       rel=1e-12)
    assert r["column_safer"] == 1.0 and r["column_weaker"] == 0.0


def test_background_rejects_unknown_excitations(tmp_path):
    with pytest.raises(ValueError, match="unknown excitation"):
        background.fig3a(tmp_path / "f.png", signals=["square"])
    with pytest.raises(ValueError, match="must start with 1"):
        background.fig3b(tmp_path / "f.png", blocks=(2, 3))
