"""Figures and HTML (rockarch.output): no global matplotlib state, the arch figure cropped to
the arch, site legends with whole record names, one stylesheet."""

import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr
from PIL import Image

from rockarch.arch import analyse, circular
from rockarch.output import figures, html
from rockarch.output.arch_plots import mechanism_figure, plot_mechanism
from rockarch.output.tables import boundary_table

SRC = Path(__file__).parents[2] / "src" / "rockarch"


def test_no_backend_switch_and_no_pyplot_in_the_package():
    hits = [f"{p.relative_to(SRC)}:{i}" for p in SRC.rglob("*.py")
            for i, line in enumerate(p.read_text().splitlines(), 1)
            if re.search(r"matplotlib\.use\(|import matplotlib\.pyplot|import pyplot|plt\.",
                         line)]
    assert hits == []


def test_figures_leave_the_session_backend_alone(tmp_path):
    before = matplotlib.rcParams._get_backend_or_none()
    ds = xr.Dataset({"overturned": (("p", "ratio"), np.array([[0, 1], [0, 0]], bool)),
                     "boundary": ("p", np.array([1.5, np.nan]))},
                    coords={"p": [1.0, 2.0], "ratio": [1.0, 2.0]})
    ax = figures.plot_oas(ds)
    figures.save_figure(ax.figure, tmp_path / "o.png")
    assert matplotlib.rcParams._get_backend_or_none() == before
    assert (tmp_path / "o.png").read_bytes()[:4] == b"\x89PNG"


def _blank_rows(img: np.ndarray) -> tuple[int, int]:
    """Rows of pure background at the top and bottom of an RGB image."""
    ink = (img < 250).any(axis=(1, 2))
    rows = np.flatnonzero(ink)
    return int(rows[0]), int(img.shape[0] - 1 - rows[-1])


def test_arch_figure_has_no_empty_band(tmp_path):
    """The Sect. 9 arch (README's arch_sect9.png): cropped to the drawing, the legend below
    the x label (before: ~80 px of empty band above the title)."""
    path = plot_mechanism(analyse(circular(10.0, 2.89, 0.35)), tmp_path / "a.png")
    img = np.array(Image.open(path).convert("RGB"))
    top, bottom = _blank_rows(img)
    # bbox_inches="tight" pads 0.1 in = 12 px at 120 dpi (+ antialiased edge rows)
    assert top <= 15 and bottom <= 15
    fig = mechanism_figure(analyse(circular(10.0, 2.89, 0.35)))
    fig.canvas.draw()
    legend = fig.legends[0].get_window_extent()
    xlabel = fig.axes[0].xaxis.label.get_window_extent()
    assert legend.y1 <= xlabel.y0  # no overlap


def test_site_legend_holds_whole_record_names(tmp_path):
    long = "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 (Imperial Valley-02, 5/19/1940, El Centro " \
           "Array #9, 180)"
    ds = xr.Dataset({"boundary": (("record", "p"), [[1.2, 1.1], [1.3, 1.4]]),
                     "envelope": ("p", [1.2, 1.1]), "characteristic": ("p", [1.25, 1.25]),
                     "record_name": ("record", [long, "short"])},
                    coords={"p": [1.0, 2.0]}, attrs={"percentile": 50.0, "title": "site"})
    fig = figures.plot_site(ds)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[0].replace("\n", " ") == long and labels[1] == "short"
    fig.canvas.draw()
    box = fig.axes[0].get_legend().get_window_extent()
    saved = figures.save_figure(fig, tmp_path / "s.png")
    assert box.width < Image.open(saved).size[0]  # the saved figure holds the legend


def test_site_legend_of_many_records_has_one_entry():
    n = figures.MAX_NAMED_RECORDS + 1
    ds = xr.Dataset({"boundary": (("record", "p"), np.ones((n, 2))),
                     "envelope": ("p", [1.0, 1.0]), "characteristic": ("p", [1.0, 1.0]),
                     "record_name": ("record", [f"r{k}" for k in range(n)])},
                    coords={"p": [1.0, 2.0]}, attrs={"percentile": 50.0, "title": "site"})
    labels = [t.get_text() for t in figures.plot_site(ds).axes[0].get_legend().get_texts()]
    # the percentile equals the envelope here: one line, one entry that says so
    assert labels == [f"{n} records", "envelope (= the 50th percentile)"]


