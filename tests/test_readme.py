"""The README's command-line examples: every command parses, and what the commands print
is what the README shows (every number; ``...`` in the README leaves a part out).

The quick commands (``# ~3 s`` or less, needing no file of another command) run in
``make test``; all of them, in order and in one folder, in ``make test-all``.
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import click
import pytest
import typer
from typer.testing import CliRunner

from rockarch.cli import app
from rockarch.motion.records import bundled_record_path

README = Path(__file__).resolve().parents[1] / "README.md"
DATA = bundled_record_path(180).parent
runner = CliRunner()


def examples(text: str) -> list[tuple[list[str], str, float]]:
    """(argv without "rockarch", expected output, rough seconds) of every ``$ rockarch``
    line in the README's console blocks; continuation lines end with a backslash."""
    out = []
    for block in re.findall(r"```console\n(.*?)```", text, flags=re.DOTALL):
        lines = block.splitlines()
        i = 0
        while i < len(lines):
            if not lines[i].startswith("$ "):
                i += 1
                continue
            cmd = lines[i][2:]
            while cmd.rstrip().endswith("\\"):
                i += 1
                cmd = cmd.rstrip()[:-1] + " " + lines[i]
            i += 1
            expected = []
            while i < len(lines) and lines[i].strip() and not lines[i].startswith("$ "):
                expected.append(lines[i].rstrip())
                i += 1
            m = re.search(r"#\s*~(\d+(?:\.\d+)?)\s*s", cmd)
            argv = shlex.split(cmd, comments=True)
            assert argv[0] == "rockarch", cmd
            out.append((argv[1:], "\n".join(expected), float(m.group(1)) if m else 1e9))
    return out


EXAMPLES = examples(README.read_text(encoding="utf-8"))
#: Files and folders that one example writes and others read.
WRITTEN = {"site.nc": ["site-oas"], "synth/": ["records", "synth"]}
#: Quick examples that need no file written by another one (``design --site site.nc``).
QUICK = [e for e in EXAMPLES if e[2] <= 3
         and not any(f in e[0] and e[0][:len(w)] != w for f, w in WRITTEN.items())]


def _argv(argv: list[str]) -> list[str]:
    """The README's relative paths to the bundled records, made absolute."""
    rel = "src/rockarch/motion/data"
    return [str(DATA) + a[len(rel):] if a.startswith(rel) else a for a in argv]


NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
#: Relative tolerance of a deterministic number printed in full (a closed-form-like result of
#: a fixed computation: what differs between machines is floating-point order in numpy and
#: numba builds, ~1e-14 in one step, ~1e-8 after the longest runs of the README).
REL = 1e-6
#: Chaotic quantities of a rocking history, compared as bands (relative, absolute). Measured
#: on the 20-voussoir arch under 5 s of El Centro at 1.5·ap,min (tests/mdof/test_mdof.py):
#: scaling the record by 1 + 1e-12 moves the impact count from 179 to 243 and the open
#: joints from 10 to 11; halving the step twice spans 161–251 impacts. A single history's
#: impact count is known to about ±35 %, its largest slip to about ±50 %.
CHAOTIC = {"impacts": (0.35, 3), "open_joints_max": (0.0, 2), "sliding_contacts_max": (0.0, 2),
           "max_slip": (0.5, 0.0)}


def _unit(text: str) -> float:
    """One unit in the last digit shown of a number as printed."""
    mant, _, exp = text.lower().partition("e")
    decimals = len(mant.partition(".")[2])
    return 10.0 ** (-decimals + (int(exp) if exp else 0))


def _number_ok(shown: str, got: str, key: str | None) -> bool:
    x, y = float(shown), float(got)
    if key in CHAOTIC:
        rel, ab = CHAOTIC[key]
        return abs(y - x) <= max(rel * abs(x), ab)
    if re.fullmatch(r"-?\d+", shown):
        return x == y  # a count or an index: exact
    return abs(y - x) <= max(REL * abs(x), _unit(shown) * (1 + 1e-9))


