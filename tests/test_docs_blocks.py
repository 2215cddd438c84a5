"""Every code block of docs/*.md (and the README's Python block) runs as written, and what it
prints is what the page shows (tests/docblocks.py states the rule and the markers).

``make test`` runs each page's quick steps; ``make test-all`` every step, in order, and checks
the run times the pages state.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.docblocks import (
    QUICK_SECONDS,
    ROOT,
    blocks,
    commands,
    matches,
    run_page,
    runnable,
    selected,
    show,
    shown_value,
    steps,
    timings,
)

README = ROOT / "README.md"
PAGES = sorted((ROOT / "docs").glob("*.md"))
#: Languages a block may have without a marker (runnable ones); data shown to the reader
#: (a JSON file, an output excerpt) needs ``docs-test: skip`` or ``docs-test: file NAME``.
RUNNABLE = ("python", "console")
#: The README's console examples are tests/test_readme.py's; its Python block runs here.
RUNS = [(p, RUNNABLE) for p in PAGES if any(s for s in steps(p))] + [(README, ("python",))]
IDS = [str(p.relative_to(ROOT)) for p, _ in RUNS]


# --------------------------------------------------------------------------- the rule


def test_matching_rule():
    assert matches('{"b": [null, ...], "c": 4.00703125}', '{"b": [null, 1, 2], "c": 4.00703125}')
    assert not matches('{"c": 4.0078125}', '{"c": 4.00703125}')
    assert matches("a\n...\nz", "a\nb\nc\nz")
    # another machine's last bits pass; a real change does not
    assert matches('{"t": 0.585899835700924}', '{"t": 0.5858998357009273}')
    assert not matches('{"t": 0.585899835700924}', '{"t": 0.5859010}')
    assert matches("ap,min = 2.4529 m/s", "ap,min = 2.4530 m/s")  # a rounding flip
    assert not matches("ap,min = 2.4529 m/s", "ap,min = 2.4532 m/s")
    assert matches('{"impacts": 476}', '{"impacts": 400}')  # chaotic: a band
    assert not matches('{"impacts": 476}', '{"impacts": 200}')
    assert not matches('{"steps": 476}', '{"steps": 475}')  # integers are exact
    assert not matches("rows: 3", "rows: 3 and more")


def test_values_are_shown_as_the_docs_write_them():
    np = pytest.importorskip("numpy")
    assert show((True, np.float64(2.5), np.int64(3))) == "True, 2.5, 3"
    assert show(np.array([np.nan, 4.0])) == "[nan, 4.0]"
    assert show({"a": (1, 2)}) == '{"a": (1, 2)}'
    assert shown_value("# -> 0.392..., 1") == "0.392..., 1"
    assert shown_value("# [nan, nan, 4.00703125]") == "[nan, nan, 4.00703125]"
    assert shown_value("# True, 2.0405..., 1.0, 1") == "True, 2.0405..., 1.0, 1"
    assert shown_value("# LP (N voussoirs), four-hinge p") is None  # prose


def test_a_wrong_value_or_output_fails(tmp_path):
    """The runner can fail: a page whose comment shows another value, and one whose command
    prints something else, both fail and name the page's line (the pages themselves pass)."""
    page = tmp_path / "page.md"
    page.write_text("# t\n\n```python\nx = 2 + 2\nx   # -> 5\n```\n", encoding="utf-8")
    proc, _ = run_page(page, True, tmp_path)
    assert proc.returncode != 0 and "page.md:5" in proc.stderr and "'5'" in proc.stderr
    page.write_text("# t\n\n```python\nx = 2 + 2\nx   # -> 4\n```\n\n```console\n"
                    "$ rockarch arch --shape circular --span 10 --rise 5 --min-thickness"
                    " --json\n{\"d_min\": 0.6}\n```\n", encoding="utf-8")
    proc, _ = run_page(page, True, tmp_path)
    assert proc.returncode != 0 and "page.md:9" in proc.stderr, proc.stderr


def test_quick_steps_leave_out_what_depends_on_slow_ones(tmp_path):
    page = tmp_path / "page.md"
    page.write_text(
        "```console\n$ rockarch records synth syn/ --n 50   # ~5 s\n"
        "$ rockarch records info syn/\n$ rockarch arch --shape circular --span 10 --rise 5\n"
        "```\n<!-- docs-test: slow -->\n```python\nx = 1\n```\n```python\ny = x\n```\n",
        encoding="utf-8")
    quick = [s.where for s in selected(steps(page), everything=False)]
    assert quick == [f"{page}:4"]


