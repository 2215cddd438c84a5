"""MDOF animation (rockarch.output.animation, `rockarch animate`): frames chosen from the
frame rate and duration, the last frame what its title says, the progress bar."""

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.motion.signals import pulse
from rockarch.output import animation
from rockarch.systems import system

runner = CliRunner()
ARCH = ["--shape", "catenary", "--span", "10", "--rise", "3", "--thickness", "0.25",
        "--blocks", "8", "--signal", "sine", "--period", "1"]


@pytest.fixture(scope="module")
def collapse():
    """A small arch that collapses during the pulse (ratio 1.5)."""
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=8,
               t_free=0.5)
    r = s.simulate(pulse("sine", period=1.0), ratio=1.5)
    assert r.overturned
    return r


@pytest.fixture(scope="module")
def safe():
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=8,
               t_free=0.3)
    r = s.simulate(pulse("sine", period=1.0), ratio=0.9)
    assert not r.overturned
    return r


def test_frames_follow_fps_and_end_at_the_collapse(collapse):
    plan = animation.plan_frames(collapse, fps=10, max_frames=500, magnify=1.0)
    t = collapse.t[plan.indices]
    assert t[-1] == pytest.approx(collapse.t_overturn)
    # floor(10 * t_end) + 1 frames, 0.1 s apart (to the record spacing, one MDOF step)
    assert plan.indices.size == int(10 * collapse.t_overturn) + 1
    assert np.allclose(np.diff(t), t[-1] / (t.size - 1), atol=2 * collapse.h)
    # played in real time (GIF durations are whole centiseconds), then held
    assert plan.durations_ms[-1] == animation.HOLD * 1000
    assert plan.durations_ms[:-1].sum() == pytest.approx(1000 * t[-1], abs=5 * t.size)


def test_max_frames_caps_the_count(collapse):
    plan = animation.plan_frames(collapse, fps=100, max_frames=7, magnify=1.0)
    assert plan.indices.size == 7 and plan.indices[0] == 0


def test_last_frame_is_magnified_until_visible(collapse):
    plan = animation.plan_frames(collapse, fps=10, max_frames=50, magnify=1.0)
    last = int(plan.indices[-1])
    base = np.concatenate(animation._outlines(collapse, collapse.q[0]))
    size = np.ptp(base, axis=0).max()
    shown = np.concatenate(animation._outlines(
        collapse, animation._config(collapse, last, plan.final_magnify))) - base
    # visible: the largest displacement is at least FINAL_VISIBLE/5 of the size (the factor
    # is rounded down to 1, 2, 5 x 10^k, so at worst 2.5x smaller than the target)
    assert np.abs(shown).max() >= animation.FINAL_VISIBLE / 2.5 * size
    big = animation.plan_frames(collapse, fps=10, max_frames=50, magnify=1e4)
    assert big.final_magnify == 1e4  # a larger factor asked for is kept


def test_structure_at_rest_is_not_magnified():
    """Below ap,min nothing moves (displacements are round-off, ~1e-14 m): the last frame
    keeps factor 1 instead of magnifying the round-off."""
    s = system("mdof", shape="catenary", span=10, rise=3, thickness=0.25, blocks=8,
               t_free=0.1)
    r = s.simulate(pulse("sine", period=1.0), ratio=0.5)
    assert np.abs(r.q - r.q[0]).max() < 1e-12
    assert animation.plan_frames(r, 10, 50, 1.0).final_magnify == 1.0


def test_titles_say_what_the_frame_shows(collapse, safe):
    assert animation._title(collapse, 5, 2, 1.0, False) == \
        f"t = {collapse.t[5]:.2f} s, open joints: 2"
    last = animation._title(collapse, collapse.t.size - 1, 3, 5.0, True)
    assert last.startswith(f"COLLAPSE at t = {collapse.t_overturn:.3f} s")
    assert last.endswith("displacements ×5")
    assert "(end, safe)" in animation._title(safe, safe.t.size - 1, 0, 1.0, True)


