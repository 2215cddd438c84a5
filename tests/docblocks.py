"""The fenced code blocks of README.md and docs/*.md, run as written, and the rule by which
what they print is what the docs show.

Used by ``tests/test_readme.py`` (the README's console examples) and
``tests/test_docs_blocks.py`` (every block of docs/ and the README's Python block).

The rule (docs/architecture.md, "Where to add … a docs page"):

- A ```` ```python ```` block runs as written, in order within its page, as one script (one
  namespace per page; ``__name__ == "__main__"``), in a temporary folder. After an expression,
  a comment ``# -> VALUE``, or ``# VALUE`` where VALUE starts like a Python value (a number,
  ``True``/``False``/``None``/``nan``, a quote or an opening bracket), is what the expression
  computes: checked with :func:`matches` (``...`` stands for anything). Any other comment is
  prose.
- A ```` ```console ```` block: each ``$ rockarch ...`` or ``$ .venv/bin/python ...`` line
  (continued with a backslash) runs in the page's folder (where ``src/``, ``examples/``,
  ``benchmarks/`` and ``validation/`` are those of the repository, as in a clone), after the
  page's earlier blocks; the
  lines after it are its output (stdout; ``error: ...`` means exit status 2 and that stderr).
  A command that takes more than :data:`QUICK_SECONDS` on an idle 2-core machine says so with
  ``# ~N s`` (or ``# ~N min``).
- An HTML comment on the line just before a fence: ``<!-- docs-test: skip -->`` (not run:
  pseudo-code, output excerpts, shell set-up), ``<!-- docs-test: slow -->`` (runs only in
  ``make test-all``), ``<!-- docs-test: file NAME -->`` (the block is a file the page asks the
  reader to save: written as NAME in the page's folder for the blocks after it).

``make test`` runs each page's quick steps (blocks and commands), leaving out the slow ones
and what depends on them (the Python blocks after a slow one; a command naming a file a slow
step writes); ``make test-all`` runs every step in order.
"""

from __future__ import annotations

import ast
import contextlib
import io
import json
import os
import re
import runpy
import shlex
import subprocess
import sys
import tokenize
import traceback
import warnings
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: A command stated to take longer than this (or without a stated time) runs only in
#: ``make test-all``; without a stated time a command must be quicker than this.
QUICK_SECONDS = 3.0
#: Folders of the repository whose files the docs read (linked into the page's folder).
REPO_PREFIXES = ("src/", "examples/", "benchmarks/", "validation/")
MARKER = re.compile(r"^\s*<!--\s*docs-test:\s*(skip|slow|file)\s*(\S*)\s*-->\s*$")
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([\w+-]*)\s*$")
TIME = re.compile(r"#\s*~\s*(\d+(?:\.\d+)?)\s*(s|min)\b")

# --------------------------------------------------------------------------- the blocks


@dataclass(frozen=True)
class Block:
    """One fenced block: its page, the line of its opening fence (1-based), its language,
    its text (indentation of the fence removed) and its marker (skip, slow, file)."""

    path: Path
    line: int
    lang: str
    text: str
    marker: str | None = None
    arg: str = ""

    @property
    def where(self) -> str:
        return f"{_rel(self.path)}:{self.line}"


