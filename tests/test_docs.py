"""The docstrings' citations of docs/theory.md point at equations and sections that exist,
and no docstring cites a file outside the repository or an issue number."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
THEORY = (ROOT / "docs" / "theory.md").read_text(encoding="utf-8")
SOURCES = sorted((ROOT / "src" / "rockarch").rglob("*.py"))


def _cited_equations(text: str) -> set[str]:
    """Equation numbers cited as 'theory.md Eq. 1.4', 'Eqs. (4.1)–(4.3)', 'Eq. (9.2)'."""
    out = set()
    for m in re.finditer(r"theory\.md,?\s+Eqs?\.\s*([(\d.)\s,–\-and]+)", text):
        out.update(re.findall(r"\d+\.\d+", m.group(1)))
    return out


def test_equations_are_cited_by_number():
    """'Eq. 3' (no section) cannot be found in docs/theory.md, whose equations are (N.k)."""
    bad = [p.name for p in SOURCES
           if re.search(r"theory\.md,?\s+Eqs?\.\s*\(?\d+\)?(?![\d.])",
                        p.read_text(encoding="utf-8"))]
    assert not bad, bad


def test_every_cited_equation_exists():
    labels = set(re.findall(r"\((\d+\.\d+)\)", THEORY))
    missing = {}
    for path in SOURCES:
        for eq in _cited_equations(path.read_text(encoding="utf-8")) - labels:
            missing.setdefault(eq, []).append(path.name)
    assert not missing, f"equations cited but not in docs/theory.md: {missing}"


def test_every_cited_section_exists():
    sections = set(re.findall(r"^##+ (\d+(?:\.\d+)?)[. ]", THEORY, flags=re.M))
    missing = {}
    for path in SOURCES:
        text = path.read_text(encoding="utf-8")
        for sec in re.findall(r"theory\.md,?\s+(?:§|Sect\.\s*)(\d+)", text):
            if sec not in sections:
                missing.setdefault(sec, []).append(path.name)
    assert not missing, f"sections cited but not in docs/theory.md: {missing}"


def test_no_citation_outside_the_repository():
    bad = [f"{p.relative_to(ROOT)}:{i}" for p in SOURCES
           for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
           if re.search(r"physics note|\bissue \d+|shared/docs", line, flags=re.I)]
    assert not bad, bad


def test_docs_cite_no_issue_number():
    """The user's docs stand alone: no page cites a tracker's issue number."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    bad = [f"{p.relative_to(ROOT)}:{i}" for p in pages
           for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
           if re.search(r"\bissues? \d+|the issue's", line, flags=re.I)]
    assert not bad, bad


#: A citation: "Eq. 2.1", "Eqs. (4.1)–(4.3)", "§11.2", "Sect. 4 and 8", optionally after
#: "paper"/"the paper's" (then it is the source paper's numbering, not docs/theory.md's).
_CITATION = re.compile(
    r"(?P<paper>paper(?:'s)?\s+)?(?P<what>Eqs?\.|§§?|Sects?\.)\s*"
    r"(?P<nums>\(?\d+(?:\.\d+)?[a-z]?\)?(?:\s*(?:[–,-]|and|to)\s*\(?\d+(?:\.\d+)?[a-z]?\)?)*)",
    flags=re.I)
def _theory_labels() -> tuple[set[str], set[str]]:
    """(equation tags, section numbers) of docs/theory.md: ``\\tag*{(2.1)}`` in display
    maths, ``(9.1)`` ending a line in the code blocks, headings ``## 2.`` / ``### 11.2``."""
    eqs = set(re.findall(r"\\tag\*\{\((\d+\.\d+[a-z]?)\)\}", THEORY))
    eqs |= set(re.findall(r"\((\d+\.\d+[a-z]?)\)[ \t]*$", THEORY, flags=re.M))
    secs = set(re.findall(r"^##+ (\d+(?:\.\d+)?)[. ]", THEORY, flags=re.M))
    return eqs, secs