def test_site_legend_names_only_visible_curves():
    """Two records: the 50th percentile ('lower') is the envelope, drawn once; when the
    curves differ, the percentile is drawn over the envelope (visible where they meet)."""
    ds = xr.Dataset({"boundary": (("record", "p"), [[1.2, 1.1], [1.3, 1.4]]),
                     "envelope": ("p", [1.2, 1.1]), "characteristic": ("p", [1.2, 1.1]),
                     "record_name": ("record", ["a", "b"])},
                    coords={"p": [1.0, 2.0]}, attrs={"percentile": 50.0, "title": "site"})
    ax = figures.plot_site(ds).axes[0]
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "a", "b", "envelope (= the 50th percentile)"]
    ds["characteristic"] = ("p", [1.25, 1.1])
    ax = figures.plot_site(ds).axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[-2:] == ["envelope", "50th percentile"]
    env, pct = ax.get_lines()[-2:]
    assert pct.get_zorder() > env.get_zorder() and pct.get_linestyle() == "--"
    # where no record overturns within the ratio range the curves have no value: a marker
    # at the range's top says so (the blank low-p band of a site was unexplained)
    ds = ds.assign(envelope=("p", [np.nan, 1.1]), ratio=("ratio", [1.0, 5.0]))
    ax = figures.plot_site(ds).axes[0]
    mark = ax.get_lines()[-1]
    assert mark.get_label() == "no record overturns up to ap/ap,min = 5"
    assert list(mark.get_xdata()) == [1.0] and list(mark.get_ydata()) == [5.0]


def test_one_stylesheet_and_escaped_tables():
    page = html.page("t <1>", html.table(["a&b"], [["<x>", 2]]))
    assert page.count("<style>") == 1 and html.STYLESHEET in page
    assert "<title>t &lt;1&gt;</title>" in page and "<td>&lt;x&gt;</td>" in page
    assert "<th>a&amp;b</th>" in page


@pytest.mark.parametrize("b, text", [(4.00703125, "4.0070"), (np.nan, "> 5 (none in range)")])
def test_boundary_table_format(b, text):
    lines = boundary_table(np.array([2.0]), np.array([b]), 5.0)
    assert lines[0] == f"{'p [1/s]':>10}  {'boundary ap/ap,min':>20}"
    assert lines[1] == f"{'2':>10}  {text:>20}"


def _labels_with_units(fig) -> list[tuple[str, str]]:
    """(x label, y label) of every axes of a figure that has ticks; axes sharing their x
    axis (stacked panels) take the label of the one that shows it."""
    def xlabel(ax):
        return " ".join(a.get_xlabel() for a in ax.get_shared_x_axes().get_siblings(ax))

    return [(xlabel(ax), ax.get_ylabel()) for ax in fig.axes if ax.get_xticks().size]


def test_every_figure_kind_labels_its_axes_with_units():
    """The CLI's figures: each axis named, with its unit in brackets ([-] dimensionless)."""
    import rockarch as ra
    from rockarch.mdof import column
    from rockarch.output.collapse_plots import collapse_figure
    from rockarch.output.fragility_plots import plot_fragility
    from rockarch.risk import fragility as fr

    blk = ra.system("block", alpha=0.1, p=2.0)
    sines = [ra.pulse("sine", period=t) for t in (0.5, 1.0, 2.0)]
    oas = ra.oas(blk, sines[1], p=[1.0, 2.0], ratio=[1.0, 2.0, 3.0])
    ida = fr.ida(blk, sines, 2.0, ratio=np.linspace(1, 5, 9))
    figs = {"response": figures.plot_response(ra.simulate(blk, sines[1], ratio=2.0),
                                              sines[1]),
            "oas": figures.plot_oas(oas).figure,
            "fragility": plot_fragility(fr.fit_ida(ida, n_bootstrap=20)),
            "collapse": collapse_figure(column([(0.4, 1.0), (0.3, 0.8)])),
            "mechanism": mechanism_figure(analyse(circular(10, 2.89, 0.35)))}
    for name, fig in figs.items():
        for xl, yl in _labels_with_units(fig):
            assert re.search(r"\[.+\]", xl) and re.search(r"\[.+\]", yl), (name, xl, yl)


def test_a_response_that_slid_shows_its_slip():
    """An MDOF response with friction that slid gets a panel of its largest joint slip
    (mm); one that did not keeps the rotation and ground panels alone."""
    import rockarch as ra
    from rockarch import mdof
    from rockarch.mdof import builders as bd

    step = ra.pulse("step", period=0.2, ap=0.5 * 9.81)
    slid = mdof.simulate(bd.with_friction(mdof.single_block(1.0, 1.0), 0.1), step,
                         t_free=1.0)
    rests = mdof.simulate(bd.with_friction(mdof.single_block(1.0, 1.0), 0.8), step,
                          t_free=1.0)
    fig = figures.plot_response(slid, step)
    panel = [ax for ax in fig.axes if "slip" in ax.get_ylabel()]
    assert len(fig.axes) == 3 and len(panel) == 1 and "[mm]" in panel[0].get_ylabel()
    assert max(ln.get_ydata().max() for ln in panel[0].lines) == pytest.approx(
        1e3 * slid.max_slip, rel=1e-6)
    assert rests.sliding_contacts_max == 0 and len(figures.plot_response(rests).axes) == 2