def _rel(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


def blocks(path: Path) -> list[Block]:
    """Every fenced block of a Markdown file, in order."""
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, lang = m.group(1), m.group(2), m.group(3).lower()
        start, body = i, []
        i += 1
        while i < len(lines) and not (lines[i].strip().startswith(fence)
                                      and not lines[i].strip().strip(fence[0])):
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
            i += 1
        i += 1
        mk = MARKER.match(lines[start - 1]) if start else None
        out.append(Block(path, start + 1, lang, "\n".join(body) + "\n",
                         mk.group(1) if mk else None, mk.group(2) if mk else ""))
    return out


# --------------------------------------------------------------------------- commands


@dataclass(frozen=True)
class Command:
    """One ``$ ...`` line of a console block (continuations joined): its doc line, its
    words (comment removed), the output shown after it and its stated time in seconds."""

    block: Block
    line: int
    argv: tuple[str, ...]
    expected: str
    seconds: float | None

    @property
    def where(self) -> str:
        return f"{_rel(self.block.path)}:{self.line}"

    @property
    def slow(self) -> bool:
        return self.block.marker == "slow" or (self.seconds or 0.0) > QUICK_SECONDS


def commands(block: Block) -> list[Command]:
    """The commands of a console block and the output shown under each."""
    lines = block.text.splitlines()
    out, i = [], 0
    while i < len(lines):
        if not lines[i].startswith("$ "):
            i += 1
            continue
        first = i
        cmd = lines[i][2:]
        while cmd.rstrip().endswith("\\") and i + 1 < len(lines):
            i += 1
            cmd = cmd.rstrip()[:-1] + " " + lines[i]
        i += 1
        expected = []
        while i < len(lines) and not lines[i].startswith("$ "):
            expected.append(lines[i].rstrip())
            i += 1
        while expected and not expected[-1]:
            expected.pop()
        m = TIME.search(cmd)
        seconds = None if m is None else float(m.group(1)) * (60 if m.group(2) == "min" else 1)
        out.append(Command(block, block.line + 1 + first, tuple(shlex.split(cmd, comments=True)),
                           "\n".join(expected), seconds))
    return out


def runnable(argv: tuple[str, ...] | list[str]) -> bool:
    """A command the docs may show: rockarch, or Python (the project's .venv or python3)
    running a file of the repository, after optional ``VAR=value`` settings."""
    words = [a for a in argv if not re.fullmatch(r"[A-Z_]+=\S*", a)]
    return bool(words) and (words[0] == "rockarch"
                            or words[0] in (".venv/bin/python", "python", "python3"))


def repo_path(arg: str) -> str:
    """A relative path into the repository (``src/rockarch/motion/data/...``), made absolute
    (the docs are run from a temporary folder); other words unchanged."""
    for prefix in REPO_PREFIXES:
        if arg.startswith(prefix):
            return str(ROOT / arg)
        if arg.startswith("--") and "=" + prefix in arg:
            opt, _, val = arg.partition("=")
            return f"{opt}={ROOT / val}"
    return arg


# --------------------------------------------------------------------------- matching

NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
#: Relative tolerance of a deterministic number printed in full (a closed-form-like result of
#: a fixed computation: what differs between machines is floating-point order in numpy and
#: numba builds, ~1e-14 in one step, ~1e-8 after the longest runs of the README).
REL = 1e-6
#: Chaotic quantities of a rocking history, compared as bands (relative, absolute). Measured
#: on the 20-voussoir arch under 5 s of El Centro at 1.5·ap,min (tests/mdof/test_mdof.py):
#: scaling the record by 1 + 1e-9 moves the impact count from 238 to 232 and the open
#: joints from 11 to 9; halving the step twice spans 232–403 impacts (2026-11-29). A
#: single history's impact count is known to about ±35 %, its largest slip to about ±50 %.
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
    """``expected`` (the docs) and ``actual`` (what was printed) are the same text, except
    that ``...`` stands for anything (also lines) and numbers agree as a user on another
    machine would read them: within :data:`REL` relative or one unit of the last digit
    shown, whichever is larger; integers exactly; the :data:`CHAOTIC` JSON keys within
    their bands."""
    actual = "\n".join(line.rstrip() for line in actual.strip().splitlines())
    expected = "\n".join(line.rstrip() for line in expected.strip().splitlines())
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


# --------------------------------------------------------------------------- values


def show(value, quote: str = '"', top: bool = True) -> str:
    """A value as the docs write it: Python literals, numpy scalars and arrays as plain
    numbers and lists, a tuple at the top level without parentheses (``a, b``), dict keys
    in ``quote``."""
    import numpy as np

    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return quote + value + quote
    if isinstance(value, np.ndarray):
        return show(value.tolist(), quote, False)
    if isinstance(value, tuple):
        inner = ", ".join(show(v, quote, False) for v in value)
        return inner if top else f"({inner}{',' if len(value) == 1 else ''})"
    if isinstance(value, list):
        return "[" + ", ".join(show(v, quote, False) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{show(k, quote, False)}: {show(v, quote, False)}"
                               for k, v in value.items()) + "}"
    return repr(value)


def check_value(value, expected: str, where: str) -> None:
    """The value an expression of a docs page computes is the one its comment shows."""
    shown = [show(value, q) for q in ('"', "'")]
    if isinstance(value, tuple):
        shown += [f"({s}{',' if len(value) == 1 else ''})" for s in shown]
    if not any(matches(expected, s) for s in shown):
        _mismatch(f"{where}: the docs show {expected!r}, the code computes {shown[0]!r}")


def _mismatch(message: str) -> None:
    """Fail, or with DOCS_COLLECT set (updating a page's outputs by hand) print the
    mismatch on stderr and go on to the page's next step."""
    if os.environ.get("DOCS_COLLECT"):
        print("MISMATCH " + message, file=sys.stderr)
        return
    raise AssertionError(message)


_VALUE_START = re.compile(r"(-?\d|-?\.\d|True\b|False\b|None\b|-?nan\b|-?inf\b|[\[{(\"'])")


def shown_value(comment: str) -> str | None:
    """The value a comment after an expression shows, or None for prose."""
    text = comment.lstrip("#").strip()
    if text.startswith("->"):
        return text[2:].strip()
    return text if _VALUE_START.match(text) else None


def _comments(source: str) -> dict[int, str]:
    """Line (1-based) -> the comment ending that line."""
    out = {}
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.COMMENT:
            out[tok.start[0]] = tok.string
    return out


def _checked_source(source: str, where: tuple[str, int]) -> str:
    """A Python block with every expression whose line ends in a shown value wrapped in
    ``__docs_check__(expr, shown, 'page:line')`` (line numbers unchanged)."""
    comments = _comments(source)
    lines = source.splitlines(keepends=True)
    edits = []
    for node in ast.walk(ast.parse(source)):
        if not (isinstance(node, ast.Expr) and node.end_lineno in comments):
            continue
        wanted = shown_value(comments[node.end_lineno])
        if wanted is None or not _last_on_line(node, source):
            continue
        edits.append((node, wanted))
    for node, wanted in sorted(edits, key=lambda e: (e[0].lineno, e[0].col_offset),
                               reverse=True):
        v = node.value
        ln0, ln1 = v.lineno - 1, v.end_lineno - 1
        c0 = len(lines[ln0].encode()[:v.col_offset].decode())  # ast counts UTF-8 bytes
        c1 = len(lines[ln1].encode()[:v.end_col_offset].decode())
        doc_line = f"{where[0]}:{where[1] + v.end_lineno}"
        lines[ln1] = lines[ln1][:c1] + f"), {wanted!r}, {doc_line!r})" + lines[ln1][c1:]
        lines[ln0] = lines[ln0][:c0] + "__docs_check__((" + lines[ln0][c0:]
    return "".join(lines)


def _last_on_line(node: ast.Expr, source: str) -> bool:
    """The expression is the last statement of its last line (``a = 1; a`` checks ``a``)."""
    rest = source.splitlines()[node.end_lineno - 1].encode()[node.end_col_offset:].decode()
    return rest.lstrip().startswith("#")


# --------------------------------------------------------------------------- pages


@dataclass
class Step:
    """A Python block, a console command or a file to write, in page order."""

    kind: str  # "python", "command", "file"
    where: str
    block: Block
    command: Command | None = None
    slow: bool = False
    writes: set[str] = field(default_factory=set)
    reads: set[str] = field(default_factory=set)


def _path_words(words) -> set[str]:
    """Words that name a relative file or folder (``site.nc``, ``synth/``)."""
    out = set()
    for w in words:
        w = w.partition("=")[2] if w.startswith("--") else w
        if w and not w.startswith(("-", "/", "~")) and not w.startswith(REPO_PREFIXES) \
                and re.fullmatch(r"[\w./-]+", w) and ("/" in w or re.search(r"\.\w+$", w)) \
                and not re.fullmatch(NUMBER, w):
            out.add(w.rstrip("/"))
    return out


def _strings(source: str) -> set[str]:
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return set()
    return {n.value.rstrip("/") for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str)}


