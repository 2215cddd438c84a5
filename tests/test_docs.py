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
