"""The README's command-line examples: every command parses, and what the commands print
is what the README shows (every number; ``...`` in the README leaves a part out; the rule is
:func:`tests.docblocks.matches`). The README's Python block runs in tests/test_docs_blocks.py.

The quick commands (``# ~3 s`` or less, needing no file of another command) run in
``make test``; all of them, in order and in one folder, in ``make test-all``.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import click
import pytest
import typer
from typer.testing import CliRunner

from rockarch.cli import app
from tests.docblocks import blocks, commands, matches, repo_path

README = Path(__file__).resolve().parents[1] / "README.md"
runner = CliRunner()


def examples(path: Path) -> list[tuple[list[str], str, float]]:
    """(argv without "rockarch", expected output, rough seconds) of every ``$ rockarch``
    line in the README's console blocks; continuation lines end with a backslash."""
    out = []
    for c in (c for b in blocks(path) if b.lang == "console" for c in commands(b)):
        assert c.argv[0] == "rockarch", c.where
        out.append((list(c.argv[1:]), c.expected, 1e9 if c.seconds is None else c.seconds))
    return out


EXAMPLES = examples(README)
#: Files and folders that one example writes and others read.
WRITTEN = {"site.nc": ["site-oas"], "synth/": ["records", "synth"],
           "fragility.json": ["fragility"]}
#: Quick examples that need no file written by another one (``design --site site.nc``).
QUICK = [e for e in EXAMPLES if e[2] <= 3
         and not any(f in e[0] and e[0][:len(w)] != w for f, w in WRITTEN.items())]


def _argv(argv: list[str]) -> list[str]:
    """The README's relative paths to the bundled records, made absolute."""
    return [repo_path(a) for a in argv]


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


def _normalised_report(text: str, out: str) -> str:
    """A demo report without what differs between runs: its folder and the timing."""
    text = text.replace(out, "OUT")
    return re.sub(r"computed in \d+(\.\d+)? s", "computed in T s", text)


@pytest.mark.slow  # ~60 s: the whole demo (make demo)
def test_docs_demo_report_is_what_make_demo_writes(tmp_path):
    """docs/demo/report.md (linked from the README) is what `make demo` writes now; rebuild
    it with `.venv/bin/python examples/demo.py --out docs/demo`."""
    root = README.parent
    # from the clone's root, as `make demo` runs it (the rerun command names the records
    # by their path in the clone)
    subprocess.run([sys.executable, str(root / "examples" / "demo.py"), "--out",
                    str(tmp_path)], check=True, capture_output=True, cwd=root, timeout=900)
    fresh = _normalised_report((tmp_path / "report.md").read_text(), str(tmp_path))
    kept = _normalised_report((root / "docs" / "demo" / "report.md").read_text(),
                              "docs/demo")
    assert kept == fresh