def steps(path: Path, langs: tuple[str, ...] = ("python", "console")) -> list[Step]:
    """The runnable steps of a page, in order (skipped blocks left out)."""
    out = []
    for b in blocks(path):
        if b.marker == "skip":
            continue
        if b.marker == "file":
            out.append(Step("file", b.where, b, writes={b.arg}))
        elif b.lang == "python" and "python" in langs:
            out.append(Step("python", b.where, b, slow=b.marker == "slow",
                            reads=_strings(b.text), writes=_strings(b.text)))
        elif b.lang == "console" and "console" in langs:
            for c in commands(b):
                words = _path_words(c.argv)
                out.append(Step("command", c.where, b, c, slow=c.slow, reads=words,
                                writes=words))
    return out


def selected(page_steps: list[Step], everything: bool) -> list[Step]:
    """All steps, or the quick ones that depend on no left-out step: no Python block after a
    left-out Python block (one namespace), no step naming a file a left-out step names."""
    if everything:
        return list(page_steps)
    out, dropped_words, python_dropped = [], set(), False
    for s in page_steps:
        drop = s.slow or bool(s.reads & dropped_words) or (s.kind == "python" and python_dropped)
        if drop:
            dropped_words |= s.writes
            python_dropped |= s.kind == "python"
        else:
            out.append(s)
    return out