def matches(expected: str, actual: str) -> bool:
    """``expected`` (the README) and ``actual`` (what was printed) are the same text, except
    that ``...`` stands for anything (also lines) and numbers agree as a user on another
    machine would read them: within :data:`REL` relative or one unit of the last digit
    shown, whichever is larger; integers exactly; the :data:`CHAOTIC` JSON keys within
    their bands."""
    actual = "\n".join(line.rstrip() for line in actual.strip().splitlines())
    segments = expected.split("...")
    pos = 0
    for n, segment in enumerate(segments):
        pieces = re.split(rf"({NUMBER})", segment)
        rx, wanted = [], []
        for i, piece in enumerate(pieces):
            if i % 2 == 0:
                rx.append(re.escape(piece))
            else:
                key = re.search(r'"(\w+)":\s*$', "".join(pieces[:i]))
                rx.append(f"({NUMBER})")
                wanted.append((piece, key.group(1) if key else None))
        pattern = re.compile("".join(rx) + (r"\Z" if n == len(segments) - 1 else ""))
        start = pos
        while True:  # the leftmost place where the text and the numbers both agree
            m = (pattern.match if n == 0 else pattern.search)(actual, start)
            if m is None:
                return False
            if all(_number_ok(s, g, k) for (s, k), g in zip(wanted, m.groups(), strict=True)):
                pos = m.end()
                break
            if n == 0:
                return False
            start = m.start() + 1
    return True


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


def test_every_example_parses_and_says_its_run_time():
    assert len(EXAMPLES) >= 10 and len(QUICK) >= 6
    root = typer.main.get_command(app)
    for argv, expected, seconds in EXAMPLES:
        assert expected, f"no output shown for rockarch {' '.join(argv)}"
        assert seconds < 1e9, f"no '# ~N s' run time for rockarch {' '.join(argv)}"
        cmd, rest = root, list(argv)
        while isinstance(cmd, click.Group):
            cmd = cmd.get_command(None, rest.pop(0))
            assert cmd is not None, argv
        cmd.make_context("rockarch", _argv(rest))  # unknown options or values raise here


def _run(argv: list[str], expected: str) -> None:
    res = runner.invoke(app, _argv(argv))
    assert res.exit_code == 0, (argv, res.stderr, res.exception)
    assert matches(expected, res.stdout), (
        f"rockarch {' '.join(argv)}\nREADME:\n{expected}\nprinted:\n{res.stdout}")


@pytest.mark.parametrize("argv, expected", [e[:2] for e in QUICK],
                         ids=[" ".join(e[0][:2]) for e in QUICK])
def test_quick_examples_print_what_the_readme_shows(argv, expected, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _run(argv, expected)


@pytest.mark.slow  # ~60 s: every example, including the record OAS, site OAS and animation
def test_all_examples_in_order(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for argv, expected, _ in EXAMPLES:
        _run(argv, expected)


def test_python_block_runs_and_shows_what_it_computes():
    """The README's Python block runs as written, and the values its comments show are the
    computed ones (same rule as the console block: the README is the output of the code)."""
    block = re.search(r"```python\n(.*?)```", README.read_text(encoding="utf-8"),
                      flags=re.DOTALL).group(1)
    ns: dict = {}
    exec(compile(block, "README.md", "exec"), ns)  # noqa: S102 - the README's own example
    assert ns["ds"].boundary.values[-1] == pytest.approx(4.00703125, rel=REL)
    assert "[nan, nan, 4.00703125]" in block
    shown = dict(re.findall(r"^(r\.[^#\n]+?)\s+# (.+)$", block, flags=re.M))
    first = "r.overturned, r.t_overturn, r.max_rotation_ratio, r.impacts"
    # the block's first r is the block's, the second (the arch's) is ns["r"] now
    d = ns["r"].to_dict()
    printed = "{" + ", ".join(f'"{k}": {v!r}' for k, v in d.items()) + "}"
    assert matches(shown["r.to_dict()"], printed), (shown["r.to_dict()"], printed)
    blk = ns["blk"].simulate(ns["m"], p=2.0, ratio=4.1)
    values = ", ".join(repr(v) for v in (blk.overturned, blk.t_overturn,
                                          blk.max_rotation_ratio, blk.impacts))
    assert matches(shown[first], values), (shown[first], values)


def _normalised_report(text: str, out: str) -> str:
    """A demo report without what differs between runs: its folder and the timing."""
    text = text.replace(out, "OUT")
    return re.sub(r"computed in \d+(\.\d+)? s", "computed in T s", text)


@pytest.mark.slow  # ~60 s: the whole demo (make demo)
def test_docs_demo_report_is_what_make_demo_writes(tmp_path):
    """docs/demo/report.md (linked from the README) is what `make demo` writes now; rebuild
    it with `.venv/bin/python examples/demo.py --out docs/demo`."""
    root = README.parent
    subprocess.run([sys.executable, str(root / "examples" / "demo.py"), "--out",
                    str(tmp_path)], check=True, capture_output=True, cwd=tmp_path,
                   timeout=900)
    fresh = _normalised_report((tmp_path / "report.md").read_text(), str(tmp_path))
    kept = _normalised_report((root / "docs" / "demo" / "report.md").read_text(),
                              "docs/demo")
    assert kept == fresh