def dangling_citations(text: str, eqs: set[str], secs: set[str]) -> list[str]:
    """The citations of ``text`` (whitespace folded, so that one broken over lines counts)
    that docs/theory.md does not have: an equation that is not tagged there, a section
    that is not a heading; "the physics note" and "Eq. 3 of ..." always."""
    flat = re.sub(r"\s+", " ", text)
    odd = list(re.finditer(r"physics note|\bEqs?\. \d+ of\b", flat, flags=re.I))
    bad = [m.group(0) for m in odd]
    for m in _CITATION.finditer(flat):
        before = flat[max(0, m.start() - 20):m.start()].lower()  # "(paper Sect. 9, Eq. 16)"
        if m.group("paper") or "paper" in before or m.start() in {o.start() for o in odd}:
            continue
        known = secs if m.group("what").lower().startswith(("§", "sect")) else eqs
        nums = re.findall(r"\d+(?:\.\d+)?[a-z]?", m.group("nums"))
        if any(n not in known for n in nums):
            cited = m.group(0).strip()
            bad.append(cited[:-1] if cited.count(")") > cited.count("(") else cited)
    return bad


def test_every_citation_in_src_is_in_theory():
    """Every Eq./§/Sect. cited anywhere in src/ (docstrings, comments, messages) that is not
    the paper's is an equation tag or a heading of docs/theory.md."""
    eqs, secs = _theory_labels()
    found = {(str(p.relative_to(ROOT / "src" / "rockarch")), c)
             for p in SOURCES for c in dangling_citations(p.read_text(encoding="utf-8"),
                                                          eqs, secs)}
    assert found == set(), sorted(found)


def test_dangling_citations_are_found():
    """The check catches the forms a user review found (and lets the good ones through)."""
    eqs, secs = _theory_labels()
    assert {"2.1", "2.2", "6.3a", "9.1", "11.30a"} <= eqs and {"2", "11.2"} <= secs
    bad = dangling_citations(
        'x (Eq. 3 of docs/theory.md); y (physics\n    note section 2); z (Eq. 12–14); '
        "w (Sect. 12); v Eqs. (4.1)–(4.9)", eqs, secs)
    assert bad == ["Eq. 3 of", "physics note", "Eq. 12–14", "Sect. 12", "Eqs. (4.1)–(4.9)"]
    assert dangling_citations("Eqs. (2.1)–(2.2), §11.2, paper Eqs. 12–14, the paper's "
                              "Sect. 9, Eq. (6.3a)", eqs, secs) == []


#: The front door of docs/index.md and the README: ``help(ra.X)`` must stand on its own.
FRONT_DOOR = ("oas", "simulate", "batch", "make_arch", "read_record", "el_centro",
              "synthetic_suite", "system", "read_suite")


def test_front_door_docstrings_are_complete():
    """Each has a one-line summary and numpy-style Parameters and Returns sections naming
    every parameter, with units where a parameter has them."""
    import inspect

    import rockarch as ra

    for name in FRONT_DOOR:
        fn = getattr(ra, name)
        doc = inspect.getdoc(fn)
        summary, _, body = doc.partition("\n\n")
        assert "\n" not in summary and summary.endswith("."), (name, summary)
        for section in ("Parameters\n----------", "Returns\n-------"):
            assert section in body, (name, section)
        params = body.split("Parameters\n----------")[1].split("\n\n")[0]
        documented = re.findall(r"^(\w+(?:, \w+)*) :", params, flags=re.M)
        names = {n for group in documented for n in group.split(", ")}
        missing = [p for p in inspect.signature(fn).parameters if p not in names]
        assert not missing, (name, missing)


def test_front_door_examples_run():
    """The Examples of the front-door docstrings compute what they show."""
    import doctest

    import rockarch as ra

    finder, runner = doctest.DocTestFinder(recurse=False), doctest.DocTestRunner()
    ran = 0
    for name in FRONT_DOOR:
        for test in finder.find(getattr(ra, name), name):
            runner.run(test)
            ran += len(test.examples)
    assert runner.failures == 0 and ran >= 20, (runner.failures, ran)