def page_script(path: Path, chosen: list[Step]) -> str:
    """One Python script that runs the chosen steps of a page in order: the page's Python
    blocks at their own line numbers (a traceback names the page's lines), the commands and
    files as calls between them."""
    n = len(path.read_text(encoding="utf-8").splitlines())
    lines = [""] * (n + 2)
    lines[0] = (f"import sys; sys.path.insert(0, {str(ROOT / 'tests')!r}); "
                "from docblocks import check_value as __docs_check__, "
                "run_command as __docs_run__, write_file as __docs_file__; "
                "__name__ == '__main__' and 'tests.conftest' not in sys.modules "
                "and __import__('conftest')  # the suite's settings (run alone)")
    for s in chosen:
        b = s.block
        if s.kind == "python":
            src = _checked_source(b.text, (_rel(path), b.line)).splitlines()
            lines[b.line:b.line + len(src)] = src  # body starts on the line after the fence
        elif s.kind == "file":  # (only the main process: workers import the script too)
            lines[b.line] = f"if __name__ == '__main__': __docs_file__({b.arg!r}, {b.text!r})"
        else:
            c = s.command
            lines[c.line - 1] = (f"if __name__ == '__main__': "
                                 f"__docs_run__({list(c.argv)!r}, {c.expected!r}, {c.where!r})")
    return "\n".join(lines) + "\n"


def write_file(name: str, text: str) -> None:
    Path(name).parent.mkdir(parents=True, exist_ok=True)
    Path(name).write_text(text, encoding="utf-8")


