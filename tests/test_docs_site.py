"""The docs as a site (mkdocs.yml, ``make docs``): every package has its API page with a
one-line purpose and the theory sections it implements, every page is in the navigation.
The strict build itself runs in ``make test-all`` (``make docs``)."""

from __future__ import annotations

import ast
import re

import pytest

from tests.docblocks import ROOT

DOCS = ROOT / "docs"
MKDOCS = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
THEORY = (DOCS / "theory.md").read_text(encoding="utf-8")
#: The packages of src/rockarch (docs/architecture.md), each with an API page.
PACKAGES = ["core", "motion", "arch", "rocking", "mdof", "systems", "spectra", "risk", "design",
            "output", "paper", "cli"]


def _docstring(name: str) -> str:
    path = ROOT / "src" / "rockarch" / name / "__init__.py"
    path = path if path.exists() else ROOT / "src" / "rockarch" / f"{name}.py"
    return ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""


def test_every_package_of_the_tree_has_a_page():
    tree = {p.name.removesuffix(".py") for p in (ROOT / "src" / "rockarch").iterdir()
            if not p.name.startswith("_") and (p.is_dir() or p.suffix == ".py")
            and p.name != "__pycache__"}
    assert tree == set(PACKAGES)
    for name in PACKAGES:
        page = (DOCS / "api" / f"{name}.md").read_text(encoding="utf-8")
        assert f"::: rockarch.{name}\n" in page, name
        assert f"api/{name}.md" in MKDOCS, name


@pytest.mark.parametrize("name", PACKAGES)
def test_package_docstring_states_purpose_and_theory(name):
    """First line: the package's purpose, one sentence; then a "Theory:" paragraph naming
    the docs/theory.md sections it implements (they exist), or saying it has none."""
    doc = _docstring(name)
    first = doc.splitlines()[0]
    assert first.endswith(".") and len(first) <= 96, first
    theory = re.search(r"^Theory:(.*(?:\n(?!\n).*)*)", doc, flags=re.M)
    assert theory, f"rockarch.{name}: no 'Theory:' paragraph"
    sections = set(re.findall(r"^##+ (\d+(?:\.\d+)?)[. ]", THEORY, flags=re.M))
    cited = re.findall(r"§(\d+(?:\.\d+)?)", theory.group(1))
    assert cited or "none" in theory.group(1), theory.group(0)
    assert set(cited) <= sections, (cited, sections)


def test_every_page_is_in_the_navigation():
    pages = {str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md") if "_hooks" not in p.parts}
    missing = {p for p in pages if p not in MKDOCS}
    assert not missing, missing


def test_the_site_is_built_offline():
    """No page loads anything from the network: system fonts, MathJax from the package."""
    assert "font: false" in MKDOCS and "- offline" in MKDOCS
    assert not re.search(r"https?://", MKDOCS.split("nav:")[1])
    js = (DOCS / "javascripts" / "mathjax.js").read_text(encoding="utf-8")
    assert "http" not in js