def test_gif_frames_and_progress(collapse, tmp_path, capsys):
    gif = tmp_path / "a.gif"
    animation.animate(collapse, gif, fps=4, max_frames=20, progress=True)
    err = capsys.readouterr().err
    assert "frames:" in err and "|" in err  # a tqdm bar (cleared when done)
    plan = animation.plan_frames(collapse, 4, 20, 1.0)
    with Image.open(gif) as im:
        # Pillow merges identical consecutive frames, so at most the planned count; the
        # canvas is 10 x 4.1 in at 100 dpi, which matplotlib versions round to 409 or 410 px
        assert 2 <= im.n_frames <= plan.indices.size
        assert im.size[0] == 1000 and abs(im.size[1] - 410) <= 1
        first = np.array(im.convert("RGB"))
        im.seek(im.n_frames - 1)
        assert im.info["duration"] == animation.HOLD * 1000
        last = np.array(im.convert("RGB"))
    assert (first != last).any(axis=2).mean() > 0.01  # the held frame shows the motion
    animation.animate(collapse, tmp_path / "b.gif", fps=2, max_frames=20)
    assert capsys.readouterr().err == ""  # default: a bar only when stderr is a terminal
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.gif", "b.gif"]


def test_cli_progress_on_request(tmp_path):
    res = runner.invoke(app, ["animate", *ARCH, "--ratio", "1.5", "--t-free", "0.2", "--fps",
                              "3", "--out", str(tmp_path / "b.gif"), "--progress"])
    assert res.exit_code == 0 and "frames:" in res.stderr


@pytest.mark.parametrize("opt, msg", [
    (["--fps", "0"], "--fps must lie in [1, 100]"),
    (["--frames", "1"], "--frames must lie in [2, 10000]"),
    (["--magnify", "0.5"], "--magnify must lie in [1, 10000]"),
    (["--magnify", "nan"], "--magnify must lie in [1, 10000]"),
])
def test_cli_bad_animation_options(tmp_path, opt, msg):
    res = runner.invoke(app, ["animate", *ARCH, "--ratio", "1.5", *opt, "--out",
                              str(tmp_path / "a.gif")])
    assert res.exit_code == 2 and msg in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1 and not list(tmp_path.iterdir())


def test_mdof_time_history_figure(collapse, tmp_path):
    """`simulate mdof --plot`: the curve is the measure of max_rotation_ratio (every step is
    recorded, so its maximum is the reported one)."""
    from rockarch.output.figures import plot_response

    fig = plot_response(collapse, collapse.ground)
    y = fig.axes[0].lines[0].get_ydata()
    assert y.max() == pytest.approx(collapse.max_rotation_ratio, rel=1e-12)
    res = runner.invoke(app, ["simulate", "mdof", *ARCH, "--ratio", "1.5", "--t-free", "0.5",
                              "--plot", str(tmp_path / "h.png")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "h.png").read_bytes()[:4] == b"\x89PNG"


def test_sliding_joint_is_drawn_blue():
    # a block (mu = 0.1) sliding on a wide pedestal under a 0.3 g step of 0.3 s (Newmark:
    # 0.265 m): while it slides, its joint is drawn in the sliding colour and counted in the
    # title, from the first frame after the start to its stop at t = 0.3 + v/(mu g) = 0.9 s
    # (where the run ends, at rest)
    from rockarch.mdof import builders as bd
    from rockarch.mdof import simulate as simulate_mdof
    from rockarch.motion.signals import step

    a = bd.from_polygons([[[0, 1], [0.4, 1], [0.4, 1.2], [0, 1.2]]], mu=0.1,
                         supports=[[[-2, 0], [2, 0], [2, 1], [-2, 1]]])
    r = simulate_mdof(a, step(0.3 * 9.81, 0.3), t_free=1.0)
    plan = animation.plan_frames(r, fps=10, max_frames=50, magnify=1.0)
    rend = animation._Renderer(r, plan)
    seen = []
    for i in plan.indices:
        rend.frame(int(i), 1.0, False)
        line = rend.joint_lines[0]
        seen.append((float(r.t[i]), line.get_visible() and line.get_color() == "tab:blue",
                     rend.title.get_text()))
    sliding = [t for t, blue, _ in seen if blue]
    assert sliding and min(sliding) < 0.15 and 0.8 < max(sliding) < 0.95
    assert any("sliding: 1" in title for _, _, title in seen)
    assert not seen[0][1] and "sliding: 0" in seen[0][2]
    assert r.max_slip == pytest.approx(0.265, rel=2e-3)