def test_the_legend_of_an_overturned_mdof_history_leaves_its_red_x_free():
    # the history ends at overturning, its red x at the top right corner: the legend sat
    # there over it (and the x was cut in half by the axes' edge)
    import rockarch as ra
    from rockarch import mdof
    from rockarch.arch import catenary

    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 10)
    sine = ra.pulse("sine", period=1.0, ap=1.5 * a.ap_min)
    resp = mdof.simulate(a, sine)
    assert resp.overturned
    fig = figures.plot_response(resp, sine)
    fig.canvas.draw()
    ax = fig.axes[0]
    (cross,) = [ln for ln in ax.lines if ln.get_label().startswith("overturned")]
    xy = ax.transData.transform((cross.get_xdata()[0], cross.get_ydata()[0]))
    legend = ax.get_legend().get_window_extent()
    assert not legend.contains(*xy)
    assert not legend.overlaps(cross.get_window_extent())  # nor any part of the x


def test_fragility_axis_in_the_units_of_json_and_g_on_top():
    """--json gives the median in m/s²: the x axis too, with PGA in g on a second axis."""
    import rockarch as ra
    from rockarch.output.fragility_plots import plot_fragility
    from rockarch.risk import fragility as fr

    blk = ra.system("block", alpha=0.1, p=2.0)
    ida = fr.ida(blk, [ra.pulse("sine", period=t) for t in (0.5, 1.0)], 2.0,
                 ratio=np.linspace(1, 5, 9))
    frag = fr.fit_ida(ida, n_bootstrap=0)
    fig = plot_fragility(frag)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "PGA [m/s²]"
    top = [a for a in ax.child_axes if a.get_xlabel()]
    assert [a.get_xlabel() for a in top] == ["PGA [g = 9.80665 m/s²]"]  # which g
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(f"θ = {frag.fit.median:.3g} m/s²" in t for t in legend), legend


def test_long_histories_are_drawn_by_their_envelope():
    """5e6 samples are drawn as min/max per bin: the same extremes and their times, in
    time order, 2·DISPLAY_BINS points (the figure of the largest harmonic stays < 1 GB)."""
    t = np.linspace(0.0, 500.0, 2_000_001)
    y = np.sin(2 * np.pi * t / 0.1) * np.exp(-t / 300) + 1e-3 * np.cos(t)
    td, yd = figures.for_display(t, y)
    assert td.size == 2 * figures.DISPLAY_BINS and np.all(np.diff(td) >= 0)
    assert yd.max() == y.max() and yd.min() == y.min()
    assert td[np.argmax(yd)] == t[np.argmax(y)]
    short = np.arange(10.0)
    assert figures.for_display(short, short)[0] is short  # short lines as they are


def test_mechanism_label_is_on_the_coordinate_of_the_text_output():
    # the arch command prints delta_u for both directions; the figure's label reads u on that
    # coordinate too (before: u = delta_u/2 for +1 but part 1's rotation, 0.0245, for -1)
    from rockarch.output.arch_plots import mechanism_figure

    for direction in (1, -1):
        res = analyse(circular(10.0, 2.89, 0.35), direction=direction)
        fig = mechanism_figure(res)
        labels = [t.get_text() for t in fig.legends[0].get_texts()]
        assert f"mechanism half way to neutral, u = {0.5 * res.delta:.3g} rad" in labels


def test_collapse_figure_of_a_column_is_not_a_sliver_and_its_legend_covers_nothing():
    # a slender column's mechanism: drawn at least 0.6 as wide as tall (before: a sliver whose
    # x tick labels ran into each other), the legend below the axes (before: over its top)
    from rockarch.mdof import column
    from rockarch.output.collapse_plots import collapse_figure

    fig = collapse_figure(column([(0.3, 1.5), (0.2, 1.0)]))
    ax = fig.axes[0]
    assert "g (g = 9.81 m/s²; ground accelerating" in ax.get_title()  # the structure's g
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x1 - x0 >= 0.6 * (y1 - y0) * (1 - 1e-9)
    fig.canvas.draw()
    legend = fig.legends[0].get_window_extent()
    assert legend.y1 <= ax.get_window_extent().y0  # below the axes, over no block