def run_command(argv: list[str], expected: str, where: str) -> None:
    """Run one command of a console block here (rockarch in this process, Python in a
    subprocess) and check what it prints against what the docs show."""
    import resource
    import time

    env = dict(os.environ)
    while argv and re.fullmatch(r"[A-Z_]+=\S*", argv[0]):
        k, _, v = argv[0].partition("=")
        env[k] = v
        argv = argv[1:]
    error = expected.startswith("error:")
    # CPU seconds (this process's threads and its finished children): what a command costs,
    # whatever else shares the machine
    t0 = time.process_time() + resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    if argv[0] == "rockarch":
        from typer.testing import CliRunner

        from rockarch.cli import app

        res = CliRunner().invoke(app, argv[1:], env={k: v for k, v in env.items()
                                                      if k not in os.environ
                                                      or os.environ[k] != v})
        code, out, err = res.exit_code, res.stdout, res.stderr
        if res.exception is not None and not isinstance(res.exception, SystemExit):
            import traceback

            err += "".join(traceback.format_exception(res.exception))
    else:
        p = subprocess.run([sys.executable, *argv[1:]], capture_output=True, text=True,
                           env=env)
        code, out, err = p.returncode, p.stdout, p.stderr
    cpu = time.process_time() + resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - t0
    print(json.dumps({"where": where, "seconds": round(cpu, 2)}), file=sys.stderr)
    want = 2 if error else 0
    if code != want:
        raise AssertionError(f"{where}: {' '.join(argv)}\nexit status {code} (docs: {want})\n"
                             f"stdout:\n{out}\nstderr:\n{err}")
    if expected and not matches(expected, err if error else out) \
            and not matches(expected, out + err):
        _mismatch(f"{where}: {' '.join(argv)}\nthe docs show:\n{expected}\nprinted:\n{out}{err}")


def run_page(path: Path, everything: bool, folder: Path, langs=("python", "console")
             ) -> tuple[subprocess.CompletedProcess, list[Step]]:
    """Run a page's chosen steps as one script in ``folder``; the completed run (its stderr
    holds one JSON line of run time per command) and the steps run."""
    chosen = selected(steps(path, langs), everything)
    for prefix in REPO_PREFIXES:  # the page runs as from a clone: src/..., examples/... exist
        if not (folder / prefix).exists():
            (folder / prefix.rstrip("/")).symlink_to(ROOT / prefix, target_is_directory=True)
    script = folder / (path.stem + ".md.py")
    script.write_text(page_script(path, chosen), encoding="utf-8")
    return run_script(script), chosen


def run_script(script: Path) -> subprocess.CompletedProcess:
    """Run a page's script as ``python SCRIPT`` would in its folder (``__name__`` is
    ``"__main__"``; a process pool's workers import the script by its path), but in this
    process: the suite's imports and compiled kernels are loaded once per test process, not
    once per page (~3 s each). Its output is captured; the working folder, ``sys.argv``,
    ``sys.path``, the environment, the warning filters, numpy's settings and matplotlib's
    figures are as before afterwards. The exit status: 0, a SystemExit's, or 1 after an
    exception (its traceback on stderr, naming the page's lines)."""
    import numpy as np

    out, err = io.StringIO(), io.StringIO()
    saved = (os.getcwd(), sys.argv[:], sys.path[:], dict(os.environ), np.geterr(),
             np.get_printoptions())
    code = 0
    try:
        os.chdir(script.parent)
        sys.argv = [script.name]
        sys.path.insert(0, str(script.parent))
        os.environ["MPLBACKEND"] = "Agg"
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), \
                warnings.catch_warnings():
            try:
                runpy.run_path(str(script.resolve()), run_name="__main__")
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
            except Exception:
                traceback.print_exc()
                code = 1
    finally:
        cwd, sys.argv, sys.path[:], env, npe, npp = saved
        os.chdir(cwd)
        os.environ.clear()
        os.environ.update(env)
        np.seterr(**npe)
        np.set_printoptions(**npp)
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close("all")
    return subprocess.CompletedProcess([sys.executable, script.name], code, out.getvalue(),
                                       err.getvalue())


def timings(stderr: str) -> dict[str, float]:
    """``where -> CPU seconds`` of the commands a page script ran."""
    out = {}
    for line in stderr.splitlines():
        if line.startswith('{"where"'):
            d = json.loads(line)
            out[d["where"]] = d["seconds"]
    return out


__all__ = ["Block", "Command", "Step", "blocks", "check_value", "commands", "matches",
           "page_script", "run_command", "run_page", "run_script", "selected", "show",
           "shown_value", "steps", "timings"]