# --------------------------------------------------------------------------- the pages


@pytest.mark.parametrize("path", [README, *PAGES], ids=lambda p: p.name)
def test_every_block_runs_or_says_why_not(path):
    """A block is Python or a console session, or is marked: skip (with what it is), slow,
    or a file the page asks the reader to save. A console block runs only rockarch and the
    repository's Python scripts."""
    bad = []
    for b in blocks(path):
        if b.marker in ("skip", "file"):
            continue
        if b.lang not in RUNNABLE:
            bad.append(f"{b.where}: ```{b.lang or ''} block neither python nor console nor "
                       "marked <!-- docs-test: skip|slow|file NAME -->")
        elif b.lang == "console":
            cmds = commands(b)
            if not cmds:
                bad.append(f"{b.where}: console block without a '$ ' command")
            bad += [f"{c.where}: not a rockarch or python command: {' '.join(c.argv)}"
                    for c in cmds if not runnable(c.argv)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("path", [README, *PAGES], ids=lambda p: p.name)
def test_no_command_hides_in_an_indented_block(path):
    """Commands belong in ```console blocks (run by this test); an indented code block is
    for equations only."""
    lines = path.read_text(encoding="utf-8").splitlines()
    fenced, bad = False, []
    for i, line in enumerate(lines):
        if re.match(r"^\s*(```|~~~)", line):
            fenced = not fenced
        elif not fenced and re.match(r"^ {4}(\$ |rockarch |\.venv/|python|PYTHONPATH=)", line) \
                and (i == 0 or not lines[i - 1].strip()):
            bad.append(f"{path.name}:{i + 1}: {line.strip()[:60]}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("path", [README, *PAGES], ids=lambda p: p.name)
def test_docs_name_only_what_a_user_has(path):
    """No path of a development machine (../shared, /work/, /home/, /tmp/...) and no
    developers' note: the bundled data, files the docs' own commands create, or files they
    say how to download."""
    text = path.read_text(encoding="utf-8")
    bad = [f"{path.name}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}"
           for m in re.finditer(r"\.\./shared\b|(?<![\w.~])/(?:work|home|tmp|root|Users)/\S*"
                                r"|physics note", text)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("path", [README, *PAGES], ids=lambda p: p.name)
def test_every_long_command_states_its_time(path):
    """A quick command runs in `make test`; a slow one says how slow (`# ~N s`)."""
    bad = [f"{c.where}: marked slow without a '# ~N s' time" for b in blocks(path)
           if b.lang == "console" and b.marker == "slow" for c in commands(b)
           if c.seconds is None]
    assert not bad, "\n".join(bad)


def _run(path: Path, langs, everything: bool, tmp_path: Path) -> dict[str, float]:
    proc, chosen = run_page(path, everything, tmp_path, langs)
    assert proc.returncode == 0, f"{path.name}:\n{proc.stderr[-6000:]}"
    return timings(proc.stderr)


@pytest.mark.parametrize("path, langs", RUNS, ids=IDS)
def test_quick_blocks_run_as_written(path, langs, tmp_path):
    if not selected(steps(path, langs), everything=False):
        pytest.skip("every step of this page is slow (make test-all)")
    _run(path, langs, False, tmp_path)


@pytest.mark.slow  # every block of every page, in order: minutes (the sum of the stated times)
@pytest.mark.parametrize("path, langs", RUNS, ids=IDS)
def test_all_blocks_run_as_written_in_their_stated_time(path, langs, tmp_path):
    """Every step in order; a command's CPU time stays within a few times its stated time
    (CPU time: other jobs on the machine do not count; a numba-threaded command uses up to
    2 CPU seconds a second on 2 cores) and never beyond 2 minutes without a stated time."""
    took = _run(path, langs, True, tmp_path)
    stated = {c.where: c.seconds for s in steps(path, langs) if (c := s.command)}
    slow = {w: t for w, t in took.items()
            if t > max(120.0, 4 * (stated.get(w) or QUICK_SECONDS))}
    assert not slow, f"commands far slower than the page says (seconds): {slow}"
